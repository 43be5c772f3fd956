"""The wall's condensing coefficient and the leak law against the period's direct
measurements: Callendar and Nicolson (Min. Proc. ICE 131, 1897-98), read in Freytag's
report, Dinglers Polytechnisches Journal 312 (1899) pp. 161-165.  The measurements are
in ``tests/data/callendar_nicolson_1897.csv`` (each with its DPJ page) and
:data:`corliss.thermo.leak_law.CALLENDAR_NICOLSON_TESTS`.
"""

from __future__ import annotations

import copy
import csv
import functools
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import corliss
from corliss.engine import wall
from corliss.thermo import leak_law, wall_cycle
from corliss.scene import bundled_scenes, scene_from_dict
from corliss.thermo.steam import HEOSSteam

DATA = Path(__file__).parent / "data" / "callendar_nicolson_1897.csv"


def _measured(quantity, speed_rpm, where=None):
    with DATA.open() as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    for r in rows:
        if r["quantity"] == quantity and (r["speed_rpm"] or None) == (
                None if speed_rpm is None else f"{speed_rpm:g}") and (
                where is None or r["where"] == where):
            return float(r["value"])
    raise KeyError((quantity, speed_rpm, where))


@functools.lru_cache(maxsize=None)
def _their_card(n=360):
    """The saturation temperature over a revolution of a card like theirs (DPJ 312 p.
    162: 0.2 cut-off, steam 164.5 to 100 degC, non-condensing): admission at the
    saturation pressure of 164.5 degC to 0.2 of the stroke, hyperbolic expansion to
    release at 0.95, the exhaust at 100 degC's, compression from 0.1 of the return
    stroke, clearance 8 % (a slide-valve engine's; theirs is not given), the infinite
    rod's piston."""
    heos = HEOSSteam()
    p1 = brentq(lambda p: heos.t_sat(p) - 437.65, 4e5, 1.2e6)
    pb = brentq(lambda p: heos.t_sat(p) - 373.15, 5e4, 2e5)
    c, cut, rel, comp = 0.08, 0.2, 0.95, 0.9
    th = np.arange(n) * 2.0 * np.pi / n
    x = 0.5 * (1.0 - np.cos(th))
    out = th < np.pi
    p = np.where(out, np.where(x <= cut, p1, np.where(x <= rel, p1 * (cut + c) / (x + c), pb)),
                 np.where(x >= 1.0 - comp, pb, pb * (1.0 - comp + c) / (x + c)))
    p = np.clip(p, pb, p1)
    return tuple(heos.t_sat(v) for v in p)


@functools.lru_cache(maxsize=None)
def _cycle(speed_rpm, h):
    """Their cover's mean at 1 mm (142 degC at 46 rpm, p. 162) held where the wave has
    died; the surface and 1 mm under it reported."""
    return wall_cycle.periodic_wall_cycle(np.array(_their_card()), speed_rpm, h, (0.0, 1e-3),
                                          T_deep_K=_measured("wall_mean", 46) + 273.15)


def test_callendar_and_nicolsons_coefficient_is_four_kcal_per_second_m2_and_degc():
    """DPJ 312 p. 164: 4 kcal per second, m2 and degC on clean dry surfaces; their
    largest condensation, 23.74 kg of steam per m2, hour and degC (p. 165), times the
    latent heat at 150 degC (2.114 MJ/kg, IAPWS-95) is 13.9 kW/(m2 K), 17 % under it
    (the two are different readings of one law; 20 % covers them).  The engine's
    default condensing coefficient is theirs."""
    h = wall_cycle.CALLENDAR_NICOLSON_W_M2K
    assert h == pytest.approx(16747.2, rel=1e-9)
    heos = HEOSSteam()
    sat = heos.pt(heos_p := brentq(lambda p: heos.t_sat(p) - 423.15, 3e5, 6e5), 423.2)
    wet = heos.px(heos_p, 0.0)
    L = sat.h - wet.h
    assert wall_cycle.CALLENDAR_NICOLSON_MAX_KG_M2SK * L == pytest.approx(h, rel=0.20)
    assert wall.CONDENSING_W_M2K == h


def test_the_surface_peaks_near_their_149_degc_and_takes_their_heat_at_44_rpm():
    """At 44 rpm the surface rose to 149 degC while the steam late in admission was at
    164 (p. 163), and the most heat the wall took in a cycle was 16.2 kcal/m2, 67.8
    kJ/m2 (p. 163).  With their coefficient the wall of this module peaks within 3 K
    of 149 degC (their thermo-junctions read 1/20 degC, the surface is their
    computation, the card and the held mean are this test's: 3 K) and takes the heat
    to 25 % (the largest they saw against one card of theirs)."""
    r = _cycle(44.0, wall_cycle.CALLENDAR_NICOLSON_W_M2K)
    assert r["T_K"][0].max() - 273.15 == pytest.approx(_measured("surface_peak", 44), abs=3.0)
    assert r["heat_in_J_m2"] / 1e3 == pytest.approx(_measured("heat_per_cycle", None), rel=0.25)


@pytest.mark.parametrize("speed_rpm", [44.0, 77.0])
def test_the_surface_swings_more_than_theirs_but_under_three_times(speed_rpm):
    """Their computed swing of the surface: 11.5 K at 44 rpm, 6 K at 77 (p. 162).  With
    their coefficient the surface swings more than theirs (19.9 K and 16.4 K, 1.7 and
    2.7 times) and under three times it: the film law here boils the water off at the
    condensing coefficient until it is gone, and the surface follows the falling
    saturation temperature further than theirs did (they saw the water leave
    "explosively", not all its heat taken from the wall, p. 165).  The old default,
    3e5 W/(m2 K), swings it more than three times theirs (40.6 K and 39.4 K), which
    is why it was left."""
    measured = _measured("surface_swing", speed_rpm)
    swing = _cycle(speed_rpm, wall_cycle.CALLENDAR_NICOLSON_W_M2K)["swing_K"][0]
    assert measured < swing < 3.0 * measured
    assert _cycle(speed_rpm, 3.0e5)["swing_K"][0] > 3.0 * measured


def test_the_swing_falls_with_speed_as_theirs():
    """11.5 K at 44 rpm, 6 K at 77 (p. 162): the swing at the surface and at 1 mm
    falls from 44 to 77 to 102 rpm (the range of their runs, p. 161)."""
    h = wall_cycle.CALLENDAR_NICOLSON_W_M2K
    s = [_cycle(n, h)["swing_K"] for n in (44.0, 77.0, 102.0)]
    assert s[0][0] > s[1][0] > s[2][0]
    assert s[0][1] > s[1][1] > s[2][1]


def test_the_rate_of_leak_is_what_their_tests_give():
    """DPJ 312 p. 163: the rate of leak of the flat valve, 1.36 kg per hour per lbf/in2
    (3 lb/h per psi): the first blocked-port test, 51 kg in 25 min at 6.4 kg/cm2
    gauge, gives it to 2 % (the report's rounding); the second, 144 kg in 66.5 min at
    5.6, a fifth more (the valve's oil film had worn, the report says): within 25 %."""
    rates = [leak_law.rate_of_leak_kg_s_Pa(t.mass_kg, t.duration_s, t.dp_Pa)
             for t in leak_law.CALLENDAR_NICOLSON_TESTS[:2]]
    R = leak_law.CALLENDAR_NICOLSON_RATE_KG_S_PA
    assert rates[0] == pytest.approx(R, rel=0.02)
    assert rates[1] == pytest.approx(R, rel=0.25)
    assert 3.0 * 0.45359237 == pytest.approx(R * leak_law.HOUR_S * leak_law.PSI_PA, rel=2e-3)


def test_the_leak_follows_the_difference_the_opening_and_the_faces():
    """Callendar and Nicolson (p. 164): proportional to the pressure difference and to
    the perimeter of the port's opening, falling with the width of the faces (Capper
    1905, in Lineham App. VI: inversely as the lap); reversing the difference reverses
    the flow.  100 psi across their valve: 136 kg/h."""
    R = leak_law.CALLENDAR_NICOLSON_RATE_KG_S_PA
    p = leak_law.PSI_PA
    m = leak_law.leak_flow_kg_s(114.7 * p, 14.7 * p, R)
    assert m * leak_law.HOUR_S == pytest.approx(136.0, rel=1e-9)
    assert leak_law.leak_flow_kg_s(14.7 * p, 114.7 * p, R) == pytest.approx(-m)
    assert leak_law.leak_flow_kg_s(64.7 * p, 14.7 * p, R) == pytest.approx(0.5 * m)
    assert leak_law.leak_flow_kg_s(114.7 * p, 14.7 * p, R, 2.0, 1.0, 1.0, 1.0) == pytest.approx(
        2.0 * m)
    assert leak_law.leak_flow_kg_s(114.7 * p, 14.7 * p, R, 1.0, 1.0, 2.0, 1.0) == pytest.approx(
        0.5 * m)
    with pytest.raises(ValueError, match="rate_kg_s_Pa"):
        leak_law.leak_flow_kg_s(1.0, 0.0, -R)


@pytest.mark.parametrize("speed_rpm", [44.0, 77.0])
def test_the_engines_surface_swings_as_their_wall_within_three_times(speed_rpm):
    """The engine's own skin wall on the bundled scene after their engine (single-acting
    10.5 x 12 in, 0.2 cut-off, 100.5 psia, non-condensing): the head end's surface
    swings more than their computed 11.5 K (44 rpm) and 6 K (77 rpm) and under three
    times it (15.9 and 15.5 K: the lumped surface node's swing hardly falls with speed,
    where theirs halved); with the old default, 3e5 W/(m2 K), more than three times
    (41 and 44 K)."""
    data = tomllib.loads(bundled_scenes()["callendar-nicolson-single-acting"].read_text())
    data["run"].update({"speed": f"{speed_rpm:g} rpm", "fidelity": "fast"})
    measured = _measured("surface_swing", speed_rpm)
    swing = corliss.simulate(scene_from_dict(data, name="cn")).summary[
        "wall_surface_swing_head_K"]
    assert measured < swing < 3.0 * measured
    old = copy.deepcopy(data)
    old["engine"]["condensing_coefficient"] = "300 kW/m2 K"
    assert corliss.simulate(scene_from_dict(old, name="cn-old")).summary[
        "wall_surface_swing_head_K"] > 3.0 * measured
