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
  segment between kinks divided into equal steps no longer than the step asked for.

Output samples between steps come from cubic Hermite interpolation on the states and
derivatives at the step ends (third-order, well inside the step error).

Compiled code is cached on disk by numba (``cache=True``): a run pays compilation
once per machine (measured in the accuracy study and the issue notes).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from corliss.thermo.steam_table import lookup

TIER_TABLE, TIER_PERFECT = 0, 1
N_DYN, N_QUAD = 4, 5
N_STATE = N_DYN + 2 * N_QUAD
RHO_MIN, U_MIN, U_MAX = 0.02, 1.0e6, 4.0e6
TWO_PI = 2.0 * math.pi


@njit(cache=True)
def _flux(p0, rho0, p1, kappa, band):
    r = p1 / p0
    if r >= 1.0:
        return 0.0
    lin = 1.0
    if r > 1.0 - band:
        lin = (1.0 - r) / band
        r = 1.0 - band
    r_crit = (2.0 / (kappa + 1.0)) ** (kappa / (kappa - 1.0))
    if r < r_crit:
        r = r_crit
    term = r ** (2.0 / kappa) - r ** ((kappa + 1.0) / kappa)
    if term <= 0.0:
        return 0.0
    return lin * math.sqrt(2.0 * kappa / (kappa - 1.0) * p0 * rho0 * term)


@njit(cache=True)
def _port(area, cd, p1, rho1, k1, p2, rho2, k2, band):
    if area <= 0.0:
        return 0.0
    if p1 >= p2:
        return cd * area * _flux(p1, rho1, p2, k1, band)
    return -cd * area * _flux(p2, rho2, p1, k2, band)


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
def _area(grid, areas, port, t):
    n = grid.shape[0]
    k = np.searchsorted(grid, t) - 1
    if k < 0:
        k = 0
    if k > n - 2:
        k = n - 2
    g0 = grid[k]
    w = (t - g0) / (grid[k + 1] - g0)
    return areas[port, k] * (1.0 - w) + areas[port, k + 1] * w


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
    t = th % TWO_PI
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
        k = 1.3 if sup else 1.035 + 0.1 * x
        h = u + p / rho
        a_s = _area(grid, areas, 2 * end, t)
        a_e = _area(grid, areas, 2 * end + 1, t)
        ms = _port(a_s, cd[2 * end], pc, rc, kc, p, rho, k, band)
        me = _port(a_e, cd[2 * end + 1], pe, re, ke, p, rho, k, band)
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
def integrate_cycle(y0, stops, out_theta, method, rtol, atol, step, geo, grid, areas, cd,
                    res, omega, band, tier, tab, perf):
    """Integrate from ``stops[0]`` to ``stops[-1]``, restarting at every stop.

    Returns ``(y_end, samples, nfev, ok)``; ``samples[:, k]`` is the state at
    ``out_theta[k]``.
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
