"""The period's laws of initial condensation imposed as a schedule: Marks's
(Relative Proportions, Arts. 74-82) and English's (Proc. IMechE 1887-89, through
Gottlob, DPJ 267, 1888, pp. 293-302).

Both are imposed the same way (:class:`ScheduledWallHeat`, one schedule for two laws):
the heat a law gives for a cycle leaves each end's steam from admission to cut-off and
comes back from cut-off to compression, each spread over the crank angle in proportion
to the wall exposed, so each end nets zero over a cycle (:func:`schedule_row`).

**Marks's law.**

The loss is proportional to the temperature drop from cut-off to exhaust, to the
cast-iron surface exposed, and to the time it was exposed to the exhaust (Art. 75)::

    condensation per stroke = C (T_b - T_e) (pi d / 2N) (d + Y(e) s)          (eq. 221)
    Y(e) = 1 - [sqrt(1 - (2e - 1)^2) - (2e - 1) acos(2e - 1)] / pi           (curve of condensation)

with d the bore and s the stroke, N strokes per unit time, e the true cut-off (a
fraction of the volume with one clearance), T_b the steam temperature at cut-off and
T_e the exhaust temperature.  C = 0.02047 lb of steam per ft2, degF and minute, the
mean of his concordant experiments (Art. 82, p. 209).

**English's law** (DPJ 267, p. 302; :func:`english_heat_J`): the heat the
steam-swept surfaces hold at a piston position, in English units [Btu, lb/ft3, ft2]::

    C = K gamma_1 S_c / sqrt(n) (1 - (gamma_0 + 0.06) / gamma_1 S / S_c)

with K = 80 unjacketed and 60 jacketed (Gottlob's metric 13.55 and 10.16 [kcal, kg/m3,
m2], 0.9612 kg/m3 for 0.06), n revolutions per second, S_c the clearance surface (piston
and cover faces included), S the surface the steam touches at the piston position
considered, gamma_1 and gamma_0 the densities of saturated steam at the admission
pressure and at the back pressure (at the exhaust's closing).  At S = S_c it is the
"sudden condensation" of the entering steam on the clearance surface; "this heat is
given back in part over the piston's travel, in proportion to the surface growing"
(p. 300).  The law was fitted to English's trials on a 16 x 18 in engine and to
clearance-only trials on a 10 x 14 in portable-engine cylinder, jacketed but for its
covers, whose piston, valve and condenser "were found perfectly tight" (p. 302): it is
condensation without leakage.

How the model reads it (:class:`EnglishLaw`):

* the heat of a cycle is C at cut-off, S the wall the steam touches then: what the
  surfaces hold at the end of admission, the water English says counts (p. 297).  It is
  taken over the admission and given back from cut-off to compression on Marks's
  schedule, where English's own line gives it back in proportion to the surface
  uncovered and the rest in the exhaust; the water at cut-off is his, its timing after
  cut-off the schedule's.  Where the line is below zero at cut-off (a long cut-off, a
  low admission density) the walls hold nothing and no heat is taken;
* S_c and S are :func:`exposed_wall_m2`'s, the piston and cover faces and the barrel
  (the clearance counted as the barrel it would fill), the surface the kernel's other
  wall laws use.  It leaves out the passages: English's 10 x 14 in cylinder had 2 ft2
  of clearance surface where the rule gives 1.26, so the law gives the model's engines
  less than their real clearance surfaces would;
* n is the crank's revolutions per second, for every end: each end takes steam once a
  revolution, a double-acting cylinder's two ends each with its own S_c and S, a
  single-acting cylinder's steam end alone (its idle end has no wall heat);
* gamma_1 and gamma_0 are read from each end's own steam, at its cut-off and at its
  compression, in the cycle before (the supply's and the exhaust's saturation in the
  first): the admission pressure as the period read it off the card, and the back
  pressure at the exhaust's closing, a compound's receiver for its HP ends;
* K is 60 where the scene has a ``jacket``, 80 without.
"""

from __future__ import annotations

import logging
import math

import numpy as np

from corliss.engine.kernels.data import H_MARKS_Q, H_MARKS_WALL_EXPAND, H_MODEL, WALL_MARKS
from corliss.engine.kernels.properties import visited_states
from corliss.keys import units
from corliss.thermo.steam import HEOSSteam, latent_heat, saturated_vapour_density

log = logging.getLogger(__name__)

#: Marks's mean constant of condensation, Art. 82, in kg / (m2 K s).
MARKS_C = 0.02047 * units.POUND_kg / (units.FOOT_m ** 2 * (5.0 / 9.0) * 60.0)

#: English's constant, unjacketed and jacketed, in his units: Btu per (lb/ft3 ft2) and
#: sqrt(second) (DPJ 267, 1888, p. 302: 80 and 60).
ENGLISH_K_BTU = {False: 80.0, True: 60.0}
#: The density English adds to gamma_0, 0.06 lb/ft3 (p. 302; Gottlob's 0.9612 kg/m3).
ENGLISH_GAMMA_LB_FT3 = 0.06
#: One British thermal unit (International Table) [J].
BTU_J = units.from_unit(1.0, "Btu")
#: English's constants in SI, J per (kg/m3 m2) times sqrt(s) (80 Btu/(lb/ft) is 56,718
#: J m/kg; Gottlob's metric 13.55 kcal/(kg/m) is 56,731).
ENGLISH_K_SI = {jacketed: k * BTU_J * units.FOOT_m / units.POUND_kg
                for jacketed, k in ENGLISH_K_BTU.items()}
#: English's added density in SI [kg/m3].
ENGLISH_GAMMA_KG_M3 = ENGLISH_GAMMA_LB_FT3 * units.POUND_kg / units.FOOT_m ** 3


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
    ap = geometry.area_head_m2 if end == 0 else geometry.area_crank_m2
    V = geometry.volumes_m3(np.asarray(theta, dtype=float))[end]
    return 2.0 * ap + math.pi * geometry.spec.bore_m * V / ap


def schedule_row(geometry, end: int, events: dict, heat_J: float):
    """Columns 5-10 of a node's wall-heat row for a law imposed as a schedule.

    The heat ``heat_J`` leaves the steam from admission to cut-off and comes back from
    cut-off to compression, each spread over the crank angle in proportion to the wall
    exposed (:func:`exposed_wall_m2`); see :func:`corliss.engine.network.with_wall_heat`.

    Parameters
    ----------
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    end : int
        0 for the head end, 1 for the crank end.
    events : dict
        That end's valve events (``admission_deg``, ``cutoff_deg``,
        ``compression_deg`` [deg of its own crank angle]).
    heat_J : float
        The heat of a cycle [J].

    Returns
    -------
    tuple of float or None
        The heat of a cycle [J]; the admission, cut-off and compression angles [rad];
        the exposed wall integrated over admission and over cut-off to compression
        [m2 rad].  None when the end has no admission, cut-off or compression (the
        schedule needs all three).
    """
    from scipy.integrate import simpson
    ev = events
    if ev["cutoff_deg"] is None or ev["compression_deg"] is None or ev["admission_deg"] is None:
        return None
    a0, a1, a2 = (math.radians(ev[k]) for k in ("admission_deg", "cutoff_deg", "compression_deg"))

    def integral(a, b):
        # Simpson's rule on 721 points: 1e-12 of the integral, where the trapezoid's
        # 2e-7 would leave the heat given back that far from the heat taken
        span = (b - a) % (2 * math.pi)
        th = a + np.linspace(0.0, span, 721)
        return float(simpson(exposed_wall_m2(geometry, end, th), x=th))

    return (heat_J, a0, a1, a2, integral(a0, a1), integral(a1, a2))


def marks_law_row(geometry, end: int, events: dict, strokes_per_s: float, t_cutoff_K: float,
                  t_exhaust_K: float, latent_J_kg: float, phase_rad: float = 0.0):
    """Columns 5-10 of a node's wall-heat row for Marks's law.

    The heat is eq. 221's condensation times the latent heat at the cut-off pressure
    (Art. 74: "multiply by the total heat less the heat of the liquid"), imposed by
    :func:`schedule_row`.

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
        As :func:`schedule_row`; None when the end has no cut-off or compression
        (Marks's law needs both).
    """
    ev = events
    if ev["cutoff_deg"] is None or ev["compression_deg"] is None or ev["admission_deg"] is None:
        return None
    vc, vs = geometry.clearance_m3[end], geometry.swept_m3[end]
    e_true = (vc + vs * ev["cutoff_frac"]) / (vc + vs)
    mass = marks_condensation_kg(geometry.spec.bore_m, geometry.spec.stroke_m, strokes_per_s,
                                 e_true, t_cutoff_K, t_exhaust_K)
    return schedule_row(geometry, end, ev, mass * latent_J_kg)


def english_heat_J(rho_admission_kg_m3: float, rho_back_kg_m3: float, clearance_wall_m2: float,
                   swept_wall_m2: float, rev_per_s: float, jacketed: bool) -> float:
    """English's law: the heat the steam-swept surfaces hold at a piston position.

    ``C = K (gamma_1 S_c - (gamma_0 + 0.06) S) / sqrt(n)`` (T. English, Proc. IMechE
    1887-89, through S. Gottlob, DPJ 267, 1888, p. 302), K = 80 Btu per (lb/ft3 ft2)
    s^(1/2) unjacketed and 60 jacketed (:data:`ENGLISH_K_SI`), 0.06 lb/ft3 added to
    gamma_0 (:data:`ENGLISH_GAMMA_KG_M3`), in SI here.  Never below zero: where the
    line falls below zero the surface has given back all it took.

    Parameters
    ----------
    rho_admission_kg_m3 : float
        ``gamma_1``, the density of saturated steam at the admission pressure [kg/m3].
    rho_back_kg_m3 : float
        ``gamma_0``, the density of saturated steam at the back pressure at the
        exhaust's closing [kg/m3].
    clearance_wall_m2 : float
        ``S_c``, the clearance's surface, piston and cover faces included [m2].
    swept_wall_m2 : float
        ``S``, the surface the steam touches at the piston position considered [m2];
        ``S_c`` at the end of the stroke.
    rev_per_s : float
        ``n``, revolutions of the crank per second [1/s]: each end takes steam once a
        revolution, double-acting or single-acting.
    jacketed : bool
        Whether the cylinder is jacketed (K = 60) or not (K = 80).

    Returns
    -------
    float
        The heat the surfaces hold, taken from the steam [J], zero or more.
    """
    c = (rho_admission_kg_m3 * clearance_wall_m2
         - (rho_back_kg_m3 + ENGLISH_GAMMA_KG_M3) * swept_wall_m2)
    return max(ENGLISH_K_SI[bool(jacketed)] * c / math.sqrt(rev_per_s), 0.0)


def english_law_row(geometry, end: int, events: dict, rev_per_s: float,
                    rho_admission_kg_m3: float, rho_back_kg_m3: float, jacketed: bool):
    """Columns 5-10 of a node's wall-heat row for English's law.

    The heat is :func:`english_heat_J` at cut-off (S the wall exposed at cut-off, S_c at
    the end's dead centre, both :func:`exposed_wall_m2`): what the surfaces hold at the
    end of admission, the water English says counts (DPJ 267, p. 297), taken over the
    admission and given back from cut-off to compression by :func:`schedule_row`.

    Parameters
    ----------
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    end : int
        0 for the head end, 1 for the crank end.
    events : dict
        That end's valve events (``admission_deg``, ``cutoff_deg``,
        ``compression_deg`` [deg of its own crank angle]).
    rev_per_s : float
        Revolutions of the crank per second [1/s].
    rho_admission_kg_m3 : float
        Density of saturated steam at the admission pressure [kg/m3].
    rho_back_kg_m3 : float
        Density of saturated steam at the back pressure [kg/m3].
    jacketed : bool
        Whether the cylinder is jacketed.

    Returns
    -------
    tuple of float or None
        As :func:`schedule_row`.
    """
    if events["cutoff_deg"] is None:
        return None
    s_c = float(exposed_wall_m2(geometry, end, math.pi * end))
    s = float(exposed_wall_m2(geometry, end, math.radians(events["cutoff_deg"])))
    heat = english_heat_J(rho_admission_kg_m3, rho_back_kg_m3, s_c, s, rev_per_s, jacketed)
    return schedule_row(geometry, end, events, heat)


class ScheduledWallHeat:
    """Keeps the rows of a network's piston ends whose wall heat is a law imposed as a
    schedule (model code 3) up to date, cycle by cycle.

    Each cycle's heat uses the steam's pressure at cut-off and at compression of the
    cycle before (at first, the supply's and the exhaust's saturation temperatures);
    the law is a subclass's :meth:`heat_row`.

    Parameters
    ----------
    network : corliss.engine.network.Network
        The compiled network; its piston ends whose wall-heat row is a schedule (model
        code 3) are kept.
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    events : dict
        Valve events by end (``"head"``, ``"crank"``), as :func:`schedule_row` reads.
    speed_rad_s : float
        Crank speed [rad/s].
    supply_T_K : float
        The supply's saturation temperature [K], the first cycle's cut-off temperature.
    exhaust_T_K : float
        The exhaust's saturation temperature [K], the first cycle's at compression.
    lp_events : dict, optional
        A compound's low-pressure valve events by end: its ends (``lp_head``,
        ``lp_crank``) take their rows from these and from the LP cylinder's geometry.

    Notes
    -----
    Each end's row is built from its own cylinder's geometry (``network.geometries``)
    and events, in that cylinder's own crank angle (the kernel adds the cylinder's
    phase), and its states at cut-off and compression are sampled at the shaft angles
    where that cylinder cuts off and compresses, so that each end gives back over a
    cycle what it takes.
    """

    #: The law's name, for the warning.
    name = ""

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
        self.t_compression = {i: exhaust_T_K for i, _ in self.ends}
        # the integrators restart where a window opens or shuts, as at the ports'
        # kinks: a switch inside a step is integrated to the step's error only, and
        # the heat taken and given back would not balance to round-off
        network.schedule_stops.extend(self.stops_rad())
        if self.ends:
            log.warning("wall_heat_model = \"%s\" imposes %s heat as a schedule, "
                        "whatever the steam's temperature: the heat given back after release "
                        "goes into the little steam left and can heat it beyond any wall's "
                        "temperature.  It is the period's rule, kept for comparison; "
                        "\"skin\" (the default) obeys the second law", self.name, self.what)

    #: What the law's heat is, for the warning.
    what = ""

    def stops_rad(self) -> list[float]:
        """The shaft angles where the schedule's windows open or shut.

        Returns
        -------
        list of float
            Each kept end's admission, cut-off and compression, as shaft angles in
            [0, 2 pi) [rad] (the cylinder's own angle less its phase).
        """
        out: list[float] = []
        for i, end in self.ends:
            _, ev, phase = self._end(i, end)
            out.extend((math.radians(ev[k]) - phase) % (2 * math.pi)
                       for k in ("admission_deg", "cutoff_deg", "compression_deg")
                       if ev[k] is not None)
        return out

    def set_events(self, events: dict) -> None:
        """Take the (first or high-pressure) gear's events at another setting.

        The rows (:meth:`rows`, :meth:`apply`) and the stops (:meth:`stops_rad`) then
        follow them; a compound's LP ends keep their own gear's.

        Parameters
        ----------
        events : dict
            Valve events by end (``"head"``, ``"crank"``), as :func:`schedule_row` reads.
        """
        self.events = events

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

    def heat_row(self, i: int, end: int, geometry, events: dict):
        """The law's row of node ``i`` (a subclass's).

        Parameters
        ----------
        i : int
            The node.
        end : int
            0 for the head end, 1 for the crank end.
        geometry : corliss.engine.geometry.CylinderGeometry
            The node's cylinder.
        events : dict
            The end's valve events.

        Returns
        -------
        tuple of float or None
            As :func:`schedule_row`.
        """
        raise NotImplementedError

    def rows(self) -> dict:
        """The rows for the current states at cut-off and compression.

        Returns
        -------
        dict
            Node index -> columns 5-10 of its wall-heat row (:func:`schedule_row`;
            zero heat for an end without cut-off or compression).
        """
        out = {}
        for i, end in self.ends:
            geo, ev, _ = self._end(i, end)
            row = self.heat_row(i, end, geo, ev)
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
        """Take the saturation temperatures at cut-off and compression from a cycle's
        samples.

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
        net = self.network
        # the samples' angles from the first (a turn of the speed loop may start at
        # any multiple of 2 pi)
        rel = out_theta - out_theta[0]
        for i, end in self.ends:
            _, ev, phase = self._end(i, end)
            for key, kept in (("cutoff_deg", self.t_cutoff),
                              ("compression_deg", self.t_compression)):
                if ev[key] is None:
                    continue
                # the shaft's angle of this cylinder's event (its own angle leads by
                # its phase), the state there interpolated between the samples either
                # side: the pressure falls steeply at cut-off, and English's heat, a
                # difference of two terms, moved 2 to 10 % with the nearest sample's
                th = (math.radians(ev[key]) - phase - out_theta[0]) % (2 * math.pi)
                k = min(max(int(np.searchsorted(rel, th)), 1), rel.size - 1)
                w = min(max((th - rel[k - 1]) / (rel[k] - rel[k - 1]), 0.0), 1.0)
                V = float(net.volume(i, np.array([th + out_theta[0]]))[0])
                m = (1.0 - w) * samples[2 * i, k - 1] + w * samples[2 * i, k]
                U = (1.0 - w) * samples[2 * i + 1, k - 1] + w * samples[2 * i + 1, k]
                if not (m > 0.0 and np.isfinite(U)):
                    continue
                # read as the run read it: Marks's heat given back into the thin
                # exhaust steam can lift it beyond the properties' greatest energy
                p_Pa, _, _ = visited_states(steam, np.array([m / V]), np.array([U / m]))
                p = float(p_Pa[0])
                kept[i] = self._heos.t_sat(min(p, 2.2e7))


class MarksLaw(ScheduledWallHeat):
    """Marks's law (eq. 221) as the schedule (:class:`ScheduledWallHeat`).

    Each cycle's heat uses the steam temperature at cut-off of the cycle before (at
    first, the supply's saturation temperature) and the exhaust's saturation
    temperature (Marks's T_b and T_e, Art. 75).

    Parameters
    ----------
    network : corliss.engine.network.Network
        The compiled network.
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    events : dict
        Valve events by end, as :func:`marks_law_row` reads.
    speed_rad_s : float
        Crank speed [rad/s].
    supply_T_K : float
        The supply's saturation temperature [K].
    exhaust_T_K : float
        The exhaust's saturation temperature [K].
    lp_events : dict, optional
        A compound's low-pressure valve events by end.
    """

    name = "marks"
    what = "eq. 221's"

    def heat_row(self, i: int, end: int, geometry, events: dict):
        """Marks's row of node ``i`` (:func:`marks_law_row`).

        Parameters
        ----------
        i : int
            The node.
        end : int
            0 for the head end, 1 for the crank end.
        geometry : corliss.engine.geometry.CylinderGeometry
            The node's cylinder.
        events : dict
            The end's valve events.

        Returns
        -------
        tuple of float or None
            As :func:`schedule_row`.
        """
        t = self.t_cutoff[i]
        return marks_law_row(geometry, end, events, self.strokes_per_s, t, self.t_exhaust,
                             self.latent(t))


class EnglishLaw(ScheduledWallHeat):
    """English's law (DPJ 267, 1888, p. 302) as the schedule (:class:`ScheduledWallHeat`).

    Each end's heat is :func:`english_law_row`'s, with ``gamma_1`` the density of
    saturated steam at the end's pressure at cut-off of the cycle before (the
    admission pressure, as the period read it off the card) and ``gamma_0`` at its
    pressure at compression (the back pressure "at the exhaust's closing", p. 302): a
    compound's HP ends exhaust into the receiver, its LP ends are admitted from it.
    ``n`` is the revolutions per second: each end, of a double-acting cylinder or a
    single-acting one, takes steam once a revolution (English's clearance trials took
    it at one end); a single-acting cylinder's idle end has no row.

    Parameters
    ----------
    network : corliss.engine.network.Network
        The compiled network.
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    events : dict
        Valve events by end, as :func:`english_law_row` reads.
    speed_rad_s : float
        Crank speed [rad/s].
    supply_T_K : float
        The supply's saturation temperature [K], the first cycle's at cut-off.
    exhaust_T_K : float
        The exhaust's saturation temperature [K], the first cycle's at compression.
    lp_events : dict, optional
        A compound's low-pressure valve events by end.
    jacketed : bool, optional
        A jacketed cylinder (English's 60; 80 without).
    """

    name = "english"
    what = "English's"

    def __init__(self, network, geometry, events: dict, speed_rad_s: float, supply_T_K: float,
                 exhaust_T_K: float, lp_events: dict | None = None, jacketed: bool = False):
        super().__init__(network, geometry, events, speed_rad_s, supply_T_K, exhaust_T_K,
                         lp_events)
        self.jacketed = jacketed

    def heat_row(self, i: int, end: int, geometry, events: dict):
        """English's row of node ``i`` (:func:`english_law_row`).

        Parameters
        ----------
        i : int
            The node.
        end : int
            0 for the head end, 1 for the crank end.
        geometry : corliss.engine.geometry.CylinderGeometry
            The node's cylinder.
        events : dict
            The end's valve events.

        Returns
        -------
        tuple of float or None
            As :func:`schedule_row`.
        """
        return english_law_row(geometry, end, events, 0.5 * self.strokes_per_s,
                               saturated_vapour_density(self.t_cutoff[i]),
                               saturated_vapour_density(self.t_compression[i]), self.jacketed)


#: The laws imposed as a schedule, by ``wall_heat_model``.
SCHEDULED_LAWS = {"marks": MarksLaw, "english": EnglishLaw}


def wall_schedule(scene, network, geometry, events: dict, speed_rad_s: float, supply_T_K: float,
                  exhaust_T_K: float, lp_events: dict | None = None):
    """The schedule that keeps a run's wall-heat rows, when its wall heat is a period law.

    Parameters
    ----------
    scene : corliss.scene.Scene
        The scene: ``run.effects`` and ``engine.wall_heat_model``, ``engine.jacket``.
    network : corliss.engine.network.Network
        The compiled network.
    geometry : corliss.engine.geometry.CylinderGeometry
        The cylinder.
    events : dict
        Valve events by end.
    speed_rad_s : float
        Crank speed [rad/s].
    supply_T_K : float
        The supply's saturation temperature [K].
    exhaust_T_K : float
        The exhaust's saturation temperature [K].
    lp_events : dict, optional
        A compound's low-pressure valve events by end.

    Returns
    -------
    ScheduledWallHeat or None
        :class:`MarksLaw` or :class:`EnglishLaw` (jacketed where the scene has a
        jacket); None without the ``wall_heat`` effect or with another wall model.
    """
    model = scene.engine.wall_heat_model
    if not scene.run.has("wall_heat") or model not in SCHEDULED_LAWS:
        return None
    if model == "english":
        return EnglishLaw(network, geometry, events, speed_rad_s, supply_T_K, exhaust_T_K,
                          lp_events, jacketed=scene.engine.jacket != "none")
    return MarksLaw(network, geometry, events, speed_rad_s, supply_T_K, exhaust_T_K, lp_events)
