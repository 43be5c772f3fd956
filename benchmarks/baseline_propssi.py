"""The straightforward baseline: scipy ``solve_ivp`` with ``PropsSI`` in the right-hand side.

Written the way an engineer would write it in an afternoon for the default scene
(12 x 24 in slide-valve engine, 120 rpm, 100 psig): both cylinder ends as control
volumes over time, the valve motion and port areas evaluated inside the right-hand
side, steam properties by ``PropsSI`` calls, LSODA at rtol 1e-6 (RK45 drove the mass negative in a
blow-down and stopped).  It is the yardstick
the accuracy study divides by; it is not used by corliss.

Run alone: ``python benchmarks/baseline_propssi.py`` prints seconds per cycle and the
indicated power.
"""

from __future__ import annotations

import math
import time

import numpy as np
from CoolProp.CoolProp import PropsSI
from scipy.integrate import solve_ivp

IN = 0.0254
PSI = 6894.757
BORE, STROKE, ROD, PROD = 12 * IN, 24 * IN, 60 * IN, 2.5 * IN
CLEAR = 0.08
R_ECC, LAP, LEAD, PORT_W, PORT_L, CD, ECC_ROD = 3 * IN, 1 * IN, 0.25 * IN, 1.25 * IN, 9.6 * IN, 0.7, 60 * IN
P_SUP, P_EXH = 114.696 * PSI, 14.696 * PSI
RPM = 120.0


def run(cycles: int = 3):
    omega = RPM * 2 * math.pi / 60
    A_h = math.pi / 4 * BORE ** 2
    A_c = A_h - math.pi / 4 * PROD ** 2
    Vs_h, Vs_c = A_h * STROKE, A_c * STROKE
    delta = math.asin((LAP + LEAD) / R_ECC)
    rho_s = PropsSI("D", "P", P_SUP, "Q", 1, "Water")
    h_s = PropsSI("H", "P", P_SUP, "Q", 1, "Water")
    rho_e = PropsSI("D", "P", P_EXH, "Q", 1, "Water")
    h_e = PropsSI("H", "P", P_EXH, "Q", 1, "Water")
    k = 1.135

    def flux(p0, r0, p1):
        r = max(p1 / p0, (2 / (k + 1)) ** (k / (k - 1)))
        r = min(r, 0.99)
        g = math.sqrt(2 * k / (k - 1) * p0 * r0 * (r ** (2 / k) - r ** ((k + 1) / k)))
        if p1 / p0 > 0.99:
            g *= (1 - p1 / p0) / 0.01
        return g

    def flow(area, p_res, r_res, p, rho):
        if area <= 0:
            return 0.0
        if p_res >= p:
            return CD * area * flux(p_res, r_res, p)
        return -CD * area * flux(p, rho, p_res)

    def rhs(t, y):
        th = omega * t
        Rc = STROKE / 2
        s = Rc * (1 - math.cos(th)) + ROD - math.sqrt(ROD ** 2 - (Rc * math.sin(th)) ** 2)
        ds = (Rc * math.sin(th) + Rc ** 2 * math.sin(th) * math.cos(th)
              / math.sqrt(ROD ** 2 - (Rc * math.sin(th)) ** 2)) * omega
        x = R_ECC * math.sin(th + delta) + (math.sqrt(ECC_ROD ** 2 - (R_ECC * math.cos(delta)) ** 2)
                                             - math.sqrt(ECC_ROD ** 2 - (R_ECC * math.cos(th + delta)) ** 2))
        opening = [x - LAP, -x, -x - LAP, x]
        areas = [min(max(o, 0.0), PORT_W) * PORT_L for o in opening]
        vols = [(CLEAR * Vs_h + A_h * s, A_h * ds), (CLEAR * Vs_c + A_c * (STROKE - s), -A_c * ds)]
        dy = np.zeros(6)
        for e in range(2):
            m, U = y[2 * e], y[2 * e + 1]
            V, dV = vols[e]
            rho, u = m / V, U / m
            p = PropsSI("P", "D", rho, "U", u, "Water")
            h = PropsSI("H", "D", rho, "U", u, "Water")
            ms = flow(areas[2 * e], P_SUP, rho_s, p, rho)
            me = flow(areas[2 * e + 1], P_EXH, rho_e, p, rho)
            dy[2 * e] = ms + me
            dy[2 * e + 1] = ms * (h_s if ms > 0 else h) + me * (h_e if me > 0 else h) - p * dV
            dy[4 + e] = p * dV
        return dy

    V0h, V0c = CLEAR * Vs_h, CLEAR * Vs_c + Vs_c
    u_s = PropsSI("U", "P", P_SUP, "Q", 1, "Water")
    u_e = PropsSI("U", "P", P_EXH, "Q", 1, "Water")
    y0 = [V0h * rho_s, V0h * rho_s * u_s, V0c * rho_e, V0c * rho_e * u_e, 0.0, 0.0]
    period = 2 * math.pi / omega
    t0 = time.perf_counter()
    works = []
    y = np.array(y0)
    for c in range(cycles):
        y[4:] = 0.0
        sol = solve_ivp(rhs, (c * period, (c + 1) * period), y, method="LSODA", rtol=1e-6,
                        atol=[1e-8, 1e1, 1e-8, 1e1, 1e-3, 1e-3])
        y = sol.y[:, -1].copy()
        works.append(y[4] + y[5])
    wall = time.perf_counter() - t0
    return wall / cycles, works[-1] / period


if __name__ == "__main__":
    per_cycle, power = run()
    print(f"baseline: {per_cycle:.3f} s per cycle, indicated power {power / 745.7:.2f} ihp")
