"""The governor's equation of motion is written once
(:func:`corliss.engine.kernels.governor.governor_motion`), called compiled by the speed
loop and in its Python form by the mean-value model.

The two forms are one source of correctly rounded operations; at random states they
agree to the bit.  The physics against the common form of :mod:`corliss.governors`
(``M z'' + 1/2 M' z'^2 = G w_g^2 - R - c z' - F_f sat(z'/v_e) - J dw_g/dt``):
at rest at the balance speed ``w_g^2 = R / G`` the governor does not move; away from
it the acceleration is the closed form's; friction saturates at the creep speed;
the stops are inelastic.
"""

from __future__ import annotations

import numpy as np
import pytest

from corliss.engine.kernels.governor import governor_motion

RNG = np.random.default_rng(26)


def _states(n):
    for _ in range(n):
        yield (RNG.uniform(-0.05, 1.05), RNG.uniform(-2.0, 2.0), *RNG.uniform(0.5, 20.0, 1),
               RNG.uniform(-5.0, 5.0), *RNG.uniform(1e-4, 1e-2, 1), *RNG.uniform(10.0, 500.0, 1),
               RNG.uniform(-0.5, 0.5), RNG.uniform(0.5, 3.0), RNG.uniform(0.0, 50.0),
               RNG.uniform(0.0, 20.0), RNG.uniform(0.01, 0.1), RNG.uniform(5.0, 40.0),
               RNG.uniform(-20.0, 20.0))


def test_compiled_and_python_forms_agree():
    for state in _states(300):
        assert governor_motion(*state) == governor_motion.py_func(*state)


def test_the_common_form():
    M, dM, G, R, J, ratio, c, F, ve = 4.0, 0.5, 2e-3, 200.0, 0.1, 1.5, 10.0, 5.0, 0.05
    w_bal = np.sqrt(R / G) / ratio
    # at rest at the balance speed, steady shaft: no motion
    zd, zdd = governor_motion(0.5, 0.0, M, dM, G, R, J, ratio, c, F, ve, w_bal, 0.0)
    # G w_g^2 - R cancels to the round-off of R (1e-16 R / M)
    assert zd == 0.0 and abs(zdd) < 1e-14 * R / M
    # moving at zd faster than the creep speed, the shaft accelerating: the closed form
    w, wdot, zd = 1.1 * w_bal, 3.0, 0.2
    want = (G * (ratio * w) ** 2 - R - c * zd - F - J * ratio * wdot - 0.5 * dM * zd ** 2) / M
    got = governor_motion(0.5, zd, M, dM, G, R, J, ratio, c, F, ve, w, wdot)
    assert got[0] == zd
    assert got[1] == pytest.approx(want, rel=1e-14)      # reordered sum: round-off
    # within the creep speed friction is proportional: half the creep speed, half of F
    half = governor_motion(0.5, 0.5 * ve, M, 0.0, G, R, 0.0, ratio, 0.0, F, ve, w_bal, 0.0)
    assert half[1] == pytest.approx(-0.5 * F / M, rel=1e-12)


def test_stops_are_inelastic():
    M, dM, G, R, J, ratio, c, F, ve = 4.0, 0.5, 2e-3, 200.0, 0.1, 1.5, 10.0, 5.0, 0.05
    slow = 0.5 * np.sqrt(R / G) / ratio
    fast = 2.0 * np.sqrt(R / G) / ratio
    assert governor_motion(0.0, -0.1, M, dM, G, R, J, ratio, c, F, ve, slow, 0.0) == (0.0, 0.0)
    assert governor_motion(1.0, 0.1, M, dM, G, R, J, ratio, c, F, ve, fast, 0.0) == (0.0, 0.0)
    # leaving a stop is free
    zd, zdd = governor_motion(0.0, 0.0, M, dM, G, R, J, ratio, c, F, ve, fast, 0.0)
    assert zdd > 0.0
