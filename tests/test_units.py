"""Quantity strings: conversions checked against the definitions of the units."""

import math

import pytest

from corliss.keys import units
from corliss.errors import InputError


def test_gauge_pressure_needs_the_barometer():
    # 100 psig on a standard barometer is 114.696 psia; 1 psi = 6894.757 Pa (NIST SP 811).
    assert units.parse("100 psig", "pressure") == pytest.approx(114.696 * 6894.757, rel=1e-6)
    # the same gauge reading on a mountain barometer of 12 psia
    assert units.parse("100 psig", "pressure", barometer_Pa=12 * units.PSI_Pa) == pytest.approx(
        112 * units.PSI_Pa, rel=1e-12)


def test_vacuum_is_read_down_from_the_barometer():
    # 26 inHg vacuum with a 29.92 inHg barometer leaves 3.92 inHg absolute = 13.27 kPa
    baro = 29.92 * 3386.389
    assert units.parse("26 inHg vacuum", "pressure", barometer_Pa=baro) == pytest.approx(
        3.92 * 3386.389, rel=1e-9)


def test_temperatures_and_mixed_fractions():
    assert units.parse("212 degF", "temperature") == pytest.approx(373.15, abs=1e-9)
    assert units.parse("100 degC", "temperature") == pytest.approx(373.15)
    assert units.parse("2 3/4 in", "length") == pytest.approx(2.75 * 0.0254)
    assert units.parse("3/16 in", "length") == pytest.approx(0.1875 * 0.0254)
    assert units.parse("-0.125 in", "length") == pytest.approx(-0.125 * 0.0254)


def test_other_kinds():
    assert units.parse("200 rpm", "speed") == pytest.approx(200 * 2 * math.pi / 60)
    assert units.parse("1 hp", "power") == pytest.approx(550 * 0.3048 * 4.4482216152605)
    assert units.parse("1 lbf ft", "torque") == pytest.approx(1.3558179483, rel=1e-9)
    assert units.parse("1.5 min", "time") == 90.0
    assert units.parse("25 deg", "angle") == pytest.approx(math.radians(25))
    assert units.parse("1 lb ft2", "inertia") == pytest.approx(0.0421401101, rel=1e-8)


@pytest.mark.parametrize("text,kind", [("12", "length"), (12, "length"), ("100 psi", "pressure"),
                                       ("3 furlongs", "length"), ("100 rpm", "length")])
def test_bad_quantities_are_refused_with_the_key(text, kind):
    with pytest.raises(InputError) as e:
        units.parse(text, kind, "engine.bore")
    assert "engine.bore" in str(e.value)


def test_round_trip():
    for unit in ("psia", "psig", "bar", "kPa"):
        v = units.from_unit(123.4, unit)
        assert units.to_unit(v, unit) == pytest.approx(123.4)


def test_output_frames_convert_rates_torques_and_powers():
    """CSV columns leave in the scene's units with the unit in the name: 1 lb/h of steam
    is 0.45359237 kg/h, 1 lbf ft is 1.3558179483 N m, 1 hp is 745.69987 W (550 ft lbf/s),
    pressures absolute."""
    import pandas as pd

    from corliss.frames.columns import convert_frame
    df = pd.DataFrame({"steam_rate_kg_per_h": [0.45359237], "torque_N_m": [1.3558179483314004],
                       "power_W": [745.69987158227], "p_head_Pa": [101325.0]})
    us, us_units = convert_frame(df, "US", 101325.0)
    assert us["steam_rate_lb_per_h"][0] == pytest.approx(1.0)
    assert us["torque_lbf_ft"][0] == pytest.approx(1.0)
    assert us["power_hp"][0] == pytest.approx(1.0)
    assert us["p_head_psia"][0] == pytest.approx(14.695949, rel=1e-6)
    assert set(us_units) == set(us.columns)
    si, si_units = convert_frame(df, "SI", 101325.0)
    assert si["steam_rate_kg_per_h"][0] == pytest.approx(0.45359237)
    assert si["p_head_kPa_abs"][0] == pytest.approx(101.325)
    assert set(si_units) == set(si.columns)


@pytest.mark.parametrize("text, absolute_Pa", [
    # 7 bar absolute is 700 kPa; gauge adds the standard barometer, 101.325 kPa
    ("7 bara", 7e5), ("7 bar(a)", 7e5), ("7 bar abs", 7e5), ("7 bar absolute", 7e5),
    ("7 barg", 7e5 + 101_325.0), ("7 bar(g)", 7e5 + 101_325.0), ("7 bar gauge", 7e5 + 101_325.0),
    ("700 kPa(a)", 7e5), ("700 kPa abs", 7e5), ("700 kPa(g)", 801_325.0), ("700 kPag", 801_325.0),
    ("0.7 MPa(a)", 7e5), ("0.7 MPa(g)", 801_325.0),
    ("100 psi(a)", 100 * 6894.757293168361), ("100 psi gage", 114.69594877551 * 6894.757293168361),
    ("101325 Pa", 101_325.0), ("1 atm", 101_325.0),
])
def test_absolute_and_gauge_spelt_out(text, absolute_Pa):
    """Every pressure unit a gauge may read in is taken as absolute or gauge only when
    the scene says which (1 bar = 1e5 Pa, 1 psi = 6894.757 Pa, NIST SP 811; the standard
    atmosphere 101 325 Pa)."""
    assert units.parse(text, "pressure") == pytest.approx(absolute_Pa, rel=1e-9)


@pytest.mark.parametrize("text, spelt", [("7 bar", "7 bara"), ("700 kPa", "700 kPa(a)"),
                                         ("0.7 MPa", "0.7 MPa(g)"), ("100 psi", "100 psig")])
def test_a_bare_pressure_unit_is_refused_with_its_spellings(text, spelt):
    with pytest.raises(InputError) as e:
        units.parse(text, "pressure", "supply.pressure")
    assert e.value.key == "supply.pressure" and spelt in str(e.value)
    assert "does not say which" in str(e.value)


@pytest.mark.parametrize("text", ["120 rpm", "120 RPM", "120 rev/min", "120 r/min", "2 rev/s"])
def test_speed_spellings(text):
    """120 revolutions a minute are 4 pi rad/s, as is 2 rev/s."""
    assert units.parse(text, "speed") == pytest.approx(4.0 * math.pi, rel=1e-12)


def test_a_misspelt_key_is_reported_missing_with_the_key_the_scene_has():
    """``boer`` for ``bore``: the message says engine.bore is missing and names the
    misspelling; an unknown key is refused with the nearest key the table takes."""
    import tomllib

    from corliss.scene.loader import default_scene_path, scene_from_dict
    data = tomllib.loads(default_scene_path().read_text())
    data["engine"]["boer"] = data["engine"].pop("bore")
    with pytest.raises(InputError) as e:
        scene_from_dict(data)
    assert e.value.key == "engine.bore"
    assert str(e.value).startswith("engine.bore is missing") and "engine.boer" in str(e.value)
    data = tomllib.loads(default_scene_path().read_text())
    data["valve_gear"]["eccentricty"] = "3 in"
    with pytest.raises(InputError) as e:
        scene_from_dict(data)
    assert e.value.key == "valve_gear.eccentricty"
    assert "valve_gear.eccentricity?" in str(e.value)


def test_thou_is_a_thousandth_of_an_inch_wherever_a_length_is_read():
    """``thou``: 0.001 in, the inch being 25.4 mm exactly (international yard and pound,
    1959), so 15 thou = 0.381 mm.  A scene's lap and lead in thou give the valve events
    of the same lap and lead in inches, to the last bit of the events' arithmetic
    (1e-12 of a fraction of the stroke: 1 in and 1000 thou differ by a rounding of
    the factor's last bit), and a study's range and a design's lead read it too."""
    from corliss.engine.model import scene_events
    from corliss.keys.edits import parse_range
    from tests.conftest import make_scene

    assert units.parse("15 thou", "length") == pytest.approx(0.381e-3, rel=1e-12)
    assert units.parse("2 1/2 thou", "length") == pytest.approx(2.5 * 25.4e-6, rel=1e-12)
    assert units.to_unit(0.381e-3, "thou") == pytest.approx(15.0, rel=1e-12)
    inches = scene_events(make_scene(valve_gear={"lap": "1 in", "lead": "0.25 in"}))
    thou = scene_events(make_scene(valve_gear={"lap": "1000 thou", "lead": "250 thou"}))
    for end in ("head", "crank"):
        for key, value in inches[end].items():
            if isinstance(value, float):
                assert thou[end][key] == pytest.approx(value, abs=1e-12), (end, key)
    r = parse_range("valve_gear.lap=900:1100thou")
    assert (r.low, r.high, r.unit) == (900.0, 1100.0, "thou")
    with pytest.raises(InputError, match="angle in one of"):
        units.parse("15 thou", "angle")
