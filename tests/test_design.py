"""``corliss design``: the valve from the events asked.

Three kinds of test.  Spangler's own problems (H. W. Spangler, *Valve-Gears*, 2nd ed.,
1910), each worked here in closed form from his Zeuner relations, against the design
function (the book prints no answers, so the closed forms are derived in each
docstring).  Round trips: design with finite connecting and eccentric rods, build the
scene, and find its events with the package's forward events (the ones ``corliss
events`` prints), which must be those asked within 0.05 deg of crank angle.  And a
design that cannot exist: an InputError naming the event asked and what is valid.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from corliss import scene_events
from corliss.cli import commands as cli
from corliss.files.design_output import design
from corliss.engine.model import build_gear
from corliss.errors import InputError
from corliss.scene.loader import find_scene, load_scene
from corliss.valves.design import design_slide_valve, zeuner_valve
from corliss.valves.slide_valve import SlideValveSpec

from conftest import make_scene

IN = 0.0254
#: The issue's tolerance on a designed event [deg of crank angle].
EVENT_DEG = 0.05
#: Infinite connecting rod: piston at (1 - cos theta) / 2 of the stroke (Spangler's
#: "stroke fraction k with infinite rod" is the crank angle arccos(1 - 2k), Art. 6, Fig. 6).
HARMONIC = lambda t: (1.0 - math.cos(t)) / 2.0  # noqa: E731


def zeuner_base(port_in=2.0) -> SlideValveSpec:
    """A valve with infinite eccentric rod; its throw, advance and laps are designed."""
    return SlideValveSpec(1.0 * IN, (0.0, 0.0), (0.0, 0.0), 0.0, port_in * IN, 10 * IN)


def slider_crank(R, L):
    """s(theta)/S = [R (1 - cos) + L - sqrt(L^2 - R^2 sin^2)] / 2R (Spangler Art. 6 by
    drawing; the closed form, Marks Art. 96, eqs. 239-241)."""
    return lambda t: (R * (1 - math.cos(t)) + L - math.sqrt(L * L - (R * math.sin(t)) ** 2)) / (2 * R)


def crank_at_piston(s, R, L):
    """Crank angle [rad] in [0, pi] with the piston s from head-end dead centre, closed
    form: with A = R + L - s the slider crank gives (A - R cos)^2 = L^2 - R^2 sin^2,
    so cos theta = (A^2 - L^2 + R^2) / (2 A R)."""
    A = R + L - s
    return math.acos((A * A - L * L + R * R) / (2 * A * R))


def _diff(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


# ------------------------------------------------------------------ Spangler's problems
def test_problem_9_cutoff_lead_and_opening_art_22():
    """Spangler Ch. III, Problem 9 (end of the chapter, after Art. 25): "Given
    steam-lead 1/4 inch, cut-off .8 stroke, port-opening 1 1/4 inches, to determine the
    angular advance, lap, and eccentricity" -- his Problem 4, Art. 22, p. 22.

    Art. 22 (as printed): with beta = w_c - 90 deg (w_c the crank at cut-off),
    (l + p) cos(delta + beta) = l and (l + p) sin(delta) = l + i; eliminating l,
    tan(phi) = [p + (p - i) sin beta] / [(i - p) cos beta] and
    delta = phi + arccos(-i cos(phi) / ((p - i) cos beta)), phi in the second quadrant
    and the arccos taken on its negative branch (the other root, 196 deg, is the
    valve turned inside out).  Then l = (p sin(delta) - i) / (1 - sin(delta)) and
    r = l + p.  With infinite rods .8 stroke is w_c = arccos(1 - 1.6) = 126.87 deg
    (cos -0.6, sin 0.8): delta = 30.510 deg, l = 0.78125 in = 25/32, r = 2.03125 in.
    Tolerance 1e-9 in and 1e-7 deg: both are exact, the design solving to 1e-14."""
    i, p = 0.25, 1.25
    wc = math.acos(1 - 2 * 0.8)
    beta = wc - math.pi / 2
    phi = math.atan2(p + (p - i) * math.sin(beta), (i - p) * math.cos(beta))
    assert 90 < math.degrees(phi) < 180
    delta = phi - math.acos(-i * math.cos(phi) / ((p - i) * math.cos(beta)))
    lap = (p * math.sin(delta) - i) / (1 - math.sin(delta))
    r = lap + p
    assert math.degrees(delta) == pytest.approx(30.510, abs=1e-3)
    d = design_slide_valve(zeuner_base(), HARMONIC, cutoff=0.8, lead_m=i * IN,
                           max_opening_m=p * IN)
    assert math.degrees(d.angular_advance_rad) == pytest.approx(math.degrees(delta), abs=1e-7)
    assert d.eccentricity_m / IN == pytest.approx(r, abs=1e-9)
    assert d.lap_m[0] / IN == pytest.approx(lap, abs=1e-9)
    assert d.lap_m[1] / IN == pytest.approx(lap, abs=1e-9)     # infinite rods: ends alike
    # and the first check of Art. 22's two equations themselves
    assert (lap + p) * math.cos(delta + beta) == pytest.approx(lap, abs=1e-12)
    # the Zeuner start is the answer already (nothing finite to correct)
    assert d.zeuner["eccentricity_m"] / IN == pytest.approx(r, abs=1e-9)


def test_problem_10_lap_lead_and_cutoff_art_20():
    """Spangler Ch. III, Problem 10: "Given lap 7/8 inch, lead 1/4 inch, and cut-off at
    .8 stroke, to determine the eccentricity and angular advance" -- Problem 2,
    Art. 20, p. 20 (the valve circle through o, the lap point on the cut-off line and
    the lead point on the dead line).  In closed form: r sin(delta) = l + i and
    r sin(w_c + delta) = l, so sin(w_c + delta)/sin(delta) = l/(l + i), i.e.
    cot(delta) = (l/(l + i) - cos w_c) / sin w_c.  With cos w_c = -0.6, sin w_c = 0.8:
    cot(delta) = (7/9 + 0.6)/0.8 = 1.72222, delta = 30.141 deg, r = (l + i)/sin(delta)
    = 2.2405 in.  Exact; tolerance 1e-9."""
    l, i = 0.875, 0.25
    wc = math.acos(-0.6)
    delta = math.atan2(math.sin(wc), l / (l + i) - math.cos(wc))
    r = (l + i) / math.sin(delta)
    assert (math.degrees(delta), r) == pytest.approx((30.141, 2.2405), abs=1e-3)
    d = design_slide_valve(zeuner_base(), HARMONIC, cutoff=0.8, lead_m=i * IN, lap_m=l * IN)
    assert d.angular_advance_rad == pytest.approx(delta, abs=1e-10)
    assert d.eccentricity_m / IN == pytest.approx(r, abs=1e-9)
    assert d.lead_m[0] / IN == pytest.approx(i, abs=1e-9)
    assert d.zeuner["angular_advance_rad"] == pytest.approx(delta, abs=1e-10)


def test_problem_21_throw_lap_and_cutoff_art_19():
    """Spangler Ch. IV, Problem 21: a steam valve of a four-valve engine, "the cut-off
    is to take place at 3/4 stroke, with 1/2 lap.  If r = 1 3/4 inches" -- the advance
    that does it is Problem 1 (Art. 19, p. 19) run backwards: the lap is the chord of
    the valve circle on the cut-off line, l = r sin(w_c + delta), so
    delta = 180 deg - asin(l/r) - w_c with w_c = arccos(1 - 1.5) = 120 deg:
    delta = 60 - 16.602 = 43.398 deg, and the lead r sin(delta) - l = 0.7025 in.
    Exact; tolerance 1e-9."""
    r, l = 1.75, 0.5
    delta = math.pi - math.asin(l / r) - math.radians(120.0)
    assert math.degrees(delta) == pytest.approx(43.398, abs=1e-3)
    d = design_slide_valve(zeuner_base(), HARMONIC, cutoff=0.75, eccentricity_m=r * IN,
                           lap_m=l * IN)
    assert d.angular_advance_rad == pytest.approx(delta, abs=1e-10)
    assert d.lead_m[0] / IN == pytest.approx(r * math.sin(delta) - l, abs=1e-9)
    assert d.zeuner["angular_advance_rad"] == pytest.approx(delta, abs=1e-10)


def test_problem_22_unequal_laps_for_equal_cutoff_art_31():
    """Spangler Ch. V, Problem 22: "Given r = 2 3/8 inches, ... delta = 30 deg, stroke
    18 inches, connecting-rod 45 inches.  What must be the lap to cut-off at 14 inches
    on each stroke?  If the exhaust is to close at 16 inches, what must be the
    exhaust-lap on each stroke?" -- equalising by unequal laps, Art. 31, p. 34: each
    end's lap is the chord of its valve circle on its own crank line at cut-off.

    Closed form (R = 9, L = 45 in; crank angles from :func:`crank_at_piston`, x = r
    sin(theta + delta) with the eccentric rod infinite, as the problem gives none):
    head cut-off, piston 14 in out: cos = (40^2 - 45^2 + 9^2)/(2 40 9) = -0.47778,
    theta = 118.540 deg, lap_h = r sin(148.540 deg) = 1.2395 in.  Crank end cut-off 14 in
    along its stroke, the piston 4 in from the head end: cos = 556/900, theta = 360 -
    51.846 deg, lap_c = -x = 0.8838 in.  Exhaust closing at 16 in of the return stroke:
    the head end's at the piston 2 in from the head (cos = 760/936, theta = 324.288 deg),
    exhaust lap e_h = -x = 0.2364 in; the crank end's with the piston 16 in from the
    head (cos = -500/684, theta = 136.970 deg), e_c = x = 0.5355 in.  The head end's lead
    r sin(delta) - lap_h = -0.052 in is negative: the port opens after the dead point,
    as the notes on the book say of this problem (§7, case 1).  Exact; tolerance 1e-9 in.
    """
    R, L, r, delta = 9.0, 45.0, 2.375, math.radians(30.0)
    x = lambda th: r * math.sin(th + delta)  # noqa: E731
    th_ch = crank_at_piston(14.0, R, L)
    th_cc = 2 * math.pi - crank_at_piston(4.0, R, L)
    th_kh = 2 * math.pi - crank_at_piston(2.0, R, L)
    th_kc = crank_at_piston(16.0, R, L)
    want = {"lap": (x(th_ch), -x(th_cc)), "exhaust": (-x(th_kh), x(th_kc))}
    assert want["lap"] == pytest.approx((1.2395, 0.8838), abs=1e-4)
    assert want["exhaust"] == pytest.approx((0.2364, 0.5355), abs=1e-4)
    d = design_slide_valve(zeuner_base(), slider_crank(R, L), cutoff=14 / 18,
                           eccentricity_m=r * IN, angular_advance_rad=delta,
                           compression=2 / 18)
    assert [v / IN for v in d.lap_m] == pytest.approx(want["lap"], abs=1e-9)
    assert [v / IN for v in d.exhaust_lap_m] == pytest.approx(want["exhaust"], abs=1e-9)
    assert d.lead_m[0] / IN == pytest.approx(r * math.sin(delta) - want["lap"][0], abs=1e-9)
    assert d.lead_m[0] < 0.0 < d.lead_m[1]
    # Art. 31 and Question 46: for equal cut-offs the lap is greater at the head end
    assert d.lap_m[0] > d.lap_m[1]


def test_problem_3_angle_of_lead_port_and_overtravel_art_21():
    """Spangler's Problem 3 (Art. 21, p. 21): "Given the cut-off, angle of lead, width of
    port, and the overtravel, to determine eccentricity, lap, lead, and angular
    advance".  The port opens at the angle of lead lam before the dead point and closes
    at the cut-off w_c: asin(l/r) - delta = -lam and 180 deg - asin(l/r) - delta = w_c,
    so delta = (180 deg - w_c + lam)/2 -- the valve circle's diameter bisects the two
    crank lines, as the book constructs it; then r - l = port + overtravel (Art. 18)
    with l = r sin(w_c + delta).  For cut-off 3/4 (w_c = 120 deg with infinite rods),
    lam = 10 deg, port 1 1/4 in and overtravel 1/4 in: delta = 35 deg,
    r = 1.5/(1 - sin 155 deg) = 2.5979 in, l = 1.0979 in, lead r sin 35 deg - l =
    0.3922 in.  Exact; tolerance 1e-9."""
    lam, port, over = math.radians(10.0), 1.25, 0.25
    wc = math.radians(120.0)
    delta = (math.pi - wc + lam) / 2
    r = (port + over) / (1 - math.sin(wc + delta))
    lap = r - port - over
    assert (math.degrees(delta), r, lap) == pytest.approx((35.0, 2.5979, 1.0979), abs=1e-4)
    d = design_slide_valve(zeuner_base(port), HARMONIC, cutoff=0.75, lead_angle_rad=lam,
                           overtravel_m=over * IN)
    assert d.angular_advance_rad == pytest.approx(delta, abs=1e-10)
    assert d.eccentricity_m / IN == pytest.approx(r, abs=1e-9)
    assert d.lap_m[0] / IN == pytest.approx(lap, abs=1e-9)
    assert d.lead_m[0] / IN == pytest.approx(r * math.sin(delta) - lap, abs=1e-9)
    assert d.events["head"]["admission_deg"] == pytest.approx(350.0, abs=1e-6)
    # the closed form the solve starts from is the answer itself with infinite rods
    assert d.zeuner["angular_advance_rad"] == pytest.approx(delta, abs=1e-10)
    assert d.zeuner["eccentricity_m"] / IN == pytest.approx(r, abs=1e-9)
    assert d.events["head"]["overtravel_m"] / IN == pytest.approx(over, abs=1e-6)


def test_the_zeuner_closed_form_helper_refuses_what_cannot_be():
    """Art. 20 with lap 7/8 and lead 1/4: cot(delta) = (l/(l + i) - cos w_c)/sin w_c is
    positive only for w_c > arccos(7/9) = 38.94 deg; an earlier cut-off has no valve
    with an advance below 90 deg; a later one has."""
    l, i = 0.875 * IN, 0.25 * IN
    edge = math.acos(0.875 / 1.125)
    assert zeuner_valve(edge - math.radians(1.0), lap=l, lead=i) is None
    assert zeuner_valve(edge + math.radians(1.0), lap=l, lead=i) is not None


# ------------------------------------------------------------------ round trips
def _check_round_trip(d, asked: dict):
    """Every event asked, at every end asked, is the designed scene's within 0.05 deg;
    the events come from ``scene_events`` on the scene rebuilt from its TOML text."""
    ev = scene_events(d.scene)
    for end, want in asked.items():
        for key, deg in want.items():
            assert ev[end][key] is not None, (end, key)
            assert _diff(ev[end][key], deg) < EVENT_DEG, (end, key, ev[end][key], deg)
    return ev


def _asked_deg(scene, end, key, frac):
    """The crank angle [deg] of a piston fraction on the slider crank, closed form."""
    R = scene.engine.stroke_m / 2
    L = scene.engine.connecting_rod_m
    S = 2 * R
    if key in ("cutoff_deg", "release_deg"):          # outstroke of that end
        if end == "head":
            return math.degrees(crank_at_piston(frac * S, R, L))
        return 360.0 - math.degrees(crank_at_piston((1 - frac) * S, R, L))
    if end == "head":                                 # compression: its return stroke
        return 360.0 - math.degrees(crank_at_piston(frac * S, R, L))
    return math.degrees(crank_at_piston((1 - frac) * S, R, L))


def test_round_trip_equal_cutoffs_with_finite_rods(tmp_path):
    """The default engine (rod 5 cranks, eccentric rod 60 in): cut-off 0.6 and release
    0.9 at both ends, lead 1/4 in and opening 1 1/4 in at the head end.  The design
    written as a scene, read back from its file, gives those events within 0.05 deg of
    the crank angles the slider crank puts them at (closed form), the head lead and
    greatest opening as asked (1e-9 in: the lead is exact, the opening is the valve's
    own extreme, derived in the module), and unequal laps with the head lap greater
    (Art. 31)."""
    sc = make_scene()
    d = design(sc, cutoff=0.6, lead="0.25 in", max_opening="1.25 in", release=0.9)
    asked = {end: {k: _asked_deg(sc, end, k, f) for k, f in (("cutoff_deg", 0.6),
                                                              ("release_deg", 0.9))}
             for end in ("head", "crank")}
    _check_round_trip(d, asked)
    assert d.valve.lead_m[0] / IN == pytest.approx(0.25, abs=1e-9)
    assert d.valve.max_opening_m[0] / IN == pytest.approx(1.25, abs=1e-9)
    ev = scene_events(d.scene)
    # the scene written: eccentricity and lap to 0.001 in (half a thou each at most)
    assert ev["head"]["max_port_opening_m"] / IN == pytest.approx(1.25, abs=1e-3)
    assert d.valve.lap_m[0] > d.valve.lap_m[1]
    # the finite rods matter: the infinite-rod valve would miss the crank end's cut-off
    assert abs(d.valve.lap_m[1] - d.valve.zeuner["lap_m"]) > 0.05 * IN
    # the written file is the scene
    files = d.write(tmp_path)
    again = load_scene(files["scene"])
    _check_round_trip(type(d)(scene=again, text=d.text, valve=d.valve, events=d.events,
                              base=d.base), asked)
    assert files["zeuner"].stat().st_size > 10_000 and files["bilgram"].stat().st_size > 10_000


def test_round_trip_equal_laps_gives_equal_leads_and_unequal_cutoffs():
    """equalise = "laps": equal laps and exhaust laps; the head end cuts off at 0.5 and
    compresses at 0.1 as asked (within 0.05 deg), the two leads are equal (the valve
    set for equal lead: Marks Art. 96), and the crank end's cut-off is the shorter --
    Spangler Art. 32, Question 47: "if a plain slide-valve is directly connected ... and
    is set for equal lead, on which end is the cut-off the shorter?"."""
    sc = make_scene()
    d = design(sc, cutoff=0.5, lead="0.125 in", max_opening="1.0 in", compression=0.1,
               equalise="laps")
    ev = _check_round_trip(d, {"head": {"cutoff_deg": _asked_deg(sc, "head", "cutoff_deg", 0.5),
                                        "compression_deg": _asked_deg(sc, "head",
                                                                      "compression_deg", 0.1)}})
    assert d.valve.lap_m[0] == d.valve.lap_m[1]
    assert d.valve.exhaust_lap_m[0] == d.valve.exhaust_lap_m[1]
    assert ev["head"]["lead_m"] == pytest.approx(ev["crank"]["lead_m"], abs=1e-9)
    assert ev["crank"]["cutoff_frac"] < ev["head"]["cutoff_frac"] - 0.05


@pytest.mark.parametrize("gear", [
    {"connection": "reverse_lever"},
    {"steam": "inside"},
    {"setting": "mid_travel"},
    {"eccentric_rod": "30 in"},
])
def test_round_trip_other_connections_and_rods(gear):
    """A reverse lever, steam taken inside (the eccentric's shortfall then moves the
    valve the other way, Spangler Arts. 24, 29), a valve set for mid travel, a short
    eccentric rod: different cut-offs per end (0.55 head, 0.6 crank) and release 0.92,
    each within 0.05 deg."""
    sc = make_scene(valve_gear=gear)
    d = design(sc, cutoff=0.55, cutoff_crank=0.6, lead="0.2 in", max_opening="1.1 in",
               release=0.92)
    _check_round_trip(d, {"head": {"cutoff_deg": _asked_deg(sc, "head", "cutoff_deg", 0.55),
                                   "release_deg": _asked_deg(sc, "head", "release_deg", 0.92)},
                          "crank": {"cutoff_deg": _asked_deg(sc, "crank", "cutoff_deg", 0.6),
                                    "release_deg": _asked_deg(sc, "crank", "release_deg", 0.92)}})


def test_round_trip_reference_end_crank_and_si_units():
    """The lead and opening held at the crank end, and a scene in SI: the crank end's
    lead is the 5 mm asked (1e-9 m) and its greatest opening 25 mm; the designed keys
    written in mm (the keys kept from the scene as they were)."""
    sc = make_scene(output={"units": "SI", "dir": "out"})
    d = design(sc, cutoff=0.7, lead="5 mm", max_opening="25 mm", exhaust_lap="2 mm",
               reference_end="crank")
    _check_round_trip(d, {end: {"cutoff_deg": _asked_deg(sc, end, "cutoff_deg", 0.7)}
                          for end in ("head", "crank")})
    assert d.valve.lead_m[1] == pytest.approx(0.005, abs=1e-9)
    assert d.valve.max_opening_m[1] == pytest.approx(0.025, abs=1e-9)
    assert d.valve.exhaust_lap_m == pytest.approx((0.002, 0.002), abs=1e-12)
    designed = [ln for ln in d.text.splitlines()
                if ln.startswith(("eccentricity", "lap", "exhaust_lap"))]
    assert len(designed) == 3 and all(ln.endswith(" mm\"]") or ln.endswith(" mm\"")
                                      for ln in designed), designed


def test_round_trip_angle_of_lead_and_overtravel_with_finite_rods():
    """Art. 21's data on the default engine's rods: the head end admits 6 deg before its
    dead centre and both ends cut off at 0.7 (within 0.05 deg), and the head port is
    overrun by the 0.2 in asked (the events' overtravel, to 1e-3 in: the extreme of the
    finite-rod valve is exact, the events sample it every 0.05 deg, and the scene
    written rounds the eccentricity and the lap to 0.001 in, half a thou each at
    most)."""
    sc = make_scene()
    d = design(sc, cutoff=0.7, lead_angle="6 deg", overtravel="0.2 in")
    ev = _check_round_trip(d, {"head": {"admission_deg": 354.0,
                                        "cutoff_deg": _asked_deg(sc, "head", "cutoff_deg", 0.7)},
                               "crank": {"cutoff_deg": _asked_deg(sc, "crank", "cutoff_deg", 0.7)}})
    assert ev["head"]["overtravel_m"] / IN == pytest.approx(0.2, abs=1e-3)


def test_cli_design_then_events_then_run(tmp_path, capsys):
    """Through the command line: ``corliss design`` writes the scene, ``corliss events``
    on it prints the events asked (within 0.05 deg), and ``corliss run`` runs it."""
    out = tmp_path / "d"
    assert cli.main(["design", "--cutoff", "0.65", "--lead", "0.25in", "--max-opening",
                     "1.25in", "--compression", "0.08", "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "eccentricity" in printed and "default.design.toml" in printed
    assert cli.main(["events", str(out / "default.design.toml"), "--json"]) == 0
    ev = json.loads(capsys.readouterr().out)
    sc = make_scene()
    for end in ("head", "crank"):
        assert _diff(ev[end]["cutoff_deg"], _asked_deg(sc, end, "cutoff_deg", 0.65)) < EVENT_DEG
        assert _diff(ev[end]["compression_deg"],
                     _asked_deg(sc, end, "compression_deg", 0.08)) < EVENT_DEG
    assert cli.main(["run", str(out / "default.design.toml"), "--out", str(tmp_path / "run"),
                     "--json", "--no-plots", "--cycles", "2", "--fidelity", "fast"]) == 0
    summary = json.loads(capsys.readouterr().out)
    # the scene written is rounded as a drawing is (laps and throw to 0.001 in, the
    # advance to 0.01 deg): near this cut-off the valve moves some 2.9 in per radian of
    # crank against the piston's 0.48 of its stroke, so a thou of valve is 1.7e-4 of
    # the stroke, and the advance's 0.005 deg 4e-5
    assert summary["events"]["head"]["cutoff_frac"] == pytest.approx(0.65, abs=5e-4)
    assert summary["indicated_power_hp"] > 0.0


@pytest.mark.parametrize("name, cutoff", [
    ("hinkley-stephenson-link", 0.35),
    ("walschaerts-locomotive", 0.5),
    ("erie-shaft-governor", 0.3),
    ("corliss-trip-gear", 0.25),
])
def test_setting_for_a_cutoff_round_trip(name, cutoff, tmp_path):
    """Link motion (the block), radial gear (the notch), shaft governor (its
    position), Corliss gear (the cam): the setting found puts the head end's cut-off
    within 0.05 deg of the crank angle the scene's slider crank gives the fraction
    asked, in the scene rebuilt from the TOML written; the gear's linkage is kept."""
    sc = load_scene(find_scene(name))
    d = design(sc, cutoff=cutoff)
    want = _asked_deg(sc, "head", "cutoff_deg", cutoff) if sc.run.has("rod_angularity") else \
        math.degrees(math.acos(1 - 2 * cutoff))
    _check_round_trip(d, {"head": {"cutoff_deg": want}})
    lo, hi = build_gear(sc).setting_range
    assert lo <= d.valve.setting <= hi
    files = d.write(tmp_path)
    assert files["scene"].exists()


def test_setting_for_the_mean_cutoff_of_both_ends():
    """``end="mean"``: the Stephenson link's two ends cut off unequally (the connecting
    rod's angularity, Spangler Art. 63); the block found puts the mean of the two
    fractions at 0.4 (to 1e-8, Brent's method closing the setting to 1e-10), with the
    head end's later than the crank end's."""
    d = design("hinkley-stephenson-link", cutoff=0.4, end="mean")
    h, c = (d.exact_events[e]["cutoff_frac"] for e in ("head", "crank"))
    assert (h + c) / 2 == pytest.approx(0.4, abs=1e-8)
    assert h > c


# ------------------------------------------------------------------ what cannot be
def test_cutoff_earlier_than_the_valve_allows_names_cutoff():
    """Art. 22 with lead 1/4 in and opening 1 1/4 in (infinite rods): l = 0 at the
    latest cut-off, where sin(delta) = i/p, w_c = 180 deg - asin(0.2), i.e. 0.98990 of
    the stroke; later needs a negative lap.  The error names the key and gives the
    range, whose upper end is that closed form to the scan's step of 0.005."""
    with pytest.raises(InputError) as e:
        design_slide_valve(zeuner_base(), HARMONIC, cutoff=0.995, lead_m=0.25 * IN,
                           max_opening_m=1.25 * IN)
    assert e.value.key == "cutoff" and e.value.value == 0.995
    top = float(e.value.expected.split(" to ")[1].split()[0])
    assert top == pytest.approx((1 + math.cos(math.asin(0.2))) / 2, abs=0.005)


def test_finite_rods_bound_the_earliest_cutoff():
    """With a 60 in eccentric rod the throw that an early cut-off needs (r = p/(1 - s),
    growing without bound, Art. 22) must stay below the rod: cut-off 0.02 is refused,
    with the range of cut-offs the rods allow."""
    with pytest.raises(InputError) as e:
        design(make_scene(), cutoff=0.02, lead="0.25 in", max_opening="1.25 in")
    assert e.value.key == "cutoff" and "from 0." in e.value.expected


def test_finite_rods_late_cutoff_range_is_true():
    """Equal cut-offs near the end of the stroke with the default engine's rods: the
    crank end's lap (Art. 31) reaches zero first, so the latest cut-off both ends can
    share is earlier than the head end alone allows.  The error names the cut-off and
    states the range, and the range is true: its last value designs, with laps >= 0,
    and a step past it (0.005) is refused."""
    kw = dict(lead="0.25 in", max_opening="1.25 in")
    with pytest.raises(InputError) as e:
        design(make_scene(), cutoff=0.995, **kw)
    assert e.value.key == "cutoff"
    top = float(e.value.expected.split(" to ")[1].split()[0])
    d = design(make_scene(), cutoff=top, **kw)
    assert min(d.valve.lap_m) >= 0.0
    with pytest.raises(InputError) as e:
        design(make_scene(), cutoff=top + 0.005, **kw)
    assert "crank end would need a negative steam lap" in e.value.expected


@pytest.mark.parametrize("kwargs, key", [
    (dict(cutoff=0.6, lead="0.25 in", max_opening="2 in"), "max_opening"),   # port 1.25 in
    (dict(cutoff=0.6, lead="1 in", max_opening="1 in"), "lead"),
    (dict(cutoff=1.2, lead="0.25 in", max_opening="1 in"), "cutoff"),
    (dict(cutoff=0.6, lead="0.25 in", max_opening="1 in", lap="1 in"), "lead, max_opening, lap"),
    (dict(cutoff=0.6, lead="0.25 in", max_opening="1 in", release=0.4), "release"),
    (dict(cutoff=0.6, lead="0.25 in", max_opening="1 in", compression=0.9), "compression"),
    (dict(cutoff=0.6, lead="0.25 in", max_opening="1 in", release=0.9, compression=0.1),
     "compression"),
    (dict(cutoff=0.6, cutoff_crank=0.62, lead="0.25 in", max_opening="1 in",
          equalise="laps"), "cutoff_crank"),
    (dict(cutoff=0.6, lap="-0.1 in", lead="0.25 in"), "lap"),
    (dict(cutoff=0.6, lead="0.25 in", max_opening="1 in", overtravel="0.1 in"), "overtravel"),
    (dict(cutoff=0.6, lead_angle="5 deg", angular_advance="30 deg"), "lead_angle"),
])
def test_impossible_designs_name_their_key(kwargs, key):
    """Each design that cannot exist says which event: an opening wider than the
    1.25 in port, a lead no less than the opening, a cut-off outside the stroke, three
    valve quantities (two fix the valve with the cut-off, Arts. 19-22), a release before
    the cut-off, a compression before the valve turns back (with advance near 35 deg at
    the head end the valve turns back at about 235 deg, so the exhaust cannot close with the
    piston still 0.9 of the stroke from the head),
    both release and compression at one end (one exhaust lap, one event, Art. 31), a
    crank-end cut-off with equal laps, a negative lap asked, an opening and an
    overtravel (one is the other plus the port, Art. 18), both the angle of lead and the
    advance (with the cut-off each fixes the other, Art. 21)."""
    with pytest.raises(InputError) as e:
        design(make_scene(), **kwargs)
    assert e.value.key == key


def test_a_gears_cutoff_out_of_its_range_names_cutoff_and_the_range():
    """The Stephenson link in full gear cuts off at its latest; 0.98 is beyond it: the
    error names the cut-off and the range over the forward settings.  A lead asked of a
    gear with a setting is refused too: its linkage is kept, only the setting found."""
    sc = load_scene(find_scene("hinkley-stephenson-link"))
    with pytest.raises(InputError) as e:
        design(sc, cutoff=0.98)
    assert e.value.key == "cutoff" and "over its settings" in e.value.expected
    with pytest.raises(InputError) as e:
        design(sc, cutoff=0.5, lead="0.25 in")
    assert e.value.key == "lead"


def test_the_package_front_door_has_design():
    """``corliss.design`` is the same function, with the command's arguments."""
    import corliss
    assert corliss.design is design
    d = corliss.design(cutoff=0.8, lead="0.25 in", max_opening="1.25 in")
    assert d.exact_events["head"]["cutoff_frac"] == pytest.approx(0.8, abs=1e-9)


def test_a_compound_or_no_valve_data_is_refused():
    """A compound's two gears are not designed; a slide valve asked only its cut-off has
    one condition of the three a plain valve needs (Arts. 19-22)."""
    with pytest.raises(InputError) as e:
        design("marks-compound-9-14x14", cutoff=0.4)
    assert e.value.key == "scene"
    with pytest.raises(InputError) as e:
        design(make_scene(), cutoff=0.4)
    assert e.value.key == "lead" and "exactly two" in e.value.expected


def test_cli_bad_design_exits_2_and_writes_nothing(tmp_path, capsys):
    """A user's mistake: exit code 2, a message naming the key, no folder made."""
    out = tmp_path / "none"
    assert cli.main(["design", "--cutoff", "0.6", "--lead", "0.25in", "--max-opening",
                     "3in", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "max_opening" in err and "port" in err and "Traceback" not in err
    assert not out.exists()


def test_the_readmes_design_warns_of_the_end_it_was_not_asked_for(tmp_path, capsys):
    """``corliss design --cutoff 0.6 --lead 0.25in --max-opening 1.25in --release 0.9``
    on the default engine (1.25 in ports, a 60 in rod on a 24 in stroke): equal cut-offs
    with the rod's angularity give the crank end a lap of its own, and with it a lead of
    some 7/8 in and a greatest opening near 2 in, past its 1.25 in port.  The design
    says so for that end, in its JSON and its printed account."""
    import json

    from corliss.cli.commands import main
    argv = ["design", "--cutoff", "0.6", "--lead", "0.25in", "--max-opening", "1.25in",
            "--release", "0.9", "--out", str(tmp_path)]
    assert main(argv + ["--json"]) == 0
    warnings = json.loads(capsys.readouterr().out)["warnings"]
    assert any(w.startswith("crank end: lead") for w in warnings), warnings
    assert any(w.startswith("crank end: greatest opening") and "1.25 in port" in w
               for w in warnings), warnings
    assert not any(w.startswith("head end") for w in warnings)   # the end asked for
    assert main(argv) == 0
    assert "WARNING          crank end: lead" in capsys.readouterr().out


def _warned_length_in(warning: str, before: str) -> float:
    """The length [in] a warning quotes right after ``before`` ("greatest opening ")."""
    return float(warning.split(before, 1)[1].split(" in", 1)[0])


def test_a_gears_setting_warns_of_the_other_ends_cutoff_lead_and_opening():
    """A gear with a setting is set for the cut-off asked at one end; its linkage gives
    the other end its own cut-off, lead and opening, which the design now checks as it
    checks a slide valve's other end.

    Joy's radial gear (the bundled locomotive, 1 in ports) set for 0.35 at the head end
    cuts off the crank end near 0.43 and drives the crank port's edge some 3/8 in past
    its 1 in width: the crank end is warned of its cut-off (more than 0.067 of the
    stroke, Peabody's greatest inequality from the rod's angularity alone, from the one
    asked) and of its opening (more than a quarter past the port, the slide valve's
    rule); the head end, asked, is not.  The numbers quoted are those of the written
    scene's events (what ``corliss events`` prints) to the warning's three figures and
    the setting's rounding to 1e-4 (0.01 in, 0.002 of the stroke).  Porter-Allen's gear
    at 0.35 gives the crank end a lead under half the head end's: warned as a slide
    valve's is."""
    d = design("joy-radial-gear", cutoff=0.35)
    crank = d.events["crank"]
    greatest_in = (crank["max_port_opening_m"] + crank["overtravel_m"]) / IN
    assert greatest_in > 1.25 * 1.0 and crank["cutoff_frac"] - 0.35 > 0.067   # the premise
    cut = [w for w in d.warnings if w.startswith("crank end: cut-off")]
    assert len(cut) == 1 and "0.350 asked at the head end" in cut[0], d.warnings
    assert float(cut[0].split("cut-off ", 1)[1].split(" ", 1)[0]) == pytest.approx(
        crank["cutoff_frac"], abs=2e-3)
    opening = [w for w in d.warnings if w.startswith("crank end: greatest opening")]
    assert len(opening) == 1 and "on a 1 in port" in opening[0], d.warnings
    assert _warned_length_in(opening[0], "greatest opening ") == pytest.approx(greatest_in,
                                                                               abs=0.01)
    assert not any(w.startswith("head end") for w in d.warnings), d.warnings

    pa = design("porter-allen-engine", cutoff=0.35)
    head, crank = pa.events["head"]["lead_m"], pa.events["crank"]["lead_m"]
    assert 0.0 < crank < 0.5 * head                                                # the premise
    lead = [w for w in pa.warnings if w.startswith("crank end: lead")]
    assert len(lead) == 1 and "at the head end" in lead[0], pa.warnings
    assert _warned_length_in(lead[0], "lead ") == pytest.approx(crank / IN, abs=0.01)


def test_a_gears_setting_within_the_rules_is_not_warned_of():
    """The Stephenson link of the Hinkley locomotive set for 0.35: the crank end cuts off
    at 0.29 (the rod's angularity, within Peabody's 0.067), the leads are equal and
    the greatest opening (0.43 in) is well inside the 1.25 in port: no warning of an
    end."""
    d = design("hinkley-stephenson-link", cutoff=0.35)
    assert abs(d.events["crank"]["cutoff_frac"] - 0.35) < 0.067                    # the premise
    assert not any(w.startswith(("head end", "crank end")) for w in d.warnings), d.warnings


def test_a_refusal_quotes_lengths_in_the_scenes_units():
    """``design``'s messages quote lengths in the scene's unit system: asked for a 3 in
    opening on the default engine's 1.25 in port, an SI scene is told of 76.2 mm and a
    31.75 mm port (25.4 mm to the inch, exact), an inch scene of 3 in and 1.25 in; an
    inch scene written in SI (``units_system="SI"``, ``--units SI``) is told in mm.  A
    refusal from the solve (a cut-off so early that the crank end would need a negative
    lap) names its lengths in mm too."""
    si = make_scene(output={"units": "SI", "dir": "out"})
    with pytest.raises(InputError) as e:
        design(si, cutoff=0.6, lead="0.25 in", max_opening="3 in")
    assert e.value.key == "max_opening"
    assert str(e.value.value) == "76.2 mm" and "(31.75 mm)" in e.value.expected, str(e.value)
    with pytest.raises(InputError) as e:
        design(make_scene(), cutoff=0.6, lead="0.25 in", max_opening="3 in",
               units_system="SI")
    assert str(e.value.value) == "76.2 mm" and "(31.75 mm)" in e.value.expected, str(e.value)
    with pytest.raises(InputError) as e:
        design(make_scene(), cutoff=0.6, lead="0.25 in", max_opening="3 in")
    assert str(e.value.value) == "3 in" and "(1.25 in)" in e.value.expected, str(e.value)
    with pytest.raises(InputError) as e:
        design(si, cutoff=0.05, lead="6 mm", max_opening="25 mm")
    assert " mm" in str(e.value) and " in)" not in str(e.value) and \
        " in," not in str(e.value), str(e.value)
