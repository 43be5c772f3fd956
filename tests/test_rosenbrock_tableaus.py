"""The Rosenbrock tableaus of the compiled kernel (``tableaus.ROS_TABLEAUS``): their
order and their damping of stiff modes, from their coefficients.

Each tableau is used in the form of Hairer and Wanner (*Solving Ordinary Differential
Equations II*, Sec. IV.7, eq. 7.25),

    (1/(gamma h) - J) u_i = f(t + c_i h, y + sum_j a_ij u_j) + sum_j c_ij u_j / h
                            + d_i h df/dt,    y1 = y + sum_i b_i u_i,

which is what ``rosenbrock.cycle_ros`` evaluates.  A coefficient copied wrongly shows as
a lost order or a stability function that does not vanish at infinity; these checks
read only the coefficients (no compiled code, so they cost nothing to compile).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from corliss.engine.kernels.tableaus import ROS_TABLEAUS

#: order of the solution, and the stability function at z -> -infinity: Shampine's
#: 4(3) pair (Press et al., Numerical Recipes, 2nd ed., Sec. 16.6) is A-stable but not
#: L-stable, R(-inf) = 1/3; RODAS3 (Sandu et al., Atmos. Environ. 31, 1997) and RODAS4
#: (Hairer and Wanner, Solving ODEs II, Sec. VI.4) are L-stable, R(-inf) = 0
EXPECTED = {"ros4": (4, 1.0 / 3.0), "rodas3": (3, 0.0), "rodas4": (4, 0.0)}


def _step(tableau, f, dfdt, lam, t, y, h):
    """One step on the scalar problem y' = f(t, y) with Jacobian ``lam``."""
    gam, A, C, c, d, b, _e, _same, _expo = tableau
    u = np.zeros(len(b))
    for i in range(len(b)):
        fi = f(t + c[i] * h, y + A[i, :i] @ u[:i])
        u[i] = (fi + h * d[i] * dfdt(t) + C[i, :i] @ u[:i] / h) / (1.0 / (gam * h) - lam)
    return y + b @ u


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_tableau_has_its_order(name):
    """On y' = -(y - cos t) - sin t, y(0) = 1 (solution cos t, non-stiff, and
    non-autonomous so that the d_i of the time derivative count), the error at t = 2
    falls as h^p: the observed order between 20 and 40 steps is p within 0.15 (the
    error is in its asymptotic range there: 10 to 20 steps already give p within
    0.25)."""
    lam = -1.0

    def f(t, y):
        return lam * (y - math.cos(t)) - math.sin(t)

    def dfdt(t):
        return lam * math.sin(t) - math.cos(t)

    errs = []
    for n in (20, 40):
        h, y, t = 2.0 / n, 1.0, 0.0
        for _ in range(n):
            y = _step(ROS_TABLEAUS[name], f, dfdt, lam, t, y, h)
            t += h
        errs.append(abs(y - math.cos(2.0)))
    order = math.log2(errs[0] / errs[1])
    assert order == pytest.approx(EXPECTED[name][0], abs=0.15)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_tableau_damps_stiff_modes_as_it_should(name):
    """The stability function R(z) of y' = lam y, one step of h = 1 at z = lam =
    -1e9: 1/3 for Shampine's pair, 0 for the L-stable RODAS methods (to 1e-6: R(z)
    approaches its limit as 1/z)."""
    z = -1e9
    y1 = _step(ROS_TABLEAUS[name], lambda t, y: z * y, lambda t: 0.0, z, 0.0, 1.0, 1.0)
    assert y1 == pytest.approx(EXPECTED[name][1], abs=1e-6)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_error_estimate_is_of_lower_order(name):
    """The embedded error (sum e_i u_i) of one step on the problem of the order test
    falls as h^(q+1) with q the estimate's order, one less than the solution's (the
    exponent the step control takes, -1/(q+1)); observed between h = 0.1 and 0.05
    within 0.3."""
    lam = -1.0
    gam, A, C, c, d, b, e, _same, expo = ROS_TABLEAUS[name]

    def err(h):
        u = np.zeros(len(b))
        for i in range(len(b)):
            ti, yi = c[i] * h, 1.0 + A[i, :i] @ u[:i]
            fi = lam * (yi - math.cos(ti)) - math.sin(ti)
            u[i] = (fi + h * d[i] * (-1.0) + C[i, :i] @ u[:i] / h) / (1.0 / (gam * h) - lam)
        return abs(e @ u)

    slope = math.log2(err(0.1) / err(0.05))
    assert slope == pytest.approx(-1.0 / expo, abs=0.3)


def test_the_compiled_tableau_integrator_gives_the_standard_card():
    """``rosenbrock.cycle_ros`` itself, on the default scene: RODAS4 at rtol 1e-4 and
    Shampine's pair at 7e-6 give the indicated power and the steam of the ``standard``
    preset (RODAS4 at 2e-6 on this card, itself within 3e-5 of the converged reference) within the
    accuracy the study measured for them across its three scenes (0.16 % and 0.005 %,
    README "Accuracy and time"), taken as 0.3 % and 0.02 % for a margin over the
    study's worst scene.  A wrong coefficient in the compiled stage loop, which the
    checks above cannot see, shows here as a card off by far more or a run that never
    becomes periodic."""
    import dataclasses

    import corliss
    from corliss.engine.options import PRESETS

    scene = corliss.load_scene(corliss.default_scene_path())
    ref = corliss.simulate(scene.with_fidelity("standard")).summary
    for method, rtol, tol in (("rodas4", 1e-4, 3e-3), ("ros4", 7e-6, 2e-4)):
        fid = dataclasses.replace(PRESETS["standard"], name="custom", method=method, rtol=rtol)
        got = corliss.simulate(scene.replace_run(fidelity=fid)).summary
        assert got["cycles_to_converge"] is not None, method
        for key in ("indicated_power_W", "steam_per_cycle_kg"):
            assert got[key] == pytest.approx(ref[key], rel=tol), (method, key)


def test_the_ode23s_pair_follows_the_crank_end_filling():
    """The ``fast`` preset's Shampine pair keeps the crank end at chest pressure while
    its steam port stands open after the lead (185-205 deg on the default card).

    There the cylinder fills nearly at the chest's pressure: a run at rtol 1e-7 has it
    0.07-0.12 % of the supply pressure below.  The pair, linearly implicit, has a
    second, spurious solution there: its midpoint stage goes 1/(2 d) = 1.7 Newton
    steps towards the port's equilibrium, past it, where the flux is steeper in the
    pressure drop (square-root like outside the port's band), and the stage's
    derivative comes back reversed.  At constant steps of 0.3 to 0.5 deg from 192 deg
    the pair settles 0.4 to 2 % below the chest with error estimates of 0.2 to 0.7,
    accepted.  Its step control walked onto that branch from 183 deg before the
    predictive controller: the samples up to 1.2 % off the tight run's at rtol 5e-5
    (2.1 % at 7e-5), at 0.3-0.4 deg steps with a rejection every other step.  With it,
    0.12 % (the cubic Hermite output between steps of 1.7 deg swinging about the
    filling).  Tolerance 0.25 % of the supply pressure: twice that, a fifth of the
    spurious branch's offset.
    """
    import dataclasses

    import numpy as np

    import corliss
    from corliss.engine.options import PRESETS

    scene = corliss.load_scene(corliss.default_scene_path())

    def crank_end(fid):
        r = corliss.simulate(scene.replace_run(fidelity=fid))
        ts = r.timeseries
        last = ts[ts["cycle"] == ts["cycle"].max()]
        theta = np.asarray(last["crank_angle_deg"]) % 360.0
        sel = (theta >= 185.0) & (theta <= 205.0)
        return theta[sel], np.asarray(last["p_crank_Pa"])[sel], r.summary["supply_pressure_Pa"]

    fast = PRESETS["fast"]
    th, p, supply = crank_end(fast)
    th_ref, p_ref, _ = crank_end(dataclasses.replace(fast, name="tight", rtol=1e-7))
    assert np.array_equal(th, th_ref) and th.size >= 10      # every 2 deg at fast
    assert np.max(np.abs(p - p_ref)) / supply < 2.5e-3
