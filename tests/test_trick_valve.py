"""Double-ported and Allen (trick) valves, Spangler Arts. 26-27.

Art. 26: a double-ported valve admits through two ports into each passage; "the
problem is exactly the same as for a single valve", only the area doubles.
Art. 27: the Allen valve's passage admits steam past the far edge of the seat while its
end opens the port, "double the area for the same movement that could be obtained
with the ordinary valve"; the passage's mouth (width a) limits what it adds, and both
streams enter through the same port face (width w): opening = min(p + min(p, a), w)
for a plain opening p = x - lap >= 0.  Exhaust "as in the plain slide".
"""

import dataclasses
import math

import numpy as np
import pytest

from corliss.errors import InputError
from corliss.valves.events import events
from corliss.valves.portmap import tabulate
from corliss.valves.slide_valve import SlideValve, SlideValveSpec

from conftest import make_scene

IN = 0.0254
HARMONIC = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
# a locomotive valve: 2 3/4 in throw, 7/8 in lap, 1/16 in lead, 1 1/4 in ports (the
# Hinkley link's valve in full gear, Peabody 1877), 3/8 in passage (assumed)
PLAIN = SlideValveSpec(eccentricity_m=2.75 * IN, lap_m=(0.875 * IN,) * 2,
                       exhaust_lap_m=(0.0, 0.0),
                       angular_advance_rad=math.asin(0.9375 / 2.75),
                       port_width_m=1.25 * IN, port_length_m=15 * IN, eccentric_rod_m=54 * IN)
A = 0.375 * IN
ALLEN = dataclasses.replace(PLAIN, allen_passage_m=A)
TH = np.linspace(0.0, 2 * math.pi, 7201)


def test_admission_area_doubled_while_the_opening_is_under_the_passage():
    """Art. 27: twice the plain area for the same movement while the plain opening p is
    below the passage's width a; beyond it the passage adds a constant a, until the
    port face is full.  Checked against the closed form at 7201 angles (to rounding)."""
    plain, allen = SlideValve(PLAIN), SlideValve(ALLEN)
    s = plain.signed_openings(TH)
    a_plain, a_allen = plain.areas(TH), allen.areas(TH)
    w, length = PLAIN.port_width_m, PLAIN.port_length_m
    for port in (0, 2):
        p = s[port]
        small = (p > 0) & (p < A)
        assert small.sum() > 100                       # the test looks at something
        assert np.allclose(a_allen[port][small], 2 * a_plain[port][small], rtol=1e-12)
        big = p >= A
        assert np.allclose(a_allen[port][big],
                           np.minimum(p[big] + A, w) * length, rtol=1e-12)
        assert np.all(a_allen[port][p <= 0] == 0.0)
        assert a_allen[port].max() == pytest.approx(w * length, rel=1e-12)   # never more
    for port in (1, 3):                                # the exhaust is the plain slide's
        assert np.array_equal(a_allen[port], a_plain[port])


def test_events_lead_and_overtravel_unchanged():
    """The passage opens and closes with the valve's edge (Art. 27), so admission,
    cut-off, release, compression, the lead (a displacement, Art. 14) and the
    overtravel are the plain valve's, to the bisection's 1e-13 rad; only the greatest
    opening grows: with a 1 1/2 in throw the plain valve opens r - l = 5/8 in, the
    Allen valve 5/8 + 3/8 = 1 in (under the 1 1/4 in port), with an infinite rod."""
    short = dict(eccentricity_m=1.5 * IN, angular_advance_rad=math.asin(0.9375 / 1.5),
                 eccentric_rod_m=None)               # Zeuner: the opening peaks at r - l
    plain = events(SlideValve(dataclasses.replace(PLAIN, **short)), HARMONIC)
    allen = events(SlideValve(dataclasses.replace(ALLEN, **short)), HARMONIC)
    for end in ("head", "crank"):
        for key, v in plain[end].items():
            if key == "max_port_opening_m":
                # the sampled maximum (7200 a turn) of a curve flat at its top
                assert v == pytest.approx(0.625 * IN, rel=1e-5)
                assert allen[end][key] == pytest.approx(1.0 * IN, rel=1e-5)
            else:
                assert v is not None
                assert allen[end][key] == pytest.approx(v, abs=1e-9), key


def test_double_ported_valve_doubles_every_area():
    """Art. 26: two openings per edge, the same valve problem, twice the area: the same
    events, the port's largest opening (every edge it uncovers) twice one edge's."""
    single = SlideValve(PLAIN)
    double = SlideValve(dataclasses.replace(PLAIN, ports_per_end=2))
    assert np.allclose(double.areas(TH), 2 * single.areas(TH), rtol=1e-15, atol=0)
    e1, e2 = events(single, HARMONIC), events(double, HARMONIC)
    for end in ("head", "crank"):
        assert e2[end].pop("max_port_opening_m") == 2 * e1[end].pop("max_port_opening_m")
    assert e2 == e1


def test_portmap_puts_the_trick_valves_kinks_on_its_grid():
    """The Allen opening has two kinks of its own, where the passage is full (p = a) and
    where plain opening and passage together fill the port (p + a = w); the gear reports
    them as kink levels and the PortMap puts a grid point at each crossing, so reading
    the map errs only by the curve's bending between points, as for a plain valve
    (within a factor 2 of the plain valve's error; off the grid, the kinks would cost
    (slope change) h / 4, about r h length / 4, hundreds of times more)."""
    gear = SlideValve(ALLEN)
    pm = tabulate(gear)
    th = np.linspace(0.0, 2 * math.pi, 20001)
    err = np.max(np.abs(np.array([pm.areas(t) for t in th]).T - gear.areas(th)))
    plain = SlideValve(PLAIN)
    pm_plain = tabulate(plain)
    err_plain = np.max(np.abs(np.array([pm_plain.areas(t) for t in th]).T - plain.areas(th)))
    h = 2 * math.pi / 1440
    assert err < 2 * err_plain
    assert err < PLAIN.eccentricity_m * h / 4 * PLAIN.port_length_m / 50


def test_scene_key_and_its_checks():
    sc = make_scene(valve_gear={"allen_passage": "0.375 in"})
    from corliss.engine.model import build_gear
    assert build_gear(sc).spec.allen_passage_m == pytest.approx(A)
    with pytest.raises(InputError, match="valve_gear.allen_passage"):
        make_scene(valve_gear={"allen_passage": "1.5 in"})     # wider than the 1.25 in port
    link = make_scene(valve_gear={"type": "link_motion", "link": "stephenson_open",
                                  "eccentricity": "2.75 in", "angular_advance": "20 deg",
                                  "eccentric_rod": "54 in", "half_link": "6 in",
                                  "block": "3 in", "lap": "7/8 in", "lead": None,
                                  "connection": None, "steam": None,
                                  "allen_passage": "3/8 in"})
    g = build_gear(link)                       # the Allen valve on a link motion
    assert g.spec.allen_passage_m == pytest.approx(A)
    s = g.signed_openings(TH)[0]
    small = (s > 0) & (s < A)
    assert small.any()
    assert np.allclose(g.openings(TH)[0][small], 2 * s[small], rtol=1e-12)
