"""The compiled loops of a gear's tabulation (corliss.valves.crossing_kernels).

Each is held to a closed form (the crossings of a cosine sampled over a turn: at
``arccos(level)`` and ``2 pi - arccos(level)``), and to the numpy expressions the
tabulation used before them, bit for bit: the port maps, events and every scene's
outputs were found with those, and must not move by a bit.
"""

import math

import numpy as np
import pytest

from corliss.valves.crossing_kernels import inverse_quintic, merged_grid, sign_changes
from corliss.valves.events import CROSSING_NODES, CROSSING_TOL_RAD

N = 7200
TH = np.linspace(0.0, 2.0 * math.pi, N + 1)
H = TH[1] - TH[0]
STEPS = np.array(CROSSING_NODES, dtype=np.int64)


def _sign_changes_numpy(s, levels):
    """The numpy chain the kernel replaced (the crossing table's brackets)."""
    n = s.shape[1] - 1
    above = s[:, None, :] > levels[:, :, None]
    flat = np.flatnonzero(above[:, :, 1:] != above[:, :, :-1])
    ports, rest = np.divmod(flat, levels.shape[1] * n)
    levs, idx = np.divmod(rest, n)
    return ports, levs, idx, above[ports, levs, idx + 1]


def _inverse_quintic_numpy(s, ports, lev, idx, a):
    """The numpy chain the kernel replaced (inverse Lagrange through six samples)."""
    n = s.shape[1] - 1
    nodes = STEPS.astype(float)
    diag = (np.arange(STEPS.size), np.arange(STEPS.size))
    f = s[ports[None, :], (idx[None, :] + STEPS[:, None]) % n] - lev[None, :]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        diff = f[:, None, :] - f[None, :, :]
        diff[diag] = 1.0
        num = np.negative(f[None, :, :], out=np.empty(diff.shape))
        num[diag] = 1.0
        u = (nodes[:, None] * (num.prod(axis=1) / diff.prod(axis=1))).sum(axis=0)
        return a + u * H


def _cosines():
    """Four ports' openings ``r cos(theta - phi) + o`` over the turn's samples [m], and two
    levels each [m]."""
    r = np.array([0.05, 0.03, 0.07, 0.02])
    phi = np.array([0.3, 1.9, 3.5, 5.0])
    o = np.array([0.0, -0.01, 0.02, 0.005])
    s = r[:, None] * np.cos(TH[None, :] - phi[:, None]) + o[:, None]
    levels = np.column_stack([np.zeros(4), np.array([0.02, 0.01, 0.06, 0.0])])
    return s, levels, r, phi, o


def test_sign_changes_are_the_cosines_crossings():
    """Each level ``c`` is crossed twice a turn, at ``phi -+ arccos((c - o) / r)``
    (mod 2 pi): each crossing lies in the bracket the kernel gives, rising on the
    first (the cosine climbs to its top at ``phi``)."""
    s, levels, r, phi, o = _cosines()
    ports, levs, idx, rising = sign_changes(s, levels)
    assert ports.size == 2 * levels.size
    for p in range(4):
        for li in range(2):
            w = math.acos((levels[p, li] - o[p]) / r[p])
            want = sorted([((phi[p] - w) % (2 * math.pi), True),
                           ((phi[p] + w) % (2 * math.pi), False)])
            sel = (ports == p) & (levs == li)
            got = sorted(zip(TH[idx[sel]], rising[sel]))
            for (t_want, up_want), (a, up) in zip(want, got):
                # the bracket [a, a + h] holds the crossing (to a rounding of the angle)
                assert a - 1e-12 <= t_want <= a + H + 1e-12
                assert up == up_want


def test_sign_changes_equal_the_numpy_chain_with_samples_on_the_levels():
    """Samples resting exactly at a level (a seated valve) and random ones: the same
    brackets, in the same order, as the expressions it replaced."""
    rng = np.random.default_rng(3)
    s = np.round(rng.normal(size=(4, N + 1)), 1)       # many samples equal to 0.0 or 0.1
    levels = np.array([[0.0, 0.1], [0.0, -0.1], [0.1, 0.0], [0.0, 0.0]])
    got, want = sign_changes(s, levels), _sign_changes_numpy(s, levels)
    for g, w in zip(got, want):
        assert g.dtype.kind == w.dtype.kind and np.array_equal(g, w)


def test_inverse_quintic_finds_the_cosines_crossings():
    """Read off six samples, the crossing is within the crossing tolerance (1e-13 rad)
    of the closed form: the quintic's error is of the order of the step to the sixth
    power, ``(2 pi / 7200)**6 = 4e-19`` rad, so only the rounding of the samples (some
    1e-16 m over a slope of 1e-2 m/rad: 1e-14 rad) is left."""
    s, levels, r, phi, o = _cosines()
    ports, levs, idx, _ = sign_changes(s, levels)
    lev = levels[ports, levs]
    c = inverse_quintic(s, ports, lev, idx, STEPS, TH[idx], H)
    for k in range(c.size):
        p = ports[k]
        w = math.acos((lev[k] - o[p]) / r[p])
        exact = [(phi[p] - w) % (2 * math.pi), (phi[p] + w) % (2 * math.pi)]
        assert min(abs(c[k] - e) for e in exact) < CROSSING_TOL_RAD


def test_inverse_quintic_equals_the_numpy_chain():
    """Random brackets of random samples, equal samples among them (whose quotients are
    not numbers): the same bits as the expressions it replaced, products and sum taken
    in the same order."""
    rng = np.random.default_rng(5)
    s = rng.normal(size=(4, N + 1))
    s[1, 100:110] = 0.25                                 # a rest: equal samples
    ports = rng.integers(0, 4, 500)
    idx = rng.integers(0, N, 500)
    ports[:3], idx[:3] = 1, [101, 0, N - 1]              # the rest, and both wraps
    lev = rng.normal(size=500) * 0.1
    got = inverse_quintic(s, ports, lev, idx, STEPS, TH[idx], H)
    want = _inverse_quintic_numpy(s, ports, lev, idx, TH[idx])
    assert got.tobytes() == want.tobytes()


@pytest.mark.parametrize("kinks, alone", [
    (np.array([0.1, 1.0, 3.0001]), True),
    (np.array([0.0, TH[7200 // 4 * 2], 6.3]), True),      # on uniform points, past 2 pi
    (np.array([0.5, TH[3600] + 1.5e-9]), False),          # within 2e-9 of a uniform point
])
def test_merged_grid_is_the_union_and_finds_the_near_kinks(kinks, alone):
    """The union of the uniform grid and the kinks (np.union1d's array, bit for bit),
    and whether every kink is alone within 2e-9 rad (two searches of the merged grid)."""
    uniform = np.linspace(0.0, 2.0 * math.pi, 721)
    grid, got_alone = merged_grid(uniform, kinks, 2e-9)
    want = np.union1d(uniform, kinks)
    assert grid.tobytes() == want.tobytes()
    lo = np.searchsorted(want, kinks - 2e-9, "left")
    hi = np.searchsorted(want, kinks + 2e-9, "right")
    assert got_alone == bool((hi - lo == 1).all()) == alone
