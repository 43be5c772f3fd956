"""The explicit step loops: Dormand-Prince 5(4) over a steady cycle (:func:`cycle_dopri5`,
restarted at every kink of the port areas) and over a turn of the governed loop
(:func:`integrate_turn`), both by the one step loop :func:`_dopri5_steps`, and the
classical fourth-order Runge-Kutta method at a fixed step (:func:`cycle_rk4`).
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.kernels.balances import rhs
from corliss.engine.kernels.clamps import (CL_ACCEPTED, CL_NODE, settle_clamps,
                                           settle_trial, settle_visited, tally_clamps,
                                           visited_clamp_off)
from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.data import DopriScratch, LoopTurn, Physics, StepControl
from corliss.engine.kernels.loop import (N_EXTRA, N_REC, S_MAX_RHS, S_WMIN, X_OMEGA,
                                         _turn_end, _visited_clamps, transient_rhs,
                                         turn_accepted, turn_restart, turn_start, turn_stops)
from corliss.engine.kernels.mechanism import TWO_PI
from corliss.engine.kernels.properties import PR_ROWS
from corliss.engine.kernels.stepping import (copy_into, emit_samples, initial_step,
                                             put_column, segment_start, step_factor,
                                             turn_first_step)
from corliss.engine.kernels.tableaus import DOPRI_NODES, dopri_error, dopri_stage


def cycle_dopri5(y0, stops, out_theta, rtol, atol, net, tier, tab, perf, max_rhs):
    """:func:`integrate_cycle` with Dormand-Prince 5(4) (see the module docstring).

    Allocates the scratch (in Python: no compiled function to compile for it) and hands
    over to the compiled step loop :func:`_dopri5_steps`.

    Parameters
    ----------
    y0 : ndarray
        The state at ``stops[0]``; shape (n_state,).
    stops : ndarray
        Shaft angles [rad], increasing: the segments between them are integrated
        with a restart at each (:meth:`corliss.engine.network.Network.stops`).
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    rtol : float
        Relative tolerance [-].
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n_state,).
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.

    Returns
    -------
    y_end : ndarray
        The state at ``stops[-1]``; shape (n_state,).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n_state, outputs).
    nfev : int
        Right-hand-side evaluations spent.
    ok : bool
        False when the step size collapsed, the state went non-finite or more than
        ``max_rhs`` evaluations were spent.
    clamps : ndarray
        Evaluations that clamped a state, shape (6,), indexed by ``CL_*``: at visited
        states (the ends of accepted steps) and at trial states (stages, probes,
        rejected steps) apart.
    """
    n = y0.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    clamps = np.zeros(6)
    clamps[CL_NODE] = -1.0
    scratch = DopriScratch(np.empty((3, n)), np.empty((7, n)),
                           np.full((PR_ROWS, net.node_kind.shape[0]), np.nan),
                           np.empty((net.port_npts.shape[0], 4)), clamps, np.zeros((2, 4)))
    nfev, status, _ = _dopri5_steps(y, samples, stops, out_theta,
                                    StepControl(rtol, atol, max_rhs, 0),
                                    Physics(net, tier, tab, perf), scratch, True, None)
    return y, samples, nfev, status == 0, clamps


#: The position of :func:`_dopri5_steps`'s ``turn`` among its arguments: None for a
#: steady cycle, a :class:`~corliss.engine.kernels.data.LoopTurn` for a turn of the
#: governed loop; numba compiles and caches a version for each.
DOPRI_TURN_ARG = 8


@njit(cache=True, _nrt=False)
def _dopri5_steps(y, samples, stops, out_theta, ctl, phys, scratch, cycle, turn):
    """The Dormand-Prince step loop of a steady cycle (:func:`cycle_dopri5`) and of a
    turn of the governed loop (:func:`integrate_turn`), on scratch its caller allocated
    (no reference counts).

    ``y`` is advanced to the end (``stops[-1]``), ``samples`` and ``scratch.clamps``
    written.  A steady cycle (``cycle`` True, ``turn`` None): the network's right-hand
    side :func:`~corliss.engine.kernels.balances.rhs` between the stops, each segment
    from :func:`initial_step` (or the last segment's step), a step whose end needed the
    properties clamped retried shorter, and no more.  A turn (``cycle`` None, ``turn``
    the loop's :class:`~corliss.engine.kernels.data.LoopTurn`): one segment (``stops``
    the turn's start and end) or more (a wall-heat schedule's switches between,
    :func:`~corliss.engine.kernels.loop.turn_stops`), the loop's right-hand side
    :func:`~corliss.engine.kernels.loop.transient_rhs`, the first step
    :func:`turn_first_step`'s (a later segment's the last one's, its start's
    derivative evaluated afresh, :func:`~corliss.engine.kernels.loop.turn_restart`), a visited state's clamp stopping the run
    (:func:`~corliss.engine.kernels.loop._visited_clamps`), the governor's stops after
    each accepted step (the derivative evaluated again where one was struck), each
    accepted step recorded, and the run stopped where the engine stalls.

    Each version holds only its own code, by numba's pruning of the branches on an
    argument compared with None, before it types the function: it decides ``x is None``
    only where ``x`` *is* None (where ``x`` is a tuple it keeps both branches and types
    them, compiling every function they call).  So the cycle's code sits under ``if
    cycle is not None`` (None in a turn), the turn's under ``if turn is not None`` (None
    in a cycle), never under an ``else`` of the other's test.  Written so, the turn's
    version compiled the network's right-hand side :func:`rhs` too, for code it never
    runs: 11 s of the 34 s a first transient run of the ``standard`` preset took
    (process CPU, per function from numba's compile events), against 19 s without.

    Parameters
    ----------
    y : ndarray
        The state at ``stops[0]``, advanced in place; shape (n,).
    samples : ndarray
        Written: ``samples[:, k]`` the state at ``out_theta[k]``; shape (n, outputs).
    stops : ndarray
        Shaft angles [rad], increasing: the segments, each started afresh.
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    ctl : StepControl
        Tolerances and the budget of evaluations
        (:class:`~corliss.engine.kernels.data.StepControl`, its ``jac_age`` unused).
    phys : Physics
        The network and the steam's properties
        (:class:`~corliss.engine.kernels.data.Physics`).
    scratch : DopriScratch
        (:class:`~corliss.engine.kernels.data.DopriScratch`), its clamp counts written.
    cycle : True or None
        True for a steady cycle, None for a turn.
    turn : LoopTurn or None
        The governed loop's turn, or None for a steady cycle.

    Returns
    -------
    nfev : int
        Right-hand-side evaluations spent.
    status : int
        0 ok; 1 the step size collapsed or the state went non-finite; 2 the engine
        stalled (a turn); 3 the run's time passed (a turn, finished anyway); 4 more
        than ``ctl.max_rhs`` evaluations.
    n_rec : int
        Columns of ``turn.rec`` filled (0 for a cycle).
    """
    rtol, atol, max_rhs = ctl.rtol, ctl.atol, ctl.max_rhs
    net, tier, tab, perf = phys.net, phys.tier, phys.tab, phys.perf
    K, pr, cell, clamps, tally = scratch.K, scratch.pr, scratch.cell, scratch.clamps, scratch.tally
    vec = scratch.vec
    f0, ytmp, tmp = vec[0], vec[1], vec[2]
    att, att_end = tally[0], tally[1]
    nn = y.shape[0] - N_EXTRA
    if turn is not None:
        tr = turn.tr
        sc = tr.sc
        out = turn.out[0]
    nfev = 0
    n_rec = 0
    status = 0
    io = 0
    while io < out_theta.shape[0] and out_theta[io] <= stops[0]:
        put_column(samples, io, y)
        io += 1
    h_prev = 0.0
    for seg in range(stops.shape[0] - 1):
        a = stops[seg]
        b = stops[seg + 1]
        if b - a <= 0.0:
            continue
        t = a
        if cycle is not None:
            segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att)
            h = min(h_prev, b - a) if h_prev > 0.0 else initial_step(f0, y, atol, rtol, b - a)
        if turn is not None:
            if seg == 0:
                n_rec = turn_start(t, y, f0, phys, pr, cell, turn, att, clamps)
                h = turn_first_step(f0, y, atol, rtol, 0.2)
            else:
                # a schedule's switch (loop.turn_stops): the derivative afresh, the
                # step carried on as a steady cycle's segment carries it
                turn_restart(t, y, f0, phys, pr, cell, turn, att, clamps)
                h = min(h_prev, b - a)
        nfev += 1
        while t < b:
            if t + h > b or b - (t + h) < 1e-12:
                h = b - t
            copy_into(K[0], f0)
            for s_ in range(1, 7):
                dopri_stage(y, K, s_, h, ytmp)
                if cycle is not None:
                    rhs(t + DOPRI_NODES[s_] * h, ytmp, K[s_], net, tier, tab, perf, pr, cell)
                if turn is not None:
                    transient_rhs(t + DOPRI_NODES[s_] * h, ytmp, K[s_], net, tier, tab, perf,
                                  pr, cell, tr, out)
                tally_clamps(pr, t + DOPRI_NODES[s_] * h, att_end if s_ == 6 else att)
            nfev += 6
            err = dopri_error(y, ytmp, K, h, atol, rtol)
            # ytmp: the new state; K[6]: the derivative there (FSAL).  In a cycle, a
            # step whose end needed the properties clamped (a volume emptied below
            # their least density, say) is no step of the physical path: it is retried
            # shorter, as an inaccurate one is (positivity by step control); in a turn,
            # such a step stops the run (but for steam heated beyond the greatest energy)
            if cycle is not None:
                accepted = (err <= 1.0 and visited_clamp_off(att_end) == 0) or h < 1e-12
            if turn is not None:
                accepted = err <= 1.0 or h < 1e-10
            settle_trial(att, clamps)
            settle_clamps(att_end, accepted, clamps)
            if turn is not None:
                if clamps[CL_ACCEPTED] > 0.0:
                    _visited_clamps(clamps, sc)
            if accepted:
                t1 = t + h
                io = emit_samples(io, out_theta, t, y, f0, t1, ytmp, K[6], samples, tmp)
                t = t1
                copy_into(y, ytmp)
                copy_into(f0, K[6])
                if turn is not None:
                    # (out holds the values at the last stage, the step's end: FSAL)
                    nf, n_rec = turn_accepted(t, y, f0, phys, pr, cell, turn, att, clamps,
                                              n_rec)
                    nfev += nf
                h_prev = h * step_factor(err, 0.9, -0.2)
                h = h_prev
                if turn is not None:
                    if y[nn + X_OMEGA] < sc[S_WMIN]:
                        status = 2
                        break
            elif err <= 1.0:
                h = 0.5 * h      # accurate, but through a state the properties do not hold
            else:
                h = h * max(0.2, 0.9 * err ** -0.2)
            if not (h > 0.0) or not math.isfinite(y[0]):
                status = 1
                break
            if nfev > max_rhs:
                status = 4
                break
        if status != 0:
            break
    if cycle is not None:
        if status == 0:
            while io < out_theta.shape[0]:
                put_column(samples, io, y)
                io += 1
    if turn is not None:
        status = _turn_end(io, out_theta, samples, y, nn, status, turn.t_end, clamps, sc)
    return nfev, status, n_rec


@njit(cache=True)
def cycle_rk4(y0, stops, out_theta, step, net, tier, tab, perf, max_rhs):
    """:func:`integrate_cycle` with the classical Runge-Kutta method at a fixed step.

    Each segment between stops is divided into equal steps no longer than ``step``.

    Parameters
    ----------
    y0 : ndarray
        The state at ``stops[0]``; shape (n_state,).
    stops : ndarray
        Shaft angles [rad], increasing: the segments between them are integrated
        with a restart at each (:meth:`corliss.engine.network.Network.stops`).
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    step : float
        The largest fixed step [rad].
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.

    Returns
    -------
    y_end : ndarray
        The state at ``stops[-1]``; shape (n_state,).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n_state, outputs).
    nfev : int
        Right-hand-side evaluations spent.
    ok : bool
        False when the step size collapsed, the state went non-finite or more than
        ``max_rhs`` evaluations were spent.
    clamps : ndarray
        Evaluations that clamped a state, shape (6,), indexed by ``CL_*``: at visited
        states (the ends of accepted steps) and at trial states (stages, probes,
        rejected steps) apart.
    """
    n = y0.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    f0 = np.empty(n)
    f1 = np.empty(n)
    K = np.empty((4, n))
    ynew = np.empty(n)
    ytmp = np.empty(n)
    tmp = np.empty(n)
    pr = np.full((PR_ROWS, net.node_kind.shape[0]), np.nan)
    cell = np.empty((net.port_npts.shape[0], 4))
    nfev = 0
    clamps = np.zeros(6)
    clamps[CL_NODE] = -1.0
    att = np.zeros(4)
    att_end = np.zeros(4)
    io = 0
    while io < out_theta.shape[0] and out_theta[io] <= stops[0]:
        put_column(samples, io, y)
        io += 1
    for seg in range(stops.shape[0] - 1):
        a = stops[seg]
        b = stops[seg + 1]
        if b - a <= 0.0:
            continue
        t = a
        segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att)
        nfev += 1
        nstep = int(math.ceil((b - a) / step - 1e-9))
        if nstep < 1:
            nstep = 1
        h = (b - a) / nstep
        for k_ in range(nstep):
            for i in range(n):
                ytmp[i] = y[i] + 0.5 * h * f0[i]
            rhs(t + 0.5 * h, ytmp, K[1], net, tier, tab, perf, pr, cell)
            tally_clamps(pr, t + 0.5 * h, att)
            for i in range(n):
                ytmp[i] = y[i] + 0.5 * h * K[1, i]
            rhs(t + 0.5 * h, ytmp, K[2], net, tier, tab, perf, pr, cell)
            tally_clamps(pr, t + 0.5 * h, att)
            for i in range(n):
                ytmp[i] = y[i] + h * K[2, i]
            rhs(t + h, ytmp, K[3], net, tier, tab, perf, pr, cell)
            tally_clamps(pr, t + h, att)
            for i in range(n):
                ynew[i] = y[i] + h / 6.0 * (f0[i] + 2 * K[1, i] + 2 * K[2, i] + K[3, i])
            t1 = b if k_ == nstep - 1 else t + h
            rhs(t1, ynew, f1, net, tier, tab, perf, pr, cell)
            tally_clamps(pr, t1, att_end)
            settle_trial(att, clamps)
            settle_visited(att_end, clamps)
            nfev += 4
            io = emit_samples(io, out_theta, t, y, f0, t1, ynew, f1, samples, tmp)
            t = t1
            copy_into(y, ynew)
            copy_into(f0, f1)
        if not math.isfinite(y[0]) or nfev > max_rhs:
            return y, samples, nfev, False, clamps
    while io < out_theta.shape[0]:
        put_column(samples, io, y)
        io += 1
    return y, samples, nfev, True, clamps


def integrate_turn(y0, th0, out_theta, rtol, atol, net, tier, tab, perf, tr, record, t_end,
                   inner=None):
    """Integrate one turn, from ``th0`` to ``th0 + 2 pi`` (dopri5, dense Hermite output).

    Allocates the scratch (in Python, as :func:`cycle_dopri5`: a compiled caller
    would have numba optimise the loop's right-hand side linked into it once more, 1.7 s
    of a first run) and hands over to the step loop :func:`_dopri5_steps`, which a
    steady cycle shares.

    Evaluations that clamped a state to the range of the steam properties are counted:
    at trial states (stages, rejected steps) into ``sc[S_CLAMPED_TRIALS]``; at a state
    the run visits (an accepted step's end) they stop the run
    (:class:`~corliss.errors.RunError`, naming the scene quantity to look at), but for
    steam heated beyond the greatest energy (into ``sc[S_CLAMPED_HOT]``).

    Parameters
    ----------
    y0 : ndarray
        The state at ``th0`` (see :func:`transient_rhs`).
    th0 : float
        Shaft angle at the turn's start [rad].
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    rtol : float
        Relative tolerance [-].
    atol : ndarray
        Absolute tolerances, in each component's unit, of ``y0``'s shape.
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier.
    tab : tuple
        The steam table's arrays.
    perf : ndarray
        The perfect tier's parameters, shape (3,).
    tr : LoopArrays
        The loop's tables (:attr:`corliss.engine.transient.LoopTables.tr`): scalars
        ``sc`` (indices ``S_*``; the clamp counts
        written), load times [s] and fractions [-], setting grid [-],
        port areas over (setting, crank angle) [m2], governed cylinders, governor
        tables (M, M', G, R, J on a uniform z grid), trip tables, throttle areas [m2].
    record : bool
        Whether to record every accepted step.
    t_end : float
        The run's end time [s].
    inner : array_like, optional
        Shaft angles [rad] where the turn restarts its step
        (:func:`~corliss.engine.kernels.loop.turn_stops`): a wall-heat schedule's
        switches.  None (the default) for one segment.

    Returns
    -------
    y_end : ndarray
        The state at the turn's end (or where it stopped).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n, outputs).
    rec : ndarray
        Shape (:data:`N_REC`, at most 40000): per accepted step (and the start), shaft
        angle [rad], speed [rad/s], z [-], actuator [-], time [s], indicated torque
        [N m] and load torque [N m]; filled up to ``n_rec`` when ``record``.
    n_rec : int
        Columns of ``rec`` filled.
    nfev : int
        Right-hand-side evaluations.
    status : int
        0 ok; 1 the step size collapsed; 2 the engine stalled (speed below
        ``sc[S_WMIN]``); 3 time ``t_end`` passed (the turn was finished anyway); 4 the
        turn exceeded the run-time budget (``sc[S_MAX_RHS]`` evaluations).

    Raises
    ------
    RunError
        A visited state needed a clamp other than the greatest energy's.
    """
    n = y0.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    nv = net.node_kind.shape[0]
    rec = np.empty((N_REC, 40000 if record else 1))
    stops = turn_stops(th0, inner)
    scratch = DopriScratch(np.empty((3, n)), np.empty((7, n)),
                           np.full((PR_ROWS, nv), np.nan),
                           np.empty((net.port_npts.shape[0], 4)), np.zeros(6),
                           np.zeros((2, 4)))
    nfev, status, n_rec = _dopri5_steps(y, samples, stops, out_theta,
                                        StepControl(rtol, atol, tr.sc[S_MAX_RHS], 0),
                                        Physics(net, tier, tab, perf), scratch, None,
                                        LoopTurn(tr, np.empty((2, 4)), rec, record, t_end,
                                                 np.empty((3, nv))))
    return y, samples, rec, n_rec, nfev, status
