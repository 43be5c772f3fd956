"""The Hamilton-Corliss gear (Spangler Ch. XX, Arts. 155-157): wrist plate, four rotary
valves, trip and dash-pot, against the book's statements and closed forms."""

import math

import numpy as np
import pytest

from corliss.errors import InputError
from corliss.keys.toml_table import Table
from corliss.valves.corliss_gear import CorlissGear, CorlissSpec, ValveChain, parse_corliss
from corliss.valves.events import end_events

IN = 0.0254
HARMONIC = lambda t: (1 - math.cos(t)) / 2  # noqa: E731
RPM = 2.0 * math.pi / 60.0
TWO_PI = 2.0 * math.pi

# A 20 x 42 Corliss (the scene corliss-trip-gear): Art. 157's proportions, wrist plate
# radius 11 in, throw 3.5 in, steam lap 1/2 in, exhaust open 0.1 in at mid position.
STEAM = ValveChain(6 * IN, math.radians(25), 4 * IN, math.radians(-45), 30 * IN, 2.5 * IN)
EXHAUST = ValveChain(6 * IN, math.radians(30), 4 * IN, math.radians(-45), 24 * IN, 3.0 * IN)


def spec(**kw):
    base = dict(eccentricity_m=3.5 * IN, angular_advance_rad=math.radians(32),
                hook_rod_m=120 * IN, wrist_plate_radius_m=11 * IN, steam=STEAM,
                exhaust=EXHAUST, steam_lap_m=(0.5 * IN,) * 2, exhaust_lap_m=(-0.1 * IN,) * 2,
                steam_port_width_m=1.25 * IN, exhaust_port_width_m=1.875 * IN,
                port_length_m=22 * IN, dashpot_closing_time_s=0.04, setting=0.5)
    base.update(kw)
    return CorlissSpec(**base)


@pytest.fixture(scope="module")
def gear():
    return CorlissGear(spec()).with_speed(80 * RPM)


@pytest.fixture(scope="module")
def harmonic():
    return CorlissGear(spec(motion="harmonic")).with_speed(80 * RPM)


def test_toggle_action_dwell_when_closed_fast_at_the_port_edge(gear):
    """Art. 156: "The steam-valves should therefore open on that portion of their motion
    where j is moving away from oq and ql is approaching it" (and the exhaust valves
    likewise): the valve moves slowly while it is well closed and fast past the port
    edge.  Measured per unit of wrist-plate turn, dX/du at the end of the plate's swing
    that closes the valve is well under (here less than 0.6 of) its value where the edge
    crosses the port (the linear gear of Art. 156's formula has the ratio 1).  For the
    steam chain the stud is then nearer the line of the rod than at the port edge."""
    psi = gear.plate_angle(np.linspace(0.0, TWO_PI, 1441))
    u = np.linspace(-psi.max(), psi.max(), 2001)
    for chain, lap in ((STEAM, 0.5 * IN), (EXHAUST, -0.1 * IN)):
        X = chain.valve_arc(u)
        dX = np.gradient(X, u)
        edge = int(np.argmin(abs(X - lap)))
        assert dX[0] < 0.6 * dX[edge]
        assert np.all(dX > 0.0)                     # no dead point inside the swing
    # the stud's angle to the rod at the closed end and at the port edge
    X = STEAM.valve_arc(u)
    edge = int(np.argmin(abs(X - 0.5 * IN)))

    def stud_to_rod(k):
        a = STEAM.stud_angle_rad + u[k]
        j = STEAM.stud_radius_m * np.array([math.cos(a), math.sin(a)])
        g = float(STEAM.arm_angle(u[k]))
        l_ = np.array([STEAM.spindle_distance_m - STEAM.arm_m * math.cos(g),
                       STEAM.arm_m * math.sin(g)])
        rod = (l_ - j) / np.linalg.norm(l_ - j)
        return abs(math.sin(math.atan2(j[1], j[0]) - math.atan2(rod[1], rod[0])))

    assert stud_to_rod(0) < stud_to_rod(edge)


def test_latched_valve_closes_where_it_opened(gear):
    """Art. 156: "the steam-port opens when the valve has moved from its central position
    a distance equal to the lap, and if the automatic cut-off does not interfere, closes
    again at the same point": each valve's position is a function of the wrist plate's
    angle alone, so the plate stands at the same angle at latched admission and closure
    (to the root finder's 1e-13 rad, widened to 1e-9 for the plate's solution)."""
    for w in gear._geom["windows"]:
        p_open, p_close = gear.plate_angle(np.array([w["open"], w["close"]]))
        assert abs(p_open - p_close) < 1e-9


def test_mid_position_laps(gear):
    """Art. 157: with the wrist plate in its middle position the steam valves lap the
    ports (here by 1/2 in, within the book's 7/16 to 1/2 in for larger sizes) and "the
    exhaust-port is open from 1/16 to 1/8 inch" (here 0.1 in, both ends at once)."""
    th = np.linspace(0.0, TWO_PI, 7201)
    psi = gear.plate_angle(th)
    k = int(np.nonzero((psi[:-1] > 0) & (psi[1:] <= 0))[0][0])
    t0 = th[k] + (th[k + 1] - th[k]) * psi[k] / (psi[k] - psi[k + 1])
    s = gear.latched_signed_openings(np.array([t0]))[:, 0]
    # linear interpolation of psi on a 0.05 deg grid: error ~ psi'' h^2 / 8 < 1e-7 rad,
    # times a valve gear ratio of a few inches per radian
    assert s == pytest.approx([-0.5 * IN, 0.1 * IN, -0.5 * IN, 0.1 * IN], abs=1e-6)


def test_art_156_formula_when_stud_and_arm_are_square_to_the_rod():
    """Art. 156: x = (rad. valve / ql)(oj / of)(de / dc) r sin(w + d).  With the stud and
    the arm square to the rod at mid position the exact chain's gear ratio there is
    dX/du = R_v oj / ql (velocities of j and l both across the rod), whatever the rod's
    slant, and the harmonic motion is Art. 156's.  Finite-difference step 1e-5 rad:
    error ~ h^2 X''' ~ 1e-12 m/rad."""
    for rho, a in ((6.0, 6.0), (6.0, 4.0), (5.0, 7.0)):
        ch = ValveChain(rho * IN, math.pi / 2, a * IN, math.pi / 2, 30 * IN, 2.5 * IN)
        assert ch.ratio_at_mid() == pytest.approx(2.5 * IN * rho / a, rel=1e-8)
    g = CorlissGear(spec(steam=ValveChain(6 * IN, math.pi / 2, 4 * IN, math.pi / 2, 30 * IN,
                                          2.5 * IN), motion="harmonic"))
    th = np.linspace(0.0, TWO_PI, 37)
    x = (2.5 / 4.0) * (6.0 / 11.0) * 3.5 * IN * np.sin(th + math.radians(32))
    assert g.valve_arcs(th)[0] == pytest.approx(x, abs=1e-12)


def test_exact_linkage_tends_to_the_harmonic_motion_as_rods_grow():
    """Art. 156's derivation takes every rod as moving its pin along the line of stroke
    (infinite rods).  With stud and arm square to the rod (oj = ql so the rod lies on
    the line of centres), infinite hook rod and valve rod give psi = asin(r sin(w + d) /
    of) and X = R_v asin((oj / ql) sin psi) exactly; the finite rods' error falls like
    1 / length (checked: a rod ten times longer, under 0.15 of the error, allowing for
    the 1 / L^2 remainder).  That closed form tends in its turn to Art. 156's
    k r sin(w + d) as r / of -> 0, with a relative error O((r / of)^2): under 1e-3 at
    r / of = 0.02."""
    th = np.linspace(0.0, TWO_PI, 361)
    delta = math.radians(32)

    def err(scale, r_in=3.5):
        ch = ValveChain(5 * IN, math.pi / 2, 5 * IN, math.pi / 2, 30 * IN * scale, 2.5 * IN)
        g = CorlissGear(spec(steam=ch, hook_rod_m=120 * IN * scale, eccentricity_m=r_in * IN,
                             steam_lap_m=(0.1 * r_in * IN,) * 2))
        psi = np.arcsin(r_in * np.sin(th + delta) / 11.0)
        limit = 2.5 * IN * np.arcsin(np.sin(psi))
        return np.abs(g.valve_arcs(th)[0] - limit).max(), limit

    e1, _ = err(1.0)
    e10, _ = err(10.0)
    e100, _ = err(100.0)
    assert e10 < 0.15 * e1 and e100 < 0.15 * e10
    r_small = 0.02 * 11.0
    _, limit = err(1.0, r_small)
    zeuner = 2.5 * IN * (r_small / 11.0) * np.sin(th + delta)
    assert np.abs(limit - zeuner).max() < 1e-3 * np.abs(zeuner).max()


def test_cut_off_follows_the_cam_and_stops_at_the_limit_of_the_trip(harmonic):
    """Art. 155: "The governor causes the collar C and the cam F to move, thus varying
    the point at which the hook disengages, and thus varying the cut-off."  Cut-off
    grows with the cam position up to s = 1, where the hook lets go at the end of its
    travel (the wrist plate's extreme, w = 90 deg - d for x = k r sin(w + d)); beyond,
    the cam cannot reach the hook, there is no release, and the valve closes with the
    wrist plate at its lap (Art. 156: "if the automatic cut-off does not interfere,
    closes again at the same point"): at w = 180 deg - d - asin(lap / k r).  The
    trip's longest cut-off is release at the extreme plus the dash-pot's omega T."""
    g = harmonic
    kr = g._geom["k_steam"] * 3.5 * IN / (11 * IN)
    cuts = [end_events(g.with_setting(s), "head", HARMONIC)["cutoff_deg"]
            for s in (0.2, 0.4, 0.6, 0.8, 1.0)]
    assert all(a < b for a, b in zip(cuts, cuts[1:]))
    rel_max = g.release_angle_rad(1.0)[0]
    assert math.degrees(rel_max) == pytest.approx(90.0 - 32.0, abs=1e-5)   # bounded search
    omega_t = 80 * RPM * 0.04
    assert cuts[-1] == pytest.approx(math.degrees(rel_max + omega_t), abs=1e-6)
    assert g.release_angle_rad(1.2) == (None, None)
    late = end_events(g.with_setting(1.2), "head", HARMONIC)["cutoff_deg"]
    assert late == pytest.approx(180.0 - 32.0 - math.degrees(math.asin(0.5 * IN / kr)),
                                 abs=1e-9)
    assert late > cuts[-1]


def test_dash_pot_closes_in_time_so_cut_off_comes_later_at_speed(gear):
    """Art. 155: once unhooked the valve is "closed by means of the rod H, the lower end
    of which is attached to a dash-pot": it closes in its own time T, during which the
    crank turns omega T, so for the same cam the cut-off comes later at a higher speed:
    cut-off = release + omega T exactly (the events' bisection, 1e-13 rad)."""
    rel = gear.release_angle_rad()[0]
    cuts = {}
    for rpm in (60.0, 80.0, 100.0):
        g = gear.with_speed(rpm * RPM)
        cuts[rpm] = math.radians(end_events(g, "head", HARMONIC)["cutoff_deg"])
        assert cuts[rpm] == pytest.approx(rel + rpm * RPM * 0.04, abs=1e-9)
    assert cuts[60.0] < cuts[80.0] < cuts[100.0]


def test_tripped_opening_is_the_latched_one_capped_by_the_dash_pot(gear):
    """The contract the speed loop relies on: after release, within the admission, the
    steam port is open min(latched, opening at release x closing_fraction(time since
    release)); latched elsewhere; the exhaust ports always latched.  The closing law
    (a valve let go from rest, moving like a falling weight) is 1 - (t / T)^2 up to T,
    0 after."""
    th = np.linspace(0.0, TWO_PI, 2881)
    lat = gear.latched_signed_openings(th)
    act = gear.signed_openings(th)
    assert np.array_equal(act[[1, 3]], lat[[1, 3]])
    T, omega = 0.04, 80 * RPM
    for e, port in enumerate((0, 2)):
        w = gear._geom["windows"][e]
        rel = gear.release_angle_rad()[e]
        p_rel = float(gear.latched_signed_openings(np.array([rel]))[port, 0])
        since = (th - rel) % TWO_PI
        inside = since <= (w["close"] - rel) % TWO_PI
        tau = since / omega
        want = np.where(inside, np.minimum(lat[port],
                                           p_rel * np.clip(1 - (tau / T) ** 2, 0, 1)), lat[port])
        assert act[port] == pytest.approx(want, abs=1e-12)
    f = gear.closing_fraction(np.array([0.0, 0.5 * T, T, 2 * T]))
    assert f == pytest.approx([1.0, 0.75, 0.0, 0.0])


def test_safety_cam_admits_no_steam(gear):
    """Art. 155: "The cam G is to insure the hook w disengaging, if the arm v travels too
    far downwards": with the governor down (belt broken) the hook is held off and the
    steam valves are not opened.  Below s = 0 no steam port opens in the whole turn; the
    exhaust valves go on as before."""
    g = gear.with_setting(-0.1)
    s = g.signed_openings(np.linspace(0.0, TWO_PI, 7201))
    assert s[0].max() <= 0.0 and s[2].max() <= 0.0
    ev = end_events(g, "head", HARMONIC)
    assert ev["admission_deg"] is None and ev["cutoff_deg"] is None
    assert ev["release_deg"] == pytest.approx(end_events(gear, "head", HARMONIC)["release_deg"])


def test_art_157_design_ratio_gives_the_lead():
    """Art. 157: "If in this equation we put the value of d ... and make x = lap + lead,
    and w = 0, we have a ratio for oj / ql".  Designing oj / ql so from Art. 156's
    formula (lap 1/2 in, lead 1/16 in, d = 30 deg, r = 3.5 in, of = 11 in, valve radius
    2.5 in) the harmonic gear opens the head port by the lead at the dead point."""
    lap, lead, d = 0.5 * IN, IN / 16, math.radians(30)
    ratio = (lap + lead) * 11.0 / (2.5 * 3.5 * IN * math.sin(d))      # oj / ql
    ch = ValveChain(ratio * 4 * IN, math.pi / 2, 4 * IN, math.pi / 2, 30 * IN, 2.5 * IN)
    g = CorlissGear(spec(steam=ch, motion="harmonic", angular_advance_rad=d,
                         steam_lap_m=(lap, lap)))
    assert g.latched_signed_openings(np.array([0.0]))[0, 0] == pytest.approx(lead, abs=1e-9)


def _table(**over):
    d = {"type": "corliss", "eccentricity": "3.5 in", "angular_advance": "32 deg",
         "hook_rod": "120 in", "wrist_plate_radius": "11 in",
         "steam_stud_radius": "6 in", "steam_stud_angle": "25 deg", "steam_arm": "4 in",
         "steam_arm_angle": "-45 deg", "steam_spindle_distance": "30 in",
         "steam_valve_radius": "2.5 in", "exhaust_stud_radius": "6 in",
         "exhaust_stud_angle": "30 deg", "exhaust_arm": "4 in", "exhaust_arm_angle": "-45 deg",
         "exhaust_spindle_distance": "24 in", "exhaust_valve_radius": "3 in",
         "steam_lap": "0.5 in", "exhaust_lap": "-0.1 in", "steam_port_width": "1.25 in",
         "exhaust_port_width": "1.875 in", "port_length": "22 in",
         "dashpot_closing_time": "0.04 s", "setting": 0.5}
    d.update(over)
    return Table(d, "valve_gear")


def test_parse_laps_as_angles_and_errors_name_the_key():
    """A lap may be given as a spindle angle: the arc is R_v x angle (Art. 156's
    "rad. valve")."""
    sp = parse_corliss(_table(steam_lap=f"{math.degrees(0.2):.12f} deg"))
    assert sp.steam_lap_m == pytest.approx((0.5 * IN, 0.5 * IN), rel=1e-10)
    with pytest.raises(InputError, match="valve_gear.setting"):
        parse_corliss(_table(setting=2.0))
    with pytest.raises(InputError, match="valve_gear.dashpot_closing_time"):
        parse_corliss(_table(dashpot_closing_time="0 s"))
    with pytest.raises(InputError, match="valve_gear.steam_lap"):
        parse_corliss(_table(steam_lap="3 in"))              # never opens
