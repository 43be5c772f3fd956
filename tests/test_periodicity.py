"""A steady run is periodic in every state, not in its work alone.

Each cycle the runner measures how far the cycle is from periodic, state by state
(work; every volume's mass and energy; steam in against steam out; every wall
temperature), each against its own scale, and stops only when all are below the
fidelity's convergence tolerance; the summary reports them.
"""

from __future__ import annotations

import dataclasses
import tomllib

import pytest

import corliss
from corliss.scene.loader import bundled_scenes, scene_from_dict


def _conductance_scene():
    sc = corliss.load_scene(bundled_scenes()["default"])
    eng = dataclasses.replace(sc.engine, wall_heat_model="conductance")
    return dataclasses.replace(sc, engine=eng).replace_run(
        effects=sc.run.effects + ("wall_heat",))


def test_the_wall_temperature_is_periodic_when_the_run_stops():
    """The conductance wall relaxes slowly, over many cycles, towards its periodic
    temperature while the work settles in a few.  Stopped by the work alone, a run left
    the wall 0.9 K short and its heat 9 % off.  Stopped when every state is periodic,
    the wall must be within what is left of a contraction: the last cycle's change
    (below the tolerance, 1e-4 of the supply-less-exhaust temperature difference, here
    70 K) times 1/(1 - rho) for a contraction rate rho of at most 0.9 per cycle, i.e.
    within 10 x 1e-4 x 70 K = 0.07 K of the wall 40 cycles later, and the heat to the
    walls within 0.5 %."""
    scene = _conductance_scene().with_fidelity("standard")
    r = corliss.simulate(scene)
    s = r.summary
    tol = s["convergence_tolerance"]
    assert s["cycles_to_converge"] is not None
    assert set(s["periodicity_residuals"]) >= {"work", "mass", "energy", "mass_balance",
                                               "wall_temperature"}
    assert max(s["periodicity_residuals"].values()) <= tol
    dT = r.chest.T - r.exhaust.T
    later = corliss.simulate(scene.replace_run(cycles=s["cycles_to_converge"] + 40)).summary
    for end in ("head", "crank"):
        assert s[f"wall_temperature_{end}_K"] == pytest.approx(
            later[f"wall_temperature_{end}_K"], abs=10 * tol * dT)
        assert s[f"heat_to_walls_{end}_J_per_cycle"] == pytest.approx(
            later[f"heat_to_walls_{end}_J_per_cycle"], rel=5e-3)


def test_a_compound_stops_when_its_receiver_has_filled():
    """The compound's receiver fills over many cycles, slower than the work settles.
    When the run says it is periodic, thirty more cycles must change its steam rate,
    power and receiver pressure by less than twice the tolerance (what a geometric
    approach leaves once every state's change per cycle is below the tolerance and
    contracts by at least half a cycle); stopped by the work alone, the receiver's
    pressure was still 2.2e-4 from its periodic value."""
    scene = corliss.load_scene(bundled_scenes()["marks-compound-9-14x14"])
    s = corliss.simulate(scene).summary
    tol = s["convergence_tolerance"]
    assert s["cycles_to_converge"] is not None
    assert max(s["periodicity_residuals"].values()) <= tol
    later = corliss.simulate(scene.replace_run(cycles=s["cycles_to_converge"] + 30)).summary
    for key in ("steam_rate_kg_per_h", "indicated_power_W", "receiver_pressure_mean_Pa"):
        assert s[key] == pytest.approx(later[key], rel=2 * tol), key


def test_a_compound_with_every_effect_conserves_mass_and_energy():
    """Marks's 9 & 14 x 14 compound with a chest behind its pipe, leaks past valves and
    pistons, walls exchanging heat (conductance model), friction and reciprocating
    masses: over a converged cycle the steam in equals the steam out and the enthalpy
    in less the enthalpy out plus the heat equals the indicated work, to 1e-5.

    Run at rtol 1e-8 and periodic to 1e-7, so that what the balance measures is the
    model's conservation, not the drift of a cycle that is periodic only to the
    standard preset's 1e-4 (the receiver holds several cycles' steam, and its drift
    alone is 4e-5 of the enthalpy supplied at that preset)."""
    data = tomllib.loads(bundled_scenes()["marks-compound-9-14x14"].read_text())
    data["engine"].update({"reciprocating_mass": "300 lb", "friction_torque": "100 lbf ft",
                           "valve_leakage_area": "0.01 in2", "piston_leakage_area": "0.01 in2",
                           "wall_heat_model": "conductance"})
    data["supply"].update({"chest_volume": "0.2 ft3", "pipe_diameter": "3 in"})
    data["run"]["effects"] = ["port_flow", "rod_angularity", "steam_chest", "leakage",
                              "wall_heat", "friction", "inertia"]
    scene = scene_from_dict(data)
    fid = dataclasses.replace(scene.run.fidelity, rtol=1e-8, convergence_tolerance=1e-7,
                              max_cycles=200)
    s = corliss.simulate(scene.replace_run(fidelity=fid)).summary
    assert s["cycles_to_converge"] is not None
    assert s["mass_balance_error"] < 1e-5
    assert s["energy_balance_error"] < 1e-5
    assert "lp_power_W" in s and s["valve_leakage_kg_per_h"] > 0 and "brake_power_W" in s


def test_a_warm_start_settles_on_the_same_periodic_cycle_sooner():
    """A steady run started where a neighbouring run ended (another cut-off of the same
    walled engine) must reach the periodic cycle a cold start reaches: the periodic
    solution does not depend on where the cycles began.  Both stop, at the fast
    preset's own tolerance, when every state changes by under the tolerance over a
    cycle and, for the skin wall, when the wall's heat over the cycle balances to the
    tolerance times the heat it took, or the bracket on its balance's sign has closed
    to the tolerance times the supply's less the exhaust's temperature
    (corliss.engine.wall.DeepWallSearch).  So their heat to the walls may differ by up
    to twice the tolerance of the heat taken (the two runs on either side of the
    periodic cycle), their walls by twice the bracket's width, and their work by a
    few tolerances (a contraction's remainder, as above).

    When the wall's balance was held to the tolerance of the enthalpy supplied (850 kJ
    a cycle, some 30 times the wall's heat) and its secant was not bracketed, the warm
    start stopped after 2 cycles at 420.88 K and 27138 J a cycle and the cold after 10
    at 421.66 K and 26079 J: each within that criterion, the wall 0.8 K apart.  Now 6
    and 15 cycles, 421.661 and 421.656 K, 26070 and 26076 J.  The walls' temperature,
    the slowest state, starts near its periodic value, so fewer cycles are needed."""
    from corliss.engine.steady import run_steady
    sc = corliss.load_scene(bundled_scenes()["default"]).with_fidelity("fast")
    tol = sc.run.fidelity.convergence_tolerance
    assert tol == 1e-3
    sc = sc.replace_run(effects=sc.run.effects + ("wall_heat",))
    early = dataclasses.replace(sc, gear=dataclasses.replace(sc.gear, lap_m=(0.030, 0.030)))
    neighbour = run_steady(early)
    cold = run_steady(sc)
    warm = run_steady(sc, start=neighbour.final_state)
    assert warm.summary["indicated_power_W"] == pytest.approx(
        cold.summary["indicated_power_W"], rel=5 * tol)
    taken = cold.summary["heat_to_walls_head_J_per_cycle"]
    assert abs(warm.summary["heat_to_walls_head_J_per_cycle"] - taken) <= 2 * tol * taken
    assert warm.summary["wall_temperature_head_K"] == pytest.approx(
        cold.summary["wall_temperature_head_K"], abs=2 * tol * (cold.chest.T - cold.exhaust.T))
    assert warm.cycles_to_converge < cold.cycles_to_converge
