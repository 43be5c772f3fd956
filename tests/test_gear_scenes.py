"""Every gear in the registry has a scene, and every scene's gear draws and lists its events."""

import json
import tomllib
from pathlib import Path

import pytest

from corliss.cli import commands as cli
from corliss.valves import GEARS, gear_type

SCENES = Path(__file__).resolve().parent.parent / "scenes"
ALL = sorted(SCENES.glob("*.toml"))


def gear_of(path):
    return tomllib.loads(path.read_text())["valve_gear"]["type"]


def test_every_gear_has_a_scene():
    covered = {gear_of(p) for p in ALL}
    assert set(GEARS) <= covered, sorted(set(GEARS) - covered)


@pytest.mark.parametrize("path", ALL, ids=lambda p: p.stem)
def test_scene_gear_draws_and_gives_events(path, tmp_path, capsys):
    """``corliss gear`` writes the valve-travel and diagram figure; ``corliss events``
    gives both ends' events, at three settings across the range for a gear that has a
    setting, with the cut-off a fraction of the stroke where there is one."""
    assert cli.main(["gear", str(path), "--out", str(tmp_path)]) == 0
    assert (tmp_path / f"{path.stem}.gear.png").stat().st_size > 10_000
    capsys.readouterr()
    from corliss.engine.model import build_gear
    from corliss.scene.loader import load_scene
    gear = build_gear(load_scene(path))
    args = ["events", str(path), "--json"]
    if gear.setting_range is not None:
        lo, hi = gear.setting_range
        args.append("--settings=" + ",".join(f"{v:.6g}" for v in (lo, 0.5 * (lo + hi), hi)))
    assert cli.main(args) == 0
    out = json.loads(capsys.readouterr().out)
    rows = out if isinstance(out, list) else [out]
    for row in rows:
        for end in ("head", "crank"):
            c = row[end]["cutoff_frac"]
            assert c is None or 0.0 <= c <= 1.0
    assert gear_type(gear_of(path)).name == gear_of(path)
