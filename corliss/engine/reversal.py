"""A change of direction: the slip eccentric carried through zero speed by its load.

The speed loop of :mod:`corliss.engine.kernels.loop` integrates in crank angle, every
rate divided by the speed, so it cannot pass through zero speed; when a turn stalls
there (a load heavier than the engine can carry), an engine reversed by a slip
eccentric (:mod:`corliss.valves.slip_eccentric`) is carried on here, in time, through
the stop and the change of direction, the eccentric's slip, and its running backward
under steam, until its speed backward passes :data:`HANDOVER_FRACTION` of the run
speed; then the speed loop takes over again at the next head-end dead centre, running
the other way with the gear driven by the backward stop.

*Derived here*: the engine's own frame.  The crank angle ``theta`` is reckoned
positive the way the engine runs at the start ("ahead" below; for a scene that starts
astern, on its backward stop, the same holds with the stops' names exchanged).  Running backward, the angle in the direction of rotation is
``phi = -theta``; a single cylinder's volumes are even in the crank angle (the slider
crank's piston stands at the same place at ``theta`` and ``-theta``), so the cylinder
running backward at speed ``omega < 0`` is the same cylinder running ahead in ``phi``
at ``|omega|``: the loop's right-hand side evaluated at ``phi`` and ``|omega|`` gives
every rate in that frame (the flows and heat, and the work ``p dV/dphi`` with the
right sign), the indicated torque in the direction of rotation, and the friction
against it.  The load keeps its direction in the fixed frame: a constant torque
``T`` resisting the engine ahead is ``-T`` in the backward frame (it drives the engine
backward: an overhauling load, a weight being lowered).

The sheave (:mod:`corliss.valves.slip_eccentric`, module doc): running ahead the pin
drives on the forward stop, and the valve is the ahead gear's at the crank angle.  The
eccentric's sheave, held by its strap and rod, moves only when a stop pushes it; its
place is written here as the crank angle ``a`` at which the ahead gear would put the
valve where it is.  On the forward stop ``a = theta``; when the shaft turns backward
the pin leaves the stop and the sheave stands (``a`` constant) until the shaft has
turned back through the slip, ``pi - delta_f - delta_b``, where the pin meets the
backward stop and the sheave is carried round again, ``a = theta + slip``.  The valve
is then the backward gear's at ``phi`` (the module doc of the slip eccentric derives
it), the same as the ahead gear's at ``theta + slip``.  While the sheave stands, every
port's area is the ahead gear's at ``a``, fixed.  A shaft turning ahead again before
the slip is through meets the forward stop again at ``theta = a``.

At rest a Coulomb friction holds the shaft while the net torque either way is less
than it (as :mod:`corliss.engine.start_from_rest` holds an engine at rest); below a
creep speed far under any running speed (:data:`CREEP_FRACTION` of the run speed) the
rates are those at the creep speed, as there.
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.kernels import loop
from corliss.engine.kernels.properties import PR_ROWS
from corliss.valves.gear import ValveGear
from corliss.valves.single_acting import SingleActing
from corliss.valves.slip_eccentric import SlipEccentric

TWO_PI = 2.0 * math.pi
#: The backward speed [fraction of the run speed] past which the speed loop takes over
#: again (at the next head-end dead centre).
HANDOVER_FRACTION = 0.3
#: The creep speed below which the rates are those at it [fraction of the run speed].
CREEP_FRACTION = 1e-6
#: The sheave: driven by the forward stop, standing while the shaft slips inside it,
#: driven by the backward stop.
FORWARD, STANDING, BACKWARD = 0, 1, 2


def _terminal(event, direction: int) -> None:
    """Make ``event`` a terminal event of ``solve_ivp`` crossing zero in ``direction``."""
    setattr(event, "terminal", True)
    setattr(event, "direction", direction)


def reversible(scene, gear) -> bool:
    """Whether a stalled turn of this scene is carried on through a change of direction.

    A slip eccentric on a single cylinder (its volumes even in the crank angle), no
    governor, and a constant-torque load (the only law in the loop that can turn an
    engine backward: a speed-dependent load vanishes with the speed).

    Parameters
    ----------
    scene : Scene
        The transient scene.
    gear : object
        Its valve gear.

    Returns
    -------
    bool
        True where the engine is reversed by the load instead of stopping.
    """
    from_slip = getattr(gear, "name", None) == "slip_eccentric"
    return (from_slip and scene.compound is None and len(scene.engine.crank_angles_rad) == 1
            and scene.governor is None and scene.load.speed_exponent == 0)


def backward_gear(gear: ValveGear) -> ValveGear:
    """A slip eccentric's gear after the engine ran backward through the slip: the valve
    on its backward stop (a single-acting cylinder's: its inner gear's, unwrapped).

    Parameters
    ----------
    gear : ValveGear
        The run's gear: a :class:`~corliss.valves.slip_eccentric.SlipEccentric`, or a
        :class:`~corliss.valves.single_acting.SingleActing` round one.

    Returns
    -------
    ValveGear
        The slip eccentric on its backward stop.

    Raises
    ------
    TypeError
        For a gear that is not a slip eccentric (:func:`reversible` lets none through).
    """
    inner = gear.inner if isinstance(gear, SingleActing) else gear
    if not isinstance(inner, SlipEccentric):
        raise TypeError(f"the {gear.name} gear has no slip eccentric to reverse")
    return inner.reversed()


class _Shaft:
    """The loop's right-hand side in time, in the frame turning either way, with the slip
    eccentric's sheave at its place; it counts its evaluations and keeps the samples of
    every stretch integrated.

    Parameters
    ----------
    nn : int
        The network's states (the loop's follow them).
    omega_run : float
        The scene's run speed [rad/s].
    net, gear, tier, tab, perf, tr
        As :func:`run_reversal`'s.
    """

    def __init__(self, nn: int, omega_run: float, net, gear, tier, tab, perf, tr):
        self.i_w = nn + loop.X_OMEGA
        self.gear = gear
        self.slip = gear.spec.slip_rad
        self.w_f = CREEP_FRACTION * omega_run
        self.sc = tr.sc
        self.t_ref = tr.sc[loop.S_TREF]
        self.tier, self.tab, self.perf, self.tr = tier, tab, perf, tr
        # the ahead gear's areas over its crank angle, read at the sheave's place ``a``
        self.grid = net.port_grid[0, :net.port_npts[0]].copy()
        self.table = net.port_area[0, :, :net.port_npts[0]].copy()
        self.fixed = np.empty((1, 4, 2))
        self.net_fixed = net._replace(port_grid=np.array([[0.0, TWO_PI]]),
                                      port_npts=np.array([2], dtype=net.port_npts.dtype),
                                      port_area=self.fixed)
        self.dy = np.empty(nn + loop.N_EXTRA)
        # the properties' scratch starts unknown (NaN), as the compiled loops' does: a
        # value left by another run would seed the wet-state iteration
        self.pr = np.full((PR_ROWS, net.node_kind.shape[0]), np.nan)
        self.pa = np.empty((1, 4))
        self.out = np.empty(4)
        self.nfev = 0
        self.ts: list = []
        self.ths: list = []
        self.ys: list = []
        self.valves: list = []
        self.slips: list = []

    def place(self, theta: float, mode: int, anchor: float) -> float:
        """The sheave's place ``a`` (the ahead gear's crank angle) [rad]."""
        if mode == FORWARD:
            return theta
        if mode == BACKWARD:
            return theta + self.slip
        return anchor

    def frame_rates(self, theta: float, y: np.ndarray, sense: float, a: float):
        """d/dt of the loop's states in the frame turning ``sense``, and the shaft's
        acceleration in it [rad/s2]."""
        self.nfev += 1
        a = a % TWO_PI
        for p in range(4):
            self.fixed[0, p, :] = np.interp(a, self.grid, self.table[p])
        yk = y.copy()
        w_eff = max(abs(y[self.i_w]), self.w_f)
        yk[self.i_w] = w_eff
        self.sc[loop.S_TREF] = sense * self.t_ref
        loop.transient_rhs((sense * theta) % TWO_PI, yk, self.dy, self.net_fixed, self.tier,
                           self.tab, self.perf, self.pr, self.pa, self.tr, self.out)
        return self.dy * w_eff, self.out[3]

    def rhs(self, t: float, Y: np.ndarray, mode: int, anchor: float) -> np.ndarray:
        """d/dt of ``[theta, y]`` for ``solve_ivp``."""
        theta = Y[0]
        y = Y[1:]
        w = y[self.i_w]
        a = self.place(theta, mode, anchor)
        if abs(w) > self.w_f:
            sense = 1.0 if w > 0.0 else -1.0
            d, wdot = self.frame_rates(theta, y, sense, a)
        else:
            # at rest: it moves the way the net torque can turn it against friction
            sense = 1.0
            d, wdot = self.frame_rates(theta, y, 1.0, a)
            if wdot <= 0.0:
                d_b, wdot_b = self.frame_rates(theta, y, -1.0, a)
                if wdot_b > 0.0:
                    sense, d, wdot = -1.0, d_b, wdot_b
                else:
                    wdot = 0.0          # held by friction
        d[self.i_w] = sense * wdot
        return np.concatenate([[w], d])

    def keep(self, sol, mode: int, anchor: float, first: bool) -> None:
        """Keep a stretch's samples (its first sample only for the first stretch)."""
        s = slice(0 if first else 1, None)
        th = sol.y[0, s]
        self.ts.append(sol.t[s])
        self.ths.append(th)
        self.ys.append(sol.y[1:, s])
        a = np.array([self.place(x, mode, anchor) for x in th])
        self.valves.append(self.gear.travel(a % TWO_PI))
        self.slips.append(a - th)

    def samples(self) -> dict:
        """The samples kept, as :func:`run_reversal` returns them."""
        return {"t": np.concatenate(self.ts), "theta": np.concatenate(self.ths),
                "y": np.concatenate(self.ys, axis=1), "valve_m": np.concatenate(self.valves),
                "slip_rad": np.concatenate(self.slips)}

    def events(self, mode: int, anchor: float, Y: np.ndarray, omega_run: float):
        """The terminal events of the next stretch in ``mode``: the shaft turning back
        (forward stop), either stop meeting the pin (standing), ahead again or fast enough
        backward (backward stop); None when already fast enough backward."""
        i_w, w_f, slip = self.i_w, self.w_f, self.slip
        if mode == FORWARD:
            def stop(t, Y, *_):
                return Y[1 + i_w] + 0.5 * w_f      # a little past zero: turned back
            _terminal(stop, -1)
            return [stop]
        if mode == STANDING:
            def forward_stop(t, Y, *_, a=anchor):
                return Y[0] - a
            _terminal(forward_stop, 1)

            def backward_stop(t, Y, *_, a=anchor):
                return Y[0] - (a - slip)
            _terminal(backward_stop, -1)
            return [forward_stop, backward_stop]
        if -Y[1 + i_w] >= HANDOVER_FRACTION * omega_run:
            return None                         # fast enough already: to the dead centre

        def ahead_again(t, Y, *_):
            return Y[1 + i_w] - 0.5 * w_f
        _terminal(ahead_again, 1)

        def fast_enough(t, Y, *_):
            return -Y[1 + i_w] - HANDOVER_FRACTION * omega_run
        _terminal(fast_enough, 1)
        return [ahead_again, fast_enough]


def run_reversal(y0: np.ndarray, theta0: float, omega_run: float, net, gear, tier, tab, perf,
                 tr, rtol: float, atol: np.ndarray, t_max: float) -> dict:
    """Integrate in time from the start of a stalling turn through the change of direction.

    Parameters
    ----------
    y0 : ndarray
        The loop's state at the turn's start, a head-end dead centre, running ahead.
    theta0 : float
        Its crank angle [rad], a multiple of 2 pi.
    omega_run : float
        The scene's run speed [rad/s] (the handover and the creep speed).
    net : NetworkArrays
        The network's arrays with the ahead gear's port tables.
    gear : SlipEccentric
        The gear running ahead (on its forward stop).
    tier, tab, perf, tr
        The compiled loop's arrays (see
        :func:`corliss.engine.kernels.dopri5.integrate_turn`); ``tr.sc[S_TREF]`` is
        the load's torque in the ahead frame and is left as found.
    rtol : float
        Relative tolerance [-].
    atol : ndarray
        Absolute tolerances of the loop's states, in each one's unit.
    t_max : float
        The run's end time [s].

    Returns
    -------
    dict
        ``y`` the state at the handover in the backward frame (its speed ``|omega|``),
        ``phi_rad`` the angle there in the direction of rotation (a multiple of 2 pi),
        ``handed_over`` (False when the run's time ended first), ``nfev``,
        ``theta_reversed_rad`` the crank angle where the shaft first stopped and turned
        back (None if it never did), ``theta_engaged_rad`` where the backward stop took
        the sheave (None if it never did), and ``samples``: ``t`` [s], ``theta`` [rad]
        (positive ahead), ``y`` (speed signed), ``valve_m`` (the valve's displacement
        from mid travel) and ``slip_rad`` (the sheave's place less the shaft's,
        ``a - theta``: 0 on the forward stop, the slip on the backward).
    """
    from scipy.integrate import solve_ivp   # only a reversing run integrates with it

    sc = tr.sc
    nn = y0.shape[0] - loop.N_EXTRA
    shaft = _Shaft(nn, omega_run, net, gear, tier, tab, perf, tr)
    i_w, slip = shaft.i_w, shaft.slip
    floor_saved = sc[loop.S_WMIN]
    sc[loop.S_WMIN] = shaft.w_f
    Y = np.concatenate([[theta0], y0])
    Y[1 + i_w] = max(Y[1 + i_w], 0.0)
    t = float(y0[nn + loop.X_TIME])
    mode, anchor = FORWARD, theta0
    reversed_at = engaged_at = None
    handed_over = False
    first = True
    tol = np.concatenate([[1e-9], atol])
    try:
        while t < t_max:
            events = shaft.events(mode, anchor, Y, omega_run)
            if events is None:
                hit = [1]
            else:
                sol = solve_ivp(shaft.rhs, (t, t_max), Y, method="LSODA", rtol=rtol, atol=tol,
                                events=events, args=(mode, anchor))
                shaft.keep(sol, mode, anchor, first)
                first = False
                Y = sol.y[:, -1].copy()
                t = float(sol.t[-1])
                if sol.status != 1:
                    break
                hit = [i for i, e in enumerate(sol.t_events) if e.size]
            theta = Y[0]
            if mode == FORWARD:
                mode, anchor = STANDING, theta
                if reversed_at is None:
                    reversed_at = theta
            elif mode == STANDING:
                if hit[0] == 0:
                    mode = FORWARD
                else:
                    mode = BACKWARD
                    if engaged_at is None:
                        engaged_at = theta
            elif hit[0] == 0:
                mode, anchor = STANDING, theta + slip
            else:
                # on to the next head-end dead centre running backward
                theta_dc = TWO_PI * math.floor(theta / TWO_PI - 1e-9)

                def dead_centre(t, Y, *_):
                    return Y[0] - theta_dc
                _terminal(dead_centre, -1)
                sol = solve_ivp(shaft.rhs, (t, t_max), Y, method="LSODA", rtol=rtol, atol=tol,
                                events=[dead_centre], args=(mode, anchor))
                shaft.keep(sol, mode, anchor, False)
                Y = sol.y[:, -1].copy()
                t = float(sol.t[-1])
                handed_over = sol.status == 1
                break
    finally:
        sc[loop.S_WMIN] = floor_saved
        sc[loop.S_TREF] = shaft.t_ref
    y = Y[1:].copy()
    y[nn + loop.X_TIME] = t
    y[i_w] = abs(y[i_w])
    phi = -Y[0]
    return {"y": y, "phi_rad": float(round(phi / TWO_PI) * TWO_PI) if handed_over else phi,
            "handed_over": handed_over, "nfev": shaft.nfev, "theta_reversed_rad": reversed_at,
            "theta_engaged_rad": engaged_at, "samples": shaft.samples()}
