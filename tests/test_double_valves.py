"""Double valves (Spangler, *Valve-Gears*, Chs. XV-XVIII): gridiron, Polonceau, Buckeye,
Meyer and Guinotte against the book's equations and statements.

The book states no numerical answers to its problems (its figures are missing and its
worked problems are drawing constructions); where a test uses a problem's data, the
reference value is the book's construction carried out in closed form, derived in the
test's docstring.  Crank angles from the head-end dead centre; ``HARMONIC`` is the
piston fraction of an infinite connecting rod (the book's drawing convention).
"""

import dataclasses
import logging
import math

import numpy as np
import pytest

from corliss.valves import double_valve as dv
from corliss.valves.buckeye import BuckeyeGear, BuckeyeSpec
from corliss.valves.events import end_events
from corliss.valves.gridiron import GridironSpec, GridironValve
from corliss.valves.link_motion import LinkMotionSpec
from corliss.valves.meyer import MeyerSpec, MeyerValve
from corliss.valves.polonceau import (GuinotteGear, GuinotteSpec, PolonceauGear, PolonceauSpec,
                                      guinotte)
from corliss.valves.portmap import tabulate

IN = 0.0254
D = math.radians
HARMONIC = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
TH = np.linspace(0.0, 2 * math.pi, 721)


def deg(t):
    return math.degrees(t) % 360.0


def head(gear):
    return end_events(gear, "head", HARMONIC)


def slider_crank(R, Lrod):
    """Piston fraction from the head-end dead centre with a rod of length Lrod."""
    return lambda t: (R * (1 - math.cos(t)) + Lrod - math.sqrt(Lrod ** 2 - (R * math.sin(t)) ** 2)) / (2 * R)


def crank_at(frac, R, Lrod, end):
    """Crank angle [rad] at which the piston has moved ``frac`` of the stroke from that
    end's dead centre (bisection on the slider crank)."""
    f = slider_crank(R, Lrod)
    lo, hi = (0.0, math.pi) if end == "head" else (math.pi, 2 * math.pi)
    target = frac if end == "head" else 1.0 - frac
    for _ in range(80):
        m = 0.5 * (lo + hi)
        if (f(m) < target) == (end == "head"):
            lo = m
        else:
            hi = m
    return 0.5 * (lo + hi)


def main_valve(lap, width=1.0, exhaust_lap=0.0):
    return dv.MainValveSpec((lap * IN,) * 2, (exhaust_lap * IN,) * 2, width * IN, 10 * IN)


# ---------------------------------------------------------------------------------------
# Gridiron (Chap. XV)

def p61(r1=2.625, delta1=-18.0, ratio=(1.0, 1.0), setting=0.0, **kw):
    """Problem 61 (Art. 126 problems): r = r1 = 2 5/8 in, delta = -delta1 = 18 deg, lap
    5/8 in, e = 1 in, f = 1 1/4 in (exhaust and ports not given: 1 in port, no exhaust lap)."""
    e, f = 1.0 * IN, 1.25 * IN
    s = (e + f) / 2
    return GridironValve(GridironSpec(main_valve(0.625), dv.CutoffSpec("seat", (s, s), e, 10 * IN),
                                      2.625 * IN, D(18), r1 * IN, D(delta1), f, ratio, setting,
                                      **kw))


def test_gridiron_problem_61_cut_off_where_the_s_circle_cuts_the_cut_off_circle():
    """Arts. 118-121: the cut-off valve closes where its displacement r1 sin(w + d1) reaches
    s = (e + f)/2; for Problem 61, w_E = arcsin(1.125/2.625) + 18 deg = 43.38 deg, the
    main valve admitting at arcsin(lap/r) - 18 deg = -4.23 deg and cutting off at 180 -
    arcsin(lap/r) - 18 = 148.23 deg; the cut-off valve re-opens (F) at 180 - 25.38 + 18 =
    172.62 deg, between B and the other end's admission, as Art. 118 requires."""
    g = p61()
    ev = head(g)
    assert ev["cutoff_deg"] == pytest.approx(18 + math.degrees(math.asin(1.125 / 2.625)), abs=1e-7)
    assert ev["admission_deg"] == pytest.approx(360 - 4.2259, abs=1e-3)
    assert g.double_admissions() == {"head": [], "crank": []}
    crank = end_events(g, "crank", HARMONIC)
    assert crank["cutoff_deg"] == pytest.approx(ev["cutoff_deg"] + 180, abs=1e-7)  # Zeuner symmetry


def test_gridiron_seat_port_opening_art_121():
    """Art. 121: the cut-off port "begins to close when the valve has travelled (f - e)/2
    from its middle position, is entirely closed when x = s"; in between it is open by
    s - |x1| (e = 1, f = 1.25, s = 1.125 in)."""
    g = p61()
    th = np.linspace(0, 2 * math.pi, 2001)
    x1 = g.cutoff_travel(th)
    open_ = np.clip(g.cutoff_signed(th)[0], 0, g.spec.cutoff.passage_width_m)
    wide = np.abs(x1) <= 0.125 * IN
    assert np.all(np.abs(open_[wide] - 1.0 * IN) < 1e-12)
    closing = (np.abs(x1) > 0.125 * IN) & (np.abs(x1) < 1.125 * IN)
    assert np.allclose(open_[closing], 1.125 * IN - np.abs(x1[closing]), atol=1e-12)
    assert np.all(open_[np.abs(x1) >= 1.125 * IN] == 0.0)


def test_combined_opening_is_the_smaller_and_exhaust_is_the_main_valves():
    """Art. 116: steam reaches the cylinder only through both valves (in series: the
    smaller opening), "exhaust takes place under the valve a as in an ordinary slide"."""
    g = p61()
    th = np.linspace(0, 2 * math.pi, 1441)
    comb, main, cut = g.openings(th), g.main_signed(th), g.cutoff_signed(th)
    w = g.spec.main.port_width_m
    assert np.allclose(comb[0], np.minimum(np.clip(main[0], 0, w), np.clip(cut[0], 0, 1 * IN)))
    assert np.allclose(comb[1], np.clip(main[1], 0, w)) and np.allclose(comb[3], np.clip(main[3], 0, w))
    pm = tabulate(g)
    assert pm.area_m2[0].max() <= w * 10 * IN + 1e-15


def test_gridiron_varying_throw_and_advance_art_123():
    """Art. 123: "if the angle of advance alone is increased the cut-off is later ... If
    the value of oi [the throw] alone is increased the cut-off is earlier".  The lever of
    Art. 124 changes the travel "in the proportion of ih to ij": a greater ratio (setting)
    cuts off earlier."""
    by_throw = [head(p61(r1=r))["cutoff_deg"] for r in (1.8, 2.2, 2.625, 2.9)]
    assert all(a > b for a, b in zip(by_throw, by_throw[1:]))
    # the advance is negative (Art. 118): "increased" is the angle goi made larger
    by_adv = [head(p61(delta1=d))["cutoff_deg"] for d in (-12, -18, -24, -30)]
    assert all(a < b for a, b in zip(by_adv, by_adv[1:]))
    lever = p61(r1=2.625, ratio=(0.7, 1.1))
    cuts = [head(lever.with_setting(s))["cutoff_deg"] for s in (0, 0.5, 1)]
    assert cuts[0] > cuts[1] > cuts[2]


def test_gridiron_double_admission_where_the_throw_is_too_small():
    """Art. 118: F (re-opening) must fall after B (main cut-off), "otherwise steam would be
    admitted twice during one stroke".  With x1 = r1 sin(w + d1), F is at 180 deg -
    arcsin(s/r1) - d1; F = B = 148.226 deg gives r1* = s / sin(180 - d1 - B) =
    1.125 / sin(49.774 deg) = 1.4735 in: below it the detector finds the second admission
    from F to B; above it, none."""
    B = 180 - math.degrees(math.asin(0.625 / 2.625)) - 18
    r_star = 1.125 / math.sin(D(180 + 18 - B))
    assert r_star == pytest.approx(1.4735, abs=1e-4)
    bad = p61(r1=r_star * 0.95).double_admissions()
    assert len(bad["head"]) == 1 and len(bad["crank"]) == 1
    start, end = bad["head"][0]
    F = 180 - math.degrees(math.asin(1.125 / (0.95 * r_star))) + 18
    assert start == pytest.approx(F, abs=1e-6) and end == pytest.approx(B, abs=1e-6)
    assert p61(r1=r_star * 1.05).double_admissions() == {"head": [], "crank": []}


# ---------------------------------------------------------------------------------------
# Relative valve circle, Polonceau (Chap. XVI)

def test_relative_valve_circle_art_128():
    """Art. 128: ef = r sin(w + d) - r1 sin(w + d1) = (r cos d - r1 cos d1) sin w + (r sin d
    - r1 sin d1) cos w, a circle through o of diameter |r e^{i d} - r1 e^{i d1}| (Art. 129:
    ok equal and parallel to dc).  Problem 71's data: r = 1 5/8, d = 15, r1 = 1 7/8,
    d1 = 85; cut-off where ef = s = 1 1/8 in: w = arcsin(s / r_x) - delta_x."""
    r, d, r1, d1, s = 1.625 * IN, D(15), 1.875 * IN, D(85), 1.125 * IN
    g = meyer(r=r, delta=d, r1=r1, delta1=d1, lap=0.5, span=2 * (s + 2.0 * IN), block=2.0 * IN,
              ymax=0.0)
    ef = r * np.sin(TH + d) - r1 * np.sin(TH + d1)
    assert np.allclose(g.closing_travel(TH), ef, atol=1e-15)
    C, S = r * math.sin(d) - r1 * math.sin(d1), r * math.cos(d) - r1 * math.cos(d1)
    assert np.allclose(ef, C * np.cos(TH) + S * np.sin(TH), atol=1e-15)
    rx = math.hypot(C, S)
    assert rx == pytest.approx(math.sqrt(r * r + r1 * r1 - 2 * r * r1 * math.cos(d1 - d)))
    w = math.asin(s / rx) - math.atan2(C, S)
    ev = head(g)
    assert ev["cutoff_deg"] == pytest.approx(deg(w), abs=1e-7)


def polonceau(u1=1.0, s=0.75, lap=0.875):
    """Problem 64's link (r = 2 3/8 in, g = 57 in, delta = 27 deg, link 12 in: c = 6 in);
    main valve lap 7/8 in (the book's lead of 1/4 in is the Gooch lead r(sin d + (c/g) cos d)
    - lap = 1.3 - lap, so the lap for a 1/4 in lead would be 1.05 in; 7/8 in is used to keep
    a usable cut-off range); block lap s."""
    return PolonceauGear(PolonceauSpec(main_valve(lap, 1.25), dv.CutoffSpec("riding", (s * IN,) * 2,
                                       1.5 * IN, 10 * IN), 2.375 * IN, D(27), 57 * IN, 6 * IN,
                                       6 * IN, u1))


def test_polonceau_relative_circle_centre_on_the_perpendicular_art_132():
    """Art. 132: "As for a Gooch link fe is parallel to on, the centre of the relative
    valve-circle is on on": C_r = 0, x_r = ((u - u1) r / c)(cos d - (c/g) sin d) sin w."""
    g = polonceau(u1=0.25)
    C, S = g.zeuner_closing_coefficients()
    assert abs(C) < 1e-15
    assert S == pytest.approx((6 - 1.5) * 2.375 / 6 * (math.cos(D(27)) - 6 / 57 * math.sin(D(27))) * IN)


def test_polonceau_limits_art_131_133():
    """Art. 131: rods at the same point, "the valves move together and the cut-off is that
    due to the main valve".  Art. 133: lowering the cut-off rod cuts off earlier, the
    earliest at u1 = -c; the latest usable cut-off (beyond it steam enters twice) lies as
    far before mid stroke as the main valve's cut-off lies after it (in crank angle, the
    relative circle being symmetric about the perpendicular)."""
    B = head(polonceau(1.0))["cutoff_deg"]
    cuts = [head(polonceau(u))["cutoff_deg"] for u in (-1.0, -0.5, 0.0, 0.3)]
    assert all(a < b for a, b in zip(cuts, cuts[1:]))
    # the latest setting without a second admission, by bisection on the detector
    # (above u1/c = 0.625 the relative travel no longer reaches s = 3/4 in at all and the
    # main valve cuts off alone; between the limit and that, steam enters twice)
    lo, hi = -1.0, 0.6
    assert not polonceau(lo).double_admissions()["head"] and polonceau(hi).double_admissions()["head"]
    for _ in range(30):
        m = 0.5 * (lo + hi)
        lo, hi = (m, hi) if not polonceau(m).double_admissions()["head"] else (lo, m)
    latest = head(polonceau(lo))["cutoff_deg"]
    assert 90 - latest == pytest.approx(B - 90, abs=0.05)   # bisection to 1e-9 of u1/c


def test_polonceau_same_point_gives_main_cut_off():
    """Art. 131, with a block lap s > 0 and u1 = u: x_r = 0, the passages never close, and
    the cut-off is the main valve's own, 180 - arcsin(lap / R) - delta_v."""
    g = polonceau(1.0)
    C, S = g.main_coefficients()
    w = math.pi - math.asin(0.875 * IN / math.hypot(C, S)) - math.atan2(C, S)
    assert head(g)["cutoff_deg"] == pytest.approx(deg(w), abs=1e-7)


def test_polonceau_exact_link_tends_to_zeuner():
    """The exact Gooch link (finite rods, curved link, the block slipping as the link
    swings) differs from Art. 65's form by terms of order (r/c)^2 and (c/g)^2: with the
    link's half chord and the block offsets scaled by k and the rods by k^2, the
    difference in both the main and the relative motion falls as 1/k^2 (ratio 4 within
    15 %)."""
    errs = []
    for k in (1, 2, 4):
        sp = dataclasses.replace(polonceau(0.0).spec, eccentric_rod_m=57 * k * k * IN,
                                 half_link_m=6 * k * IN, main_block_m=6 * k * IN)
        z, ex = PolonceauGear(sp), PolonceauGear(dataclasses.replace(sp, motion="exact"))
        errs.append(max(np.abs(ex.closing_travel(TH) - z.closing_travel(TH)).max(),
                        np.abs(ex.main_travel(TH) - z.main_travel(TH)).max()))
    assert all(3.4 < a / b < 4.6 for a, b in zip(errs, errs[1:])), errs


# ---------------------------------------------------------------------------------------
# Buckeye (Chap. XVII)

def p67(delta1=0.0, s=1.0, swing=0.0, setting=0.0, **kw):
    """Problem 67: lap 1 1/4 in, port opening 1 5/8 in, maximum cut-off at 2/3 stroke,
    r1 = r, s = 1 in.  Travel: r = lap + greatest opening = 2.875 in (Art. 19); the main
    valve cuts off at w_m = arccos(1 - 4/3) = 109.47 deg (infinite rod), so
    delta = 180 - arcsin(1.25/2.875) - w_m = 44.757 deg (Art. 2.3 closed form)."""
    r = 2.875 * IN
    delta = math.pi - math.asin(1.25 / 2.875) - math.acos(1 - 4 / 3)
    return BuckeyeGear(BuckeyeSpec(main_valve(1.25, 1.625), dv.CutoffSpec("riding", (s * IN,) * 2,
                                   1.625 * IN, 10 * IN), r, delta, r, D(delta1), D(swing),
                                   setting, **kw))


def test_buckeye_problem_67_settings():
    """Art. 138: the block closes where r1 sin(w + d1) = s, i.e. d1 = arcsin(s/r1) - w_c.
    For Problem 67 (s/r1 = 1/2.875): 2/3 stroke (109.47 deg) needs d1 = -89.12 deg,
    1/3 stroke (70.53 deg) d1 = -50.18 deg, an angular movement of 38.94 deg.  Problem 68
    asks whether s changes that movement: d1(2/3) - d1(1/3) = w(1/3) - w(2/3), independent
    of s."""
    a = math.degrees(math.asin(1 / 2.875))
    for frac in (2 / 3, 1 / 3):
        wc = math.degrees(math.acos(1 - 2 * frac))
        assert head(p67(a - wc))["cutoff_frac"] == pytest.approx(frac, abs=1e-9)
    assert a - 109.4712 == pytest.approx(-89.117, abs=1e-3)
    movement = []
    for s in (0.75, 1.0, 1.25):
        a = math.degrees(math.asin(s / 2.875))
        movement.append((a - 70.5288) - (a - 109.4712))
        assert head(p67(a - 109.4712, s=s))["cutoff_frac"] == pytest.approx(2 / 3, abs=1e-5)
        assert head(p67(a - 70.5288, s=s))["cutoff_frac"] == pytest.approx(1 / 3, abs=1e-5)
    assert np.ptp(movement) < 1e-12


def test_buckeye_art_139_statements():
    """Art. 139: "If the angle of advance delta1 is zero, the cut-off takes place at on,
    and the port is again open to steam at oj after the main valve has cut off at ok.  As
    delta1 increases negatively the point of cut-off is later and later", up to the main
    valve's.  The governor (Art. 140) turns the loose eccentric: here forward with speed,
    so the cut-off shortens as the setting rises."""
    ev0 = head(p67(0.0))
    assert ev0["cutoff_deg"] < 90.0 and p67(0.0).double_admissions() == {"head": [], "crank": []}
    reopen = 180 - math.degrees(math.asin(1 / 2.875))    # x_r falls back to s
    assert reopen > head(p67(0.0))["cutoff_deg"] and reopen > 109.4712
    cuts = [head(p67(d))["cutoff_frac"] for d in (0, -20, -40, -60, -80)]
    assert all(a < b for a, b in zip(cuts, cuts[1:]))
    assert head(p67(-120))["cutoff_frac"] == pytest.approx(2 / 3, abs=1e-9)   # the main valve's
    gov = p67(-89.12, swing=60.0)
    fr = [head(gov.with_setting(x))["cutoff_frac"] for x in (0, 0.25, 0.5)]
    assert fr[0] > fr[1] > fr[2]


def test_buckeye_earliest_cut_off_and_too_large_s():
    """Art. 139: the limit of the adjustment is where the re-opening oe reaches the main
    valve's cut-off, and there "the earliest possible cut-off ... will be found to be at or
    before the beginning of the stroke".  In closed form the limit is d1* = 180 - arcsin(s/r1)
    - w_m and the cut-off there is 2 arcsin(s/r1) - arcsin(l/r) - delta, at or before the
    dead point when s <= l (Problem 67: 2(20.35) - 25.77 - 44.76 = -29.8 deg), so no setting
    of the governor admits steam twice.  Problem 68 asks whether s can be made too large:
    with s > l the cut-off at the limit falls after the main valve opens, and the detector
    finds settings that admit twice."""
    a, lap_a = math.asin(1 / 2.875), math.asin(1.25 / 2.875)
    delta = math.pi - lap_a - math.acos(1 - 4 / 3)
    assert math.degrees(2 * a - lap_a - delta) == pytest.approx(-29.82, abs=0.01)
    d1s = np.arange(-120.0, 91.0, 5.0)
    assert not any(p67(d).double_admissions()["head"] for d in d1s)
    twice = [d for d in d1s if p67(d, s=1.75).double_admissions()["head"]]
    assert twice, "s = 1.75 in > lap: some advance should admit twice"
    limit = 180 - math.degrees(math.asin(1.75 / 2.875)) - 109.4712
    assert min(twice) > limit


def test_buckeye_beyond_the_limit_the_cut_off_valve_holds_the_admission_back(caplog):
    """Art. 118: "the cut-off valve must open between D and A in order that the steam may be
    admitted as soon as the main valve opens".  Past the limit of Art. 139 (d1* = 50.18 deg
    for Problem 67) the blocks close before the main valve opens (at arcsin(l/r) - delta =
    -18.99 deg) and re-open at 180 - arcsin(s/r1) - d1, before the main cut-off: at d1 = 55
    deg steam enters only from 104.65 deg; at d1 = 40 deg the blocks re-open only after the
    main valve has closed and no steam enters that stroke."""
    A = math.degrees(math.asin(1.25 / 2.875)) - math.degrees(math.pi - math.asin(1.25 / 2.875)
                                                              - math.acos(1 - 4 / 3))
    (a, b), = p67(55.0).late_admissions()["head"]
    assert a == pytest.approx(A % 360, abs=0.05)          # the main valve's edge, to a sample
    assert b == pytest.approx(180 - math.degrees(math.asin(1 / 2.875)) - 55, abs=1e-6)
    assert p67(40.0).late_admissions()["head"] == [(pytest.approx(A % 360, abs=0.05), None)]
    assert p67(-60.0).late_admissions() == {"head": [], "crank": []}
    with caplog.at_level(logging.WARNING):
        dv.built(p67(40.0))
    assert "no steam is admitted at all" in caplog.text


def test_buckeye_relative_motion_independent_of_main_eccentric_art_137():
    """Art. 137: the relative movement r sin(w + d) + r1 sin(w - d1) - r sin(w + d) is the
    cut-off eccentric's alone.  In the real linkage (finite rods, d on its arc about f, h on
    its arc about i) the floating lever keeps j - d = f - h exactly, and the main eccentric
    enters only through the small swing of i: changing its advance by 30 deg and its throw
    by 30 % moves the relative motion by a second-order amount, which shrinks as the
    linkage grows (halved or better when every length is doubled)."""
    def linkage(scale, r_main=2.875, adv=None):
        g = p67(-60.0, motion="exact", eccentric_rod_m=scale * 40 * IN,
                cutoff_eccentric_rod_m=scale * 40 * IN, rock_lever_m=scale * 24 * IN,
                floating_lever_m=scale * 24 * IN)
        sp = dataclasses.replace(g.spec, eccentricity_m=r_main * IN,
                                 angular_advance_rad=g.spec.angular_advance_rad if adv is None else adv)
        return BuckeyeGear(sp)

    diffs = []
    for scale in (1.0, 2.0, 4.0):
        a = linkage(scale).closing_travel(TH)
        b = linkage(scale, r_main=2.0, adv=D(15)).closing_travel(TH)
        diffs.append(np.abs(a - b).max())
    assert diffs[0] < 0.03 * 2.875 * IN        # a few hundredths of the throw at real size
    assert diffs[1] < 0.55 * diffs[0] and diffs[2] < 0.55 * diffs[1]


def test_buckeye_exact_linkage_converges_to_zeuner():
    """The exact linkage tends to Zeuner's form as rods and levers grow: the error is of
    order r^2 / length, so it halves (within 10 %) when every length doubles."""
    errs = []
    for scale in (1.0, 2.0, 4.0, 8.0):
        g = p67(-60.0, motion="exact", eccentric_rod_m=scale * 40 * IN,
                cutoff_eccentric_rod_m=scale * 40 * IN, rock_lever_m=scale * 24 * IN)
        z = p67(-60.0)
        errs.append(max(np.abs(g.main_travel(TH) - z.main_travel(TH)).max(),
                        np.abs(g.closing_travel(TH) - z.closing_travel(TH)).max()))
    ratios = [a / b for a, b in zip(errs, errs[1:])]
    assert all(1.8 < q < 2.2 for q in ratios), ratios
    assert errs[-1] < 0.01 * IN


# ---------------------------------------------------------------------------------------
# Meyer (Chap. XVIII)

def meyer(r, delta, r1, delta1, lap, span, block, ymax, e=0.75 * IN, setting=0.0,
          offset=(0.0, 0.0), width=1.0, **kw):
    spec = MeyerSpec(main_valve(lap, width), dv.CutoffSpec("riding", (0.0, 0.0), e, 10 * IN, block),
                     r, delta, r1, delta1, span, block, ymax, offset, setting, **kw)
    spec = dataclasses.replace(spec, cutoff=dataclasses.replace(spec.cutoff, lap_m=spec.block_lap()))
    return MeyerValve(spec)


def p70(setting=0.0, rx_dir_deg=0.0, margin=0.125, **kw):
    """Problem 70: main valve cuts off at 3/4 stroke (w_m = 120 deg, infinite rod), r = 1 3/4
    in, angle of lead 8 deg, e = 3/4 in, r_x = 1 1/2 in, blocks together at the latest
    cut-off (3/4 stroke).  Art. 143's construction in closed form: admission at -8 deg and
    cut-off at 120 deg are symmetric about the valve circle's diameter, so
    delta = (180 - 120 - (-8))/2 = 34 deg, lap = r sin(w_m + delta) = 0.7671 in; the
    relative circle's centre on the cut-off line ag: x_r = r_x sin(w + 90 - w_m); the cut-off
    eccentric is the main one less the relative one (Art. 129): r1 = 1.7352 in,
    delta1 = 84.98 deg (Problem 71's 85 deg); with y = 0 at the latest cut-off,
    L/2 - d = r_x (Art. 143); y for cut-off at w is r_x - r_x sin(w + 90 - w_m) (Art. 142);
    L/2 > e + y_max + r_x (Art. 144), here by ``margin`` (1/8 in), with y_max the 1/8-stroke
    y, and d = L/2 - r_x.
    ``rx_dir_deg`` turns the relative circle off the cut-off line (a poorer design)."""
    r, wm = 1.75 * IN, D(120)
    delta = (math.pi - wm + D(8)) / 2
    lap = r * math.sin(wm + delta)
    rx = 1.5 * IN
    dx = math.pi / 2 - wm + D(rx_dir_deg)
    C1, S1 = r * math.sin(delta) - rx * math.sin(dx), r * math.cos(delta) - rx * math.cos(dx)
    ymax = rx - rx * math.sin(math.acos(0.75) + math.pi / 2 - wm)
    half = 0.75 * IN + ymax + rx + margin * IN
    d = half - rx
    return meyer(r, delta, math.hypot(C1, S1), math.atan2(C1, S1), lap / IN, 2 * half, d, ymax,
                 setting=setting, **kw)


def test_meyer_problem_70_design():
    """Problem 70 by Art. 143: the numbers of the construction (docstring of ``p70``), and the
    gear they give cuts off at 3/4 with the blocks together, at 3/8 and 1/8 stroke with y
    from Art. 142 (y = L/2 - d - s with s = x_r at the cut-off crank angle)."""
    g = p70()
    s = g.spec
    assert math.degrees(s.angular_advance_rad) == pytest.approx(34.0)
    assert s.main.lap_m[0] / IN == pytest.approx(0.7671, abs=1e-4)
    assert s.cutoff_eccentricity_m / IN == pytest.approx(1.7352, abs=1e-4)
    assert math.degrees(s.cutoff_angular_advance_rad) == pytest.approx(84.98, abs=0.01)
    assert head(g)["cutoff_frac"] == pytest.approx(0.75, abs=1e-6)    # touches at w_m
    for frac in (3 / 8, 1 / 8):
        w = math.acos(1 - 2 * frac)
        y = 1.5 * IN - 1.5 * IN * math.sin(w + math.pi / 2 - D(120))
        gy = g.with_setting(y / s.max_half_spacing_m)
        assert gy.spec.cutoff.lap_m[0] == pytest.approx(s.port_span_m / 2 - s.block_length_m - y)
        assert head(gy)["cutoff_frac"] == pytest.approx(frac, abs=1e-9)
        assert end_events(gy, "crank", HARMONIC)["cutoff_frac"] == pytest.approx(frac, abs=1e-9)
    assert g.spec.max_half_spacing_m / IN == pytest.approx(1.2033, abs=1e-4)


def test_meyer_hand_wheel_art_142():
    """Art. 142: "Suppose now ... the blocks b and c are moved closer together.  The
    distance s ... is increased" and the cut-off later; apart, earlier.  Across the screw's
    range of the Art. 143 design steam enters once only."""
    g = p70()
    fr = [head(g.with_setting(x))["cutoff_frac"] for x in np.linspace(0, 1, 6)]
    assert all(a > b for a, b in zip(fr, fr[1:]))
    for x in np.linspace(0, 1, 6):
        assert g.with_setting(x).double_admissions() == {"head": [], "crank": []}


def test_meyer_double_admission_when_the_relative_circle_leaves_the_cut_off_line(caplog):
    """Arts. 142-143: "the point g or h, in which the circle with s as a radius cuts the
    relative valve-circle a second time, must not occur before the main valve cuts off";
    Art. 143 avoids it by putting the relative circle's centre on the main cut-off line.
    With the relative circle turned 40 deg off that line, the blocks near together (a large
    s) let the passage re-open before the main valve cuts off: steam twice, ended by the
    main valve's cut-off at 120 deg; a scene's gear built so logs a warning."""
    bad = p70(rx_dir_deg=40.0, setting=0.1)
    spans = bad.double_admissions()
    assert len(spans["head"]) == 1 and len(spans["crank"]) == 1
    start, end = spans["head"][0]
    assert end == pytest.approx(120.0, abs=1e-6)      # the main valve's cut-off ends it
    with caplog.at_level(logging.WARNING):
        dv.built(bad)
    assert "admitted twice" in caplog.text
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        dv.built(p70(setting=0.1))
    assert "admitted twice" not in caplog.text


def test_meyer_block_length_art_144():
    """Art. 144: "The relative valve-motion should never be so great that the left-hand edge
    of c uncovers the left-hand edge of the passage ...: d + s - r_x > e, or L/2 - y - r_x
    > e".  With the top of the valve 1/10 in too short for that at the widest y, the block
    uncovers the passage from its far side while the relative travel is near its greatest
    (x_r > s + d - e), steam entering a second time until the main valve cuts off; with
    Art. 144's span it does not."""
    g = p70(setting=1.0)       # y = y_max: s least
    s = g.spec.cutoff.lap_m[0]
    assert g.spec.block_length_m + s - 1.5 * IN > 0.75 * IN
    assert g.double_admissions() == {"head": [], "crank": []}
    short = p70(setting=1.0, margin=-0.1)
    sp = short.spec
    assert sp.port_span_m / 2 - sp.max_half_spacing_m - 1.5 * IN < 0.75 * IN
    (start, end), = short.double_admissions()["head"]
    assert end == pytest.approx(120.0, abs=1e-6)


def test_meyer_right_and_left_screw_cannot_equalise_every_cut_off():
    """Problem 72 and Q. 178: stroke 30 in, rod 60 in, r = r1 = 2 1/4 in, delta = 30,
    delta1 = 90 deg, L = 17, e = 2, d = 5 3/8 in; "cut-off exactly at 1/4 stroke and at
    5/8 stroke in each end: what must be the value of y for each block".  Each block's y
    is L/2 - d - s with s = +-x_r at its end's crank angle for that piston position.  Set so
    (one block offset from the other), the gear cuts off at exactly 1/4 in both ends; but the
    offset needed differs between 1/4 and 5/8, so the right-and-left screw, moving both
    blocks alike, cannot keep the cut-offs equal at every setting."""
    R, Lr = 15 * IN, 60 * IN
    r = 2.25 * IN
    C, S = r * math.sin(D(30)) - r, r * math.cos(D(30))
    xr = lambda w: C * math.cos(w) + S * math.sin(w)  # noqa: E731
    ys = {}
    for frac in (0.25, 0.625):
        wh, wc = crank_at(frac, R, Lr, "head"), crank_at(frac, R, Lr, "crank")
        ys[frac] = (8.5 * IN - 5.375 * IN - xr(wh), 8.5 * IN - 5.375 * IN + xr(wc))
    off = {k: v[0] - v[1] for k, v in ys.items()}
    assert abs(off[0.25] - off[0.625]) > 0.05 * IN
    yh, yc = ys[0.25]
    base = min(yh, yc)
    g = meyer(r, D(30), r, D(90), 0.5, 17 * IN, 5.375 * IN, 3.0 * IN, e=2 * IN,
              offset=(yh - base, yc - base), setting=base / (3.0 * IN), width=1.5)
    frac = slider_crank(R, Lr)
    assert end_events(g, "head", frac)["cutoff_frac"] == pytest.approx(0.25, abs=1e-9)
    assert end_events(g, "crank", frac)["cutoff_frac"] == pytest.approx(0.25, abs=1e-9)
    even = g.with_setting((ys[0.625][0] - (yh - base)) / (3.0 * IN))
    assert end_events(even, "head", frac)["cutoff_frac"] == pytest.approx(0.625, abs=1e-9)
    assert abs(end_events(even, "crank", frac)["cutoff_frac"] - 0.625) > 0.005


def test_meyer_exact_converges_to_zeuner():
    """With rods of finite length g each valve's error against Zeuner's form is the rod
    shortfall, of order r^2/(2g): ten times the rod, a tenth the error (within 5 %)."""
    errs = []
    for g_in in (20.0, 200.0, 2000.0):
        ex = p70(motion="exact", eccentric_rod_m=g_in * IN, cutoff_eccentric_rod_m=g_in * IN)
        z = p70()
        errs.append(np.abs(ex.closing_travel(TH) - z.closing_travel(TH)).max()
                    + np.abs(ex.main_travel(TH) - z.main_travel(TH)).max())
    assert 9.5 < errs[0] / errs[1] < 10.5 and 9.5 < errs[1] / errs[2] < 10.5
    # the exact gear is still set for equal lead: the rod correction vanishes at dead centres
    ex = p70(motion="exact", eccentric_rod_m=20 * IN, cutoff_eccentric_rod_m=20 * IN)
    assert ex.main_travel(np.array([0.0, math.pi])) == pytest.approx(
        p70().main_travel(np.array([0.0, math.pi])), abs=1e-15)


def test_gridiron_exact_converges_to_zeuner():
    """As for the Meyer valve: the exact gridiron's error falls tenfold with a tenfold rod."""
    errs = []
    for g_in in (30.0, 300.0):
        ex = p61(motion="exact", eccentric_rod_m=g_in * IN, cutoff_eccentric_rod_m=g_in * IN)
        errs.append(np.abs(ex.cutoff_travel(TH) - p61().cutoff_travel(TH)).max())
    assert 9.5 < errs[0] / errs[1] < 10.5


# ---------------------------------------------------------------------------------------
# Guinotte (Arts. 146-148)

P73 = dict(r=2.75, d=22.5, r1=2.625, d1=30.0, g1=60.0, c1=4.75, r2=1.75, d2=45.0, g2=50.0, c2=5.75)


def p73(setting=1.0, s=0.75):
    """Problem 73: r = 2 3/4 in, delta = 22 1/2, r1 = 2 5/8, d1 = 30, g1 = 60, c1 = 4 3/4,
    r2 = 1 3/4, d2 = 45, g2 = 50, c2 = 5 3/4 (lap and s not given: 1 in and 3/4 in)."""
    p = P73
    return GuinotteGear(GuinotteSpec(main_valve(1.0), dv.CutoffSpec("riding", (s * IN,) * 2,
                                     1.0 * IN, 10 * IN), p["r"] * IN, D(p["d"]),
                                     (p["r1"] * IN, D(p["d1"]), p["g1"] * IN, p["c1"] * IN),
                                     (p["r2"] * IN, D(p["d2"]), p["g2"] * IN, p["c2"] * IN),
                                     setting))


def test_guinotte_centres_on_an_inclined_line_art_147_148():
    """Art. 147: A and B contain u to the first power, "therefore the centre of the
    valve-circles moves in a straight line inclined to os"; Art. 148: at u = c1 the centre
    is that of a Gooch motion with data r1, d1, c1, g1, at u = -c2 that of one with r2, d2,
    c2, g2 and B2 = -r2 (cos d2 - (c2/g2) sin d2).  Problem 73's data."""
    p = P73
    g = p73()
    pts = np.array([g.cutoff_coefficients(u * IN) for u in (-p["c2"], -2.0, 0.0, 2.5, p["c1"])])
    v = pts - pts[0]
    cross = v[1:, 0] * v[-1, 1] - v[1:, 1] * v[-1, 0]
    assert np.all(np.abs(cross) < 1e-15)                        # collinear
    assert abs(pts[-1, 0] - pts[0, 0]) > 0.1 * IN               # not perpendicular to os
    r1, d1, g1, c1 = p["r1"], D(p["d1"]), p["g1"], p["c1"]
    assert pts[-1] / IN == pytest.approx([r1 * (math.sin(d1) + c1 / g1 * math.cos(d1)),
                                          r1 * (math.cos(d1) - c1 / g1 * math.sin(d1))])
    r2, d2, g2, c2 = p["r2"], D(p["d2"]), p["g2"], p["c2"]
    assert pts[0] / IN == pytest.approx([r2 * (math.sin(d2) + c2 / g2 * math.cos(d2)),
                                         -r2 * (math.cos(d2) - c2 / g2 * math.sin(d2))])
    cuts = [head(g.with_setting(x))["cutoff_deg"] for x in (1.0, 0.0, -1.0)]
    assert len(set(round(c, 6) for c in cuts)) == 3


def test_guinotte_with_equal_ends_is_gooch():
    """Art. 146: the Guinotte link is "a Gooch motion similar to Fig. 46, except" for its
    unequal eccentrics, rods and link parts: made equal, Art. 147 reduces to Gooch's
    C = r (sin d + (c/g) cos d), S = (u r / c)(cos d - (c/g) sin d) (Art. 65), as the
    link-motion module gives them."""
    for u in (-5.0, -1.0, 0.0, 3.0, 5.0):
        got = guinotte(2.5, D(25), 55.0, 5.0, 2.5, D(25), 55.0, 5.0, u)
        ref = LinkMotionSpec(kind="gooch", eccentricity_m=2.5, angular_advance_rad=D(25),
                             eccentric_rod_m=55.0, half_link_m=5.0, block_m=u, lap_m=(0, 0),
                             exhaust_lap_m=(0, 0), port_width_m=1, port_length_m=1).coefficients()
        assert got == pytest.approx(ref, abs=1e-14)


# ---------------------------------------------------------------------------------------
# scenes

@pytest.mark.parametrize("name", ["meyer-cutoff", "buckeye-engine"])
def test_scene_gear_drawing_and_settings(name, tmp_path, capsys):
    """Each scene's gear draws its own figure and lists events at several settings; the
    cut-off shortens as the setting rises (hand wheel apart; governor forward)."""
    import json
    from pathlib import Path

    from corliss.cli import commands as cli
    scene = Path(__file__).resolve().parent.parent / "scenes" / f"{name}.toml"
    assert cli.main(["gear", str(scene), "--out", str(tmp_path)]) == 0
    assert (tmp_path / f"{name}.gear.png").read_bytes()[:4] == b"\x89PNG"
    capsys.readouterr()
    assert cli.main(["events", str(scene), "--settings", "0,0.5,1"]) == 0
    rows = json.loads(capsys.readouterr().out)
    cut = [row["head"]["cutoff_frac"] for row in rows]
    assert cut[0] > cut[1] > cut[2]


GEAR_TABLES = {
    "gridiron": dict(eccentricity="2.625 in", angular_advance="18 deg", lap="0.625 in",
                     cutoff_eccentricity="2.625 in", cutoff_angular_advance="-18 deg",
                     seat_port_width="1 in", valve_port_width="1.25 in", lever_ratio=[0.8, 1.1]),
    "polonceau": dict(eccentricity="2.375 in", angular_advance="27 deg", eccentric_rod="57 in",
                      half_link="6 in", lap="0.875 in", cutoff_lap="0.75 in",
                      passage_width="1.5 in", setting=-0.5),
    "guinotte": dict(eccentricity="2.75 in", angular_advance="22.5 deg", lap="1 in",
                     cutoff_eccentricity_1="2.625 in", cutoff_angular_advance_1="30 deg",
                     cutoff_eccentric_rod_1="60 in", link_part_1="4.75 in",
                     cutoff_eccentricity_2="1.75 in", cutoff_angular_advance_2="45 deg",
                     cutoff_eccentric_rod_2="50 in", link_part_2="5.75 in",
                     cutoff_lap="0.75 in", passage_width="1 in", setting=0.5),
}


@pytest.mark.parametrize("kind", sorted(GEAR_TABLES))
def test_scene_tables_of_the_other_gears(kind):
    """The gridiron, Polonceau and Guinotte tables read as the classes are built in the
    tests above (Problems 61, 64, 73), and a misspelt key is refused."""
    import tomllib
    from pathlib import Path

    from corliss.engine.model import build_gear
    from corliss.errors import InputError
    from corliss.scene.loader import scene_from_dict
    path = Path(__file__).resolve().parent.parent / "scenes" / "meyer-cutoff.toml"
    data = tomllib.loads(path.read_text())
    data["valve_gear"] = {"type": kind, "port_width": "1 in", "port_length": "10 in",
                          **GEAR_TABLES[kind]}
    gear = build_gear(scene_from_dict(data))
    ref = {"gridiron": p61(ratio=(0.8, 1.1)), "polonceau": polonceau(-0.5),
           "guinotte": p73(0.5)}[kind]
    assert np.allclose(gear.signed_openings(TH), ref.signed_openings(TH), atol=1e-15)
    data["valve_gear"]["lapp"] = "1 in"
    with pytest.raises(InputError, match="lapp"):
        scene_from_dict(data)


def test_a_scene_that_admits_twice_warns(caplog):
    """The gear a scene builds logs the second admission of its setting (Art. 118)."""
    import tomllib
    from pathlib import Path

    from corliss.engine.model import build_gear
    from corliss.scene.loader import scene_from_dict
    path = Path(__file__).resolve().parent.parent / "scenes" / "meyer-cutoff.toml"
    data = tomllib.loads(path.read_text())
    data["valve_gear"] = {"type": "gridiron", "port_width": "1 in", "port_length": "10 in",
                          **GEAR_TABLES["gridiron"], "cutoff_eccentricity": "1.3 in",
                          "lever_ratio": [1.0, 1.0]}
    with caplog.at_level(logging.WARNING):
        build_gear(scene_from_dict(data))
    assert "admitted twice in the head-end stroke" in caplog.text
