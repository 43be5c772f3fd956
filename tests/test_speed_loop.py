"""The speed loop without a governor: flywheel energy against the torque integral, the
load laws, and the clear errors of a transient scene."""

import math

import numpy as np
import pytest

from conftest import make_scene
from corliss.engine.simulate import simulate
from corliss.errors import InputError

TRANSIENT = {"mode": "transient", "speed": "120 rpm", "duration": "1.5 s", "warmup_cycles": 2,
             "effects": ["port_flow", "rod_angularity", "inertia", "friction"]}
ENGINE = {"reciprocating_mass": "600 lb", "friction_torque": "150 lbf ft",
          "friction_torque_per_speed": "2 lbf ft/rpm"}


def _run(load, flywheel=None, **run):
    scene = make_scene(engine=ENGINE, run={**TRANSIENT, **run},
                       flywheel=flywheel or {"rim_weight": "4000 lb", "mean_radius": "4 ft"},
                       load=load)
    return scene, simulate(scene)


@pytest.mark.parametrize("method", ["dopri5", "ros4"])
def test_flywheel_energy_balances_the_torque_integral(method):
    """Lagrange's equation for the crank train (see corliss.engine.kernels.loop) makes
    d/dt (1/2 I_e omega^2) = (T_gas - T_friction - T_load) omega, so over whole turns,
    which start and end at a dead centre where the reciprocating parts are at rest
    (ds/dtheta = 0, I_e = I), the change of the flywheel's kinetic energy equals the
    indicated work less the friction and load work.  The load ramps and varies with
    speed, and the reciprocating inertia is on, so every term moves.
    Tolerance 1e-5 of the kinetic-energy change: the integrator's rtol is 1e-6.  With
    the Rosenbrock loop this also checks its Jacobian's speed column: without it the
    method lost its order and the balance was off by 3e-5."""
    scene, r = _run({"torque": "5000 lbf ft", "kind": "ramp", "ramp_start": "0.3 s",
                     "ramp_end": "0.9 s", "ramp_fraction": 1.7, "speed_law": "proportional"},
                    method=method)
    c = r.cycles
    inertia = scene.flywheel.inertia_kg_m2
    w0 = c["speed_start_rpm"].iloc[0] * math.pi / 30
    w1 = c["speed_end_rpm"].iloc[-1] * math.pi / 30
    d_ke = 0.5 * inertia * (w1 ** 2 - w0 ** 2)
    work = (c["work_J"] - c["friction_work_J"] - c["load_work_J"]).sum()
    assert abs(d_ke) > 0.05 * 0.5 * inertia * w0 ** 2     # the speed really changed
    assert work == pytest.approx(d_ke, rel=1e-5)


def test_rim_flywheel_is_m_r_squared():
    """Marks Art. 61: the rim, arms neglected, has moment of inertia (W/g) r^2."""
    scene = make_scene(engine=ENGINE, run=TRANSIENT,
                       flywheel={"rim_weight": "4000 lb", "mean_radius": "4 ft"},
                       load={"torque": "1000 lbf ft"})
    assert scene.flywheel.inertia_kg_m2 == pytest.approx(4000 * 0.45359237 * (4 * 0.3048) ** 2)


def test_load_laws_scale_the_torque_with_speed():
    """T_load = T_ref (omega/omega_ref)^k: over each turn the load's mean torque divided
    by T_ref equals the turn's mean of (omega/omega_ref)^k.  Checked with the turn's mean
    speed, which differs from the mean of the power by the speed's fluctuation within a
    turn (well under 1 % with this flywheel): tolerance 0.5 %."""
    for law, k in (("constant", 0), ("proportional", 1), ("square", 2)):
        scene, r = _run({"torque": "2000 lbf ft", "speed_law": law}, duration="0.8 s")
        c = r.cycles
        dt = c["t_end_s"] - c["t_start_s"]
        mean_torque = c["load_work_J"] / (2 * math.pi)
        ratio = (c["mean_speed_rpm"] / 120.0) ** k
        np.testing.assert_allclose(mean_torque / scene.load.torque_N_m, ratio, rtol=5e-3)
        assert (dt > 0).all()


def test_a_step_in_load_changes_the_acceleration_by_the_step():
    """Ungoverned, at the step the load torque drops by (1 - f) T_ref, so the flywheel's
    acceleration jumps by (1 - f) T_ref / I (within a turn, where the indicated torque
    hardly changes).  Compare the turn-mean accelerations of the turns around the step:
    the jump should be the step over the inertia within 10 % (the indicated torque does
    change a little with speed between those turns)."""
    scene, r = _run({"torque": "3000 lbf ft", "kind": "step", "step_time": "0.8 s",
                     "step_fraction": 0.25}, flywheel={"moment_of_inertia": "20000 lb ft2"},
                    effects=["port_flow", "rod_angularity"], duration="1.6 s")
    c = r.cycles
    acc = (c["speed_end_rpm"] - c["speed_start_rpm"]) * math.pi / 30 / (c["t_end_s"] - c["t_start_s"])
    before = acc[c["t_end_s"] < 0.8].iloc[-1]
    after = acc[c["t_start_s"] > 0.8].iloc[0]
    expect = 0.75 * scene.load.torque_N_m / scene.flywheel.inertia_kg_m2
    assert after - before == pytest.approx(expect, rel=0.1)


@pytest.mark.parametrize("sections, key", [
    ({"run": {**TRANSIENT}}, "flywheel"),
    ({"run": {**TRANSIENT}, "flywheel": {"moment_of_inertia": "100 kg m2"}}, "load"),
    ({"run": {**TRANSIENT}, "flywheel": {"moment_of_inertia": "100 kg m2", "rim_weight": "1 lb"},
      "load": {"torque": "1 N m"}}, "flywheel.moment_of_inertia"),
    ({"run": {**TRANSIENT}, "flywheel": {"moment_of_inertia": "100 kg m2"},
      "load": {"torque": "1 N m", "power": "1 hp"}}, "load.torque"),
    ({"run": {**TRANSIENT}, "flywheel": {"moment_of_inertia": "100 kg m2"},
      "load": {"torque": "1 N m", "kind": "step", "step_time": "1 s", "step_fraction": 9}},
     "load.step_fraction"),
    ({"run": {**TRANSIENT, "duration": None}, "flywheel": {"moment_of_inertia": "100 kg m2"},
      "load": {"torque": "1 N m"}}, "run.duration"),
    ({"flywheel": {"moment_of_inertia": "100 kg m2"}}, "flywheel"),
    ({"run": {**TRANSIENT}, "flywheel": {"moment_of_inertia": "100 kg m2"},
      "load": {"torque": "1 N m", "kind": "schedule", "schedule": "no-such-file.csv"}},
     "load.schedule"),
])
def test_transient_scene_errors_name_the_key(sections, key):
    with pytest.raises(InputError) as exc:
        make_scene(engine=ENGINE, **sections)
    assert exc.value.key == key


def test_schedule_from_csv(tmp_path):
    """A CSV schedule is read piecewise linearly and held beyond its ends."""
    from corliss.engine.load import parse_load
    from corliss.keys.toml_table import Table
    f = tmp_path / "loads.csv"
    f.write_text("time_s,load_fraction\n0,1\n2,1\n2,0.5\n4,0.25\n")
    spec = parse_load(Table({"torque": "100 N m", "kind": "schedule", "schedule": "loads.csv"},
                            "load"), 10.0, tmp_path)
    np.testing.assert_allclose(spec.fraction([1.0, 2.5, 3.0, 9.0]), [1.0, 0.4375, 0.375, 0.25])
    assert spec.change_times_s()[0] == 2.0


WATT = {"type": "watt", "arm_length": "12 in", "ball_mass": "12 lb",
        "arm_angle_at_rest": "30 deg", "arm_angle_at_top": "42 deg", "ratio": 0.5}
TRANSIENT_SECTIONS = {"flywheel": {"moment_of_inertia": "100 kg m2"}, "load": {"torque": "1 N m"}}


@pytest.mark.parametrize("sections, key", [
    # a throttling governor needs the chest and pipe its throttle sits in
    ({"run": {**TRANSIENT}, "governor": WATT}, "governor.type"),
    # a governor on the gear needs a gear with a setting (the plain slide valve has none)
    ({"run": {**TRANSIENT}, "governor": {"type": "erie", "weight_mass": "6 lb",
                                          "pivot_radius": "3 in", "arm_length": "6 in",
                                          "weight_radius_at_rest": "6.5 in",
                                          "weight_radius_at_top": "7.5 in", "spring_arm": "2 in",
                                          "spring_stiffness": "8 lbf/in",
                                          "spring_preload": "111 lbf"}}, "governor.type"),
    ({"run": {**TRANSIENT}, "governor": {**WATT, "type": "no-such-governor"}}, "governor.type"),
    ({"run": {**TRANSIENT}, "governor": {**WATT, "ball_mass": "12 lbf"}}, "governor.ball_mass"),
    ({"run": {"mode": "steady"}, "governor": WATT}, "governor"),
])
def test_governor_scene_errors_name_the_key(sections, key):
    """A governor that cannot act on the scene's engine is refused before any work, with
    the key named: the throttle needs ``steam_chest`` and a pipe; a gear governor needs a
    gear with a setting; a steady run has no governor; units are checked."""
    with pytest.raises(InputError) as exc:
        make_scene(engine=ENGINE, **TRANSIENT_SECTIONS, **sections)
    assert exc.value.key == key


def test_cli_refuses_cycles_for_a_transient_scene(tmp_path, capsys):
    from pathlib import Path

    from corliss.cli import commands as cli
    scene = Path(__file__).resolve().parent.parent / "scenes" / "watt-throttling-governor.toml"
    assert cli.main(["run", str(scene), "--cycles", "3", "--out", str(tmp_path)]) == 2
    assert "--duration" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())
