"""The crank-resolved filling-and-emptying model of the two cylinder ends.

Each end is a control volume of mass m and internal energy U, connected to the
steam chest and to the exhaust through its two ports.  With crank speed omega
constant, over crank angle theta (first law for an open system, no wall heat)::

    dm/dtheta = (mdot_steam + mdot_exhaust) / omega
    dU/dtheta = (mdot_steam h_steam + mdot_exhaust h_exhaust) / omega - p dV/dtheta

where each mdot is positive into the cylinder and carries the enthalpy of the side
it comes from (:func:`corliss.thermo.orifice.port_flow`).  Pressure, temperature and
enthalpy come from the property backend given density m/V and u = U/m.  Five
quadratures per end ride along: mass and enthalpy from the chest, from the exhaust,
and the indicated work integral p dV; they give the steam rate and close the mass and
energy balances.

The state vector is a plain array and the right-hand side reads the PortMap by
interpolation, so a compiled kernel can replace :meth:`CrankResolved.rhs` without
touching the assembly.  Integration stops at every kink of the port areas.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from corliss.engine.geometry import CylinderGeometry
from corliss.thermo.orifice import kappa_of, port_flow
from corliss.thermo.steam import State, Steam
from corliss.valves.portmap import PortMap

TWO_PI = 2.0 * math.pi
N_DYN = 4        # m_head, U_head, m_crank, U_crank
N_QUAD = 5       # per end: m_chest, H_chest, m_exhaust, H_exhaust, work
N_STATE = N_DYN + 2 * N_QUAD
RHO_MIN = 0.02       # [kg/m3], saturated vapour near 25 degC (far below any condenser)
U_MIN = 1.0e6        # [J/kg], wet steam of dryness about 0.35
U_MAX = 4.0e6        # [J/kg], superheated far beyond any engine


def quad_index(end: int, what: str) -> int:
    """Index of a quadrature in the state vector (end 0 = head, 1 = crank)."""
    return N_DYN + end * N_QUAD + ("m_chest", "H_chest", "m_exhaust", "H_exhaust", "work").index(what)


class CrankResolved:
    """Right-hand side and cycle integration of the two-end model.

    Parameters
    ----------
    geometry : CylinderGeometry
    portmap : PortMap
    steam : Steam
    chest, exhaust : State
        Reservoir states (constant).
    omega : float
        Crank speed [rad/s].
    method : str
        ``solve_ivp`` method.
    rtol : float
        Relative tolerance [-].
    band : float
        Regularisation band of the orifice law [-].
    """

    def __init__(self, geometry: CylinderGeometry, portmap: PortMap, steam: Steam,
                 chest: State, exhaust: State, omega: float, method: str = "LSODA",
                 rtol: float = 1e-6, band: float = 0.01):
        self.geometry = geometry
        self.portmap = portmap
        self.steam = steam
        self.chest = chest
        self.exhaust = exhaust
        self.omega = omega
        self.method = method
        self.rtol = rtol
        self.band = band
        self.k_chest = kappa_of(chest.x, chest.superheated)
        self.k_exh = kappa_of(exhaust.x, exhaust.superheated)
        g = geometry
        self._R = g.crank_m
        self._L = g.spec.connecting_rod_m
        self._S = g.spec.stroke_m
        self._Ah, self._Ac = g.area_head_m2, g.area_crank_m2
        self._Vch, self._Vcc = g.clearance_m3
        self._ang = g.rod_angularity
        self._grid = portmap.theta_rad
        self._areas = [portmap.area_m2[i] for i in range(4)]
        self._cd = [float(c) for c in portmap.cd]
        vmax = sum(g.swept_m3) + sum(g.clearance_m3)
        m_scale = vmax * chest.rho
        scale = np.empty(N_STATE)
        scale[[0, 2]] = m_scale
        scale[[1, 3]] = m_scale * chest.u
        for e in range(2):
            scale[quad_index(e, "m_chest")] = m_scale
            scale[quad_index(e, "m_exhaust")] = m_scale
            scale[quad_index(e, "H_chest")] = m_scale * chest.h
            scale[quad_index(e, "H_exhaust")] = m_scale * chest.h
            scale[quad_index(e, "work")] = chest.p * vmax
        self.atol = rtol * scale
        self.nfev = 0

    def volumes(self, th: float):
        """(V_head, dV_head/dtheta, V_crank, dV_crank/dtheta) [m3, m3/rad]."""
        R, L = self._R, self._L
        sn, cs = math.sin(th), math.cos(th)
        s = R * (1.0 - cs)
        ds = R * sn
        if self._ang:
            root = math.sqrt(L * L - R * R * sn * sn)
            s += L - root
            ds += R * R * sn * cs / root
        return (self._Vch + self._Ah * s, self._Ah * ds,
                self._Vcc + self._Ac * (self._S - s), -self._Ac * ds)

    def _admissible(self, m: float, U: float, V: float) -> tuple[float, float]:
        """Density and internal energy clamped to where steam properties exist.

        Implicit and adaptive integrators probe trial states (a negative mass in a
        stiff blow-down); clamping keeps the right-hand side defined there, and its
        flows then push the state back, instead of the property call failing.
        """
        rho = m / V
        if not rho > RHO_MIN:
            return RHO_MIN, self.chest.u
        u = U / m
        return rho, min(max(u, U_MIN), U_MAX)

    def end_flows(self, area_s: float, area_e: float, cd_s: float, cd_e: float, m: float,
                  U: float, V: float):
        """Port flows of one end: (mdot_s, hflow_s, mdot_e, hflow_e, p) [kg/s, W, Pa]."""
        try:
            st = self.steam.du(*self._admissible(m, U, V))
        except ValueError:   # a trial state with no steam state: treat as exhaust steam
            st = self.exhaust
        k = kappa_of(st.x, st.superheated)
        ch, ex = self.chest, self.exhaust
        ms = port_flow(area_s, cd_s, ch.p, ch.rho, self.k_chest, st.p, st.rho, k, self.band)
        me = port_flow(area_e, cd_e, ex.p, ex.rho, self.k_exh, st.p, st.rho, k, self.band)
        hs = ms * (ch.h if ms > 0.0 else st.h)
        he = me * (ex.h if me > 0.0 else st.h)
        return ms, hs, me, he, st.p

    def rhs(self, th: float, y: np.ndarray) -> np.ndarray:
        """Derivatives with respect to crank angle [per rad]."""
        self.nfev += 1
        t = th % TWO_PI
        g, a = self._grid, self._areas
        Vh, dVh, Vc, dVc = self.volumes(th)
        w = self.omega
        dy = np.empty(N_STATE)
        for end, (V, dV, i_s, i_e) in enumerate(((Vh, dVh, 0, 1), (Vc, dVc, 2, 3))):
            As = np.interp(t, g, a[i_s])
            Ae = np.interp(t, g, a[i_e])
            ms, hs, me, he, p = self.end_flows(As, Ae, self._cd[i_s], self._cd[i_e],
                                               y[2 * end], y[2 * end + 1], V)
            dy[2 * end] = (ms + me) / w
            dy[2 * end + 1] = (hs + he) / w - p * dV
            q = N_DYN + end * N_QUAD
            dy[q] = ms / w
            dy[q + 1] = hs / w
            dy[q + 2] = me / w
            dy[q + 3] = he / w
            dy[q + 4] = p * dV
        return dy

    def segments(self, theta0: float) -> list[float]:
        """Stops over one cycle from ``theta0``: every kink of the port areas."""
        bp = np.sort(np.asarray(self.portmap.breakpoints_rad) % TWO_PI)
        stops = [theta0 + ((b - theta0) % TWO_PI) for b in bp]
        stops = sorted(s for s in stops if 1e-9 < s - theta0 < TWO_PI - 1e-9)
        return [theta0] + stops + [theta0 + TWO_PI]

    def cycle(self, y0: np.ndarray, theta0: float, out_theta: np.ndarray):
        """Integrate one cycle from ``theta0``.

        Parameters
        ----------
        y0 : ndarray
            State at ``theta0`` (quadratures are reset to zero).
        out_theta : ndarray
            Crank angles within [theta0, theta0 + 2 pi] where the state is sampled.

        Returns
        -------
        y_end : ndarray
            State at the end of the cycle (quadratures = cycle totals).
        samples : ndarray
            State at ``out_theta``, shape ``(N_STATE, len(out_theta))``.
        """
        y = np.array(y0, dtype=float)
        y[N_DYN:] = 0.0
        samples = np.full((N_STATE, len(out_theta)), np.nan)
        stops = self.segments(theta0)
        for a, b in zip(stops[:-1], stops[1:]):
            sel = np.nonzero((out_theta >= a) & (out_theta <= b))[0]
            t_eval = np.unique(np.append(out_theta[sel], b))
            sol = solve_ivp(self.rhs, (a, b), y, method=self.method, rtol=self.rtol,
                            atol=self.atol, t_eval=t_eval)
            if not sol.success:
                raise RuntimeError(f"integration failed between {math.degrees(a):.2f} and "
                                   f"{math.degrees(b):.2f} deg: {sol.message}")
            if sel.size:
                samples[:, sel] = sol.y[:, np.searchsorted(sol.t, out_theta[sel])]
            y = sol.y[:, -1].copy()
        return y, samples

    def initial_state(self) -> np.ndarray:
        """A start at head dead centre: head end full of chest steam, crank end of exhaust."""
        Vh, _, Vc, _ = self.volumes(0.0)
        y = np.zeros(N_STATE)
        y[0], y[1] = Vh * self.chest.rho, Vh * self.chest.rho * self.chest.u
        y[2], y[3] = Vc * self.exhaust.rho, Vc * self.exhaust.rho * self.exhaust.u
        return y
