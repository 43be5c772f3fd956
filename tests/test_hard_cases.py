"""Hard cases, one named test each: the edges of valve setting, steam state and speed
where a filling-and-emptying model is stiff, nearly singular or meets the edge of its
property range.

Every case asserts the same things:

- the run completes periodic within a bounded number of right-hand-side evaluations
  per cycle (``MAX_RHS_PER_CYCLE``: 30 times the 3,400 the default card needs at the
  ``standard`` preset: the explicit integrator's step is held by the ports' filling
  time constant, which in crank angle grows as the speed falls, twelvefold at 10 rpm;
  a run that needs more is stepping through a near-singularity);
- nothing is NaN in the time series, the cycles or the summary;
- mass and energy over the converged cycle close: steam in less steam out, and
  enthalpy in less enthalpy out plus heat less work, to ``BALANCE`` of the largest
  flow (ten times the standard preset's periodicity tolerance, for a cycle that
  integrates a stiff blow-down) plus the change of the engine's contents that the
  periodicity tolerance allows (what matters when a valve that barely opens passes
  micrograms a cycle);
- every cylinder pressure stays within what adiabatic compression or expansion of
  steam from the reservoirs can reach: above the lower reservoir pressure times
  (Vc/(Vc+Vs))^1.4 and below the higher one times ((Vc+Vs)/Vc)^1.4, with 1.4 above any
  isentropic exponent of steam (1.3 superheated, 1.135 dry saturated, Zeuner); every
  temperature above the triple point (273.16 K) and below the hotter reservoir's
  temperature times ((Vc+Vs)/Vc)^0.4;
- the indicated work and the steam per cycle agree with the same case run at a
  hundred times tighter tolerance (dopri5 at rtol 1e-8) to ``AGREE`` of the card's scale
  (the work of the swept volume at supply pressure; the steam of the swept volume at
  chest density): the standard preset claims 0.01 % on the accuracy study's scenes,
  and a hard case is allowed ten times that.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import tomllib

import pytest

import corliss
from corliss.scene.loader import bundled_scenes, scene_from_dict

MAX_RHS_PER_CYCLE = 100_000
BALANCE = 1e-3
#: Agreement of a run with the same run at a tighter tolerance, in work and steam per
#: cycle against their scales; the ``fast`` preset's too: its predictive step control
#: (kernel._ros_steps) gives a periodic cycle, where the error-only control scattered
#: the default card's steam per cycle by about 0.15 % of the scale from one cycle to the
#: next and needed 4e-3 here (which cycle its periodicity test stopped at decided it).
AGREE = 1e-3
TRIPLE_POINT_K = 273.16


def _scene(name: str = "default", **changes):
    """A bundled scene with ``changes = {section: {key: value}}`` applied."""
    data = tomllib.loads(bundled_scenes()[name].read_text())
    data = copy.deepcopy(data)
    for section, values in changes.items():
        data.setdefault(section, {}).update(values)
    return scene_from_dict(data, name=f"hard-{name}")


def _tight(scene):
    fid = scene.run.fidelity
    tight = dataclasses.replace(fid, name="tight", method="dopri5", rtol=1e-8,
                                convergence_tolerance=min(fid.convergence_tolerance, 1e-6),
                                max_cycles=max(fid.max_cycles, 60))
    return scene.replace_run(fidelity=tight)


def _check(scene, *, compare: bool = True):
    """Run ``scene`` and assert the suite's common properties; returns the result."""
    r = corliss.simulate(scene)
    s = r.summary
    assert s["cycles_to_converge"] is not None, "not periodic within max_cycles"
    assert s["rhs_evaluations"] / s["cycles_simulated"] < MAX_RHS_PER_CYCLE
    for name in ("timeseries", "cycles"):
        frame = getattr(r, name)
        assert not frame.isna().to_numpy().any(), f"NaN in the {name}"
    for k, v in s.items():
        if isinstance(v, float):
            assert math.isfinite(v), k
    # mass and energy over the last cycle: what came in less what went out is what the
    # engine's contents changed by, and a periodic run allows them to change by the
    # convergence tolerance times what they hold (the steam in every volume at its
    # most, its energy at the chest's enthalpy)
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    tol = s["convergence_tolerance"]
    held = sum(last[c].max() for c in last.columns if c.startswith("m_") and c.endswith("_kg"))
    row = r.last_cycle
    m_in, m_out = float(row["m_supply_kg"]), float(row["m_exhaust_kg"])
    assert abs(m_in + m_out) < BALANCE * max(abs(m_in), abs(m_out)) + tol * held
    if "H_exhaust_J" in row:
        Q = sum(float(row[c]) for c in row.index if c.startswith("Q_") and "to_wall" not in c)
        flows = [float(row["H_supply_J"]), float(row["H_exhaust_J"]), float(row["work_J"]), Q]
        assert (abs(flows[0] + flows[1] + Q - flows[2])
                < BALANCE * max(map(abs, flows)) + tol * held * r.chest.h)
    p_lo, p_hi = sorted((r.chest.p, r.exhaust.p))
    t_hi = max(r.chest.T, r.exhaust.T)
    for prefix, geo, _ in r.cylinder_list:
        for e, end in enumerate(("head", "crank")):
            ratio = (geo.clearance_m3[e] + geo.swept_m3[e]) / geo.clearance_m3[e]
            p = last[f"p_{prefix}{end}_Pa"].to_numpy()
            T = last[f"T_{prefix}{end}_K"].to_numpy()
            assert p.min() > p_lo * ratio ** -1.4, (end, p.min())
            assert p.max() < p_hi * ratio ** 1.4, (end, p.max())
            assert T.min() > TRIPLE_POINT_K and T.max() < t_hi * ratio ** 0.4, (end, T.min(), T.max())
            assert last[f"m_{prefix}{end}_kg"].min() > 0.0
    if compare:
        ref = corliss.simulate(_tight(scene)).summary
        swept = sum(sum(g.swept_m3) for _, g, _ in r.cylinder_list)
        w_scale = swept * r.chest.p
        m_scale = swept * r.chest.rho
        assert abs(s["indicated_work_J_per_cycle"] - ref["indicated_work_J_per_cycle"]) < AGREE * w_scale
        assert abs(s["steam_per_cycle_kg"] - ref["steam_per_cycle_kg"]) < AGREE * m_scale
    return r


def test_valve_whose_opening_tends_to_zero():
    """Lap within 0.01 in of the eccentricity: the steam port opens 0.01 in at most."""
    r = _check(_scene(valve_gear={"lap": "2.99 in", "lead": "0 in"}))
    assert r.events["head"]["max_port_opening_m"] < 0.0003


def test_port_open_for_a_fraction_of_a_degree():
    """Lap = eccentricity x cos(0.25 deg): the steam edge passes the port for about
    half a degree of crank (the valve's displacement exceeds the lap only there)."""
    lap_in = 3.0 * math.cos(math.radians(0.25))
    r = _check(_scene(valve_gear={"lap": f"{lap_in:.6f} in", "lead": "0 in"}))
    ev = r.events["head"]
    assert ((ev["cutoff_deg"] - ev["admission_deg"]) % 360.0) < 1.0


def test_cut_off_near_one_percent():
    """The Corliss trip gear with its cam set just above its rest: the steam valves
    trip in the first percent or two of the stroke."""
    r = _check(_scene("corliss-trip-gear", valve_gear={"setting": 0.005}))
    assert 0.0 < r.events["head"]["cutoff_frac"] < 0.03


def test_cut_off_at_95_percent():
    """A plain valve of small lap (0.3 in on a 3 in eccentric) cuts off near 95 %."""
    r = _check(_scene(valve_gear={"lap": "0.35 in", "lead": "0.1 in"}))
    assert 0.93 < r.events["head"]["cutoff_frac"] < 0.99


def test_negative_lead():
    """The valve opens after dead centre (lead -0.1 in): admission late."""
    r = _check(_scene(valve_gear={"lead": "-0.1 in"}))
    assert 0.0 < r.events["head"]["admission_deg"] < 10.0


@pytest.mark.parametrize("lap", ["0 in", "-0.2 in"], ids=["zero", "negative"])
def test_zero_and_negative_steam_lap(lap):
    r = _check(_scene(valve_gear={"lap": lap, "lead": "0.1 in"}))
    assert r.events["head"]["cutoff_frac"] > 0.99


@pytest.mark.parametrize("exhaust_lap", ["0 in", "-0.2 in"], ids=["zero", "negative"])
def test_zero_and_negative_exhaust_lap(exhaust_lap):
    _check(_scene(valve_gear={"exhaust_lap": exhaust_lap}))


def test_compression_above_chest_pressure():
    """Early compression (1 in of exhaust lap) into 2 % clearance lifts the cushion
    above chest pressure: the steam flows back into the chest at admission."""
    r = _check(_scene(engine={"clearance": 0.02}, valve_gear={"exhaust_lap": "1 in"}))
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    assert last["p_head_Pa"].max() > r.chest.p


def test_one_percent_clearance_with_heavy_compression():
    _check(_scene(engine={"clearance": 0.01}, valve_gear={"exhaust_lap": "0.75 in"}))


def test_superheat_expanding_into_wet_steam():
    """Slightly superheated steam (15 degF) cut off early (1.8 in of lap) expands
    through the saturation line: wet at release."""
    r = _check(_scene(supply={"temperature": "353 degF"}, valve_gear={"lap": "1.8 in"}))
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    assert last["x_head_frac"].max() == pytest.approx(1.0)
    assert last["x_head_frac"].min() < 0.999


def test_exhaust_into_28_5_inches_of_vacuum():
    r = _check(_scene(exhaust={"pressure": "28.5 inHg vacuum"}))
    assert r.exhaust.p < 5000.0


def test_wet_supply():
    r = _check(_scene(supply={"dryness": 0.9}))
    assert r.chest.x == pytest.approx(0.9)


def test_throttle_nearly_shut():
    """A chest of 0.3 ft3 behind a 4 in pipe, the throttle open 2 %: the chest
    pressure falls far below the supply's."""
    r = _check(_scene(supply={"chest_volume": "0.3 ft3", "pipe_diameter": "4 in",
                              "throttle": 0.02},
                      run={"effects": ["port_flow", "rod_angularity", "steam_chest"]}))
    assert r.summary["chest_pressure_mean_Pa"] < 0.5 * r.chest.p


def test_corliss_trip_at_the_limit_of_its_range_with_a_slow_dash_pot():
    """The cam at the rest end of its range trips the valves at admission, and a
    dash-pot slower (0.4 s) than the gear's own closing lets them close late."""
    _check(_scene("corliss-trip-gear", valve_gear={"setting": 0.0,
                                                   "dashpot_closing_time": "0.4 s"}))


@pytest.mark.parametrize("speed", ["10 rpm", "600 rpm"])
def test_very_slow_and_very_fast(speed):
    _check(_scene(run={"speed": speed}))


@pytest.mark.parametrize("speed", ["120 rpm", "10 rpm"])
def test_the_standard_preset_keeps_its_accuracy_target(speed):
    """The ``standard`` preset promises indicated power and steam within 0.01 % of a
    converged card (README, "Accuracy and time").  On the default card, at its own
    120 rpm and at 10 rpm, where the ports' filling is twelve times stiffer in crank
    angle (its Rosenbrock method, RODAS4 at 2e-6 with the exact Jacobian, measured
    0.0007 % and 0.002 % at 120 rpm, and under 0.006 % at 10 rpm, where dopri5 at 1e-6
    was 0.03 % off in steam), against dopri5 at 1e-8 periodic to 1e-6."""
    scene = _scene(run={"speed": speed})
    got = corliss.simulate(scene).summary
    ref = corliss.simulate(_tight(scene)).summary
    for key in ("indicated_work_J_per_cycle", "steam_per_cycle_kg"):
        assert got[key] == pytest.approx(ref[key], rel=1e-4), key


@pytest.mark.parametrize("fidelity", ["fast", "standard", "reference"])
def test_every_fidelity_tier_on_the_default_card(fidelity):
    """Each preset on the default card, checked as the suite checks a hard case
    (the reference tier is its own tight comparison)."""
    _check(_scene(run={"fidelity": fidelity}), compare=fidelity != "reference")
