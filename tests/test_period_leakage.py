"""The ``leakage`` effect by the period's law (``[engine] leakage_model = "period"``):
a flow equal to a rate of leak times the pressure difference, independent of speed
(Callendar and Nicolson, Min. Proc. ICE 131, 1897-98, in DPJ 312, 1899, pp. 163-164;
:mod:`corliss.thermo.leak_law`)."""

from __future__ import annotations

import pytest

import corliss
from conftest import make_scene
from corliss.errors import InputError
from corliss.thermo import leak_law

RATE = "3 lb/h psi"          # Callendar and Nicolson's flat slide valve (DPJ 312 p. 163)
#: the same in SI: 3 lb is 1.3608 kg, the report's 1.36 rounded [kg/(s Pa)]
R_SI = 3.0 * 0.45359237 / 3600.0 / leak_law.PSI_PA


def _leaky(speed="120 rpm", **engine):
    return corliss.simulate(make_scene(
        engine={"leakage_model": "period", "valve_leak_rate": RATE, **engine},
        run={"effects": ["port_flow", "rod_angularity", "leakage"], "speed": speed,
             "fidelity": "fast"}))


def test_the_valve_leak_is_the_rate_times_the_difference_at_any_speed():
    """Chest (the supply, 114.7 psia) straight to the exhaust (atmosphere): 3 lb/h per
    psi of a 100 psi difference is 300 lb/h (136.08 kg/h) whatever the speed (the period's
    "independent of speed"): at 60 and 180 rpm the hourly leak is that to 1e-6 (the
    integration's quadrature of a constant flow), though a cycle takes three times as
    long at the one as at the other; the mass and energy balances close with it (the
    fast preset's 1e-4)."""
    for speed in ("60 rpm", "180 rpm"):
        r = _leaky(speed)
        s = r.summary
        dp = r.chest.p - r.exhaust.p       # the reservoirs' pressures as the tier gives them
        want = R_SI * dp * 3600.0
        assert s["valve_leak_exhaust_kg_per_h"] == pytest.approx(want, rel=1e-6)
        assert s["valve_leakage_fraction_of_steam"] == pytest.approx(
            want / s["steam_rate_kg_per_h"], rel=1e-6)
        assert s["mass_balance_error"] < 1e-4
        assert s["energy_balance_error"] < 1e-4


def test_the_piston_leak_runs_from_the_end_at_higher_pressure():
    """Past the piston, head to crank, R (p_head - p_crank) at every instant: over a
    cycle of the (symmetric but for the rod) default engine the net is small against
    the gross, and its sign follows the pressures' integral (the quadrature of the law
    over the last cycle's samples, to the trapezoid's error, 2 %)."""
    import numpy as np
    r = _leaky(piston_leak_rate="1 lb/h psi")
    ts = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    t = ts["time_s"].to_numpy()
    dp = ts["p_head_Pa"].to_numpy() - ts["p_crank_Pa"].to_numpy()
    R = R_SI / 3.0
    want = float(np.trapezoid(R * dp, t))
    got = float(r.last_cycle["m_piston_leak_kg"])
    gross = float(np.trapezoid(R * np.abs(dp), t))
    assert abs(got - want) < 0.02 * gross


def test_the_period_law_needs_a_rate():
    with pytest.raises(InputError, match="engine.valve_leak_rate"):
        make_scene(engine={"leakage_model": "period"},
                   run={"effects": ["port_flow", "rod_angularity", "leakage"]})
