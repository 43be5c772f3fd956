"""Jacobians of the right-hand side over the dynamic states, and W = I - h d J's inverse
and solves: the analytic one (the steam table's and the port flow's own derivatives)
where the wall heat does not depend on the state, the finite-difference one (columns
grouped by the network's structure) elsewhere, and the governed loop's (the network's
columns plus the shaft and governor states).
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.kernels.balances import edge_side, marks_window, rhs
from corliss.engine.kernels.clamps import tally_clamps
from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.loop import N_EXTRA, X_OMEGA, X_Z, X_ZDOT, transient_rhs
from corliss.engine.kernels.mechanism import (_port_area_slopes, _volume_curvature,
                                              edge_area, node_volume, port_areas)
from corliss.engine.kernels.data import (GEO_AREA_CRANK, GEO_AREA_HEAD, H_MARKS_Q, H_MODEL,
                                         WALL_MARKS, WALL_NONE)
from corliss.engine.kernels.properties import (PERF_CV, PERF_R, PERF_U_REF, PR_AT, PR_CLAMP,
                                               PR_DV, PR_H, PR_KAPPA, PR_P, PR_RHO, PR_SUP, PR_T,
                                               PR_V, TIER_PERFECT, admissible_flagged)
from corliss.engine.kernels.stepping import copy_into
from corliss.thermo.leak_law import linear_leak
from corliss.thermo.orifice import port_flow_partials
from corliss.thermo.steam_table import kappa_partials, lookup_near, pressure_partials


@njit(cache=True, inline="always")
def _exact_jacobian_holds(net):
    """Whether :func:`_jacobian_exact` covers the network's right-hand side: no wall
    heat that depends on the state (none, or Marks's schedule); the film and wall
    temperature models are differentiated by finite differences."""
    heat = net.heat
    for i in range(heat.shape[0]):
        if heat[i, H_MODEL] != WALL_NONE and heat[i, H_MODEL] != WALL_MARKS:
            return False
    return True


def exact_jacobian_covers(net) -> bool:
    """Whether the Rosenbrock methods' Jacobian of this network is exact.

    The Python face of the compiled test the integrators make: no wall heat that
    depends on the state (none, or Marks's schedule).

    Parameters
    ----------
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).

    Returns
    -------
    bool
        True when :func:`_jacobian_exact` covers the network.
    """
    return bool(_exact_jacobian_holds.py_func(net))


@njit(cache=True, _nrt=False)
def _jacobian_exact(t, y, J, T, net, tier, tab, perf, pr, cell, jd, slope):
    """The Jacobian of :func:`rhs` over the dynamic columns, and its time derivative,
    from the derivatives of its parts, for a network :func:`_exact_jacobian_holds`
    covers.

    Each node's pressure, density, enthalpy and port-flow exponent depend on its own
    mass m and energy E alone, through rho = m/V and u = E/m: their partials in
    (rho, u) come from the table's own interpolation
    (:func:`corliss.thermo.steam_table.pressure_partials`,
    :func:`~corliss.thermo.steam_table.kappa_partials`) or the perfect gas's closed
    form, and go to (m, E) by the chain rule (none in a coordinate the state's clamp
    holds), and to the crank angle through the volume (drho/dtheta = -rho V'/V).  Each
    node's work term ``-p dV/dtheta`` then moves its energy row and work quadrature
    (in time also through V''); each edge's flow
    (:func:`corliss.thermo.orifice.port_flow_partials`, and in time its area's slope
    on the PortMap table) and the enthalpy it carries (of the side it leaves) move the
    rows of its two ends and its quadratures.  Marks's schedule
    (:func:`~corliss.engine.kernels.balances.marks_window`) does not depend on the
    state but moves in crank angle with the wall exposed, ``pi D V' / A_p`` of it,
    in the energy row and the heat quadratures.  ``pr`` is written with the properties
    at ``y``, ``jd`` (shape (12, nodes)) with their partials, ``slope`` (shape
    (cylinders, 4)) with the ports' area slopes.

    A node whose properties on ``pr`` are those of its state at (``t``, ``y``) (the
    angle, mass and energy of rows :data:`PR_AT` on: an integrator's step starts
    where its last evaluation was) and were not clamped keeps that evaluation's volume,
    pressure and temperature, and only the partials are computed
    (:func:`corliss.thermo.steam_table.pressure_partials`: the same numbers, without
    the lookup's iteration, about a third of this function's time).
    """
    nv = net.node_kind.shape[0]
    n = y.shape[0]
    ndyn = 2 * nv
    for i in range(n):
        T[i] = 0.0
        for j in range(ndyn):
            J[i, j] = 0.0
    for i in range(nv):
        known = (pr[PR_CLAMP, i] == 0.0 and pr[PR_AT, i] == t
                 and pr[PR_AT + 1, i] == y[2 * i] and pr[PR_AT + 2, i] == y[2 * i + 1])
        if known:
            V, dV = pr[PR_V, i], pr[PR_DV, i]
        else:
            V, dV = node_volume(t, net, i)
            pr[PR_DV, i] = dV
            pr[PR_V, i] = V
        m = y[2 * i]
        if m > 0.0:
            u = y[2 * i + 1] / m
            u_m = -u / m
            u_e = 1.0 / m
        else:
            u = 2.6e6
            u_m = 0.0
            u_e = 0.0
        r_m = 1.0 / V
        r_t = -m / V * dV / V
        rho, u, code = admissible_flagged(m / V, u)
        if code & 3:
            r_m = 0.0
            r_t = 0.0
        if code & 12:
            u_m = 0.0
            u_e = 0.0
        if tier == TIER_PERFECT:
            R, cv, u_ref = perf[PERF_R], perf[PERF_CV], perf[PERF_U_REF]
            Tk = (u - u_ref) / cv
            if Tk < 1.0:
                Tk = 1.0
                p_r, p_u = R * Tk, 0.0
            else:
                p_r, p_u = R * Tk, rho * R / cv
            p = rho * R * Tk
            k, k_r, k_u = 1.0 + R / cv, 0.0, 0.0
        else:
            if known:
                p, Tk, sup, c2 = pr[PR_P, i], pr[PR_T, i], pr[PR_SUP, i] != 0.0, 0
            else:
                p, Tk, x, sup, c2 = lookup_near(tab, rho, u, pr[PR_T, i])
            # (the lookup skipped for a known node: one copy of the partials' code,
            # which numba inlines)
            p_r, p_u = pressure_partials(tab, rho, u, p, Tk, sup, c2)
            k, k_r, k_u = kappa_partials(tab, rho, u)
        h_r = p_r / rho - p / (rho * rho)
        h_u = 1.0 + p_u / rho
        pr[PR_P, i] = p
        pr[PR_RHO, i] = rho
        pr[PR_H, i] = u + p / rho
        pr[PR_KAPPA, i] = k
        # rows: d(p, rho, h, kappa) / d(m, E), then / dtheta
        jd[0, i] = p_r * r_m + p_u * u_m
        jd[1, i] = p_u * u_e
        jd[2, i] = r_m
        jd[3, i] = 0.0
        jd[4, i] = h_r * r_m + h_u * u_m
        jd[5, i] = h_u * u_e
        jd[6, i] = k_r * r_m + k_u * u_m
        jd[7, i] = k_u * u_e
        jd[8, i] = p_r * r_t
        jd[9, i] = r_t
        jd[10, i] = h_r * r_t
        jd[11, i] = k_r * r_t
        q0 = ndyn + 2 * net.edge_a.shape[0] + 5 * i
        for v in range(2):
            J[2 * i + 1, 2 * i + v] = -jd[v, i] * dV
            J[q0, 2 * i + v] = jd[v, i] * dV
        w_t = jd[8, i] * dV + p * _volume_curvature(t, net, i)
        T[2 * i + 1] = -w_t
        T[q0] = w_t
        if net.heat[i, H_MODEL] == WALL_MARKS:
            # Marks's schedule: s Q A / W with A = 2 A_p + pi D V / A_p, the wall
            # exposed, moves in crank angle with the volume (not with the state); its
            # steps at the windows' ends are the valve events, where the integrators
            # stop
            sm, W = marks_window(t, net, i)
            if sm != 0.0:
                c = net.node_cyl[i]
                ap = net.geometry[c, GEO_AREA_HEAD if net.node_end[i] == 0 else GEO_AREA_CRANK]
                bore = math.sqrt(4.0 * net.geometry[c, GEO_AREA_HEAD] / math.pi)
                q_t = sm * net.heat[i, H_MARKS_Q] * math.pi * bore * dV / (ap * W)
                T[2 * i + 1] += q_t
                T[q0 + 1] = q_t
                if sm < 0.0:
                    T[q0 + 2] = -q_t
    omega, band, res = net.omega[0], net.band, net.reservoirs
    ea, eb, ecd, ekind, ecyl, eport = net.edge_a, net.edge_b, net.edge_cd, net.edge_kind, net.edge_cyl, net.edge_port
    port_areas(t, net, cell)
    _port_area_slopes(t, net, slope)
    for e in range(ea.shape[0]):
        area = edge_area(net, e, cell)
        if area <= 0.0:
            # a shut port: no flow and no partials (port_flow_partials's own test), nor
            # in time (the area's slope enters only where the area is open), as in
            # :func:`balances`
            continue
        a = ea[e]
        b = eb[e]
        pa, ra, ha, ka = edge_side(a, pr, res)
        pb, rb, hb, kb = edge_side(b, pr, res)
        if ekind[e] == 2:
            # the period's linear leak: R (p_a - p_b), its partials R and -R
            md, d1p, d1r, d1k, d2p, d2r, d2k = (linear_leak(area, pa, pb), area, 0.0, 0.0,
                                                -area, 0.0, 0.0)
        else:
            md, d1p, d1r, d1k, d2p, d2r, d2k = port_flow_partials(
                area, ecd[e], pa, ra, ka, pb, rb, kb, band, True)
        # the side upstream as the flow's partials take it (side a at equal pressures):
        # not by the sign of md, which is 0 there, where the right-hand side carries no
        # enthalpy and its two one-sided derivatives carry side a's (pressure of b
        # falling) or b's (rising); mixing a's flux slope with b's enthalpy matched
        # neither (a steam chest that has equalised with the supply to the last bit)
        up_a = pa >= pb
        h_up = ha if up_a else hb
        # in time: the area's slope (the flow is proportional to the area) and the
        # two sides' states
        md_t = md / area * slope[ecyl[e], eport[e]] if ekind[e] == 0 and area > 0.0 else 0.0
        hd_t = 0.0
        for side in range(2):
            nd = a if side == 0 else b
            if nd < 0:
                continue
            dp, dr, dk = (d1p, d1r, d1k) if side == 0 else (d2p, d2r, d2k)
            carries = up_a == (side == 0)
            md_t += dp * jd[8, nd] + dr * jd[9, nd] + dk * jd[11, nd]
            if carries:
                hd_t += md * jd[10, nd]
            for v in range(2):
                col = 2 * nd + v
                dmd = dp * jd[v, nd] + dr * jd[2 + v, nd] + dk * jd[6 + v, nd]
                dhd = dmd * h_up
                if carries:
                    dhd += md * jd[4 + v, nd]
                dmd /= omega
                dhd /= omega
                if a >= 0:
                    J[2 * a, col] -= dmd
                    J[2 * a + 1, col] -= dhd
                if b >= 0:
                    J[2 * b, col] += dmd
                    J[2 * b + 1, col] += dhd
                J[ndyn + 2 * e, col] += dmd
                J[ndyn + 2 * e + 1, col] += dhd
        hd_t += md_t * h_up
        md_t /= omega
        hd_t /= omega
        if a >= 0:
            T[2 * a] -= md_t
            T[2 * a + 1] -= hd_t
        if b >= 0:
            T[2 * b] += md_t
            T[2 * b + 1] += hd_t
        T[ndyn + 2 * e] += md_t
        T[ndyn + 2 * e + 1] += hd_t


#: The loop's states that take a column of the Rosenbrock method's Jacobian besides the
#: network's dynamic ones: speed, governor coordinate and its rate (offsets from the
#: network's length).
LOOP_COLUMNS = np.array([X_OMEGA, X_Z, X_ZDOT])


@njit(cache=True, inline="always")
def _fd_jacobian(t, y, f0, J, T, yscale, cols, phys, scratch, cycle, turn, span):
    """Jacobian of the dynamic columns, and the time derivative, by finite differences,
    for the Rosenbrock step loop, over a steady cycle (``cycle`` True, ``turn`` None,
    through :func:`_jacobian`) and over a turn of the governed loop (``cycle`` None,
    inlined into the loop).  As in the step loops, the cycle's code is guarded by
    ``cycle``, the turn's by ``turn``: numba prunes a branch on ``x is None`` only
    where ``x`` is None, so each version compiles only its own right-hand side.

    A steady cycle's: columns of one colour
    (``cols``, :class:`~corliss.engine.kernels.data.Columns`) are perturbed together
    (their rows do not overlap), so a single cylinder costs two evaluations, and the
    time derivative a forward difference, one more.

    A turn's (``turn`` the loop's :class:`~corliss.engine.kernels.data.LoopTurn`): by
    finite differences of :func:`~corliss.engine.kernels.loop.transient_rhs` alone,
    with the columns of :data:`LOOP_COLUMNS` (speed, governor coordinate and its rate)
    after the network's; ``J`` has shape (n, ndyn + 3).  The network's columns are
    perturbed by colour as a cycle's; the loop's own rows (speed, governor, works) see
    every node, but only through the indicated torque sum p_i dV_i/dtheta, so a
    colour's change of such a row is shared among the colour's columns as each one's
    node changed that sum (``turn.tq[0]`` holds each node's p dV/dtheta at ``y``,
    ``turn.tq[2]`` is scratch).  The loop's three columns are perturbed one at a time.
    Without them the method lost its order: the flywheel's energy and the work
    integrals parted by 1e-5 of the change even at rtol 1e-7
    (tests/test_speed_loop.py).

    The time derivative is a one-sided difference of a step of 1e-7 of the angle,
    at least 1e-7 rad and at most 1e-6 rad, taken within the segment ``span``, a
    pair of angles [rad] (from where its derivative was read to its end): forward,
    backward where the forward one would pass the segment's end, and shorter where
    neither fits.  A wall-heat schedule switches at the segment's end, so a difference
    across it took the heat's jump over the step; and a step of 1e-7 of the angle alone grew with a
    long run (1e-4 rad at 1,000 rad) until its truncation spoilt the derivative.  On
    the bundled compound under Marks's law, slowing over 128 turns at rtol 1e-6, the
    turns' ends netted up to 7e-7 of the heat taken with the step of 1e-7 of the angle
    across the switch, 1.4e-8 with it kept short of the switch, and 5e-10 with it also
    capped (dopri5: 6e-10).  The cap's rounding: an ulp of the angle over 1e-6 rad,
    1.5e-5 of the difference at 1e5 rad (hours of a run).

    Clamped evaluations go into the step's tally ``att``; ``yp``, ``fp`` (length of
    the state) and ``dl`` (of the dynamic states) are scratch, fields of ``scratch``
    (:class:`~corliss.engine.kernels.data.StepScratch`); ``phys`` is
    :class:`~corliss.engine.kernels.data.Physics`.  Returns the evaluations of the
    right-hand side spent.
    """
    net, tier, tab, perf = phys.net, phys.tier, phys.tab, phys.perf
    pr, cell, att, yp, fp = scratch.pr, scratch.cell, scratch.att, scratch.yp, scratch.fp
    dl = scratch.dl
    color, owner = cols.color, cols.owner
    if turn is not None:
        tr = turn.tr
        out, tq0, dtq = turn.out[1], turn.tq[0], turn.tq[2]
    n = y.shape[0]
    nn = n - N_EXTRA
    ndyn = color.shape[0]
    ncol = owner.shape[0]
    for j in range(ndyn):
        dl[j] = 1e-7 * max(abs(y[j]), yscale[j])
    for c in range(ncol):
        copy_into(yp, y)
        for j in range(ndyn):
            if color[j] == c:
                yp[j] += dl[j]
        if cycle is not None:
            rhs(t, yp, fp, net, tier, tab, perf, pr, cell)
        if turn is not None:
            transient_rhs(t, yp, fp, net, tier, tab, perf, pr, cell, tr, out)
        tally_clamps(pr, t, att)
        for j in range(ndyn):
            if color[j] == c:
                for i in range(n):
                    J[i, j] = 0.0
        # the network's rows (a turn's owner covers those alone)
        for i in range(owner.shape[1]):
            j = owner[c, i]
            if j >= 0:
                J[i, j] = (fp[i] - f0[i]) / dl[j]
        if turn is not None:
            total = 0.0
            for i in range(dtq.shape[0]):
                dtq[i] = pr[PR_P, i] * pr[PR_DV, i] - tq0[i]
                total += dtq[i]
            if total != 0.0:
                for j in range(ndyn):
                    if color[j] == c:
                        share = dtq[j // 2] / total
                        for i in range(nn, n):
                            J[i, j] = (fp[i] - f0[i]) * share / dl[j]
    nfev = ncol + 1
    if turn is not None:
        for k in range(LOOP_COLUMNS.shape[0]):
            q = nn + LOOP_COLUMNS[k]
            d = 1e-7 * max(abs(y[q]), yscale[q])
            copy_into(yp, y)
            yp[q] += d
            transient_rhs(t, yp, fp, net, tier, tab, perf, pr, cell, tr, out)
            tally_clamps(pr, t, att)
            for i in range(n):
                J[i, ndyn + k] = (fp[i] - f0[i]) / d
        nfev += LOOP_COLUMNS.shape[0]
    dt = 1e-7 * min(max(abs(t), 1.0), 10.0)
    t_lo, t_hi = span
    if t + dt > t_hi:
        if t - dt >= t_lo:
            dt = -dt
        elif t_hi - t >= t - t_lo:
            dt = 0.5 * (t_hi - t)
        else:
            dt = -0.5 * (t - t_lo)
    if cycle is not None:
        rhs(t + dt, y, fp, net, tier, tab, perf, pr, cell)
    if turn is not None:
        transient_rhs(t + dt, y, fp, net, tier, tab, perf, pr, cell, tr, out)
    tally_clamps(pr, t + dt, att)
    for i in range(n):
        T[i] = (fp[i] - f0[i]) / dt
    return nfev


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _jacobian(t, y, f0, J, T, yscale, cols, phys, scratch, span):
    """A steady cycle's Jacobian of the dynamic columns, and the time derivative:
    analytic (:func:`_jacobian_exact`, no evaluation of :func:`rhs`) where it covers
    the network, else :func:`_fd_jacobian`'s.  Arguments and return as
    :func:`_fd_jacobian`'s (``jd`` and ``slope`` of ``scratch`` the analytic one's;
    ``span`` the finite differences' segment)."""
    if _exact_jacobian_holds(phys.net):
        _jacobian_exact(t, y, J, T, phys.net, phys.tier, phys.tab, phys.perf, scratch.pr,
                        scratch.cell, scratch.jd, scratch.slope)
        return 0
    return _fd_jacobian(t, y, f0, J, T, yscale, cols, phys, scratch, True, None, span)


@njit(cache=True, _nrt=False)
def gauss_jordan(A, Winv):
    """Invert ``A`` into ``Winv`` (which holds the identity), by Gauss-Jordan elimination
    with partial pivoting, ``A`` overwritten: a few rows, no LAPACK call, and none to
    compile.  Shared by the steady and transient Rosenbrock integrators.

    Parameters
    ----------
    A : ndarray
        The matrix, shape (m, m); overwritten.
    Winv : ndarray
        The identity on entry, the inverse of ``A`` on return; shape (m, m).
    """
    ndyn = A.shape[0]
    for c in range(ndyn):
        piv = c
        for r in range(c + 1, ndyn):
            if abs(A[r, c]) > abs(A[piv, c]):
                piv = r
        if piv != c:
            for j in range(ndyn):
                A[c, j], A[piv, j] = A[piv, j], A[c, j]
                Winv[c, j], Winv[piv, j] = Winv[piv, j], Winv[c, j]
        d = 1.0 / A[c, c]
        for j in range(ndyn):
            A[c, j] *= d
            Winv[c, j] *= d
        for r in range(ndyn):
            if r != c:
                f = A[r, c]
                if f != 0.0:
                    for j in range(ndyn):
                        A[r, j] -= f * A[c, j]
                        Winv[r, j] -= f * Winv[c, j]


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _w_inverse(J, hd, Winv, A):
    """Inverse of the dynamic block of W = I - hd J into ``Winv``
    (:func:`gauss_jordan`); ``A`` is scratch of its shape."""
    ndyn = J.shape[1]
    for i in range(ndyn):
        for j in range(ndyn):
            A[i, j] = (1.0 if i == j else 0.0) - hd * J[i, j]
            Winv[i, j] = 1.0 if i == j else 0.0
    gauss_jordan(A, Winv)


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _w_solve(J, Winv, hd, x, out):
    """Solve W out = x: the dynamic block by its inverse, the quadratures (which do
    not feed back) by substitution, out_q = x_q + hd J_q,dyn out_dyn."""
    ndyn = J.shape[1]
    for i in range(ndyn):
        acc = 0.0
        for j in range(ndyn):
            acc += Winv[i, j] * x[j]
        out[i] = acc
    for q in range(ndyn, x.shape[0]):
        acc = x[q]
        for j in range(ndyn):
            acc += hd * J[q, j] * out[j]
        out[q] = acc


@njit(cache=True, inline="always")
def _column_state(k, ndyn, nn):
    """The state of the Jacobian's column ``k``: the network's dynamic ones, then
    :data:`LOOP_COLUMNS`."""
    if k < ndyn:
        return k
    return nn + LOOP_COLUMNS[k - ndyn]


@njit(cache=True)
def _loop_w_inverse(J, hd, Winv, A, ndyn, nn):
    """Inverse of the block of W = I - hd J over the Jacobian's columns (their rows and
    columns) into ``Winv``, by :func:`corliss.engine.kernels.jacobians.gauss_jordan`, as
    :func:`corliss.engine.kernels._w_inverse`; ``A`` is scratch of its shape."""
    m = J.shape[1]
    for i in range(m):
        r = _column_state(i, ndyn, nn)
        for j in range(m):
            A[i, j] = (1.0 if i == j else 0.0) - hd * J[r, j]
            Winv[i, j] = 1.0 if i == j else 0.0
    gauss_jordan(A, Winv)


@njit(cache=True)
def _loop_w_solve(J, Winv, hd, x, out, ndyn, nn, xs):
    """Solve W out = x: the Jacobian's columns' states by the inverse, the rest (which
    do not feed back) by substitution, out_q = x_q + hd J_q out_columns; ``xs`` is
    scratch of the columns' length."""
    m = J.shape[1]
    for i in range(m):
        acc = 0.0
        for j in range(m):
            acc += Winv[i, j] * x[_column_state(j, ndyn, nn)]
        xs[i] = acc
    for q in range(x.shape[0]):
        acc = x[q]
        for j in range(m):
            acc += hd * J[q, j] * xs[j]
        out[q] = acc
    for i in range(m):
        out[_column_state(i, ndyn, nn)] = xs[i]
