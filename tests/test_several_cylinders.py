"""Several identical cylinders on one shaft (Marks Arts. 54-59)."""

import pytest

import corliss
from corliss.errors import InputError

from conftest import make_scene

ARRANGEMENTS = {1: None, 2: ["0 deg", "90 deg"], 3: ["0 deg", "120 deg", "240 deg"]}
# Marks Art. 60, Table IV part A, n = 5 (this engine's rod is 5 cranks): c for constant
# pressure with one crank, two at 90 deg, three at 120 deg
TABLE_IV_N5 = {1: 0.2577, 2: 0.1422, 3: 0.0594}


def engine(n):
    eng = {"cylinders": n}
    if ARRANGEMENTS[n]:
        eng["crank_angles"] = ARRANGEMENTS[n]
    return make_scene(engine=eng)


@pytest.fixture(scope="module")
def runs():
    return {n: corliss.simulate(engine(n)).summary for n in ARRANGEMENTS}


def test_cylinders_from_a_stiff_chest_add_up(runs):
    """With the chest at boiler pressure the cylinders do not interact: n of them give n
    times the power and the steam of one (to 1e-4, the cycle-to-cycle tolerance)."""
    for n in (2, 3):
        assert runs[n]["indicated_power_W"] == pytest.approx(n * runs[1]["indicated_power_W"],
                                                             rel=1e-4)
        assert runs[n]["steam_rate_kg_per_h"] == pytest.approx(
            n * runs[1]["steam_rate_kg_per_h"], rel=1e-4)
        assert runs[n]["mep_mean_Pa"] == pytest.approx(runs[1]["mep_mean_Pa"], rel=1e-4)


def test_more_cranks_even_out_the_crank_effort(runs):
    """Marks Arts. 57-60: the energy a flywheel must store, as a fraction c of one
    cylinder's work per stroke, falls from one crank to two at right angles to three at
    120 deg.  This engine admits to 0.88 of its stroke, nearly Marks's "without
    expansion" case, so its c lies near Table IV's constant-pressure column for n = 5:
    within 15 % (the card's expansion tail, compression and wire-drawing make it differ
    from a constant pressure)."""
    c = {n: runs[n]["fluctuation_coefficient_c"] for n in ARRANGEMENTS}
    assert c[1] > c[2] > c[3]
    for n, want in TABLE_IV_N5.items():
        assert c[n] == pytest.approx(want, rel=0.15)


def test_crank_angles_must_match_the_cylinders():
    with pytest.raises(InputError, match="engine.crank_angles"):
        make_scene(engine={"cylinders": 2, "crank_angles": ["0 deg"]})
    with pytest.raises(InputError, match="engine.cylinders"):
        make_scene(engine={"cylinders": 2}, run={"model": "ideal"})


def test_every_cylinder_leaks():
    """With ``leakage``, each of two identical cylinders fed from a stiff chest leaks as
    much as a single one does, so the valve leakage doubles (to 1e-4, the cycle-to-cycle
    tolerance) and the energy balance closes."""
    leaks = {"valve_leakage_area": "0.02 in2", "piston_leakage_area": "0.05 in2"}
    effects = {"effects": ["port_flow", "rod_angularity", "leakage"]}
    one = corliss.simulate(make_scene(engine=leaks, run=effects)).summary
    two = corliss.simulate(make_scene(engine={**leaks, "cylinders": 2,
                                              "crank_angles": ["0 deg", "90 deg"]},
                                      run=effects)).summary
    assert two["valve_leakage_kg_per_h"] == pytest.approx(2 * one["valve_leakage_kg_per_h"],
                                                          rel=1e-4)
    assert two["energy_balance_error"] < 1e-5
