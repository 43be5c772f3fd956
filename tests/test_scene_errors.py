"""Mistaken scenes fail before any work, with a message naming the key and what is valid."""

import json
import subprocess
import sys

import pytest

import corliss
from corliss.errors import InputError

from conftest import make_scene


@pytest.mark.parametrize("changes,key,words", [
    ({"engine": {"bore": "12"}}, "engine.bore", "unit"),
    ({"valve_gear": {"lap": "3.5 in"}}, "valve_gear.lap", "never opens"),
    ({"engine": {"connecting_rod": "12 in"}}, "engine.connecting_rod", "longer than the crank"),
    ({"supply": {"pressure": "0 psig"}}, "supply.pressure", "above the exhaust"),
    ({"exhaust": {"pressure": "120 psig"}}, "supply.pressure", "above the exhaust"),
    ({"engine": {"strok": "24 in"}}, "engine.strok", "known key"),
    ({"valve_gear": {"type": "walschaert"}}, "valve_gear.type", "slide_valve"),
    ({"valve_gear": {"eccentricty": "3 in"}}, "valve_gear.eccentricty", "known key"),
    ({"valve_gear": {"port_width": None}}, "valve_gear.port_width", "required"),
    ({"supply": {"pressure": "100 psi"}}, "supply.pressure", "psig"),
    ({"supply": {"temperature": "250 degF"}}, "supply.temperature", "saturation"),
    # ideal ports carry the skin wall only (issue 12)
    ({"engine": {"wall_heat_model": "marks"}, "run": {"effects": ["wall_heat"]}},
     "engine.wall_heat_model", "port_flow"),
    ({"engine": {"wall_heat_model": "english"}, "run": {"effects": ["wall_heat"]}},
     "engine.wall_heat_model", "port_flow"),
    ({"engine": {"wall_heat_model": "englsh"}}, "engine.wall_heat_model", "'english'"),
    ({"run": {"effects": ["wall_heat"], "model": "ideal"}}, "run.model", "crank_resolved"),
    ({"run": {"effects": ["port_flo"]}}, "run.effects", "port_flow"),
    ({"run": {"model": "exact"}}, "run.model", "crank_resolved"),
    ({"engine": {"clearance": 0}}, "engine.clearance", "between 0 and 1"),
    ({"valve_gear": {"lead": "2.5 in"}}, "valve_gear.lead", "eccentricity"),
])
def test_mistakes_name_their_key(changes, key, words):
    with pytest.raises(InputError) as e:
        make_scene(**changes)
    msg = str(e.value)
    assert key in msg, msg
    assert words in msg, msg


def test_unknown_section(base_dict):
    base_dict["gearing"] = {}
    with pytest.raises(InputError, match="gearing"):
        corliss.scene_from_dict(base_dict)


def test_cli_bad_scene_exits_2_without_traceback_or_files(tmp_path, base_dict):
    """A user's mistake: exit code 2, one paragraph on stderr, nothing written."""
    bad = tmp_path / "bad.toml"
    bad.write_text(
        "[engine]\nbore = \"12 in\"\nstroke = \"24 in\"\nconnecting_rod = \"10 in\"\n"
        "clearance = 0.08\n[supply]\npressure = \"100 psig\"\n[exhaust]\npressure = \"0 psig\"\n"
        "[valve_gear]\ntype = \"slide_valve\"\neccentricity = \"3 in\"\nlap = \"1 in\"\n"
        "lead = \"0.25 in\"\nport_width = \"1 in\"\nport_length = \"9 in\"\n"
        "[run]\nspeed = \"120 rpm\"\n")
    out = tmp_path / "out"
    p = subprocess.run([sys.executable, "-m", "corliss.cli.commands", "run", str(bad), "--out", str(out)],
                       capture_output=True, text=True)
    assert p.returncode == 2
    assert "engine.connecting_rod" in p.stderr
    assert "Traceback" not in p.stderr
    assert not out.exists()
    p = subprocess.run([sys.executable, "-m", "corliss.cli.commands", "events", str(tmp_path / "nope.toml"),
                        "--json"], capture_output=True, text=True)
    assert p.returncode == 2 and "scene" in p.stderr and "Traceback" not in p.stderr


def test_scene_example_round_trips(base_dict):
    """The contract's scene loads, and every value is SI."""
    s = corliss.scene_from_dict(base_dict)
    assert s.engine.bore_m == pytest.approx(0.3048)
    assert s.supply.pressure_Pa == pytest.approx(114.696 * 6894.757, rel=1e-6)
    assert s.run.speed_rpm == pytest.approx(120.0)
    json.dumps(s.resolved())
