"""The declared keys of the scene's sections (``[engine]``, ``[supply]``, ``[run]``, ...).

The keys of ``[valve_gear]`` and ``[governor]`` belong to the gear or governor named
by their ``type`` and are declared on its registry entry
(:data:`corliss.valves.GEARS`, :data:`corliss.governors.GOVERNORS`); ``[lp_valve_gear]``
takes the keys of its gear as ``[valve_gear]`` does.  The loader
(:mod:`corliss.scene.loader`) reads every section through these groups.
"""

from __future__ import annotations

import math

from corliss.keys import limits, units
from corliss.engine.flywheel import INERTIA_RANGE, RIM_MASS_RANGE, RIM_RADIUS_RANGE
from corliss.engine.load import SPEED_LAWS
from corliss.engine.options import EFFECTS, EXPANSION_LAWS, METHODS, MODELS, PRESETS
from corliss.keys.declared import POSITIVE_LENGTH, ZERO_OR_MORE, Derived, Key, group
from corliss.keys.toml_table import DISCHARGE_COEFFICIENT
from corliss.thermo.steam import BACKENDS
from corliss.valves.single_acting import STEAM_ENDS

#: How a transient run's time series is recorded (see :class:`corliss.engine.scene_specs.RunSpec`).
RECORD_CHOICES = ("step", "degree", "cycle")
#: How a governed transient run starts (see :class:`corliss.engine.scene_specs.RunSpec`).
START_CHOICES = ("equilibrium", "run_speed", "rest")
#: Wall-heat models of the ``wall_heat`` effect.
WALL_HEAT_MODELS = ("skin", "marks", "english", "conductance", "adair")
#: Models of the ``leakage`` effect.
LEAKAGE_MODELS = ("orifice", "period")
#: The parts of the wall a steam jacket may cover (corliss.engine.wall.jacketed_area_m2).
JACKETS = ("none", "barrel", "covers", "barrel_and_covers")
#: Cylinder sizes: a model's half-inch cylinder to the largest engines built [m].
CYLINDER_RANGE = (1e-3, 5.0)

ENGINE = group(
    "engine", "The cylinder (or identical cylinders): its size, rod, masses, friction, leaks "
    "and walls.",
    Key("bore", "length", "Cylinder bore.", within=CYLINDER_RANGE, unit="in"),
    Key("stroke", "length", "Piston stroke (twice the crank).", within=CYLINDER_RANGE, unit="in"),
    Key("connecting_rod", "length", "Connecting rod, centre to centre; longer than the crank.",
        within=(1e-3, 25.0), unit="in"),
    Key("clearance", "fraction", "Clearance volume as a fraction of the end's swept volume "
        "(0.005 to 0.5), once or [head, crank].", ends=True),
    Key("piston_rod_diameter", "length", "Piston rod diameter (takes area from the crank-end "
        "piston face); zero or more, less than the bore.", default="0 in", within=ZERO_OR_MORE,
        unit="in"),
    Key("cylinders", "integer", "Identical cylinders on one shaft.", default=1, within=(1, 6)),
    Key("crank_angles", "angle_list", "How far each crank follows the first, the first \"0 deg\" "
        "(default evenly spaced; 0 and 90 deg for two).",
        default=Derived("evenly spaced; [\"0 deg\", \"90 deg\"] for two")),
    Key("reciprocating_mass", "mass", "Piston, rod and crosshead mass in the crank effort.",
        default=None, effect="inertia"),
    Key("friction_torque", "torque", "Engine friction torque, constant part (zero or more).",
        default="0 N m", within=ZERO_OR_MORE, effect="friction"),
    Key("friction_torque_per_speed", "torque_per_speed", "Engine friction torque growing "
        "with speed (zero or more).", default="0 N m s", within=ZERO_OR_MORE,
        effect="friction"),
    Key("valve_leakage_area", "area", "Equivalent orifice of the leak past the valve into "
        "each end, up to 5 % of the piston area.", default="0 in2", effect="leakage"),
    Key("piston_leakage_area", "area", "Equivalent orifice of the leak past the piston, up "
        "to 5 % of the piston area.", default="0 in2", effect="leakage"),
    Key("leakage_model", "choice", "How the leaks flow: as orifices of equivalent area, or "
        "by the period's law (a rate of leak times the pressure difference, Callendar and "
        "Nicolson 1897).", default="orifice", choices=LEAKAGE_MODELS, effect="leakage"),
    Key("valve_leak_rate", "leak_rate", "Rate of leak of the valve, chest to exhaust, per "
        "unit of pressure difference (Callendar and Nicolson's flat slide valve: "
        "3 lb/h psi).", default="0 lb/h psi", effect="leakage"),
    Key("piston_leak_rate", "leak_rate", "Rate of leak past the piston per unit of "
        "pressure difference.", default="0 lb/h psi", effect="leakage"),
    Key("steam_edge_leak_rate", "leak_rate", "Rate of leak past each closed steam edge "
        "of the valve, the chest (or receiver) into the end, per unit of pressure "
        "difference, for a valve of 8 in ports whose face covers them by 2.11 in; each "
        "edge scaled by its port's length and inversely by its face's width (the period's "
        "law; Callendar and Nicolson's valve: 3 lb/h psi for its whole leak).",
        default="0 lb/h psi", effect="leakage"),
    Key("exhaust_edge_leak_rate", "leak_rate", "Rate of leak past each closed exhaust edge "
        "of the valve, the end to the exhaust, per unit of pressure difference, for the "
        "same reference valve and scaled the same way.", default="0 lb/h psi",
        effect="leakage"),
    Key("wall_heat_model", "choice", "How heat passes between steam and cylinder walls: a "
        "wall with a temperature (skin), or a period law imposed as a schedule (marks, "
        "english: English's law, its jacketed constant with a jacket), or a conductance.",
        default="skin", choices=WALL_HEAT_MODELS, effect="wall_heat"),
    Key("marks_constant", "heat_transfer", "Marks's constant of condensation (Art. 82), "
        "above zero.", default="18.13 Btu/ft2 degF min", effect="wall_heat"),
    Key("condensing_coefficient", "heat_transfer", "Film coefficient of condensing steam "
        "on the wall (above zero), or \"marks\" (Marks's eq. 221); the default is Callendar and "
        "Nicolson's measured 4 kcal/s m2 degC.", default="16747.2 W/m2 K",
        choices=("marks",), effect="wall_heat"),
    Key("jacket", "choice", "A steam jacket on the barrel, on the covers (the cylinder's two "
        "end covers; the piston's faces are never jacketed), or on both, at its steam's "
        "saturation temperature (jacket_pressure, lp_jacket_pressure).",
        default="none",
        choices=JACKETS, effect="wall_heat"),
    Key("jacket_pressure", "pressure", "Pressure of the jacket's steam on the high-pressure "
        "(or only) cylinder, absolute or gauge stated; from the exhaust pressure up to the "
        "supply pressure; unset: the supply's.", default=None, unit="psia",
        when="with a jacket", effect="wall_heat"),
    Key("lp_jacket_pressure", "pressure", "Pressure of the jacket's steam on a compound's "
        "low-pressure cylinder, absolute or gauge stated; from the exhaust pressure up to "
        "the supply pressure; unset: the receiver's starting pressure, sqrt(supply x "
        "exhaust).", default=None, unit="psia", when="with a jacket, in a compound",
        effect="wall_heat"),
    Key("wall_thickness", "length", "Cylinder wall thickness, 1 mm to half the bore.",
        default="1 in", within=(1e-3, math.inf), unit="in", effect="wall_heat"),
    Key("steam_ends", "choice", "The ends that take steam: both (double-acting), or head or "
        "crank alone (single-acting: the other end's exhaust port stands open).",
        default="both", choices=STEAM_ENDS),
)

SUPPLY = group(
    "supply", "Steam at the chest (or at the boiler, with the steam_chest effect).",
    Key("pressure", "pressure", "Supply pressure, absolute or gauge stated; below the critical "
        "22.064 MPa, above the exhaust pressure.", unit="psia"),
    Key("barometer", "pressure", "Atmospheric pressure that gauge and vacuum readings are "
        "taken against.", default="14.696 psia", unit="psia"),
    Key("temperature", "temperature", "Superheated steam temperature (at or above "
        "saturation), or \"saturated\".", default="saturated", choices=("saturated",)),
    Key("dryness", "number", "Dryness fraction of saturated steam, in (0, 1].", default=1.0,
        within=(0.0, 1.0), when="with saturated steam (no temperature)"),
    Key("chest_volume", "volume", "Steam chest volume, at least 0.05 of the swept volume.",
        default=None, unit="ft3", effect="steam_chest"),
    Key("pipe_diameter", "length", "Bore of the steam pipe from the boiler.", default=None,
        within=POSITIVE_LENGTH, unit="in", effect="steam_chest"),
    Key("pipe_discharge_coefficient", "number", "Discharge coefficient of the pipe taken as "
        "one orifice.", default=0.8, within=DISCHARGE_COEFFICIENT, effect="steam_chest"),
    Key("throttle", "number", "Throttle opening, above 0 (shut) up to 1 (wide open).",
        default=1.0, within=(0.0, 1.0), effect="steam_chest"),
    Key("throttle_law", "choice", "Open area against opening: a gate (linear) or a disc "
        "turned through 90 deg (butterfly).", default="linear", choices=("linear", "butterfly"),
        effect="steam_chest"),
)

EXHAUST = group(
    "exhaust", "Back pressure: atmosphere, condenser or receiver, held constant.",
    Key("pressure", "pressure", "Back pressure, absolute or gauge or vacuum stated.",
        unit="psia"),
)

RUN = group(
    "run", "What to simulate and how accurately.",
    Key("mode", "choice", "Constant speed (steady) or speed as a state with flywheel, load "
        "and governor (transient).", default="steady", choices=("steady", "transient")),
    Key("model", "choice", "Crank-resolved cycle, ideal card, or mean-value maps (transient "
        "only).", default="crank_resolved", choices=MODELS),
    Key("speed", "speed", "Crank speed (a transient run's initial speed).",
        within=(0.1 * units.RPM_RAD_S, math.inf), unit="rpm"),
    Key("effects", "list", "The effects the model includes.",
        default=["port_flow", "rod_angularity"], choices=tuple(EFFECTS)),
    Key("fidelity", "choice", "Preset of accuracy knobs (any knob below overrides it).",
        default="standard", choices=tuple(PRESETS)),
    Key("properties", "choice", "Steam property tier (overrides the preset's).",
        default=Derived("the fidelity preset's"), choices=tuple(BACKENDS)),
    Key("method", "choice", "Integrator of the steady cycle and of the transient loop "
        "(overrides the preset's, which for standard is rodas4 at 2e-6 wherever the "
        "Jacobian is exact and dopri5 at 1e-6 with a skin, conductance or Adair wall); "
        "the compiled ones need properties \"table\" or \"perfect\"; the transient loop "
        "has dopri5, ros4, rodas3 and rodas4, and takes dopri5 for any other.",
        default=Derived("the fidelity preset's"), choices=METHODS),
    Key("rtol", "number", "Relative tolerance of the integrator.",
        default=Derived("the fidelity preset's"), within=(1e-13, 1e-2)),
    Key("convergence_tolerance", "number", "Cycle-to-cycle change taken as periodic, a "
        "fraction in (0, 0.5).", default=Derived("the fidelity preset's"), within=(0.0, 0.5)),
    Key("max_cycles", "integer", "Most cycles run to reach a periodic state.",
        default=Derived("the fidelity preset's"), within=(2, 1000)),
    Key("step", "angle", "Crank-angle step of the output and of fixed-step integrators, "
        "0.01 to 10 deg.", default=Derived("the fidelity preset's"),
        within=(math.radians(0.01), math.radians(10.0)), unit="deg"),
    Key("portmap_points", "integer", "Crank angles the port areas are tabulated at.",
        default=Derived("the fidelity preset's"), within=(90, 100_000)),
    Key("cycles", "integer", "Run exactly this many cycles (steady only); absent: until "
        "periodic.", default=None, within=(1, limits.MAX_CYCLES)),
    Key("expansion", "choice", "Expansion law of the ideal card.", default="hyperbolic",
        choices=EXPANSION_LAWS),
    Key("duration", "time", "Simulated time of a transient run, above 0 up to 1 h.",
        default=None, within=(0.0, limits.MAX_DURATION_S),
        when="in a transient run (required there)"),
    Key("record", "choice", "Time series: every step (transient only), every output step "
        "of crank angle, or once a turn (a steady run's last cycle at every output step).",
        default=Derived("by a transient's length; degree in a steady run"),
        choices=RECORD_CHOICES),
    Key("settling_band", "number", "Speed band, as a fraction of the final mean speed, the "
        "settling time is measured to; in (0, 0.5).", default=0.002, within=(0.0, 0.5)),
    Key("warmup_cycles", "integer", "Turns at the initial speed, governor held, before "
        "t = 0.", default=3, within=(0, 100)),
    Key("start", "choice", "How a transient run starts.", default="equilibrium",
        choices=START_CHOICES),
    Key("start_angle", "angle", "Crank angle of a start from rest.", default=None, unit="deg",
        when="with start = \"rest\" in a transient run (required there)"),
    Key("until_settled", "flag", "Run past duration until the speed has settled, up to "
        "max_duration (transient only).", default=False),
    Key("max_duration", "time", "The longest a run until_settled goes on, from duration up "
        "to 1 h.", default=Derived("10 x duration, at most 1 h"),
        within=(0.0, limits.MAX_DURATION_S), when="with until_settled = true"),
)

OUTPUT = group(
    "output", "Where and how results are written.",
    Key("units", "choice", "Units of the CSV files and plots.", default="US",
        choices=("US", "SI")),
    Key("dir", "string", "Output directory, relative to the working directory.",
        default="out"),
)

COMPOUND = group(
    "compound", "The low-pressure cylinder of a compound engine and its receiver.",
    Key("lp_bore", "length", "LP cylinder bore.", within=POSITIVE_LENGTH, unit="in"),
    Key("lp_stroke", "length", "LP stroke.", default=Derived("the HP stroke"),
        within=POSITIVE_LENGTH, unit="in"),
    Key("lp_connecting_rod", "length", "LP connecting rod, longer than the LP crank.",
        default=Derived("the HP connecting rod"), within=POSITIVE_LENGTH, unit="in"),
    Key("lp_piston_rod_diameter", "length", "LP piston rod diameter (zero or more).",
        default=Derived("the HP piston rod diameter"), within=ZERO_OR_MORE, unit="in"),
    Key("lp_clearance", "fraction", "LP clearance fraction, once or [head, crank].",
        default=Derived("the HP clearance"), ends=True),
    Key("lp_crank_angle", "angle", "How far the LP crank follows the HP crank.",
        default="90 deg", unit="deg"),
    Key("receiver_volume", "volume", "Receiver and passages between the cylinders, at least "
        "0.05 of the HP swept volume.", unit="ft3"),
)

COMPARE = group(
    "compare", "How corliss compare governs the engine by throttle and by cut-off.",
    Key("throttled_setting", "number", "The gear setting the throttled variant keeps, within "
        "the gear's setting range.", default=Derived("the study's default")),
    Key("setting_range", "number_pair", "[least, greatest] settings the cut-off governor "
        "may use, within the gear's.", default=Derived("the study's default")),
    Key("chest_volume", "volume", "Steam chest of both variants, when [supply] has none.",
        default=Derived("the study's default"), unit="ft3"),
    Key("pipe_diameter", "length", "Steam pipe of both variants, when [supply] has none.",
        default=Derived("the study's default"), within=POSITIVE_LENGTH, unit="in"),
)

FLYWHEEL = group(
    "flywheel", "The rotating train's inertia (transient runs): moment_of_inertia, or "
    "rim_weight with mean_radius.",
    Key("moment_of_inertia", "inertia", "Moment of inertia about the shaft.", default=None,
        within=INERTIA_RANGE, when="instead of rim_weight and mean_radius"),
    Key("rim_weight", "mass", "Mass of the rim (Marks Art. 61 sizes a flywheel by its rim).",
        default=None, within=RIM_MASS_RANGE, unit="lb", when="with mean_radius"),
    Key("mean_radius", "length", "Mean radius of the rim.", default=None,
        within=RIM_RADIUS_RANGE, unit="ft", when="with rim_weight"),
    Key("other_inertia", "inertia", "Inertia of the rest of the train, added.",
        default="0 kg m2"),
)

LOAD = group(
    "load", "The shaft load of a transient run: a reference torque or power and its "
    "schedule.",
    Key("torque", "torque", "Reference load torque (zero or more).", default=None,
        within=ZERO_OR_MORE, when="instead of power"),
    Key("power", "power", "Reference load power at the run's speed (zero or more).",
        default=None, within=ZERO_OR_MORE, unit="hp", when="instead of torque"),
    Key("speed_law", "choice", "How the load torque varies with speed (k = 0, 1, 2).",
        default="constant", choices=tuple(SPEED_LAWS)),
    Key("kind", "choice", "The schedule of the load fraction.", default="constant",
        choices=("constant", "step", "ramp", "schedule")),
    Key("initial_fraction", "number", "Load before the step or ramp, a fraction of the "
        "reference load: a step from 50 % to 80 % is initial_fraction = 0.5, step_fraction "
        "= 0.8; the engine starts settled at it.", default=1.0, within=(0.0, 5.0),
        when="with kind = \"step\" or \"ramp\""),
    Key("step_time", "time", "When the step comes (zero or more).", within=ZERO_OR_MORE,
        when="with kind = \"step\""),
    Key("step_fraction", "number", "Load after the step, a fraction of the reference load.",
        within=(0.0, 5.0), when="with kind = \"step\""),
    Key("ramp_start", "time", "When the ramp starts (zero or more).", within=ZERO_OR_MORE,
        when="with kind = \"ramp\""),
    Key("ramp_end", "time", "When the ramp ends, after its start.", when="with kind = \"ramp\""),
    Key("ramp_fraction", "number", "Load at the ramp's end, a fraction of the reference "
        "load.", within=(0.0, 5.0), when="with kind = \"ramp\""),
    Key("schedule", "string", "CSV file (relative to the scene) with columns time_s and "
        "load_fraction.", when="with kind = \"schedule\""),
)

#: The sections' groups by section name (``[valve_gear]``, ``[lp_valve_gear]`` and
#: ``[governor]`` take their type's keys; ``title`` is a string, not a table).
SECTION_KEYS = {g.name: g for g in (ENGINE, SUPPLY, EXHAUST, RUN, OUTPUT, COMPOUND, COMPARE,
                                    FLYWHEEL, LOAD)}
#: The key every ``[valve_gear]``, ``[lp_valve_gear]`` and ``[governor]`` table has.
TYPE_DOC = "The registry name of the {noun} (corliss list {plural})."
