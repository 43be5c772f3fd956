"""The compiled speed loop: cylinders, shaft, flywheel, load and governor integrated together.

The engine's control volumes are those of :mod:`corliss.engine.network`, with their
balances from :func:`corliss.engine.kernels.balances.balances`; here the crank speed omega is a
state instead of a constant, and three more states join it: the governor's coordinate
z in [0, 1], its rate dz/dt, and the time t.  Crank angle stays the independent
variable (a cycle is a fixed span of it, so per-cycle quantities are integrals over
one turn), and every rate is divided by omega.

Shaft (the crank train as one degree of freedom, Lagrange's equation for theta)::

    I_e(theta) domega/dt + 1/2 I_e'(theta) omega^2 = T_gas - T_friction - T_load
    I_e = I_flywheel + sum_c m_rec (ds_c/dtheta)^2          (``inertia`` effect)
    T_gas = sum_i p_i dV_i/dtheta                             (indicated torque)

so that d/dt (1/2 I_e omega^2) = (T_gas - T_friction - T_load) omega: the flywheel's
energy balances the torque integral (a test checks this).  Friction, when the scene
names it, is T_f0 + T_f1 omega; the load is T_ref f(t) (omega/omega_ref)^k with f
piecewise linear in time (steps are two points at one time) and k = 0, 1 or 2.

Governor (the common form of :mod:`corliss.governors`, its equation of motion
:func:`corliss.engine.kernels.governor.governor_motion`; spindle speed w_g = ratio
omega)::

    M(z) z'' + 1/2 M'(z) z'^2 = G(z) w_g^2 - R(z) - c z' - F_f sat(z'/v_e) - J(z) dw_g/dt

with M, M', G, R, J tabulated on a uniform grid of z and read linearly.  Coulomb
friction is regularised over a creep speed v_e (a governor held by friction creeps at
less than v_e, small against its travel in a cycle).  Stops at z = 0 and z = 1 are
inelastic: the right-hand side does not push past a stop, and after every step z is
clipped to [0, 1] with the velocity into the stop removed.

The governor's actuator value a = a0 + (a1 - a0) z either opens the throttle (the
steam pipe's effective area read from a table of opening) or sets the valve gear,
whose port areas come from a table over (setting, crank angle), both uniform grids,
read bilinearly.  Integration: Dormand-Prince 5(4)
(:func:`corliss.engine.kernels.dopri5.integrate_turn`), or a Rosenbrock tableau of
:data:`corliss.engine.kernels.tableaus.ROS_TABLEAUS`
(:func:`corliss.engine.kernels.rosenbrock.integrate_turn_ros`, the ``fast`` preset's
``ros4``), with no stops inside a cycle at the ports' kinks (they move with the
setting), but at a wall-heat schedule's switches where a run has one
(:func:`turn_stops`).

:func:`transient_rhs` is compiled without numba's reference counting
(``_nrt=False``), as :func:`corliss.engine.kernels.balances.rhs` is and for its reason: it
allocates nothing, and the counts on the arrays read from the network and table tuples
were most of its cost; the small helpers it calls are inlined into it, and so compiled
the same way.
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.kernels.balances import SWITCH_MARGIN_RAD, balances
from corliss.engine.kernels.clamps import (CL_ACCEPTED, CL_ACCEPTED_CODE, CL_REJECTED,
                                           CL_REJECTED_CODE, settle_visited, tally_clamps)
from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.governor import governor_motion
from corliss.engine.kernels.mechanism import TWO_PI, piston_kinematics, port_areas
from corliss.engine.kernels.data import (TRIP_AREA, TRIP_CLOSING, TRIP_GRID, TRIP_RELEASE,
                                         TRIP_SCALARS, TS_CLOSE_ANGLE, TS_CLOSE_TIME,
                                         TS_N_CLOSING, TS_N_SETTINGS, TS_OPEN_ANGLE)
from corliss.engine.kernels.properties import PR_DV, PR_P, node_states
from corliss.engine.kernels.stepping import put_column
from corliss.errors import RunError


# layout of the scalar parameters ``sc``
S_INERTIA, S_MREC, S_TF0, S_TF1, S_RATIO, S_DAMP, S_FRIC, S_VEPS = 0, 1, 2, 3, 4, 5, 6, 7


S_KLAW, S_TREF, S_WREF, S_ACT_GEAR, S_A0, S_A1, S_HAS_GOV, S_THR_EDGE = 8, 9, 10, 11, 12, 13, 14, 15


S_FREEZE, S_FRICTION_ON, S_WMIN, S_TRIP, S_SAFE_Z, S_SAFE_A, S_MAX_RHS = 16, 17, 18, 19, 20, 21, 22


#: written by :func:`integrate_turn`, summed over the turns: evaluations that clamped a
#: trial state to the steam properties' range, and the OR of their codes
S_CLAMPED_TRIALS, S_CLAMPED_TRIAL_CODE = 23, 24


#: and evaluations at visited states heated beyond the properties' greatest energy,
#: evaluated at it (the one clamp that does not stop a run; see
#: :mod:`corliss.engine.crank_resolved`)
S_CLAMPED_HOT = 25


#: the Rosenbrock loop's next step [rad], carried from turn to turn (0: none yet)
S_STEP = 26


N_SCALARS = 27


# the extra states after the network's, relative to its length
X_OMEGA, X_Z, X_ZDOT, X_TIME, X_WLOAD, X_WFRIC, X_WGAS, X_ZDT, X_ADT = 0, 1, 2, 3, 4, 5, 6, 7, 8


N_EXTRA = 9


#: what a recorded step keeps: theta, omega, z, actuator, t, T_gas, T_load, then
#: p of every node
N_REC = 7


@njit(cache=True, inline="always")
def _lin(grid0, dgrid, table, x):
    """Linear interpolation in a table on a uniform grid, clamped at its ends."""
    n = table.shape[0]
    f = (x - grid0) / dgrid
    if f <= 0.0:
        return table[0]
    if f >= n - 1:
        return table[n - 1]
    k = int(f)
    w = f - k
    return table[k] * (1.0 - w) + table[k + 1] * w


@njit(cache=True, inline="always")
def uniform_cell(x, x0, x1, n):
    """The cell of a value on a uniform grid, and its weight, clamped to the grid.

    Parameters
    ----------
    x : float
        The value.
    x0, x1 : float
        The grid's first and last points (``x1 > x0`` when ``n >= 2``).
    n : int
        Points of the grid.

    Returns
    -------
    k : int
        The cell: ``x`` lies between points ``k`` and ``k + 1``.
    w : float
        The weight of point ``k + 1`` [-], 0 to 1 ((0, 0) for a single point).
    """
    if n < 2:
        return 0, 0.0
    f = (x - x0) / (x1 - x0) * (n - 1)
    if f < 0.0:
        f = 0.0
    if f > n - 1:
        f = n - 1.0
    k = int(f)
    if k > n - 2:
        k = n - 2
    return k, f - k


@njit(cache=True, inline="always")
def load_factor(t, lt, lf):
    """The load schedule ``f(t)``: piecewise linear, constant beyond its ends.

    At a step (two points at one time) the value after it.

    Parameters
    ----------
    t : float
        Time [s].
    lt : ndarray
        The schedule's times [s], non-decreasing.
    lf : ndarray
        The load fractions at those times [-].

    Returns
    -------
    float
        ``f(t)`` [-].
    """
    n = lt.shape[0]
    if t <= lt[0]:
        return lf[0]
    if t >= lt[n - 1]:
        return lf[n - 1]
    k = np.searchsorted(lt, t, side="right") - 1
    dt = lt[k + 1] - lt[k]
    if dt <= 0.0:
        return lf[k + 1]
    return lf[k] + (lf[k + 1] - lf[k]) * (t - lt[k]) / dt


@njit(cache=True, inline="always")
def governed_areas(th, s, omega, net, tr, pa):
    """Port areas of the governed cylinders at a gear setting.

    Bilinear in the (setting, crank angle) table; with a trip gear, the steam valves
    released at the setting's cam and closed by the dash-pot in its own time
    (:func:`trip_areas`).

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    s : float
        The gear's setting [-] (the governor's actuator value).
    omega : float
        Shaft speed [rad/s] (the dash-pot closes in time, not angle).
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tr : LoopArrays
        The loop's tables (:attr:`corliss.engine.transient.LoopTables.tr`): scalars
        ``sc`` (indices ``S_*``), load times [s] and fractions [-], setting grid [-],
        port areas over (setting, crank angle) [m2], governed cylinders, governor
        tables (M, M', G, R, J on a uniform z grid), trip tables, throttle areas [m2].
    pa : ndarray
        The port areas [m2], shape (cylinders, 4), overwritten for the governed
        cylinders.
    """
    sc, sgrid, area_s, governed = tr.sc, tr.setting_grid, tr.area_s, tr.governed
    phase = net.phase
    ns = sgrid.shape[0]
    nth = area_s.shape[3] - 1
    j, ws = uniform_cell(s, sgrid[0], sgrid[ns - 1], ns)
    j1 = j + 1 if ns > 1 else j
    for c in range(governed.shape[0]):
        if governed[c] == 0:
            continue
        t = (th + phase[c]) % TWO_PI
        ft = t / TWO_PI * nth
        k = int(ft)
        if k > nth - 1:
            k = nth - 1
        wt = ft - k
        for p in range(4):
            a0 = area_s[c, p, j, k] * (1.0 - wt) + area_s[c, p, j, k + 1] * wt
            a1 = area_s[c, p, j1, k] * (1.0 - wt) + area_s[c, p, j1, k + 1] * wt
            pa[c, p] = a0 * (1.0 - ws) + a1 * ws
        if sc[S_TRIP] > 0.0:
            trip_areas(t, s, omega, tr, c, pa)


@njit(cache=True, inline="always")
def trip_areas(t, s, omega, tr, c, pa):
    """A trip gear's steam ports (0: head, 2: crank) after the release.

    The latched opening (as tabulated) until the cam releases the valve at its release
    angle, then at most the opening at release times the dash-pot's closing fraction
    of the time since release, until the latched valve would have closed anyway.

    Parameters
    ----------
    t : float
        The cylinder's own crank angle, within one turn [rad].
    s : float
        The gear's setting [-].
    omega : float
        Shaft speed [rad/s].
    tr : LoopArrays
        The loop's tables (:attr:`corliss.engine.transient.LoopTables.tr`): scalars
        ``sc`` (indices ``S_*``), load times [s] and fractions [-], setting grid [-],
        port areas over (setting, crank angle) [m2], governed cylinders, governor
        tables (M, M', G, R, J on a uniform z grid), trip tables, throttle areas [m2].
    c : int
        The cylinder.
    pa : ndarray
        The port areas [m2], shape (cylinders, 4), the steam ports' reduced in place.
    """
    trip = tr.trip
    # trip rows TRIP_*, its scalars' columns TS_* (kernels.data)
    sg = trip[TRIP_GRID]
    n = int(trip[TRIP_SCALARS, TS_N_SETTINGS])
    nf = int(trip[TRIP_SCALARS, TS_N_CLOSING])
    tclose = trip[TRIP_SCALARS, TS_CLOSE_TIME]
    for e in range(2):
        port = 2 * e
        k, w = uniform_cell(s, sg[0], sg[n - 1], n)
        k1 = k + 1 if n > 1 else k
        r0 = trip[TRIP_RELEASE + e, k]
        r1 = trip[TRIP_RELEASE + e, k1]
        if math.isnan(r0) or math.isnan(r1):
            continue
        rel = r0 * (1.0 - w) + r1 * w
        open_ang = trip[TRIP_SCALARS, TS_OPEN_ANGLE + e]
        close_ang = trip[TRIP_SCALARS, TS_CLOSE_ANGLE + e]
        # angles measured from the latched opening, so the window does not wrap
        since_open = (t - open_ang) % TWO_PI
        rel_from_open = (rel - open_ang) % TWO_PI
        window = (close_ang - open_ang) % TWO_PI
        if rel_from_open >= window:
            continue
        if since_open < rel_from_open or since_open > window:
            continue
        a_rel = trip[TRIP_AREA + e, k] * (1.0 - w) + trip[TRIP_AREA + e, k1] * w
        tau = (since_open - rel_from_open) / omega
        frac = _lin(0.0, tclose / (nf - 1), trip[TRIP_CLOSING, :nf], tau) if tau < tclose else 0.0
        lim = a_rel * frac
        if pa[c, port] > lim:
            pa[c, port] = lim


@njit(cache=True, inline="always")
def actuator(z, sc):
    """The governor's actuator value at its coordinate ``z``: a gear's setting or a
    throttle's opening, linear over the actuator's range, or the safety cams' value
    where a Corliss governor has fallen below its range.

    Parameters
    ----------
    z : float
        The governor's coordinate [-] (clipped to 0 to 1).
    sc : ndarray
        The loop's scalars (``S_A0``, ``S_A1``, ``S_SAFE_Z``, ``S_SAFE_A``).

    Returns
    -------
    float
        The actuator's value [-].
    """
    zc = min(max(z, 0.0), 1.0)
    if zc < sc[S_SAFE_Z]:      # the safety cams (a Corliss governor fallen below its range)
        return sc[S_SAFE_A]
    return sc[S_A0] + (sc[S_A1] - sc[S_A0]) * zc


@njit(cache=True, _nrt=False)
def transient_rhs(th, y, dy, net, tier, tab, perf, pr, pa, tr, out):
    """Derivatives with respect to crank angle of the whole loop.

    The network's balances at the state's speed (written into ``net.omega[0]``), the
    governor's actuator applied to the throttle's area or the gear's ports, the shaft
    and the governor as in the module's docstring, and the work quadratures.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    y : ndarray
        The state: the network's (:class:`~corliss.engine.network.Network`), then the
        :data:`N_EXTRA` loop states (``X_*``: speed [rad/s], z [-], dz/dt [1/s], time
        [s], load, friction and gas work [J], integrals of z and actuator over time
        [s]).
    dy : ndarray
        Written: the derivatives per radian, of ``y``'s shape.
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier (:data:`corliss.engine.kernels.properties.TIER_TABLE` or
        ``TIER_PERFECT``).
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,).
    pr : ndarray
        Scratch, written: the node properties (rows as in
        :func:`corliss.engine.kernels.properties.node_states`), shape (PR_ROWS, nodes).
    pa : ndarray
        Scratch for the port areas [m2], shape (cylinders, 4).
    tr : LoopArrays
        The loop's tables (:attr:`corliss.engine.transient.LoopTables.tr`): scalars
        ``sc`` (indices ``S_*``), load times [s] and fractions [-], setting grid [-],
        port areas over (setting, crank angle) [m2], governed cylinders, governor
        tables (M, M', G, R, J on a uniform z grid), trip tables, throttle areas [m2].
    out : ndarray
        Written, for recording: indicated torque ``T_gas`` [N m], load torque [N m],
        actuator value [-] and ``domega/dt`` [rad/s2]; shape (4,).
    """
    sc, lt, lf, gov = tr.sc, tr.load_t, tr.load_f, tr.gov
    nv = net.node_kind.shape[0]
    nn = y.shape[0] - N_EXTRA
    omega = y[nn + X_OMEGA]
    if omega < sc[S_WMIN]:
        omega = sc[S_WMIN]
    z = y[nn + X_Z]
    zd = y[nn + X_ZDOT]
    zc = min(max(z, 0.0), 1.0)
    act = actuator(z, sc)
    net.omega[0] = omega
    node_states(th, y, net, tier, tab, perf, pr)
    port_areas(th, net, pa)
    if sc[S_HAS_GOV] > 0.0:
        if sc[S_ACT_GEAR] > 0.0:
            governed_areas(th, act, omega, net, tr, pa)
        else:
            e = int(sc[S_THR_EDGE])
            net.edge_area[e] = _lin(0.0, 1.0 / (tr.throttle.shape[0] - 1), tr.throttle, act)
    balances(th, y, pr, dy, net, pa)
    # shaft
    tgas = 0.0
    for i in range(nv):
        tgas += pr[PR_P, i] * pr[PR_DV, i]
    ie = sc[S_INERTIA]
    die = 0.0
    mrec = sc[S_MREC]
    if mrec > 0.0:
        for c in range(net.geometry.shape[0]):
            ds, d2s = piston_kinematics(th, net, c)
            ie += mrec * ds * ds
            die += 2.0 * mrec * ds * d2s
    t = y[nn + X_TIME]
    tload = sc[S_TREF] * load_factor(t, lt, lf)
    k = sc[S_KLAW]
    if k > 0.0:
        tload *= (omega / sc[S_WREF]) ** k
    tf = 0.0
    if sc[S_FRICTION_ON] > 0.0:
        tf = sc[S_TF0] + sc[S_TF1] * omega
    wdot = (tgas - tf - tload - 0.5 * die * omega * omega) / ie
    if sc[S_FREEZE] == 1.0:    # 1: speed and governor held; 2: the governor only
        wdot = 0.0
    dy[nn + X_OMEGA] = wdot / omega
    dy[nn + X_TIME] = 1.0 / omega
    dy[nn + X_WLOAD] = tload
    dy[nn + X_WFRIC] = tf
    dy[nn + X_WGAS] = tgas
    dy[nn + X_ZDT] = zc / omega
    dy[nn + X_ADT] = act / omega
    # governor
    zdd = 0.0
    if sc[S_HAS_GOV] > 0.0 and sc[S_FREEZE] == 0.0:
        ng = gov.shape[1]
        dz = 1.0 / (ng - 1)
        M = _lin(0.0, dz, gov[0], zc)
        dM = _lin(0.0, dz, gov[1], zc)
        G = _lin(0.0, dz, gov[2], zc)
        R = _lin(0.0, dz, gov[3], zc)
        J = _lin(0.0, dz, gov[4], zc)
        zd, zdd = governor_motion(z, zd, M, dM, G, R, J, sc[S_RATIO], sc[S_DAMP],
                                  sc[S_FRIC], sc[S_VEPS], omega, wdot)
        dy[nn + X_Z] = zd / omega
        dy[nn + X_ZDOT] = zdd / omega
    else:
        dy[nn + X_Z] = 0.0
        dy[nn + X_ZDOT] = 0.0
    out[0] = tgas
    out[1] = tload
    out[2] = act
    out[3] = wdot


@njit(cache=True)
def _project(y, nn):
    """Inelastic stops of the governor: z in [0, 1], no velocity into a stop."""
    z = y[nn + X_Z]
    if z < 0.0:
        y[nn + X_Z] = 0.0
        if y[nn + X_ZDOT] < 0.0:
            y[nn + X_ZDOT] = 0.0
    elif z > 1.0:
        y[nn + X_Z] = 1.0
        if y[nn + X_ZDOT] > 0.0:
            y[nn + X_ZDOT] = 0.0


@njit(cache=True, inline="always")
def _record(rec, k, t, y, nn, out):
    """Column ``k`` of a turn's record (:func:`integrate_turn`'s ``rec``): the shaft
    angle [rad], speed [rad/s], z [-], actuator [-], time [s], indicated and load
    torques [N m] (``out`` holds the actuator and the torques of the evaluation at
    ``t``, ``y``)."""
    rec[0, k] = t
    rec[1, k] = y[nn + X_OMEGA]
    rec[2, k] = y[nn + X_Z]
    rec[3, k] = out[2]
    rec[4, k] = y[nn + X_TIME]
    rec[5, k] = out[0]
    rec[6, k] = out[1]


@njit(cache=True, inline="always")
def _turn_end(io, out_theta, samples, y, nn, status, t_end, clamps, sc):
    """A turn's end, for both loops: the samples not reached take the last state, the
    status says when the run's time has passed, and the turn's clamped trials go into
    ``sc``; returns the status."""
    while io < out_theta.shape[0]:
        put_column(samples, io, y)
        io += 1
    if status == 0 and y[nn + X_TIME] >= t_end:
        status = 3
    sc[S_CLAMPED_TRIALS] += clamps[CL_REJECTED]
    sc[S_CLAMPED_TRIAL_CODE] = float(int(sc[S_CLAMPED_TRIAL_CODE]) | int(clamps[CL_REJECTED_CODE]))
    return status


@njit(cache=True)
def _visited_clamps(clamps, sc):
    """A visited state needed a clamp: stop the run, unless it was only heated beyond
    the greatest energy (counted into ``sc[S_CLAMPED_HOT]``)."""
    code = int(clamps[CL_ACCEPTED_CODE])
    if code & ~8:
        _clamp_error(code)
    sc[S_CLAMPED_HOT] += clamps[CL_ACCEPTED]
    clamps[CL_ACCEPTED] = 0.0
    clamps[CL_ACCEPTED_CODE] = 0.0


@njit(cache=True)
def _clamp_error(code):
    """Stop the run: an accepted step needed a state clamped to the range of the steam
    properties (the bits of :data:`corliss.thermo.steam_table.CLAMP_CODES`); the
    message names the scene quantity that most likely caused it."""
    if code & 1 or code & 16 or code & 32:
        raise RunError("the steam in a cylinder left the range of the steam properties in an "
                       "accepted step (below their least density, or colder than the triple "
                       "point): a condenser vacuum deeper than they reach.  The run was "
                       "stopped rather than continue on clamped properties; check "
                       "exhaust.pressure")
    if code & 2:
        raise RunError("the steam in a cylinder was compressed above the greatest density the "
                       "steam properties cover, in an accepted step.  The run was stopped "
                       "rather than continue on clamped properties; check supply.pressure")
    if code & 8:
        raise RunError("the steam in a cylinder was heated beyond the range of the steam "
                       "properties in an accepted step.  The run was stopped rather than "
                       "continue on clamped properties; check supply.temperature")
    raise RunError("the steam in a cylinder became wetter than the range of the steam "
                   "properties in an accepted step.  The run was stopped rather than continue "
                   "on clamped properties; check supply.dryness")


@njit(cache=True, inline="always")
def _node_torques(pr, tq):
    """Each node's share of the indicated torque, p dV/dtheta [N m], of the latest
    evaluation (as :func:`transient_rhs` sums it)."""
    for i in range(tq.shape[0]):
        tq[i] = pr[PR_P, i] * pr[PR_DV, i]


@njit(cache=True, inline="always")
def turn_start(t, y, f0, phys, pr, cell, turn, att, clamps):
    """A turn's start, for both step loops: the derivative there, a visited state's
    (its clamps settled as one's), each node's share of the indicated torque
    (``turn.tq[0]``), and the record's first column when the turn records.

    Parameters
    ----------
    t : float
        The turn's start [rad].
    y : ndarray
        The state there.
    f0 : ndarray
        Written: the derivative there (per radian).
    phys : Physics
        The network and the steam's properties
        (:class:`~corliss.engine.kernels.data.Physics`).
    pr, cell : ndarray
        Scratch: the node properties and the port areas [m2].
    turn : LoopTurn
        The turn (:class:`~corliss.engine.kernels.data.LoopTurn`).
    att : ndarray
        A step attempt's clamp tally, shape (4,), used and cleared.
    clamps : ndarray
        The turn's clamp counts, shape (6,), updated.

    Returns
    -------
    int
        The record's columns filled: 1 when the turn records, else 0.
    """
    out = turn.out[0]
    transient_rhs(t, y, f0, phys.net, phys.tier, phys.tab, phys.perf, pr, cell, turn.tr, out)
    _node_torques(pr, turn.tq[0])
    tally_clamps(pr, t, att)
    settle_visited(att, clamps)
    if turn.record:
        _record(turn.rec, 0, t, y, y.shape[0] - N_EXTRA, out)
        return 1
    return 0


@njit(cache=True, inline="always")
def turn_restart(t, y, f0, phys, pr, cell, turn, att, clamps):
    """A segment's start after a stop inside a turn (:func:`turn_stops`), for both step
    loops: as :func:`turn_start`, the derivative there afresh (the right-hand side
    switches at the stop, so the last step's end derivative may be the other side's),
    its clamps settled as a visited state's and the node torques taken, but nothing
    recorded (the stop's state is the last accepted step's end, recorded already).

    Parameters
    ----------
    t : float
        The stop [rad].
    y : ndarray
        The state there.
    f0 : ndarray
        Written: the derivative there (per radian).
    phys, pr, cell, turn, att, clamps
        As :func:`turn_start`'s.

    Returns
    -------
    float
        The shaft angle the derivative was read at [rad], past the switch: where the
        segment's Jacobian must be read too, so that its differences are taken from
        ``f0``'s window (:func:`corliss.engine.kernels.rosenbrock._ros_steps`).
    """
    # read past the switch (the stop is SWITCH_MARGIN_RAD short of it): the segment's
    # first stage must see the window it integrates
    te = t + 2.0 * SWITCH_MARGIN_RAD
    transient_rhs(te, y, f0, phys.net, phys.tier, phys.tab, phys.perf, pr, cell, turn.tr,
                  turn.out[0])
    _node_torques(pr, turn.tq[0])
    tally_clamps(pr, te, att)
    settle_visited(att, clamps)
    return te


def turn_stops(th0: float, inner_rad) -> np.ndarray:
    """The stops of a turn from ``th0``: its start and end, and between them each of
    ``inner_rad`` (shaft angles, any multiple of 2 pi) that falls inside the turn.

    The step loops restart at each stop (a steady cycle's
    :meth:`corliss.engine.network.Network.stops`): a wall-heat schedule switches there,
    and a switch inside a step is integrated only to the step's error.

    Parameters
    ----------
    th0 : float
        The turn's start [rad].
    inner_rad : array_like or None
        Shaft angles of the switches [rad]; None or empty for none.

    Returns
    -------
    ndarray
        Increasing shaft angles [rad], ``th0`` first and ``th0 + 2 pi`` last, each switch
        between put :data:`SWITCH_MARGIN_RAD` short of it; just the two ends without
        switches (the loop's one segment).
    """
    if inner_rad is None or len(inner_rad) == 0:
        return np.array([th0, th0 + TWO_PI])
    rel = sorted({float(p - th0 - SWITCH_MARGIN_RAD) % TWO_PI for p in inner_rad})
    inner = [th0 + r for r in rel if 1e-8 < r < TWO_PI - 1e-8]
    return np.array([th0] + inner + [th0 + TWO_PI])


@njit(cache=True, inline="always")
def turn_accepted(t, y, f0, phys, pr, cell, turn, att, clamps, n_rec):
    """After an accepted step of a turn, for both step loops (``y`` and ``f0`` the
    state and derivative at its end, ``turn.out[0]`` that evaluation's outputs): the
    governor's stops (:func:`_project`), the derivative evaluated afresh where one was
    struck (a visited state: its clamps settled, a stop of the run raised as
    :func:`_visited_clamps` says, the node torques ``turn.tq[0]`` taken), and the step
    recorded while the record has room.

    Parameters
    ----------
    t : float
        The step's end [rad].
    y : ndarray
        The state there, projected in place.
    f0 : ndarray
        The derivative there, evaluated again in place where a stop was struck.
    phys, pr, cell, turn, att, clamps
        As :func:`turn_start`'s.
    n_rec : int
        The record's columns filled so far.

    Returns
    -------
    nfev : int
        Right-hand-side evaluations spent (0 or 1).
    n_rec : int
        The record's columns filled now.
    """
    nn = y.shape[0] - N_EXTRA
    out = turn.out[0]
    nfev = 0
    before = y[nn + X_Z]
    _project(y, nn)
    if y[nn + X_Z] != before:   # a stop was struck: restart the derivative
        transient_rhs(t, y, f0, phys.net, phys.tier, phys.tab, phys.perf, pr, cell, turn.tr,
                      out)
        _node_torques(pr, turn.tq[0])
        tally_clamps(pr, t, att)
        settle_visited(att, clamps)
        if clamps[CL_ACCEPTED] > 0.0:
            _visited_clamps(clamps, turn.tr.sc)
        nfev = 1
    if turn.record and n_rec < turn.rec.shape[1]:
        # out holds the values at the step's end
        _record(turn.rec, n_rec, t, y, nn, out)
        n_rec += 1
    return nfev, n_rec
