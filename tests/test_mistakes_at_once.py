"""A scene with several mistakes is refused with all of them in one message, so a user
fixes them in one pass instead of one run per mistake."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from corliss.cli import commands as cli
from corliss.errors import InputError, InputErrors
from corliss.scene.loader import bundled_scenes, key_errors, scene_from_dict

SCENES = Path(__file__).resolve().parent.parent / "scenes"


def _default() -> dict:
    return tomllib.loads((SCENES / "default.toml").read_text(encoding="utf-8"))


def test_three_mistakes_reported_together(tmp_path, capsys):
    d = _default()
    d["engine"]["bore"] = "12 furlongs"        # no such unit
    d["engine"]["strok"] = "24 in"             # misspelt key
    d["run"]["fidelity"] = "ultra"             # no such choice
    with pytest.raises(InputErrors) as e:
        scene_from_dict(d)
    keys = [x.key for x in e.value.errors]
    assert keys == ["engine.bore", "engine.strok", "run.fidelity"]
    assert "engine.stroke?" in str(e.value)
    # the command says all three at once, exit 2, nothing written
    text = (SCENES / "default.toml").read_text(encoding="utf-8")
    text = text.replace('bore = "12 in"', 'bore = "12 furlongs"').replace(
        'fidelity = "standard"', 'fidelity = "ultra"').replace('[engine]', '[engine]\nstrok = "24 in"')
    p = tmp_path / "three.toml"
    p.write_text(text, encoding="utf-8")
    assert cli.main(["run", str(p), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("corliss: engine.bore = ") and "2 more mistakes" in err
    assert all(k in err for k in keys)
    assert not (tmp_path / "out").exists()


def test_one_mistake_keeps_its_own_message():
    d = _default()
    d["run"]["fidelity"] = "ultra"
    with pytest.raises(InputError) as e:
        scene_from_dict(d)
    assert not isinstance(e.value, InputErrors) and e.value.key == "run.fidelity"


@pytest.mark.parametrize("name", sorted(bundled_scenes()))
def test_no_bundled_scene_shows_a_key_mistake(name):
    """The key-by-key pass must not refuse what the loader takes."""
    data = tomllib.loads(bundled_scenes()[name].read_text(encoding="utf-8"))
    assert key_errors(data) == []
