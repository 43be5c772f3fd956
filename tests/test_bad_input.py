"""Bad input never reaches the physics: every cause found by mutating the bundled
scenes gets a regression test here, through the command line as a user meets it:
exit code 2, the offending key named, no traceback, no file written, quickly.
"""

from __future__ import annotations

import re
import time
import tomllib
from pathlib import Path

import pytest

from corliss.cli import commands as cli
from corliss.engine.kernels import stepping
from corliss.engine import transient as transient_runner
from corliss.scene.loader import bundled_scenes

SCENES = bundled_scenes()
#: A refusal comes before any work: well under a second; the bound is generous for a
#: loaded machine and catches a hang.
REFUSAL_S = 20.0


def _mutated(tmp_path: Path, name: str, section: str, key: str, value: str) -> Path:
    """The bundled scene ``name`` with ``section.key`` set to the TOML text ``value``."""
    text = SCENES[name].read_text()
    lines = text.splitlines()
    head = next(i for i, ln in enumerate(lines) if ln.strip() == f"[{section}]")
    for i in range(head + 1, len(lines)):
        if lines[i].startswith("["):
            lines.insert(i, f"{key} = {value}")
            break
        if re.match(rf"{re.escape(key)}\s*=", lines[i]):
            lines[i] = f"{key} = {value}"
            break
    else:
        lines.append(f"{key} = {value}")
    path = tmp_path / f"{name}-mutated.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


def _refused(args: list[str], out: Path, capsys, key: str) -> str:
    t0 = time.perf_counter()
    code = cli.main([*args, "--out", str(out)] if args[0] in ("run", "gear") else args)
    elapsed = time.perf_counter() - t0
    err = capsys.readouterr().err
    assert code == 2, err
    assert key in err, err
    assert "Traceback" not in err
    assert not out.exists() or not any(out.iterdir())
    assert elapsed < REFUSAL_S
    return err


# --- quantity strings -------------------------------------------------------------------

@pytest.mark.parametrize("value, why", [
    ('"1/0 in"', "denominator"),
    ('"' + "7" * 401 + '/3 in"', "at most"),
    ('"' + "9" * 5000 + ' 1/2 in"', "at most"),
    ('"1e999 in"', "finite"),
], ids=["division-by-zero", "401-digit-numerator", "5000-digit-whole", "infinite"])
def test_a_quantity_string_is_read_by_a_grammar_that_only_refuses(value, why, tmp_path, capsys):
    path = _mutated(tmp_path, "default", "engine", "connecting_rod", value)
    err = _refused(["run", str(path)], tmp_path / "out", capsys, "engine.connecting_rod")
    assert why in err


def test_an_lp_piston_rod_as_wide_as_the_lp_bore_is_refused(tmp_path, capsys):
    """The LP rod takes its area from the LP crank end: one as wide as the 14 in LP
    bore (or the HP's rod, inherited, on a smaller LP) leaves no piston there."""
    path = _mutated(tmp_path, "marks-compound-9-14x14", "compound", "lp_piston_rod_diameter",
                    '"14 in"')
    err = _refused(["run", str(path)], tmp_path / "out", capsys,
                   "compound.lp_piston_rod_diameter")
    assert "less than the LP bore (14 in)" in err


def test_an_infinite_radius_rod_is_refused(tmp_path, capsys):
    path = _mutated(tmp_path, "walschaerts-locomotive", "valve_gear", "radius_rod", '"1e999 in"')
    _refused(["run", str(path)], tmp_path / "out", capsys, "valve_gear.radius_rod")


def test_an_infinite_spring_preload_is_refused(tmp_path, capsys):
    path = _mutated(tmp_path, "ball-governor", "governor", "spring_preload", '"1e999 lbf"')
    _refused(["run", str(path)], tmp_path / "out", capsys, "governor.spring_preload")


@pytest.mark.parametrize("command", ["events", "gear"])
def test_an_infinite_speed_is_refused_by_events_and_gear(command, tmp_path, capsys):
    path = _mutated(tmp_path, "default", "run", "speed", '"1e999 rpm"')
    _refused([command, str(path)], tmp_path / "out", capsys, "run.speed")


def test_a_value_outside_its_physical_range_names_the_range(tmp_path, capsys):
    path = _mutated(tmp_path, "default", "engine", "bore", '"40 ft"')
    err = _refused(["run", str(path)], tmp_path / "out", capsys, "engine.bore")
    assert "from 0.001 m to 5 m" in err


# --- files that are not UTF-8 TOML ------------------------------------------------------

@pytest.mark.parametrize("content, where", [
    (bytes(range(256)) * 4, "line"),
    (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR", "line"),
    ("title = 'utf-16'\n".encode("utf-16"), "line 1"),
    (SCENES["default"].read_text().replace('title = "12 x 24', 'title = "12 \xd7 24')
     .encode("latin-1"), "line 9"),
], ids=["binary", "png", "utf-16", "latin-1-title"])
def test_a_file_that_is_not_utf8_toml_is_refused_naming_the_line(content, where, tmp_path,
                                                                  capsys):
    path = tmp_path / "bad.toml"
    path.write_bytes(content)
    err = _refused(["run", str(path)], tmp_path / "out", capsys, "scene")
    assert where in err


def test_a_file_that_is_not_toml_is_refused(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text("[engine\nbore = 12 in\n")
    err = _refused(["events", str(path)], tmp_path / "out", capsys, "scene")
    assert "TOML" in err


# --- load schedules -----------------------------------------------------------------------

def _schedule_scene(tmp_path: Path, csv_bytes: bytes) -> Path:
    (tmp_path / "schedule.csv").write_bytes(csv_bytes)
    text = SCENES["porter-allen-governor"].read_text()
    data = tomllib.loads(text)
    assert "load" in data
    lines = text.splitlines()
    head = lines.index("[load]")
    end = next((i for i in range(head + 1, len(lines)) if lines[i].startswith("[")), len(lines))
    keep = [ln for ln in lines[head + 1:end]
            if re.match(r"(power|torque|speed_law)\s*=", ln) or not re.match(r"\w+\s*=", ln)]
    lines[head + 1:end] = keep + ['kind = "schedule"', 'schedule = "schedule.csv"']
    path = tmp_path / "scheduled.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("csv_bytes, why", [
    (bytes(range(256)), "UTF-8"),
    ("time_s,load_fraction\n0,1\n5,0.5 \xe9\n".encode("latin-1"), "line 3"),
    (b"time_s,load_fraction\n0,1\n5\n", "line 3 has too few cells"),
    (b"time_s,load_fraction\n0,1\nnan,0.5\n", "finite"),
    (b"time_s,load_fraction\n0,1\n5,0.5\n2,0.5\n", "line 4 goes back"),
    (b"time,load\n0,1\n", "header"),
], ids=["binary", "latin-1", "short-row", "nan-time", "decreasing", "no-header"])
def test_a_bad_schedule_is_refused_naming_its_line(csv_bytes, why, tmp_path, capsys):
    path = _schedule_scene(tmp_path, csv_bytes)
    err = _refused(["run", str(path)], tmp_path / "out", capsys, "load.schedule")
    assert why in err


# --- steam states outside the property range ---------------------------------------------

@pytest.mark.parametrize("section, key, value", [
    ("supply", "pressure", '"4000 psia"'),
    ("supply", "pressure", '"1e30 psia"'),
    ("exhaust", "pressure", '"1e-30 psia"'),
], ids=["saturated-above-critical", "1e30-psia", "exhaust-1e-30-psia"])
def test_steam_states_outside_the_properties_are_refused(section, key, value, tmp_path, capsys):
    path = _mutated(tmp_path, "default", section, key, value)
    _refused(["run", str(path)], tmp_path / "out", capsys, f"{section}.{key}")


def test_a_wet_supply_the_table_cannot_hold_is_refused(tmp_path, capsys):
    """Steam of dryness 0.5 at 100 psig has 1.65 MJ/kg, below the table tier's 2 MJ/kg."""
    path = _mutated(tmp_path, "default", "supply", "dryness", "0.5")
    err = _refused(["run", str(path)], tmp_path / "out", capsys, "supply.dryness")
    assert "heos" in err


# --- the causes of hangs ------------------------------------------------------------------

@pytest.mark.parametrize("name, section, key, value", [
    ("default", "run", "speed", '"1e-30 rpm"'),
    ("ball-governor", "governor", "friction_torque", '"1e30 lbf ft"'),
    ("watt-throttling-governor", "governor", "friction", '"1e30 lbf"'),
    ("default", "engine", "stroke", '"1e-30 in"'),
    ("default", "valve_gear", "ports_per_end", str(10 ** 30)),
], ids=["speed", "shaft-governor-friction", "flyball-friction", "stroke", "ports"])
def test_what_hung_is_refused_before_any_work(name, section, key, value, tmp_path, capsys):
    path = _mutated(tmp_path, name, section, key, value)
    _refused(["run", str(path)], tmp_path / "out", capsys, f"{section}.{key}")


def test_a_cycle_that_exhausts_its_budget_stops_with_a_message(tmp_path, capsys, monkeypatch):
    """The budget is the guard behind the ranges: a cycle that needs more evaluations
    than it allows stops the run with a message naming the likely scene quantities, and
    writes nothing.  (A budget of 500 evaluations stands in for a run far outside the
    physical; the default card needs 3,400 a cycle.)"""
    monkeypatch.setattr(stepping, "MAX_RHS_PER_CYCLE", 500)
    out = tmp_path / "out"
    code = cli.main(["run", "--out", str(out), "--cycles", "2"])
    err = capsys.readouterr().err
    assert code == 5 and "run.speed" in err and "engine.stroke" in err, err
    assert not out.exists()


def test_a_turn_that_exhausts_its_budget_stops_with_a_message(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(transient_runner, "MAX_RHS_PER_CYCLE", 500)
    out = tmp_path / "out"
    code = cli.main(["run", "porter-allen-governor", "--out", str(out), "--duration", "0.5 s",
                     "--fidelity", "fast"])
    err = capsys.readouterr().err
    assert code == 5 and "run.speed" in err and "warm-up" in err, err
    assert not out.exists()


# --- valid settings at the ends of their ranges -------------------------------------------

@pytest.mark.parametrize("name, setting", [
    ("corliss-trip-gear", "0.0"),
    ("joy-radial-gear", "-1.0"),
    ("buckeye-engine", "1.0"),
    ("porter-allen-engine", "1.0"),
], ids=["corliss-trips-at-admission", "radial-full-backward", "buckeye-top", "porter-allen-top"])
def test_settings_at_the_ends_of_their_ranges_are_results(name, setting, tmp_path, capsys):
    """An engine doing little or no net work at the end of its gear's range is a result:
    every file written, the fluctuation coefficient null when the work is not positive."""
    import json
    path = _mutated(tmp_path, name, "valve_gear", "setting", setting)
    out = tmp_path / "out"
    code = cli.main(["run", str(path), "--out", str(out), "--cycles", "3", "--fidelity", "fast"])
    err = capsys.readouterr().err
    stem = path.stem
    s = json.loads((out / f"{stem}.summary.json").read_text())
    # a card doing no net work is a result that failed physically: exit 4, files written
    assert code == (4 if s["indicated_power_W"] <= 0 or s["steam_rate_kg_per_h"] < 0
                    else 0), err
    names = {p.name for p in out.iterdir()}
    assert {f"{stem}.card.png", f"{stem}.effort.png", f"{stem}.summary.json"} <= names
    s = json.loads((out / f"{stem}.summary.json").read_text())
    if s["indicated_power_W"] <= 0:
        assert s["fluctuation_coefficient_c"] is None
    for end in ("head", "crank"):
        for v in s["events"][end].values():
            assert v is None or isinstance(v, float)


# --- messages that name the right key ------------------------------------------------------

def test_a_governor_top_setting_out_of_range_is_named_as_itself(tmp_path, capsys):
    path = _mutated(tmp_path, "corliss-governor", "governor", "setting_at_top", "50.0")
    err = _refused(["run", str(path)], tmp_path / "out", capsys, "governor.setting_at_top")
    assert "50.0" in err and "nan" not in err


# --- found by the scene fuzzing (tests/test_scene_fuzz.py) ---------------------------------

@pytest.mark.parametrize("name, section, value", [
    ("default", "valve_gear", '["slide_valve"]'),
    ("default", "valve_gear", "{ name = 1 }"),
    ("porter-allen-governor", "governor", '["porter_allen"]'),
    ("marks-compound-9-14x14", "lp_valve_gear", "7"),
], ids=["gear-list", "gear-table", "governor-list", "lp-gear-number"])
def test_a_type_that_is_not_a_name_is_refused_naming_its_own_table(name, section, value,
                                                                    tmp_path, capsys):
    """A list or a table as a gear's or governor's type crashed the registry look-up
    (unhashable); the LP gear's type was named ``valve_gear.type``."""
    path = _mutated(tmp_path, name, section, "type", value)
    err = _refused(["events", str(path)], tmp_path / "out", capsys, f"{section}.type")
    assert "from the registry" in err


def test_a_load_without_power_or_torque_says_so(tmp_path, capsys):
    """The message said "either torque or power, not both" when neither was given."""
    text = SCENES["porter-allen-governor"].read_text()
    path = tmp_path / "no-power.toml"
    path.write_text("\n".join(ln for ln in text.splitlines()
                              if not re.match(r"power\s*=", ln)) + "\n")
    err = _refused(["events", str(path)], tmp_path / "out", capsys, "load.power")
    assert "not both" not in err and "required" in err


def test_a_throttling_governor_without_the_chest_names_run_effects(tmp_path, capsys):
    """Deleting run.effects left a throttling governor without its steam chest; the
    message named only governor.type."""
    text = SCENES["watt-throttling-governor"].read_text()
    path = tmp_path / "no-effects.toml"
    path.write_text("\n".join(ln for ln in text.splitlines()
                              if not re.match(r"effects\s*=", ln)) + "\n")
    err = _refused(["events", str(path)], tmp_path / "out", capsys, "governor.type")
    assert "run.effects" in err


@pytest.mark.parametrize("name, section, key, value, why", [
    ("corliss-governor", "governor", "ratio", "3.75e12", "from 0.05 to 20"),
    ("porter-allen-engine", "valve_gear", "exhaust_ratio", "1e12", "from 0.05 to 20"),
    ("gridiron-valve", "valve_gear", "lever_ratio", "[inf, inf]", "from 0.05 to 20"),
    ("gridiron-valve", "valve_gear", "lever_ratio", "[6e11, 1e12]", "from 0.05 to 20"),
    ("default", "valve_gear", "discharge_coefficient", "7e-13", "from 0.1 to 1"),
    ("twin-90-degrees", "supply", "pipe_discharge_coefficient", "1e-12", "from 0.1 to 1"),
    ("default", "engine", "clearance", "8e-14", "from 0.005 to 0.5"),
    ("marks-compound-9-14x14", "compound", "lp_clearance", "7e-14", "from 0.005 to 0.5"),
], ids=["governor-ratio", "exhaust-ratio", "lever-ratio-inf", "lever-ratio-huge",
        "discharge-coefficient", "pipe-discharge-coefficient", "clearance", "lp-clearance"])
def test_ratios_and_fractions_outside_their_range_are_refused(name, section, key, value, why,
                                                              tmp_path, capsys):
    """Were accepted: ratios of 1e12 (an infinite lever ratio gave non-finite events),
    coefficients of discharge of 1e-12, a clearance of 1e-13 (which drove the steam out
    of its properties once the run had begun)."""
    path = _mutated(tmp_path, name, section, key, value)
    err = _refused(["run", str(path)], tmp_path / "out", capsys, f"{section}.{key}")
    assert why in err


@pytest.mark.parametrize("name, section, key, value", [
    ("marks-compound-9-14x14", "compound", "receiver_volume", '"1.9e-12 ft3"'),
    ("marks-compound-9-14x14", "compound", "receiver_volume", '"1e-3 ft3"'),
    ("porter-throttling-governor", "supply", "chest_volume", '"3e-13 ft3"'),
    ("watt-throttling-governor", "supply", "chest_volume", '"0.01 ft3"'),
], ids=["receiver-1e-12", "receiver-0.2-percent", "chest-1e-13", "chest-0.6-percent"])
def test_a_vessel_far_smaller_than_its_cylinder_is_refused(name, section, key, value, tmp_path,
                                                          capsys):
    """A receiver of 0.2 % of the HP cylinder ran for minutes over two cycles; a chest of
    0.6 % of the cylinder was drawn below the steam properties after the run began.  A
    vessel is now at least a twentieth of the swept volume it feeds."""
    path = _mutated(tmp_path, name, section, key, value)
    err = _refused(["run", str(path)], tmp_path / "out", capsys, f"{section}.{key}")
    assert "swept volume" in err


@pytest.mark.parametrize("name, key, value", [
    ("watt-throttling-governor", "ball_mass", '"1.2e-11 lb"'),
    ("armington-sims-governor", "weight_mass", '"1e-11 lb"'),
    ("corliss-governor", "arm_angle_at_rest", '"3e-11 deg"'),
], ids=["ball-mass", "weight-mass", "arm-angle"])
def test_a_governor_without_body_is_refused(name, key, value, tmp_path, capsys):
    """A ball of 1e-11 lb made a run step two million times a cycle (30 s, then the
    budget); an arm at 3e-11 deg from the spindle divided by zero (warnings on the
    user's terminal) before another key was blamed."""
    path = _mutated(tmp_path, name, "governor", key, value)
    err = _refused(["run", str(path)], tmp_path / "out", capsys, f"governor.{key}")
    assert "Warning" not in err


def test_a_flywheel_of_a_microgram_is_refused(tmp_path, capsys):
    """A rim of 8e-9 lb was accepted and the run 'stalled at t = 0': no engine has such a
    flywheel; the key's range says what would be valid."""
    path = _mutated(tmp_path, "porter-allen-governor", "flywheel", "rim_weight", '"8e-9 lb"')
    err = _refused(["run", str(path)], tmp_path / "out", capsys, "flywheel.rim_weight")
    assert "from 0.1 kg to 100000 kg" in err
