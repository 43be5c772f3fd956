"""A slide valve's travel in one compiled loop (corliss.valves.travel_kernel).

Held to Spangler's closed forms (Art. 13: Zeuner's ``r sin(theta + delta)``, and the
finite rod's shortfall vanishing where the eccentric stands at right angles to the
line of motion), and to the numpy expressions it replaced, bit for bit: every port
map, event and scene output was found with those.
"""

import math

import numpy as np
import pytest

from corliss.valves.slide_valve import LappedValve, SlideValve, SlideValveSpec
from corliss.valves.travel_kernel import eccentric_travel

TH = np.linspace(0.0, 2.0 * math.pi, 7201)

SPECS = [
    dict(eccentric_rod_m=None),
    dict(eccentric_rod_m=1.524),
    dict(eccentric_rod_m=0.9, setting="mid_travel"),
    dict(eccentric_rod_m=0.9, steam="inside"),
    dict(eccentric_rod_m=0.9, steam="inside", connection="reverse_lever",
         setting="mid_travel"),
]


def _gear(**kw):
    base = dict(eccentricity_m=0.0762, lap_m=(0.028, 0.026), exhaust_lap_m=(0.002, -0.001),
                angular_advance_rad=0.4715, port_width_m=0.0337, port_length_m=0.244)
    base.update(kw)
    return SlideValve(SlideValveSpec(**base))


def test_sin_and_cos_are_numpys():
    """Without a rod, throw 1 and no advance, the loop's displacement is ``sin(theta)``:
    the same bits as np.sin (both the C library's sin), over a turn's samples and
    random angles of several turns."""
    rng = np.random.default_rng(2)
    th = np.concatenate([TH, rng.uniform(-20.0, 20.0, 100_000)])
    x = eccentric_travel(th, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, False)
    assert x.tobytes() == np.sin(th).tobytes()


@pytest.mark.parametrize("kw", SPECS)
def test_travel_equals_the_numpy_expressions(kw):
    """The compiled 1-d path against the numpy path (a 2-d array of the same angles
    takes it), bit for bit; and the four signed openings against the rows of
    :meth:`LappedValve.signed_openings`."""
    gear = _gear(**kw)
    x = gear.travel(TH)
    assert x.tobytes() == gear.travel(TH[None, :])[0].tobytes()
    assert gear.signed_openings(TH).tobytes() == LappedValve.signed_openings(gear, TH).tobytes()


@pytest.mark.parametrize("kw", SPECS)
def test_travel_at_the_eccentrics_right_angle(kw):
    """Where ``theta + delta = pi / 2`` the eccentric's centre is at its full throw and
    the rod is parallel to the line of motion: the shortfall ``g - sqrt(g**2 - (r cos
    (theta + delta))**2)`` is zero, so the displacement is ``r`` less ``sigma`` times
    the equal-lead setting's shift (``g - sqrt(g**2 - (r cos delta)**2)``) (Spangler
    Art. 13).  Tolerance 1e-15 m: a few roundings of a 0.08 m displacement."""
    gear = _gear(**kw)
    s = gear.spec
    th = np.array([0.5 * math.pi - s.angular_advance_rad, 0.3])
    g, r, d = s.eccentric_rod_m, s.eccentricity_m, s.angular_advance_rad
    shift = 0.0
    if g is not None and s.setting == "equal_lead":
        shift = g - math.sqrt(g * g - (r * math.cos(d)) ** 2)
    assert abs(gear.travel(th)[0] - (r - s.sigma * shift)) < 1e-15
    # and at any angle: r sin(theta + delta) plus sigma times the shortfall, less shift
    short = 0.0 if g is None else g - math.sqrt(g * g - (r * math.cos(0.3 + d)) ** 2) - shift
    assert abs(gear.travel(th)[1] - (r * math.sin(0.3 + d) + s.sigma * short)) < 1e-15
