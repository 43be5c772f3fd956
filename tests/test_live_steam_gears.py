"""The slip eccentric, the oscillating cylinder and the Baker gear: events against
independent calculations, reversal and port geometry, published statements on the
Baker gear, and the bundled scenes through run, animate and design."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from corliss.cli import commands as cli
from corliss.engine.model import build_gear, scene_events
from corliss.errors import InputError
from corliss.scene.loader import find_scene, load_scene, scene_from_dict
from corliss.valves.baker import BakerGear, baker_layout
from corliss.valves.events import events
from corliss.valves.oscillating import OscillatingCylinder, swing_angle
from corliss.valves.slip_eccentric import SlipEccentric, SlipEccentricSpec

IN = 0.0254
#: Events are found by the gear's root finder to 1e-13 rad; the closed forms are exact:
#: 1e-9 deg is far above both and far below any error of substance.
EXACT_DEG = 1e-9


def _harmonic(theta):
    """Fraction of stroke with an infinite rod, (1 - cos) / 2."""
    return 0.5 * (1.0 - math.cos(theta))


def _deg_close(a, b, tol):
    return abs((a - b + 180.0) % 360.0 - 180.0) <= tol


# ----------------------------------------------------------------------- slip eccentric

def _slip(fwd_deg, back_deg, direction, lap_in=0.1, exh_in=0.02):
    spec = SlipEccentricSpec(
        eccentricity_m=0.3 * IN, lap_m=(lap_in * IN,) * 2, exhaust_lap_m=(exh_in * IN,) * 2,
        angular_advance_rad=0.0, port_width_m=0.19 * IN, port_length_m=1.5 * IN,
        forward_advance_rad=math.radians(fwd_deg), backward_advance_rad=math.radians(back_deg))
    return SlipEccentric(spec.running(direction))


@pytest.mark.parametrize("fwd, back, direction, lap", [
    (20.0, 35.0, "ahead", 0.10), (20.0, 35.0, "astern", 0.10), (30.0, 30.0, "ahead", 0.05)])
def test_slip_eccentric_events_against_the_closed_form(fwd, back, direction, lap):
    """Zeuner's valve, x = r sin(theta + delta) with delta the driving stop's advance
    (Spangler Art. 13): the head port opens where x = l, at theta + delta = asin(l/r),
    and closes at theta + delta = 180 deg - asin(l/r); the exhaust opens where
    -x = e, at theta + delta = 180 deg + asin(e/r), and closes at 360 deg - asin(e/r)."""
    g = _slip(fwd, back, direction, lap_in=lap)
    ev = events(g, _harmonic)["head"]
    d = fwd if direction == "ahead" else back
    r, l, e = 0.3, lap, 0.02
    want = {"admission_deg": math.degrees(math.asin(l / r)) - d,
            "cutoff_deg": 180.0 - math.degrees(math.asin(l / r)) - d,
            "release_deg": 180.0 + math.degrees(math.asin(e / r)) - d,
            "compression_deg": 360.0 - math.degrees(math.asin(e / r)) - d}
    for key, deg in want.items():
        assert _deg_close(ev[key], deg % 360.0, EXACT_DEG), (key, ev[key], deg)


def test_slip_eccentric_reversal_against_the_stops_geometry():
    """The stops' geometry in a fixed frame, counter-clockwise ahead: the eccentric is
    90 + delta_f ahead of the crank on the forward stop; running backward the shaft
    turns inside the sheave through the slip, 180 - delta_f - delta_b, so that the
    eccentric then stands at the crank's angle + 90 + delta_f + slip.  The valve is the
    eccentric's projection on the line of stroke, -r cos(angle) (so that ahead it is
    r sin(theta + delta_f)); astern the crank is at -theta.  The gear's astern travel
    must be that projection, and its slip that angle."""
    g = _slip(20.0, 35.0, "ahead")
    astern = g.reversed()
    r = g.spec.eccentricity_m
    df, db = math.radians(20.0), math.radians(35.0)
    slip = math.pi - df - db
    assert astern.spec.slip_rad == pytest.approx(slip, abs=1e-15)
    th = np.linspace(0.0, 2 * math.pi, 37)
    ahead_angle = th + math.pi / 2 + df
    np.testing.assert_allclose(g.travel(th), -r * np.cos(ahead_angle), atol=1e-15)
    astern_angle = -th + math.pi / 2 + df + slip
    np.testing.assert_allclose(astern.travel(th), -r * np.cos(astern_angle), atol=1e-15)
    assert astern.reversed().spec == g.spec
    # a wrong slip (the stops a degree further apart) would not give that travel
    wrong = -r * np.cos(-th + math.pi / 2 + df + slip + math.radians(1.0))
    assert np.max(np.abs(astern.travel(th) - wrong)) > 1e-3 * r


def _slip_scene(**gear):
    scene = load_scene(find_scene("slip-eccentric-launch"))
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in scene.data.items()}
    data["valve_gear"].update(gear)
    return data


def test_slip_eccentric_card_is_the_same_either_way_with_equal_advances():
    """Equal advances: the valve moves the same in the engine's own direction of
    rotation either way, so the astern card (and its work) is the ahead card."""
    from corliss.engine.simulate import simulate
    ahead = simulate(scene_from_dict(_slip_scene(direction="ahead"), name="ahead"))
    astern = simulate(scene_from_dict(_slip_scene(direction="astern"), name="astern"))
    assert astern.summary["indicated_work_J_per_cycle"] == pytest.approx(
        ahead.summary["indicated_work_J_per_cycle"], rel=1e-12)
    for end in ("head", "crank"):
        np.testing.assert_array_equal(astern.cards[end]["p_Pa"].to_numpy(),
                                      ahead.cards[end]["p_Pa"].to_numpy())


def test_slip_eccentric_load_step_running_astern():
    """A load step with the engine reversed (running astern on the backward stop, with
    less advance than ahead): the transient runs, the speed falls after the step, and
    the astern valve is the one it ran on (its cut-off later than ahead's)."""
    from corliss.engine.simulate import simulate
    data = _slip_scene(direction="astern", forward_advance="35 deg", backward_advance="25 deg")
    data["flywheel"] = {"rim_weight": "60 lb", "mean_radius": "7 in"}
    data["load"] = {"power": "4 hp", "kind": "step", "step_time": "0.6 s", "step_fraction": 1.3}
    data["run"] = dict(data["run"], mode="transient", duration="1.5 s")
    scene = scene_from_dict(data, name="astern-step")
    ev = scene_events(scene)
    ahead = scene_events(scene_from_dict(_slip_scene(direction="ahead", forward_advance="35 deg",
                                                     backward_advance="25 deg"), name="a"))
    assert ev["head"]["cutoff_frac"] > ahead["head"]["cutoff_frac"]
    res = simulate(scene)
    t = res.timeseries["time_s"].to_numpy()
    rpm = res.timeseries["speed_rpm"].to_numpy()
    before = rpm[(t > 0.55) & (t < 0.6)].mean()
    after = rpm[t > 1.4].mean()
    assert np.all(np.isfinite(rpm)) and after < before


def _reversing_run():
    """The bundled scene slip-eccentric-reversing: the launch engine's cylinder (Zeuner's
    motion: no eccentric rod; advances 30 deg ahead, 20 deg astern, so the slip is 130
    deg) hauling a constant-torque load that steps to 2.5 times at 0.25 s: more than
    the engine can carry, the load overhauls it (a weight being lowered), stops it and
    turns it backward."""
    from corliss.engine.simulate import simulate
    scene = load_scene(find_scene("slip-eccentric-reversing"))
    return scene, simulate(scene)


@pytest.fixture(scope="module")
def reversing():
    return _reversing_run()


def test_overhauling_load_reverses_the_slip_eccentric(reversing):
    """Through the change of direction, the valve is where the stops put the eccentric
    (module doc of corliss.valves.slip_eccentric; Zeuner's valve x = r sin(angle +
    advance), Spangler Art. 13).  Ahead, on the forward stop: x = r sin(theta +
    delta_f).  Where the speed crosses zero, at theta_r, the shaft turns back inside
    the sheave, which stands: x stays r sin(theta_r + delta_f) while the shaft turns
    back through the slip, 180 - delta_f - delta_b = 130 deg, computed here from the
    scene's advances.  From there the backward stop drives: x = r sin(-theta +
    delta_b) (theta positive ahead, so -theta is the angle in the direction of
    rotation).  The valve is the gear's own travel at the sheave's place, so 1e-12 m
    is rounding; the angle where the backward stop takes over is found by the
    integrator's event to far better than 1e-6 deg, as is the zero of the speed."""
    scene, res = reversing
    ts = res.timeseries
    rev = ts[ts["valve_m"].notna()]
    th = np.radians(rev["crank_angle_deg"].to_numpy())
    w = rev["speed_rpm"].to_numpy()
    x = rev["valve_m"].to_numpy()
    slip_deg = rev["eccentric_slip_deg"].to_numpy()
    r = 0.3 * IN
    df, db = math.radians(30.0), math.radians(20.0)
    slip = math.pi - df - db
    # the speed crosses zero once, from ahead to astern
    i = int(np.nonzero((w[:-1] > 0.0) & (w[1:] <= 0.0))[0][0])
    assert np.all(w[:i + 1] > 0.0) and np.all(w[i + 1:] < 0.0)
    # where it turned back: the sample of least speed, the first past zero (within
    # 1e-6 of the run speed, where the shaft stands still to far below 1e-9 rad)
    assert abs(w[i + 1]) < 1e-6 * 500.0
    th_r = th[i + 1]
    ahead = slip_deg == 0.0
    back = np.isclose(slip_deg, math.degrees(slip), rtol=0.0, atol=1e-9)
    standing = ~ahead & ~back
    assert ahead[:i + 1].all() and standing.any() and back.any()
    np.testing.assert_allclose(x[ahead], r * np.sin(th[ahead] + df), atol=1e-12)
    np.testing.assert_allclose(x[standing], r * math.sin(th_r + df), atol=1e-12)
    np.testing.assert_allclose(x[back], r * np.sin(-th[back] + db), atol=1e-12)
    # the backward stop takes the sheave where the shaft has turned back the slip
    th_e = th[np.argmax(back)]
    assert math.degrees(th_r - th_e) == pytest.approx(math.degrees(slip), abs=1e-6)
    assert np.all(th[standing] <= th_r + 1e-9) and np.all(th[standing] >= th_e - 1e-9)


def test_the_final_state_is_read_after_the_change_of_direction(reversing):
    """The summary's final speed, power and steam are those of the engine running
    backward: a turn through the change of direction has a net speed (its angle over its
    time), neither direction's, and the turns before it ran ahead.  So the final speed
    lies within the turn-mean speeds of the backward turns (all negative, growing), and
    the power and steam within theirs; averaged with the turns before the change of
    direction (the last five turns regardless) the final speed read -185 rpm on a run
    ending near -913 rpm."""
    scene, res = reversing
    c = res.cycles
    k = int(np.nonzero((c["speed_start_rpm"] > 0) & (c["speed_end_rpm"] < 0))[0][-1])
    after = c.iloc[k + 1:]
    s = res.summary
    assert after["mean_speed_rpm"].min() <= s["final_speed_rpm"] <= after["mean_speed_rpm"].max()
    for key, col in (("final_indicated_power_W", "indicated_power_W"),
                     ("final_steam_rate_kg_per_h", "steam_rate_kg_per_h")):
        assert after[col].min() <= s[key] <= after[col].max(), key


def test_engine_runs_backward_under_steam_after_the_slip(reversing):
    """After the change of direction the turns run backward (negative mean speeds,
    growing), the steam doing positive work in the direction of rotation on the
    backward stop's valve, and the flywheel's energy across the change of direction
    balances the work: 1/2 I (w1^2 - w0^2) = W_gas - W_load - W_friction over the
    span from the start of the turn that stalled to the dead centre where the loop
    runs on backward (the shaft equation integrated; the loop's tolerance, 1e-6
    relative at the standard fidelity, gives far better than the 1e-3 asked).  The
    constant load's work over the span is its torque times the net angle turned ahead
    (negative: the span ends behind where it began), to rounding."""
    scene, res = reversing
    c = res.cycles
    k = int(np.nonzero((c["speed_start_rpm"] > 0) & (c["speed_end_rpm"] < 0))[0][0])
    row = c.iloc[k]
    after = c.iloc[k + 1:]
    assert len(after) >= 2
    assert np.all(after["mean_speed_rpm"] < 0.0) and np.all(np.diff(after["mean_speed_rpm"]) < 0.0)
    assert np.all(after["work_J"] > 0.0)
    assert res.timeseries["eccentric_slip_deg"].iloc[-1] == pytest.approx(130.0, abs=1e-9)
    # continuous speed at the handover
    assert after["speed_start_rpm"].iloc[0] == pytest.approx(row["speed_end_rpm"], rel=1e-12)
    I = scene.flywheel.inertia_kg_m2
    w0, w1 = (row[key] * 2 * math.pi / 60 for key in ("speed_start_rpm", "speed_end_rpm"))
    work = row["work_J"] - row["load_work_J"] - row["friction_work_J"]
    assert 0.5 * I * (w1 ** 2 - w0 ** 2) == pytest.approx(work, rel=1e-3)
    # the constant load's work is its torque times the net angle turned ahead
    span = res.timeseries[res.timeseries["cycle"] == row["cycle"]]["crank_angle_deg"]
    turned = math.radians(span.iloc[-1] - span.iloc[0])
    assert row["load_work_J"] == pytest.approx(2.5 * scene.load.torque_N_m * turned, rel=1e-9)
    assert res.summary["stalled"] is False


# ----------------------------------------------------------------------- oscillating

def _osc(angle_deg, exh_deg=None, steam_ends="both"):
    scene = load_scene(find_scene("oscillating-model"))
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in scene.data.items()}
    data["valve_gear"].update(steam_port_angle=f"{angle_deg} deg",
                              exhaust_port_angle=f"{exh_deg or angle_deg} deg")
    data["engine"]["steam_ends"] = steam_ends
    return scene_from_dict(data, name="osc")


def test_swing_angle_against_the_triangle():
    """The swing from the triangle shaft-trunnion-crank pin by the law of cosines: the
    pin is d = sqrt(D^2 + R^2 - 2 D R cos(theta)) from the trunnion, and the angle at
    the trunnion has cos(psi) = (D^2 + d^2 - R^2) / (2 D d); the largest swing is
    asin(R/D), at cos(theta) = R/D."""
    g = build_gear(_osc(17.2))
    R, D = g.spec.crank_m, g.spec.trunnion_distance_m
    th = np.linspace(0.01, math.pi - 0.01, 50)
    d = np.sqrt(D * D + R * R - 2 * D * R * np.cos(th))
    psi = np.arccos((D * D + d * d - R * R) / (2 * D * d))
    np.testing.assert_allclose(swing_angle(g.spec, th), psi, atol=1e-12)
    np.testing.assert_allclose(swing_angle(g.spec, -th), -psi, atol=1e-12)
    assert float(swing_angle(g.spec, math.acos(R / D))) == pytest.approx(math.asin(R / D), abs=1e-15)


@pytest.mark.parametrize("steam_deg, exh_deg", [(17.2, 17.2), (19.0, 18.0), (22.0, 20.0)])
def test_oscillating_events_against_the_swing(steam_deg, exh_deg):
    """The head port opens and closes where the swing reaches lambda = l / rho, the
    steam port's angle less the half-widths' angle: psi = lambda rearranged is
    R sin(theta + lambda) = D sin(lambda), so admission at asin((D/R) sin lambda) -
    lambda and cut-off at 180 deg - asin((D/R) sin lambda) - lambda.  The exhaust opens
    where psi = -lambda_e: release at 180 deg + asin((D/R) sin lambda_e) + lambda_e,
    compression at 360 deg - asin((D/R) sin lambda_e) + lambda_e.  Three port
    spacings (laps from 0 to about 0.01 in).  The crank end's ports open where
    psi = -lambda (and the exhaust where psi = +lambda_e), the same equations with theta
    replaced by -theta."""
    g = build_gear(_osc(steam_deg, exh_deg))
    s = g.spec
    R, D, rho = s.crank_m, s.trunnion_distance_m, s.port_radius_m
    half = 0.5 * (s.cylinder_port_m + s.standard_port_m) / rho
    lam = math.radians(steam_deg) - half
    lam_e = math.radians(exh_deg) - half
    a = math.asin(D / R * math.sin(lam))
    b = math.asin(D / R * math.sin(lam_e))
    want = {"admission_deg": math.degrees(a - lam), "cutoff_deg": math.degrees(math.pi - a - lam),
            "release_deg": math.degrees(math.pi + b + lam_e),
            "compression_deg": math.degrees(2 * math.pi - b + lam_e)}
    ev = events(g, _harmonic)
    for key, deg in want.items():
        assert _deg_close(ev["head"][key], deg % 360.0, EXACT_DEG), (key, ev["head"][key], deg)
    # the swing is odd in theta (psi(-theta) = -psi(theta)), not half-wave symmetric: the
    # crank end's events are the head end's mirrored about the dead centre, its
    # admission at 360 deg less the head's cut-off, its release less the compression
    mirror = {"admission_deg": "cutoff_deg", "cutoff_deg": "admission_deg",
              "release_deg": "compression_deg", "compression_deg": "release_deg"}
    for key, head_key in mirror.items():
        assert _deg_close(ev["crank"][key], (360.0 - want[head_key]) % 360.0, EXACT_DEG), key


def test_oscillating_port_opening_is_the_slots_overlap():
    """Two slots on one circle, widths w_c and w_s, centres rho psi and rho beta apart
    along it: their overlap, computed here as the intersection of the two intervals,
    is the head steam port's opening."""
    g = build_gear(_osc(19.0))
    s = g.spec
    th = np.linspace(0.0, 2 * math.pi, 361)
    c = s.port_radius_m * swing_angle(s, th)
    p = s.port_radius_m * s.steam_port_angle_rad
    lo = np.maximum(c - s.cylinder_port_m / 2, p - s.standard_port_m / 2)
    hi = np.minimum(c + s.cylinder_port_m / 2, p + s.standard_port_m / 2)
    np.testing.assert_allclose(g.openings(th)[0], np.clip(hi - lo, 0.0, None), atol=1e-15)


def test_single_acting_oscillator_never_opens_its_crank_steam_port():
    """Single-acting, said as [engine] steam_ends = "head": the crank end's steam port
    never opens and it has no events, its exhaust port stands open a full port (the
    standard's port width, by which the port face's openings are measured), and the
    head end's events and openings are the double-acting cylinder's."""
    single = scene_events(_osc(19.0, steam_ends="head"))
    double = scene_events(_osc(19.0))
    assert all(single["crank"][k] is None for k in ("admission_deg", "cutoff_deg"))
    for key in ("admission_deg", "cutoff_deg", "release_deg", "compression_deg"):
        assert single["head"][key] == pytest.approx(double["head"][key], abs=1e-12)
    th = np.linspace(0, 2 * math.pi, 73)
    g1, g2 = build_gear(_osc(19.0, steam_ends="head")), build_gear(_osc(19.0))
    op1, op2 = g1.openings(th), g2.openings(th)
    assert np.all(op1[2] == 0.0)
    np.testing.assert_allclose(op1[3], g2.spec.port_width_m, rtol=1e-15)
    np.testing.assert_array_equal(op1[:2], op2[:2])


def test_single_acting_oscillator_works_its_head_end_only():
    """The crank end of a single-acting oscillator breathes the exhaust through a port
    held open.  Taking no steam, with adiabatic walls (the scene names no wall heat),
    it exchanges steam with one reservoir at constant pressure through a throttling
    port, so over a cycle it can only absorb work: its mean effective pressure is zero
    or less (a pumping loss; 4 % of the head end's here, through the scene's 3/32 in
    port at 1,500 rpm), never positive.  The head end works as the double-acting
    cylinder's does (1e-3: the ends share no volume, only the shaft, whose speed the
    steady run holds)."""
    from corliss.engine.simulate import simulate
    single = simulate(_osc(17.2, steam_ends="head")).summary
    double = simulate(_osc(17.2)).summary
    assert single["mep_crank_Pa"] < 0.0
    assert single["mep_head_Pa"] == pytest.approx(double["mep_head_Pa"], rel=1e-3)


def test_oscillating_acting_key_is_refused_naming_steam_ends():
    """One way to say single-acting: the gear's former acting key is refused, with a
    message naming the key and the engine's steam_ends that says it now, before any
    work."""
    scene = load_scene(find_scene("oscillating-model"))
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in scene.data.items()}
    data["valve_gear"]["acting"] = "single"
    with pytest.raises(InputError) as err:
        scene_from_dict(data, name="bad")
    assert "valve_gear.acting" in str(err.value) and 'steam_ends = "head"' in str(err.value)


@pytest.mark.parametrize("key, value, says", [
    ("steam_port_angle", "40 deg", "never reaches"),
    ("steam_port_angle", "5 deg", "full register"),
    ("trunnion_distance", "0.3 in", "above the crank"),
])
def test_oscillating_bad_geometry_is_named(key, value, says):
    scene = load_scene(find_scene("oscillating-model"))
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in scene.data.items()}
    data["valve_gear"][key] = value
    with pytest.raises(InputError) as err:
        scene_from_dict(data, name="bad")
    assert key in str(err.value) and says in str(err.value)


# ----------------------------------------------------------------------- Baker

def _baker(setting):
    return build_gear(load_scene(find_scene("baker-locomotive"))).with_setting(setting)


def _second_solve(gear, theta, guess):
    """The Baker linkage solved here a second way: all eight unknowns at once by
    scipy's fsolve (the gear connecting rod's three pins P, M, U; the valve pin's x and
    the combination lever's angle), from the fixed points of the layout, every
    constraint a rod's length (and the gear connecting rod straight)."""
    s = gear.spec
    lay = baker_layout(s)
    O, K = lay["O"], lay["K"]
    alpha = gear.sense * s.setting * s.max_yoke_rad
    Y = O + s.radius_bar_m * np.array([math.sin(alpha), math.cos(alpha)])
    lam = math.atan2(lay["Q0"][1], lay["Q0"][0])
    Q = s.eccentric_crank_m * np.array([math.cos(lam - theta), math.sin(lam - theta)])
    Bx, By = s.crank_m * math.cos(theta), -s.crank_m * math.sin(theta)
    Cx = Bx + math.sqrt(s.connecting_rod_m ** 2 - By * By)
    XH = np.array([Cx + lay["arm"], lay["yL"]])
    a, ell, yv = s.lever_valve_m, s.lever_crosshead_m, s.valve_height_m
    da, dl = (a, -(ell - a)) if s.admission == "inside" else (-a, -(a + ell))

    def f(z):
        P, M, U = z[0:2], z[2:4], z[4:6]
        vx, g = z[6], z[7]
        V = K + s.bell_crank_vertical_m / s.bell_crank_horizontal_m * np.array(
            [(U - K)[1], -(U - K)[0]])
        w = np.array([math.sin(g), math.cos(g)])
        W = np.array([vx, yv])
        A, L = W + da * w, W + dl * w
        return [np.hypot(*(P - Q)) - s.eccentric_rod_m,
                np.hypot(*(M - Y)) - s.radius_bar_m,
                np.hypot(*(M - P)) - s.gear_rod_lower_m,
                np.hypot(*(U - M)) - s.gear_rod_upper_m,
                np.hypot(*(U - K)) - s.bell_crank_horizontal_m,
                (M - P)[0] * (U - M)[1] - (M - P)[1] * (U - M)[0],
                np.hypot(*(A - V)) - s.valve_rod_m,
                np.hypot(*(L - XH)) - s.union_link_m]

    z, info, ok, msg = fsolve(f, guess, full_output=True, xtol=1e-13)
    assert ok == 1, msg
    return z


def _second_travel(gear):
    """x(theta) from the second solve, zeroed as the gear is (the mean of the dead
    centres), in the head-opening sense (inside admission: +x along the stroke)."""
    def raw(theta):
        p = gear.points(np.array([theta]))
        guess = np.concatenate([p["gear_rod_lower"][:, 0], p["gear_rod_middle"][:, 0],
                                p["gear_rod_top"][:, 0], [p["valve_pin"][0, 0]],
                                [math.atan2(*(p["radius_rod_pin"][:, 0] - p["valve_pin"][:, 0]))
                                 * (1 if gear.spec.admission == "inside" else -1)]])
        # a guess a little off the gear's own solution, so the second solve does the work
        z = _second_solve(gear, theta, guess + 2e-3)
        x = z[6]
        return x if gear.spec.admission == "inside" else -x
    zero = 0.5 * (raw(0.0) + raw(math.pi))
    return lambda theta: raw(theta) - zero


@pytest.mark.parametrize("setting", [1.0, 0.5, -0.7])
def test_baker_events_against_a_second_linkage_solve(setting):
    """At three yoke settings, the head end's admission and cut-off and the crank end's
    cut-off found by brentq on the second solve's valve travel agree with the gear's
    events (its Newton solve, tabulated at 1/2 deg and splined): the spline's error on
    a valve moving ~5 in a turn is below 1e-6 in, 2e-5 deg of crank at these slopes."""
    gear = _baker(setting)
    x = _second_travel(gear)
    th = np.linspace(0.0, 2 * math.pi, 13)
    np.testing.assert_allclose([x(t) for t in th], gear.travel(th), atol=1e-7)
    lap = gear.spec.lap_m[0]
    ev = events(gear, _harmonic)
    cut = brentq(lambda t: x(t) - lap, math.radians(ev["head"]["cutoff_deg"]) - 0.05,
                 math.radians(ev["head"]["cutoff_deg"]) + 0.05, xtol=1e-12)
    adm = brentq(lambda t: x(t) - lap, math.radians(ev["head"]["admission_deg"]) - 0.05,
                 math.radians(ev["head"]["admission_deg"]) + 0.05, xtol=1e-12)
    ccut = brentq(lambda t: -x(t) - lap, math.radians(ev["crank"]["cutoff_deg"]) - 0.05,
                  math.radians(ev["crank"]["cutoff_deg"]) + 0.05, xtol=1e-12)
    assert _deg_close(ev["head"]["cutoff_deg"], math.degrees(cut) % 360, 2e-4)
    assert _deg_close(ev["head"]["admission_deg"], math.degrees(adm) % 360, 2e-4)
    assert _deg_close(ev["crank"]["cutoff_deg"], math.degrees(ccut) % 360, 2e-4)


def test_baker_constant_lead_and_mid_gear_travel():
    """Published: "The crosshead moves the valve the amount of the lap and lead each
    way, and the eccentric crank gives the remainder ... In the short cut-offs the
    actual effect of the eccentric crank is reduced, while the crosshead movement is
    constant" (Pilliod Co., The Baker Valve Gear); with the bell crank blocked, "lap
    and lead travel and a port opening equal to the lead for all cut-offs" (Project
    Gutenberg ebook 17783, Baker gear Q. 18).  So the valve stands lap + lead = (a/l) R
    from mid travel at both dead centres at every setting, its travel shrinks towards
    mid gear, and in mid gear (yoke centred, the gear connecting rod's top still) it is
    2 (lap + lead), the port opening there the lead."""
    travels = []
    for setting in (1.0, 0.6, 0.3, 0.0, -0.3, -1.0):
        g = _baker(setting)
        C = g.spec.lever_valve_m / g.spec.lever_crosshead_m * g.spec.crank_m
        np.testing.assert_allclose(g.travel(np.array([0.0, math.pi])), [C, -C], atol=1e-12)
        x = g.travel(np.linspace(0, 2 * math.pi, 1441))
        travels.append(x.max() - x.min())
    assert travels[0] > travels[1] > travels[2] > travels[3]
    assert travels[3] == pytest.approx(2 * C, rel=1e-6)
    mid = _baker(0.0)
    lead = C - mid.spec.lap_m[0]
    assert scene_events(dataclasses.replace(load_scene(find_scene("baker-locomotive")),
                                            gear=mid.spec))["head"]["max_port_opening_m"] \
        == pytest.approx(lead, rel=1e-6)


def test_baker_eccentric_crank_follows_the_main_pin():
    """Published: "The eccentric crank always follows the main pin" (Project Gutenberg
    ebook 17783, Baker gear Q. 17): running ahead, the eccentric crank's pin is behind
    the main crank pin in the direction of rotation, by about a quarter turn (square to
    the line to the gear connecting rod's foot); and the engine runs ahead at a
    positive setting: the valve leads the crank (its first harmonic's sine part > 0)."""
    g = _baker(1.0)
    p = g.points(np.array([0.3]))
    B, Q = p["crank_pin"][:, 0], p["eccentric_crank_pin"][:, 0]
    # clockwise rotation: an angle measured clockwise from the main pin to the eccentric
    behind = math.remainder(math.atan2(B[1], B[0]) - math.atan2(Q[1], Q[0]), 2 * math.pi)
    assert -math.radians(120) < behind < -math.radians(60)
    th = np.linspace(0, 2 * math.pi, 720, endpoint=False)
    assert np.mean(g.travel(th) * np.sin(th)) > 0.0


def test_baker_preadmission_grows_as_the_cut_off_shortens():
    """Published: "The Baker-Pilliod improved valve gear gives a constant lead of the
    valve the distance of the steam lap, but a variable preadmission; at full gear we
    get practically no preadmission, but as the cut-off is shortened preadmission
    begins and increases" (a locomotive breakdowns and valve-gear handbook of about
    1915, its section on the Baker-Pilliod improved valve gear, Fig. 50: Google Books
    ids tKlKAAAAMAAJ p. 233 and MSZLAAAAYAAJ p. 236; no table of numbers is given, and
    none was found in any source at hand).  Each end's preadmission, the crank angle
    before its dead centre at which its steam port opens, is least at full gear and
    grows at every shorter cut-off (settings 1 to 0.15, running ahead: 4 deg at full
    gear to 20 deg at 0.17 cut-off for the scene's head end); the lead stays the same
    throughout (test above)."""
    pre_head, pre_crank, cut = [], [], []
    for s in (1.0, 0.8, 0.6, 0.4, 0.25, 0.15):
        ev = events(_baker(s), _harmonic)
        pre_head.append((360.0 - ev["head"]["admission_deg"]) % 360.0)
        pre_crank.append((180.0 - ev["crank"]["admission_deg"]) % 360.0)
        cut.append(ev["head"]["cutoff_frac"])
    assert np.all(np.diff(cut) < 0.0)
    assert np.all(np.diff(pre_head) > 0.0) and np.all(np.diff(pre_crank) > 0.0)
    assert all(0.0 < p < 90.0 for p in pre_head + pre_crank)


# ----------------------------------------------------------------------- the scenes

@pytest.mark.parametrize("name", ["slip-eccentric-launch", "oscillating-model", "baker-locomotive"])
def test_bundled_scene_runs_animates_and_designs(name, tmp_path, capsys):
    """``corliss run``, ``animate`` and ``design`` on each bundled scene (``gear`` and
    ``events`` are run on every bundled scene by tests/test_gear_scenes.py): the
    design's cut-off where the gear has a setting (Baker) or is designed whole as a
    slide valve (slip eccentric); a clear refusal for the oscillating cylinder, which
    has neither."""
    path = str(find_scene(name))
    assert cli.main(["run", path, "--out", str(tmp_path), "--no-plots"]) == 0
    assert cli.main(["animate", path, "--out", str(tmp_path), "--frames", "4"]) == 0
    assert (tmp_path / f"{name}.animation.gif").stat().st_size > 5_000
    capsys.readouterr()
    extra = {"slip-eccentric-launch": ["--lap", "0.12 in", "--lead", "0.03 in"]}.get(name, [])
    rc = cli.main(["design", path, "--cutoff", "0.6", *extra, "--out", str(tmp_path / "d")])
    if name == "oscillating-model":
        assert rc != 0 and "oscillating" in capsys.readouterr().err
    else:
        assert rc == 0
        designed = scene_events(load_scene(tmp_path / "d" / f"{name}.design.toml"))
        # the scene written rounds its lengths to 0.001 in: on these small valves a
        # thou moves the cut-off by some 1e-4 of the stroke (5e-5 measured)
        assert designed["head"]["cutoff_frac"] == pytest.approx(0.6, abs=5e-4)


def test_gears_build_their_kinds():
    """Each scene builds its gear's class (the registry's entries)."""
    for name, cls in (("slip-eccentric-launch", SlipEccentric),
                      ("oscillating-model", OscillatingCylinder),
                      ("baker-locomotive", BakerGear)):
        assert isinstance(build_gear(load_scene(find_scene(name))), cls)


# ----------------------------------------------------------------------- the pictures

def test_the_baker_gear_is_drawn_as_its_linkage():
    """The animation draws the Baker gear from its joints: each of its 14 rods, arms
    and links drawn as long as the scene's, in every frame checked, and the valve at
    the gear's travel."""
    import matplotlib.pyplot as plt

    from corliss.plot.animation import animate_gear, rod_lengths
    scene = load_scene(find_scene("baker-locomotive"))
    gear = build_gear(scene)
    drawn = animate_gear(gear, None, frames=24, stroke_m=scene.engine.stroke_m)
    try:
        assert drawn["kind"] == "radial"
        for i in (0, 5, 11, 17):
            joints = drawn["update"](i)
            lengths = rod_lengths(joints)
            assert len(lengths) == 14
            for name, (between, spec) in lengths.items():
                # the joints come from a solve to 1e-9 of the eccentric rod
                assert between == pytest.approx(spec, abs=1e-7), name
            theta = drawn["angles_rad"][i]
            assert joints.valve_m == pytest.approx(float(gear.travel(np.array([theta]))[0]),
                                                   abs=1e-6)
    finally:
        plt.close(drawn["figure"])


def test_the_oscillating_port_face_is_drawn_open_as_the_gear_opens_it():
    """Read off the picture: each end's cylinder port, drawn over the standard's ports
    developed along the arc, overlaps the steam and exhaust ports by the gear's own
    openings at the frame's crank angle."""
    import matplotlib.pyplot as plt

    from corliss.plot.animation import animate_gear
    scene = _osc(19.0)
    gear = build_gear(scene)
    s = gear.spec
    drawn = animate_gear(gear, None, frames=24, stroke_m=scene.engine.stroke_m)
    sc = drawn["scale"]
    try:
        assert drawn["kind"] == "oscillating"
        head, crank = drawn["artists"]["cylinder_ports"]
        rho, w = s.port_radius_m, s.standard_port_m
        for i in range(0, 24, 3):
            drawn["update"](i)
            seen = []
            for patch, steam, exhaust in ((head, s.steam_port_angle_rad,
                                           -s.exhaust_port_angle_rad),
                                          (crank, -s.steam_port_angle_rad,
                                           s.exhaust_port_angle_rad)):
                a = (patch.get_x() / sc, (patch.get_x() + patch.get_width()) / sc)
                for beta in (steam, exhaust):
                    b = (rho * beta - w / 2, rho * beta + w / 2)
                    seen.append(max(0.0, min(a[1], b[1]) - max(a[0], b[0])))
            want = gear.openings(np.array([drawn["angles_rad"][i]]))[:, 0]
            assert seen == pytest.approx(list(want), abs=1e-9), i
    finally:
        plt.close(drawn["figure"])
