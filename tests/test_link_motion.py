"""Link motions in Zeuner's form, against the identities Spangler proves for them."""

import math

import numpy as np
import pytest

from corliss.errors import InputError
from corliss.valves.link_motion import LinkMotionSpec

from conftest import make_scene

IN = 0.0254
R, D, G, C = 2.5 * IN, math.radians(20), 50 * IN, 5 * IN


def spec(kind, u, k=0.5):
    return LinkMotionSpec(kind, R, D, G, C, u, (IN, IN), (0.0, 0.0), 1.0 * IN, 10 * IN,
                          allen_ratio=k)


U = np.linspace(-C, C, 11)


def test_stephenson_at_full_gear_is_a_single_eccentric():
    """Spangler Art. 46: at u = c the open-rod link gives A_c = r cos d, B_c = r sin d,
    the motion of the forward eccentric alone; crossed rods at u = -c (raised link,
    Art. 55) give the same."""
    for kind, u in (("stephenson_open", C), ("stephenson_crossed", -C)):
        Cc, S = spec(kind, u).coefficients()
        assert Cc == pytest.approx(R * math.sin(D), rel=1e-12)
        assert S == pytest.approx(R * math.cos(D), rel=1e-12)


def test_allen_link_spans_stephenson_and_gooch():
    """Spangler Art. 73 (as printed, with u the block's whole offset and u1 the link's
    share): u1 = u gives Stephenson's open rods, u1 = 0 Gooch's fixed link."""
    for u in U:
        assert spec("allen", u, 1.0).coefficients() == pytest.approx(
            spec("stephenson_open", u).coefficients(), rel=1e-12, abs=1e-15)
        assert spec("allen", u, 0.0).coefficients() == pytest.approx(
            spec("gooch", u).coefficients(), rel=1e-12, abs=1e-15)


def test_lead_constant_for_gooch_rising_for_open_falling_for_crossed():
    """Art. 66: the Gooch lead is the same at every notch.  Art. 55: from full gear to
    mid gear the lead grows with open rods and shrinks with crossed rods (by
    r (c^2 - u^2) cos d / (c g) either way)."""
    lap = IN
    lead = {k: np.array([spec(k, u).coefficients()[0] - lap for u in U[5:]])  # u from 0 to c
            for k in ("gooch", "stephenson_open", "stephenson_crossed")}
    assert np.ptp(lead["gooch"]) < 1e-15
    assert np.all(np.diff(lead["stephenson_open"]) < 0)        # falls from mid to full gear
    assert np.all(np.diff(lead["stephenson_crossed"]) > 0)
    rise = lead["stephenson_open"][0] - lead["stephenson_open"][-1]
    assert rise == pytest.approx(R * C * math.cos(D) / G, rel=1e-12)


def test_mid_gear_is_symmetric_about_the_dead_point():
    """Art. 46: at u = 0 the valve moves as B_0 cos(theta), so admission and cut-off lie
    symmetrically about the dead centre and the engine does no net work."""
    from corliss.valves.events import end_events
    from corliss.valves.link_motion import LinkMotion
    ev = end_events(LinkMotion(spec("stephenson_open", 0.0)), "head", lambda t: t / math.pi)
    assert (ev["admission_deg"] - 360.0) == pytest.approx(-ev["cutoff_deg"], abs=1e-6)


def test_link_motion_scene_runs_and_checks_its_block():
    sc = make_scene(valve_gear={"type": "link_motion", "link": "stephenson_open",
                                "eccentricity": "3 in", "angular_advance": "25 deg",
                                "eccentric_rod": "60 in", "half_link": "6 in", "block": "4 in",
                                "lead": None, "connection": None, "steam": None})
    import corliss
    s = corliss.simulate(sc.with_fidelity("fast")).summary
    assert s["indicated_power_W"] > 0
    with pytest.raises(InputError, match="valve_gear.block"):
        make_scene(valve_gear={"type": "link_motion", "link": "gooch", "eccentricity": "3 in",
                               "angular_advance": "25 deg", "eccentric_rod": "60 in",
                               "half_link": "6 in", "block": "7 in", "lead": None,
                               "connection": None, "steam": None})


# Peabody, Link Motion (thesis, 1877), its Table of Results, Zeuner's solution for a
# Hinkley Locomotive Works link: r = 2 3/4 in, eccentric rods 54 in, half link 6 in, lap
# 7/8 in, full-gear lead 1/16 in, no inside lap.  Per grade w = (grade/10) c: outside lead
# [in] (col. 3), crank angle at cut-off (col. 8), piston at cut-off as a harmonic fraction
# of stroke (col. 9).  The thesis's grade-2 cut-off (72 deg 11') and its fraction (.347)
# are wrong (its own formulas give 71 deg 31' and .3415); so is grade 4's cut-off
# (97 deg 27' for 97 deg 20', following its slip in col. 5), and grade 9's (136 deg 38'
# for 136 deg 40'); those rows carry the corrected values.
PEABODY = {  # grade: (lead, cut-off [deg, min], fraction)
    0: (0.350, (44, 24), 0.143), 1: (0.347, (57, 28), 0.231), 2: (0.338, (71, 31), 0.3415),
    3: (0.324, (85, 7), 0.457), 4: (0.304, (97, 20), 0.564), 5: (0.278, (107, 55), 0.654),
    6: (0.246, (116, 56), 0.726), 7: (0.209, (124, 34), 0.784), 8: (0.166, (131, 5), 0.829),
    9: (0.117, (136, 40), 0.863), 10: (0.063, (141, 31), 0.891),
}


@pytest.mark.parametrize("grade", sorted(PEABODY))
def test_peabody_table_of_results(grade):
    """Tolerance: the thesis's precision, 0.001 in and 0.001 of stroke (2 in the last
    place where it rounds a recomputed .0005), and 1.5 arc-minutes."""
    from corliss.valves.events import end_events
    from corliss.valves.link_motion import LinkMotion
    r, c, lap = 2.75 * IN, 6 * IN, 0.875 * IN
    delta = math.asin((0.875 + 0.0625) / 2.75)
    sp = LinkMotionSpec("stephenson_open", r, delta, 54 * IN, c, grade / 10 * c, (lap, lap),
                        (0.0, 0.0), 1.25 * IN, 10 * IN)
    harmonic = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
    ev = end_events(LinkMotion(sp), "head", harmonic)
    lead, (deg, minutes), frac = PEABODY[grade]
    assert ev["lead_m"] / IN == pytest.approx(lead, abs=1.5e-3)
    assert ev["cutoff_deg"] == pytest.approx(deg + minutes / 60, abs=1.5 / 60)
    assert ev["cutoff_frac"] == pytest.approx(frac, abs=1.5e-3)


def exact(kind, u_in, k=1.0, hanger=True):
    return LinkMotion(LinkMotionSpec(kind, 2.75 * IN, math.asin(0.9375 / 2.75), 54 * IN * k,
                                     6 * IN * k, u_in * IN * k, (0.875 * IN,) * 2, (0.0, 0.0),
                                     1.25 * IN, 10 * IN, motion="exact",
                                     hanger_m=24 * IN * k if hanger else None))


from corliss.valves.link_motion import LinkMotion  # noqa: E402


@pytest.mark.parametrize("kind,u", [("stephenson_open", 3.0), ("stephenson_crossed", -3.0)])
def test_exact_linkage_converges_to_zeuner_as_the_gear_grows(kind, u):
    """Zeuner's form neglects the rods' obliquity beyond first order, the hanger's arc
    and the slip of the block (Spangler Art. 45), errors of order r^2/g and r^2/c
    (Marks Art. 96, eqs. 232 and 249).  Growing the rods, link and hanger together by k
    (r fixed), the exact linkage's departure from Zeuner's form must fall about as
    1/k: by at least a third per doubling, to under a quarter of the k = 1 departure at
    k = 4 (about 0.2 in at k = 1 for this locomotive link).  The leads agree
    closely at every size: the departures vanish at the dead points."""
    th = np.linspace(0, 2 * math.pi, 361)
    errs = []
    for k in (1.0, 2.0, 4.0):
        g = exact(kind, u, k)
        errs.append(np.max(np.abs(g.travel(th) - g.zeuner_travel(th))) / IN)
        lead = g.travel(np.array([0.0]))[0] - g.zeuner_travel(np.array([0.0]))[0]
        assert abs(lead) / IN < 0.003
    assert errs[1] < 0.67 * errs[0] and errs[2] < 0.67 * errs[1]
    assert errs[2] < 0.25 * errs[0]


def test_exact_link_cuts_off_unequally_at_the_two_ends():
    """Spangler Art. 63: with a real link the crank positions at cut-off are not 180 deg
    apart, as they are in Zeuner's form."""
    from corliss.valves.events import end_events
    g = exact("stephenson_open", 3.0)
    frac = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
    head, crank = (end_events(g, e, frac) for e in ("head", "crank"))
    gap = (crank["cutoff_deg"] - head["cutoff_deg"]) % 360
    assert abs(gap - 180.0) > 0.5
    z = LinkMotion(LinkMotionSpec("stephenson_open", 2.75 * IN, math.asin(0.9375 / 2.75),
                                  54 * IN, 6 * IN, 3 * IN, (0.875 * IN,) * 2, (0.0, 0.0),
                                  1.25 * IN, 10 * IN))
    zh, zc = (end_events(z, e, frac) for e in ("head", "crank"))
    assert (zc["cutoff_deg"] - zh["cutoff_deg"]) % 360 == pytest.approx(180.0, abs=1e-6)


# ------------------------------------------------- exact Gooch and Allen linkages

def exact_ga(kind, u_in, k=1.0, ratio=None, g1_in=40.0):
    """The Hinkley link's eccentrics, rods, link and valve as a Gooch or Allen gear with
    a 40 in radius rod, the linkage grown by k (eccentricity fixed)."""
    from corliss.valves.link_motion import allen_book_ratio
    if ratio is None:
        ratio = allen_book_ratio(54.0, g1_in)
    return LinkMotion(LinkMotionSpec(kind, 2.75 * IN, math.asin(0.9375 / 2.75), 54 * IN * k,
                                     6 * IN * k, u_in * IN * k, (0.875 * IN,) * 2, (0.0, 0.0),
                                     1.25 * IN, 10 * IN, allen_ratio=ratio, motion="exact",
                                     radius_rod_m=g1_in * IN * k))


@pytest.mark.parametrize("kind,u", [("gooch", 3.0), ("gooch", -4.5), ("allen", 3.0),
                                    ("allen", 0.0)])
def test_exact_gooch_and_allen_converge_to_zeuner_as_the_gear_grows(kind, u):
    """As for the Stephenson: Zeuner's forms (Arts. 65, 73) drop terms of order r^2/g
    and r^2/c; growing rods, link and radius rod by k, the departure must fall by at
    least a third per doubling and under 0.3 of its k = 1 size at k = 4 (it is
    0.1-0.35 in at k = 1).  The Allen link has the rocker proportions of Art. 73."""
    th = np.linspace(0, 2 * math.pi, 361)
    errs = []
    for k in (1.0, 2.0, 4.0):
        g = exact_ga(kind, u, k)
        errs.append(np.max(np.abs(g.travel(th) - g.zeuner_travel(th))) / IN)
    assert errs[1] < 0.67 * errs[0] and errs[2] < 0.67 * errs[1]
    assert errs[2] < 0.3 * errs[0]


def test_exact_gooch_lead_is_constant():
    """Art. 66-67: the Gooch lead is the same at every setting because the link is an
    arc about the valve-stem end with the crank on a dead point (link radius = radius
    rod).  In the exact linkage, hung at its middle on the line of stroke, both dead
    points put the link square and centred, so the lead does not change with the
    block at all: the same to rounding (1e-12 in) from full gear ahead to full gear
    astern, at every size.  Its value differs from Zeuner's r(sin d + (c/g) cos d) - l
    by the rods' obliquity: the exact first-order term is c/sqrt(g^2 - c^2) for the
    book's sin(gamma) = c/g (cos gamma = 1), which accounts for all but 0.0004 in of the
    0.0021 in difference at k = 1 (the rest, of order r^2/g, falls with k)."""
    d = math.asin(0.9375 / 2.75)
    for k in (1.0, 4.0):
        leads = []
        for u in np.linspace(-6.0, 6.0, 9):
            x = exact_ga("gooch", u, k).travel(np.array([0.0, math.pi])) / IN
            leads += [x[0] - 0.875, -x[1] - 0.875]
        assert np.ptp(leads) < 1e-12
        c, g = 6.0 * k, 54.0 * k
        tan_form = 2.75 * (math.sin(d) + c / math.sqrt(g * g - c * c) * math.cos(d)) - 0.875
        zeuner = 2.75 * (math.sin(d) + c / g * math.cos(d)) - 0.875
        assert abs(leads[0] - zeuner) > 0.0015
        assert abs(leads[0] - tan_form) < (0.0005 if k == 1.0 else 0.0001)


def test_allen_rocker_ratio_of_art_73_keeps_the_valve_centred():
    """Derived here: lifting the straight link u1 = k u pulls the block towards the
    shaft, over a turn, by (u1^2 + c^2 - 2 u u1)/(2 g) and dropping the radius rod's end
    u - u1 pulls the stem by (u - u1)^2/(2 g1); against full gear (u = c) the valve's
    central position moves by D = D(u) - D(c), so the leads of the two ends split by
    2 |D|.  At k = 0.5 and mid gear that is 0.275 in for the Hinkley link with a 40 in
    radius rod, which the exact linkage reproduces within 5 % (terms of order c^4/g^3).
    With Art. 73's proportions, u1 = u/(1 + (g1/g)(1 + sqrt(1 + g/g1))) (0.293 u for
    equal rods), D vanishes for every u: the split falls to under 2 % of it."""
    from corliss.valves.link_motion import allen_book_ratio
    assert allen_book_ratio(1.0, 1.0) == pytest.approx(1 / (2 + math.sqrt(2)), rel=1e-15)
    g, g1, c = 54.0, 40.0, 6.0

    def D(u, k):
        u1 = k * u
        return -(u1 * u1 + c * c - 2 * u * u1) / (2 * g) - (u - u1) ** 2 / (2 * g1)

    def split(ratio):
        x = exact_ga("allen", 0.0, ratio=ratio).travel(np.array([0.0, math.pi])) / IN
        return abs((x[0] - 0.875) - (-x[1] - 0.875))

    predicted = 2 * abs(D(0.0, 0.5) - D(c, 0.5))
    assert predicted == pytest.approx(0.275, abs=0.001)
    assert split(0.5) == pytest.approx(predicted, rel=0.05)
    assert split(allen_book_ratio(g, g1)) < 0.02 * predicted


def test_exact_gooch_and_allen_from_a_scene():
    from corliss.engine.model import build_gear
    vg = {"type": "link_motion", "link": "gooch", "eccentricity": "2.75 in",
          "angular_advance": "20 deg", "eccentric_rod": "54 in", "half_link": "6 in",
          "block": "3 in", "radius_rod": "40 in", "motion": "exact", "lead": None,
          "connection": None, "steam": None, "lap": "7/8 in"}
    g = build_gear(make_scene(valve_gear=vg))
    assert g._exact is not None and g.spec.radius_rod_m == pytest.approx(40 * IN)
    a = build_gear(make_scene(valve_gear={**vg, "link": "allen"}))
    from corliss.valves.link_motion import allen_book_ratio
    assert a.spec.allen_ratio == pytest.approx(allen_book_ratio(54.0, 40.0))
    with pytest.raises(InputError, match="valve_gear.link_radius"):
        make_scene(valve_gear={**vg, "link": "allen", "link_radius": "40 in"})
