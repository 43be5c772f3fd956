"""Crank effort: torque on the shaft against crank angle, and its fluctuation.

The piston force F (positive towards the shaft) turns the crank through the exact
slider-crank ratio (virtual work, no friction in the pins)::

    torque(theta) = F(theta) * ds/dtheta

with s the piston displacement from head-end dead centre (Marks Art. 60 III, eq. 191:
to second order ds/dtheta = r (sin theta + sin 2 theta / 2n)).  The piston force is
the pressures on the two faces, the atmosphere on the piston rod where it leaves the
crank-end gland, and, with the ``inertia`` effect, the force that accelerates the
reciprocating masses (Marks Art. 35, eqs. 92-97)::

    F = p_head A_head - p_crank A_crank - p_atm A_rod - m_rec d2s/dt2

Energy fluctuation (Marks Arts. 56-59): against a uniform resisting torque equal to
the mean, the work in excess accumulates and is given back; the spread of that
running excess, ``E_max - E_min``, is what the flywheel must store.  Marks states it
as a fraction ``c`` of the work of one stroke of one cylinder (Table IV, after Hütte).
"""

from __future__ import annotations

import math

import numpy as np


def piston_force_N(geometry, p_head_Pa, p_crank_Pa, barometer_Pa: float):
    """Net steam force on the piston and rod towards the shaft [N]."""
    rod = math.pi / 4.0 * geometry.spec.piston_rod_diameter_m ** 2
    return (np.asarray(p_head_Pa) * geometry.area_head_m2
            - np.asarray(p_crank_Pa) * geometry.area_crank_m2 - barometer_Pa * rod)


def inertia_force_N(geometry, theta, omega: float, mass_kg: float):
    """Force that accelerates the reciprocating masses, as felt at the crosshead [N].

    ``-m d2s/dt2`` at constant speed, with d2s/dtheta2 by the exact slider crank
    (an infinite rod gives Marks's eq. 92, ``m omega^2 r cos theta``).
    """
    th = np.asarray(theta, dtype=float)
    R = geometry.crank_m
    d2s = R * np.cos(th)
    if geometry.rod_angularity:
        L = geometry.spec.connecting_rod_m
        sn, cs = np.sin(th), np.cos(th)
        root = np.sqrt(L * L - (R * sn) ** 2)
        d2s = d2s + R * R * (cs * cs - sn * sn) / root + R ** 4 * sn * sn * cs * cs / root ** 3
    return -mass_kg * omega ** 2 * d2s


def torque_N_m(geometry, theta, force_N):
    """Shaft torque [N m] from the piston force [N] at crank angles [rad]."""
    return np.asarray(force_N) * geometry.dpiston_m_per_rad(theta)


def energy_fluctuation_J(theta, torque) -> float:
    """Largest spread of the running excess of work over the mean torque [J].

    ``theta`` [rad] spans whole turns (uniform grid, ends included); trapezoids.
    """
    th = np.asarray(theta, dtype=float)
    tq = np.asarray(torque, dtype=float)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (tq[1:] + tq[:-1]) * np.diff(th))])
    e = work - work[-1] * (th - th[0]) / (th[-1] - th[0])
    return float(e.max() - e.min())


def combine_cranks(theta, torque_one, phases_rad) -> np.ndarray:
    """Total torque of identical cylinders on one shaft, crank ``k`` leading by
    ``phases_rad[k]`` (Marks Arts. 54-55, 58-59: 90 deg for two, 120 deg for three)."""
    th = np.asarray(theta, dtype=float)
    period = 2.0 * math.pi
    return sum(np.interp((th + ph) % period, th, torque_one, period=period)
               for ph in phases_rad)
