"""A start from rest: the first moments of a transient run, integrated in time.

The speed loop of :mod:`corliss.engine.kernels.loop` integrates in crank angle,
every rate divided by the speed omega, which cannot start at omega = 0.  From rest the
engine is integrated in time instead, with the same right-hand side: the loop's
derivatives with respect to crank angle, evaluated with omega floored at a speed
omega_f far below any running speed, times omega_f.  For the cylinders and chest this
is exact (the flows were divided by omega_f and are multiplied back), and so for
time; for the shaft it gives I domega/dt = T_gas - T_f - T_load; the crank turns at
omega_f while the engine is at rest (a creep of omega_f t, 1e-4 rad in a second).  At
rest the engine cannot run backwards: a net torque that would turn it the wrong way
is held by the crank (the speed stays at zero, as static friction holds a real one).

The engine starts at ``start_angle`` of the crank (off dead centre: on a dead centre a
single cylinder gives no torque and stays at rest, which the run reports as a stall),
its cylinders at back pressure, the chest at the supply's, the governor down.  Once its
speed passes ``HANDOVER_FRACTION`` of the run speed the integration goes on to the
next head-end dead centre, where the crank-angle loop takes over.
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.ivp_events import terminal_event
from corliss.engine.kernels import loop
from corliss.engine.kernels.properties import PR_ROWS

TWO_PI = 2.0 * math.pi
#: The speed [fraction of the run speed] past which the crank-angle loop takes over
#: (at the next head-end dead centre).
HANDOVER_FRACTION = 0.3
#: The floor on omega while at rest [fraction of the run speed].
CREEP_FRACTION = 1e-6


def start_from_rest(y0: np.ndarray, theta0: float, omega_run: float, net, tier, tab, perf,
                    tr, rtol: float, atol: np.ndarray, t_max: float):
    """Integrate in time from rest to the crank-angle loop's handover.

    From crank angle ``theta0`` to the first head-end dead centre after the speed
    passes :data:`HANDOVER_FRACTION` of the run speed.

    Parameters
    ----------
    y0 : ndarray
        The loop's state at rest (cylinders, chest, and the extra states: omega 0, the
        governor down, time 0).
    theta0 : float
        Crank angle at the start [rad], in [0, 2 pi).
    omega_run : float
        The scene's run speed [rad/s] (sets the handover and the creep floor).
    net, tier, tab, perf, tr
        The compiled loop's arrays (see
        :func:`corliss.engine.kernels.dopri5.integrate_turn`).
    rtol : float
        Relative tolerance of the time integration [-].
    atol : ndarray
        Absolute tolerances of the loop's states, in each one's unit.
    t_max : float
        The run's duration [s]: an engine not up to the handover speed by then has not
        started (it stalled, or is still starting).

    Returns
    -------
    dict
        ``y`` the state at the dead centre, ``theta_rad`` its crank angle (a multiple
        of 2 pi), ``stalled`` (True when the engine had not reached the handover speed
        by ``t_max``),
        ``nfev``, and ``samples``: the solver's accepted points (``t``, ``theta``,
        ``y`` columns) for the time series.
    """
    sc = tr.sc
    nn = y0.shape[0] - loop.N_EXTRA
    i_w = nn + loop.X_OMEGA
    floor_saved = sc[loop.S_WMIN]
    w_f = CREEP_FRACTION * omega_run
    sc[loop.S_WMIN] = w_f
    dy = np.empty(y0.shape[0])
    pr = np.full((PR_ROWS, net.node_kind.shape[0]), np.nan)
    pa = np.empty((net.port_npts.shape[0], 4))
    out = np.empty(4)
    nfev = 0

    def rhs(t, Y):
        nonlocal nfev
        nfev += 1
        th = Y[0]
        y = Y[1:].copy()
        if y[i_w] < 0.0:
            y[i_w] = 0.0
        w_eff = max(y[i_w], w_f)
        loop.transient_rhs(th, y, dy, net, tier, tab, perf, pr, pa, tr, out)
        d = np.empty_like(Y)
        d[0] = w_eff
        d[1:] = dy * w_eff
        if y[i_w] <= w_f and d[1 + i_w] < 0.0:
            d[1 + i_w] = 0.0            # held at rest: it does not turn backwards
        return d

    def fast_enough(t, Y):
        return Y[1 + i_w] - HANDOVER_FRACTION * omega_run
    terminal_event(fast_enough, 1)

    # scipy here, where it is used: every transient run imports this module, and only a
    # start from rest integrates with it (scipy costs a third of a second to import)
    from scipy.integrate import solve_ivp
    Y = np.concatenate([[theta0], y0])
    ts, ths, ys = [], [], []
    stalled = False
    try:
        sol = solve_ivp(rhs, (0.0, t_max), Y, method="LSODA", rtol=rtol,
                        atol=np.concatenate([[1e-9], atol]), events=fast_enough)
        ts.append(sol.t)
        ths.append(sol.y[0])
        ys.append(sol.y[1:])
        Y = sol.y[:, -1].copy()
        if sol.status != 1:
            stalled = True
        else:
            theta_dc = TWO_PI * math.ceil(Y[0] / TWO_PI + 1e-9)

            def dead_centre(t, Y):
                return Y[0] - theta_dc
            terminal_event(dead_centre, 1)
            t1 = sol.t[-1]
            sol = solve_ivp(rhs, (t1, t1 + t_max), Y, method="LSODA", rtol=rtol,
                            atol=np.concatenate([[1e-9], atol]), events=dead_centre)
            ts.append(sol.t[1:])
            ths.append(sol.y[0, 1:])
            ys.append(sol.y[1:, 1:])
            Y = sol.y[:, -1].copy()
            stalled = sol.status != 1
    finally:
        sc[loop.S_WMIN] = floor_saved
    y = Y[1:].copy()
    y[nn + loop.X_TIME] = float(np.concatenate(ts)[-1])
    return {"y": y, "theta_rad": float(Y[0]) if stalled else float(round(Y[0] / TWO_PI) * TWO_PI),
            "stalled": stalled, "nfev": nfev,
            "samples": (np.concatenate(ts), np.concatenate(ths), np.concatenate(ys, axis=1))}
