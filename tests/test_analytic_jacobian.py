"""The Rosenbrock integrators' analytic Jacobian against differences.

``jacobians._jacobian_exact`` builds the Jacobian of the compiled right-hand side over
the dynamic states (each node's mass and energy) from the derivatives of its parts:
the steam table's own interpolation in (rho, u) for pressure, enthalpy and the
port-flow exponent, the closed form of the orifice flow in its two sides' states,
the chain rule through rho = m/V and u = E/m; and the right-hand side's derivative
in crank angle at a fixed state (through the volumes, and the ports' areas on their
PortMap tables).  Here they are compared, at 36 states 10 deg
apart over a cycle, with differences of the same compiled right-hand side: central, or
where the state sits on a kink, one-sided.  The kinks are real: the steam's
pressure at constant energy changes its slope where the state crosses saturation (a
cylinder end that has equalised with a dry saturated exhaust sits on that line, and
its two one-sided derivatives differ tenfold), and so do the flow's at equal
pressures and at the critical ratio; the analytic form takes the branch the
right-hand side itself takes there, so an entry passes when it matches the central
or either one-sided difference.  A state can sit exactly on such a kink: on the
steam-chest network the fourth-order ``ros4`` leaves the chest, while the ports
draw nothing, at the supply's pressure to the last bit, where the pipe's flow is 0
and turns; its two one-sided derivatives carry the supply's flux slope and enthalpy
(the chest's pressure falling) or the chest's (rising), and the analytic form must
take one pair, not the flux of one side with the enthalpy of the other (which was
1.2e-4 of the row's scale from both).  The cycle the states come from is
``rosenbrock``'s, and for the steam chest also ``ros4``'s.

The tolerance: a central difference of relative step d = 1e-6 has a truncation
error of order d^2 of a smooth function and a rounding error of order eps / d = 2e-10
of the row's terms.  A one-sided difference errs by the curvature: near equal
pressures the flow is a quadratic in (1 - r) / band (band 3.5e-3), so a step of
d in the pressure errs by about d / band of the slope; d = 1e-9 gives 3e-7, and a
rounding error of 2e-7 of the row's terms; the analytic form's own finite difference (of the
flow in the isentropic exponent, forward, step 1e-7) errs by about 1e-7 of that
term, a small share of the row's largest.  Each entry's contribution
``|J_ij| |y_j|`` is compared with the largest such contribution of its row over the
cycle: 1e-5 leaves room for the exponent's difference and would still catch a lost
term (a dropped enthalpy or exponent derivative is 1e-3 to 1 of the row).  The
differences could straddle a cell edge of the bilinear table (a jump of the
derivative) with a probability of about d over a cell's width (1e-4 a column); the
states are fixed, so the test is deterministic.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import corliss
from conftest import make_scene
from corliss.engine.kernels import jacobians
from corliss.engine.condensation import MarksLaw
from corliss.engine.crank_resolved import CrankResolved
from corliss.engine.model import assemble
from corliss.engine.options import PRESETS

ROOT = __import__("pathlib").Path(__file__).resolve().parent.parent
STEP = 1e-6     # relative step of the central differences [-]
STEP_ONE_SIDED = 1e-9   # and of the one-sided ones [-] (module docstring)
EPS = np.finfo(float).eps
TOL = 1e-5      # of the row's largest contribution over the cycle (module docstring)


def _scene(name):
    if name == "default":
        return make_scene()
    if name == "steam chest":
        return make_scene(supply={"chest_volume": "3 ft3", "pipe_diameter": "5 in"},
                          run={"effects": ["port_flow", "rod_angularity", "steam_chest"]})
    if name == "period leak":
        # the period's linear leaks (chest to exhaust, head to crank), with the chest a
        # state so that the valve's leak has partials too
        return make_scene(supply={"chest_volume": "3 ft3", "pipe_diameter": "5 in"},
                          engine={"leakage_model": "period", "valve_leak_rate": "3 lb/h psi",
                                  "piston_leak_rate": "1 lb/h psi"},
                          run={"effects": ["port_flow", "rod_angularity", "steam_chest",
                                           "leakage"]})
    if name == "marks":
        return make_scene(engine={"wall_heat_model": "marks"},
                          run={"effects": ["port_flow", "rod_angularity", "wall_heat"]})
    if name == "perfect steam":
        fid = dataclasses.replace(PRESETS["standard"], name="custom", properties="perfect")
        return make_scene().replace_run(fidelity=fid)
    return corliss.load_scene(ROOT / "scenes" / f"{name}.toml")


@pytest.mark.parametrize("name, method", [
    ("default", "rosenbrock"), ("steam chest", "rosenbrock"), ("steam chest", "ros4"),
    ("period leak", "rosenbrock"), ("marks", "rosenbrock"),
    ("perfect steam", "rosenbrock"), ("high-speed-condensing", "rosenbrock"),
    ("twin-90-degrees", "rosenbrock")])
def test_analytic_jacobian_matches_central_differences(name, method):
    """Every entry of the analytic Jacobian, and of the derivative in crank angle,
    within 1e-5 of its row's scale of the central or a one-sided difference, at 36
    states of a cycle (module docstring)."""
    scene = _scene(name)
    model = assemble(scene, tabulated=True)
    net = model.network(model.portmap)
    crank = CrankResolved(net, model.steam, method, 1e-5)
    if name == "marks":
        # Marks's schedule as a steady run sets it for its first cycle
        MarksLaw(net, model.geometry, model.events, scene.run.speed_rad_s, model.chest.T,
                 model.exhaust.T).apply(crank.net.heat)
    assert jacobians._exact_jacobian_holds(crank.net)
    # every 10 deg from 3.7 deg: off the PortMap tables' uniform grid of a quarter or
    # half degree, whose nodes are kinks of the areas in crank angle: a sample on one
    # would compare the ports' slopes of one side with differences of the other (a step
    # of the integrators may start on one: any one-sided slope serves there)
    out = np.radians(3.7 + 10.0 * np.arange(36))
    y, samples = crank.cycle(crank.initial_state(), 0.0, out)
    nd, n = net.n_dyn, y.size
    J, T = np.zeros((n, nd)), np.zeros(n)
    jd, slope = np.empty((12, net.n_nodes)), np.empty_like(crank._cell)
    exact, diffs, exact_t, diffs_t, fresh = [], [], [], [], []
    for k, th in enumerate(out):
        yk = samples[:, k].copy()
        crank._pr[:] = np.nan         # no evaluation's properties: the full lookups
        jacobians._jacobian_exact(th, yk, J, T, crank.net, crank._tier, crank._tab, crank._perf,
                               crank._pr, crank._cell, jd, slope)
        f0 = crank.rhs(th, yk)
        # after the right-hand side at the same state, as the integrators call it: the
        # node properties taken from that evaluation give the same Jacobian
        J2, T2 = np.zeros_like(J), np.zeros_like(T)
        jacobians._jacobian_exact(th, yk, J2, T2, crank.net, crank._tier, crank._tab,
                               crank._perf, crank._pr, crank._cell, jd, slope)
        fresh.append((J2 - J, T2 - T))
        # and after a right-hand side at another state (a rejected step's trial): the
        # Jacobian must not take that evaluation's properties
        crank.rhs(th, yk * (1.0 + 1e-3))
        jacobians._jacobian_exact(th, yk, J2, T2, crank.net, crank._tier, crank._tab,
                               crank._perf, crank._pr, crank._cell, jd, slope)
        fresh.append((J2 - J, T2 - T))
        Jf, Jb, Jc = np.zeros_like(J), np.zeros_like(J), np.zeros_like(J)
        for j in range(nd):
            for step, sign, out_ in ((STEP_ONE_SIDED, 1.0, Jf), (STEP_ONE_SIDED, -1.0, Jb)):
                yp = yk.copy()
                yp[j] += sign * step * abs(yk[j])
                out_[:, j] = sign * (crank.rhs(th, yp) - f0) / (step * abs(yk[j]))
            d = STEP * abs(yk[j])
            yp, ym = yk.copy(), yk.copy()
            yp[j] += d
            ym[j] -= d
            Jc[:, j] = (crank.rhs(th, yp) - crank.rhs(th, ym)) / (2.0 * d)
        # in crank angle: steps as the floats represent them (th + d - th)
        tp1, tm1, tp, tm = th + STEP_ONE_SIDED, th - STEP_ONE_SIDED, th + STEP, th - STEP
        diffs_t.append([(crank.rhs(tp1, yk) - f0) / (tp1 - th),
                        (f0 - crank.rhs(tm1, yk)) / (th - tm1),
                        (crank.rhs(tp, yk) - crank.rhs(tm, yk)) / (tp - tm)])
        exact_t.append(T.copy())
        scale = np.abs(yk[:nd])
        exact.append(J * scale)
        diffs.append([Jf * scale, Jb * scale, Jc * scale])
    exact, diffs = np.array(exact), np.array(diffs)
    central = diffs[:, 2]
    row = np.abs(central).max(axis=(0, 2))            # each row's largest term, over the cycle
    row[row == 0.0] = 1.0                             # rows nothing moves (checked exactly)
    err = np.abs(exact[:, None] - diffs).min(axis=1) / row[None, :, None]
    exact_t, diffs_t = np.array(exact_t), np.array(diffs_t)
    row_t = np.abs(diffs_t[:, 2]).max(axis=0)
    row_t[row_t == 0.0] = 1.0
    err_t = np.abs(exact_t[:, None] - diffs_t).min(axis=1) / row_t[None, :]
    if name == "marks":
        # the energy rows, which Marks's heat moves in crank angle with the wall exposed:
        # to 1e-6 of the row's scale (the differences' rounding, 2e-7 at the one-sided
        # step, module docstring); without the schedule's term they were off by 5e-4
        energy = err_t[:, 1:nd:2]
        assert energy.max() < 1e-6, f"energy rows d/dtheta: {energy.max():.2e}"
    kt, it = np.unravel_index(np.argmax(err_t), err_t.shape)
    assert err_t.max() < TOL, (f"d/dtheta: {err_t.max():.2e} at {math.degrees(out[kt]):.0f} deg, "
                               f"row {it}: {exact_t[kt, it]:.6e} against {diffs_t[kt, :, it]}")
    k, i, j = np.unravel_index(np.argmax(err), err.shape)
    assert err.max() < TOL, (f"{err.max():.2e} at {math.degrees(out[k]):.0f} deg, row {i}, "
                             f"column {j}: {exact[k, i, j]:.6e} against {diffs[k, :, i, j]}")
    # the Jacobian from the right-hand side's node properties (after an evaluation
    # at its state), or not (after one at another state): the same
    # arithmetic but for the wet lookup's iteration, which agrees within 2e-9 K from
    # any start (tests/test_property_tiers.py), a few 1e-10 of the row's terms at most
    for k, (dJ, dT) in enumerate(fresh):
        deg = math.degrees(out[k // 2])
        assert np.all(np.abs(dJ * np.abs(samples[:nd, k // 2])) <= 1e-9 * row[:, None]), (
            f"Jacobian after an evaluation at {deg:.0f} deg ({('its', 'another')[k % 2]} state)")
        assert np.all(np.abs(dT) <= 1e-9 * row_t), f"d/dtheta at {deg:.0f} deg"


def test_table_partials_match_differences_wet_and_superheated():
    """The steam table's pressure and exponent partials
    (``pressure_partials`` on ``lookup_flagged``'s answer, ``kappa_partials``)
    against central differences of
    ``lookup_flagged`` and ``kappa_at`` on a grid of wet and superheated states from
    0.05 to 20 kg/m3 and 2.0 to 3.2 MJ/kg: within 1e-5 relative, plus the differences
    rounding (4 eps |f| / d).  A central difference of relative step 1e-7 errs by
    about 1e-7 relative where the interpolation is linear in ln rho; a step that
    straddles a cell edge or saturation is covered by also accepting either one-sided
    difference."""
    from corliss.thermo.steam_table import (kappa_at, kappa_partials, load_table,
                                            lookup_flagged, pressure_partials)
    tab = load_table().arrays()
    seen = set()
    for rho in np.geomspace(0.05, 20.0, 23):
        for u in np.linspace(2.0e6, 3.2e6, 29):
            p, T, _, sup, code = lookup_flagged(tab, rho, u)
            p_r, p_u = pressure_partials(tab, rho, u, p, T, sup, code)
            if code:
                continue
            seen.add(sup)
            k, k_r, k_u = kappa_partials(tab, rho, u)
            for x, d, val, fun in ((rho, 1e-7 * rho, p_r, lambda r: lookup_flagged(tab, r, u)[0]),
                                   (u, 1e-7 * u, p_u, lambda v: lookup_flagged(tab, rho, v)[0]),
                                   (rho, 1e-7 * rho, k_r, lambda r: kappa_at(tab, r, u)),
                                   (u, 1e-7 * u, k_u, lambda v: kappa_at(tab, rho, v))):
                f0, fp, fm = fun(x), fun(x + d), fun(x - d)
                cands = ((fp - fm) / (2 * d), (fp - f0) / d, (f0 - fm) / d)
                tol = 1e-5 * max(abs(c) for c in cands) + 4.0 * EPS * abs(f0) / d
                assert min(abs(val - c) for c in cands) <= tol, (rho, u, val, cands)
    assert seen == {True, False}
