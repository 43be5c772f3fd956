"""Property tiers against HEOS, and the compiled kernel against the Python model."""

import dataclasses
import math

import numpy as np
import pytest

import corliss
from corliss.errors import InputError
from corliss.thermo import HEOSSteam
from corliss.thermo.steam import PerfectSteam, TableSteam
from corliss.thermo.steam_table import lookup, lookup_many, lookup_near

from conftest import make_scene


@pytest.fixture(scope="module")
def heos():
    return HEOSSteam()


@pytest.fixture(scope="module")
def table():
    return TableSteam()


def _grid_states(heos):
    """Wet, saturated and superheated states, 0.08 to 22 bar, plus sweeps across the
    saturated-vapour line at fixed density (the seam between the table's two parts)."""
    out = []
    for p in np.geomspace(8e3, 2.2e6, 17):
        t_sat = heos.t_sat(p)
        out += [heos.px(p, x) for x in (0.55, 0.8, 0.95, 0.999, 1.0)]
        out += [heos.pt(p, t_sat + d) for d in (0.02, 0.3, 1.0, 3.0, 20.0, 120.0, 280.0)]
    for p in (0.18e5, 1e5, 8e5):
        g = heos.px(p, 1.0)
        for du in np.linspace(-4e3, 4e3, 17):
            out.append(heos.du(g.rho, g.u + du))
    return out


def test_table_agrees_with_heos_to_its_stated_error(heos, table):
    """Stated error of the table tier, over states it was not built on: pressure and
    temperature within 1e-5 relative, dryness within 1e-6.  (Measured at build on
    4000 random states: 1.6e-6, 4.7e-6, 3e-9; the bound leaves room for the grid.)"""
    states = _grid_states(heos)
    rho = np.array([s.rho for s in states])
    u = np.array([s.u for s in states])
    p, T, x = lookup_many(table.table.arrays(), rho, u)
    ref = np.array([(s.p, s.T, s.x) for s in states])
    assert np.max(np.abs(p / ref[:, 0] - 1)) < 1e-5
    assert np.max(np.abs(T / ref[:, 1] - 1)) < 1e-5
    assert np.max(np.abs(x - ref[:, 2])) < 1e-6
    assert table.error["max_rel_error_p"] < 1e-5


def test_table_reservoir_states_agree_with_heos(heos, table):
    """The states a run sets up its reservoirs with (saturated, wet and superheated
    supplies, dry steam at back pressure, saturation temperatures) come from the table's
    own arrays, against IAPWS-95 (CoolProp HEOS) from 0.01 to 200 bar and superheat
    0.05 to 400 K.  Tolerances: saturation temperature 1e-6 relative (the saturation
    line is tabulated every 0.05 K and interpolated in ln p, measured 1e-8); saturated
    density 1e-5 relative and energies 5 J/kg (measured 1.2e-6 and 0.8 J/kg); superheated
    density 5e-5 relative and energies 50 J/kg, 20 ppm of them (the vapour grid's
    bilinear error, 1.6e-6 in p and 4.7e-6 in T at build, amplified by inverting it for
    (p, T): measured 1.4e-5 and 13 J/kg); entropy, which the table does not hold and is
    integrated along the saturation line and the grid's isochores, 0.05 J/(kg K) of
    about 7000 (measured 0.02)."""
    for p in np.geomspace(1e3, 2e7, 40):
        ts = heos.t_sat(p)
        assert table.t_sat(p) == pytest.approx(ts, rel=1e-6)
        for x in (0.6, 0.95, 1.0):
            a, b = table.px(p, x), heos.px(p, x)
            assert a.T == pytest.approx(b.T, rel=1e-6) and a.x == b.x
            assert a.rho == pytest.approx(b.rho, rel=1e-5)
            assert abs(a.u - b.u) < 5.0 and abs(a.h - b.h) < 5.0 and abs(a.s - b.s) < 0.05
        for dT in (0.05, 1.0, 30.0, 150.0, 400.0):
            b = heos.pt(p, ts + dT)
            if not (0.01 <= b.rho <= 80.0 and b.u <= 4.2e6):
                continue      # off the vapour grid: the table tier asks HEOS
            a = table.pt(p, ts + dT)
            assert a.superheated and a.T == b.T
            assert a.rho == pytest.approx(b.rho, rel=5e-5)
            assert abs(a.u - b.u) < 50.0 and abs(a.h - b.h) < 50.0 and abs(a.s - b.s) < 0.05
            # and it is the state the cylinder's lookup gives back
            p2, T2, _, sup = lookup(table.table.arrays(), a.rho, a.u)
            assert sup and p2 == pytest.approx(p, rel=1e-9) and T2 == pytest.approx(a.T, rel=1e-9)


def test_table_cannot_crash_near_saturation_or_off_the_table(heos, table):
    """The case that crashed CoolProp's TTSE backend (about 1 K above saturation near
    0.18 bar) and inputs far off the table: finite answers, clamped, never a crash."""
    tab = table.table.arrays()
    t_sat = heos.t_sat(0.18e5)
    for dT in (-0.5, 0.0, 0.2, 1.0, 1.5):
        st = heos.pt(0.18e5, t_sat + dT) if dT > 0 else heos.px(0.18e5, 1.0 + dT / 10)
        p, T, x, _ = lookup(tab, st.rho, st.u)
        assert p == pytest.approx(st.p, rel=1e-5)
    for rho, u in ((1e-12, 2.5e6), (1e6, 2.5e6), (1.0, -1e9), (1.0, 1e12), (-3.0, 2.5e6),
                   (1.0, float("nan")), (float("nan"), 2.6e6), (float("inf"), 2.6e6)):
        p, T, x, _ = lookup(tab, rho, u)
        assert math.isfinite(p) and math.isfinite(T) and 0.0 <= x <= 1.0


def test_wet_lookup_answers_the_same_from_any_start(heos, table):
    """The wet state's Newton iteration started from a node's previous temperature
    (``lookup_near``, as the compiled right-hand side starts it) answers what it
    answers from the saturated-vapour end, from any start: near and far, either side,
    the bracket's ends, outside it, garbage.  The iteration is safeguarded by its
    bracket and stops on a Newton step below 1e-7 K, after which it is within about
    1e-14 K (quadratic convergence), or on a bracket narrower than 1e-9 K; so the two
    answers agree within 2e-9 K, and the pressure within 2e-9 K times dln p/dT (below
    0.1 per K over the table) relative.  States: the wet, saturated and superheated
    grid from 0.08 to 22 bar and the sweeps across the saturated-vapour line, where
    the root sits at the bracket's top."""
    tab = table.table.arrays()
    wet = 0
    for st in _grid_states(heos):
        p0, T0, x0, sup0, c0 = lookup_near(tab, st.rho, st.u, math.nan)
        wet += not sup0
        for start in (T0, T0 + 1e-9, T0 - 0.01, T0 + 0.4, T0 - 3.0, T0 - 60.0, T0 + 60.0,
                      273.16, 273.17, 647.0, -5.0, 1e9, math.inf):
            p, T, x, sup, c = lookup_near(tab, st.rho, st.u, start)
            assert (sup, c) == (sup0, c0), (st, start)
            assert abs(T - T0) <= 2e-9, (st, start, T - T0)
            assert p == pytest.approx(p0, rel=2e-10, abs=0.0), (st, start)
            assert x == pytest.approx(x0, rel=1e-9, abs=1e-12), (st, start)
    assert wet >= 80


def test_vectorised_lookup_is_the_scalar_lookup_to_the_bit(heos, table):
    """A run's time series converts its states with :func:`lookup_many` (one compiled
    loop over every cycle's samples), the kernel with the scalar lookup: the two must
    be one function.  Over the grid's wet, saturated and superheated states and inputs
    off the table (clamped), every pressure, temperature and dryness is the same double
    (exact equality: the same arithmetic in the same order leaves no rounding to
    tolerate)."""
    tab = table.table.arrays()
    states = _grid_states(heos)
    rho = np.array([s.rho for s in states] + [1e-12, 1e6, 1.0, 1.0, -3.0, float("nan")])
    u = np.array([s.u for s in states] + [2.5e6, 2.5e6, -1e9, 1e12, 2.5e6, 2.6e6])
    got = np.array(lookup_many(tab, rho, u))
    want = np.array([lookup(tab, r, e)[:3] for r, e in zip(rho, u)]).T
    assert np.array_equal(got, want)


def test_perfect_steam_expands_as_p_v_to_the_1_3():
    """Perfect steam, kappa = 1.3: an isentropic change obeys p v^1.3 = const (closed
    form of the ideal gas with constant specific heats)."""
    st = PerfectSteam()
    a = st.pt(8e5, 500.0)
    b = st.ds(a.rho / 4.0, a.s)
    assert b.p == pytest.approx(a.p * 4.0 ** -1.3, rel=1e-12)
    c = st.ps(1e5, a.s)
    assert c.rho == pytest.approx(a.rho * (1e5 / 8e5) ** (1 / 1.3), rel=1e-12)
    d = st.du(a.rho, a.u)
    assert d.p == pytest.approx(a.p, rel=1e-12) and d.h == pytest.approx(a.h, rel=1e-12)


def test_compiled_kernel_solves_the_same_equations_as_the_python_model():
    """The compiled integrator and scipy's LSODA on the Python right-hand side, both on
    the table tier at rtol 1e-8: the same indicated work and steam to 1e-5."""
    sc = make_scene()
    base = sc.run.fidelity
    comp = corliss.simulate(sc.replace_run(fidelity=dataclasses.replace(
        base, properties="table", method="dopri5", rtol=1e-8, convergence_tolerance=1e-7)))
    py = corliss.simulate(sc.replace_run(fidelity=dataclasses.replace(
        base, properties="table", method="LSODA", rtol=1e-8, convergence_tolerance=1e-7)))
    for k in ("indicated_work_J_per_cycle", "steam_per_cycle_kg"):
        assert comp.summary[k] == pytest.approx(py.summary[k], rel=1e-5), k


def test_tiers_agree_on_the_default_card():
    """standard and fast (table, compiled) within the errors their presets promise
    (0.5 % and 2 %) of the reference (HEOS, LSODA 1e-9); perfect steam is a different
    fluid, not a tier of accuracy, but must still give a card of the same size (10 %)."""
    sc = make_scene()
    ref = corliss.simulate(sc.with_fidelity("reference")).summary
    for name, tol in (("standard", 5e-3), ("fast", 2e-2)):
        s = corliss.simulate(sc.with_fidelity(name)).summary
        for k in ("indicated_power_W", "steam_rate_kg_per_h"):
            assert s[k] == pytest.approx(ref[k], rel=tol), (name, k)
    perfect = dataclasses.replace(sc.run.fidelity, properties="perfect")
    s = corliss.simulate(sc.replace_run(fidelity=perfect)).summary
    assert s["indicated_power_W"] == pytest.approx(ref["indicated_power_W"], rel=0.1)


def test_fixed_step_rk4_converges_as_the_step_shrinks():
    """Fixed-step RK4: the error in indicated power against the reference falls as the
    crank-angle step is halved (2, 1, 0.5 deg)."""
    sc = make_scene()
    ref = corliss.simulate(sc.with_fidelity("reference")).summary["indicated_power_W"]
    errs = []
    for step in ("2 deg", "1 deg", "0.5 deg"):
        s = make_scene(run={"fidelity": "fast", "method": "rk4", "step": step})
        errs.append(abs(corliss.simulate(s).summary["indicated_power_W"] / ref - 1))
    assert errs[0] > errs[1] > errs[2]


def test_compiled_method_needs_a_compiled_tier():
    with pytest.raises(InputError, match="run.method"):
        make_scene(run={"properties": "heos", "method": "dopri5"})


def test_stiff_large_ports_stay_stable_and_cheap_with_rosenbrock():
    """Ports 1000 times too large make the filling and blow-down stiff.  The compiled
    L-stable Rosenbrock method (the fast preset) must stay stable, agree with the
    reference (HEOS, LSODA) to 0.5 % in work, and not pay for the stiffness with a
    storm of steps: fewer than 10 000 evaluations a cycle at the preset's rtol of
    5e-5 (about 5200; the explicit dopri5 needed about 3 million here)."""
    sc = make_scene()
    ref = corliss.simulate(sc.with_fidelity("reference"), portmap_scale=1000.0).summary
    fast = corliss.simulate(sc.with_fidelity("fast"), portmap_scale=1000.0)
    s = fast.summary
    assert s["indicated_work_J_per_cycle"] == pytest.approx(ref["indicated_work_J_per_cycle"],
                                                            rel=5e-3)
    assert s["rhs_evaluations"] / s["cycles_simulated"] < 10_000
    assert s["mass_balance_error"] < 1e-2
