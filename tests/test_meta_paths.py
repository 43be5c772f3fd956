"""A meta file records its scene's file relative to its own folder: no absolute path of
the machine in what a run writes, and a folder moved with its scene still reruns."""

import json
import shutil
from pathlib import Path

import corliss
from corliss.files.run_output import scene_from_meta

SCENE = Path(__file__).resolve().parents[1] / "scenes" / "default.toml"


def test_the_meta_file_records_the_scene_relative_to_itself_and_reruns_after_a_move(tmp_path):
    work = tmp_path / "a"
    (work / "scenes").mkdir(parents=True)
    scene_file = work / "scenes" / "engine.toml"
    shutil.copy(SCENE, scene_file)
    scene = corliss.load_scene(scene_file)
    r = corliss.simulate(scene)
    r.write(work / "out", plots=False)
    metas = sorted((work / "out").glob("*.meta.json"))
    assert metas
    for m in metas:
        text = m.read_text()
        assert json.loads(text)["scene_file"] == "../scenes/engine.toml"
        assert str(tmp_path) not in text
    moved = tmp_path / "b"
    shutil.move(work, moved)
    again = scene_from_meta(moved / "out" / metas[0].name)
    assert Path(again.source).resolve() == (moved / "scenes" / "engine.toml").resolve()
    assert corliss.simulate(again).summary["indicated_power_W"] == r.summary["indicated_power_W"]
