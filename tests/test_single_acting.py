"""Single-acting cylinders (``[engine] steam_ends``): the engines the period measured
condensation and leakage on were single-acting (Callendar and Nicolson's 10.5 x 12 in
engine, steam "only at the end away from the crank", Min. Proc. ICE 131, 1897-98, in
DPJ 312, 1899, p. 161).  The bundled scene after it runs through every command that
applies to a plain slide valve."""

from __future__ import annotations

import copy
import tomllib

import numpy as np
import pytest

import corliss
from corliss.cli import commands as cli
from corliss.errors import InputError
from corliss.scene import bundled_scenes, scene_from_dict

NAME = "callendar-nicolson-single-acting"


def _data(**changes):
    data = copy.deepcopy(tomllib.loads(bundled_scenes()[NAME].read_text()))
    data["run"]["fidelity"] = "fast"
    for section, values in changes.items():
        data.setdefault(section, {}).update(values)
    return data


_RUNS: dict = {}


def _run(key, **changes):
    if key not in _RUNS:
        _RUNS[key] = corliss.simulate(scene_from_dict(_data(**changes), name=key))
    return _RUNS[key]


def test_the_idle_end_takes_no_steam_and_does_no_work_at_back_pressure():
    """The crank end of a head-end single-acting cylinder: no steam from the chest over
    the cycle (its steam port never opens: exactly zero), its pressure the exhaust's
    (a full port open to it: on the cycle's mean within 0.5 %; within 5 % at every
    sample, for the fast preset's explicit steps ring by up to 4 % about the back
    pressure near the crank end's dead centre, where its volume is least and the port
    stiffest; the standard preset's, 0.3 %), so its work over the cycle is under 1 %
    of the head end's (the pumping through the port)."""
    r = _run("single", run={"effects": ["port_flow", "rod_angularity"]})
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    assert float(r.last_cycle["m_chest_crank_kg"]) == 0.0
    p = last["p_crank_Pa"].to_numpy()
    p_ex = r.scene.exhaust.pressure_Pa
    assert abs(np.mean(p) / p_ex - 1.0) < 0.005
    assert np.all(np.abs(p / p_ex - 1.0) < 0.05)
    s = r.summary
    assert abs(s["mep_crank_Pa"]) < 0.01 * s["mep_head_Pa"]


def test_double_acting_does_about_twice_the_work():
    """The same cylinder double-acting: the crank end's card adds nearly as much as the
    head end's (less the piston rod's area, 2 % of the piston's, and the gear's
    unequal cut-off at the two ends): between 1.6 and 2.1 times the single-acting
    engine's indicated work."""
    single = _run("single", run={"effects": ["port_flow", "rod_angularity"]})
    double = _run("double", run={"effects": ["port_flow", "rod_angularity"]},
                  engine={"steam_ends": "both"})
    ratio = (double.summary["indicated_work_J_per_cycle"]
             / single.summary["indicated_work_J_per_cycle"])
    assert 1.6 < ratio < 2.1


def test_a_bad_steam_ends_is_refused_naming_the_key():
    with pytest.raises(InputError, match="engine.steam_ends"):
        scene_from_dict(_data(engine={"steam_ends": "neither"}), name="bad")


def test_the_bundled_scene_runs_through_every_command(tmp_path, capsys):
    """run, events, gear, animate and design on the bundled single-acting scene (a plain
    slide valve has no setting: sweep and compare, which work a setting or a
    throttle, refuse it with a clear error, exit status 2)."""
    scene = str(bundled_scenes()[NAME])
    out = str(tmp_path)
    assert cli.main(["run", scene, "--out", out, "--fidelity", "fast", "--no-plots"]) == 0
    assert "(head)" in capsys.readouterr().out
    assert cli.main(["events", scene]) == 0
    text = capsys.readouterr().out
    assert "cut-off" in text or "cutoff" in text
    assert cli.main(["gear", scene, "--out", out]) == 0
    assert cli.main(["animate", scene, "--out", out, "--frames", "4", "--no-card"]) == 0
    assert cli.main(["design", scene, "--out", out, "--cutoff", "0.3", "--lead", "0.05in",
                     "--max-opening", "0.3in"]) == 0
    capsys.readouterr()
    assert cli.main(["sweep", scene, "--out", out, "--settings", "0.5,1"]) == 2
    assert cli.main(["compare", scene, "--out", out]) == 2
