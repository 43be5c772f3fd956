"""Every key a bundled scene's summary holds is declared, with a value of its type.

:class:`~corliss.engine.summary_keys.SteadySummary` and
:class:`~corliss.engine.summary_keys.TransientSummary` are what a type checker reads
for ``result.summary``; the summary itself is built from keys made at run time (per end,
per effect), so nothing but a run proves the declaration covers them.  Each bundled
scene runs as the fingerprint test runs it (``tests/test_every_scene_same_outputs.py``:
steady one cycle at ``fast``, transient 0.1 s at ``fast``) and every key of its summary
must be declared in the typed mapping of its kind, its value of the declared type
(``typing.get_type_hints``: float, int, str, bool, None, list and dict of those, checked
element by element).  A steady scene with a transient mode runs steady too, as the
workbench runs it, so both declarations are held by every scene that can run both.

These settings prove no physics (the physics tests do); a declared key whose value has
another type, or an undeclared key, fails here by name.
"""

from __future__ import annotations

import types
import typing
from typing import Any, Union, get_args, get_origin, get_type_hints

import pytest

from corliss.engine.model import steady_scene
from corliss.engine.simulate import simulate
from corliss.engine.summary_keys import (END_NAMES, SteadySummary, TransientSummary,
                                         end_value)
from corliss.scene import bundled_scenes, load_scene

from conftest import make_scene
from test_every_scene_same_outputs import cheap

STEADY_HINTS = get_type_hints(SteadySummary)
TRANSIENT_HINTS = get_type_hints(TransientSummary)


def conforms(value: Any, hint: Any) -> bool:
    """Whether ``value`` is of the declared type ``hint`` (a bool is no int or float,
    an int no float: the JSON written keeps them apart)."""
    origin = get_origin(hint)
    if origin in (Union, types.UnionType):
        return any(conforms(value, h) for h in get_args(hint))
    if hint is type(None) or hint is None:
        return value is None
    if hint is object or hint is Any:
        return True
    if origin is list:
        (item,) = get_args(hint)
        return isinstance(value, list) and all(conforms(v, item) for v in value)
    if origin is dict:
        k, v = get_args(hint)
        return isinstance(value, dict) and all(
            conforms(key, k) and conforms(val, v) for key, val in value.items())
    if hint is bool:
        return isinstance(value, bool)
    if hint is int:
        return isinstance(value, int) and not isinstance(value, bool)
    if hint is float:
        return isinstance(value, float)
    if hint is str:
        return isinstance(value, str)
    raise TypeError(f"the check does not know the declared type {hint!r}")


def mismatches(summary: dict, hints: dict) -> list[str]:
    """Each key of ``summary`` not declared in ``hints`` or not of its declared type."""
    out = []
    for key, value in summary.items():
        if key not in hints:
            out.append(f"{key!r} is not declared (value {value!r})")
        elif not conforms(value, hints[key]):
            out.append(f"{key!r} = {value!r} ({type(value).__name__}) is declared "
                       f"{hints[key]}")
    return out


SCENES = sorted(bundled_scenes())


@pytest.mark.parametrize("name", SCENES)
def test_every_summary_key_is_declared(name):
    """The scene's summary (steady; and transient where the scene is transient) holds
    only declared keys, each with a value of its declared type."""
    scene = load_scene(bundled_scenes()[name])
    result = simulate(cheap(scene, "fast"))
    hints = TRANSIENT_HINTS if result.kind == "transient" else STEADY_HINTS
    bad = mismatches(dict(result.summary), hints)
    assert not bad, f"{name} ({result.kind}):\n" + "\n".join(bad)
    if result.kind == "transient":
        steady = simulate(cheap(steady_scene(scene), "fast"))
        bad = mismatches(dict(steady.summary), STEADY_HINTS)
        assert not bad, f"{name} (run steady):\n" + "\n".join(bad)


def _edited(name: str, tmp_path, engine: str, effects: str):
    """A bundled scene with lines added to ``[engine]`` and effects to ``run.effects``."""
    text = bundled_scenes()[name].read_text()
    assert "[engine]\n" in text and "effects = [" in text
    text = text.replace("[engine]\n", "[engine]\n" + engine, 1)
    text = text.replace("effects = [", f"effects = [{effects}, ", 1)
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return load_scene(path)


#: Scenes beyond the bundled ones, for the keys no bundled scene writes: every effect
#: (leakage past valve and piston, friction, the chest), a jacket, per-end keys of a
#: second identical cylinder and of a compound's LP, the period's leakage law.
VARIANTS = {
    "every_effect": lambda tmp: make_scene(
        engine={"valve_leakage_area": "0.02 in2", "piston_leakage_area": "0.05 in2",
                "reciprocating_mass": "800 lb", "friction_torque": "300 lbf ft"},
        supply={"chest_volume": "2 ft3", "pipe_diameter": "4 in"},
        run={"effects": ["port_flow", "rod_angularity", "inertia", "steam_chest",
                         "leakage", "wall_heat", "friction"]}),
    "jacket": lambda tmp: make_scene(engine={"jacket": "barrel"},
                                     run={"effects": ["port_flow", "wall_heat"]}),
    "twin_walls_leaks": lambda tmp: _edited(
        "twin-90-degrees", tmp, 'valve_leakage_area = "0.02 in2"\n'
        'piston_leakage_area = "0.05 in2"\n', '"wall_heat", "leakage"'),
    "compound_walls_period_leaks": lambda tmp: _edited(
        "marks-compound-9-14x14", tmp, 'leakage_model = "period"\n'
        'valve_leak_rate = "3 lb/h psi"\npiston_leak_rate = "1 lb/h psi"\n'
        'steam_edge_leak_rate = "3 lb/h psi"\nexhaust_edge_leak_rate = "3 lb/h psi"\n',
        '"wall_heat", "leakage"'),
    "twin_edge_leaks": lambda tmp: _edited(
        "twin-90-degrees", tmp, 'leakage_model = "period"\n'
        'steam_edge_leak_rate = "3 lb/h psi"\nexhaust_edge_leak_rate = "3 lb/h psi"\n',
        '"leakage"'),
}


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_keys_of_effects_no_bundled_scene_asks_are_declared(variant, tmp_path):
    """The keys of the effects, per-end keys of further cylinders and the compound's LP
    (which no bundled scene writes) are declared with their types."""
    result = simulate(cheap(VARIANTS[variant](tmp_path), "fast"))
    bad = mismatches(dict(result.summary), STEADY_HINTS)
    assert not bad, f"{variant}:\n" + "\n".join(bad)
    wanted = {"every_effect": "valve_leak_head_kg_per_h", "jacket": "jacket_heat_W",
              "twin_walls_leaks": "missing_water_fraction_c2_crank",
              "compound_walls_period_leaks": "heat_to_walls_lp_crank_J_per_cycle",
              "twin_edge_leaks": "valve_leak_c2_crank_exhaust_kg_per_h"}[variant]
    assert wanted in result.summary       # the variant writes what it is here for


def test_the_check_refuses_what_is_not_declared():
    """The check itself: an undeclared key, a value of another type, a bool where an
    int is declared and a wrong list element are each reported."""
    summary = {"speed_rpm": 60.0, "indicated_power_W": "12 kW", "no_such_key_W": 1.0,
               "cycles_simulated": True, "effects": ["wall", 3], "cycles_to_converge": None}
    bad = mismatches(summary, STEADY_HINTS)
    assert [b.split()[0] for b in bad] == ["'indicated_power_W'", "'no_such_key_W'",
                                          "'cycles_simulated'", "'effects'"]


def test_light_summary_is_declared():
    """The part of the summary a study reads without the time series
    (``summary_with``) holds declared keys only, the same values as the whole."""
    scene = load_scene(bundled_scenes()["default"])
    result = simulate(cheap(scene, "fast"))
    part = result.summary_with(["indicated_power_W"])
    assert "peak_pressure_Pa" not in part       # the light part, not the whole
    assert not mismatches(dict(part), STEADY_HINTS)
    whole = result.summary
    assert part["indicated_power_W"] == whole["indicated_power_W"]


def test_end_value_reads_each_end():
    """``end_value`` reads the per-end key its parts name, None where it is absent,
    and refuses a key that holds no number."""
    summary: SteadySummary = {"mep_head_Pa": 2.5e5, "mep_crank_Pa": 2.4e5,
                              "wall_temperature_head_K": None, "title": "t"}
    assert end_value(summary, "mep", "head", "Pa") == 2.5e5
    assert end_value(summary, "mep", "crank", "Pa") == 2.4e5
    assert end_value(summary, "wall_temperature", "head", "K") is None
    assert end_value(summary, "missing_water_fraction", "lp_head") is None
    with pytest.raises(TypeError, match="summary key 'title_head'"):
        end_value(typing.cast(SteadySummary, {"title_head": "x"}), "title", "head")
    # every end the helper accepts has its per-end keys declared
    for end in END_NAMES:
        assert f"missing_water_fraction_{end}" in STEADY_HINTS
        assert f"heat_to_walls_{end}_J_per_cycle" in STEADY_HINTS
