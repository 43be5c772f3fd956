"""Marks's law of initial condensation (Relative Proportions, Arts. 74-82): the period's
prediction of the steam that condenses on the walls at each stroke.

The loss is proportional to the temperature drop from cut-off to exhaust, to the
cast-iron surface exposed, and to the time it was exposed to the exhaust (Art. 75)::

    condensation per stroke = C (T_b - T_e) (pi d / 2N) (d + Y(e) s)          (eq. 221)
    Y(e) = 1 - [sqrt(1 - (2e - 1)^2) - (2e - 1) acos(2e - 1)] / pi           (curve of condensation)

with d the bore and s the stroke, N strokes per unit time, e the true cut-off (a
fraction of the volume with one clearance), T_b the steam temperature at cut-off and
T_e the exhaust temperature.  C = 0.02047 lb of steam per ft2, degF and minute, the
mean of his concordant experiments (Art. 82, p. 209).
"""

from __future__ import annotations

import logging
import math

from corliss.engine.kernels.data import H_MARKS_Q, H_MARKS_WALL_EXPAND, H_MODEL, WALL_MARKS
from corliss.keys import units
from corliss.thermo.steam import HEOSSteam, latent_heat

log = logging.getLogger(__name__)

#: Marks's mean constant of condensation, Art. 82, in kg / (m2 K s).
MARKS_C = 0.02047 * units.POUND_kg / (units.FOOT_m ** 2 * (5.0 / 9.0) * 60.0)


def curve_of_condensation(e: float) -> float:
    """Marks's curve of condensation, Art. 75.

    Parameters
    ----------
    e : float
        The true cut-off: the volume at cut-off over the volume at the end of the
        stroke, clearance included in both [-]; clipped to [0, 1].

    Returns
    -------
    float
        ``Y(e)`` [-]: the fraction of the stroke's barrel that counts as exposed, 0 at
        ``e = 0`` and 1 at ``e = 1``.
    """
    a = 2.0 * min(max(e, 0.0), 1.0) - 1.0
    return 1.0 - (math.sqrt(max(1.0 - a * a, 0.0)) - a * math.acos(a)) / math.pi


def marks_condensation_kg(bore_m: float, stroke_m: float, strokes_per_s: float, e: float,
                          t_cutoff_K: float, t_exhaust_K: float, C: float = MARKS_C) -> float:
    """Steam condensed per stroke by Marks's eq. 221 (Art. 75; SI throughout).

    Parameters
    ----------
    bore_m : float
        Cylinder bore ``d`` [m].
    stroke_m : float
        Stroke ``s`` [m].
    strokes_per_s : float
        Strokes per unit time ``N`` [1/s] (two a revolution).
    e : float
        True cut-off, clearance included [-] (:func:`curve_of_condensation`).
    t_cutoff_K : float
        Steam temperature at cut-off ``T_b`` [K].
    t_exhaust_K : float
        Exhaust temperature ``T_e`` [K]; a drop below zero counts as none.
    C : float, optional
        Constant of condensation [kg/(m2 K s)]; by default Marks's mean,
        :data:`MARKS_C` (Art. 82, p. 209).

    Returns
    -------
    float
        The steam condensed on the walls at each stroke [kg].
    """
    return (C * max(t_cutoff_K - t_exhaust_K, 0.0) * math.pi * bore_m / (2.0 * strokes_per_s)
            * (bore_m + curve_of_condensation(e) * stroke_m))


def exposed_wall_m2(geometry, end: int, theta):
    """The wall the steam of one end touches.

    Piston face and cover, and the barrel uncovered with the clearance as its
    equivalent length, ``2 A_p + pi D V / A_p`` (the area the compiled kernel uses).

    Parameters
    ----------
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    end : int
        0 for the head end, 1 for the crank end.
    theta : float or numpy.ndarray
        Crank angle [rad].

    Returns
    -------
    float or numpy.ndarray
        The exposed wall [m2], shaped as ``theta``.
    """
    import numpy as np
    ap = geometry.area_head_m2 if end == 0 else geometry.area_crank_m2
    V = geometry.volumes_m3(np.asarray(theta, dtype=float))[end]
    return 2.0 * ap + math.pi * geometry.spec.bore_m * V / ap


def marks_law_row(geometry, end: int, events: dict, strokes_per_s: float, t_cutoff_K: float,
                  t_exhaust_K: float, latent_J_kg: float, phase_rad: float = 0.0):
    """Columns 5-10 of a node's wall-heat row for Marks's law.

    The heat is eq. 221's condensation times the latent heat at the cut-off pressure
    (Art. 74: "multiply by the total heat less the heat of the liquid"); see
    :func:`corliss.engine.network.with_wall_heat` for the row.

    Parameters
    ----------
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    end : int
        0 for the head end, 1 for the crank end.
    events : dict
        That end's valve events (``admission_deg``, ``cutoff_deg``,
        ``compression_deg`` [deg of its own crank angle] and ``cutoff_frac`` [-]).
    strokes_per_s : float
        Strokes per unit time [1/s].
    t_cutoff_K : float
        Steam temperature at cut-off [K].
    t_exhaust_K : float
        Exhaust temperature [K].
    latent_J_kg : float
        Latent heat at the cut-off temperature [J/kg].
    phase_rad : float, optional
        Phase of the cylinder's crank [rad]; unused (the events are in the end's own
        crank angle).

    Returns
    -------
    tuple of float or None
        The heat of a cycle [J]; the admission, cut-off and compression angles [rad];
        the exposed wall integrated over admission and over cut-off to compression
        [m2 rad].  None when the end has no cut-off or compression (Marks's law needs
        both).
    """
    import numpy as np
    ev = events
    if ev["cutoff_deg"] is None or ev["compression_deg"] is None or ev["admission_deg"] is None:
        return None
    a0, a1, a2 = (math.radians(ev[k]) for k in ("admission_deg", "cutoff_deg", "compression_deg"))
    vc, vs = geometry.clearance_m3[end], geometry.swept_m3[end]
    e_true = (vc + vs * ev["cutoff_frac"]) / (vc + vs)
    mass = marks_condensation_kg(geometry.spec.bore_m, geometry.spec.stroke_m, strokes_per_s,
                                 e_true, t_cutoff_K, t_exhaust_K)

    def integral(a, b):
        span = (b - a) % (2 * math.pi)
        th = a + np.linspace(0.0, span, 721)
        return float(np.trapezoid(exposed_wall_m2(geometry, end, th), th))

    return (mass * latent_J_kg, a0, a1, a2, integral(a0, a1), integral(a1, a2))


class MarksLaw:
    """Keeps the Marks's-law rows of a network's piston ends up to date, cycle by cycle.

    Each cycle's heat uses the steam temperature at cut-off of the cycle before (at
    first, the supply's saturation temperature) and the exhaust's saturation
    temperature (Marks's T_b and T_e, Art. 75).

    Parameters
    ----------
    network : corliss.engine.network.Network
        The compiled network; its piston ends whose wall-heat row is Marks's law
        (model code 3) are kept.
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    events : dict
        Valve events by end (``"head"``, ``"crank"``), as :func:`marks_law_row` reads.
    speed_rad_s : float
        Crank speed [rad/s].
    supply_T_K : float
        The supply's saturation temperature [K], the first cycle's cut-off temperature.
    exhaust_T_K : float
        The exhaust's saturation temperature [K].
    lp_events : dict, optional
        A compound's low-pressure valve events by end: its ends (``lp_head``,
        ``lp_crank``) take their rows from these and from the LP cylinder's geometry.

    Notes
    -----
    Each end's row is built from its own cylinder's geometry (``network.geometries``)
    and events, in that cylinder's own crank angle (the kernel adds the cylinder's
    phase), and its cut-off temperature is sampled at the shaft angle where that
    cylinder cuts off, so that each end gives back over a cycle what it takes.
    """

    def __init__(self, network, geometry, events: dict, speed_rad_s: float, supply_T_K: float,
                 exhaust_T_K: float, lp_events: dict | None = None):
        self.network = network
        self.geometry = geometry
        self.events = events
        self.lp_events = lp_events
        self.strokes_per_s = 2.0 * speed_rad_s / (2.0 * math.pi)
        self.t_exhaust = exhaust_T_K
        self._heos = HEOSSteam()
        self.ends = [(i, 0 if network.node_end[i] == 0 else 1)
                     for i, row in enumerate(network.node_heat) if row[H_MODEL] == WALL_MARKS]
        self.t_cutoff = {i: supply_T_K for i, _ in self.ends}
        if self.ends:
            log.warning("wall_heat_model = \"marks\" imposes eq. 221's heat as a schedule, "
                        "whatever the steam's temperature: the heat given back after release "
                        "goes into the little steam left and can heat it beyond any wall's "
                        "temperature.  It is the period's rule, kept for comparison; "
                        "\"skin\" (the default) obeys the second law")

    @staticmethod
    def latent(T: float) -> float:
        """Latent heat ``h_g - h_f`` at a saturation temperature (IAPWS-95).

        Parameters
        ----------
        T : float
            Saturation temperature [K].

        Returns
        -------
        float
            The latent heat [J/kg].
        """
        return latent_heat(T)

    def _end(self, i: int, end: int):
        """Node ``i``'s cylinder geometry, valve events and phase [rad]."""
        net = self.network
        c = net.node_cyl[i]
        lp_events = self.lp_events
        evs = (lp_events if lp_events is not None and net.node_names[i].startswith("lp_")
               else self.events)
        return (net.geometries[c], evs["head" if end == 0 else "crank"],
                float(net.phases[c]))

    def rows(self) -> dict:
        """The Marks's-law rows for the current cut-off temperatures.

        Returns
        -------
        dict
            Node index -> columns 5-10 of its wall-heat row (:func:`marks_law_row`;
            zero heat for an end without cut-off or compression).
        """
        out = {}
        for i, end in self.ends:
            geo, ev, _ = self._end(i, end)
            row = marks_law_row(geo, end, ev, self.strokes_per_s, self.t_cutoff[i],
                                self.t_exhaust, self.latent(self.t_cutoff[i]))
            out[i] = row if row is not None else (0.0, 0.0, 0.0, 0.0, 1.0, 1.0)
        return out

    def apply(self, heat_array) -> None:
        """Write the rows into the compiled network's wall-heat array.

        Parameters
        ----------
        heat_array : numpy.ndarray
            The network's wall-heat array, shape ``(nodes, columns)``; columns 5-10 of
            each kept node are overwritten in place.
        """
        for i, row in self.rows().items():
            heat_array[i, H_MARKS_Q:H_MARKS_WALL_EXPAND + 1] = row

    def update(self, steam, samples, out_theta) -> None:
        """Take the cut-off temperatures from a cycle's samples.

        Parameters
        ----------
        steam : corliss.thermo.steam.Steam
            The run's steam properties.
        samples : numpy.ndarray
            The cycle's sampled state, shape ``(2 nodes, samples)``: each node's mass
            [kg] and internal energy [J] in alternate rows.
        out_theta : numpy.ndarray
            Crank angles of the samples [rad].
        """
        import numpy as np
        net = self.network
        for i, end in self.ends:
            _, ev, phase = self._end(i, end)
            if ev["cutoff_deg"] is None:
                continue
            # the shaft's angle where this cylinder cuts off (its own angle leads by
            # its phase)
            th = (math.radians(ev["cutoff_deg"]) - phase) % (2 * math.pi)
            k = int(np.argmin(np.abs(((out_theta - th) + math.pi) % (2 * math.pi) - math.pi)))
            V = float(net.volume(i, np.array([out_theta[k]]))[0])
            m, U = samples[2 * i, k], samples[2 * i + 1, k]
            if not (m > 0.0 and np.isfinite(U)):
                continue
            st = steam.du(m / V, U / m)
            self.t_cutoff[i] = self._heos.t_sat(min(st.p, 2.2e7))
