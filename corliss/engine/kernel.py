"""The compiled hot loop: right-hand side and integrators of the crank-resolved model.

The same equations as :class:`corliss.engine.crank_resolved.CrankResolved` (see there),
compiled with numba: geometry and PortMap arrays, reservoir states and the property
table go in as plain numbers and arrays, one call integrates a whole cycle.  Two
integrators:

* ``"dopri5"``: Dormand-Prince 5(4), adaptive, with the usual error norm
  ``max |err_i| / (atol_i + rtol |y_i|)``, step-size control with safety 0.9 and
  limits 0.2-5, FSAL; restarted at every kink of the port areas, so a port opening
  never lies inside a step (no storm of rejected steps);
* ``"rk4"``: classical fourth-order Runge-Kutta at a fixed crank-angle step, each
  segment between kinks divided into equal steps no longer than the step asked for;
* ``"rosenbrock"``: the L-stable Rosenbrock 2(3) pair of Shampine and Reichelt
  (MATLAB's ode23s), with a finite-difference Jacobian that uses the model's
  structure (each end's 2 x 2 block; the quadratures do not feed back).  Pressure
  equalisation through an open port is stiff (an eigenvalue near -300 per radian on
  the default engine), which holds the explicit methods to steps of about 0.6 deg
  whatever their tolerance; the Rosenbrock method steps over it.

Output samples between steps come from cubic Hermite interpolation on the states and
derivatives at the step ends (third-order, well inside the step error).

Compiled code is cached on disk by numba (``cache=True``): a run pays compilation
once per machine (measured in the accuracy study and the issue notes).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from corliss.engine.crank_resolved import N_DYN, N_QUAD, RHO_MIN, TWO_PI, U_MAX, U_MIN
from corliss.thermo.orifice import kappa_of, port_flow
from corliss.thermo.steam_table import lookup

TIER_TABLE, TIER_PERFECT = 0, 1


@njit(cache=True)
def props(tier, tab, perf, rho, u):
    """(p, T, dryness, superheated) from the compiled tier, inputs clamped."""
    if not rho > RHO_MIN:
        rho = RHO_MIN
    if not u > U_MIN:
        u = U_MIN
    if u > U_MAX:
        u = U_MAX
    if tier == TIER_PERFECT:
        R, cv, u_ref = perf[0], perf[1], perf[2]
        T = (u - u_ref) / cv
        if T < 1.0:
            T = 1.0
        return rho * R * T, T, 1.0, True
    return lookup(tab, rho, u)


@njit(cache=True)
def _cell(grid, t):
    """Index and weight of ``t`` in the PortMap grid (one search serves all ports)."""
    n = grid.shape[0]
    k = np.searchsorted(grid, t) - 1
    if k < 0:
        k = 0
    if k > n - 2:
        k = n - 2
    g0 = grid[k]
    return k, (t - g0) / (grid[k + 1] - g0)


@njit(cache=True)
def rhs(th, y, dy, geo, grid, areas, cd, res, omega, band, tier, tab, perf):
    """Derivatives with respect to crank angle, written into ``dy``."""
    R, L, S, Ah, Ac, Vch, Vcc, ang = geo[0], geo[1], geo[2], geo[3], geo[4], geo[5], geo[6], geo[7]
    sn = math.sin(th)
    cs = math.cos(th)
    s = R * (1.0 - cs)
    ds = R * sn
    if ang > 0.0:
        root = math.sqrt(L * L - R * R * sn * sn)
        s += L - root
        ds += R * R * sn * cs / root
    kc_, wc_ = _cell(grid, th % TWO_PI)
    pc, rc, hc, kc, pe, re, he, ke = res[0], res[1], res[2], res[3], res[4], res[5], res[6], res[7]
    for end in range(2):
        if end == 0:
            V = Vch + Ah * s
            dV = Ah * ds
        else:
            V = Vcc + Ac * (S - s)
            dV = -Ac * ds
        m = y[2 * end]
        U = y[2 * end + 1]
        rho = m / V
        u = U / m if m > 0.0 else hc
        p, T, x, sup = props(tier, tab, perf, rho, u)
        if rho < RHO_MIN:
            rho = RHO_MIN
        k = kappa_of(x, sup)
        h = u + p / rho
        a_s = areas[2 * end, kc_] * (1.0 - wc_) + areas[2 * end, kc_ + 1] * wc_
        a_e = areas[2 * end + 1, kc_] * (1.0 - wc_) + areas[2 * end + 1, kc_ + 1] * wc_
        ms = port_flow(a_s, cd[2 * end], pc, rc, kc, p, rho, k, band)
        me = port_flow(a_e, cd[2 * end + 1], pe, re, ke, p, rho, k, band)
        hs = ms * (hc if ms > 0.0 else h)
        he_ = me * (he if me > 0.0 else h)
        dy[2 * end] = (ms + me) / omega
        dy[2 * end + 1] = (hs + he_) / omega - p * dV
        q = N_DYN + end * N_QUAD
        dy[q] = ms / omega
        dy[q + 1] = hs / omega
        dy[q + 2] = me / omega
        dy[q + 3] = he_ / omega
        dy[q + 4] = p * dV


# Dormand-Prince 5(4) tableau
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = np.array([
    [0, 0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0],
    [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
])
_B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0])
_E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


@njit(cache=True)
def _hermite(t0, y0, f0, t1, y1, f1, t, out):
    h = t1 - t0
    s = (t - t0) / h
    h00 = 2 * s ** 3 - 3 * s ** 2 + 1
    h10 = s ** 3 - 2 * s ** 2 + s
    h01 = -2 * s ** 3 + 3 * s ** 2
    h11 = s ** 3 - s ** 2
    for i in range(y0.shape[0]):
        out[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]


@njit(cache=True)
def _w_solve(J, hd, x, out):
    """Solve (I - hd J) out = x for the model's Jacobian structure.

    Only the four dynamic states (m, U of each end) feed back; each end's 2 x 2 block
    is solved directly, and the quadratures follow by substitution:
    out_q = x_q + hd J_q,dyn out_dyn.
    """
    for e in range(2):
        i = 2 * e
        a = 1.0 - hd * J[i, i]
        b = -hd * J[i, i + 1]
        c = -hd * J[i + 1, i]
        d = 1.0 - hd * J[i + 1, i + 1]
        det = a * d - b * c
        out[i] = (d * x[i] - b * x[i + 1]) / det
        out[i + 1] = (a * x[i + 1] - c * x[i]) / det
    for q in range(N_DYN, x.shape[0]):
        acc = x[q]
        for j in range(N_DYN):
            acc += hd * J[q, j] * out[j]
        out[q] = acc


@njit(cache=True)
def _jacobian(t, y, f0, J, T, yscale, geo, grid, areas, cd, res, omega, band, tier, tab, perf):
    """Finite-difference Jacobian of the dynamic columns and the time derivative.

    The two ends do not interact (constant chest and exhaust), so one evaluation
    perturbs the mass of both ends and one their energy: 3 evaluations in all.
    """
    n = y.shape[0]
    yp = y.copy()
    fp = np.empty(n)
    for col in range(2):
        dlt0 = 1e-7 * max(abs(y[col]), yscale[col])
        dlt1 = 1e-7 * max(abs(y[col + 2]), yscale[col + 2])
        yp[:] = y
        yp[col] += dlt0
        yp[col + 2] += dlt1
        rhs(t, yp, fp, geo, grid, areas, cd, res, omega, band, tier, tab, perf)
        for i in range(n):
            J[i, col] = 0.0
            J[i, col + 2] = 0.0
        # head-end rows and head quadratures see the head perturbation only
        for i in (0, 1):
            J[i, col] = (fp[i] - f0[i]) / dlt0
        for i in (2, 3):
            J[i, col + 2] = (fp[i] - f0[i]) / dlt1
        for i in range(N_DYN, N_DYN + N_QUAD):
            J[i, col] = (fp[i] - f0[i]) / dlt0
        for i in range(N_DYN + N_QUAD, n):
            J[i, col + 2] = (fp[i] - f0[i]) / dlt1
    dt = 1e-7 * max(abs(t), 1.0)
    rhs(t + dt, y, fp, geo, grid, areas, cd, res, omega, band, tier, tab, perf)
    for i in range(n):
        T[i] = (fp[i] - f0[i]) / dt


@njit(cache=True)
def integrate_cycle(y0, stops, out_theta, method, rtol, atol, step, geo, grid, areas, cd,
                    res, omega, band, tier, tab, perf):
    """Integrate from ``stops[0]`` to ``stops[-1]``, restarting at every stop.

    ``method``: 0 dopri5, 1 rk4, 2 Rosenbrock ode23s.  Returns
    ``(y_end, samples, nfev, ok)``; ``samples[:, k]`` is the state at ``out_theta[k]``.
    """
    n = y0.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    f0 = np.empty(n)
    f1 = np.empty(n)
    K = np.empty((7, n))
    ytmp = np.empty(n)
    ynew = np.empty(n)
    tmp = np.empty(n)
    nfev = 0
    io = 0
    hp = np.zeros(3)   # (next step, next output index, failed) from the Rosenbrock segment
    # samples at or before the start
    while io < out_theta.shape[0] and out_theta[io] <= stops[0]:
        samples[:, io] = y
        io += 1
    h_prev = 0.0
    for seg in range(stops.shape[0] - 1):
        a = stops[seg]
        b = stops[seg + 1]
        if b - a <= 0.0:
            continue
        t = a
        rhs(t, y, f0, geo, grid, areas, cd, res, omega, band, tier, tab, perf)
        nfev += 1
        if method == 1:   # rk4, fixed step
            nstep = int(math.ceil((b - a) / step - 1e-9))
            if nstep < 1:
                nstep = 1
            h = (b - a) / nstep
            for _ in range(nstep):
                rhs(t + 0.5 * h, y + 0.5 * h * f0, K[1], geo, grid, areas, cd, res, omega,
                    band, tier, tab, perf)
                rhs(t + 0.5 * h, y + 0.5 * h * K[1], K[2], geo, grid, areas, cd, res, omega,
                    band, tier, tab, perf)
                rhs(t + h, y + h * K[2], K[3], geo, grid, areas, cd, res, omega, band, tier,
                    tab, perf)
                for i in range(n):
                    ynew[i] = y[i] + h / 6.0 * (f0[i] + 2 * K[1, i] + 2 * K[2, i] + K[3, i])
                t1 = b if _ == nstep - 1 else t + h
                rhs(t1, ynew, f1, geo, grid, areas, cd, res, omega, band, tier, tab, perf)
                nfev += 4
                while io < out_theta.shape[0] and out_theta[io] <= t1:
                    _hermite(t, y, f0, t1, ynew, f1, out_theta[io], tmp)
                    samples[:, io] = tmp
                    io += 1
                t = t1
                y[:] = ynew
                f0[:] = f1
            continue
        if method == 2:   # Rosenbrock ode23s, adaptive, L-stable
            nfev += _ros23_segment(t, b, y, f0, samples, out_theta, io, rtol, atol, h_prev,
                                   geo, grid, areas, cd, res, omega, band, tier, tab, perf, hp)
            io = int(hp[1])
            h_prev = hp[0]
            if not math.isfinite(y[0]) or hp[2] > 0.0:
                return y, samples, nfev, False
            continue
        # dopri5, adaptive
        if h_prev > 0.0:
            h = min(h_prev, b - a)
        else:
            scale = 0.0
            for i in range(n):
                v = abs(f0[i]) / (atol[i] + rtol * abs(y[i]))
                if v > scale:
                    scale = v
            h = 0.01 * (rtol ** 0.2) / scale if scale > 0.0 else (b - a)
            h = min(max(h, 1e-9), b - a)
        while t < b:
            if t + h > b or b - (t + h) < 1e-12:
                h = b - t
            K[0, :] = f0
            for s_ in range(1, 7):
                for i in range(n):
                    acc = 0.0
                    for j in range(s_):
                        acc += _A[s_, j] * K[j, i]
                    ytmp[i] = y[i] + h * acc
                rhs(t + _C[s_] * h, ytmp, K[s_], geo, grid, areas, cd, res, omega, band, tier,
                    tab, perf)
            nfev += 6
            # ytmp now holds the 5th-order solution (stage 7 evaluated there: FSAL)
            err = 0.0
            for i in range(n):
                e = 0.0
                for j in range(7):
                    e += _E[j] * K[j, i]
                e = abs(h * e) / (atol[i] + rtol * max(abs(y[i]), abs(ytmp[i])))
                if e > err:
                    err = e
            if err <= 1.0 or h < 1e-12:
                t1 = t + h
                while io < out_theta.shape[0] and out_theta[io] <= t1:
                    _hermite(t, y, f0, t1, ytmp, K[6], out_theta[io], tmp)
                    samples[:, io] = tmp
                    io += 1
                t = t1
                y[:] = ytmp
                f0[:] = K[6]
                fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.9 * err ** -0.2))
                h_prev = h * fac
                h = h_prev
            else:
                h = h * max(0.2, 0.9 * err ** -0.2)
            if not (h > 0.0) or not math.isfinite(y[0]):
                return y, samples, nfev, False
    while io < out_theta.shape[0]:
        samples[:, io] = y
        io += 1
    return y, samples, nfev, True


_D = 1.0 / (2.0 + math.sqrt(2.0))
_E32 = 6.0 + math.sqrt(2.0)


@njit(cache=True)
def _ros23_segment(t, b, y, f0, samples, out_theta, io, rtol, atol, h_prev, geo, grid, areas,
                   cd, res, omega, band, tier, tab, perf, hp):
    """One segment of the Rosenbrock 2(3) method of Shampine and Reichelt (MATLAB's
    ode23s; SIAM J. Sci. Comput. 18, 1997), L-stable, with its third-order error
    estimate.  Updates ``y`` and ``f0`` in place; returns the evaluations spent and
    leaves (next step, next output index, failed) in ``hp``."""
    n = y.shape[0]
    J = np.zeros((n, N_DYN))
    Jfull = np.zeros((n, n))
    T = np.empty(n)
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    F1 = np.empty(n)
    F2 = np.empty(n)
    x = np.empty(n)
    ytmp = np.empty(n)
    tmp = np.empty(n)
    yscale = atol / rtol
    nfev = 0
    if h_prev > 0.0:
        h = min(h_prev, b - t)
    else:
        h = min(1e-3, b - t)
    hp[2] = 0.0
    while t < b:
        if t + h > b or b - (t + h) < 1e-12:
            h = b - t
        _jacobian(t, y, f0, Jfull, T, yscale, geo, grid, areas, cd, res, omega, band, tier,
                  tab, perf)
        nfev += 3
        for i in range(n):
            for j in range(N_DYN):
                J[i, j] = Jfull[i, j]
        hd = h * _D
        for i in range(n):
            x[i] = f0[i] + hd * T[i]
        _w_solve(J, hd, x, k1)
        for i in range(n):
            ytmp[i] = y[i] + 0.5 * h * k1[i]
        rhs(t + 0.5 * h, ytmp, F1, geo, grid, areas, cd, res, omega, band, tier, tab, perf)
        for i in range(n):
            x[i] = F1[i] - k1[i]
        _w_solve(J, hd, x, k2)
        for i in range(n):
            k2[i] += k1[i]
            ytmp[i] = y[i] + h * k2[i]
        rhs(t + h, ytmp, F2, geo, grid, areas, cd, res, omega, band, tier, tab, perf)
        nfev += 2
        for i in range(n):
            x[i] = F2[i] - _E32 * (k2[i] - F1[i]) - 2.0 * (k1[i] - f0[i]) + hd * T[i]
        _w_solve(J, hd, x, k3)
        err = 0.0
        for i in range(n):
            e = abs(h / 6.0 * (k1[i] - 2.0 * k2[i] + k3[i]))
            e /= atol[i] + rtol * max(abs(y[i]), abs(ytmp[i]))
            if e > err:
                err = e
        if err <= 1.0 or h < 1e-12:
            t1 = t + h
            while io < out_theta.shape[0] and out_theta[io] <= t1:
                _hermite(t, y, f0, t1, ytmp, F2, out_theta[io], tmp)
                samples[:, io] = tmp
                io += 1
            t = t1
            y[:] = ytmp
            f0[:] = F2
            fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.8 * err ** (-1.0 / 3.0)))
            h = h * fac
        else:
            h = h * max(0.2, 0.8 * err ** (-1.0 / 3.0))
        if not (h > 0.0) or not math.isfinite(y[0]):
            hp[2] = 1.0
            break
    hp[0] = h
    hp[1] = io
    return nfev
