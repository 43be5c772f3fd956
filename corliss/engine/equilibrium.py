"""Cylinder ends with ideal ports: the textbook model without ``port_flow``.

While an end is open to the chest its pressure is chest pressure; while open to the
exhaust, back pressure; while closed, its steam expands or is compressed
reversibly and adiabatically (constant entropy, real steam).  The processes, for a
control volume of mass m, volume V and specific enthalpy h:

* opening to a reservoir at a different pressure, at constant volume: if the
  reservoir is higher, a filling ``m2 u2 = m1 u1 + (m2 - m1) h_res`` to its pressure;
  if lower, a blow-down in which the steam left behind expands isentropically
  (the standard filling-and-emptying idealisation);
* open, volume growing: inflow at the reservoir's enthalpy at constant pressure,
  ``d(m h) = h_res dm`` (from dU = h_res dm - p dV with dp = 0);
* open, volume shrinking: outflow at the cylinder's own state.

These are what the crank-resolved model tends to as the port areas grow without
bound; the ideal card with ``expansion = "isentropic"`` is the same stepping with
admission from dead centre to cut-off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from corliss.thermo.steam import State, Steam

CLOSED, STEAM, EXHAUST = 0, 1, 2


@dataclass
class EndTrace:
    """One end over one cycle of the ideal-port stepping.

    The arrays have one entry per point of the grid, ``n + 1`` of them; at a point where
    a port opens, the state after the filling or blow-down.

    Parameters
    ----------
    theta_rad : ndarray
        Crank angles of the grid [rad].
    V_m3 : ndarray
        Volume of the end [m3].
    p_Pa : ndarray
        Pressure [Pa].
    T_K : ndarray
        Temperature [K].
    x : ndarray
        Dryness [-] (as the steam state gives it).
    m_kg : ndarray
        Mass in the end [kg].
    work_J : float
        Work of the steam on the piston over the cycle [J].
    m_chest_kg : float
        Net mass from the chest over the cycle [kg].
    H_chest_J : float
        Net enthalpy from the chest over the cycle [J].
    m_exhaust_kg : float
        Net mass from the exhaust over the cycle [kg] (negative: to it).
    H_exhaust_J : float
        Net enthalpy from the exhaust over the cycle [J] (negative: to it).
    wall : dict or None
        With the skin wall, its totals over the cycle: ``Q_J`` the heat into the
        steam [J], ``Q_to_wall_J`` the heat into the wall [J], ``T_deep_K`` the deep
        wall's temperature [K].
    wall_records : ndarray or None
        With the skin wall, at each point of the grid: the surface's temperature [K],
        the film [kg], and the heat into the steam so far, all of it, down T_w - T_sat
        and by convection [J] (columns).
    """

    theta_rad: np.ndarray
    V_m3: np.ndarray
    p_Pa: np.ndarray
    T_K: np.ndarray
    x: np.ndarray
    m_kg: np.ndarray
    work_J: float
    m_chest_kg: float      # net mass from the chest over the cycle
    H_chest_J: float       # net enthalpy from the chest
    m_exhaust_kg: float    # net mass from the exhaust (negative: to it)
    H_exhaust_J: float
    wall: dict | None = None    # the wall's totals over the cycle (heat into the steam,
    #                             heat to the wall [J], the deep wall [K]), or None
    wall_records: np.ndarray | None = None   # surface [K], film [kg], heats so far [J]


def _fill(steam: Steam, st: State, m: float, V: float, res: State) -> tuple[State, float]:
    """Constant-volume filling from a reservoir at higher pressure."""
    U = m * st.u

    def excess(m2):
        u2 = (U + (m2 - m) * res.h) / m2
        return steam.du(m2 / V, u2).p - res.p

    hi = m * 1.5
    while excess(hi) < 0.0:
        hi *= 2.0
    # scipy at its one point of use: the crank-resolved runs import this module and
    # never fill an ideal end, and scipy.optimize costs a third of a second to import
    from scipy.optimize import brentq
    m2 = brentq(excess, m, hi, xtol=1e-14 * m, rtol=1e-12)
    return steam.du(m2 / V, (U + (m2 - m) * res.h) / m2), m2


def _open_step(steam: Steam, st: State, m: float, V1: float, res: State, dm_w: float = 0.0,
               dH_w: float = 0.0):
    """One step open to a reservoir at its pressure: returns state, mass, inflow, enthalpy
    in (with a wall, its mass ``dm_w`` and enthalpy ``dH_w`` taken in at that pressure
    too, :meth:`corliss.engine.wall.IdealPortWall.exchange`)."""
    H = m * st.h + dH_w
    m0 = m
    m += dm_w
    own: State | None = st      # the end's own state, None when the wall's share decides
    if dm_w != 0.0 or dH_w != 0.0:
        # the wall's share at the reservoir's pressure (when it condensed half or more
        # of what the end held, the port fills it whatever the rest's state: what
        # condenses leaves the rest at its own enthalpy)
        own = steam.ph(res.p, H / m) if m > 0.5 * m0 else None
    if own is not None and V1 * own.rho <= m:    # shrinking: outflow at own state
        m1 = V1 * own.rho
        return own, m1, m1 - m, own.h * (m1 - m)
    h1 = own.h if own is not None else res.h
    try:
        for _ in range(30):
            s1 = steam.ph(res.p, h1)
            m1 = V1 * s1.rho
            h_new = (H + res.h * (m1 - m)) / m1
            if abs(h_new - h1) < 1e-9 * abs(h1):
                h1 = h_new
                break
            h1 = h_new
        else:
            raise ValueError("the fixed point did not settle")
    except ValueError:
        h1 = _fill_at_pressure(steam, H, m, V1, res)
    s1 = steam.ph(res.p, h1)
    m1 = V1 * s1.rho
    return s1, m1, m1 - m, res.h * (m1 - m)


#: Steps of a blow-down with a wall whose film the outflow sweeps [-]
#: (:func:`_blow_down_sweeping`).
BLOW_DOWN_STEPS = 32


def _blow_down_sweeping(steam: Steam, st: State, m: float, V: float, p_res: float, wall):
    """A blow-down at constant volume ``V`` [m3] from ``st`` (mass ``m`` [kg]) to
    ``p_res`` [Pa] that sweeps the wall's film as it goes.

    The port-flow model sweeps the film beyond the clinging drops continuously, in
    the proportion of the steam leaving, into the steam as water of the film's
    enthalpy, and part of the water swept early in the blow-down leaves with the rest
    of it (:func:`corliss.engine.kernels.balances.sweep_films`): of the film's excess
    ``e``, a share ``1 - m2/m`` is swept while only ``(m2/m) ln(m/m2)`` of ``e`` is
    still in the end when it is over.  Swept once after the blow-down, as a single
    step would, all ``(1 - m2/m) e`` would stay (at release on the Meyer engine, half
    as much again), the exhaust's mixture would be wetter and the wall cooler than
    the port-flow model's as its ports grow.  The blow-down is therefore taken in
    :data:`BLOW_DOWN_STEPS` steps geometric in pressure: each an isentropic expansion
    of what stays, then the sweep of the share that left, mixed in at constant
    volume; the last step's sweep is left to the wall's next exchange
    (``wall.outflow``), at the reservoir's pressure, as before.

    Returns
    -------
    tuple
        The state and mass [kg] after, the mass [kg] and energy [J] that left through
        the port (negative), the energy as the enthalpy carried out.
    """
    m0, U0, swept, given = m, m * st.u, 0.0, 0.0
    ratio = (p_res / st.p) ** (1.0 / BLOW_DOWN_STEPS)
    for k in range(1, BLOW_DOWN_STEPS + 1):
        p_k = p_res if k == BLOW_DOWN_STEPS else st.p * ratio
        st2 = steam.ps(p_k, st.s)
        m2 = V * st2.rho
        share = max((m - m2) / m, 0.0)
        if k == BLOW_DOWN_STEPS:
            wall.outflow = share        # the film it sweeps: at the next exchange
            st, m = st2, m2
            break
        sw = wall.sweep(share)
        swept += sw
        if sw > 0.0:
            # the water at the surface's temperature (the wall's h_film)
            dH = sw * wall.h_L + wall.take_swept_heat()
            given += dH
            m3 = m2 + sw
            st, m = steam.du(m3 / V, (m2 * st2.u + dH) / m3), m3
        else:
            st, m = st2, m2
    # what left: the mass less the water the wall gave; the energy likewise
    return st, m, m - m0 - swept, m * st.u - U0 - given


def _fill_at_pressure(steam: Steam, H: float, m: float, V1: float, res: State) -> float:
    """The enthalpy [J/kg] of an end filled to ``V1`` at the reservoir's pressure from
    contents of mass ``m`` and enthalpy ``H`` (``m`` may be below nothing, when a wall
    condensed more than the end held): the root of ``m1 = V1 rho(p, h1)``, ``m1 h1 = H
    + h_res (m1 - m)``, bracketed, where the fixed point does not settle (very wet
    contents: the density changes fast with the enthalpy)."""
    from scipy.optimize import brentq
    c = H - res.h * m                 # h1 = h_res + c / m1
    h_f = steam.px(res.p, 0.0).h

    def f(m1):
        return m1 - V1 * steam.ph(res.p, res.h + c / m1).rho

    if c < 0.0:
        lo = c / (h_f - res.h) * (1.0 + 1e-9)      # h1 just above saturated water
    else:
        lo = max(m, 1e-9 * V1 * res.rho)
    hi = max(2.0 * lo, V1 * res.rho)
    while f(hi) < 0.0:
        hi *= 2.0
    m1 = brentq(f, lo, hi, rtol=1e-12)
    return res.h + c / m1


def step_end(steam: Steam, theta: np.ndarray, V: np.ndarray, conn: np.ndarray,
             st: State, m: float, chest: State, exhaust: State,
             wall=None, omega: float = 1.0) -> tuple[EndTrace, State, float]:
    """Step one end through one cycle of the grid.

    Parameters
    ----------
    steam : Steam
        The property tier.
    theta, V : ndarray
        Crank angles [rad] and end volumes [m3], ``n + 1`` points.
    conn : ndarray of int
        Connection over each of the ``n`` intervals: CLOSED, STEAM or EXHAUST.
    st, m : State, float
        State and mass [kg] at ``theta[0]``.
    chest, exhaust : State
        Reservoir states.
    wall : IdealPortWall, optional
        The end's wall (:class:`corliss.engine.wall.IdealPortWall`): it exchanges heat
        and water with the steam over each step before the ports act.
    omega : float
        Shaft speed [rad/s] (the wall's time).

    Returns
    -------
    trace : EndTrace
        The cycle's trace.
    state : State
        The state at the cycle's end.
    mass : float
        The mass at the cycle's end [kg].
    """
    n = len(theta) - 1
    p = np.empty(n + 1)
    T = np.empty(n + 1)
    x = np.empty(n + 1)
    mm = np.empty(n + 1)
    work = 0.0
    flows = np.zeros((3, 2))   # [connection] -> (mass in, enthalpy in) over the cycle
    prev = CLOSED
    for i in range(n):
        c = int(conn[i])
        if c != CLOSED and (c != prev or i == 0):
            res = chest if c == STEAM else exhaust
            # (1e-7: a state carried at the reservoir's pressure reads back within the
            # property solvers' tolerance)
            if st.p < res.p * (1 - 1e-7):
                st2, m2 = _fill(steam, st, m, V[i], res)
                dm, dH = m2 - m, res.h * (m2 - m)
            elif st.p > res.p * (1 + 1e-7):
                if wall is not None:
                    st2, m2, dm, dH = _blow_down_sweeping(steam, st, m, V[i], res.p, wall)
                else:
                    st2 = steam.ps(res.p, st.s)
                    m2 = V[i] * st2.rho
                    dm, dH = m2 - m, m2 * st2.u - m * st.u   # energy left = carried out
            else:
                st2, m2, dm, dH = st, m, 0.0, 0.0
            flows[c] += (dm, dH)
            st, m = st2, m2
        prev = c
        p[i], T[i], x[i], mm[i] = st.p, st.T, st.x, m
        dm_w = dH_w = 0.0
        if wall is not None:
            wall.record()
            st, m, dm_w, dH_w = wall.exchange(steam, st, m, V[i],
                                              (theta[i + 1] - theta[i]) / omega, c != CLOSED,
                                              chest if c == STEAM and V[i + 1] > V[i] else None)
        p0 = st.p
        if c == CLOSED:
            st = steam.ds(m / V[i + 1], st.s)
            work += 0.5 * (p0 + st.p) * (V[i + 1] - V[i])
        else:
            res = chest if c == STEAM else exhaust
            st, m1, dm, dH = _open_step(steam, st, m, V[i + 1], res, dm_w, dH_w)
            work += res.p * (V[i + 1] - V[i])
            flows[c] += (dm, dH)
            if wall is not None and dm < 0.0:
                wall.outflow = -dm / (m1 - dm)
            m = m1
    p[n], T[n], x[n], mm[n] = st.p, st.T, st.x, m
    totals = recs = None
    if wall is not None:
        wall.record()
        recs = np.array(wall.records)
        totals = {"Q_J": wall.Q, "Q_to_wall_J": wall.Q_to_wall, "T_deep_K": wall.T_deep}
    trace = EndTrace(theta, V, p, T, x, mm, work, flows[STEAM, 0], flows[STEAM, 1],
                     flows[EXHAUST, 0], flows[EXHAUST, 1], totals, recs)
    return trace, st, m


def run_cycles(steam: Steam, theta: np.ndarray, volumes: tuple[np.ndarray, np.ndarray],
               conns: tuple[np.ndarray, np.ndarray], chest: State, exhaust: State,
               tol: float, max_cycles: int, cycles: int | None = None, walls=None,
               omega: float = 1.0, every_point: bool = True):
    """Repeat the cycle until the indicated work is periodic.

    Each end starts full of exhaust steam; the cycle is periodic when the work of both
    ends changes by no more than ``tol`` of itself from one cycle to the next.

    With ``walls`` (an :class:`corliss.engine.wall.IdealPortWall` per end) the cycle is
    periodic when the work, each surface's temperature (against the supply's less the
    exhaust's temperature), each film (against the steam its end holds) and each deep
    wall's heat balance over the cycle (against the heat it took, or its bracket
    against the temperature scale, :class:`corliss.engine.wall.DeepWallSearch`) change
    by less than ``tol``; the deep wall takes its step once the rest is periodic, as the
    crank-resolved runner's (:func:`corliss.engine.steady.run_steady`).

    Parameters
    ----------
    steam : Steam
        The property tier.
    theta : ndarray
        The crank grid [rad], ``n + 1`` points (:func:`stepping_grid`).
    volumes : (ndarray, ndarray)
        Head- and crank-end volumes at the grid's points [m3].
    conns : (ndarray, ndarray)
        Head- and crank-end connections over the ``n`` intervals
        (:func:`connection_from_areas`).
    chest, exhaust : State
        Reservoir states.
    tol : float
        Relative change of the cycle's work that counts as periodic [-].
    max_cycles : int
        Most cycles run when ``cycles`` is None (three times as many with walls).
    cycles : int, optional
        Run exactly this many cycles, without the test.
    walls : list of IdealPortWall, optional
        Head and crank walls (skin model).
    omega : float
        Shaft speed [rad/s] (the walls' time).
    every_point : bool
        Keep every point of every cycle; false: of each cycle but the last only its
        first point (:func:`first_point`), so that the cycles run take no memory beyond
        what a run recording once a cycle writes.

    Returns
    -------
    traces : list of (EndTrace, EndTrace)
        Head and crank traces of every cycle run.
    converged_after : int or None
        Cycles it took (None when ``cycles`` fixed the count or it did not converge).
    """
    states = []
    for V in volumes:   # start each end full of exhaust steam
        states.append((exhaust, V[0] * exhaust.rho))
    traces: list[tuple[EndTrace, ...]] = []
    w_prev = None
    n_max = cycles if cycles is not None else max_cycles * (3 if walls else 1)
    converged = None
    dT_scale = max(chest.T - exhaust.T, 1.0)
    for k in range(1, n_max + 1):
        out = []
        start = [(w.T_deep + w.dT, w.film) for w in walls] if walls else []
        for j in range(2):
            if walls:
                walls[j].begin_cycle()
            tr, st, m = step_end(steam, theta, volumes[j], conns[j], *states[j], chest, exhaust,
                                 walls[j] if walls else None, omega)
            states[j] = (st, m)
            out.append(tr)
        if traces and not every_point:
            traces[-1] = tuple(first_point(tr) for tr in traces[-1])
        traces.append(tuple(out))
        w = out[0].work_J + out[1].work_J
        change = abs(w - w_prev) / max(abs(w), 1e-300) if w_prev is not None else math.inf
        if walls:
            inner = change
            for (t0, f0), wl, tr in zip(start, walls, out):
                inner = max(inner, abs(wl.T_deep + wl.dT - t0) / dT_scale,
                            abs(wl.film - f0) / max(float(np.max(tr.m_kg)), 1e-300))
            # each wall's balance against its own heat, or its bracket against the
            # temperature scale (as the crank-resolved runner's, corliss.engine.steady)
            trusted = inner <= tol
            steps = [wl.deep_step(False, dT_scale=dT_scale, trusted=trusted) for wl in walls]
            settled = inner <= max(10.0 * tol, 0.1 * max(abs(s[0]) for s in steps) / dT_scale)
            if settled:
                for wl in walls:
                    wl.deep_step(True, dT_scale=dT_scale, trusted=trusted)
            change = max(inner, max(s[1] for s in steps))
        if cycles is None and change <= tol:
            converged = k
            break
        w_prev = w
    return traces, converged


def first_point(trace: EndTrace) -> EndTrace:
    """A cycle's trace cut to its first point: the start of the cycle, its totals whole.

    Parameters
    ----------
    trace : EndTrace
        One end over one cycle.

    Returns
    -------
    EndTrace
        The same totals (work, steam, enthalpy, wall), each array its first entry only
        (copied, so the cycle's arrays are freed).
    """
    return replace(trace, theta_rad=trace.theta_rad[:1].copy(), V_m3=trace.V_m3[:1].copy(),
                   p_Pa=trace.p_Pa[:1].copy(), T_K=trace.T_K[:1].copy(),
                   x=trace.x[:1].copy(), m_kg=trace.m_kg[:1].copy(),
                   wall_records=None if trace.wall_records is None
                   else trace.wall_records[:1].copy())


def connection_from_areas(open_steam: np.ndarray, open_exhaust: np.ndarray) -> np.ndarray:
    """Connection code of each interval from port-open masks.

    Steam wins a blow-through (both ports open).

    Parameters
    ----------
    open_steam, open_exhaust : ndarray of bool
        Whether the steam port and the exhaust port are open over each interval; one
        shape.

    Returns
    -------
    ndarray of int8
        :data:`STEAM`, :data:`EXHAUST` or :data:`CLOSED` for each interval.
    """
    c = np.full(open_steam.shape, CLOSED, dtype=np.int8)
    c[open_exhaust] = EXHAUST
    c[open_steam] = STEAM
    return c


def stepping_grid(breakpoints: np.ndarray, step_rad: float) -> np.ndarray:
    """A crank grid over one turn through every kink of the port areas.

    Parameters
    ----------
    breakpoints : ndarray
        Crank angles where a port area has a kink [rad] (taken modulo ``2 pi``).
    step_rad : float
        The largest spacing [rad] (at least 4 intervals a turn).

    Returns
    -------
    ndarray
        Increasing crank angles from 0 to ``2 pi`` [rad], both included, points closer
        than 1e-10 rad merged.
    """
    n = max(int(math.ceil(2 * math.pi / step_rad)), 4)
    g = np.union1d(np.linspace(0.0, 2 * math.pi, n + 1), np.asarray(breakpoints) % (2 * math.pi))
    g = g[np.concatenate([[True], np.diff(g) > 1e-10])]
    return g
