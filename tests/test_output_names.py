"""Output names that never collide: every command's files carry the scene's name, the
command, and the unit system when it is not the scene's own
(:func:`corliss.files.run_output.output_stem`); a design or fit that would still
replace another of the same name is refused, exit 2, before any work.

Issue 28: ``design`` and ``fit`` wrote fixed names (``design.toml``, ``fit.json``),
so the README's two ``design`` lines overwrote each other, and a US and an SI run of
one scene wrote the same files.
"""

from __future__ import annotations

import hashlib
import json
import tomllib

import pytest

from corliss.cli import commands as cli
from corliss.keys import units


def _snapshot(folder):
    """{name: SHA-256} of every file in ``folder``."""
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest()
            for p in folder.iterdir() if p.is_file()}


def test_commands_and_unit_systems_into_one_folder_never_overwrite_each_other(
        tmp_path, capsys, monkeypatch):
    """Into one ``--out``: a run of the default scene in its own units (US) and in
    SI, the README's two designs (the default scene's valve, the Stephenson link's
    notch) and the default's design in SI, the gear's figure in both systems, and a
    fit of the lap to the run's own card in both systems.  Each command adds files
    and changes none written before it.  The two runs are the same engine: their
    indicated powers agree (hp against kW, 1e-9: the same run, converted)."""
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "out"
    seen: dict[str, str] = {}

    def step(argv):
        assert cli.main(argv + ["--out", str(out)]) == 0, argv
        capsys.readouterr()
        now = _snapshot(out)
        changed = [n for n, h in seen.items() if now.get(n) != h]
        assert not changed, (argv, changed)
        added = set(now) - set(seen)
        assert added, argv                     # each command wrote files of its own
        seen.update(now)
        return added

    fast = ["--fidelity", "fast", "--cycles", "2", "--no-plots"]
    us = step(["run", *fast])
    si = step(["run", "--units", "SI", *fast])
    assert "default.summary.json" in us and "default.SI.summary.json" in si
    p_us = json.loads((out / "default.summary.json").read_text())["indicated_power_W"]
    p_si = json.loads((out / "default.SI.summary.json").read_text())["indicated_power_W"]
    assert p_si == pytest.approx(p_us, rel=1e-9)
    assert "default.design.toml" in step(["design", "--cutoff", "0.6", "--lead", "0.25in",
                                          "--max-opening", "1.25in", "--release", "0.9"])
    assert "hinkley-stephenson-link.design.toml" in step(
        ["design", "hinkley-stephenson-link", "--cutoff", "0.35"])
    assert "default.SI.design.toml" in step(["design", "--units", "SI", "--cutoff", "0.6",
                                             "--lead", "6mm", "--max-opening", "31mm",
                                             "--release", "0.9"])
    assert "default.gear.png" in step(["gear", "default"])
    assert "default.SI.gear.png" in step(["gear", "default", "--units", "SI"])
    card = str(out / "default.cards.csv")
    vary = ["--vary", "valve_gear.lap=0.8:1.2in", "--no-plots"]
    assert {"default.fit.json", "default.fit.toml"} == step(["fit", "default", card, *vary])
    assert {"default.SI.fit.json", "default.SI.fit.toml"} == step(
        ["fit", "default", card, *vary, "--units", "SI"])
    # the fit in SI is a scene in SI, the lap fitted in millimetres: the same fit as
    # the US one's inches, to the 0.005 mm of its rounding (to 0.01 mm)
    lap_si = tomllib.loads((out / "default.SI.fit.toml").read_text())["valve_gear"]["lap"]
    lap_us = tomllib.loads((out / "default.fit.toml").read_text())["valve_gear"]["lap"]
    assert lap_si.endswith(" mm") and lap_us.endswith(" in")
    assert units.parse(lap_si, "length") == pytest.approx(units.parse(lap_us, "length"),
                                                          abs=0.005e-3 + 1e-12)


def test_a_second_design_of_one_scene_is_refused_not_written_over(tmp_path, capsys):
    """Two designs of the default scene into one folder share their stem; the second
    is refused with exit 2, naming ``--out``, the file and what to do, and the folder
    is as the first left it.  The same design again writes the same text, and may."""
    out = tmp_path / "out"
    first = ["design", "--cutoff", "0.6", "--lead", "0.25in", "--max-opening", "1.25in",
             "--release", "0.9", "--out", str(out)]
    assert cli.main(first) == 0
    before = _snapshot(out)
    capsys.readouterr()
    assert cli.main(["design", "--cutoff", "0.7", "--lead", "0.25in", "--max-opening",
                     "1.25in", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and "default.design.toml" in err and "another --out" in err, err
    assert "Traceback" not in err
    assert _snapshot(out) == before
    assert cli.main(first) == 0
    assert _snapshot(out) == before


def test_a_second_fit_of_other_ranges_is_refused_before_any_simulation(tmp_path, capsys):
    """A folder holding a fit of the scene (``default.fit.json``) refuses a fit of
    other ranges with exit 2 before any simulation (the recorded ranges differ), and
    is left as it was."""
    out = tmp_path / "out"
    out.mkdir()
    card = tmp_path / "card.csv"
    card.write_text("end,crank_angle [deg],pressure [psig]\nhead,0,80\nhead,90,60\n")
    (out / "default.fit.json").write_text(json.dumps({"vary": ["valve_gear.lap=0.8:1.2in"]}))
    before = _snapshot(out)
    assert cli.main(["fit", "default", str(card), "--vary", "engine.clearance=0.04:0.14",
                     "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "default.fit.json" in err and "another --out" in err and "Traceback" not in err
    assert _snapshot(out) == before
