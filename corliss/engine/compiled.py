"""The crank-resolved model on the compiled kernel: arrays in Python, one call a cycle.

Same interface as :class:`corliss.engine.crank_resolved.CrankResolved` (``cycle``,
``initial_state``, ``nfev``), same equations; the difference is where the loop runs.
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine import kernel
from corliss.engine.crank_resolved import CrankResolved
from corliss.thermo.orifice import kappa_of

METHODS = {"dopri5": 0, "rk4": 1, "rosenbrock": 2}


class CompiledCrankResolved(CrankResolved):
    """Crank-resolved model integrated by :func:`corliss.engine.kernel.integrate_cycle`.

    Parameters
    ----------
    method : str
        ``"dopri5"`` (adaptive) or ``"rk4"`` (fixed step).
    step_deg : float
        Crank-angle step of ``rk4`` [deg].
    Other parameters as :class:`CrankResolved`; ``steam`` must have a kernel tier.
    """

    def __init__(self, geometry, portmap, steam, chest, exhaust, omega, method="dopri5",
                 rtol=1e-6, band=0.01, step_deg=1.0):
        super().__init__(geometry, portmap, steam, chest, exhaust, omega, method, rtol, band)
        if steam.kernel_tier is None:
            raise ValueError(f"property tier {steam.name!r} has no compiled form")
        g = geometry
        self._geo = np.array([g.crank_m, g.spec.connecting_rod_m, g.spec.stroke_m,
                              g.area_head_m2, g.area_crank_m2, *g.clearance_m3,
                              1.0 if g.rod_angularity else 0.0])
        self._res = np.array([chest.p, chest.rho, chest.h, kappa_of(chest.x, chest.superheated),
                              exhaust.p, exhaust.rho, exhaust.h,
                              kappa_of(exhaust.x, exhaust.superheated)])
        self._tier = steam.kernel_tier
        if self._tier == kernel.TIER_TABLE:
            self._tab = steam.table.arrays()
            self._perf = np.zeros(3)
        else:
            from corliss.thermo.steam_table import load_table
            self._tab = load_table().arrays()   # unused by the perfect tier, typed the same
            self._perf = np.array(steam.perfect_params())
        self._method = METHODS[method]
        self._step = math.radians(step_deg)
        self._grid = np.ascontiguousarray(portmap.theta_rad)
        self._areas_arr = np.ascontiguousarray(portmap.area_m2)
        self._cd_arr = np.ascontiguousarray(portmap.cd, dtype=float)

    def cycle(self, y0, theta0, out_theta):
        y = np.array(y0, dtype=float)
        y[kernel.N_DYN:] = 0.0
        stops = np.asarray(self.segments(theta0), dtype=float)
        y_end, samples, nfev, ok = kernel.integrate_cycle(
            y, stops, np.asarray(out_theta, dtype=float), self._method, self.rtol, self.atol,
            self._step, self._geo, self._grid, self._areas_arr, self._cd_arr, self._res,
            self.omega, self.band, self._tier, self._tab, self._perf)
        self.nfev += nfev
        if not ok:
            raise RuntimeError("the compiled integrator failed (step size collapsed or the "
                               "state left the steam table); try a smaller rtol or step")
        return y_end, samples
