"""The scene reference is the loader's own declarations (issue 16).

The committed page equals the generator's output; the keys it lists are the keys the
loader accepts: every declared key, set in a bundled scene of its gear, governor or
section, is read (refused, if at all, for its value or its settings, never as an
unknown key), and every key a bundled scene uses is declared.  ``corliss explain`` and
``corliss list keys`` print the same declarations.
"""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path

import pytest

from corliss.cli import commands as cli
from corliss.keys import units
from corliss.errors import InputError
from corliss.governors import GOVERNORS
from corliss.keys.declared import REQUIRED, Derived, Key, UndeclaredKeyError, group
from corliss.scene.loader import bundled_scenes, scene_from_dict
from corliss.scene.reference import REGENERATE, reference_markdown
from corliss.scene.sections import SECTION_KEYS
from corliss.keys.toml_table import Table
from corliss.valves import GEARS

PAGE = Path(__file__).resolve().parent.parent / "docs" / "scene-reference.md"
SCENES = {name: tomllib.loads(p.read_text(encoding="utf-8"))
          for name, p in bundled_scenes().items()}
#: The words of the two refusals :meth:`corliss.keys.toml_table.Table.finish` makes: a key that
#: no declaration has, and a declared key these settings do not read.
UNKNOWN, UNREAD = "a known key", "reads it only"


def test_committed_page_is_the_generated_one():
    assert PAGE.read_text(encoding="utf-8") == reference_markdown(), (
        f"docs/scene-reference.md is stale: regenerate it with `{REGENERATE}`")


def _table_of(section: str, data: dict):
    """The group a bundled scene's table is read through."""
    if section in ("valve_gear", "lp_valve_gear"):
        return GEARS[data["type"]].keys
    if section == "governor":
        return GOVERNORS[data["type"]].keys
    return SECTION_KEYS[section]


def test_every_key_a_bundled_scene_uses_is_declared():
    for name, data in SCENES.items():
        for section, table in data.items():
            if section == "title":
                continue
            declared = _table_of(section, table)
            missing = set(table) - set(declared.names)
            assert not missing, f"{name}: [{section}] {sorted(missing)} not declared"


def _example(k: Key, section: str, scenes: list):
    """A value for ``k``: its default, else one a bundled scene gives it, else one of its
    kind (a value out of range is refused for its value, which still shows it read)."""
    if k.default is not REQUIRED and k.default is not None and not isinstance(k.default,
                                                                              Derived):
        return k.default
    for data in scenes:
        if k.name in data.get(section, {}):
            return data[section][k.name]
    if k.is_quantity:
        return f"1 {units.RANGES[k.kind][2]}"
    return {"number": 0.5, "integer": 1, "choice": (k.choices or ("x",))[0], "string": "x",
            "flag": False, "list": list(k.choices[:1]), "fraction": 0.1,
            "number_pair": [0.2, 0.8], "angle_list": ["0 deg"], "arc": "0.1 in"}[k.kind]


def _cases():
    """(scene name, section, group) for every gear, governor and section."""
    cases = []
    for section, reg in (("valve_gear", GEARS), ("governor", GOVERNORS)):
        for type_name in sorted(reg):
            scene = next(n for n, d in SCENES.items()
                         if d.get(section, {}).get("type") == type_name)
            cases.append((scene, section, reg[type_name].keys))
    for section, g in SECTION_KEYS.items():
        scene = next((n for n, d in SCENES.items() if section in d), "default")
        cases.append((scene, section, g))
    return cases


@pytest.mark.parametrize("scene,section,keys", _cases(),
                         ids=lambda v: getattr(v, "name", v))
def test_every_declared_key_is_read(scene, section, keys):
    """Set each declared key the scene lacks; the loader reads it: it loads, or refuses
    the value or the combination; a key declared without a condition is never left
    unread, and none is refused as unknown."""
    base = SCENES[scene]
    same_kind = [d for d in SCENES.values()
                 if d.get(section, {}).get("type") == base.get(section, {}).get("type")]
    for k in keys.keys:
        if k.name in base.get(section, {}):
            continue
        data = copy.deepcopy(base)
        data.setdefault(section, {})[k.name] = _example(k, section, same_kind)
        try:
            scene_from_dict(data)
        except InputError as exc:
            msg = str(exc)
            assert UNKNOWN not in msg, f"{section}.{k.name} refused as unknown: {msg}"
            if UNREAD in msg:
                assert k.when, f"{section}.{k.name} is declared as always read: {msg}"


@pytest.mark.parametrize("scene,section,keys", _cases(),
                         ids=lambda v: getattr(v, "name", v))
def test_a_declared_default_is_the_loaders(scene, section, keys):
    """The scene without a key loads as the scene with the key set to its declared
    default (or both are refused alike): the default the reference shows is the one the
    loader takes, for every key read whatever the settings."""
    base = SCENES[scene]
    for k in keys.keys:
        if k.required or k.default is None or isinstance(k.default, Derived) or k.when:
            continue
        without, written = copy.deepcopy(base), copy.deepcopy(base)
        without.setdefault(section, {}).pop(k.name, None)
        written.setdefault(section, {})[k.name] = k.default
        assert _outcome(without) == _outcome(written), \
            f"{section}.{k.name}: the loader's default is not {k.default_text()}"


def _outcome(data: dict) -> str:
    """The scene loaded (its repr: NaN equals NaN there), or that it was refused (the
    key named may differ: a default can make another key the culprit)."""
    try:
        return repr(scene_from_dict(data))
    except InputError:
        return "refused"


def test_reading_an_undeclared_key_is_a_programming_error():
    t = Table({"lap": "1 in"}, "valve_gear",
              keys=group("g", "A group.", Key("lap", "length", "Lap.", unit="in")))
    assert t.get("lap") == pytest.approx(0.0254)
    with pytest.raises(UndeclaredKeyError):
        t.has("lead")
    with pytest.raises(UndeclaredKeyError):
        t.angle("lap")          # read as another kind than declared


def test_a_misspelt_required_gear_key_is_missing_with_the_closest_named():
    data = copy.deepcopy(SCENES["default"])
    data["valve_gear"]["eccentricty"] = data["valve_gear"].pop("eccentricity")
    with pytest.raises(InputError) as e:
        scene_from_dict(data)
    msg = str(e.value)
    assert "valve_gear.eccentricity" in msg and "required" in msg, msg
    assert "valve_gear.eccentricty" in msg, msg


def test_a_required_key_given_under_another_gears_name_is_named():
    """Issue 16's Stephenson locomotive: a user who writes the slide valve's ``lead``
    for the link's ``angular_advance`` is told the advance is missing and that the
    ``lead`` written instead is not a key of the link motion."""
    data = copy.deepcopy(SCENES["hinkley-stephenson-link"])
    data["valve_gear"].pop("angular_advance")
    data["valve_gear"]["lead"] = "0.25 in"
    with pytest.raises(InputError) as e:
        scene_from_dict(data)
    msg = str(e.value)
    assert "valve_gear.angular_advance" in msg and "required" in msg, msg
    assert "valve_gear.lead" in msg and "link_motion does not take" in msg, msg


def test_a_declared_key_another_setting_reads_says_so():
    """``radius_rod`` of the Polonceau gear is read with the exact motion only."""
    data = copy.deepcopy(SCENES["polonceau-valve"])
    data["valve_gear"]["motion"] = "zeuner"
    data["valve_gear"]["radius_rod"] = "40 in"
    with pytest.raises(InputError) as e:
        scene_from_dict(data)
    assert "valve_gear.radius_rod" in str(e.value) and "motion" in str(e.value)


def test_another_gears_key_is_named_as_such():
    """Issue 16's Stephenson locomotive: ``lead`` is the slide valve's, not the link's."""
    data = copy.deepcopy(SCENES["hinkley-stephenson-link"])
    data["valve_gear"]["lead"] = "0.25 in"
    with pytest.raises(InputError) as e:
        scene_from_dict(data)
    msg = str(e.value)
    assert "valve_gear.lead" in msg and "angular_advance" in msg, msg
    assert "lead is a key of slide_valve" in msg, msg


def test_explain_prints_a_key_as_declared(capsys):
    assert cli.main(["explain", "valve_gear.lap"]) == 0
    out = capsys.readouterr().out
    assert GEARS["slide_valve"].keys["lap"].doc in out
    assert "once or [head, crank]" in out and "slide_valve" in out and "link_motion" in out
    assert cli.main(["explain", "governor.ball_mass"]) == 0
    out = capsys.readouterr().out
    assert "lb" in out and "porter" in out and "spring" in out
    assert cli.main(["explain", "run.effects"]) == 0
    out = capsys.readouterr().out
    assert "wall_heat" in out and "port_flow" in out
    assert cli.main(["explain", "slide_valve"]) == 0
    out = capsys.readouterr().out
    assert "valve_gear.angular_advance" in out and "valve_gear.lead" in out


def test_explain_an_unknown_key_suggests_the_closest(capsys):
    assert cli.main(["explain", "valve_gear.lapp"]) == 2
    err = capsys.readouterr().err
    assert "valve_gear.lap" in err and "closest" in err


def test_explain_a_key_without_its_section_explains_every_table_s(capsys):
    """``corliss explain lap``: the key in every table that declares it, the gear's
    ``[valve_gear]`` first, and nothing for a name no table has."""
    assert cli.main(["explain", "lap"]) == 0
    out = capsys.readouterr().out
    assert out.index("valve_gear.lap") < out.index("lp_valve_gear.lap")
    assert cli.main(["explain", "bore"]) == 0
    assert capsys.readouterr().out.startswith("engine.bore")
    assert cli.main(["explain", "xyzzy"]) == 2


def test_list_keys_of_a_governor(capsys):
    assert cli.main(["list", "keys", "porter"]) == 0
    out = capsys.readouterr().out
    assert "governor.load_mass" in out and "governor.opening_at_rest" in out
    assert "governor.setting_at_rest" not in out        # a throttling governor
    assert cli.main(["list", "keys", "portr"]) == 2
    assert "porter" in capsys.readouterr().err
