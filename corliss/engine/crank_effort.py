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
    """Net steam force on the piston and rod towards the shaft.

    ``F = p_head A_head - p_crank A_crank - p_atm A_rod``: the atmosphere presses on
    the piston rod where it leaves the crank-end gland.

    Parameters
    ----------
    geometry : CylinderGeometry
        The cylinder (piston areas and rod diameter).
    p_head_Pa, p_crank_Pa : float or array_like
        Absolute pressures in the head and crank ends [Pa], of one shape.
    barometer_Pa : float
        Atmospheric pressure on the rod [Pa].

    Returns
    -------
    ndarray
        The force towards the shaft [N], of the pressures' shape.
    """
    rod = math.pi / 4.0 * geometry.spec.piston_rod_diameter_m ** 2
    return (np.asarray(p_head_Pa) * geometry.area_head_m2
            - np.asarray(p_crank_Pa) * geometry.area_crank_m2 - barometer_Pa * rod)


def inertia_force_N(geometry, theta, omega: float, mass_kg: float):
    """Force that accelerates the reciprocating masses, as felt at the crosshead.

    ``-m d2s/dt2`` at constant speed, ``d2s/dt2 = omega^2 d2s/dtheta2``, with
    ``d2s/dtheta2`` by the exact slider crank when the geometry has rod angularity
    (an infinite rod gives Marks's eq. 92, ``m omega^2 r cos theta``, Art. 35).
    Positive towards the shaft, like the steam force it is added to: it holds the
    piston back at the start of the stroke and drives it at the end.

    Parameters
    ----------
    geometry : CylinderGeometry
        The cylinder (crank radius, connecting rod, rod angularity).
    theta : float or array_like
        Crank angle from head-end dead centre [rad].
    omega : float
        Shaft speed [rad/s].
    mass_kg : float
        The reciprocating mass [kg].

    Returns
    -------
    ndarray
        The force towards the shaft [N], of ``theta``'s shape.
    """
    return -mass_kg * omega ** 2 * geometry.d2piston_m_per_rad2(theta)


def torque_N_m(geometry, theta, force_N):
    """Shaft torque from the piston force: ``F ds/dtheta`` (virtual work, Marks Art. 60).

    Parameters
    ----------
    geometry : CylinderGeometry
        The cylinder (its slider-crank ``ds/dtheta``).
    theta : float or array_like
        Crank angle from head-end dead centre [rad].
    force_N : float or array_like
        Piston force towards the shaft [N], broadcast against ``theta``.

    Returns
    -------
    ndarray
        The torque on the shaft [N m], positive in the direction of rotation.
    """
    return np.asarray(force_N) * geometry.dpiston_m_per_rad(theta)


def energy_fluctuation_J(theta, torque) -> float:
    """Largest spread of the running excess of work over the mean torque.

    The work of the torque less that of a uniform torque doing the same work over the
    span, integrated by trapezoids; its range ``E_max - E_min`` is what the flywheel
    stores and gives back (Marks Arts. 56-59).

    Parameters
    ----------
    theta : array_like
        Crank angles [rad], increasing, spanning whole turns, ends included; shape (n,).
    torque : array_like
        The torque at each angle [N m]; shape (n,).

    Returns
    -------
    float
        The energy fluctuation ``E_max - E_min`` [J].
    """
    th = np.asarray(theta, dtype=float)
    tq = np.asarray(torque, dtype=float)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (tq[1:] + tq[:-1]) * np.diff(th))])
    e = work - work[-1] * (th - th[0]) / (th[-1] - th[0])
    return float(e.max() - e.min())


def combine_cranks(theta, torque_one, phases_rad) -> np.ndarray:
    """Total torque of identical cylinders on one shaft.

    Crank ``k`` leads the first by ``phases_rad[k]`` (Marks Arts. 54-55, 58-59: 90 deg
    for two, 120 deg for three); each cylinder's torque is the one cylinder's, read
    periodically at its own crank angle.

    Parameters
    ----------
    theta : array_like
        Crank angles of the first crank over one turn [rad]; shape (n,).
    torque_one : array_like
        One cylinder's torque at those angles [N m]; shape (n,).
    phases_rad : sequence of float
        The lead of each crank [rad], the first's (0) included.

    Returns
    -------
    ndarray
        The shaft's total torque at ``theta`` [N m]; shape (n,).
    """
    th = np.asarray(theta, dtype=float)
    period = 2.0 * math.pi
    return sum(np.interp((th + ph) % period, th, torque_one, period=period)
               for ph in phases_rad)
