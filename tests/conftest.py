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
#: subset.  Chosen by measurement: in a whole run of the suite on two cores shared at a
#: load of 16 to 18 (47 min; ``--durations=100``), the files whose slowest tests took
#: 50 s of worker time or more; together 56 of the run's 94 worker-minutes.
SLOW_FILES = frozenset({
    "test_docs.py", "test_startup.py", "test_scene_fuzz.py", "test_wall_ideal_ports.py",
    "test_notebooks.py", "test_cards.py", "test_every_scene_same_outputs.py",
    "test_outputs.py", "test_property_tiers.py", "test_governor_scenes.py",
    "test_study_stops.py", "test_governed_start.py", "test_workbench.py",
    "test_wall_skin.py", "test_random_engines.py", "test_fit.py", "test_kernel_data.py",
    "test_wall_heat.py", "test_packaging.py",
})


def pytest_collection_modifyitems(config, items):
    """Mark every test of :data:`SLOW_FILES` ``slow``."""
    for item in items:
        if item.path.name in SLOW_FILES:
            item.add_marker(pytest.mark.slow)
