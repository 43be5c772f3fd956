"""Step-size control and output shared by every step loop: the first step, the error-only
and predictive (Gustafsson) step factors, the start of a segment between port kinks,
and the samples written at the output angles.
"""

from __future__ import annotations

from corliss.engine.kernels.balances import past_switch, rhs
from corliss.engine.kernels.clamps import settle_visited, tally_clamps
from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.tableaus import hermite


#: The run-time budget: right-hand-side evaluations allowed in one cycle (or one turn of
#: the transient loop).  The default card needs 3,400 at the standard preset and a
#: 10 rpm engine 36,000; a cycle that needs 2,000,000 (about half a minute) is stepping
#: through something no engine does (a speed, stroke or friction far outside the
#: physical), and the run stops with a message instead of hanging.
MAX_RHS_PER_CYCLE = 2_000_000


@njit(cache=True, _nrt=False)
def copy_into(dst, src):
    """``dst[:] = src`` for 1-d arrays of one length.

    Without the shape check's error path, which numba would compile into every
    caller.

    Parameters
    ----------
    dst : ndarray
        Written; shape (n,).
    src : ndarray
        Shape (n,).
    """
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@njit(cache=True, _nrt=False)
def put_column(samples, k, y):
    """``samples[:, k] = y``, as :func:`copy_into`.

    Parameters
    ----------
    samples : ndarray
        Written at column ``k``; shape (n, outputs).
    k : int
        The column.
    y : ndarray
        Shape (n,).
    """
    for i in range(y.shape[0]):
        samples[i, k] = y[i]


@njit(cache=True, _nrt=False)
def emit_samples(io, out_theta, t0, y0, f0, t1, y1, f1, samples, tmp):
    """Write the states at the output angles a step passed (cubic Hermite on the step).

    Parameters
    ----------
    io : int
        The next output angle not yet written.
    out_theta : ndarray
        The output angles [rad], increasing; shape (outputs,).
    t0, t1 : float
        The step's ends [rad].
    y0, y1 : ndarray
        The states there; shape (n,).
    f0, f1 : ndarray
        Their derivatives (per radian); shape (n,).
    samples : ndarray
        Written at the columns of ``out_theta[io:]`` up to ``t1``; shape (n, outputs).
    tmp : ndarray
        Scratch; shape (n,).

    Returns
    -------
    int
        The index of the next output angle not written.
    """
    while io < out_theta.shape[0] and out_theta[io] <= t1:
        hermite(t0, y0, f0, t1, y1, f1, out_theta[io], tmp)
        put_column(samples, io, tmp)
        io += 1
    return io


@njit(cache=True, inline="always")
def derivative_scale(f0, y, atol, rtol):
    """The derivative's size in the error's scale, the first steps' measure.

    Parameters
    ----------
    f0 : ndarray
        The derivative (per radian); shape (n,).
    y : ndarray
        The state; shape (n,).
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n,).
    rtol : float
        Relative tolerance [-].

    Returns
    -------
    float
        ``max_i |f_i| / (atol_i + rtol |y_i|)`` [1/rad].
    """
    scale = 0.0
    for i in range(y.shape[0]):
        v = abs(f0[i]) / (atol[i] + rtol * abs(y[i]))
        if v > scale:
            scale = v
    return scale


@njit(cache=True, _nrt=False)
def initial_step(f0, y, atol, rtol, span):
    """A first step from the derivative's scale.

    ``0.01 rtol^(1/5) / max_i (|f_i| / (atol_i + rtol |y_i|))``.

    Parameters
    ----------
    f0, y, atol, rtol
        The derivative at the start, the state there and the tolerances, as
        :func:`derivative_scale` takes them.
    span : float
        The segment's length [rad].

    Returns
    -------
    float
        The step [rad], within [1e-9, ``span``] (``span`` when nothing changes).
    """
    scale = derivative_scale(f0, y, atol, rtol)
    h = 0.01 * (rtol ** 0.2) / scale if scale > 0.0 else span
    return min(max(h, 1e-9), span)


@njit(cache=True, _nrt=False)
def turn_first_step(f0, y, atol, rtol, root):
    """The first step of a turn of the governed loop, from the derivative's scale.

    ``0.01 rtol^root / max_i (|f_i| / (atol_i + rtol |y_i|))``, within [1e-7, 0.05].

    Parameters
    ----------
    f0, y, atol, rtol
        The derivative at the start, the state there and the tolerances, as
        :func:`derivative_scale` takes them.
    root : float
        The power of ``rtol``, ``1 / (order + 1)`` of the method's error [-].

    Returns
    -------
    float
        The step [rad] (0.01 when nothing changes).
    """
    scale = derivative_scale(f0, y, atol, rtol)
    h = 0.01 * (rtol ** root) / scale if scale > 0.0 else 0.01
    return min(max(h, 1e-7), 0.05)


@njit(cache=True, _nrt=False)
def starting_step(t, y, f0, atol, rtol, span, expo, phys, scratch):
    """A first step from the derivative and its change over a trial Euler step.

    Hairer, Norsett and Wanner's starting step (*Solving Ordinary Differential
    Equations I*, Sec. II.4), in the error's max norm: with ``d0``, ``d1`` the scaled
    state and derivative, a trial step ``h0 = 0.01 d0 / d1``; ``d2`` the scaled change
    of the derivative over it, per radian; the step ``(0.01 / max(d1, d2))^(-expo)``,
    at most ``100 h0``.  One evaluation of :func:`rhs` (its clamps go into ``att``, a
    trial's); ``pr`` is left as it came (the properties at ``t``, ``y``, where the
    step's Jacobian may take them).

    Parameters
    ----------
    t : float
        The start [rad].
    y : ndarray
        The state there; shape (n_state,).
    f0 : ndarray
        The derivative there (per radian); shape (n_state,).
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n_state,).
    rtol : float
        Relative tolerance [-].
    span : float
        The segment's length [rad].
    expo : float
        The exponent, ``-1 / (order + 1)`` of the method's error estimate [-].
    phys : Physics
        The network's arrays and the steam's compiled properties
        (:class:`corliss.engine.kernels.data.Physics`).
    scratch : StepScratch
        (:class:`corliss.engine.kernels.data.StepScratch`): ``pr`` the node properties
        at ``t``, ``y``, shape (:data:`PR_ROWS`, nodes), used as scratch and restored;
        ``cell`` scratch for the port areas [m2], shape (cylinders, 4); ``att`` a step
        attempt's clamp tally, shape (4,), added to; ``yp``, ``fp`` scratch, shape
        (n_state,); ``jd`` scratch of at least ``pr``'s rows, shape (rows, nodes).

    Returns
    -------
    float
        The step [rad], within [1e-9, ``span``].
    """
    net, tier, tab, perf = phys.net, phys.tier, phys.tab, phys.perf
    pr, cell, att, yp, fp = scratch.pr, scratch.cell, scratch.att, scratch.yp, scratch.fp
    prs = scratch.jd
    n = y.shape[0]
    d0 = 0.0
    d1 = 0.0
    for i in range(n):
        sc = atol[i] + rtol * abs(y[i])
        d0 = max(d0, abs(y[i]) / sc)
        d1 = max(d1, abs(f0[i]) / sc)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, span)
    for i in range(n):
        yp[i] = y[i] + h0 * f0[i]
    for r in range(pr.shape[0]):
        for i in range(pr.shape[1]):
            prs[r, i] = pr[r, i]
    rhs(t + h0, yp, fp, net, tier, tab, perf, pr, cell)
    tally_clamps(pr, t + h0, att)
    for r in range(pr.shape[0]):
        for i in range(pr.shape[1]):
            pr[r, i] = prs[r, i]
    d2 = 0.0
    for i in range(n):
        d2 = max(d2, abs(fp[i] - f0[i]) / (atol[i] + rtol * abs(y[i])))
    d2 /= h0
    m = max(d1, d2)
    h1 = max(1e-6, h0 * 1e-3) if m <= 1e-15 else (0.01 / m) ** (-expo)
    return min(max(min(100.0 * h0, h1), 1e-9), span)


@njit(cache=True, _nrt=False)
def step_factor(err, safety, expo):
    """The ratio of the next step to this one after an accepted step.

    Parameters
    ----------
    err : float
        The step's scaled error [-].
    safety : float
        The safety factor [-] (0.9 for dopri5 and the Rosenbrock methods).
    expo : float
        The exponent, ``-1 / (order + 1)`` of the error estimate [-].

    Returns
    -------
    float
        ``safety err^expo`` kept within [0.2, 5] (5 for an error of zero).
    """
    if err == 0.0:
        return 5.0
    return min(5.0, max(0.2, safety * err ** expo))


@njit(cache=True, _nrt=False)
def predictive_factor(err, h, err_acc, h_acc, safety, expo):
    """The ratio of the next step to this one after an accepted step, by Gustafsson's
    predictive controller.

    The smaller of :func:`step_factor` and the ratio that the error's trend over the
    last two accepted steps predicts, ``safety (h / h_acc) err^(2 expo) err_acc^(-expo)``
    (Hairer and Wanner, *Solving Ordinary Differential Equations II*, Sec. IV.8,
    eq. 8.21, as their codes RODAS and RADAU5 apply it, ``err_acc`` kept at least 0.01).

    Parameters
    ----------
    err : float
        The step's scaled error [-].
    h : float
        The step [rad].
    err_acc : float
        The scaled error of the accepted step before it, at least 0.01 [-]; 0 when
        there was none (the factor is then :func:`step_factor`'s).
    h_acc : float
        That step [rad].
    safety : float
        The safety factor [-].
    expo : float
        The exponent, ``-1 / (order + 1)`` of the error estimate [-].

    Returns
    -------
    float
        The ratio [-], within [0.2, 5].
    """
    fac = step_factor(err, safety, expo)
    if err_acc > 0.0 and err > 0.0:
        gus = safety * (h / h_acc) * err ** (2.0 * expo) * err_acc ** (-expo)
        fac = min(fac, min(5.0, max(0.2, gus)))
    return fac


@njit(cache=True, _nrt=False)
def segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att):
    """The derivative at the start of a segment between kinks, a visited state.

    Read past a wall-heat schedule's switch where the segment starts just short of one
    (:func:`~corliss.engine.kernels.balances.past_switch`).

    Its clamps are settled as a visited state's.

    Parameters
    ----------
    t : float
        The segment's start [rad].
    y : ndarray
        The state, shape (n_state,), laid out as
        :class:`~corliss.engine.network.Network` says (masses [kg] and internal
        energies [J] of the nodes first).
    f0 : ndarray
        Written: the derivative there (per radian); shape (n_state,).
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    pr : ndarray
        Scratch, written: node properties, shape (:data:`PR_ROWS`, nodes): rows
        pressure [Pa], density [kg/m3], enthalpy [J/kg], port-flow exponent [-],
        dV/dtheta [m3/rad], volume [m3], temperature [K], wetted-wall temperature
        [K], clamp code (:data:`PR_CLAMP`), dryness [-]
        (:data:`PR_X`), whether superheated (:data:`PR_SUP`) and the state
        they are of (:data:`PR_AT`).
    cell : ndarray
        Scratch for the port areas [m2], shape (cylinders, 4).
    clamps : ndarray
        The cycle's clamp counts, shape (6,), updated, indexed by ``CL_*``.
    att : ndarray
        A step attempt's clamp tally, shape (4,), used and cleared: clamped
        evaluations, the OR of their codes, shaft angle [rad] and node of the first.
    """
    te = past_switch(t, net)
    rhs(te, y, f0, net, tier, tab, perf, pr, cell)
    tally_clamps(pr, te, att)
    settle_visited(att, clamps)
