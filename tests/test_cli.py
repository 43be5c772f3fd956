"""The CLI and the JSON contract that scripts outside the project read."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from corliss.cli import commands as cli

SUMMARY_KEYS = ("indicated_power_W", "indicated_power_hp", "mep_head_Pa", "mep_crank_Pa",
                "mep_mean_Pa", "steam_rate_kg_per_h", "water_rate_kg_per_kWh",
                "water_rate_lb_per_ihp_h", "speed_rpm", "cycles_to_converge", "events")
EVENT_KEYS = ("admission_deg", "cutoff_deg", "cutoff_frac", "release_deg", "release_frac",
              "compression_deg", "compression_frac", "lead_m", "max_port_opening_m")
SCENES = Path(__file__).resolve().parent.parent / "scenes"


def test_run_default_writes_card_csv_meta_and_prints_json(tmp_path, capsys):
    assert cli.main(["run", "--out", str(tmp_path), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    for k in SUMMARY_KEYS:
        assert k in s, k
    for end in ("head", "crank"):
        for k in EVENT_KEYS:
            assert k in s["events"][end]
        for k in ("admission_deg", "cutoff_deg", "release_deg", "compression_deg"):
            assert 0.0 <= s["events"][end][k] < 360.0
    # consistency of the contract's units: W = hp * 745.7; kg/kWh = kg/h / kW
    assert s["indicated_power_W"] == pytest.approx(s["indicated_power_hp"] * 745.69987, rel=1e-6)
    assert s["water_rate_kg_per_kWh"] == pytest.approx(
        s["steam_rate_kg_per_h"] / (s["indicated_power_W"] / 1e3), rel=1e-9)
    assert s["speed_rpm"] == pytest.approx(120.0)
    files = sorted(p.name for p in tmp_path.iterdir())
    assert files == ["default.card.png", "default.cards.csv", "default.cards.meta.json",
                     "default.cycles.csv", "default.cycles.meta.json",
                     "default.effort.png", "default.summary.json", "default.timeseries.csv",
                     "default.timeseries.meta.json"]
    meta = json.loads((tmp_path / "default.timeseries.meta.json").read_text())
    for k in ("corliss_version", "coolprop_version", "property_backend", "scene", "columns",
              "created_utc"):
        assert k in meta
    header = (tmp_path / "default.timeseries.csv").read_text().splitlines()[0].split(",")
    assert "p_head_psia" in header and "crank_angle_deg" in header
    assert meta["columns"]["p_head_psia"] == "psia absolute"
    assert (tmp_path / "default.card.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_events_json_matches_the_summary_events(tmp_path, capsys):
    scene = SCENES / "default.toml"
    assert cli.main(["events", str(scene), "--json"]) == 0
    ev = json.loads(capsys.readouterr().out)
    assert set(ev) == {"head", "crank"}
    for end in ev:
        for k in EVENT_KEYS:
            assert k in ev[end]


def test_console_script_is_installed():
    p = subprocess.run([sys.executable, "-m", "corliss.cli.commands", "list", "gears"],
                       capture_output=True, text=True)
    assert p.returncode == 0 and "slide_valve" in p.stdout


def test_fidelity_and_cycles_change_time_not_meaning(tmp_path, capsys):
    """``--fidelity`` and ``--cycles`` from the CLI: the same events and summary keys at
    every tier, indicated power within the 2 % the fast tier promises, and exactly N
    cycles when N is given."""
    out = {}
    for fid in ("fast", "standard"):
        assert cli.main(["run", "--out", str(tmp_path), "--json", "--fidelity", fid]) == 0
        out[fid] = json.loads(capsys.readouterr().out)
    assert out["fast"]["fidelity"] == "fast" and out["standard"]["fidelity"] == "standard"
    assert set(out["fast"]) == set(out["standard"])
    assert out["fast"]["events"] == out["standard"]["events"]
    assert out["fast"]["indicated_power_W"] == pytest.approx(out["standard"]["indicated_power_W"],
                                                             rel=0.02)
    assert cli.main(["run", "--out", str(tmp_path), "--json", "--cycles", "2"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["cycles_simulated"] == 2 and s["cycles_to_converge"] is None


def test_events_at_settings_and_the_gear_drawing(tmp_path, capsys):
    """``corliss events --settings`` lists a link's events notch by notch (the leads of
    Peabody's grades 0, 5 and 10: .350, .278, .063 in), refuses settings for a gear
    without any, and ``corliss gear`` draws the travel and the Zeuner diagram."""
    scene = SCENES / "hinkley-stephenson-link.toml"
    assert cli.main(["events", str(scene), "--settings", "0,0.5,1"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["setting"] for r in rows] == [0.0, 0.5, 1.0]
    leads = [r["head"]["lead_m"] / 0.0254 for r in rows]
    assert leads == pytest.approx([0.350, 0.278, 0.0625], abs=1.5e-3)
    assert cli.main(["events", str(SCENES / "default.toml"), "--settings", "1"]) == 2
    assert "--settings" in capsys.readouterr().err
    assert cli.main(["gear", str(scene), "--out", str(tmp_path)]) == 0
    assert (tmp_path / "hinkley-stephenson-link.gear.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("system", ["US", "SI"])
def test_a_jacketed_run_prints_its_condensation_and_the_jackets_steam(tmp_path, capsys,
                                                                      system):
    """A run with walls prints the missing water of each end, the wetness at cut-off
    with and without the wall's film, and, with a jacket, the
    jacket's steam and the water rate counting it, in the run's units, the same
    figures as its summary file (Marks Art. 79: the jacket is paid for in steam)."""
    text = (SCENES / "meyer-cutoff.toml").read_text()
    text = text.replace("effects = [", 'effects = ["wall_heat", ', 1)
    text = text.replace("[engine]\n", '[engine]\njacket = "barrel"\n', 1)
    text = text.replace('fidelity = "standard"', 'fidelity = "fast"')
    scene = tmp_path / "jacketed.toml"
    scene.write_text(text)
    out = tmp_path / "out"
    assert cli.main(["run", str(scene), "--out", str(out), "--no-plots",
                     "--units", system]) == 0
    printed = capsys.readouterr().out
    # an inch scene's SI files carry the system in their stem (tests/test_output_names.py)
    stem = "jacketed" if system == "US" else "jacketed.SI"
    s = json.loads((out / f"{stem}.summary.json").read_text())
    line = next(x for x in printed.splitlines() if x.strip().startswith("jacket"))
    steam = float(line.split()[1])
    rate = float(line.split("with it")[1].split()[0])
    if system == "US":
        assert steam == pytest.approx(s["jacket_steam_kg_per_h"] / 0.45359237, abs=0.05)
        # kg/kWh to lb per ihp-hour: over 0.45359237 kg/lb, times 0.74570 kW/hp
        assert rate == pytest.approx(s["water_rate_with_jacket_kg_per_kWh"] / 0.45359237
                                     * 0.745699872, rel=1e-3)
        assert "lb per ihp-hour" in line
    else:
        assert steam == pytest.approx(s["jacket_steam_kg_per_h"], abs=0.05)
        assert rate == pytest.approx(s["water_rate_with_jacket_kg_per_kWh"], rel=1e-3)
        assert "kg/kWh" in line
    miss = next(x for x in printed.splitlines() if x.strip().startswith("missing water"))
    assert f"{s['missing_water_fraction_head']:.3f}" in miss
    # the wetness at cut-off both ways: the mixture's own water, and with the wall's
    # film counted (English, through DPJ 267, 1888, p. 302: what counts is all the
    # water present at the end of admission)
    wet = next(x for x in printed.splitlines() if x.strip().startswith("wet at cut-off"))
    for end in ("head", "crank"):
        assert f"{s[f'wet_fraction_at_cutoff_{end}']:.3f} in the steam" in wet
        assert f"{s[f'wet_fraction_at_cutoff_with_film_{end}']:.3f} with the film" in wet


class _Log:
    """A stream that is not a terminal, keeping what was written."""

    def __init__(self):
        self.text = ""

    def isatty(self):
        return False

    def write(self, s):
        self.text += s

    def flush(self):
        pass


def test_a_slow_first_run_step_says_what_it_is_doing_while_it_runs(monkeypatch):
    """A notice opens a step (building the steam table), the next record closes it; a
    numba compile is a step of its own while it lasts; each is reported every few
    seconds while it runs, and nothing once it is over."""
    import logging
    import time

    from numba.core import event

    from corliss.cli import heartbeat
    from corliss.logs import NOTICE
    monkeypatch.setattr(heartbeat, "AFTER_S", 0.5)
    monkeypatch.setattr(heartbeat, "EVERY_S", 0.9)
    stream = _Log()
    beat = heartbeat.Heartbeat(lambda: stream)
    log = logging.getLogger("corliss.test_heartbeat")
    log.addHandler(beat)
    log.setLevel(logging.INFO)
    beat.start()
    try:
        log.log(NOTICE, "building the steam table once for this machine (about a minute)")
        time.sleep(2.3)
        log.info("built steam table in 2.3 s")
        time.sleep(1.5)
        building = stream.text
        assert "still building the steam table" in building
        event.start_event("numba:compile", data={"dispatcher": cli.main})
        time.sleep(2.3)
        event.end_event("numba:compile", data={"dispatcher": cli.main})
        time.sleep(1.5)
    finally:
        beat.stop()
        log.removeHandler(beat)
    compiling = stream.text[len(building):]
    assert "still compiling main" in compiling and "steam table" not in compiling
    assert stream.text.endswith("\n") and stream.text.count("\n") <= 6
