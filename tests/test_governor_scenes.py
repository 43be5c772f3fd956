"""Every governor in the registry has a scene that runs its load step and writes its CSVs."""

import json
import tomllib
from pathlib import Path

import pandas as pd
import pytest

from corliss.cli import commands as cli
from corliss.governors import GOVERNORS

SCENES = Path(__file__).resolve().parent.parent / "scenes"


def governed_scenes():
    out = {}
    for path in sorted(SCENES.glob("*.toml")):
        data = tomllib.loads(path.read_text())
        if "governor" in data:
            out[path] = data["governor"]["type"]
    return out


def test_every_governor_has_a_scene():
    covered = set(governed_scenes().values())
    assert set(GOVERNORS) <= covered, sorted(set(GOVERNORS) - covered)


@pytest.mark.parametrize("path", sorted(governed_scenes()), ids=lambda p: p.stem)
def test_governed_scene_runs_its_load_step(path, tmp_path, capsys):
    """The scene's load step as bundled: it writes the per-turn table and the time series
    with their meta files and the figure; the governor catches the step (the speed
    settles to the scene's band and does not hunt) with a regulation of a few per cent
    at most, of the sign a centrifugal governor gives (Marks Art. 70: a lighter load runs
    faster)."""
    assert cli.main(["run", str(path), "--out", str(tmp_path), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    for suffix in ("cycles.csv", "cycles.meta.json", "timeseries.csv", "timeseries.meta.json",
                   "loadstep.png", "summary.json"):
        assert (tmp_path / f"{path.stem}.{suffix}").is_file(), suffix
    cycles = pd.read_csv(tmp_path / f"{path.stem}.cycles.csv")
    assert len(cycles) == s["turns"]
    assert not s["stalled"] and not s["hunting"]
    assert s["settling_time_s"] is not None
    load = tomllib.loads(path.read_text())["load"]
    if load.get("step_fraction", 1.0) < 1.0:
        assert 0.0 <= s["regulation_frac"] < 0.12
