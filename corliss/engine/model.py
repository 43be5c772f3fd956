"""The one place a scene becomes a model: geometry, valve gear, port map, reservoirs and
the network of control volumes holding only the effects the scene names.

Every runner (steady, transient, mean-value, sweep) builds what it needs here, so an
effect is assembled the same way whichever runner asks; tests import these pieces to
check one layer of the model at a time.
"""

from __future__ import annotations

import dataclasses
import logging
import math
from dataclasses import dataclass

from corliss.engine import wall
from corliss.engine.geometry import CylinderGeometry
from corliss.engine.leak_paths import edge_leak_scales
from corliss.engine.scene_specs import SceneSpec
from corliss.engine.network import (Network, compound, single_cylinder, with_leakage,
                                    with_period_leakage, with_steam_chest, with_wall_heat)
from corliss.engine.options import PRESETS
from corliss.errors import InputError
from corliss.thermo.steam import State, Steam, make_steam
from corliss.thermo.wall_properties import transport_properties
from corliss.valves import events as valve_events
from corliss.valves import gear_type, tabulate
from corliss.valves.gear import ValveGear
from corliss.valves.portmap import PortMap
from corliss.valves.single_acting import single_acting

log = logging.getLogger(__name__)


def geometry_of(scene) -> CylinderGeometry:
    """The cylinder's geometry; the rod's angularity only with ``rod_angularity``.

    Parameters
    ----------
    scene : Scene
        The scene.

    Returns
    -------
    CylinderGeometry
        The (first or high-pressure) cylinder: exact slider crank with the
        ``rod_angularity`` effect, an infinite rod without.
    """
    return CylinderGeometry(scene.engine, rod_angularity=scene.run.has("rod_angularity"))


def lp_geometry_of(scene) -> CylinderGeometry | None:
    """A compound's low-pressure cylinder geometry.

    Parameters
    ----------
    scene : Scene
        The scene.

    Returns
    -------
    CylinderGeometry or None
        The LP cylinder (rod angularity as for :func:`geometry_of`); None for a simple
        engine.
    """
    if scene.compound is None:
        return None
    return CylinderGeometry(scene.compound.lp_engine,
                            rod_angularity=scene.run.has("rod_angularity"))


def build_gear(scene):
    """The scene's valve gear, built from its registry entry.

    Parameters
    ----------
    scene : Scene
        The scene.

    Returns
    -------
    object
        The valve gear (:mod:`corliss.valves`), at the run's speed for gears whose
        motion depends on it (those with a ``with_speed``).
    """
    gear = single_acting(gear_type(scene.gear_type).build(scene.gear), scene.engine.steam_ends)
    return gear.with_speed(scene.run.speed_rad_s) if hasattr(gear, "with_speed") else gear


def build_lp_gear(scene):
    """A compound's low-pressure valve gear.

    Parameters
    ----------
    scene : Scene
        The scene.

    Returns
    -------
    object or None
        The LP cylinder's valve gear; None for a simple engine.
    """
    if scene.compound is None:
        return None
    return single_acting(gear_type(scene.compound.lp_gear_type).build(scene.compound.lp_gear),
                         scene.compound.lp_engine.steam_ends)


def scene_events(scene, settings: list[float] | None = None):
    """Valve events of both ends, without simulating.

    Parameters
    ----------
    scene : Scene
        The scene.
    settings : list of float, optional
        Values of the gear's setting (e.g. the block offset of a link motion).

    Returns
    -------
    dict or list of dict
        The events of each end (see :func:`corliss.valves.events.events`); with
        ``settings``, a list of ``{"setting": s, "head": {...}, "crank": {...}}``.

    Raises
    ------
    InputError
        ``settings`` for a gear without a setting, or a setting outside its range.
    """
    geo = geometry_of(scene)
    gear = build_gear(scene)

    def frac(t):
        return float(geo.fraction(t))

    if settings is None:
        return valve_events(gear, frac)
    if gear.setting_range is None:
        raise InputError("--settings", settings, f"no settings: the {gear.name} gear has none")
    lo, hi = gear.setting_range
    out = []
    for v in settings:
        if not lo <= v <= hi:
            raise InputError("--settings", v, f"settings from {lo} to {hi} ({gear.setting_name})")
        out.append({"setting": v, **valve_events(gear.with_setting(v), frac)})
    return out


def reservoir_states(scene, steam: Steam) -> tuple[State, State]:
    """The two reservoirs' states.

    Parameters
    ----------
    scene : Scene
        The scene: supply pressure and temperature (superheated) or dryness, and
        exhaust pressure.
    steam : Steam
        The property tier.

    Returns
    -------
    chest : State
        The supply steam at the chest.
    exhaust : State
        Dry saturated steam at back pressure.
    """
    s = scene.supply
    # the states are a function of the tier's own data (a table tier's table: the
    # same object for every run of a process, a stand-in's while one is put in) and of
    # the four numbers: a study's runs share their reservoirs, found once
    table = getattr(steam, "table", None)
    key = (type(steam), id(table), s.pressure_Pa, s.temperature_K, s.dryness,
           scene.exhaust.pressure_Pa)
    kept = _RESERVOIRS.get(key)
    if kept is not None and kept[0] is table:
        return kept[1]
    chest = (steam.pt(s.pressure_Pa, s.temperature_K) if s.temperature_K is not None
             else steam.px(s.pressure_Pa, s.dryness))
    states = (chest, steam.px(scene.exhaust.pressure_Pa, 1.0))
    if len(_RESERVOIRS) >= RESERVOIRS_KEPT:
        _RESERVOIRS.clear()
    _RESERVOIRS[key] = (table, states)
    return states


#: Reservoir states kept by :func:`reservoir_states` (the table they came from, kept
#: beside them so that its id stays its own), and how many.
_RESERVOIRS: dict = {}
RESERVOIRS_KEPT = 64


def build_network(scene, geo, pm, steam: Steam, chest: State, exhaust: State) -> Network:
    """The network of control volumes the scene's effects call for.

    One cylinder (or identical ones on ``engine.crank_angles``) or a compound with its
    receiver (which starts dry saturated at the geometric mean of supply and back
    pressure); then, as named, ``steam_chest``, ``leakage`` and ``wall_heat`` (a
    transient run takes the ``conductance`` wall in place of the ``skin``, with a
    warning).

    Parameters
    ----------
    scene : Scene
        The scene.
    geo : CylinderGeometry
        The (first or high-pressure) cylinder.
    pm : PortMap
        Its port areas against crank angle.
    steam : Steam
        The property tier.
    chest, exhaust : State
        The reservoirs (:func:`reservoir_states`).

    Returns
    -------
    Network
        A fresh network.
    """
    fid = scene.run.fidelity
    omega = scene.run.speed_rad_s
    if scene.compound is None:
        net = single_cylinder(geo, pm, chest, exhaust, omega,
                              crank_angles=scene.engine.crank_angles_rad)
    else:
        cp = scene.compound
        lp_pm = tabulate(build_lp_gear(scene), fid.portmap_points)
        # the receiver starts at the geometric mean of supply and back pressure
        rec = steam.px(math.sqrt(chest.p * exhaust.p), 1.0)
        net = compound(geo, pm, lp_geometry_of(scene), lp_pm, cp.lp_phase_rad,
                       cp.receiver_volume_m3, chest, exhaust, rec, omega)
    if scene.run.has("steam_chest"):
        net = with_steam_chest(net, scene.supply)
    if scene.run.has("leakage") and scene.engine.leakage_model == "period":
        eng = scene.engine
        scales = None
        if eng.steam_edge_leak_rate_kg_s_Pa or eng.exhaust_edge_leak_rate_kg_s_Pa:
            # each edge's share by its port's length and face's width, at the
            # scene's setting (corliss.engine.leak_paths); a governed transient run
            # sets the governed gear's turn by turn (transient.GovernedEdgeLeaks)
            gears = [build_gear(scene)] + ([build_lp_gear(scene)] if scene.compound else [])
            scales = [edge_leak_scales(g) for g in gears]
            scales += [scales[0]] * (len(net.geometries) - len(scales))
        net = with_period_leakage(
            net, eng.valve_leak_rate_kg_s_Pa, eng.piston_leak_rate_kg_s_Pa,
            eng.steam_edge_leak_rate_kg_s_Pa, eng.exhaust_edge_leak_rate_kg_s_Pa, scales,
            idle_ends={"both": (), "head": (1,), "crank": (0,)}[eng.steam_ends])
    elif scene.run.has("leakage"):
        net = with_leakage(net, scene.engine.valve_leakage_area_m2,
                           scene.engine.piston_leakage_area_m2)
    if scene.run.has("wall_heat"):
        eng = scene.engine
        jacket_T = None
        from corliss.thermo.steam import HEOSSteam
        heos = HEOSSteam()
        t_sat = heos.t_sat(scene.supply.pressure_Pa)
        if eng.jacket != "none":
            # each cylinder's jacket at its own steam's saturation (the scene's pressure,
            # or the supply's, the LP's its receiver's: wall.jacket_pressures_Pa)
            jacket_T = tuple(heos.t_sat(p) for p in wall.jacket_pressures_Pa(
                scene.supply.pressure_Pa, scene.exhaust.pressure_Pa, scene.compound is not None,
                eng.jacket_pressure_Pa, eng.lp_jacket_pressure_Pa))
        supply_T = scene.supply.temperature_K
        superheat = supply_T - t_sat if supply_T is not None else 0.0
        model = eng.wall_heat_model
        if model == "skin" and scene.run.mode == "transient":
            # the speed loop restarts every state past the nodes' each turn, which
            # would empty the skin's film: its walls are Marks's conductance
            log.warning("the speed loop runs wall_heat with the \"conductance\" wall; the "
                        "\"skin\" wall (surface temperature and film as states) is for "
                        "steady runs")
            model = "conductance"
        net = with_wall_heat(net, model, eng.marks_constant_W_m2K,
                             transport_properties(chest.p, chest.T),
                             condensing_W_m2K=eng.condensing_W_m2K, jacket_T_K=jacket_T,
                             wall_thickness_m=eng.wall_thickness_m,
                             idle_ends={"both": (), "head": (1,), "crank": (0,)}[eng.steam_ends],
                             supply_superheat_K=superheat,
                             jacket=eng.jacket if eng.jacket != "none" else "barrel")
    return net


@dataclass
class Model:
    """A scene assembled: what every runner starts from.

    Parameters
    ----------
    scene : Scene
        The scene assembled.
    steam : Steam
        The property tier of the scene's fidelity.
    chest, exhaust : State
        Supply steam at the chest; dry saturated steam at back pressure.
    geometry : CylinderGeometry
        The (first or high-pressure) cylinder.
    gear : ValveGear
        The valve gear (a registry entry built from the scene).
    portmap : PortMap or None
        Port areas against crank angle (None for the ideal card).
    events : dict
        Valve events of each end, found on the gear's own motion.
    lp_events : dict or None
        A compound's low-pressure valve events.
    """

    scene: SceneSpec
    steam: Steam
    chest: State
    exhaust: State
    geometry: CylinderGeometry
    gear: ValveGear
    portmap: PortMap | None
    events: dict
    lp_events: dict | None = None

    def network(self, portmap=None) -> Network:
        """A fresh network of the scene's control volumes (:func:`build_network`).

        Parameters
        ----------
        portmap : PortMap, optional
            Port areas to build it on (default: the model's).

        Returns
        -------
        Network
            The network.
        """
        return build_network(self.scene, self.geometry, portmap or self.portmap, self.steam,
                             self.chest, self.exhaust)


#: How many port maps :func:`_tabulated` keeps (a study's runs share one where its
#: gear's keys are not varied; a few, so that alternating scenes share theirs too).
PORTMAPS_KEPT = 8
_portmaps: dict = {}


def _tabulated(scene, gear, n: int):
    """:func:`~corliss.valves.portmap.tabulate` of the scene's gear on ``n`` intervals,
    kept for the next run of a gear built from the same keys (a study's runs that vary
    no key of the gear: the same map, found once instead of every run).

    The gear is a function of the scene's gear type and table, its steam ends and, for
    a gear whose motion depends on it, the run's speed (:func:`build_gear`): those are
    the key.  A table that cannot be hashed is tabulated each time.  The map is shared:
    nothing changes one in place (:meth:`PortMap.scaled` makes a new one).
    """
    speed = scene.run.speed_rad_s if hasattr(gear, "with_speed") else None
    key = (scene.gear_type, scene.gear, scene.engine.steam_ends, speed, n)
    try:
        pm = _portmaps.get(key)
    except TypeError:              # a gear table with an unhashable value
        return tabulate(gear, n)
    if pm is None:
        pm = tabulate(gear, n)
        while _portmaps and len(_portmaps) >= PORTMAPS_KEPT:
            _portmaps.pop(next(iter(_portmaps)))
        if PORTMAPS_KEPT > 0:
            _portmaps[key] = pm
    return pm


def assemble(scene, *, tabulated: bool = True) -> Model:
    """Build the model of a scene.

    Parameters
    ----------
    scene : Scene
        The scene.
    tabulated : bool
        Whether to tabulate the gear's port areas (a PortMap at the fidelity's
        ``portmap_points``); the ideal card needs none.

    Returns
    -------
    Model
        Property tier, reservoirs, geometry, gear, port map (or None) and the valve
        events found on the gear's motion (at the port map's crossings when
        tabulated).
    """
    fid = scene.run.fidelity
    steam = make_steam(fid.properties)
    chest, exhaust = reservoir_states(scene, steam)
    geo = geometry_of(scene)
    gear = build_gear(scene)
    pm = _tabulated(scene, gear, fid.portmap_points) if tabulated else None
    ev = valve_events(gear, lambda t: float(geo.fraction(t)), pm.crossings if pm else None,
                      pm.signed_samples if pm else None, geo.fraction)
    lp_events = None
    if scene.compound is not None:
        lp_geo = lp_geometry_of(scene)
        assert lp_geo is not None       # a compound has its low-pressure cylinder
        lp_events = valve_events(build_lp_gear(scene), lambda t: float(lp_geo.fraction(t)))
    return Model(scene, steam, chest, exhaust, geo, gear, pm, ev, lp_events)


# --- scenes derived for studies across the load range -----------------------------------

KNOBS = ("setting", "throttle")


def steady_scene(scene, fidelity: str | None = None):
    """The scene as a steady run: no flywheel, load or governor, speed held.

    Parameters
    ----------
    scene : Scene
        The scene.
    fidelity : str, optional
        A preset of :data:`corliss.engine.options.PRESETS` to set as well (the copy
        :meth:`Scene.with_fidelity` would make, made steady, in one copy: a study
        makes one a run).

    Returns
    -------
    Scene
        A copy with ``run.mode = "steady"`` and no duration, flywheel, load or
        governor.

    Raises
    ------
    InputError
        A fidelity that is not a preset.
    """
    changes: dict = {"mode": "steady", "duration_s": None}
    if fidelity is not None:
        if fidelity not in PRESETS:
            raise InputError("run.fidelity", fidelity, "one of " + ", ".join(PRESETS))
        changes["fidelity"] = PRESETS[fidelity]
    run = _replaced(scene.run, changes)
    return _replaced(scene, {"run": run, "governor": None, "governor_type": None,
                             "flywheel": None, "load": None})


#: The field names of each dataclass :func:`_replaced` may copy (empty: one it may not).
_PLAIN_FIELDS: dict = {}


def _replaced(spec, changes: dict):
    """``dataclasses.replace(spec, **changes)`` for a frozen dataclass that neither
    checks nor derives anything as it is made (no ``__post_init__``, every field set by
    ``__init__``: a scene, a run spec), made without its ``__init__``: an equal object,
    made in a fraction of the time (a study makes two a run)."""
    names = _PLAIN_FIELDS.get(type(spec))
    if names is None:
        fields = dataclasses.fields(spec)
        plain = (not hasattr(spec, "__post_init__") and hasattr(spec, "__dict__")
                 and all(f.init for f in fields))
        names = _PLAIN_FIELDS[type(spec)] = (frozenset(f.name for f in fields) if plain
                                             else frozenset())
    if not names or not names.issuperset(changes):
        return dataclasses.replace(spec, **changes)
    # a new object holding the fields' values (and nothing else the old one held), the
    # changed ones set
    out = object.__new__(type(spec))
    out.__dict__.update({k: v for k, v in spec.__dict__.items() if k in names})
    out.__dict__.update(changes)
    return out


def at_knob(scene, knob: str, value: float):
    """The steady scene with the gear's setting, or the throttle's opening, at ``value``.

    Parameters
    ----------
    scene : Scene
        The scene (made steady by :func:`steady_scene`).
    knob : str
        ``"setting"`` (the gear's setting) or ``"throttle"`` (opening, 0..1).
    value : float
        The setting [-] or the opening [-].

    Returns
    -------
    Scene
        The steady scene with the knob at ``value``.

    Raises
    ------
    InputError
        A setting for a gear without one or outside its range; a throttle without the
        ``steam_chest`` effect and a pipe, or an opening outside (0, 1].
    ValueError
        A knob not in :data:`KNOBS`.
    """
    sc = steady_scene(scene)
    if knob == "setting":
        gear = build_gear(sc)
        if gear.setting_range is None:
            raise InputError("--settings", value, f"a gear with a setting; the "
                             f"{scene.gear_type} gear has none (sweep --throttle instead)")
        lo, hi = gear.setting_range
        if not lo <= value <= hi:
            raise InputError("--settings", value, f"settings from {lo} to {hi} "
                             f"({gear.setting_name})")
        return dataclasses.replace(sc, gear=gear.with_setting(value).spec)
    if knob == "throttle":
        if not sc.run.has("steam_chest") or sc.supply.pipe_diameter_m is None:
            raise InputError("--throttle", value, "a scene with the \"steam_chest\" effect and "
                             "supply.pipe_diameter: the throttle is in the steam pipe")
        if not 0.0 < value <= 1.0:
            raise InputError("--throttle", value, "openings above 0, up to 1 (wide open)")
        return dataclasses.replace(sc, supply=dataclasses.replace(sc.supply, throttle=value))
    raise ValueError(f"knob {knob!r}: one of {KNOBS}")
