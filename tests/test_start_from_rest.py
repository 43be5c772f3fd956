"""A start from rest, off dead centre: the hard case the crank-angle loop cannot take
(every rate divided by a speed of zero), integrated in time until the engine is under
way (see corliss.engine.start_from_rest)."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

import corliss
from corliss.errors import InputError
from corliss.scene.loader import bundled_scenes, scene_from_dict


def _from_rest(angle: str, duration: str, **run):
    """The Porter-Allen engine standing, its crank at ``angle``, under its full 70 hp."""
    data = tomllib.loads(bundled_scenes()["porter-allen-governor"].read_text())
    data["run"].update(start="rest", start_angle=angle, duration=duration, **run)
    data["load"] = {"power": "70 hp"}
    return scene_from_dict(data, "from-rest")


def test_from_rest_off_dead_centre_the_engine_runs_up_to_its_governed_speed():
    """At 45 deg of crank the head end takes steam and the engine starts under its full
    load.  Its speed is never negative; the flywheel's energy when the crank-angle loop
    takes over equals the work of the steam less the friction's and the load's (1e-4:
    the time integration's rtol is 1e-6); and it runs up to the speed at which its
    governor balances the load, the same operating point a start at equilibrium finds
    (within 0.1 %, a tenth of the governor's droop), and settles there."""
    scene = _from_rest("45 deg", "60 s", until_settled=True)
    r = corliss.simulate(scene)
    s = r.summary
    assert s["start"]["status"] == "rest" and not s["stalled"]
    assert r.timeseries["speed_rpm"].min() >= 0.0
    first = r.cycles.iloc[0]
    ke = 0.5 * scene.flywheel.inertia_kg_m2 * (first["speed_end_rpm"] * math.pi / 30.0) ** 2
    work = first["work_J"] - first["friction_work_J"] - first["load_work_J"]
    assert work == pytest.approx(ke, rel=1e-4)
    balanced = corliss.simulate(scene.replace_run(start="equilibrium", duration_s=2.0,
                                                  until_settled=False)).summary["start"]
    assert s["settled"]
    assert s["final_speed_rpm"] == pytest.approx(balanced["speed_rpm"], rel=1e-3)


def test_on_dead_centre_a_single_cylinder_stays_at_rest():
    """On the head-end dead centre the piston's pressure has no lever (dV/dtheta = 0):
    the engine does not move, and the run says it stalled, its speed zero throughout,
    never negative and never oscillating."""
    r = corliss.simulate(_from_rest("0 deg", "5 s"))
    s = r.summary
    assert s["stalled"]
    speed = r.timeseries["speed_rpm"].to_numpy()
    assert np.all(speed == 0.0)


def test_a_start_angle_without_a_start_from_rest_is_refused():
    data = tomllib.loads(bundled_scenes()["porter-allen-governor"].read_text())
    data["run"]["start_angle"] = "45 deg"
    with pytest.raises(InputError, match="run.start_angle"):
        scene_from_dict(data, "x")
