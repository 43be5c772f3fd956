"""Shared fixtures: scenes built in code, so tests never read files outside the project."""

from __future__ import annotations

import copy

import pytest

import corliss

#: The scene of the format's contract (12 x 24 in slide-valve engine), as a dict.
BASE = {
    "title": "test engine",
    "engine": {"bore": "12 in", "stroke": "24 in", "connecting_rod": "60 in",
               "piston_rod_diameter": "2.5 in", "clearance": 0.08},
    "supply": {"pressure": "100 psig", "temperature": "saturated", "barometer": "14.696 psia"},
    "exhaust": {"pressure": "0 psig"},
    "valve_gear": {"type": "slide_valve", "eccentricity": "3 in", "lap": "1 in",
                   "exhaust_lap": "0 in", "lead": "0.25 in", "port_width": "1.25 in",
                   "port_length": "9.6 in", "discharge_coefficient": 0.7,
                   "eccentric_rod": "60 in", "connection": "direct", "steam": "outside"},
    "run": {"mode": "steady", "speed": "120 rpm", "effects": ["port_flow", "rod_angularity"],
            "fidelity": "standard"},
    "output": {"units": "US", "dir": "out"},
}


def make_scene(**sections):
    """The base scene with some keys changed: ``make_scene(valve_gear={"lap": "1.5 in"})``.

    A value of ``None`` deletes the key.
    """
    data = copy.deepcopy(BASE)
    for sec, changes in sections.items():
        if not isinstance(changes, dict):
            data[sec] = changes
            continue
        for k, v in changes.items():
            if v is None:
                data.setdefault(sec, {}).pop(k, None)
            else:
                data.setdefault(sec, {})[k] = v
    return corliss.scene_from_dict(data, name="test")


@pytest.fixture
def base_dict():
    return copy.deepcopy(BASE)


#: The test files marked ``slow``: ``pytest -m "not slow"`` runs the rest, the quick
#: subset.  Chosen by the time each file took in a whole run of the suite on two
#: cores (``--durations``): the files whose tests together took the most.
SLOW_FILES = frozenset({
    "test_every_scene_same_outputs.py", "test_notebooks.py", "test_docs.py",
    "test_workbench.py", "test_random_engines.py", "test_outputs.py",
    "test_hard_cases.py", "test_hard_cases_transient.py", "test_scene_fuzz.py",
    "test_fuzz_inputs.py", "test_compare.py", "test_study.py", "test_study_stops.py",
    "test_fit.py", "test_governor_scenes.py", "test_same_outputs.py",
})


def pytest_collection_modifyitems(config, items):
    """Mark every test of :data:`SLOW_FILES` ``slow``."""
    for item in items:
        if item.path.name in SLOW_FILES:
            item.add_marker(pytest.mark.slow)
