"""A study's row is its scene's run, to the bit, whatever ran before it in the process.

A study's runs take shortcuts a single run does not: each run's tables are the base's
with only its keys' path copied, the keys a scene shares with the scenes loaded before
are read once (:meth:`corliss.keys.toml_table.Table.get`), a run computes only the
part of its summary the study records and never builds its time series, the events
read the port map's own samples, and a network's column colours are kept by layout.
None of it may change a number: a row's responses are those of the summary of its
scene loaded and run on its own (the scene rebuilt from the base tables with
:func:`~corliss.keys.edits.with_keys`, the whole summary), and the same study in a
fresh process, where nothing was kept from earlier runs, gives the same rows, its
right-hand-side evaluations included (the count moves with any difference in a
run's inputs, however small).
"""

from __future__ import annotations

import copy
import json
import math
import subprocess
import sys
from pathlib import Path

import corliss
from corliss.engine.model import steady_scene
from corliss.engine.steady import run_steady
from corliss.studies.responses import flatten
from conftest import BASE

VARY = ["valve_gear.port_width=1.0:1.5in", "engine.clearance=0.04:0.12",
        "valve_gear.lap=0.8:1.2in", "run.speed=90:150rpm"]
#: Rates and events (the summary's light part), the peak pressure and the crank
#: effort (read from the time series) and the evaluations.
RESPONSES = ["indicated_power_W", "steam_rate_kg_per_h", "water_rate_kg_per_kWh",
             "mass_balance_error", "events.head.cutoff_frac", "events.crank.release_deg",
             "events.head.max_port_opening_m", "rhs_evaluations", "cycles_to_converge"]
HEAVY = ["peak_pressure_Pa", "max_torque_N_m"]
ROOT = Path(__file__).resolve().parents[1]


def _study(responses):
    return corliss.study(copy.deepcopy(BASE), VARY, lhs=4, seed=7, fidelity="fast",
                         responses=responses, jobs=1)


def _bits(values) -> list[str]:
    """Each value as its exact text (a float's repr is its bits; NaN equals NaN)."""
    return [repr(float(v)) for v in values]


def test_a_row_is_its_scene_run_on_its_own_to_the_bit():
    """Each row's responses, the light ones and the heavy ones alike, against the whole
    summary of its scene loaded from the edited tables and run alone, the runs taken in
    the reverse order (whatever ran before each is different).  The scene is rebuilt by
:meth:`StudyResult.scene_of` (the base tables with the row's keys set by
:func:`~corliss.keys.edits.with_keys`, loaded whole)."""
    light = _study(RESPONSES)
    heavy = _study(HEAVY)
    assert (light.points["status"] == "ok").all()
    for run_id in reversed(range(light.runs)):
        # the base tables with the row's keys set by with_keys, loaded, at the fidelity
        sc = light.scene_of(run_id)
        assert sc.run.fidelity.name == "fast"
        row = light.points.loc[run_id]
        # the scene holds the row's values (an inch is 0.0254 m, a turn 2 pi rad)
        assert math.isclose(sc.gear.lap_m[0], row["valve_gear.lap_in"] * 0.0254, rel_tol=1e-12)
        assert math.isclose(sc.gear.port_width_m, row["valve_gear.port_width_in"] * 0.0254,
                            rel_tol=1e-12)
        assert math.isclose(sc.run.speed_rad_s, row["run.speed_rpm"] * math.pi / 30.0,
                            rel_tol=1e-12)
        assert sc.engine.clearance[0] == row["engine.clearance_frac"]
        flat = flatten(run_steady(steady_scene(sc)).summary)
        assert _bits(light.points.loc[run_id, RESPONSES]) == _bits(flat[k] for k in RESPONSES)
        assert _bits(heavy.points.loc[run_id, HEAVY]) == _bits(flat[k] for k in HEAVY)


def test_a_study_gives_the_same_rows_after_other_runs_as_in_a_fresh_process():
    """The study run here after other scenes and studies (another engine, other values
    of the same keys) against the same study in a new process that runs nothing else."""
    corliss.study("buckeye-engine", ["run.speed=150:250rpm"], lhs=2, seed=1, fidelity="fast",
                  jobs=1)
    other = copy.deepcopy(BASE)     # another base: its keys are read first here
    other["valve_gear"].update(lap="1.1 in", port_width="1.3 in")
    other["engine"]["clearance"] = 0.1
    other["run"]["speed"] = "100 rpm"
    corliss.study(other, VARY, lhs=3, seed=11, fidelity="fast", jobs=1)
    here = _study(RESPONSES)
    code = ("import json, sys; sys.path.insert(0, 'tests'); import test_study_rows as t; "
            "r = t._study(t.RESPONSES); "
            "print(json.dumps([t._bits(r.points.loc[i, t.RESPONSES]) "
            "for i in range(r.runs)]))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True,
                         text=True, check=True)
    alone = json.loads(out.stdout.strip().splitlines()[-1])
    assert [_bits(here.points.loc[i, RESPONSES]) for i in range(here.runs)] == alone
    assert all(math.isfinite(float(v)) for row in alone for v in row)


#: Edits of one or more sections, each loaded with the base scene's specs for the
#: sections it does not edit: the study's keys, the barometer (every gauge pressure of
#: the other sections moves with it), the bore (the swept volume the unedited supply's
#: chest is checked against), pressures, an output key and a value of another kind.
LIKE_EDITS = [
    {"valve_gear.lap": "1.1 in", "valve_gear.port_width": "1.3 in"},
    {"engine.clearance": 0.1, "run.speed": "100 rpm"},
    {"supply.barometer": "13.2 psia"},
    {"engine.bore": "11.5 in"},
    {"supply.pressure": "80 psig", "exhaust.pressure": "2 psig"},
    {"output.units": "SI"},
    {"run.fidelity": "fast", "valve_gear.eccentricity": "3.2 in"},
]
#: Edits the loader refuses, each for a rule of its own section or one across sections:
#: a chest too small for the larger bore's swept volume (the supply's rule, on an
#: unedited supply), lap and lead beyond the eccentricity, a clearance out of range,
#: an exhaust above the supply (across sections), a key the gear does not take.
LIKE_REFUSED = [
    {"engine.bore": "13 in"},
    {"valve_gear.lap": "2.9 in"},
    {"engine.clearance": 0.7},
    {"exhaust.pressure": "120 psig"},
    {"valve_gear.lapp": "1 in"},
]


def test_a_scene_loaded_like_its_base_is_the_scene_loaded_whole():
    """:func:`~corliss.scene.loader.scene_from_dict` with ``like`` (the base scene,
    whose specs it takes for the sections the edited tables share with it) against the
    same tables loaded whole, field by field (floats compared exactly), and the same
    error, word for word, for an edit the loader refuses.  The base has a steam chest of
    150 in3, above the least the loader takes for its 12 in bore (5 % of the swept
    volume: 0.05 x pi/4 x 12^2 x 24 = 135.7 in3) and below the least for a 13 in bore
    (159.3 in3): a bore's edit must read the unedited supply again."""
    from corliss.errors import InputError
    from corliss.keys.edits import edited, with_keys
    from corliss.scene.loader import scene_from_dict
    base = copy.deepcopy(BASE)
    base["supply"]["chest_volume"] = "150 in3"
    like = scene_from_dict(base, name="base")
    for changes in LIKE_EDITS:
        fast = scene_from_dict(edited(base, changes), name="base", like=like)
        whole = scene_from_dict(with_keys(base, changes), name="base")
        assert fast == whole, changes
        assert repr(fast) == repr(whole), changes      # every float to its last bit
    assert like.supply.chest_volume_m3 == scene_from_dict(base, name="base").supply.chest_volume_m3
    for changes in LIKE_REFUSED:
        got = []
        for load in (lambda: scene_from_dict(edited(base, changes), name="base", like=like),
                     lambda: scene_from_dict(with_keys(base, changes), name="base")):
            try:
                load()
            except InputError as exc:
                got.append(f"{type(exc).__name__}: {exc}")
        assert len(got) == 2 and got[0] == got[1], (changes, got)
