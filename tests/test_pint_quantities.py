"""pint quantities as scene values through the Python API (issue 16).

A quantity object is converted by its key's kind to SI by the object itself; corliss
never imports pint.  The scene loaded with pint quantities equals the scene loaded with
the same values as strings: both go through the same SI factors (the inch is 0.0254 m
exactly, the revolution 2 pi rad), so they agree to rounding, 1e-12 relative.
"""

from __future__ import annotations

import copy
import tomllib

import pytest

pint = pytest.importorskip("pint")

from corliss.errors import InputError  # noqa: E402
from corliss.scene.loader import bundled_scenes, scene_from_dict  # noqa: E402

U = pint.UnitRegistry()
BASE = tomllib.loads(bundled_scenes()["default"].read_text(encoding="utf-8"))


def _with(**tables):
    data = copy.deepcopy(BASE)
    for section, keys in tables.items():
        data[section].update(keys)
    return data


def test_pint_quantities_load_as_their_strings():
    strings = scene_from_dict(_with(engine={"bore": "13 in", "stroke": "2 ft"},
                                    run={"speed": "150 rpm"},
                                    valve_gear={"lap": ["0.75 in", "0.8 in"]}))
    objects = scene_from_dict(_with(engine={"bore": 13 * U.inch, "stroke": 2 * U.foot},
                                    run={"speed": 150 * U.rpm},
                                    valve_gear={"lap": [0.75 * U.inch, 0.8 * U.inch]}))
    assert objects.engine.bore_m == pytest.approx(strings.engine.bore_m, rel=1e-12)
    assert objects.engine.stroke_m == pytest.approx(strings.engine.stroke_m, rel=1e-12)
    assert objects.run.speed_rad_s == pytest.approx(strings.run.speed_rad_s, rel=1e-12)
    assert objects.gear.lap_m == pytest.approx(strings.gear.lap_m, rel=1e-12)


def test_a_pint_temperature_keeps_its_offset():
    """400 degF is (400 - 32) * 5/9 + 273.15 K = 477.594 K."""
    s = scene_from_dict(_with(supply={"pressure": "100 psig",
                                      "temperature": U.Quantity(400.0, "degF")}))
    assert s.supply.temperature_K == pytest.approx((400 - 32) * 5 / 9 + 273.15, rel=1e-12)


@pytest.mark.parametrize("tables,key,words", [
    ({"engine": {"bore": 12 * U.kg}}, "engine.bore", "length"),
    ({"supply": {"pressure": 100 * U.psi}}, "supply.pressure", "absolute or gauge"),
    ({"engine": {"bore": 30 * U.m}}, "engine.bore", "length from"),
])
def test_a_wrong_pint_quantity_names_its_key(tables, key, words):
    with pytest.raises(InputError) as e:
        scene_from_dict(_with(**tables))
    assert key in str(e.value) and words in str(e.value), str(e.value)
