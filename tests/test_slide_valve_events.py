"""Slide-valve events against the Zeuner closed forms and Marks's finite-rod analysis."""

import math

import numpy as np
import pytest

from corliss import scene_events
from corliss.engine.model import build_gear, geometry_of

from conftest import make_scene

IN = 0.0254
R, LH, LC, EH, EC, DELTA_DEG, W = 3.0, 1.0, 0.875, 0.125, -0.0625, 30.0, 1.25


def zeuner_scene(**gear):
    g = {"eccentricity": f"{R} in", "lap": [f"{LH} in", f"{LC} in"],
         "exhaust_lap": [f"{EH} in", f"{EC} in"], "lead": None,
         "angular_advance": f"{DELTA_DEG} deg", "port_width": f"{W} in", "eccentric_rod": None}
    g.update(gear)
    return make_scene(valve_gear=g)


def test_events_equal_zeuner_closed_forms():
    """Spangler Arts. 12-18, pp. 10-19: with x = r sin(theta + delta), the head end
    admits at asin(l/r) - delta, cuts off at 180 - asin(l/r) - delta, releases at
    180 + asin(e/r) - delta and compresses at 360 - asin(e/r) - delta; the crank end's
    port opens on -x, so its events are the same forms shifted by 180 deg.  Lead
    r sin(delta) - l (Art. 14); greatest opening r - l, limited by the port width (Art. 19).
    Tolerance 1e-6 deg: the events are found by bisection to 1e-9 rad."""
    ev = scene_events(zeuner_scene())
    d = DELTA_DEG
    a = lambda v: math.degrees(math.asin(v / R))  # noqa: E731
    want = {
        "head": dict(admission_deg=a(LH) - d, cutoff_deg=180 - a(LH) - d,
                     release_deg=180 + a(EH) - d, compression_deg=360 - a(EH) - d),
        "crank": dict(admission_deg=180 + a(LC) - d, cutoff_deg=360 - a(LC) - d,
                      release_deg=a(EC) - d, compression_deg=180 - a(EC) - d),
    }
    for end, w in want.items():
        for k, v in w.items():
            assert ev[end][k] == pytest.approx(v % 360.0, abs=1e-6), (end, k)
    s = math.sin(math.radians(d))
    assert ev["head"]["lead_m"] == pytest.approx((R * s - LH) * IN, abs=1e-12)
    assert ev["crank"]["lead_m"] == pytest.approx((R * s - LC) * IN, abs=1e-12)
    assert ev["head"]["max_port_opening_m"] == pytest.approx(min(R - LH, W) * IN, rel=1e-6)
    assert ev["head"]["overtravel_m"] == pytest.approx((R - LH - W) * IN, rel=1e-5)


def test_fractions_follow_the_slider_crank():
    """Cut-off fraction of the head end = s(theta_c)/S with
    s = R(1 - cos) + L - sqrt(L^2 - R^2 sin^2) (Marks Art. 96 III); the crank end's is
    measured from its own dead centre, 1 - s/S."""
    sc = zeuner_scene()
    ev = scene_events(sc)
    Rc, L = 12.0, 60.0
    for end in ("head", "crank"):
        th = math.radians(ev[end]["cutoff_deg"])
        s = Rc * (1 - math.cos(th)) + L - math.sqrt(L * L - (Rc * math.sin(th)) ** 2)
        f = s / 24.0 if end == "head" else 1 - s / 24.0
        assert ev[end]["cutoff_frac"] == pytest.approx(f, abs=1e-9)
    # rod angularity makes the head end cut off later in its stroke than the crank end
    # for equal laps (Spangler Art. 31)
    ev2 = scene_events(zeuner_scene(lap="1 in", exhaust_lap="0 in"))
    assert ev2["head"]["cutoff_frac"] > ev2["crank"]["cutoff_frac"] + 0.02


def test_finite_rod_adds_marks_missing_quantity():
    """Marks Art. 96 eq. 229: with a finite eccentric rod l and the valve set for equal
    lead, xi = r sin(w + delta) + (r^2/2l) sin(2 delta + w) sin w, for the arrangement of
    his model.  Ours for a reverse lever equals that to the next term of the binomial
    series, r^4/(8 l^3); a direct connection has the opposite sign."""
    g_in = 20.0
    th = np.linspace(0, 2 * math.pi, 721)
    d = math.radians(DELTA_DEG)
    z = (R * R / (2 * g_in)) * np.sin(2 * d + th) * np.sin(th) * IN
    zeuner = R * IN * np.sin(th + d)
    bound = R ** 4 / (8 * g_in ** 3) * IN * 1.01
    for conn, sign in (("reverse_lever", 1.0), ("direct", -1.0)):
        gear = build_gear(zeuner_scene(eccentric_rod=f"{g_in} in", connection=conn))
        err = gear.travel(th) - (zeuner + sign * z)
        assert np.max(np.abs(err)) < bound, conn
    # steam inside through a reverse lever moves the valve as steam outside, direct
    a = build_gear(zeuner_scene(eccentric_rod=f"{g_in} in"))
    b = build_gear(zeuner_scene(eccentric_rod=f"{g_in} in", connection="reverse_lever",
                                steam="inside"))
    assert np.allclose(a.signed_openings(th), b.signed_openings(th), atol=1e-15)


def _shift(ev_rod, ev_z, end, key):
    return ((ev_rod[end][key] - ev_z[end][key] + 180.0) % 360.0) - 180.0


def test_finite_rod_shifts_events_as_marks_describes():
    """Marks Art. 96 (pp. 257-258), for his model (the reverse sense in our terms,
    see the test above): while the piston moves toward the shaft (the head-end stroke)
    the missing quantity delays pre-admission, increases over-travel, hastens cut-off,
    compression and release; moving away (the crank-end stroke) the reverse.  The
    direct connection mirrors every shift.  Leads stay equal (valve set for equal lead)."""
    ez = scene_events(zeuner_scene())
    for conn, s in (("reverse_lever", 1), ("direct", -1)):
        er = scene_events(zeuner_scene(eccentric_rod="20 in", connection=conn))
        # stroke toward the shaft: head admission/cut-off/release, crank compression
        assert s * _shift(er, ez, "head", "admission_deg") > 0.05
        assert s * _shift(er, ez, "head", "cutoff_deg") < -0.05
        assert s * _shift(er, ez, "head", "release_deg") < -0.05
        assert s * _shift(er, ez, "crank", "compression_deg") < -0.05
        assert s * (er["head"]["overtravel_m"] - ez["head"]["overtravel_m"]) > 0
        # stroke away from the shaft: the reverse
        assert s * _shift(er, ez, "crank", "admission_deg") < -0.05
        assert s * _shift(er, ez, "crank", "cutoff_deg") > 0.05
        assert s * _shift(er, ez, "crank", "release_deg") > 0.05
        assert s * _shift(er, ez, "head", "compression_deg") > 0.05
        assert s * (er["crank"]["overtravel_m"] - ez["crank"]["overtravel_m"]) < 0
        for end in ("head", "crank"):
            assert er[end]["lead_m"] == pytest.approx(ez[end]["lead_m"], abs=1e-12)


def test_port_that_never_closes_or_opens_is_reported_as_null():
    """Exhaust clearance larger than the eccentricity's reach keeps the exhaust open
    all the time: release and compression never happen (null), with no crash."""
    ev = scene_events(zeuner_scene(exhaust_lap="-3.2 in"))
    assert ev["head"]["release_deg"] is None and ev["head"]["compression_deg"] is None


def test_portmap_is_exact_at_the_kinks():
    """The tabulated areas equal the gear's own areas at every kink and between grid
    points to the linear-interpolation error of a 0.25 deg grid."""
    from corliss.valves import tabulate
    sc = make_scene()
    gear = build_gear(sc)
    pm = tabulate(gear, 1440)
    exact = gear.areas(pm.breakpoints_rad)
    table = np.array([pm.areas(t) for t in pm.breakpoints_rad]).T
    assert np.allclose(table, exact, atol=1e-12)
    th = np.random.default_rng(1).uniform(0, 2 * math.pi, 200)
    table = np.array([pm.areas(t) for t in th]).T
    # second derivative of area <= r * length; grid 0.25 deg: error <= r L h^2 / 8
    h = math.radians(0.25)
    bound = 3 * IN * 9.6 * IN * h * h / 8
    assert np.max(np.abs(table - gear.areas(th))) <= bound
    geo = geometry_of(sc)
    assert geo.rod_angularity
