"""Shaft-governor eccentrics (Spangler Ch. XII) against the book's statements."""

import math

import numpy as np
import pytest

from corliss.valves.events import end_events
from corliss.valves.shaft_governor import ShaftGovernorGear, ShaftGovernorSpec
from corliss.valves.slide_valve import SlideValve, SlideValveSpec

IN = 0.0254
HARMONIC = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
S_VALUES = np.linspace(0.0, 1.0, 6)


def head(gear):
    e = end_events(gear, "head", HARMONIC)
    return e["cutoff_frac"], e["lead_m"]


def test_straight_path_keeps_the_lead_and_shortens_the_cut_off():
    """Art. 87: with the sheave slotted so that the centre moves at right angles to the
    crank, B = r sin d = lap + lead is constant while the cut-off varies (Erie, Art. 88;
    Armington & Sims, Art. 89)."""
    g = ShaftGovernorGear(ShaftGovernorSpec("straight", 2.0 * IN, math.radians(25),
                                            (0.75 * IN,) * 2, (0.0, 0.0), 1.0 * IN, 8 * IN,
                                            centre_travel_m=1.6 * IN))
    rows = [head(g.with_setting(s)) for s in S_VALUES]
    leads = [lead for _, lead in rows]
    cuts = [c for c, _ in rows]
    assert np.ptp(leads) < 1e-12
    assert all(a > b for a, b in zip(cuts, cuts[1:]))
    assert cuts[0] > 0.7 and cuts[-1] < 0.2


def test_ball_arc_raises_the_lead_as_cut_off_shortens():
    """Arts. 90-91: the Ball governor's pin swings on an arc about a point of the
    flywheel, and the distribution is "practically the same ... as in a Stephenson's link
    with open rods": lead increases as cut-off shortens."""
    g = ShaftGovernorGear(ShaftGovernorSpec("arc", 2.0 * IN, math.radians(30), (0.75 * IN,) * 2,
                                            (0.0, 0.0), 1.0 * IN, 8 * IN, arc_radius_m=1.5 * IN,
                                            arc_swing_rad=math.radians(60),
                                            arc_start_rad=math.radians(180)))
    rows = [head(g.with_setting(s)) for s in S_VALUES]
    cuts = [c for c, _ in rows]
    leads = [lead for _, lead in rows]
    assert all(a > b for a, b in zip(cuts, cuts[1:]))
    assert all(a < b for a, b in zip(leads, leads[1:]))


def _slide(r_in, delta_deg):
    return SlideValve(SlideValveSpec(r_in * IN, (0.75 * IN,) * 2, (0.0, 0.0),
                                     math.radians(delta_deg), 1.0 * IN, 8 * IN))


def test_advance_alone_and_throw_alone():
    """Arts. 85-86: changing the angular advance alone, "decreased cut-off means more
    lead"; changing the eccentricity alone, "increased cut-off means more lead"."""
    by_advance = [head(_slide(2.0, d)) for d in (20, 30, 40)]      # more advance
    assert by_advance[0][0] > by_advance[1][0] > by_advance[2][0]   # shorter cut-off
    assert by_advance[0][1] < by_advance[1][1] < by_advance[2][1]   # more lead
    by_throw = [head(_slide(r, 30)) for r in (1.6, 2.0, 2.4)]       # more throw
    assert by_throw[0][0] < by_throw[1][0] < by_throw[2][0]         # later cut-off
    assert by_throw[0][1] < by_throw[1][1] < by_throw[2][1]         # more lead


# ------------------------------------------------------------ finite eccentric rod

def _erie(rod_in=None, steam="outside", setting=0.0):
    """The straight-path gear of the first test (r0 = 2 in, delta0 = 25 deg, centre
    travel 1.6 in), with an eccentric rod of ``rod_in`` inches."""
    return ShaftGovernorGear(ShaftGovernorSpec(
        "straight", 2.0 * IN, math.radians(25), (0.75 * IN,) * 2, (0.0, 0.0), 1.0 * IN, 8 * IN,
        centre_travel_m=1.6 * IN, setting=setting,
        eccentric_rod_m=None if rod_in is None else rod_in * IN, steam=steam))


TH = np.linspace(0.0, 2.0 * math.pi, 1441)


@pytest.mark.parametrize("setting", [0.0, 0.7])
def test_finite_rod_tends_to_zeuner_as_r2_over_2g(setting):
    """Marks Art. 96, eqs. 229-232: the rod end falls short of the harmonic position by
    g - sqrt(g^2 - a^2), a = S cos(theta) - C sin(theta) the eccentric centre's offset
    across the line of stroke.  With the valve set for equal lead at rest (S0), the
    difference from Zeuner's form is sqrt(g^2 - S0^2) - sqrt(g^2 - a^2) =
    (a^2 - S0^2)/(2 g) + O(r^4/g^3); a^2 runs over [0, r^2], so g times the largest
    difference tends to max(S0^2, r^2 - S0^2)/2 with an error below (r^4 + S0^4)/(8 g^2)
    (the next term of the binomial series on each root).  Without a rod the gear is
    Zeuner's form itself."""
    z = _erie(None, setting=setting)
    assert np.array_equal(z.travel(TH), z.zeuner_travel(TH))
    C, S = z.spec.coefficients()
    S0 = z.spec.coefficients(0.0)[1]
    r2 = C * C + S * S
    limit = max(S0 * S0, r2 - S0 * S0) / 2.0
    errs = []
    for g_in in (20.0, 40.0, 80.0, 160.0):
        g = g_in * IN
        gear = _erie(g_in, setting=setting)
        assert np.array_equal(gear.zeuner_travel(TH), z.travel(TH))
        err = np.max(np.abs(gear.travel(TH) - gear.zeuner_travel(TH)))
        errs.append(err)
        # 1e-9: the 1441-point grid meets the extremes of a^2 (theta = 0, pi and where
        # the centre is square to the stroke) to within (2 pi / 1440)^2 r^2/(4 g)
        assert g * err == pytest.approx(limit, abs=(r2 * r2 + S0 ** 4) / (8 * g * g)
                                        + 3e-5 * r2)
    # the error halves with each doubling of the rod (to the r^4/g^3 term)
    assert all(0.49 < b / a < 0.51 for a, b in zip(errs, errs[1:]))


def test_finite_rod_leads_part_as_the_governor_moves():
    """The valve is set for equal lead at rest and the governor moves the eccentric
    under that setting: at a dead centre the rod's correction is sqrt(g^2 - S0^2) -
    sqrt(g^2 - S^2) at both (a = S at theta = 0 and -S at pi), so the head lead exceeds
    the crank lead by exactly 2 sigma (sqrt(g^2 - S0^2) - sqrt(g^2 - S^2)) [closed form,
    from the module's equation].  Equal at rest; on the straight path (S falling as the
    weights fly out) a directly connected valve taking steam outside (sigma = +1) loses
    head lead and gains crank lead: Art. 87's constant lead holds in Zeuner's form
    only."""
    g = 30.0 * IN
    for steam, sigma in (("outside", 1), ("inside", -1)):
        prev = None
        for s in S_VALUES:
            gear = _erie(30.0, steam=steam, setting=s)
            S0, S = gear.spec.coefficients(0.0)[1], gear.spec.coefficients()[1]
            h = end_events(gear, "head", HARMONIC)["lead_m"]
            c = end_events(gear, "crank", HARMONIC)["lead_m"]
            want = 2 * sigma * (math.sqrt(g * g - S0 * S0) - math.sqrt(g * g - S * S))
            assert h - c == pytest.approx(want, abs=1e-12)
            # the mean lead is Zeuner's C - lap: the straight path's constant lead
            assert (h + c) / 2 == pytest.approx(gear.spec.coefficients()[0] - 0.75 * IN,
                                                abs=1e-12)
            if prev is not None:
                assert sigma * (h - c) < sigma * prev
            prev = h - c
        assert prev != 0.0


def _frac(L_over_R):
    """Piston fraction from head dead centre with a connecting rod of L/R cranks:
    (R(1 - cos) + L - sqrt(L^2 - R^2 sin^2)) / 2R (Spangler Art. 6, laid off by the rod)."""
    def f(t):
        return ((1 - math.cos(t)) + L_over_R - math.sqrt(L_over_R ** 2 - math.sin(t) ** 2)) / 2
    return f


def test_finite_rod_cut_offs_not_180_deg_apart_in_the_books_sense():
    """Spangler Art. 63: with real rods "the crank positions when cut-off takes place are
    not 180 deg apart, but the errors of the diagram are such that the angularity of the
    connecting-rod ... brings the piston to more nearly the same distance from the
    beginning of each stroke".  The Armington & Sims and Ball valves take steam inside
    (Arts. 89-90; sigma = -1, the valve of Marks Art. 96's model, whose missing quantity
    hastens the cut-off of the stroke towards the shaft, the head end's, and delays the
    other's): so it is here with the governor at rest, where the valve was set for equal
    lead, and with a 5-crank connecting rod the cut-off fractions of the two ends come
    closer than in Zeuner's form.  A directly connected valve taking steam outside shifts
    them the other way (the connection mirrors the correction) and parts them further."""
    frac = _frac(5.0)
    z = _erie(None)
    zh, zc = (end_events(z, e, frac) for e in ("head", "crank"))
    assert (zc["cutoff_deg"] - zh["cutoff_deg"]) % 360 == pytest.approx(180.0, abs=1e-6)
    for steam, sign in (("inside", 1), ("outside", -1)):
        g = _erie(12.0, steam=steam)
        eh, ec = (end_events(g, e, frac) for e in ("head", "crank"))
        # 0.05 deg: far below the shift, r^2/(2 g) over the valve's speed, about 0.5 deg
        assert sign * (eh["cutoff_deg"] - zh["cutoff_deg"]) < -0.05
        assert sign * (ec["cutoff_deg"] - zc["cutoff_deg"]) > 0.05
        gap = abs(eh["cutoff_frac"] - ec["cutoff_frac"])
        gap_z = abs(zh["cutoff_frac"] - zc["cutoff_frac"])
        assert sign * (gap - gap_z) < 0


@pytest.mark.parametrize("steam", ["outside", "inside"])
def test_finite_rod_is_the_slide_valve_shifted_bodily(steam):
    """At any governor position the eccentric is a plain one of throw hypot(C, S) and
    advance atan2(C, S); the exact gear equals the slide valve on that eccentric with the
    same rod, set for equal lead at that throw (Marks Art. 96), displaced bodily by the
    difference of the two settings, sigma (sqrt(g^2 - S0^2) - sqrt(g^2 - S^2)) [closed
    form: the slide valve's zero is sqrt(g^2 - (r cos delta)^2) = sqrt(g^2 - S^2)].  So
    the correction's zero stays where the valve was set, at rest."""
    for s in S_VALUES:
        gear = _erie(12.0, steam=steam, setting=s)
        C, S = gear.spec.coefficients()
        S0 = gear.spec.coefficients(0.0)[1]
        slide = SlideValve(SlideValveSpec(math.hypot(C, S), (0.75 * IN,) * 2, (0.0, 0.0),
                                          math.atan2(C, S), 1.0 * IN, 8 * IN,
                                          eccentric_rod_m=12.0 * IN, steam=steam))
        g = 12.0 * IN
        shift = gear.spec.sigma * (math.sqrt(g * g - S0 * S0) - math.sqrt(g * g - S * S))
        assert np.allclose(gear.travel(TH), slide.travel(TH) + shift, rtol=0, atol=1e-15)
        assert np.allclose(gear.zeuner_travel(TH), slide.zeuner_travel(TH), rtol=0, atol=1e-15)
