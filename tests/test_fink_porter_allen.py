"""The Fink link motion and the Porter-Allen gear (Spangler Arts. 74-83, 30).

The dimensions are those of Spangler's Problem 46 (Ch. XI): a Fink motion with r = 1 in,
a = 6 in, b = 0, c = 10 in, radius rod 40 in, the lead 1/16 in at u = 10 in (so the lap
is 15/16 in: lap + lead = r, Art. 78).  The book prints no answers; the references
below are its identities and closed forms derived from them.
"""

import dataclasses
import math

import numpy as np
import pytest

from corliss.errors import InputError
from corliss.valves.events import end_events, events
from corliss.valves.fink_motion import (FinkLink, FinkMotion, FinkMotionSpec, PorterAllenGear,
                                        PorterAllenSpec)

from conftest import make_scene

IN = 0.0254
HARMONIC = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
R, A_ROD, C_LINK, G1 = 1 * IN, 6 * IN, 10 * IN, 40 * IN
LAP = 15 / 16 * IN
TH = np.linspace(0.0, 2 * math.pi, 721)


def link(motion="zeuner", b=0.0, rho=G1, k=1.0, k2=None):
    """Problem 46's link, a, b and c grown by k, the radius rod and link by k2."""
    k2 = k if k2 is None else k2
    return FinkLink(R, A_ROD * k, b * k, G1 * k2, C_LINK * k, rho * k2, motion)


def fink(u, motion="zeuner", **kw):
    return FinkMotion(FinkMotionSpec(link(motion, **kw), u, (LAP, LAP), (0.0, 0.0), 1 * IN,
                                     12 * IN))


def test_zeuner_form_and_valve_circle_of_art_78():
    """Art. 77-78: x = r cos w + (u r/a)(1 + b/g1) sin w; the valve circle's centre is
    (r/2, (u r/2a)(1 + b/g1)).  Events from the virtual eccentric R = sqrt(C^2 + S^2),
    tan d = C/S (notes Sec. 3): admission at asin(l/R) - d, cut-off at 180 - asin(l/R)
    - d, to the bisection's precision."""
    for b in (0.0, 2 * IN):
        lk = link(b=b)
        for u in (4 * IN, 8 * IN, 10 * IN):
            C, S = lk.coefficients(u)
            assert (C, S) == pytest.approx((R, u * R / A_ROD * (1 + b / G1)), rel=1e-15)
    for u in (4 * IN, 8 * IN, 10 * IN):
        ev = end_events(fink(u), "head", HARMONIC)
        S = u * R / A_ROD
        Rv, d = math.hypot(R, S), math.atan2(R, S)
        assert math.radians(ev["cutoff_deg"]) == pytest.approx(
            math.pi - math.asin(LAP / Rv) - d, abs=1e-9)
        assert math.radians(ev["admission_deg"]) - 2 * math.pi == pytest.approx(
            math.asin(LAP / Rv) - d, abs=1e-9)


def test_constant_lead_every_setting_zeuner_and_exact():
    """Art. 78: u = 0 gives a valve circle of diameter r, "the lap plus the lead equals
    the throw of the eccentric", and C = r for every u: the lead is r - lap = 1/16 in at
    every setting.  Art. 75: with the link's radius equal to the radius rod, on a dead
    point the link is an arc about the stem's end, so moving the block does not move
    the valve: the exact linkage keeps the same lead to rounding (1e-12 in)."""
    for u in np.linspace(-C_LINK, C_LINK, 9):
        for motion, tol in (("zeuner", 1e-15), ("second_order", 1e-15), ("exact", 1e-12 * IN)):
            ev = events(fink(u, motion), HARMONIC)
            for end in ("head", "crank"):
                assert ev[end]["lead_m"] == pytest.approx(IN / 16, abs=tol)
    # a link radius not the radius rod's (Porter-Allen, Art. 83: "slightly more") makes
    # the leads change with the block, "on one end decreased and the other increased"
    lead = {u: events(fink(u * IN, "exact", rho=41 * IN), HARMONIC) for u in (10, 4)}
    dh = lead[4]["head"]["lead_m"] - lead[10]["head"]["lead_m"]
    dc = lead[4]["crank"]["lead_m"] - lead[10]["crank"]["lead_m"]
    assert dh * dc < 0 and abs(dh) > 1e-3 * IN


@pytest.mark.parametrize("b", [0.0, 1 * IN])
def test_exact_linkage_tends_to_zeuner_and_to_equation_a(b):
    """Art. 77's derivation expands in r/a (the rod's swing) and in u/g1 (the link's arc
    taken as the parabola y^2 = 2 g1 x, sqrt(g1^2 - u^2) = g1 - u^2/2g1).  Growing a, b,
    c and u by k and the radius rod and link by k^2 (so both ratios fall as 1/k while
    the valve circle stays the same), the exact linkage's departure from Zeuner's form
    (the neglected sin^2 term, of order r^2/a) must fall as 1/k, by at least 40 % per
    doubling, and from the whole of eq. (A) as 1/k^2, by at least 70 % per doubling:
    which confirms eq. (A)'s sin^2 coefficient (with the 1/cos^3 the OCR prints as
    1/cos^2).  At k = 1 the departure from Zeuner is about 0.1 in."""
    ez, ea = [], []
    for k in (1.0, 2.0, 4.0):
        u = 8 * IN * k
        x = link("exact", b=b, k=k, k2=k * k).block_travel(u, TH)
        ez.append(np.max(np.abs(x - link("zeuner", b=b, k=k, k2=k * k).block_travel(u, TH))))
        ea.append(np.max(np.abs(x - link("second_order", b=b, k=k, k2=k * k).block_travel(u, TH))))
    assert ez[0] / IN == pytest.approx(0.09, abs=0.02)
    assert ez[1] < 0.6 * ez[0] and ez[2] < 0.6 * ez[1]
    assert ea[1] < 0.3 * ea[0] and ea[2] < 0.3 * ea[1]


def test_fixed_point_of_the_link_moves_without_the_b_factor():
    """Art. 79: a point fixed on the link a distance y from the rod moves like the
    block "putting y in the place of u".  Solving the linkage, the fixed point lacks the
    factor (1 + b/g1), which comes from the block sliding on the curved link at constant
    height: its first harmonic tends to r cos w + (y r/a) sin w.  With b = 0 the two
    agree; with b = 3 in the block's S is 7.5 % larger.  Grown as above by k = 4."""
    k = 4.0
    for b in (0.0, 3 * IN):
        lk = link("exact", b=b, k=k, k2=k * k)
        y = 8 * IN * k
        x = lk.point_travel(y, TH)
        S_fit = 2 * np.mean(x[:-1] * np.sin(TH[:-1]))       # Fourier sine coefficient
        assert S_fit == pytest.approx(y * R / (A_ROD * k), rel=0.01)
        S_block = 2 * np.mean(lk.block_travel(y, TH)[:-1] * np.sin(TH[:-1]))
        assert S_block == pytest.approx(lk.coefficients(y)[1], rel=0.01)


def test_exact_fink_cuts_off_unequally_at_the_two_ends():
    """Art. 83: "the cut-off in the two ends of the cylinder may vary greatly, as the
    variation of the actual diagram from the Zeuner diagram is greatest about the
    point of cut-off": eq. (A)'s sin^2 term is the same at w and w + 180 deg, so it
    opens one end's port and closes the other's.  Zeuner's cut-offs are 180 deg apart."""
    z = [end_events(fink(8 * IN), e, HARMONIC)["cutoff_deg"] for e in ("head", "crank")]
    x = [end_events(fink(8 * IN, "exact"), e, HARMONIC)["cutoff_deg"] for e in ("head", "crank")]
    assert (z[1] - z[0]) % 360 == pytest.approx(180.0, abs=1e-6)
    assert abs((x[1] - x[0]) % 360 - 180.0) > 2.0


# ------------------------------------------------------------------- Porter-Allen

def porter_allen(setting=0.0, motion="exact", **kw):
    spec = PorterAllenSpec(
        link=link(motion, rho=41 * IN), block_at_rest_m=10 * IN, block_at_top_m=0.0,
        drive_arm_m=6 * IN, valve_arm_m=6 * IN, steam_lap_m=(LAP, LAP),
        exhaust_point_m=10 * IN, exhaust_ratio=1.0, exhaust_lap_m=(0.0, 0.0),
        steam_port_width_m=1 * IN, steam_port_length_m=22 * IN, exhaust_port_width_m=1.5 * IN,
        exhaust_port_length_m=22 * IN, setting=setting)
    return PorterAllenGear(dataclasses.replace(spec, **kw))


S_GRID = np.linspace(0.0, 1.0, 6)


@pytest.mark.parametrize("motion", ["zeuner", "exact"])
def test_exhaust_events_do_not_change_with_the_governor(motion):
    """Art. 83: the exhaust rod "is attached permanently to one point of the link", so
    release and compression are the same at every governor position (exactly: nothing
    the governor moves is in their train), while the cut-off falls as the governor
    lifts the block towards the link's centre (Art. 84: the Porter-Allen governor
    "acts by moving the radius-rod in the link")."""
    ev = [events(porter_allen(s, motion), HARMONIC) for s in S_GRID]
    for end in ("head", "crank"):
        for key in ("release_deg", "compression_deg"):
            vals = [e[end][key] for e in ev]
            assert np.ptp(vals) == 0.0, (end, key)
        cut = [e[end]["cutoff_frac"] for e in ev]
        assert np.all(np.diff(cut) < 0), (end, cut)
        assert cut[0] > 0.7 and cut[-1] < 0.06          # from 3/4 stroke to almost none


def test_steam_valves_move_fastest_as_they_open_and_close():
    """Art. 30 / 83: the rock shaft's arms are set so "each valve is moving its fastest
    when opening and closing its port": with the arm square to the stem there, the
    opening's rate is the arm's R_v times the shaft's angular rate, the most it can be;
    the events are those of the radius rod's motion cut by the lap referred to the rod,
    R_d sin(beta) = 15/16 in (arms of equal length)."""
    g = porter_allen(0.3)
    assert g.spec.equivalent_lap_m == pytest.approx((LAP, LAP), rel=1e-12)
    ev = events(g, HARMONIC)["head"]
    for key in ("admission_deg", "cutoff_deg"):
        t = math.radians(ev[key])
        h = 1e-6
        dphi = (g.rock_angle(np.array([t + h])) - g.rock_angle(np.array([t - h])))[0] / (2 * h)
        s_plus, s_minus = g.signed_openings(np.array([t + h, t - h]))[0]
        dopen = (s_plus - s_minus) / (2 * h)
        assert abs(dopen) == pytest.approx(6 * IN * abs(dphi), rel=1e-6)
        assert g.steam_drive(np.array([t]))[0] == pytest.approx(LAP, abs=1e-9 * IN)


def test_four_ports_have_their_own_valves():
    """Four valves (Art. 30): each port's opening depends on its own valve's lap only."""
    g0 = porter_allen(0.4)
    g1 = porter_allen(0.4, steam_lap_m=(LAP, 0.8 * IN), exhaust_lap_m=(0.1 * IN, 0.0))
    s0, s1 = g0.signed_openings(TH), g1.signed_openings(TH)
    assert np.array_equal(s0[0], s1[0])                 # head steam untouched
    assert np.array_equal(s0[3], s1[3])                 # crank exhaust untouched
    assert not np.allclose(s0[1], s1[1]) and not np.allclose(s0[2], s1[2])


def test_porter_allen_is_drawn_in_its_own_panels_and_scene_checks():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from corliss.plot import plot_gear
    fig = plt.figure(figsize=(13, 5))
    out = plot_gear(porter_allen(0.5), fig, "SI")
    assert len(out["axes"]) == 3 and len(fig.axes) == 3
    plt.close(fig)
    vg = {"type": "porter_allen", "eccentricity": "1 in", "rod_a": "6 in", "radius_rod": "40 in",
          "link_radius": "41 in", "half_link": "10 in", "block_at_rest": "10 in",
          "block_at_top": "0 in", "drive_arm": "6 in", "valve_arm": "6 in",
          "steam_lap": "15/16 in", "exhaust_point": "10 in", "steam_port_width": "1 in",
          "steam_port_length": "22 in", "exhaust_port_width": "1.5 in",
          "exhaust_port_length": "22 in", "lap": None, "lead": None, "exhaust_lap": None,
          "port_width": None, "port_length": None, "eccentric_rod": None, "connection": None,
          "steam": None}
    make_scene(valve_gear=vg)
    with pytest.raises(InputError, match="valve_gear.block_at_rest"):
        make_scene(valve_gear={**vg, "block_at_rest": "11 in"})
    with pytest.raises(InputError, match="valve_gear.drive_arm"):
        make_scene(valve_gear={**vg, "drive_arm": "1.5 in"})
