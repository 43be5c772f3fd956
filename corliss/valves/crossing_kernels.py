"""Compiled loops of a gear's tabulation: the samples' changes of side of each level,
the quintic's crossing read off them, and the merged grid of a port map.

Each does, in one pass over its arrays, what a chain of numpy calls did in several
(each call making its own temporary), with the same arithmetic in the same order:
comparisons only, or IEEE additions, subtractions, multiplications and divisions
(each correctly rounded, no fused multiply-add: numba contracts none without
``fastmath``) taken in the order numpy's reductions take them (the first element,
then each next one), so that every number is the one the numpy chain gave, bit for
bit.  Compiled once and kept in numba's disk cache (``cache=True``).
"""

from __future__ import annotations

import numpy as np
from numba import njit


#: Samples counted a block in :func:`sign_changes`' first pass.
BLOCK = 256


@njit(cache=True)
def sign_changes(s: np.ndarray, levels: np.ndarray):
    """Where each port's samples pass from one side of each of its levels to the other.

    Two passes: the changes counted in blocks of :data:`BLOCK` samples (a loop the
    compiler vectorises), then only the blocks with a change read sample by sample.

    Parameters
    ----------
    s : ndarray
        Signed openings [m], shape ``(P, N + 1)``.
    levels : ndarray
        Levels [m], shape ``(P, L)``.

    Returns
    -------
    ports, levs, idx : ndarray of int64
        Each change's port, level's column and sample ``k``: sample ``k`` is above the
        level (``s > level``) and sample ``k + 1`` not, or the reverse; in the order of
        the flat index ``(port, level, k)``.
    rising : ndarray of bool
        Whether sample ``k + 1`` is the one above.
    """
    n_p, n1 = s.shape
    n_l = levels.shape[1]
    nb = (n1 - 1 + BLOCK - 1) // BLOCK
    cnt = np.zeros((n_p, n_l, nb), dtype=np.int64)
    total = 0
    for p in range(n_p):
        for li in range(n_l):
            lv = levels[p, li]
            for b in range(nb):
                k0 = b * BLOCK
                k1 = min(k0 + BLOCK, n1 - 1)
                left = s[p, k0:k1]
                right = s[p, k0 + 1:k1 + 1]
                c = 0
                for k in range(left.size):
                    c += int(left[k] > lv) ^ int(right[k] > lv)
                cnt[p, li, b] = c
                total += c
    ports = np.empty(total, dtype=np.int64)
    levs = np.empty(total, dtype=np.int64)
    idx = np.empty(total, dtype=np.int64)
    rising = np.empty(total, dtype=np.bool_)
    j = 0
    for p in range(n_p):
        for li in range(n_l):
            lv = levels[p, li]
            for b in range(nb):
                if cnt[p, li, b] == 0:
                    continue
                for k in range(b * BLOCK, min(b * BLOCK + BLOCK, n1 - 1)):
                    here = s[p, k] > lv
                    after = s[p, k + 1] > lv
                    if here != after:
                        ports[j] = p
                        levs[j] = li
                        idx[j] = k
                        rising[j] = after
                        j += 1
    return ports, levs, idx, rising


@njit(cache=True, error_model="numpy")
def inverse_quintic(s: np.ndarray, ports: np.ndarray, lev: np.ndarray, idx: np.ndarray,
                    steps: np.ndarray, a: np.ndarray, h: float) -> np.ndarray:
    """The angle where the quintic through the samples ``idx + steps`` (a turn's samples
    wrapping round), taken as the angle against the opening, puts each level: inverse
    Lagrange interpolation in closed form [rad].

    With ``f_i`` the samples less the level and ``u_i`` the steps, ``u = sum_i u_i
    prod_{k != i} (0 - f_k) / prod_{k != i} (f_i - f_k)``, each product and the sum
    taken in the order of ``steps``; the crossing is ``a + u h``.  Not a number or
    infinite where two samples are equal (the caller proves every crossing on the gear).

    Parameters
    ----------
    s : ndarray
        Signed openings [m] at ``N + 1`` uniform angles, shape ``(P, N + 1)``, the last
        a turn after the first.
    ports, idx : ndarray of int64
        Each crossing's port and the first sample of its bracket.
    lev : ndarray
        Each crossing's level [m].
    steps : ndarray of int64
        The samples read, in steps from ``idx``.
    a : ndarray
        Each bracket's left end [rad].
    h : float
        The samples' step [rad].

    Returns
    -------
    ndarray
        The crossings [rad].
    """
    n = s.shape[1] - 1
    m = steps.size
    f = np.empty(m)
    out = np.empty(ports.size)
    for j in range(ports.size):
        for i in range(m):
            f[i] = s[ports[j], (idx[j] + steps[i]) % n] - lev[j]
        u = 0.0
        for i in range(m):
            pn = 1.0 if i == 0 else -f[0]
            pd = 1.0 if i == 0 else f[i] - f[0]
            for k in range(1, m):
                if k == i:
                    pn *= 1.0
                    pd *= 1.0
                else:
                    pn *= -f[k]
                    pd *= f[i] - f[k]
            term = steps[i] * (pn / pd)
            u = term if i == 0 else u + term
        out[j] = a[j] + u * h
    return out


@njit(cache=True)
def merged_grid(uniform: np.ndarray, kinks: np.ndarray, near: float):
    """The sorted union of two sorted arrays of distinct angles, and whether each of the
    second's lies alone within ``near`` in it.

    Parameters
    ----------
    uniform, kinks : ndarray
        Angles [rad], each increasing, without repeats.
    near : float
        Half the width of the window around each kink [rad].

    Returns
    -------
    grid : ndarray
        Every angle of either, once, increasing (an angle in both is kept once).
    alone : bool
        True when every kink is the only angle of ``grid`` in ``[kink - near, kink +
        near]``.
    """
    nu, nk = uniform.size, kinks.size
    grid = np.empty(nu + nk)
    i = k = g = 0
    while i < nu or k < nk:
        if k >= nk or (i < nu and uniform[i] < kinks[k]):
            v = uniform[i]
            i += 1
        elif i >= nu or kinks[k] < uniform[i]:
            v = kinks[k]
            k += 1
        else:
            v = uniform[i]
            i += 1
            k += 1
        grid[g] = v
        g += 1
    grid = grid[:g]
    alone = True
    j = 0
    for k in range(nk):
        lo_v, hi_v = kinks[k] - near, kinks[k] + near
        while j < g and grid[j] < lo_v:
            j += 1
        c = 0
        q = j
        while q < g and grid[q] <= hi_v:
            c += 1
            q += 1
        if c != 1:
            alone = False
    return grid, alone
