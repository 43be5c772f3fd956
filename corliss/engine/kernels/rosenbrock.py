"""The Rosenbrock step loops: one loop for every tableau (the ode23s pair, ``ros4``,
RODAS3, RODAS4) over a steady cycle (:func:`cycle_ros`, compiled in versions by
whether the pair's controller and the finite-difference Jacobian are used), and over
a turn of the governed loop (:func:`integrate_turn_ros`).
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.kernels.balances import rhs
from corliss.engine.kernels.clamps import (CL_ACCEPTED, CL_NODE, settle_clamps,
                                           settle_trial, settle_visited, tally_clamps,
                                           visited_clamp_off)
from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.data import (LoopScratch, Physics, RosScratch, StepControl,
                                         StepScratch, Tableau)
from corliss.engine.kernels.jacobians import (LOOP_COLUMNS, _exact_jacobian_holds,
                                              _jacobian, _jacobian_exact, _loop_jacobian,
                                              _loop_w_inverse, _loop_w_solve, _w_inverse,
                                              _w_solve)
from corliss.engine.kernels.loop import (N_EXTRA, N_REC, S_MAX_RHS, S_STEP, S_WMIN,
                                         X_OMEGA, X_Z, _node_torques, _project, _record,
                                         _turn_end, _visited_clamps, transient_rhs)
from corliss.engine.kernels.mechanism import TWO_PI
from corliss.engine.kernels.properties import PR_ROWS
from corliss.engine.kernels.stepping import (copy_into, emit_samples, initial_step,
                                             predictive_factor, put_column, segment_start,
                                             starting_step, step_factor)
from corliss.engine.kernels.tableaus import (KIND_ODE23S, _D, _E32, tableau_argument,
                                             tableau_solution, tableau_stage_rhs)


def cycle_ros(y0, stops, out_theta, rtol, atol, net, tier, tab, perf, color, owner,
              max_rhs, jac_age, gam, tA, tC, tc, td, tb, te, same, expo, kind):
    """:func:`integrate_cycle` with a Rosenbrock method: the ode23s pair, or a tableau's.

    One compiled step loop for every Rosenbrock method (segments, Jacobian, W, step
    control, clamps, output), with the stages of the method: Shampine and Reichelt's
    2(3) pair of ode23s (``kind`` :data:`KIND_ODE23S`, its formulas as the paper
    writes them; the tableau's arrays are then unused) or those of a tableau
    (:data:`KIND_TABLEAU`, :data:`ROS_TABLEAUS`).  The ode23s pair evaluates the
    derivative at the step's end as its last stage, for every step; a tableau's method
    evaluates it (for the next step and the output) only for a step whose error passes.
    The ode23s pair's steps follow Gustafsson's predictive controller
    (:func:`predictive_factor`) from Hairer, Norsett and Wanner's starting step
    (:func:`starting_step`); a tableau's, the error alone (:func:`step_factor`) from
    :func:`initial_step`.  On the default card the error-alone control drove the pair's
    steps at the crank end's admission through a cycle of acceptance at an error of
    0.2, growth and rejection, onto a spurious solution of the pair (the cylinder
    0.5-1 % below the chest, at 0.3-0.4 deg steps: its midpoint stage overshoots the
    port's equilibrium into the steeper square-root flux and comes back reversed);
    the predictive controller keeps to the filling at 1.7 deg steps, with 353
    evaluations a cycle against 454.
    Allocates the scratch (in Python: no compiled function to compile for it) and hands
    over to the compiled step loop :func:`_ros_steps`.

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
    color : ndarray of int64
        The colour of each dynamic column
        (:meth:`corliss.engine.network.Network.column_colors`).
    owner : ndarray of int64
        Which column of each colour moves each row; shape (colours, n_state).
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.
    jac_age : int
        Accepted steps a Jacobian serves (:data:`JACOBIAN_AGE`); it is computed
        afresh at every segment's start and after a step rejected on a Jacobian
        older than the step.
    gam : float
        The method's diagonal gamma [-] (ode23s: 1 / (2 + sqrt 2)).
    tA, tC : ndarray
        The tableau's stage coefficients a_ij and c_ij, shape (stages, stages), below
        the diagonal [-].
    tc, td, tb, te : ndarray
        Its stage angles c_i (fractions of the step), the coefficients d_i of the time
        derivative, the weights b_i of the solution and e_i of the error [-]; shape
        (stages,) (ode23s: 4 stages' scratch).
    same : ndarray of int64
        Per stage: 0 evaluate, 1 its argument is the step's start, 2 the stage
        before's; shape (stages,).
    expo : float
        The exponent of the step's ratio to its error, ``-1/(order + 1)`` of the
        error estimate [-].
    kind : int
        :data:`KIND_ODE23S` or :data:`KIND_TABLEAU`.  The step loop takes it as
        ``pair``, True or None: numba prunes the branches of the other kind from a
        version compiled for None (``pair is None`` is known when it types the
        function), so a run compiles only its own kind's stages; likewise whether the
        network's Jacobian is analytic or by finite differences (``finite``, None or
        True).  With both, a first cycle of the ``standard`` preset compiled in 11.7 s
        instead of 16.7 s.

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
    ndyn = color.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    vec = np.empty((9, n))
    U = np.empty((tb.shape[0], n))
    J = np.zeros((n, ndyn))
    mats = np.empty((2, ndyn, ndyn))
    dl = np.empty(ndyn)
    pr = np.full((PR_ROWS, net.node_kind.shape[0]), np.nan)
    jd = np.full((max(12, PR_ROWS), net.node_kind.shape[0]), np.nan)   # also holds pr's rows (starting_step)
    cyl = np.empty((2, net.port_npts.shape[0], 4))
    clamps = np.zeros(6)
    clamps[CL_NODE] = -1.0
    tally = np.zeros((2, 4))
    nfev, ok = _ros_steps(y, samples, stops, out_theta,
                          StepControl(rtol, atol, max_rhs, jac_age),
                          Physics(net, tier, tab, perf), color, owner,
                          Tableau(gam, tA, tC, tc, td, tb, te, same, expo),
                          True if kind == KIND_ODE23S else None,
                          None if _exact_jacobian_holds.py_func(net) else True,
                          RosScratch(vec, U, J, mats, dl, pr, jd, cyl, clamps, tally))
    return y, samples, nfev, ok, clamps


@njit(cache=True, _nrt=False)
def _ros_steps(y, samples, stops, out_theta, ctl, phys, color, owner, tableau, pair, finite,
               scratch):
    """:func:`cycle_ros`'s steps, on scratch it allocated (no reference counts:
    the views of the scratch taken here cost nothing).  ``y`` is advanced to the
    cycle's end, ``samples`` and ``clamps`` written; returns the evaluations spent
    and whether the cycle ended well.  ``pair``: True for the ode23s pair, None for a
    tableau's method; ``finite``: True for a network whose Jacobian is taken by finite
    differences (:func:`_exact_jacobian_holds` false), None for the analytic one.  Each
    is a separate compiled version without the other's code.  ``ctl``
    (:class:`~corliss.engine.kernels.data.StepControl`), ``phys``
    (:class:`~corliss.engine.kernels.data.Physics`), ``tableau``
    (:class:`~corliss.engine.kernels.data.Tableau`) and ``scratch``
    (:class:`~corliss.engine.kernels.data.RosScratch`) are :func:`cycle_ros`'s."""
    rtol, atol, max_rhs, jac_age = ctl.rtol, ctl.atol, ctl.max_rhs, ctl.jac_age
    net, tier, tab, perf = phys.net, phys.tier, phys.tab, phys.perf
    gam, tA, tC, tc, td = tableau.gamma, tableau.A, tableau.C, tableau.c, tableau.d
    tb, te, same, expo = tableau.b, tableau.e, tableau.same, tableau.expo
    vec, U, J, mats, dl = scratch.vec, scratch.U, scratch.J, scratch.mats, scratch.dl
    pr, jd, cyl, clamps, tally = scratch.pr, scratch.jd, scratch.cyl, scratch.clamps, scratch.tally
    n = y.shape[0]
    ns = tb.shape[0]
    safety = 0.9
    # the ode23s pair's steps by Gustafsson's predictive controller, no growth on the
    # step after a rejection (:func:`predictive_factor`); a tableau's by the error alone
    predictive = pair is not None
    f0, f1, ytmp, tmp, T, x, yscale, yp, fp = (vec[0], vec[1], vec[2], vec[3], vec[4],
                                               vec[5], vec[6], vec[7], vec[8])
    for i in range(n):
        yscale[i] = atol[i] / rtol
    Winv, A = mats[0], mats[1]
    slope, cell = cyl[0], cyl[1]
    att, att_end = tally[0], tally[1]
    steps = StepScratch(pr, cell, att, yp, fp, dl, jd, slope)
    nfev = 0
    io = 0
    while io < out_theta.shape[0] and out_theta[io] <= stops[0]:
        put_column(samples, io, y)
        io += 1
    h_prev = 0.0
    h_acc = 0.0            # the last accepted step, and its error (at least 0.01)
    err_acc = 0.0
    rejected = False       # the last step tried was rejected
    t_end = -1.0           # the angle of the last accepted step's end, f0 evaluated there
    for seg in range(stops.shape[0] - 1):
        a = stops[seg]
        b = stops[seg + 1]
        if b - a <= 0.0:
            continue
        t = a
        if not (predictive and t_end == a):
            # (the ode23s pair's last step ended on this stop: f0 is the derivative at
            # this angle and state, evaluated and its clamps settled as a visited
            # state's; the area's kink changes the derivative's slope, not its value)
            segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att)
            nfev += 1
        if h_prev > 0.0:
            h = min(h_prev, b - a)
        elif predictive:
            h = starting_step(t, y, f0, atol, rtol, b - a, expo, phys, steps)
            nfev += 1
        else:
            h = initial_step(f0, y, atol, rtol, b - a)
        age = jac_age          # accepted steps since J and T were computed
        h_w = -1.0             # the step W was inverted for
        while t < b:
            if t + h > b or b - (t + h) < 1e-12:
                h = b - t
            if age >= jac_age:
                if finite is None:
                    # called from here, not through :func:`_jacobian`: through it, a call
                    # cost 2.2 us against 0.7 us (the default scene; numba's handling of a
                    # function that passes the network and table tuples on, it seems)
                    _jacobian_exact(t, y, J, T, net, tier, tab, perf, pr, cell, jd, slope)
                else:
                    nfev += _jacobian(t, y, f0, J, T, yscale, color, owner, phys, steps)
                age = 0
                h_w = -1.0
            hd = h * gam
            if h != h_w:
                _w_inverse(J, hd, Winv, A)
                h_w = h
            if pair is not None:
                # Shampine and Reichelt's formulas, k_i in U[i]; the end's derivative
                # is the third stage's argument
                for i in range(n):
                    x[i] = f0[i] + hd * T[i]
                _w_solve(J, Winv, hd, x, U[0])
                for i in range(n):
                    ytmp[i] = y[i] + 0.5 * h * U[0, i]
                rhs(t + 0.5 * h, ytmp, U[1], net, tier, tab, perf, pr, cell)
                tally_clamps(pr, t + 0.5 * h, att)
                for i in range(n):
                    x[i] = U[1, i] - U[0, i]
                _w_solve(J, Winv, hd, x, U[2])
                for i in range(n):
                    U[2, i] += U[0, i]
                    ytmp[i] = y[i] + h * U[2, i]
                rhs(t + h, ytmp, f1, net, tier, tab, perf, pr, cell)
                tally_clamps(pr, t + h, att_end)
                nfev += 2
                for i in range(n):
                    x[i] = (f1[i] - _E32 * (U[2, i] - U[1, i]) - 2.0 * (U[0, i] - f0[i])
                            + hd * T[i])
                _w_solve(J, Winv, hd, x, U[3])
                err = 0.0
                for i in range(n):
                    e = abs(h / 6.0 * (U[0, i] - 2.0 * U[2, i] + U[3, i]))
                    e /= atol[i] + rtol * max(abs(y[i]), abs(ytmp[i]))
                    if e > err:
                        err = e
                accepted = (err <= 1.0 and visited_clamp_off(att_end) == 0) or h < 1e-12
            else:
                # u_i = hd W^-1 (...), W = I - hd J: the stages of I/(gamma h) - J
                for st in range(ns):
                    if st == 0 or same[st] == 1:
                        copy_into(fp, f0)
                    elif same[st] == 0:
                        tableau_argument(y, U, tA, st, ytmp)
                        rhs(t + tc[st] * h, ytmp, fp, net, tier, tab, perf, pr, cell)
                        tally_clamps(pr, t + tc[st] * h, att)
                        nfev += 1
                    tableau_stage_rhs(fp, T, U, tC, td, st, h, x)
                    _w_solve(J, Winv, hd, x, U[st])
                    for i in range(n):
                        U[st, i] *= hd
                err = tableau_solution(y, U, tb, te, atol, rtol, ytmp)
                accepted = err <= 1.0 or h < 1e-12
                if accepted:
                    rhs(t + h, ytmp, f1, net, tier, tab, perf, pr, cell)
                    tally_clamps(pr, t + h, att_end)
                    nfev += 1
                    # a step whose end needed the properties clamped is retried shorter
                    accepted = visited_clamp_off(att_end) == 0 or h < 1e-12
            settle_trial(att, clamps)
            settle_clamps(att_end, accepted, clamps)
            if accepted:
                t1 = t + h
                io = emit_samples(io, out_theta, t, y, f0, t1, ytmp, f1, samples, tmp)
                t = t1
                t_end = t1
                copy_into(y, ytmp)
                copy_into(f0, f1)
                age += 1
                if predictive:
                    fac = predictive_factor(err, h, err_acc, h_acc, safety, expo)
                    if rejected:
                        fac = min(fac, 1.0)
                    h_acc = h
                    err_acc = max(err, 1e-2)
                else:
                    fac = step_factor(err, safety, expo)
                rejected = False
                h_prev = h * fac
                h = h_prev
            else:
                rejected = True
                if age > 0:
                    age = jac_age    # rejected on an old Jacobian: a fresh one
                if err <= 1.0:
                    h = 0.5 * h  # accurate, but through a state the properties do not hold
                else:
                    h = h * max(0.2, safety * err ** expo)
            if not (h > 0.0) or not math.isfinite(y[0]) or nfev > max_rhs:
                return nfev, False
    while io < out_theta.shape[0]:
        put_column(samples, io, y)
        io += 1
    return nfev, True


#: Accepted steps of the Rosenbrock methods one Jacobian serves (1: a fresh one every
#: step; the retry of a rejected step reuses the one of its start, which is the same).
#: Serving 2 or 4 steps cost more evaluations than it saved on the default card (more
#: and shorter steps), at ``fast``'s tolerance and at ``standard``'s.
JACOBIAN_AGE = 1


#: The tableau methods of :func:`cycle_ros`, by code from 3.
ROS_METHODS = ("ros4", "rodas3", "rodas4")


#: Every method :func:`cycle_ros` integrates (on :func:`_jacobian`).
ROSENBROCK_METHODS = ("rosenbrock",) + ROS_METHODS


#: :func:`cycle_ros`'s tableau arguments for the ode23s pair: its gamma and four
#: stages' scratch (its stages are its own formulas), its safety and exponent.
_ODE23S_ARGS = Tableau(_D, np.zeros((4, 4)), np.zeros((4, 4)), np.zeros(4), np.zeros(4),
                       np.zeros(4), np.zeros(4), np.zeros(4, dtype=np.int64), -1.0 / 3.0)


@njit(cache=True)
def integrate_turn_ros(y0, th0, out_theta, rtol, atol, phys, tr, record, t_end, color, owner,
                       tableau):
    """Integrate one turn as :func:`integrate_turn`, with a Rosenbrock method.

    The tableau's method of :func:`corliss.engine.kernels.rosenbrock.cycle_ros` (one of
    :data:`corliss.engine.kernels.tableaus.ROS_TABLEAUS`) on the Jacobian of
    :func:`_loop_jacobian`, one a step (the retry of a rejected step reuses it; the
    linear algebra is :func:`corliss.engine.kernels._w_inverse`'s and ``_w_solve``'s
    over the Jacobian's columns, which here are not the first states).  dopri5 is held
    by the stiff pressure equalisation through an open port to steps of 1 to 2 deg
    whatever its tolerance (an eigenvalue of -60 to -330 per radian on the
    Porter-Allen engine, the step times it at 2.2 to 3.1, the edge of its stability);
    this one steps over it, which pays at loose tolerances (``fast``) and on a steam
    chest's stiffer flow: at tight ones the Porter-Allen engine's port flow holds every
    method to such steps by its own pace, and the Jacobian's six evaluations a step
    then cost more than they save (:data:`corliss.engine.options.PRESETS`).  The step
    carries over from turn to turn (``sc[S_STEP]``).  Returns, raises and counts clamps
    as :func:`integrate_turn`; a step whose end needs the properties clamped (but for
    the greatest energy's) is retried shorter.

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
    phys : Physics
        The network's arrays and the steam's compiled properties
        (:class:`corliss.engine.kernels.data.Physics`).
    tr : LoopArrays
        The loop's tables (:attr:`corliss.engine.transient.LoopTables.tr`), as
        :func:`integrate_turn`; ``sc[S_STEP]`` read and written.
    record : bool
        Whether to record every accepted step.
    t_end : float
        The run's end time [s].
    color : ndarray of int64
        The colour of each dynamic column
        (:meth:`corliss.engine.network.Network.column_colors`).
    owner : ndarray of int64
        Which column of each colour moves each of the network's rows; shape (colours,
        n_state of the network).
    tableau : Tableau
        The method's tableau (:class:`corliss.engine.kernels.data.Tableau`): gamma,
        stage coefficients a_ij and c_ij, stage angles, coefficients of the derivative
        in crank angle, weights of the solution and of the error, which stages are
        evaluated, and the exponent of the step's ratio to its error [-].

    Returns
    -------
    y_end : ndarray
        The state at the turn's end (or where it stopped).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n, outputs).
    rec : ndarray
        Per accepted step, as :func:`integrate_turn`; shape (:data:`N_REC`, at most
        40000).
    n_rec : int
        Columns of ``rec`` filled.
    nfev : int
        Right-hand-side evaluations.
    status : int
        As :func:`integrate_turn`.

    Raises
    ------
    RunError
        A visited state needed a clamp other than the greatest energy's.
    """
    net, tier, tab, perf = phys.net, phys.tier, phys.tab, phys.perf
    gam, tA, tC, tc, td = tableau.gamma, tableau.A, tableau.C, tableau.c, tableau.d
    tb, te, same, expo = tableau.b, tableau.e, tableau.same, tableau.expo
    n = y0.shape[0]
    nn = n - N_EXTRA
    ndyn = color.shape[0]
    ns = tb.shape[0]
    nv = net.node_kind.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    nrec_max = 40000 if record else 1
    rec = np.empty((N_REC, nrec_max))
    n_rec = 0
    f0 = np.empty(n)
    f1 = np.empty(n)
    U = np.empty((ns, n))
    ytmp = np.empty(n)
    tmp = np.empty(n)
    m = ndyn + LOOP_COLUMNS.shape[0]
    J = np.zeros((n, m))
    Winv = np.empty((m, m))
    A = np.empty((m, m))
    xs = np.empty(m)
    T = np.empty(n)
    x = np.empty(n)
    yscale = atol / rtol
    yp = np.empty(n)
    fp = np.empty(n)
    dl = np.empty(ndyn)
    tq0 = np.empty(nv)
    tq1 = np.empty(nv)
    dtq = np.empty(nv)
    pr = np.full((PR_ROWS, nv), np.nan)
    pa = np.empty((net.port_npts.shape[0], 4))
    out = np.empty(4)
    out1 = np.empty(4)
    sc = tr.sc
    clamps = np.zeros(6)
    att = np.zeros(4)
    att_end = np.zeros(4)
    loop_scratch = LoopScratch(pr, pa, out1, att, yp, fp, dl, dtq)
    a = th0
    b = th0 + TWO_PI
    t = a
    transient_rhs(t, y, f0, net, tier, tab, perf, pr, pa, tr, out)
    _node_torques(pr, tq0)
    tally_clamps(pr, t, att)
    settle_visited(att, clamps)
    nfev = 1
    io = 0
    while io < out_theta.shape[0] and out_theta[io] <= a:
        put_column(samples, io, y)
        io += 1
    if record:
        _record(rec, 0, t, y, nn, out)
        n_rec = 1
    h = sc[S_STEP]
    if not (h > 0.0):
        scale = 0.0
        for i in range(n):
            v = abs(f0[i]) / (atol[i] + rtol * abs(y[i]))
            if v > scale:
                scale = v
        h = 0.01 * (rtol ** 0.25) / scale if scale > 0.0 else 0.01
        h = min(max(h, 1e-7), 0.05)
    fresh = True           # J and T are not yet those of the step's start
    h_w = -1.0             # the step W was inverted for
    status = 0
    while t < b:
        if t + h > b or b - (t + h) < 1e-12:
            h = b - t
        if fresh:
            nfev += _loop_jacobian(t, y, f0, tq0, J, T, yscale, color, owner, phys, tr,
                                   loop_scratch)
            fresh = False
            h_w = -1.0
        hd = h * gam
        if h != h_w:
            _loop_w_inverse(J, hd, Winv, A, ndyn, nn)
            h_w = h
        for st in range(ns):
            if st == 0 or same[st] == 1:
                copy_into(fp, f0)
            elif same[st] == 0:
                tableau_argument(y, U, tA, st, ytmp)
                transient_rhs(t + tc[st] * h, ytmp, fp, net, tier, tab, perf, pr, pa, tr, out1)
                tally_clamps(pr, t + tc[st] * h, att)
                nfev += 1
            tableau_stage_rhs(fp, T, U, tC, td, st, h, x)
            _loop_w_solve(J, Winv, hd, x, U[st], ndyn, nn, xs)
            for i in range(n):
                U[st, i] *= hd
        err = tableau_solution(y, U, tb, te, atol, rtol, ytmp)
        accepted = err <= 1.0 or h < 1e-10
        if accepted:
            transient_rhs(t + h, ytmp, f1, net, tier, tab, perf, pr, pa, tr, out)
            _node_torques(pr, tq1)
            tally_clamps(pr, t + h, att_end)
            nfev += 1
            # a step whose end needed the properties clamped is retried shorter
            accepted = visited_clamp_off(att_end) == 0 or h < 1e-10
        settle_trial(att, clamps)
        settle_clamps(att_end, accepted, clamps)
        if clamps[CL_ACCEPTED] > 0.0:
            _visited_clamps(clamps, sc)
        if accepted:
            t1 = t + h
            io = emit_samples(io, out_theta, t, y, f0, t1, ytmp, f1, samples, tmp)
            t = t1
            copy_into(y, ytmp)
            copy_into(f0, f1)
            copy_into(tq0, tq1)
            before = y[nn + X_Z]
            _project(y, nn)
            if y[nn + X_Z] != before:   # a stop was struck: restart the derivative
                transient_rhs(t, y, f0, net, tier, tab, perf, pr, pa, tr, out)
                _node_torques(pr, tq0)
                tally_clamps(pr, t, att)
                settle_visited(att, clamps)
                if clamps[CL_ACCEPTED] > 0.0:
                    _visited_clamps(clamps, sc)
                nfev += 1
            fresh = True
            if record and n_rec < nrec_max:
                # out[] holds the values at the step's end
                _record(rec, n_rec, t, y, nn, out)
                n_rec += 1
            h_next = h * step_factor(err, 0.9, expo)
            if t < b:
                sc[S_STEP] = h_next
            h = h_next
            if y[nn + X_OMEGA] < sc[S_WMIN]:
                status = 2
                break
        elif err <= 1.0:
            h = 0.5 * h  # accurate, but through a state the properties do not hold
        else:
            h = h * max(0.2, 0.9 * err ** expo)
        if not (h > 0.0) or not math.isfinite(y[0]):
            status = 1
            break
        if nfev > sc[S_MAX_RHS]:
            status = 4
            break
    status = _turn_end(io, out_theta, samples, y, nn, status, t_end, clamps, sc)
    return y, samples, rec, n_rec, nfev, status
