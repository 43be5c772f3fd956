"""Leakage, and effects that cost nothing when the scene does not name them."""

import dataclasses
import math

import numpy as np
import pytest

import corliss
from corliss.engine.options import EFFECTS
from corliss.errors import InputError

from conftest import make_scene

DATA = {"engine": {"valve_leakage_area": "0.02 in2", "piston_leakage_area": "0.05 in2",
                   "reciprocating_mass": "800 lb", "friction_torque": "300 lbf ft"},
        "supply": {"chest_volume": "2 ft3", "pipe_diameter": "4 in"}}


def test_effects_not_named_cost_nothing():
    """A scene that carries the data of every effect but names none runs exactly the
    model of a scene without that data: the same states, the same number of
    right-hand-side evaluations, the same summary keys.  Naming them changes the run."""
    plain = corliss.simulate(make_scene())
    quiet = corliss.simulate(make_scene(**DATA))
    assert quiet.rhs_evaluations == plain.rhs_evaluations
    assert np.array_equal(quiet.timeseries.to_numpy(), plain.timeseries.to_numpy())
    assert set(quiet.summary) == set(plain.summary)
    loud = corliss.simulate(make_scene(**DATA, run={"effects": list(EFFECTS)}))
    assert loud.rhs_evaluations != plain.rhs_evaluations
    for k in ("valve_leakage_kg_per_h", "brake_power_W", "chest_pressure_mean_Pa"):
        assert k in loud.summary and k not in plain.summary


@pytest.fixture(scope="module")
def leaky():
    sc = make_scene(engine={"valve_leakage_area": "0.02 in2", "piston_leakage_area": "0.05 in2"},
                    run={"effects": ["port_flow", "rod_angularity", "leakage"]})
    fid = dataclasses.replace(sc.run.fidelity, rtol=1e-8, convergence_tolerance=1e-7)
    return corliss.simulate(sc.replace_run(fidelity=fid))


def test_leakage_closes_the_mass_and_energy_balance(leaky):
    """With leaks, everything that enters from the supply (ports and leaks) leaves by
    the exhaust, and the enthalpy in less out is the indicated work (tolerance 1e-5,
    the integration's; the leak between the ends is internal and cancels)."""
    assert leaky.summary["mass_balance_error"] < 1e-5
    assert leaky.summary["energy_balance_error"] < 1e-5


def test_valve_leak_lies_between_its_orifice_bounds(leaky):
    """The leak into an end is an orifice from chest pressure: at most the choked flow
    Cd A G* all the cycle long, at least that flow over the part of the cycle when the
    end is below the critical pressure ratio (Saint-Venant and Wantzel; dry saturated
    steam, kappa = 1.135)."""
    s = leaky.summary
    k = 1.135
    ch = leaky.chest
    g_star = math.sqrt(k * ch.p * ch.rho * (2 / (k + 1)) ** ((k + 1) / (k - 1)))
    area = 0.02 * 0.0254 ** 2
    period = 2 * math.pi / leaky.scene.run.speed_rad_s
    leak = leaky.last_cycle["m_valve_leak_head_kg"]
    ts = leaky.timeseries[leaky.timeseries["cycle"] == leaky.timeseries["cycle"].max()]
    r_crit = (2 / (k + 1)) ** (k / (k - 1))
    choked = np.mean(ts["p_head_Pa"].to_numpy()[:-1] < r_crit * ch.p)
    assert 0.7 * area * g_star * choked * period < leak < 0.7 * area * g_star * period
    assert s["valve_leakage_kg_per_h"] == pytest.approx(
        (leak + leaky.last_cycle["m_valve_leak_crank_kg"]) * 120 * 60, rel=1e-12)


def test_leakage_costs_steam_and_work():
    plain = corliss.simulate(make_scene()).summary
    s = corliss.simulate(make_scene(engine={"valve_leakage_area": "0.02 in2"},
                                    run={"effects": ["port_flow", "rod_angularity",
                                                     "leakage"]})).summary
    assert s["steam_rate_kg_per_h"] > plain["steam_rate_kg_per_h"] * 1.005
    assert s["water_rate_kg_per_kWh"] > plain["water_rate_kg_per_kWh"]


def test_leakage_needs_an_area():
    with pytest.raises(InputError, match="engine.valve_leakage_area"):
        make_scene(run={"effects": ["port_flow", "leakage"]})
