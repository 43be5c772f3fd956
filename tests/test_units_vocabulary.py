"""One vocabulary: a command that prints a quantity takes --units, and names each
quantity by the unit it is printed in."""

import json

import pytest

from corliss.cli import commands as cli
from corliss.frames.columns import convert_record


def _events(argv, capsys):
    assert cli.main(["events", "default", "--json", *argv]) == 0
    return json.loads(capsys.readouterr().out)


def test_events_print_lengths_in_the_asked_units_named_by_them(capsys):
    """The default scene's slide valve is written with a lead of 0.25 in
    (scenes/default.toml): in US units the head end's lead reads 0.25 as ``lead_in``,
    in SI 6.35 as ``lead_mm`` (25.4 mm to the inch, exact by the 1959 definition), and
    without --units 0.00635 as ``lead_m``, as before.  Angles and fractions are the
    same in every system."""
    si = _events([], capsys)["head"]
    us = _events(["--units", "US"], capsys)["head"]
    mm = _events(["--units", "SI"], capsys)["head"]
    assert si["lead_m"] == pytest.approx(0.00635, rel=1e-12)
    assert us["lead_in"] == pytest.approx(0.25, rel=1e-12) and "lead_m" not in us
    assert mm["lead_mm"] == pytest.approx(6.35, rel=1e-12)
    assert us["max_port_opening_in"] == pytest.approx(si["max_port_opening_m"] / 0.0254)
    for k in ("cutoff_frac", "admission_deg", "compression_frac"):
        assert us[k] == si[k] == mm[k]


def test_a_record_converts_like_a_table():
    """convert_record renames and converts as the tables' columns are: psia absolute
    from Pa (6894.757 Pa to the psi), None kept, labels passed through."""
    got = convert_record({"p_head_Pa": 689475.7, "lead_m": None, "end": "head"}, "US")
    assert got["p_head_psia"] == pytest.approx(100.0, rel=1e-6)
    assert got["lead_in"] is None and got["end"] == "head"


def test_study_prints_its_ranges_in_the_asked_units(tmp_path, capsys):
    """Two runs of the default engine (lap 0.8 and 1.2 in): the indicated power printed
    in hp with --units US and in kW with --units SI, the same power (745.7 W to the
    horse-power); the m.e.p., a difference of pressures, in psi or kPa, not absolute."""
    argv = ["study", "default", "--vary", "valve_gear.lap=0.8:1.2in", "--grid", "--levels",
            "2", "--fidelity", "fast", "--jobs", "1", "--out", str(tmp_path)]
    got = {}
    for system in ("US", "SI"):
        assert cli.main([*argv, "--units", system]) == 0
        lines = capsys.readouterr().out.splitlines()
        got[system] = {ln.split()[0]: float(ln.split()[1]) for ln in lines
                       if ln.startswith("  ") and " to " in ln}
    assert got["US"]["indicated_power_hp"] * 0.7456999 == pytest.approx(
        got["SI"]["indicated_power_kW"], rel=1e-4)       # printed to five figures
    assert got["US"]["mep_mean_psi"] * 6.894757 == pytest.approx(
        got["SI"]["mep_mean_kPa"], rel=1e-4)
