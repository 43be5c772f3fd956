"""The slider crank in its two forms agrees to round-off: the compiled kernels' scalar
form (:func:`corliss.engine.kernels.mechanism.slider_crank`, which
``piston_position`` and ``piston_kinematics`` call) and the array form of the Python
paths (:class:`corliss.engine.geometry.CylinderGeometry`, which
:mod:`corliss.engine.crank_effort` calls).

The two forms are one law with their operations in different orders (each keeps the
last bits of the numbers computed from it), so they agree to a few units in the last
place: 1e-15 relative to the stroke for travel and velocity, 1e-14 for acceleration,
whose last term ``R^4 sin^2 cos^2 / root^3`` is rounded by a power routine in one form
and by products in the other.

The physics against closed forms (Marks, *The Steam Engine*, Art. 96 III, eqs.
239-241): travel 0 and 2R at the dead centres; with an infinite rod the harmonic
``R (1 - cos a)``; mid-stroke behind the harmonic by ``L - sqrt(L^2 - R^2)``; velocity
and acceleration the derivatives of travel (central differences, whose truncation
h^2 s'''/6 at h = 1e-5 rad is below 1e-11 m for R = 0.3 m).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from corliss.engine.geometry import CylinderGeometry, EngineSpec
from corliss.engine.kernels.mechanism import slider_crank

RNG = np.random.default_rng(26)


def _geometry(R, L, angular=True):
    spec = EngineSpec(bore_m=0.4, stroke_m=2 * R, connecting_rod_m=L,
                      piston_rod_diameter_m=0.05, clearance=(0.05, 0.05))
    return CylinderGeometry(spec, rod_angularity=angular)


def _compiled(R, L, a, angular=True):
    out = np.array([slider_crank(R, L, math.sin(x), math.cos(x), angular) for x in a])
    return out[:, 0], out[:, 1], out[:, 2]


def _arrays(R, L, a, angular=True):
    g = _geometry(R, L, angular)
    return g.piston_m(a), g.dpiston_m_per_rad(a), g.d2piston_m_per_rad2(a)


@pytest.mark.parametrize("angular", [True, False])
def test_compiled_and_array_forms_agree(angular):
    for _ in range(40):
        R = RNG.uniform(0.05, 0.5)
        L = R * RNG.uniform(3.0, 8.0)
        a = RNG.uniform(-2 * math.pi, 4 * math.pi, 50)
        for k, (c, p) in enumerate(zip(_compiled(R, L, a, angular), _arrays(R, L, a, angular))):
            tol = (1e-15, 1e-15, 1e-14)[k] * 2 * R
            np.testing.assert_allclose(c, p, rtol=0, atol=tol)


def test_dead_centres_and_infinite_rod():
    R, L = 0.3, 1.5
    s = _compiled(R, L, np.array([0.0, math.pi, 0.5 * math.pi]))[0]
    assert s[0] == 0.0 and s[1] == pytest.approx(2 * R, rel=1e-15)
    assert s[2] == pytest.approx(R + L - math.sqrt(L * L - R * R), rel=1e-15)
    a = RNG.uniform(0.0, 2 * math.pi, 50)
    np.testing.assert_allclose(_compiled(R, L, a, False)[0], R * (1 - np.cos(a)), rtol=0,
                               atol=1e-16)


@pytest.mark.parametrize("form", [_compiled, _arrays])
@pytest.mark.parametrize("angular", [True, False])
def test_derivatives_are_those_of_the_travel(form, angular):
    R, L, h = 0.3, 1.2, 1e-5
    a = np.linspace(0.0, 2 * math.pi, 37)
    _, ds, d2s = form(R, L, a, angular)
    up, down = form(R, L, a + h, angular), form(R, L, a - h, angular)
    # central differences: truncation h^2/6 |s'''| < 1e-11 m, cancellation 1e-16 R / h
    np.testing.assert_allclose(ds, (up[0] - down[0]) / (2 * h), rtol=0, atol=1e-9)
    np.testing.assert_allclose(d2s, (up[1] - down[1]) / (2 * h), rtol=0, atol=1e-9)
