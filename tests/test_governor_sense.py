"""A governor acts in the stabilising sense or is refused before any work.

Marks Art. 70: a governor governs because, as the speed rises and its balls or weights
fly out, it shuts off steam (closes the throttle, or shortens the cut-off).  One that
gives more steam as it lifts accelerates a speeding engine: a load change runs it away.
And a spring-loaded governor balances at the speed its spring sets, ``omega^2 = R / G``
(Marks Art. 97): a spring that puts that speed far from run.speed starts the engine
far from the speed it was written for.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from corliss.keys import units
from corliss.governors.operating_point import working_travel
from corliss.errors import InputError
from corliss.governors import GOVERNORS
from corliss.scene.loader import scene_from_dict

SCENES = Path(__file__).resolve().parent.parent / "scenes"


def _data(name: str) -> dict:
    return tomllib.loads((SCENES / f"{name}.toml").read_text(encoding="utf-8"))


def test_wrong_way_corliss_governor_refused_naming_both_keys():
    """The Corliss trip cams at setting 0 never admit and at 1 cut off at ~0.4 of the
    stroke: with setting_at_rest = 0 and setting_at_top = 1 the governor lengthens the
    cut-off as the speed rises."""
    d = _data("corliss-governor")
    d["governor"]["setting_at_rest"] = 0.0
    d["governor"]["setting_at_top"] = 1.0
    with pytest.raises(InputError) as e:
        scene_from_dict(d, name="wrong-way")
    msg = str(e.value)
    assert "governor.setting_at_rest" in msg and "governor.setting_at_top" in msg
    assert "more steam as the engine speeds up" in msg


def test_wrong_way_throttle_refused_naming_both_keys():
    d = _data("watt-throttling-governor")
    d["governor"]["opening_at_rest"] = 0.2
    d["governor"]["opening_at_top"] = 0.9
    with pytest.raises(InputError, match=r"governor.opening_at_rest = 0.2 .*"
                                         r"governor.opening_at_top = 0.9"):
        scene_from_dict(d, name="wrong-way")


def test_corliss_defaults_act_the_right_way():
    """Neither key written: the defaults (0 at rest, 1 at top) would act the wrong way on
    the Corliss gear, so they are swapped; the cut-off then shortens as z rises."""
    d = _data("corliss-governor")
    del d["governor"]["setting_at_rest"], d["governor"]["setting_at_top"]
    scene = scene_from_dict(d, name="defaults")
    a = scene.governor.actuator
    assert (a.at_rest, a.at_top) == (1.0, 0.0)
    # the shaft governors' gear runs the other way: its defaults are kept
    d = _data("armington-sims-governor")
    del d["governor"]["setting_at_rest"], d["governor"]["setting_at_top"]
    a = scene_from_dict(d, name="defaults").governor.actuator
    assert (a.at_rest, a.at_top) == (0.0, 1.0)


def _mid_speed_rpm(scene) -> float:
    gov = GOVERNORS.lookup(scene.governor_type).build(scene.governor)
    lo, hi = working_travel(gov.mechanism(11))
    return float(gov.equilibrium_speed_rad_s(np.array([0.5 * (lo + hi)]))[0]) \
        / units.RPM_RAD_S


def test_stiff_shaft_governor_spring_refused_with_the_spring_that_serves():
    """A 200 lbf/in spring on the Armington & Sims governor (17 lbf/in in the bundled
    scene) balances mid-travel at about 345 rpm for an engine written for 300: refused,
    with the stiffness that would serve; that stiffness, written into the scene, loads
    and balances mid-travel at run.speed (omega^2 is linear in the stiffness, so the
    two-point solve is exact up to the tabulation: 0.5 %)."""
    d = _data("armington-sims-governor")
    d["governor"]["spring_stiffness"] = "200 lbf/in"
    with pytest.raises(InputError) as e:
        scene_from_dict(d, name="stiff")
    msg = str(e.value)
    assert "governor.spring_stiffness" in msg
    k = re.search(r'spring_stiffness = "([0-9.]+) lbf/in"', msg).group(1)
    p = re.search(r'spring_preload = "([0-9.]+) lbf"', msg).group(1)
    for key, value in (("spring_stiffness", f"{k} lbf/in"), ("spring_preload", f"{p} lbf")):
        fixed = _data("armington-sims-governor")
        fixed["governor"]["spring_stiffness"] = "200 lbf/in"
        fixed["governor"][key] = value
        scene = scene_from_dict(fixed, name="fixed")
        assert _mid_speed_rpm(scene) == pytest.approx(300.0, rel=5e-3)
