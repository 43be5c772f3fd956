"""Scene keys named on the command line (``KEY=LOW:HIGH``) reach the loaded scene in SI."""

import tomllib

import pytest

from corliss.keys import units
from corliss.errors import InputError
from corliss.scene.loader import default_scene_path, scene_from_dict
from corliss.keys.edits import get_key, parse_range, with_keys


def _default():
    return tomllib.loads(default_scene_path().read_text())


def test_a_range_in_inches_sets_the_lap_the_gear_reads():
    """0.9 in written through a range whose unit is given once reaches the slide valve
    as 0.9 x 0.0254 m on both ends (exact conversion, so 1e-12 relative)."""
    r = parse_range("valve_gear.lap=0.8:1.2in")
    assert (r.low, r.high, r.unit) == (0.8, 1.2, "in")
    data = _default()
    scene = scene_from_dict(with_keys(data, {r.key: r.text(0.9)}))
    assert scene.gear.lap_m == pytest.approx((0.9 * units.INCH_m,) * 2, rel=1e-12)
    assert get_key(data, "valve_gear.lap") == "1 in", "the scene read is not changed"


def test_a_dimensionless_range_stays_a_number():
    r = parse_range("engine.clearance=0.04:0.12")
    scene = scene_from_dict(with_keys(_default(), {r.key: r.text(0.1)}))
    assert scene.engine.clearance == pytest.approx((0.1, 0.1))


@pytest.mark.parametrize("spec, key", [
    ("valve_gear.lap", "--vary"),                      # no range
    ("lap=0.8in:1.2in", "--vary"),                     # not dotted
    ("valve_gear.lap=1.2in:0.8in", "--vary valve_gear.lap"),   # low above high
    ("valve_gear.lap=0.8in:30mm", "--vary valve_gear.lap"),    # two units
])
def test_a_bad_range_names_the_option(spec, key):
    with pytest.raises(InputError) as err:
        parse_range(spec)
    assert err.value.key == key


def test_a_key_of_a_missing_table_is_refused():
    with pytest.raises(InputError) as err:
        with_keys(_default(), {"governor.spring.rate": "10 lbf/in"})
    assert err.value.key == "governor.spring.rate"
