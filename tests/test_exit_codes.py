"""Exit statuses a script can trust (``docs/exit-codes.md``), each provoked by a scene.

0 a good result; 2 a mistake in the input, an unusable output folder included, before
any work and with nothing written; 4 a run that completed but failed physically, with
every file written and the reasons in the summary's ``failures``.  The physics of each
failure is the scene's: a card at ten times its speed through the same ports does
negative work (the piston pushes the steam back through ports it cannot fill, Marks
Art. 9's port sizing is for piston speeds of 600 ft/min, not 6000); a shaft governor
at its top stop with all load thrown off cannot hold the speed (its top stop's cut-off
still makes work); the loop without a dash-pot hunts (Marks Art. 97, and the linear
boundary of tests/test_governed_loop.py); a load five times the engine's stalls it.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from corliss.cli import commands as cli
from corliss.engine.verdict import EXIT_PHYSICAL

SCENES = Path(__file__).resolve().parent.parent / "scenes"

HUNTING = """
title = "loop test engine, no dash-pot"
[engine]
bore = "9 in"
stroke = "10 in"
connecting_rod = "25 in"
piston_rod_diameter = "1.5 in"
clearance = 0.1
friction_torque = "15 lbf ft"
[supply]
pressure = "90 psig"
temperature = "saturated"
[exhaust]
pressure = "1 psig"
[valve_gear]
type = "shaft_governor"
path = "straight"
eccentricity = "1.75 in"
angular_advance = "22 deg"
centre_travel = "1.7 in"
setting = 0.5
lap = "0.5 in"
exhaust_lap = "-0.0625 in"
port_width = "0.75 in"
port_length = "10 in"
discharge_coefficient = 0.75
[governor]
type = "porter_allen"
arm_length = "8 in"
ball_mass = "4 lb"
balls = 2
load_mass = "30 lb"
arm_angle_at_rest = "30 deg"
arm_angle_at_top = "45 deg"
ratio = 0.78
friction = "0 lbf"
dashpot = "0 lbf s/ft"
setting_at_rest = 0.4
setting_at_top = 1.0
[flywheel]
rim_weight = "1500 lb"
mean_radius = "20 in"
[load]
power = "35 hp"
kind = "step"
step_time = "2 s"
step_fraction = 0.8
[run]
mode = "transient"
speed = "280 rpm"
duration = "10 s"
effects = ["port_flow", "rod_angularity", "friction"]
record = "cycle"
[output]
units = "US"
dir = "out"
"""


def _scene(tmp_path: Path, name: str, text: str, *subs: tuple[str, str]) -> Path:
    for old, new in subs:
        assert old in text, old
        text = text.replace(old, new)
    p = tmp_path / f"{name}.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _bundled(name: str) -> str:
    return (SCENES / f"{name}.toml").read_text(encoding="utf-8")


def _run(scene: Path, out: Path, *extra: str) -> tuple[int, dict]:
    rc = cli.main(["run", str(scene), "--out", str(out), "--no-plots", "--fidelity", "fast",
                   *extra])
    summary = json.loads((out / f"{scene.stem}.summary.json").read_text(encoding="utf-8"))
    return rc, summary


def _failures(summary: dict) -> set[str]:
    return {f["failure"] for f in summary["failures"]}


def test_a_good_run_exits_0_with_no_failures(tmp_path):
    rc, s = _run(SCENES / "default.toml", tmp_path)
    assert rc == 0 and s["failures"] == []


def test_negative_work_exits_4_with_files_written(tmp_path, capsys):
    scene = _scene(tmp_path, "too-fast", _bundled("default"),
                   ('speed = "120 rpm"', 'speed = "3000 rpm"'))
    rc, s = _run(scene, tmp_path / "out")
    assert rc == EXIT_PHYSICAL
    assert "negative_work" in _failures(s) and s["indicated_power_W"] < 0
    assert (tmp_path / "out" / "too-fast.cycles.csv").is_file()
    assert "failed (negative_work)" in capsys.readouterr().err


def test_not_periodic_exits_4(tmp_path):
    scene = _scene(tmp_path, "short", _bundled("default"),
                   ('fidelity = "standard"', 'fidelity = "standard"\nmax_cycles = 3\n'
                    'convergence_tolerance = 1e-12'))
    rc = cli.main(["run", str(scene), "--out", str(tmp_path), "--no-plots"])
    s = json.loads((tmp_path / "short.summary.json").read_text(encoding="utf-8"))
    assert rc == EXIT_PHYSICAL and _failures(s) == {"not_periodic"}


def test_run_away_exits_4(tmp_path):
    """All load thrown off a light flywheel with no engine friction: the governor
    reaches its top stop and the speed climbs past the speed it balances at there."""
    scene = _scene(tmp_path, "run-away", _bundled("armington-sims-governor"),
                   ('power = "100 hp"', 'power = "5 hp"'), ('duration = "20 s"', 'duration = "4 s"'),
                   ('step_time = "8 s"', 'step_time = "0.5 s"'),
                   ('step_fraction = 0.5', 'step_fraction = 0.0'),
                   ('friction_torque = "40 lbf ft"', 'friction_torque = "0 lbf ft"'),
                   ('rim_weight = "1500 lb"', 'rim_weight = "300 lb"'))
    rc, s = _run(scene, tmp_path)
    assert rc == EXIT_PHYSICAL and "run_away" in _failures(s)
    top = float(re.search(r"balances there at ([0-9.]+) rpm",
                          s["failures"][0]["reason"]).group(1))
    assert s["final_speed_rpm"] > 1.05 * top


def test_stall_exits_4(tmp_path):
    scene = _scene(tmp_path, "stall", _bundled("armington-sims-governor"),
                   ('step_fraction = 0.5', 'step_fraction = 5.0'),
                   ('step_time = "8 s"', 'step_time = "0.5 s"'),
                   ('duration = "20 s"', 'duration = "4 s"'))
    rc, s = _run(scene, tmp_path)
    assert rc == EXIT_PHYSICAL and "stalled" in _failures(s) and s["stalled"]


def test_hunting_exits_4_and_not_settled_when_settling_was_asked(tmp_path):
    scene = _scene(tmp_path, "hunting", HUNTING)
    rc, s = _run(scene, tmp_path)
    assert rc == EXIT_PHYSICAL and _failures(s) == {"hunting"}   # not settled: not asked
    scene = _scene(tmp_path, "hunting-until", HUNTING,
                   ('record = "cycle"', 'record = "cycle"\nmax_duration = "12 s"'))
    rc, s = _run(scene, tmp_path, "--until-settled")
    assert rc == EXIT_PHYSICAL and {"hunting", "not_settled"} <= _failures(s)


@pytest.mark.parametrize("make_bad", ["file", "under_file"])
def test_unusable_out_exits_2_before_any_work(tmp_path, capsys, make_bad):
    (tmp_path / "a_file").write_text("x")
    out = tmp_path / "a_file" if make_bad == "file" else tmp_path / "a_file" / "sub"
    rc = cli.main(["run", "default", "--out", str(out), "--no-plots"])
    err = capsys.readouterr().err
    assert rc == 2 and "--out" in err and "Nothing was simulated" in err
    assert "Traceback" not in err


def test_python_dash_m_and_verbose_after_the_subcommand():
    import subprocess
    import sys
    p = subprocess.run([sys.executable, "-m", "corliss", "list", "effects", "-v"],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0 and "port_flow" in p.stdout
    assert cli.build_parser().parse_args(["run", "-v"]).verbose is True
    assert cli.build_parser().parse_args(["-v", "run"]).verbose is True
    assert cli.build_parser().parse_args(["run"]).verbose is False


def test_reference_tier_with_marks_law_reads_overheated_steam_at_the_properties_edge(
        tmp_path, capsys):
    """Marks's law returns its heat from cut-off to compression whatever steam is left
    (Art. 75): on the default engine at 120 rpm the thin exhaust steam of the head end
    reaches 8.2 MJ/kg, beyond any steam property (IAPWS-95 is fitted to 1273 K; CoolProp
    finds no state beyond 3000 K).  The run goes on with that state's properties read at
    the greatest energy (docs/limits.md: the one clamp a run goes on with), warning with
    the key to check; the HEOS reference tier's time series read the sampled states
    the same way, where they raised ValueError (a traceback, exit 1, no files).  Each
    sample's temperature is HEOS's at its density and the lesser of its energy and the
    properties' greatest (4.2 MJ/kg): to 1e-6, the CSV's nine significant figures."""
    from corliss.engine.kernels.properties import U_MAX
    from corliss.thermo.steam import HEOSSteam
    scene = _scene(tmp_path, "marks-heos", _bundled("default"),
                   ("clearance = 0.08", "clearance = 0.08\nwall_heat_model = \"marks\""),
                   ('effects = ["port_flow", "rod_angularity"]',
                    'effects = ["port_flow", "rod_angularity", "wall_heat"]'))
    out = tmp_path / "out"
    rc = cli.main(["run", str(scene), "--out", str(out), "--no-plots", "--fidelity",
                   "reference", "--cycles", "2", "--units", "SI"])
    err = capsys.readouterr().err
    assert rc == 0
    assert "Traceback" not in err and "check engine.wall_heat_model" in err
    summary = json.loads((out / "marks-heos.SI.summary.json").read_text(encoding="utf-8"))
    assert summary["clamped_hot_state_evaluations_count"] > 0
    rows = (out / "marks-heos.SI.timeseries.csv").read_text(encoding="utf-8").splitlines()
    head = rows[0].split(",")
    col = {name: head.index(name) for name in ("T_head_degC", "V_head_m3", "m_head_kg")}
    heos = HEOSSteam()
    hottest = max((r.split(",") for r in rows[1:]), key=lambda r: float(r[col["T_head_degC"]]))
    rho = float(hottest[col["m_head_kg"]]) / float(hottest[col["V_head_m3"]])
    T_K = float(hottest[col["T_head_degC"]]) + 273.15
    assert T_K == pytest.approx(heos.du(rho, U_MAX).T, rel=1e-6)
