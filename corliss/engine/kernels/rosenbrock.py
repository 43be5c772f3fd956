"""The Rosenbrock step loop: one loop (:func:`_ros_steps`) for every tableau (the ode23s
pair, ``ros4``, RODAS3, RODAS4), over a steady cycle (:func:`cycle_ros`) and over a
turn of the governed loop (:func:`integrate_turn_ros`), compiled in versions by whether
the pair's controller, the finite-difference Jacobian and the loop's turn are used.
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.kernels.balances import past_switch, rhs
from corliss.engine.kernels.clamps import (CL_ACCEPTED, CL_NODE, settle_clamps,
                                           settle_trial, tally_clamps, visited_clamp_off)
from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.data import (Columns, LoopTurn, Physics, RosScratch,
                                         StepControl, StepScratch, Tableau)
from corliss.engine.kernels.jacobians import (LOOP_COLUMNS, _exact_jacobian_holds,
                                              _fd_jacobian, _jacobian, _jacobian_exact,
                                              _loop_w_inverse, _loop_w_solve, _w_inverse,
                                              _w_solve)
from corliss.engine.kernels.loop import (N_EXTRA, N_REC, S_MAX_RHS, S_STEP, S_WMIN,
                                         X_OMEGA, _node_torques, _turn_end, _visited_clamps,
                                         transient_rhs, turn_accepted, turn_restart,
                                         turn_start, turn_stops)
from corliss.engine.kernels.mechanism import TWO_PI
from corliss.engine.kernels.properties import PR_ROWS
from corliss.engine.kernels.stepping import (copy_into, emit_samples, initial_step,
                                             predictive_factor, put_column, segment_start,
                                             starting_step, step_factor, turn_first_step)
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
    clamps = np.zeros(6)
    clamps[CL_NODE] = -1.0
    scratch = RosScratch(np.empty((10, n)), np.empty((tb.shape[0], n)), np.zeros((n, ndyn)),
                         np.empty((2, ndyn, ndyn)), np.empty(ndyn),
                         np.full((PR_ROWS, net.node_kind.shape[0]), np.nan),
                         # jd also holds pr's rows (starting_step)
                         np.full((max(12, PR_ROWS), net.node_kind.shape[0]), np.nan),
                         np.empty((2, net.port_npts.shape[0], 4)), clamps, np.zeros((2, 4)))
    nfev, status, _ = _ros_steps(y, samples, stops, out_theta,
                                 StepControl(rtol, atol, max_rhs, jac_age),
                                 Physics(net, tier, tab, perf), Columns(color, owner),
                                 Tableau(gam, tA, tC, tc, td, tb, te, same, expo),
                                 True if kind == KIND_ODE23S else None,
                                 None if _exact_jacobian_holds.py_func(net) else True,
                                 scratch, True, None)
    return y, samples, nfev, status == 0, clamps


#: The positions of :func:`_ros_steps`'s ``pair`` (True: the ode23s pair; None: a
#: tableau's method), ``finite`` (True: the Jacobian by finite differences; None: the
#: analytic one) and ``turn`` (None: a steady cycle) among its arguments: numba
#: compiles and caches a version for each combination a run takes
#: (:func:`corliss.engine.kernels.cache.cycle_kernel_uncached`).
ROS_PAIR_ARG, ROS_FINITE_ARG, ROS_TURN_ARG = 8, 9, 12


@njit(cache=True, _nrt=False)
def _ros_steps(y, samples, stops, out_theta, ctl, phys, cols, tableau, pair, finite, scratch,
               cycle, turn):
    """The Rosenbrock step loop of a steady cycle (:func:`cycle_ros`) and of a turn of the
    governed loop (:func:`integrate_turn_ros`), on scratch its caller allocated (no
    reference counts: the views of the scratch taken here cost nothing).

    ``y`` is advanced to the end (``stops[-1]``), ``samples`` and ``scratch.clamps``
    written.  ``pair``: True for the ode23s pair, None for a tableau's method;
    ``finite``: True for a network whose Jacobian is taken by finite differences
    (:func:`_exact_jacobian_holds` false), None for the analytic one; ``cycle`` True
    and ``turn`` None for a steady cycle, ``cycle`` None and ``turn`` the loop's
    :class:`~corliss.engine.kernels.data.LoopTurn` for a turn.  Each is a separate
    compiled version; a version taking None for one of them holds none of the code
    that argument's branches guard (numba prunes them as it types the function: see
    :func:`~corliss.engine.kernels.dopri5._dopri5_steps` on why the cycle's code and
    the turn's are each guarded by their own argument).  A steady cycle: the network's right-hand side
    :func:`~corliss.engine.kernels.balances.rhs` between the stops, a step whose end
    needed the properties clamped retried shorter.  A turn (a tableau's method on the
    finite-difference Jacobian): one segment (``stops`` the turn's start and end) or
    more (a wall-heat schedule's switches between,
    :func:`~corliss.engine.kernels.loop.turn_stops`), the loop's right-hand side
    :func:`~corliss.engine.kernels.loop.transient_rhs` and its Jacobian
    (:func:`_fd_jacobian` with ``turn``, one a step), the first step carried over from
    the turn before (``sc[S_STEP]``) or :func:`turn_first_step`'s (a later segment's
    the last one's), a later segment's derivative and first Jacobian both read past
    its switch (:func:`~corliss.engine.kernels.loop.turn_restart`, as a cycle's read at
    :func:`~corliss.engine.kernels.balances.past_switch`: a Jacobian read at the stop,
    on the window before, took its differences against the derivative of the window
    after, the jump of the heat over each column's perturbation), a visited
    state's clamp stopping the run (but for the greatest energy's), the governor's
    stops after each accepted step, each accepted step recorded, and the run stopped
    where the engine stalls.

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
        Tolerances, budget of evaluations and the Jacobian's age
        (:class:`~corliss.engine.kernels.data.StepControl`).
    phys : Physics
        The network and the steam's properties
        (:class:`~corliss.engine.kernels.data.Physics`).
    cols : Columns
        The Jacobian's column groups (:class:`~corliss.engine.kernels.data.Columns`).
    tableau : Tableau
        The method's tableau (:class:`~corliss.engine.kernels.data.Tableau`).
    pair : True or None
        The ode23s pair's formulas and controller, or the tableau's.
    finite : True or None
        The finite-difference Jacobian, or the analytic one.
    scratch : RosScratch
        (:class:`~corliss.engine.kernels.data.RosScratch`), its clamp counts written.
    cycle : True or None
        True for a steady cycle, None for a turn.
    turn : LoopTurn or None
        The governed loop's turn, or None for a steady cycle.

    Returns
    -------
    nfev : int
        Right-hand-side evaluations spent.
    status : int
        As :func:`corliss.engine.kernels.dopri5._dopri5_steps`'s.
    n_rec : int
        Columns of ``turn.rec`` filled (0 for a cycle).
    """
    rtol, atol, max_rhs, jac_age = ctl.rtol, ctl.atol, ctl.max_rhs, ctl.jac_age
    net, tier, tab, perf = phys.net, phys.tier, phys.tab, phys.perf
    color = cols.color
    gam, tA, tC, tc, td = tableau.gamma, tableau.A, tableau.C, tableau.c, tableau.d
    tb, te, same, expo = tableau.b, tableau.e, tableau.same, tableau.expo
    vec, U, J, mats, dl = scratch.vec, scratch.U, scratch.J, scratch.mats, scratch.dl
    pr, jd, cyl, clamps, tally = scratch.pr, scratch.jd, scratch.cyl, scratch.clamps, scratch.tally
    n = y.shape[0]
    nn = n - N_EXTRA
    ndyn = color.shape[0]
    ns = tb.shape[0]
    safety = 0.9
    # the shortest step taken whatever its error or clamps
    h_min = 1e-12
    if turn is not None:
        h_min = 1e-10
    # the ode23s pair's steps by Gustafsson's predictive controller, no growth on the
    # step after a rejection (:func:`predictive_factor`); a tableau's by the error alone
    predictive = pair is not None
    f0, f1, ytmp, tmp, T, x, yscale, yp, fp = (vec[0], vec[1], vec[2], vec[3], vec[4],
                                               vec[5], vec[6], vec[7], vec[8])
    xs = vec[9]
    for i in range(n):
        yscale[i] = atol[i] / rtol
    Winv, A = mats[0], mats[1]
    slope, cell = cyl[0], cyl[1]
    att, att_end = tally[0], tally[1]
    steps = StepScratch(pr, cell, att, yp, fp, dl, jd, slope)
    if turn is not None:
        tr = turn.tr
        sc = tr.sc
        out, out1 = turn.out[0], turn.out[1]
        tq0, tq1 = turn.tq[0], turn.tq[1]
    nfev = 0
    n_rec = 0
    status = 0
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
        ta = a                 # where the segment reads its first derivative and Jacobian
        if cycle is not None:
            ta = past_switch(a, net)
            if not (predictive and t_end == a and ta == a):
                # (the ode23s pair's last step ended on this stop: f0 is the derivative
                # at this angle and state, evaluated and its clamps settled as a visited
                # state's; the area's kink changes the derivative's slope, not its value;
                # a schedule's switch changes its value: read afresh past it)
                segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att)
                nfev += 1
            if h_prev > 0.0:
                h = min(h_prev, b - a)
            elif predictive:
                h = starting_step(t, y, f0, atol, rtol, b - a, expo, phys, steps)
                nfev += 1
            else:
                h = initial_step(f0, y, atol, rtol, b - a)
        if turn is not None:
            if seg == 0:
                n_rec = turn_start(t, y, f0, phys, pr, cell, turn, att, clamps)
                nfev += 1
                h = sc[S_STEP]
                if not (h > 0.0):
                    h = turn_first_step(f0, y, atol, rtol, 0.25)
            else:
                # a schedule's switch (loop.turn_stops): the derivative afresh, read
                # past the switch, and the segment's first Jacobian read there too
                ta = turn_restart(t, y, f0, phys, pr, cell, turn, att, clamps)
                nfev += 1
                h = min(h_prev, b - a)
        age = jac_age          # accepted steps since J and T were computed
        h_w = -1.0             # the step W was inverted for
        while t < b:
            if t + h > b or b - (t + h) < 1e-12:
                h = b - t
            if age >= jac_age:
                if turn is not None:
                    # inlined here: compiled apart, the loop's right-hand side linked into
                    # it was optimised once more by LLVM, seconds of a first run
                    nfev += _fd_jacobian(max(t, ta), y, f0, J, T, yscale, cols, phys,
                                         steps, None, turn, (ta, b))
                if cycle is not None:
                    if finite is None:
                        # called from here, not through :func:`_jacobian`: through it, a
                        # call cost 2.2 us against 0.7 us (the default scene; numba's
                        # handling of a function that passes the network and table tuples
                        # on, it seems)
                        _jacobian_exact(max(t, ta), y, J, T, net, tier, tab, perf, pr, cell,
                                        jd, slope)
                    else:
                        nfev += _jacobian(max(t, ta), y, f0, J, T, yscale, cols, phys, steps,
                                          (ta, b))
                age = 0
                h_w = -1.0
            hd = h * gam
            if h != h_w:
                if cycle is not None:
                    _w_inverse(J, hd, Winv, A)
                if turn is not None:
                    _loop_w_inverse(J, hd, Winv, A, ndyn, nn)
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
                        if cycle is not None:
                            rhs(t + tc[st] * h, ytmp, fp, net, tier, tab, perf, pr, cell)
                        if turn is not None:
                            transient_rhs(t + tc[st] * h, ytmp, fp, net, tier, tab, perf, pr,
                                          cell, tr, out1)
                        tally_clamps(pr, t + tc[st] * h, att)
                        nfev += 1
                    tableau_stage_rhs(fp, T, U, tC, td, st, h, x)
                    if cycle is not None:
                        _w_solve(J, Winv, hd, x, U[st])
                    if turn is not None:
                        _loop_w_solve(J, Winv, hd, x, U[st], ndyn, nn, xs)
                    for i in range(n):
                        U[st, i] *= hd
                err = tableau_solution(y, U, tb, te, atol, rtol, ytmp)
                accepted = err <= 1.0 or h < h_min
                if accepted:
                    if cycle is not None:
                        rhs(t + h, ytmp, f1, net, tier, tab, perf, pr, cell)
                    if turn is not None:
                        transient_rhs(t + h, ytmp, f1, net, tier, tab, perf, pr, cell, tr, out)
                        _node_torques(pr, tq1)
                    tally_clamps(pr, t + h, att_end)
                    nfev += 1
                    # a step whose end needed the properties clamped is retried shorter
                    accepted = visited_clamp_off(att_end) == 0 or h < h_min
            settle_trial(att, clamps)
            settle_clamps(att_end, accepted, clamps)
            if turn is not None:
                if clamps[CL_ACCEPTED] > 0.0:
                    _visited_clamps(clamps, sc)
            if accepted:
                t1 = t + h
                io = emit_samples(io, out_theta, t, y, f0, t1, ytmp, f1, samples, tmp)
                t = t1
                t_end = t1
                copy_into(y, ytmp)
                copy_into(f0, f1)
                age += 1
                if turn is not None:
                    copy_into(tq0, tq1)
                    nf, n_rec = turn_accepted(t, y, f0, phys, pr, cell, turn, att, clamps,
                                              n_rec)
                    nfev += nf
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
                if turn is not None:
                    if t < b:
                        sc[S_STEP] = h
                    if y[nn + X_OMEGA] < sc[S_WMIN]:
                        status = 2
                        break
            else:
                rejected = True
                if age > 0:
                    age = jac_age    # rejected on an old Jacobian: a fresh one
                if err <= 1.0:
                    h = 0.5 * h  # accurate, but through a state the properties do not hold
                else:
                    h = h * max(0.2, safety * err ** expo)
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


def integrate_turn_ros(y0, th0, out_theta, rtol, atol, phys, tr, record, t_end, color, owner,
                       tableau, inner=None):
    """Integrate one turn as :func:`integrate_turn`, with a Rosenbrock method.

    The tableau's method of :func:`cycle_ros` (one of
    :data:`corliss.engine.kernels.tableaus.ROS_TABLEAUS`) by the same step loop,
    :func:`_ros_steps`, on the loop's finite-difference Jacobian (:func:`_fd_jacobian`
    with the loop's columns), one a step (the retry of a rejected step reuses it; the
    linear algebra is :func:`_loop_w_inverse`'s and :func:`_loop_w_solve`'s over the
    Jacobian's columns, which here are not the first states).  dopri5 is held
    by the stiff pressure equalisation through an open port to steps of 1 to 2 deg
    whatever its tolerance (an eigenvalue of -60 to -330 per radian on the
    Porter-Allen engine, the step times it at 2.2 to 3.1, the edge of its stability);
    this one steps over it, which pays at loose tolerances (``fast``) and on a steam
    chest's stiffer flow: at tight ones the Porter-Allen engine's port flow holds every
    method to such steps by its own pace, and the Jacobian's six evaluations a step
    then cost more than they save (:data:`corliss.engine.options.PRESETS`).  The step
    carries over from turn to turn (``sc[S_STEP]``).  Returns, raises and counts clamps
    as :func:`integrate_turn`; a step whose end needs the properties clamped (but for
    the greatest energy's) is retried shorter.  Allocates the scratch in Python, as
    :func:`cycle_ros` (see :func:`integrate_turn`).

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
    inner : array_like, optional
        Shaft angles [rad] where the turn restarts its step, as
        :func:`integrate_turn`'s.

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
    net = phys.net
    n = y0.shape[0]
    ndyn = color.shape[0]
    m = ndyn + LOOP_COLUMNS.shape[0]
    nv = net.node_kind.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    rec = np.empty((N_REC, 40000 if record else 1))
    stops = turn_stops(th0, inner)
    # jd: none (the analytic Jacobian and the pair's starting step are a cycle's)
    scratch = RosScratch(np.empty((10, n)), np.empty((tableau.b.shape[0], n)),
                         np.zeros((n, m)), np.empty((2, m, m)), np.empty(ndyn),
                         np.full((PR_ROWS, nv), np.nan), np.empty((0, 0)),
                         np.empty((2, net.port_npts.shape[0], 4)), np.zeros(6),
                         np.zeros((2, 4)))
    nfev, status, n_rec = _ros_steps(y, samples, stops, out_theta,
                                     StepControl(rtol, atol, tr.sc[S_MAX_RHS], 1), phys,
                                     Columns(color, owner), tableau, None, True, scratch,
                                     None, LoopTurn(tr, np.empty((2, 4)), rec, record, t_end,
                                              np.empty((3, nv))))
    return y, samples, rec, n_rec, nfev, status
