"""Slider-crank kinematics and the volumes of the two cylinder ends.

Crank angle ``theta`` = 0 at head-end dead centre (piston farthest from the shaft).
Piston displacement from the head-end dead centre, towards the shaft, with crank
radius R and connecting rod L (Marks Art. 96 III, eqs. 239-241)::

    s(theta) = R (1 - cos theta) + L - sqrt(L^2 - R^2 sin^2 theta)

and with an infinite rod (no ``rod_angularity`` effect) ``s = R (1 - cos theta)``.
The head end's volume is its clearance plus ``A_head s``; the crank end's is its
clearance plus ``A_crank (S - s)``, where ``A_crank`` is the piston area less the
piston rod.  Clearance is a fraction of that end's swept volume.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class EngineSpec:
    """A double-acting cylinder (all SI).

    Parameters
    ----------
    bore_m, stroke_m, connecting_rod_m, piston_rod_diameter_m : float
        Cylinder bore, piston stroke, connecting rod centre to centre, piston rod
        diameter [m].
    clearance : tuple of float
        Clearance volume of the (head, crank) end as a fraction of that end's swept
        volume [-].
    reciprocating_mass_kg : float or None
        Piston, rod, crosshead and the reciprocating share of the connecting rod [kg]
        (for the ``inertia`` effect).
    friction_torque_N_m : float
        Constant part of the engine's friction torque [N m] (``friction`` effect).
    friction_N_m_s : float
        Speed-proportional part of the friction torque [N m s/rad].
    valve_leakage_area_m2, piston_leakage_area_m2 : float
        Equivalent orifice areas of the leaks past the valve (into each end) and past
        the piston (between the ends) [m2] (``leakage`` effect).
    wall_heat_model : str
        ``"skin"`` (a wall with a temperature, :mod:`corliss.engine.wall`; the
        default), ``"marks"`` (his law as a schedule), ``"conductance"`` or ``"adair"``
        (``wall_heat`` effect).
    marks_constant_W_m2K : float
        Marks's constant of condensation as a surface conductance [W/(m2 K)]
        (Art. 82: 18.13 Btu per ft2, degF and minute).
    crank_angles_rad : tuple of float
        One entry per identical cylinder on the shaft: the angle each crank follows
        the first [rad] (Marks Arts. 54-59: 90 deg for two, 120 deg for three).
    condensing_W_m2K : float or None
        The skin model's coefficient of condensation and evaporation on the wall
        [W/(m2 K)] (:mod:`corliss.engine.wall`); None: set by Marks's eq. 221
        (:mod:`corliss.engine.calibration`).
    jacket : str
        ``"none"``, ``"barrel"``, ``"covers"`` or ``"barrel_and_covers"``: the parts of
        the wall whose outer face is held at the jacket steam's saturation temperature
        (skin model; :func:`corliss.engine.wall.jacketed_area_m2`).
    wall_thickness_m : float
        The wall between bore (or cover's face) and jacket [m] (skin model, with a
        jacket).
    steam_ends : str
        The ends that take steam: ``"both"`` (double-acting), ``"head"`` or ``"crank"``
        (single-acting: the other end's exhaust port stands open,
        :mod:`corliss.valves.single_acting`).
    leakage_model : str
        ``"orifice"`` (the leak areas above) or ``"period"`` (the rates of leak below,
        :mod:`corliss.thermo.leak_law`).
    valve_leak_rate_kg_s_Pa, piston_leak_rate_kg_s_Pa : float
        Rates of leak of the valve (chest to exhaust) and past the piston, flow per
        unit of pressure difference [kg/(s Pa)] (``leakage`` effect, period model).
    steam_edge_leak_rate_kg_s_Pa, exhaust_edge_leak_rate_kg_s_Pa : float
        Rates of leak past each closed steam edge (the steam side into the end) and
        each closed exhaust edge (the end to the exhaust side) of the reference valve
        (:mod:`corliss.engine.leak_paths`), flow per unit of pressure difference
        [kg/(s Pa)] (``leakage`` effect, period model).
    jacket_pressure_Pa, lp_jacket_pressure_Pa : float or None
        The jacket steam's absolute pressure [Pa] on the high-pressure (or only)
        cylinder and on a compound's low-pressure cylinder; None: the defaults of
        :func:`corliss.engine.wall.jacket_pressures_Pa`.
    """

    bore_m: float
    stroke_m: float
    connecting_rod_m: float
    piston_rod_diameter_m: float
    clearance: tuple[float, float]
    reciprocating_mass_kg: float | None = None
    friction_torque_N_m: float = 0.0
    friction_N_m_s: float = 0.0
    valve_leakage_area_m2: float = 0.0
    piston_leakage_area_m2: float = 0.0
    wall_heat_model: str = "skin"
    marks_constant_W_m2K: float = 6176.8
    crank_angles_rad: tuple[float, ...] = (0.0,)
    condensing_W_m2K: float | None = 16747.2
    jacket: str = "none"
    wall_thickness_m: float = 0.0254
    steam_ends: str = "both"
    leakage_model: str = "orifice"
    valve_leak_rate_kg_s_Pa: float = 0.0
    piston_leak_rate_kg_s_Pa: float = 0.0
    steam_edge_leak_rate_kg_s_Pa: float = 0.0
    exhaust_edge_leak_rate_kg_s_Pa: float = 0.0
    jacket_pressure_Pa: float | None = None
    lp_jacket_pressure_Pa: float | None = None


@dataclass(frozen=True)
class CylinderGeometry:
    """Kinematics and end volumes of one cylinder.

    Parameters
    ----------
    spec : EngineSpec
        The cylinder's dimensions.
    rod_angularity : bool
        True: exact slider crank; False: infinite connecting rod.
    """

    spec: EngineSpec
    rod_angularity: bool = True

    @property
    def crank_m(self) -> float:
        """Crank radius R [m]."""
        return 0.5 * self.spec.stroke_m

    @property
    def area_head_m2(self) -> float:
        """Piston area on the head side [m2]."""
        return math.pi / 4.0 * self.spec.bore_m ** 2

    @property
    def area_crank_m2(self) -> float:
        """Piston area on the crank side, less the piston rod [m2]."""
        return self.area_head_m2 - math.pi / 4.0 * self.spec.piston_rod_diameter_m ** 2

    @property
    def swept_m3(self) -> tuple[float, float]:
        """Swept volume of the (head, crank) end [m3]."""
        return (self.area_head_m2 * self.spec.stroke_m, self.area_crank_m2 * self.spec.stroke_m)

    @property
    def clearance_m3(self) -> tuple[float, float]:
        """Clearance volume of the (head, crank) end [m3]."""
        sh, sc = self.swept_m3
        return (self.spec.clearance[0] * sh, self.spec.clearance[1] * sc)

    def piston_m(self, theta):
        """Piston displacement from head-end dead centre (Marks Art. 96 III, eqs. 239-241).

        Parameters
        ----------
        theta : float or array_like
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        ndarray
            ``s = R (1 - cos theta) + L - sqrt(L^2 - R^2 sin^2 theta)`` [m] (without
            rod angularity, ``R (1 - cos theta)``, eq. 239), of ``theta``'s shape.
        """
        # the displacement alone, by the operations of :meth:`_slider_crank` (the same
        # bits): the volumes and the events read it alone, a dozen times a run
        R = self.crank_m
        th = np.asarray(theta, dtype=float)
        s = R * (1.0 - np.cos(th))
        if self.rod_angularity:
            L = self.spec.connecting_rod_m
            s = s + L - np.sqrt(L * L - (R * np.sin(th)) ** 2)
        return s

    def dpiston_m_per_rad(self, theta):
        """Derivative of the piston displacement with crank angle.

        Parameters
        ----------
        theta : float or array_like
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        ndarray
            ``ds/dtheta = R sin theta + R^2 sin theta cos theta / sqrt(L^2 - R^2
            sin^2 theta)`` [m/rad], of ``theta``'s shape.
        """
        return self._slider_crank(theta)[1]

    def d2piston_m_per_rad2(self, theta):
        """Second derivative of the piston displacement with crank angle.

        Parameters
        ----------
        theta : float or array_like
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        ndarray
            ``d2s/dtheta2`` [m/rad2], of ``theta``'s shape.
        """
        return self._slider_crank(theta)[2]

    def _slider_crank(self, theta):
        """``(s, ds/dtheta, d2s/dtheta2)`` on arrays [m, m/rad, m/rad2].

        The slider crank's array form: the compiled kernels' scalar form is
        :func:`corliss.engine.kernels.mechanism.slider_crank`, the same law (Marks Art.
        96 III, eqs. 239-241) with its operations in another order, which this one keeps
        so that the numbers computed from it (a run's initial masses, its valve events)
        keep their last bits; tests/test_slider_crank.py holds the two forms equal to
        round-off at random states.
        """
        R = self.crank_m
        th = np.asarray(theta, dtype=float)
        sn, cs = np.sin(th), np.cos(th)
        s = R * (1.0 - cs)
        ds = R * sn
        d2s = R * cs
        if self.rod_angularity:
            L = self.spec.connecting_rod_m
            root = np.sqrt(L * L - (R * sn) ** 2)
            s = s + L - root
            ds = ds + R * R * sn * cs / root
            d2s = d2s + R * R * (cs * cs - sn * sn) / root + R ** 4 * sn * sn * cs * cs / root ** 3
        return s, ds, d2s

    def fraction(self, theta):
        """Piston position as a fraction of the stroke from head-end dead centre.

        Parameters
        ----------
        theta : float or array_like
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        ndarray
            ``s / S`` [-], 0 at head-end and 1 at crank-end dead centre.
        """
        return self.piston_m(theta) / self.spec.stroke_m

    def volumes_m3(self, theta):
        """Volumes of the two cylinder ends, clearance included.

        Parameters
        ----------
        theta : float or array_like
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        V_head : ndarray
            ``clearance + A_head s`` [m3], of ``theta``'s shape.
        V_crank : ndarray
            ``clearance + A_crank (S - s)`` [m3], of ``theta``'s shape.
        """
        s = self.piston_m(theta)
        ch, cc = self.clearance_m3
        return (ch + self.area_head_m2 * s,
                cc + self.area_crank_m2 * (self.spec.stroke_m - s))

    def dvolumes_m3_per_rad(self, theta):
        """Derivatives of the end volumes with crank angle.

        Parameters
        ----------
        theta : float or array_like
            Crank angle from head-end dead centre [rad].

        Returns
        -------
        dV_head : ndarray
            ``A_head ds/dtheta`` [m3/rad], of ``theta``'s shape.
        dV_crank : ndarray
            ``-A_crank ds/dtheta`` [m3/rad], of ``theta``'s shape.
        """
        ds = self.dpiston_m_per_rad(theta)
        return (self.area_head_m2 * ds, -self.area_crank_m2 * ds)
