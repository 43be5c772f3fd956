"""The Bilgram diagram (Spangler Ch. XIX, Arts. 149-150) against Zeuner's events."""

import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from corliss.plot import bilgram_events, plot_bilgram_diagram  # noqa: E402
from corliss.valves.events import events  # noqa: E402
from corliss.valves.shaft_governor import ShaftGovernorGear, ShaftGovernorSpec  # noqa: E402
from corliss.valves.slide_valve import SlideValve, SlideValveSpec  # noqa: E402

IN = 0.0254
HARMONIC = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
KEYS = ("admission_deg", "cutoff_deg", "release_deg", "compression_deg")

# (r, lap head/crank, exhaust lap head/crank [in], delta [deg]): the Problem 1 kind of
# valve (Art. 19, 150), with equal and unequal laps, exhaust lap, exhaust clearance and
# zero exhaust lap
VALVES = [
    (3.0, (1.0, 1.0), (0.0, 0.0), 25.0),
    (2.625, (0.625, 0.625), (0.125, 0.125), 18.0),
    (2.0, (0.875, 0.75), (0.0625, -0.0625), 35.0),
    (1.75, (0.5, 0.6), (-0.1, 0.2), 30.0),
]


def slide(r, laps, elaps, delta):
    return SlideValve(SlideValveSpec(r * IN, tuple(v * IN for v in laps),
                                     tuple(v * IN for v in elaps), math.radians(delta),
                                     1.0 * IN, 10 * IN))


def _diff(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


@pytest.mark.parametrize("valve", VALVES)
def test_bilgram_gives_zeuners_events(valve):
    """Art. 150: "the problems connected with the simple valve can be solved as easily
    with this diagram as with the Zeuner diagram": the crank lines tangent to the lap
    and exhaust-lap circles about the Bilgram point (Art. 149) are the crank angles at
    which ``events`` finds, by bisection on the port openings, every admission, cut-off,
    release and compression of both ends.  0.1 deg is the drawing's tolerance the brief
    allows; the two are in fact the same angles to rounding."""
    gear = slide(*valve)
    z = events(gear, HARMONIC)
    b = bilgram_events(gear)
    for end in ("head", "crank"):
        for key in KEYS:
            assert z[end][key] is not None
            assert _diff(b[end][key], z[end][key]) < 0.1, (end, key)
            assert _diff(b[end][key], z[end][key]) < 1e-6, (end, key)


@pytest.mark.parametrize("valve", VALVES)
def test_dk_is_lap_plus_lead(valve):
    """Art. 149: "dk perpendicular to oa ... equal to the lap plus the lead"; the leads
    read so equal the openings at dead centre that ``events`` gives."""
    gear = slide(*valve)
    z = events(gear, HARMONIC)
    b = bilgram_events(gear)
    r, laps, _, delta = valve
    assert b["head"]["lead_m"] + laps[0] * IN == pytest.approx(r * IN * math.sin(math.radians(delta)),
                                                               abs=1e-15)
    for end in ("head", "crank"):
        assert b[end]["lead_m"] == pytest.approx(z[end]["lead_m"], abs=1e-12)


def test_a_circle_about_o_means_no_event():
    """A lap circle that encloses o has no tangent from o: that port never opens (here
    an exhaust clearance wider than the throw keeps the exhaust open all the time)."""
    gear = slide(2.0, (0.75, 0.75), (-2.5, -2.5), 30.0)
    b = bilgram_events(gear)
    z = events(gear, HARMONIC)
    assert b["head"]["release_deg"] is None and z["head"]["release_deg"] is None
    assert _diff(b["head"]["cutoff_deg"], z["head"]["cutoff_deg"]) < 1e-6


def test_drawn_from_the_zeuner_form_of_a_gear_with_a_finite_rod():
    """For a gear with an exact motion the diagram is Zeuner's (``zeuner_travel``): the
    Bilgram point is (S, -C) of the eccentric centre, at distance r = hypot(C, S) from o,
    and the events are those of Zeuner's form, not of the exact motion."""
    import matplotlib.pyplot as plt
    spec = ShaftGovernorSpec("straight", 2.0 * IN, math.radians(25), (0.75 * IN,) * 2,
                             (0.0, 0.0), 1.0 * IN, 8 * IN, centre_travel_m=1.6 * IN,
                             setting=0.5, eccentric_rod_m=10 * IN)
    exact = ShaftGovernorGear(spec)
    C, S = spec.coefficients()
    zform = SlideValve(SlideValveSpec(math.hypot(C, S), (0.75 * IN,) * 2, (0.0, 0.0),
                                      math.atan2(C, S), 1.0 * IN, 8 * IN))
    b, z = bilgram_events(exact), events(zform, HARMONIC)
    assert _diff(b["head"]["cutoff_deg"], z["head"]["cutoff_deg"]) < 1e-6
    assert _diff(b["head"]["cutoff_deg"], events(exact, HARMONIC)["head"]["cutoff_deg"]) > 0.5
    fig, ax = plt.subplots()
    out = plot_bilgram_diagram(exact, ax, "SI")
    d = out["lines"]["d"].get_data()
    assert (d[0][0], d[1][0]) == pytest.approx((S * 1000, -C * 1000), rel=1e-12)
    circle = out["lines"]["valve_circle"].get_data()
    assert np.allclose(np.hypot(*circle), math.hypot(C, S) * 1000)
    plt.close(fig)
