"""A TOML scene into frozen, validated specs in SI.

Every dimensional value is a quantity string with its unit; unknown keys, missing
units and impossible geometry are :class:`~corliss.errors.InputError` naming the key,
the value and what would be valid, raised before any work starts.  The format is
described in ``docs/scenes.md`` and ``docs/scene-reference.md`` and shown by
``scenes/default.toml``.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from corliss.keys import limits, units
from corliss.engine.flywheel import FlywheelSpec, parse_flywheel
from corliss.engine.geometry import EngineSpec
from corliss.engine.load import LoadSpec, parse_load
from corliss.engine.options import (COMPILED_METHODS, EFFECT_KEYS, EFFECTS, PLANNED_EFFECTS,
                                    PRESETS, SCIPY_METHODS)
from corliss.engine.output_size import check_output_samples
from corliss.engine.scene_specs import (CompoundSpec, ExhaustSpec, RunSpec,
                                       SupplySpec)
from corliss.errors import InputError, InputErrors
from corliss.keys.declared import REQUIRED
from corliss.scene.sections import (COMPARE, COMPOUND, ENGINE, EXHAUST, FLYWHEEL, LOAD, OUTPUT,
                                  RECORD_CHOICES, RUN, START_CHOICES, SUPPLY)  # noqa: F401
from corliss.keys.toml_table import Table
from corliss.keys.textfiles import read_text
from corliss.thermo import steam_table
from corliss.thermo.steam import BACKENDS, HEOSSteam, TableSteam
from corliss.valves import GEARS

log = logging.getLogger(__name__)

SECTIONS = ("title", "engine", "supply", "exhaust", "valve_gear", "run", "output", "compound",
            "lp_valve_gear", "governor", "flywheel", "load", "compare")


@dataclass(frozen=True)
class OutputSpec:
    """Where and how results are written.

    Parameters
    ----------
    units : str
        ``"US"`` or ``"SI"`` in CSV and plots.
    dir : str
        Output directory, relative to the working directory.
    """

    units: str
    dir: str


@dataclass(frozen=True)
class CompareSpec:
    """The ``[compare]`` section: how `corliss compare` governs the engine both ways
    (every field None: the study's default, see :mod:`corliss.studies.compare`).

    Parameters
    ----------
    throttled_setting : float or None
        The gear setting the throttled variant keeps [-].
    setting_range : (float, float) or None
        The settings the cut-off governor may use [-].
    chest_volume_m3, pipe_diameter_m : float or None
        Steam chest [m3] and pipe [m] of both variants, when the scene's [supply] has none.
    """

    throttled_setting: float | None = None
    setting_range: tuple[float, float] | None = None
    chest_volume_m3: float | None = None
    pipe_diameter_m: float | None = None


def _compare(t: Table, swept_m3: float, gear) -> CompareSpec:
    lo, hi = gear.setting_range or (None, None)
    fixed = rng = None
    if t.has("throttled_setting"):
        if lo is None:
            raise InputError(t.key("throttled_setting"), t.raw("throttled_setting"),
                             "no setting: the gear has none")
        fixed = t.get("throttled_setting", None, within=(lo, hi))
    if t.has("setting_range"):
        raw = t.raw("setting_range")
        ok = (lo is not None and isinstance(raw, list) and len(raw) == 2
              and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in raw)
              and lo <= min(raw) < max(raw) <= hi)
        if not ok:
            raise InputError(t.key("setting_range"), raw,
                             f"[least, greatest] settings within the gear's {lo} to {hi}")
        rng = (float(min(raw)), float(max(raw)))
    chest = _vessel(t, "chest_volume", swept_m3, "a cylinder") if t.has("chest_volume") else None
    pipe = t.get("pipe_diameter", None)
    t.finish()
    return CompareSpec(fixed, rng, chest, pipe)


@dataclass(frozen=True)
class Scene:
    """A validated scene, all SI.  Build it with :func:`load_scene`.

    Parameters
    ----------
    title : str
        The scene's title.
    engine : EngineSpec
        The cylinder(s).
    supply, exhaust : SupplySpec, ExhaustSpec
        Steam in and out.
    gear_type : str
        The valve gear's registry name.
    gear : object
        Its spec.
    run, output : RunSpec, OutputSpec
        What to simulate; where results go.
    name : str
        The scene's name (its file's stem).
    source : str or None
        Its file's path.
    compound : CompoundSpec or None
        The LP cylinder of a compound.
    governor_type : str or None
        The governor's registry name.
    governor : object or None
        Its spec.
    flywheel, load : FlywheelSpec or None, LoadSpec or None
        A transient run's flywheel and load specs.
    compare : CompareSpec or None
        The ``[compare]`` section.
    data : dict or None
        The scene's tables as read.
    text : str or None
        The scene file's text.
    """

    title: str
    engine: EngineSpec
    supply: SupplySpec
    exhaust: ExhaustSpec
    gear_type: str
    gear: object
    run: RunSpec
    output: OutputSpec
    name: str = "scene"
    source: str | None = None
    compound: CompoundSpec | None = None
    governor_type: str | None = None
    governor: object | None = None
    flywheel: FlywheelSpec | None = None
    load: LoadSpec | None = None
    compare: CompareSpec | None = None
    #: The scene's tables as read (TOML or a dict), to rebuild it exactly.
    data: dict | None = dataclasses.field(default=None, compare=False, repr=False)
    #: The scene file's text, when it was read from a file.
    text: str | None = dataclasses.field(default=None, compare=False, repr=False)

    def resolved(self) -> dict:
        """The scene as resolved SI values (for result metadata).

        Returns
        -------
        dict
            Its fields, nested, without the raw tables and text.
        """
        out = dataclasses.asdict(self)
        for raw in ("data", "text"):
            out.pop(raw)
        return out

    def replace_run(self, **changes) -> "Scene":
        """A copy with fields of ``run`` changed (e.g. ``cycles=3``).

        Parameters
        ----------
        **changes
            Fields of :class:`RunSpec` and their new values.

        Returns
        -------
        Scene
            The copy.
        """
        return dataclasses.replace(self, run=dataclasses.replace(self.run, **changes))

    def with_fidelity(self, name: str) -> "Scene":
        """A copy at another fidelity preset.

        Parameters
        ----------
        name : str
            A preset of :data:`corliss.engine.options.PRESETS`.

        Returns
        -------
        Scene
            The copy.
        """
        if name not in PRESETS:
            raise InputError("run.fidelity", name, "one of " + ", ".join(PRESETS))
        return self.replace_run(fidelity=PRESETS[name])


#: Clearance [fraction of the end's swept volume]: from half a percent (a uniflow
#: engine has one or two; zero makes the compression pressure infinite, and a
#: hundred-billionth drove the steam out of its properties) to half the swept volume.
CLEARANCE_RANGE = (0.005, 0.5)
#: The least steam chest or receiver, as a fraction of the swept volume of the cylinder
#: it feeds: a smaller vessel empties in a small part of a stroke and the run grows stiff
#: beyond any engine (a receiver of 0.2 % of the HP cylinder ran for minutes over two
#: cycles; a chest of 0.6 % was drawn below the steam properties).
VESSEL_LEAST_OF_SWEPT = 0.05


def _pair_fraction(t: Table, key: str) -> tuple[float, float]:
    raw = t.raw(key)
    vals = raw if isinstance(raw, list) else [raw, raw]
    if len(vals) != 2 or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in vals):
        raise InputError(t.key(key), raw, "a fraction of the swept volume, or [head, crank]")
    lo, hi = CLEARANCE_RANGE
    for v in vals:
        if not lo <= v <= hi:
            raise InputError(t.key(key), raw, f"a clearance fraction between 0 and 1, from "
                             f"{lo:g} to {hi:g} of the swept volume (zero clearance makes "
                             "compression pressure infinite)")
    return (float(vals[0]), float(vals[1]))


def _vessel(t: Table, key: str, swept_m3: float, what: str) -> float:
    """A steam chest's or receiver's volume [m3], at least
    :data:`VESSEL_LEAST_OF_SWEPT` of the swept volume of the cylinder it feeds."""
    v = t.get(key, REQUIRED)
    least = VESSEL_LEAST_OF_SWEPT * swept_m3
    if not v >= least:
        raise InputError(t.key(key), t.raw(key), f"a volume of at least "
                         f"{VESSEL_LEAST_OF_SWEPT:g} of the swept volume of {what} "
                         f"({least:.3g} m3, {least / units.FOOT_m ** 3:.3g} ft3): a smaller "
                         "one empties within a small part of a stroke")
    return v


def _engine(t: Table) -> EngineSpec:
    # from a model's half-inch cylinder to the largest engines built (about 5 m of stroke)
    bore = t.get("bore")
    stroke = t.get("stroke")
    rod = t.get("connecting_rod")
    if rod <= stroke / 2.0:
        raise InputError(t.key("connecting_rod"), t.raw("connecting_rod"),
                         f"a connecting rod longer than the crank (half the stroke, "
                         f"{stroke / 2 / units.INCH_m:.4g} in)")
    prd = t.get("piston_rod_diameter")
    if not 0.0 <= prd < bore:
        raise InputError(t.key("piston_rod_diameter"), t.raw("piston_rod_diameter"),
                         "a piston rod diameter from zero up to less than the bore")
    mass = t.get("reciprocating_mass")
    if mass is not None and not mass > 0.0:
        raise InputError(t.key("reciprocating_mass"), t.raw("reciprocating_mass"),
                         "a mass greater than zero")
    f0 = t.get("friction_torque")
    f1 = t.get("friction_torque_per_speed")
    if f0 < 0.0 or f1 < 0.0:
        raise InputError(t.key("friction_torque"), t.raw("friction_torque", None),
                         "friction torques of zero or more (they oppose the motion)")
    leaks = []
    for k in ("valve_leakage_area", "piston_leakage_area"):
        a = t.get(k)
        if a < 0.0 or a > 0.05 * math.pi / 4 * bore ** 2:
            raise InputError(t.key(k), t.raw(k), "an equivalent leak area from zero to 5 % of "
                             "the piston area")
        leaks.append(a)
    n_cyl = t.get("cylinders")
    angles = t.get("crank_angles", [f"{360.0 * k / n_cyl} deg" for k in range(n_cyl)]
                   if n_cyl != 2 else ["0 deg", "90 deg"])
    if not isinstance(angles, list) or len(angles) != n_cyl:
        raise InputError(t.key("crank_angles"), angles, f"a list of {n_cyl} crank angles, the "
                         "first \"0 deg\" (how far each crank follows the first)")
    crank_angles = tuple(units.parse(a, "angle", t.key("crank_angles")) for a in angles)
    if abs(crank_angles[0]) > 1e-12:
        raise InputError(t.key("crank_angles"), angles, "a list whose first angle is \"0 deg\"")
    model = t.get("wall_heat_model")
    marks = t.get("marks_constant")
    if not marks > 0.0:
        raise InputError(t.key("marks_constant"), t.raw("marks_constant"), "a conductance above 0")
    condensing = None     # "marks": set by Marks's eq. 221 (corliss.engine.calibration)
    if t.raw("condensing_coefficient", None) != "marks":
        condensing = t.get("condensing_coefficient")
        if not condensing > 0.0:
            raise InputError(t.key("condensing_coefficient"), t.raw("condensing_coefficient"),
                             "a coefficient above 0, or \"marks\"")
    jacket = t.get("jacket")
    jacket_pressures = tuple(t.get(k) for k in ("jacket_pressure", "lp_jacket_pressure"))
    for k, p in zip(("jacket_pressure", "lp_jacket_pressure"), jacket_pressures):
        if p is not None and jacket == "none":
            raise InputError(t.key(k), t.raw(k), "no value without a jacket: set engine.jacket "
                             "to \"barrel\", \"covers\" or \"barrel_and_covers\"")
    thickness = t.get("wall_thickness", within=(1e-3, 0.5 * bore))
    leak_model = t.get("leakage_model")
    rates = [t.get(k) for k in ("valve_leak_rate", "piston_leak_rate",
                                "steam_edge_leak_rate", "exhaust_edge_leak_rate")]
    valve_leak, piston_leak = leaks
    spec = EngineSpec(bore, stroke, rod, prd, _pair_fraction(t, "clearance"), mass, f0, f1,
                      valve_leak, piston_leak, model, marks, crank_angles, condensing, jacket, thickness,
                      t.get("steam_ends"), leak_model, *rates, *jacket_pressures)
    t.finish()
    return spec


def _check_jacket_pressures(data: dict, engine: EngineSpec, supply, exhaust,
                            compound: bool) -> None:
    """Refuse a jacket's steam pressure above the supply's or below the exhaust's (a
    jacket is fed from the boiler's main or a receiver, and drains against at least
    the exhaust), and ``lp_jacket_pressure`` on an engine without a low-pressure
    cylinder.

    Parameters
    ----------
    data : dict
        The scene's TOML tables (for the values as written).
    engine : EngineSpec
        The engine, its jacket pressures read.
    supply : SupplySpec
        The supply.
    exhaust : ExhaustSpec
        The exhaust.
    compound : bool
        Whether the scene is a compound.

    Returns
    -------
    None
    """
    raw = data.get("engine", {})
    lo, hi = exhaust.pressure_Pa, supply.pressure_Pa
    for k, p in (("jacket_pressure", engine.jacket_pressure_Pa),
                 ("lp_jacket_pressure", engine.lp_jacket_pressure_Pa)):
        if p is None:
            continue
        if k == "lp_jacket_pressure" and not compound:
            raise InputError(f"engine.{k}", raw.get(k), "no value: only a compound has a "
                             "low-pressure cylinder (engine.jacket_pressure sets this one's)")
        if not lo <= p <= hi:
            raise InputError(f"engine.{k}", raw.get(k), f"a pressure from the exhaust's "
                             f"{lo / units.PSI_Pa:.4g} psia up to the supply's "
                             f"{hi / units.PSI_Pa:.4g} psia")


def _registered(t: Table, registry):
    """The entry of ``registry`` (valve gears or governors) that the table's ``type``
    names; a value that is not the name of one (another type, a list, a table) is
    refused naming this table's key."""
    raw = t.raw("type")
    if not isinstance(raw, str) or raw not in registry:
        raise InputError(t.key("type"), raw, f"a {registry.noun} from the registry: "
                         + ", ".join(sorted(registry)))
    return registry[raw]


def _compound(t: Table, hp: EngineSpec, lp_gear_data, hp_gear_type, hp_gear,
              barometer: float) -> CompoundSpec:
    """The [compound] section: LP cylinder, its crank, the receiver; [lp_valve_gear] or,
    without it, the HP's gear with its port lengths scaled to the LP bore."""
    bore = t.get("lp_bore")
    stroke = t.get("lp_stroke", f"{hp.stroke_m} m")
    rod = t.get("lp_connecting_rod", f"{hp.connecting_rod_m} m")
    if rod <= stroke / 2.0:
        raise InputError(t.key("lp_connecting_rod"), t.raw("lp_connecting_rod", None),
                         "a connecting rod longer than the LP crank")
    prd = t.get("lp_piston_rod_diameter", f"{hp.piston_rod_diameter_m} m")
    if not prd < bore:
        raise InputError(t.key("lp_piston_rod_diameter"),
                         t.raw("lp_piston_rod_diameter", f"{hp.piston_rod_diameter_m} m"),
                         f"an LP piston rod diameter less than the LP bore "
                         f"({bore / units.INCH_m:.4g} in)")
    clearance = _pair_fraction(t, "lp_clearance") if t.has("lp_clearance") else hp.clearance
    lp = dataclasses.replace(hp, bore_m=bore, stroke_m=stroke, connecting_rod_m=rod,
                             piston_rod_diameter_m=prd, clearance=clearance,
                             valve_leakage_area_m2=0.0, piston_leakage_area_m2=0.0,
                             crank_angles_rad=(0.0,))
    follows = t.get("lp_crank_angle")
    receiver = _vessel(t, "receiver_volume", math.pi / 4.0 * hp.bore_m ** 2 * hp.stroke_m,
                       "the HP cylinder")
    t.finish()
    if lp_gear_data is not None:
        vg = Table(lp_gear_data, "lp_valve_gear", barometer)
        gt = _registered(vg, GEARS)
        vg.bind(gt.keys)
        lp_gear = gt.parse(vg)
        vg.finish({n: e.keys for n, e in GEARS.items()})
        name = gt.name
    else:
        name = hp_gear_type.name
        lp_gear = dataclasses.replace(hp_gear, port_length_m=hp_gear.port_length_m * bore / hp.bore_m)
    return CompoundSpec(lp, name, lp_gear, -follows, receiver)


#: The reservoir states :func:`_check_states` found inside the properties' range (a
#: study's runs share their supply and exhaust: checked once, not once a run).
_STATES_PASSED: set = set()
#: How many it keeps.
STATES_KEPT = 256


def _check_states(data: dict, supply: SupplySpec, exhaust: ExhaustSpec, run: RunSpec) -> None:
    """Supply and exhaust steam inside the range of the steam properties the run uses,
    before any work: below the critical pressure (IAPWS: 22.064 MPa; no steam and
    water apart above it), and for the ``table`` tier inside the table's density and
    energy, with room for the exhaust steam to expand a little below back pressure.
    States that passed are kept, and pass again without a look (a refusal is found
    again each time, to name the key as written); states that passed on the built
    table pass without a look at the disk (a study's every run: its file is not asked
    for again), those that passed on the stand-in are looked at again once the table
    is built."""
    key = (supply.pressure_Pa, supply.temperature_K, supply.dryness, exhaust.pressure_Pa,
           run.fidelity.properties)
    if (key, True) in _STATES_PASSED:
        return
    built = steam_table.table_path().is_file()
    if (key, built) in _STATES_PASSED:
        return
    _check_states_once(data, supply, exhaust, run)
    if len(_STATES_PASSED) >= STATES_KEPT:
        _STATES_PASSED.clear()
    _STATES_PASSED.add((key, built))


def _check_states_once(data: dict, supply: SupplySpec, exhaust: ExhaustSpec,
                       run: RunSpec) -> None:
    """:func:`_check_states`, looked at."""
    raw_p = data["supply"].get("pressure")
    if supply.pressure_Pa >= units.CRITICAL_PRESSURE_Pa:
        raise InputError("supply.pressure", raw_p, "a pressure below the critical pressure of "
                         "water, 22.064 MPa (3200 psia): above it there is no saturated steam")
    if exhaust.pressure_Pa >= units.CRITICAL_PRESSURE_Pa:
        raise InputError("exhaust.pressure", data["exhaust"].get("pressure"),
                         "a pressure below the critical pressure of water, 22.064 MPa")
    if run.fidelity.properties != "table":
        return
    # the table's own states (CoolProp only for a state off its arrays); before the table
    # is built (a machine's first run, which builds it beside the compilation:
    # corliss.engine.first_run), the shipped miniature table's, whose ranges are the same
    if steam_table.table_path().is_file():
        steam = TableSteam()
    else:
        with steam_table.stand_in(steam_table.mini_table()):
            steam = TableSteam()
    chest = (steam.pt(supply.pressure_Pa, supply.temperature_K) if supply.temperature_K
             else steam.px(supply.pressure_Pa, supply.dryness))
    if not steam_table.covers(chest.rho, chest.u):
        key = ("supply.dryness" if supply.dryness < 1.0 else
               "supply.temperature" if chest.u > steam_table.PARAMS["u_max"] else
               "supply.pressure")
        raise InputError(key, data["supply"].get(key.split(".")[1], raw_p),
                         f"supply steam the \"table\" property tier covers (density "
                         f"{steam_table.PARAMS['rho_min']:g} to {steam_table.PARAMS['rho_max']:g} "
                         f"kg/m3, internal energy {steam_table.PARAMS['u_min'] / 1e6:g} to "
                         f"{steam_table.PARAMS['u_max'] / 1e6:g} MJ/kg; this steam is "
                         f"{chest.rho:.3g} kg/m3, {chest.u / 1e6:.3g} MJ/kg), or "
                         f"run.properties = \"heos\"")
    # the exhaust steam expands below back pressure in the cylinder: a fifth of its
    # density in hand
    ex = steam.px(exhaust.pressure_Pa, 1.0)
    if ex.rho < 1.2 * steam_table.PARAMS["rho_min"]:
        raise InputError("exhaust.pressure", data["exhaust"].get("pressure"),
                         f"an exhaust the \"table\" property tier covers: dry steam at back "
                         f"pressure of at least {1.2 * steam_table.PARAMS['rho_min']:g} kg/m3 "
                         f"(this is {ex.rho:.3g} kg/m3), or run.properties = \"heos\"")


def _supply(t: Table, swept_m3: float) -> SupplySpec:
    """The [supply] table; ``swept_m3``: one cylinder's swept volume (the least chest)."""
    p = t.get("pressure")
    temp_raw = t.raw("temperature")
    dryness = 1.0
    temperature = None
    if t.has("dryness"):
        dryness = t.get("dryness")
        if not 0.0 < dryness <= 1.0:
            raise InputError(t.key("dryness"), dryness, "a dryness fraction in (0, 1]")
        if temp_raw != "saturated":
            raise InputError(t.key("dryness"), dryness,
                             "dryness only with saturated (wet) steam, not with a temperature")
    if temp_raw != "saturated":
        temperature = t.get("temperature")
        if p >= 22.064e6:
            raise InputError(t.key("pressure"), t.raw("pressure"), "a subcritical pressure")
        t_sat = HEOSSteam().t_sat(p)
        if temperature < t_sat - 1e-6:
            raise InputError(t.key("temperature"), temp_raw,
                             f"\"saturated\" or a temperature at or above saturation "
                             f"({t_sat - 273.15:.1f} degC at this pressure)")
        if temperature - t_sat < 1e-3:
            temperature = None
    chest = (_vessel(t, "chest_volume", swept_m3, "a cylinder") if t.has("chest_volume")
             else None)
    pipe = t.get("pipe_diameter")
    cd = t.get("pipe_discharge_coefficient")
    throttle = t.get("throttle")
    if not 0.0 < throttle <= 1.0:
        raise InputError(t.key("throttle"), throttle,
                         "an opening above 0 (shut) and up to 1 (wide open)")
    law = t.get("throttle_law")
    t.finish()
    return SupplySpec(p, temperature, dryness, t.barometer_Pa, chest, pipe, cd, throttle, law)


def _swept_of(engine: EngineSpec) -> float:
    """One cylinder's swept volume [m3], as the loader finds it for the supply's checks."""
    return math.pi / 4.0 * engine.bore_m ** 2 * engine.stroke_m


#: The sections whose specs :func:`scene_from_dict` may take from a scene ``like``.
_REUSABLE = ("supply", "engine", "exhaust", "valve_gear", "run", "output")


def _shared_sections(data: dict, like: Scene | None) -> set:
    """The sections of :data:`_REUSABLE` whose table ``data`` shares with ``like``'s
    (the same object); none without ``like`` or when ``like`` was not loaded from
    tables."""
    if like is None or like.data is None:
        return set()
    return {k for k in _REUSABLE
            if k in data and k in like.data and data[k] is like.data[k]}


def _run(t: Table) -> RunSpec:
    mode = t.get("mode")
    model = t.get("model")
    # a tenth of a turn a minute (a museum engine turned over slowly) to 5000 rpm
    speed = t.get("speed")
    effects = t.get("effects")
    if not isinstance(effects, list) or not all(isinstance(e, str) for e in effects):
        raise InputError(t.key("effects"), effects, "a list of effect names")
    for e in effects:
        if e in PLANNED_EFFECTS:
            raise InputError(t.key("effects"), e, "an effect this version has ("
                             + ", ".join(EFFECTS) + f"); {e!r} is planned but not built yet")
        if e not in EFFECTS:
            raise InputError(t.key("effects"), e, "one of " + ", ".join(EFFECTS))
    preset = t.get("fidelity")
    fid = PRESETS[preset]
    changes = {}
    if t.has("properties"):
        changes["properties"] = t.get("properties", None)
    if t.has("method"):
        changes["method"] = t.get("method", None)
        changes["transient_method"] = None    # the transient loop's too
    if t.has("rtol"):
        changes["rtol"] = t.get("rtol", None)
    if t.has("convergence_tolerance"):
        changes["convergence_tolerance"] = t.get("convergence_tolerance", None)
        if not 0.0 < changes["convergence_tolerance"] < 0.5:
            raise InputError(t.key("convergence_tolerance"), changes["convergence_tolerance"],
                             "a fraction between 0 and 0.5")
    if t.has("max_cycles"):
        changes["max_cycles"] = t.get("max_cycles", None)
    if t.has("step"):
        changes["step_deg"] = math.degrees(t.get("step", None))
        if not 0.01 <= changes["step_deg"] <= 10.0:
            raise InputError(t.key("step"), t.raw("step"), "a crank-angle step from 0.01 to 10 deg")
    if t.has("portmap_points"):
        changes["portmap_points"] = t.get("portmap_points", None)
    if changes:
        fid = dataclasses.replace(fid, name="custom", **changes)
    if fid.method in COMPILED_METHODS and BACKENDS[fid.properties].kernel_tier is None:
        raise InputError(t.key("method"), fid.method,
                         f"a scipy method ({', '.join(SCIPY_METHODS)}) with properties = "
                         f"{fid.properties!r}, or properties = \"table\" or \"perfect\" for the "
                         "compiled integrators")
    cycles = None
    if t.has("cycles"):
        cycles = t.integer("cycles")
        if cycles < 1:
            raise InputError(t.key("cycles"), cycles, "a whole number of cycles >= 1")
    expansion = t.get("expansion")
    if model == "mean_value" and mode != "transient":
        raise InputError(t.key("model"), model, "\"crank_resolved\" or \"ideal\" in a steady "
                         "run: the mean-value model steps a transient turn by turn")
    duration = None
    if mode == "transient":
        duration = t.get("duration", REQUIRED)
        if not 0.0 < duration <= limits.MAX_DURATION_S:
            raise InputError(t.key("duration"), t.raw("duration"), "a time above 0, up to 1 h")
        if cycles is not None:
            raise InputError(t.key("cycles"), cycles, "no cycles in a transient run: give "
                             "run.duration")
    elif t.has("duration"):
        raise InputError(t.key("duration"), t.raw("duration"), "no duration in a steady run "
                         "(it runs until periodic, or run.cycles); or mode = \"transient\"")
    record = t.get("record", None)
    if record == "step" and mode != "transient":
        raise InputError(t.key("record"), record, "\"degree\" (every cycle at every output "
                         "step) or \"cycle\" (each cycle once, the last at every output step) "
                         "in a steady run: \"step\" records a transient's integrator steps")
    band = t.get("settling_band")
    if not 0.0 < band < 0.5:
        raise InputError(t.key("settling_band"), band, "a fraction of the speed between 0 and 0.5")
    warm = t.get("warmup_cycles")
    start = t.get("start")
    start_angle = 0.0
    if start == "rest" or t.has("start_angle"):
        if start != "rest" or mode != "transient":
            raise InputError(t.key("start_angle"), t.raw("start_angle", None), "no start_angle "
                             "unless start = \"rest\" in a transient run")
        start_angle = t.get("start_angle", REQUIRED) % (2.0 * math.pi)
        if model == "mean_value":
            raise InputError(t.key("start"), start, "\"equilibrium\" or \"run_speed\" with "
                             "the mean-value model: its maps hold running speeds only")
    until = t.raw("until_settled")
    if not isinstance(until, bool):
        raise InputError(t.key("until_settled"), until, "true or false")
    longest = None
    if until or t.has("max_duration"):
        if mode != "transient":
            raise InputError(t.key("until_settled"), until, "a transient run (mode = "
                             "\"transient\"): a steady run always runs until periodic")
        assert duration is not None     # read above for every transient run
        longest = t.get("max_duration", f"{min(10.0 * duration, limits.MAX_DURATION_S)} s",
                        within=(duration, limits.MAX_DURATION_S))
    t.finish()
    spec = RunSpec(mode, model, speed, tuple(dict.fromkeys(effects)), fid, cycles, expansion,
                   duration, record, band, warm, start, until, longest, start_angle)
    check_output_samples(spec)
    return spec


def scene_from_dict(data: dict, name: str = "scene", source: str | None = None, *,
                    like: Scene | None = None) -> Scene:
    """Validate a parsed TOML document into a :class:`Scene`; every mistake at once.

    Parameters
    ----------
    data : dict
        The scene's tables, as TOML reads them.
    name : str
        The scene's name.
    source : str, optional
        The path it was read from (a load schedule is found beside it).
    like : Scene, optional
        A scene loaded from tables that ``data`` shares sections with, the same
        objects (:func:`corliss.keys.edits.edited` of ``like.data``: a study's run):
        each of its sections' specs whose table ``data`` shares, and whose inputs from
        other sections (the barometer, the swept volume) are the same numbers, is
        taken as it is instead of being read again (the same spec: a section's spec is
        a function of those); the tables edited are read and every rule across
        sections checked as for any scene.  Neither's shared tables may be changed in
        place.

    Returns
    -------
    Scene
        The validated scene, all SI.

    Raises
    ------
    InputError
        Naming the offending key; :class:`~corliss.errors.InputErrors` (an InputError)
        listing every mistake when the scene has several: each key read on its own
        against its declaration (kind, units, range, choices), every unknown section and
        key, and the first mistake the whole scene's checks found.
    """
    try:
        return _scene_from_dict(data, name, source, like)
    except InputError as first:
        if isinstance(first, InputErrors):
            raise
        # the loader's own mistake first (the one a single-mistake scene reports)
        # (a key the first message already names, a misspelling it points out, once)
        errors = [first] + [e for e in key_errors(data)
                            if e.key != first.key and e.key not in str(first)]
        if len(errors) > 1:
            raise InputErrors(errors) from None
        raise


#: The sections read by one key group each (the gear and governor by their registry).
_SECTION_KEYS = {"engine": ENGINE, "supply": SUPPLY, "exhaust": EXHAUST, "run": RUN,
                 "output": OUTPUT, "flywheel": FLYWHEEL, "load": LOAD, "compare": COMPARE,
                 "compound": COMPOUND}


def key_errors(data: dict) -> list[InputError]:
    """Every mistake of a scene that shows in one key alone, or in its sections.

    Unknown and missing sections; in each section, each key read on its own by its
    declaration (kind, units, range, choices) and each key the section does not take.
    Mistakes between keys (a lap larger than the travel, a governor that acts the wrong
    way) need the scene's other values and are left to :func:`scene_from_dict`.

    Parameters
    ----------
    data : dict
        The scene's tables, as TOML reads them.

    Returns
    -------
    list of InputError
        In the scene's order of sections and keys; empty when none shows this way.
    """
    from corliss.governors import GOVERNORS
    errors: list[InputError] = []
    for key in data:
        if key not in SECTIONS:
            errors.append(InputError(key, data[key], "a known section: " + ", ".join(SECTIONS)))
    for key in SECTIONS[1:6]:
        if key not in data:
            errors.append(InputError(key, None, f"a [{key}] section: it is required"))
    barometer = units.STANDARD_ATMOSPHERE_Pa
    sup = data.get("supply")
    if isinstance(sup, dict) and "barometer" in sup:
        try:
            barometer = Table(sup, "supply", keys=SUPPLY).get("barometer")
        except InputError:
            pass            # reported with the supply's keys below
    for section, table in data.items():
        if section not in SECTIONS or section == "title":
            continue
        if not isinstance(table, dict):
            errors.append(InputError(section, table, "a table (a [section] in the scene)"))
            continue
        group = _SECTION_KEYS.get(section)
        registry = {"valve_gear": GEARS, "lp_valve_gear": GEARS,
                    "governor": GOVERNORS}.get(section)
        if registry is not None:
            t = Table(table, section, barometer)
            try:
                group = _registered(t, registry).keys
            except InputError as exc:
                errors.append(exc)
                continue
        if group is None:
            continue
        for key in table:
            if key == "type" and registry is not None:
                continue
            if key not in group:
                try:
                    Table({key: table[key]}, section, barometer, group).finish(
                        {n: e.keys for n, e in registry.items()} if registry else None)
                except InputError as exc:
                    errors.append(exc)
                continue
            t = Table(table, section, barometer, group)
            try:
                if group[key].kind == "fraction":
                    _pair_fraction(t, key)              # one fraction or [head, crank]
                elif key == "temperature" and table[key] == "saturated":
                    pass
                else:
                    t.get(key)
            except InputError as exc:
                errors.append(exc)
            except Exception:   # noqa: BLE001 - a key read only beside others: left to the loader
                pass
    return errors


def _scene_from_dict(data: dict, name: str = "scene", source: str | None = None,
                     like: Scene | None = None) -> Scene:
    """Validate a parsed TOML document into a :class:`Scene`.

    Parameters
    ----------
    data : dict
        The scene's tables, as TOML reads them.
    name : str
        The scene's name.
    source : str, optional
        The path it was read from (a load schedule is found beside it).
    like : Scene, optional
        A scene whose unedited sections' specs are taken (:func:`scene_from_dict`).

    Returns
    -------
    Scene
        The validated scene, all SI.

    Raises
    ------
    InputError
        Naming the first offending key.
    """
    for key in data:
        if key not in SECTIONS:
            raise InputError(key, data[key], "a known section: " + ", ".join(SECTIONS))
    for key in SECTIONS[1:6]:
        if key not in data:
            raise InputError(key, None, f"a [{key}] section: it is required")
    shared = _shared_sections(data, like)
    sup = Table(data["supply"], "supply", keys=SUPPLY)
    if like is not None and "supply" in shared:
        barometer = like.supply.barometer_Pa
    else:
        barometer = sup.get("barometer")
    sup.barometer_Pa = barometer
    if like is not None and barometer != like.supply.barometer_Pa:
        shared = set()          # every gauge pressure read again on the new barometer
    engine = (like.engine if like is not None and "engine" in shared
              else _engine(Table(data["engine"], "engine", barometer, ENGINE)))
    swept = _swept_of(engine)
    if like is not None and "supply" in shared and swept == _swept_of(like.engine):
        supply = like.supply
    else:
        if "supply" in shared:
            sup.has("barometer")        # read with the scene ``like``, for the finish
        supply = _supply(sup, swept)
    if like is not None and "exhaust" in shared:
        exhaust = like.exhaust
    else:
        ex = Table(data["exhaust"], "exhaust", barometer, EXHAUST)
        exhaust = ExhaustSpec(ex.get("pressure"))
        ex.finish()
    if not supply.pressure_Pa > exhaust.pressure_Pa:
        raise InputError("supply.pressure", data["supply"].get("pressure"),
                         f"a supply pressure above the exhaust pressure "
                         f"({data['exhaust'].get('pressure')!r} = "
                         f"{exhaust.pressure_Pa / units.PSI_Pa:.4g} psia)")
    if like is not None and "valve_gear" in shared:
        gt, gear = GEARS[like.gear_type], like.gear
    else:
        vg = Table(data["valve_gear"], "valve_gear", barometer)
        gt = _registered(vg, GEARS)
        vg.bind(gt.keys)
        gear = gt.parse(vg)
        vg.finish({n: e.keys for n, e in GEARS.items()})
    run = (like.run if like is not None and "run" in shared
           else _run(Table(data["run"], "run", barometer, RUN)))
    _check_states(data, supply, exhaust, run)
    for effect, keys in EFFECT_KEYS.items():
        for k in keys:
            sec, _, key = k.rpartition(".")
            if run.has(effect) and key not in data[sec or "engine"]:
                raise InputError(f"{sec or 'engine'}.{key}", None, f"a value: the {effect!r} "
                                 "effect named in run.effects needs it")
    if run.has("leakage") and engine.leakage_model == "period":
        if not (engine.valve_leak_rate_kg_s_Pa or engine.piston_leak_rate_kg_s_Pa
                or engine.steam_edge_leak_rate_kg_s_Pa
                or engine.exhaust_edge_leak_rate_kg_s_Pa):
            raise InputError("engine.valve_leak_rate", None, "a rate of leak (or "
                             "engine.piston_leak_rate, steam_edge_leak_rate or "
                             "exhaust_edge_leak_rate): the 'leakage' effect by the period's "
                             "law needs one")
    elif run.has("leakage") and not (engine.valve_leakage_area_m2
                                     or engine.piston_leakage_area_m2):
        raise InputError("engine.valve_leakage_area", None, "a leak area (or "
                         "engine.piston_leakage_area): the 'leakage' effect needs one")
    for effect in ("leakage", "steam_chest"):
        if run.has(effect) and not run.has("port_flow"):
            raise InputError("run.effects", list(run.effects), f"\"port_flow\" beside "
                             f"\"{effect}\": it acts through finite ports")
    if run.has("wall_heat") and run.model == "ideal":
        raise InputError("run.model", run.model, "\"crank_resolved\" with \"wall_heat\": "
                         "the ideal card is algebraic, without a wall")
    if (run.has("wall_heat") and not run.has("port_flow")
            and engine.wall_heat_model != "skin"):
        # ideal ports carry the skin wall (corliss.engine.wall.IdealPortWall) only
        raise InputError("engine.wall_heat_model", engine.wall_heat_model,
                         "\"skin\" with ideal ports (or \"port_flow\" in run.effects)")
    compound = None
    if len(engine.crank_angles_rad) > 1 and (run.model != "crank_resolved"
                                             or not run.has("port_flow")):
        raise InputError("engine.cylinders", len(engine.crank_angles_rad),
                         "1, or run.model = \"crank_resolved\" with \"port_flow\" for several")
    if "compound" in data:
        if len(engine.crank_angles_rad) > 1:
            raise InputError("engine.cylinders", len(engine.crank_angles_rad),
                             "1 in a compound: its second cylinder is the [compound] LP")
        compound = _compound(Table(data["compound"], "compound", barometer, COMPOUND), engine,
                             data.get("lp_valve_gear"), gt, gear, barometer)
        if run.model != "crank_resolved" or not run.has("port_flow"):
            raise InputError("compound", "[...]", "run.model = \"crank_resolved\" with "
                             "\"port_flow\": the receiver fills and empties through ports")
    elif "lp_valve_gear" in data:
        raise InputError("lp_valve_gear", "[...]", "a [compound] section beside it")
    _check_jacket_pressures(data, engine, supply, exhaust, compound is not None)
    if like is not None and "output" in shared:
        output = like.output
    else:
        out = Table(data.get("output", {}), "output", barometer, OUTPUT)
        output = OutputSpec(out.get("units"), out.get("dir"))
        out.finish()
    title = data.get("title", name)
    if not isinstance(title, str):
        raise InputError("title", title, "a string")
    if len(title) > limits.MAX_TITLE_CHARS or not title.isprintable():
        raise InputError("title", title[:80] + ("..." if len(title) > 80 else ""),
                         f"a line of printable text of at most {limits.MAX_TITLE_CHARS} "
                         "characters (no control characters: it goes into every file)")
    loop = _speed_loop(data, run, supply, gt, gear, barometer,
                       Path(source).parent if source else None, engine)
    cmp = None
    if "compare" in data:
        cmp = _compare(Table(data["compare"], "compare", barometer, COMPARE),
                       math.pi / 4.0 * engine.bore_m ** 2 * engine.stroke_m, gt.build(gear))
    return Scene(title, engine, supply, exhaust, gt.name, gear, run, output, name, source, compound,
                 **loop, compare=cmp, data=data)


def _speed_loop(data: dict, run: RunSpec, supply: SupplySpec, gt, gear, barometer: float,
                scene_dir: Path | None, engine: EngineSpec) -> dict:
    """The [flywheel], [load] and [governor] sections of a transient run, checked against
    the rest of the scene (what the governor moves must exist)."""
    present = [k for k in ("governor", "flywheel", "load") if k in data]
    if run.mode != "transient":
        if present:
            raise InputError(present[0], "[...]", "run.mode = \"transient\" beside it: a steady "
                             "run holds the speed, so it has no flywheel, load or governor")
        return {}
    for key in ("flywheel", "load"):
        if key not in data:
            raise InputError(key, None, f"a [{key}] section: a transient run needs one")
    if run.model not in ("crank_resolved", "mean_value") or not run.has("port_flow"):
        raise InputError("run.model", run.model, "\"crank_resolved\" or \"mean_value\" (maps "
                         "from crank-resolved cards) with \"port_flow\" in a transient run")
    flywheel = parse_flywheel(Table(data["flywheel"], "flywheel", barometer, FLYWHEEL))
    load = parse_load(Table(data["load"], "load", barometer, LOAD), run.speed_rad_s, scene_dir)
    out = {"flywheel": flywheel, "load": load}
    if "governor" in data:
        # the governors are loaded for a governed scene only: a steady run imports none
        from corliss.governors import GOVERNORS
        g = Table(data["governor"], "governor", barometer)
        gov_t = _registered(g, GOVERNORS)
        g.bind(gov_t.keys)
        spec = gov_t.parse(g)
        g.finish({n: e.keys for n, e in GOVERNORS.items()})
        governor = gov_t.build(spec)
        mech = governor.mechanism(11)
        lo_hi = mech.actuator_range()
        if mech.acts_on == "throttle":
            if not run.has("steam_chest") or supply.pipe_diameter_m is None:
                raise InputError("governor.type", gov_t.name, "a throttling governor needs "
                                 "\"steam_chest\" in run.effects and supply.pipe_diameter: it "
                                 "moves the throttle in the steam pipe")
            if not (0.0 <= lo_hi[0] and lo_hi[1] <= 1.0):
                raise InputError("governor.opening_at_rest", [mech.actuator_at_rest,
                                 mech.actuator_at_top], "throttle openings from 0 to 1 at rest "
                                 "and at the top stop")
        else:
            g_obj = gt.build(gear)
            if g_obj.setting_range is None:
                raise InputError("governor.type", gov_t.name, f"a valve gear with a setting for "
                                 f"the governor to move; the {gt.name} gear has none")
            lo, hi = g_obj.setting_range
            ends = [("governor.setting_at_rest", mech.actuator_at_rest),
                    ("governor.setting_at_top", mech.actuator_at_top)]
            if mech.safety_z > 0.0 and math.isfinite(mech.actuator_safety):
                ends.append(("governor.safety_setting", mech.actuator_safety))
            for key, value in ends:
                if not lo - 1e-12 <= value <= hi + 1e-12:
                    raise InputError(key, g.raw(key.split(".")[1], value),
                                     f"a gear setting within the {gt.name} gear's range "
                                     f"{lo} to {hi} ({g_obj.setting_name})")
        spec = _check_governor_sense(spec, mech, g, gt, gear, run, engine)
        governor = gov_t.build(spec)
        mech = governor.mechanism(11)
        _check_governed_speed(governor, mech, g, run)
        _check_governor_spring(gov_t, spec, mech, g, run)
        out["governor_type"] = gov_t.name
        out["governor"] = spec
    return out


#: How far outside its working range [fraction of speed] a governor's run speed may lie:
#: a load step carries the speed a few per cent past the range; a governor whose range
#: lies a quarter or more away from the run speed cannot govern that engine.
GOVERNED_SPEED_MARGIN = 0.25


#: The smallest change of the mean cut-off [fraction of stroke] between the governor's
#: rest and its top stop that counts as governing: a governor whose travel moves the
#: cut-off less than this does nothing an engine would notice.
GOVERNOR_SENSE_MIN_FRAC = 1e-3


def _admitted_frac(ev: dict) -> float:
    """An end's cut-off as a fraction of stroke: 0 when the valve never opens, 1 when it
    opens and never cuts off."""
    if ev["admission_deg"] is None:
        return 0.0
    return 1.0 if ev["cutoff_frac"] is None else float(ev["cutoff_frac"])


def _mean_cutoff(gear_obj, geo, setting: float) -> float:
    from corliss.valves.events import events as valve_events
    ev = valve_events(gear_obj.with_setting(setting), lambda t: float(geo.fraction(t)))
    return 0.5 * (_admitted_frac(ev["head"]) + _admitted_frac(ev["crank"]))


def _check_governor_sense(spec, mech, g: Table, gt, gear, run: RunSpec, engine: EngineSpec):
    """A governor must act in the stabilising sense: as the speed rises and it lifts from
    rest (z = 0) to its top stop (z = 1), the throttle closes or the cut-off shortens.

    The static characteristic's sense is read from its two ends before any work: the
    throttle openings, or the mean cut-off of the two ends (:mod:`corliss.valves.events`)
    at the gear settings at rest and at the top stop.  A governor acting the wrong way
    (it gives more steam as the engine speeds up, so a load change runs away) is refused,
    naming both keys; when neither key is written, their defaults are swapped to the
    sense that governs, and the log says so.

    Returns
    -------
    spec
        The governor's spec, with its actuator's ends swapped when the defaults acted the
        wrong way.
    """
    a = spec.actuator
    given = [k for k in (("opening_at_rest", "opening_at_top") if a.acts_on == "throttle"
                         else ("setting_at_rest", "setting_at_top")) if k in g.data]
    if a.acts_on == "throttle":
        at_rest, at_top = a.at_rest, a.at_top
        what = (f"the throttle opens from {at_rest:g} at rest to {at_top:g} at the top stop")
    else:
        from corliss.engine.geometry import CylinderGeometry
        gear_obj = gt.build(gear)
        if hasattr(gear_obj, "with_speed"):
            gear_obj = gear_obj.with_speed(run.speed_rad_s)
        geo = CylinderGeometry(engine, rod_angularity=run.has("rod_angularity"))
        at_rest = _mean_cutoff(gear_obj, geo, a.at_rest)
        at_top = _mean_cutoff(gear_obj, geo, a.at_top)
        what = (f"on the valve_gear ({gt.name}), the mean cut-off goes from {at_rest:.3g} of "
                f"the stroke at rest (setting {a.at_rest:g}) to {at_top:.3g} at the top stop "
                f"(setting {a.at_top:g})")
    if at_top < at_rest - GOVERNOR_SENSE_MIN_FRAC:
        return spec
    if at_top > at_rest + GOVERNOR_SENSE_MIN_FRAC and not given:
        log.info("governor: the default %s act the wrong way for the %s gear (%s); swapped",
                 "openings" if a.acts_on == "throttle" else "settings", gt.name, what)
        return dataclasses.replace(spec, actuator=dataclasses.replace(
            a, at_rest=a.at_top, at_top=a.at_rest))
    keys = (("governor.opening_at_rest", "governor.opening_at_top") if a.acts_on == "throttle"
            else ("governor.setting_at_rest", "governor.setting_at_top"))
    sense = ("gives more steam as the engine speeds up, so a load change would run it away"
             if at_top > at_rest else "does not change the steam the engine takes")
    raise InputError(keys[0], a.at_rest,
                     f"with {keys[1]} = {a.at_top:g}, a governor that gives less steam as it "
                     f"lifts: {what}; it {sense}. "
                     + ("Swap the two values" if at_top > at_rest else
                        "Give the gear's setting of the longest cut-off at rest and of the "
                        "shortest at the top stop"))


#: How far the speed at which a spring-loaded governor balances in the middle of its
#: travel may lie from the run speed [fraction]: the bundled governors, of 4.5 to 7.7 %
#: droop, balance within 1 % of run.speed at mid-travel, and a start from equilibrium
#: lands within half the droop of it; a spring that puts the middle a tenth away
#: starts the engine as far from the speed it was written for.
SPRING_SPEED_MARGIN = 0.10


def _check_governor_spring(gov_t, spec, mech, g: Table, run: RunSpec) -> None:
    """Refuse a spring-loaded governor (shaft or Hartnell) whose spring balances the
    middle of its working travel far from run.speed, with the stiffness (preload kept)
    and the preload (stiffness kept) that would balance it there."""
    if not (hasattr(spec, "spring_stiffness_N_m") and hasattr(spec, "spring_preload_N")):
        return
    from corliss.governors.operating_point import working_travel   # a governed scene only
    lo, hi = working_travel(mech)
    z_mid = np.array([0.5 * (lo + hi)])
    target = run.speed_rad_s

    def mid_speed(sp) -> float:
        return float(gov_t.build(sp).equilibrium_speed_rad_s(z_mid)[0])

    w = mid_speed(spec)
    if abs(w / target - 1.0) <= SPRING_SPEED_MARGIN:
        return

    def solve(field: str) -> float | None:
        # the spring's moment is linear in its stiffness and preload, so the squared
        # speed is linear in each (omega^2 = R / G): two evaluations give the root
        x0 = getattr(spec, field)
        x1 = x0 * 1.5 + 1.0
        w0 = w ** 2
        w1 = mid_speed(dataclasses.replace(spec, **{field: x1})) ** 2
        if w1 == w0:
            return None
        x = x0 + (target ** 2 - w0) * (x1 - x0) / (w1 - w0)
        return x if x >= 0.0 else None

    k = solve("spring_stiffness_N_m")
    p = solve("spring_preload_N")
    us = not any(str(g.raw(n, "")).strip().endswith(("N/m", "N", "kN", "N/mm"))
                 for n in ("spring_stiffness", "spring_preload"))
    fix = []
    if k is not None:
        fix.append("spring_stiffness = " + (f"\"{k * units.INCH_m / units.LBF_N:.3g} lbf/in\""
                                            if us else f"\"{k:.4g} N/m\""))
    if p is not None:
        fix.append("spring_preload = " + (f"\"{p / units.LBF_N:.4g} lbf\"" if us else
                                          f"\"{p:.4g} N\""))
    raise InputError("governor.spring_stiffness", g.raw("spring_stiffness", None),
                     f"a spring that balances the governor near run.speed = "
                     f"{run.speed_rpm:.4g} rpm: in the middle of its travel it balances at "
                     f"{w / units.RPM_RAD_S:.4g} rpm, so the engine would start and run "
                     f"{100 * (w / target - 1.0):+.0f} % from the speed it was written for"
                     + ("; " + " or ".join(fix) + " (the other kept) would balance it at "
                        "run.speed" if fix else ""))


def _check_governed_speed(gov, mech, g: Table, run: RunSpec) -> None:
    """Refuse a governor ``gov`` (tabulated as ``mech``) whose static characteristic
    balances nowhere near the run speed (a drive ratio that puts its working speed far
    from the engine's), naming the key and the speed it would govern at."""
    from corliss.governors.operating_point import working_travel   # a governed scene only
    ends = np.array(working_travel(mech))
    lo, hi = gov.equilibrium_speed_rad_s(ends) / units.RPM_RAD_S
    rpm = run.speed_rpm
    if (1.0 - GOVERNED_SPEED_MARGIN) * lo <= rpm <= (1.0 + GOVERNED_SPEED_MARGIN) * hi:
        return
    where = (f"this governor balances between {lo:.4g} and {hi:.4g} rpm of the engine, far "
             f"from run.speed = {rpm:.4g} rpm")
    if "ratio" in g.data:
        ratio = mech.ratio * 0.5 * (lo + hi) / rpm
        raise InputError("governor.ratio", g.raw("ratio"), f"a drive ratio that puts the "
                         f"governor's working speeds about the engine's: {where}; a ratio "
                         f"near {ratio:.3g} would govern at run.speed")
    raise InputError("run.speed", run.speed_rpm, f"a speed within the governor's working "
                     f"range: {where} (its springs and weights set that range)")


def load_scene(path: str | Path) -> Scene:
    """Read and validate a scene file.

    Parameters
    ----------
    path : str or Path
        A TOML scene.

    Returns
    -------
    Scene
        The validated scene, with the file's text.

    Raises
    ------
    InputError
        If the file is missing, is not TOML, or any key is invalid.
    """
    p = Path(path)
    text = read_text(p, "scene", "a scene file (.toml)")
    try:
        data = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, RecursionError, ValueError) as exc:
        # (tomllib's RecursionError: tables or arrays nested thousands deep; ValueError:
        # an integer of more digits than Python converts, 4300)
        raise InputError("scene", str(path), f"a TOML file ({str(exc)[:200]})") from None
    return dataclasses.replace(scene_from_dict(data, name=p.stem, source=str(p)), text=text)


def default_scene_path() -> Path:
    """The bundled default scene (a 12 x 24 in slide-valve engine).

    Returns
    -------
    Path
        Its file.
    """
    return bundled_scenes()["default"]


def bundled_scenes() -> dict[str, Path]:
    """The scenes that come with the package.

    Returns
    -------
    dict
        ``{name: path}``, sorted by name.
    """
    from importlib.resources import files
    root = Path(str(files("corliss.scenes")))
    return {p.stem: p for p in sorted(root.glob("*.toml"))}


def find_scene(name_or_path: str | Path) -> Path:
    """A scene file by path, or a bundled scene by name (``"default"``, ...).

    Parameters
    ----------
    name_or_path : str or Path
        A path, or a bundled scene's name (with or without ``.toml``).

    Returns
    -------
    Path
        The scene file.

    Raises
    ------
    InputError
        If it is neither an existing file nor the name of a bundled scene.
    """
    p = Path(name_or_path)
    if p.is_file():
        return p
    scenes = bundled_scenes()
    stem = p.name[:-5] if p.name.endswith(".toml") else p.name
    if p.parent == Path(".") and stem in scenes:
        return scenes[stem]
    raise InputError("scene", str(name_or_path), "the path of an existing scene file (.toml) "
                     "or the name of a bundled scene (corliss list scenes): "
                     + ", ".join(scenes))
