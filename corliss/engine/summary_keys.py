"""The keys of a run's summary, each with its type: :class:`SteadySummary` and
:class:`TransientSummary`.

A summary is a JSON object (SI unless a key names its unit).  Its keys are a finite set:
the contract's keys, those of the effects a scene asks for (friction, leakage, wall heat,
a jacket), and the per-end keys written for each end of each cylinder, ``head`` and
``crank`` of the first, ``c2_head`` ... ``c6_crank`` of further identical cylinders
(:func:`~corliss.engine.network.cylinder_prefix`, at most six, ``scene.engine.cylinders``)
and ``lp_head``, ``lp_crank`` of a compound's low-pressure cylinder.  Every key is
optional (``total=False``): which appear depends on the scene.  Code that reads a
per-end key by its end goes through :func:`end_value`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Literal, TypedDict, cast

__all__ = ["SteadySummary", "TransientSummary", "SummaryEnd", "end_value", "END_NAMES"]

#: The ends whose keys a summary can hold: both ends of each cylinder.
SummaryEnd = Literal[
    "head", "crank", "c2_head", "c2_crank", "c3_head", "c3_crank",
    "c4_head", "c4_crank", "c5_head", "c5_crank", "c6_head", "c6_crank",
    "lp_head", "lp_crank"]

#: Every value of :data:`SummaryEnd`, in order.
END_NAMES: tuple[SummaryEnd, ...] = (
    "head", "crank", "c2_head", "c2_crank", "c3_head", "c3_crank",
    "c4_head", "c4_crank", "c5_head", "c5_crank", "c6_head", "c6_crank",
    "lp_head", "lp_crank")


class SteadySummary(TypedDict, total=False):
    """The summary of a steady run (:attr:`corliss.engine.result.SteadyResult.summary`).

    SI unless a key names its unit; ``_frac`` and names without a unit are fractions
    [-].  Which keys appear depends on the scene (see the module's docstring).
    """

    # the run
    title: str
    kind: str                               # "steady"
    model: str                              # "crank_resolved", "ideal", ...
    effects: list[str]                      # the physical effects the run included
    fidelity: str                           # the fidelity preset's name
    property_tier: str                      # the steam properties: "table" or "heos"
    speed_rpm: float
    # power, work and steam
    indicated_power_W: float
    indicated_power_hp: float
    indicated_work_J_per_cycle: float
    mep_head_Pa: float                      # mean effective pressure of the head end
    mep_crank_Pa: float                     # ... of the crank end
    mep_mean_Pa: float                      # over all cylinders (a compound's on its LP)
    steam_per_cycle_kg: float               # steam from the supply in one cycle
    steam_rate_kg_per_h: float
    water_rate_kg_per_kWh: float | None     # None when the card does no work
    water_rate_lb_per_ihp_h: float | None   # None when the card does no work
    peak_pressure_Pa: float                 # highest pressure on any card
    supply_pressure_Pa: float               # the chest's
    exhaust_pressure_Pa: float
    # convergence and balances
    cycles_simulated: int
    cycles_to_converge: int | None          # None when the cycle count is fixed
    convergence_tolerance: float            # relative change of the state per cycle [-]
    periodicity_residuals: dict[str, float]  # state name to its relative residual [-]
    # only where a skin wall's deep wall has no periodic state (corliss.engine.wall.WallJump):
    # "none: the balance jumps", and each such end's band [K] and balances at its edges [J]
    wall_periodic_state: str
    wall_balance_jumps: list[dict[str, str | float]]
    mass_balance_error: float | None        # |supply + exhaust| / supply [-]
    energy_balance_error: float | None      # first-law residual / supply enthalpy [-]
    rhs_evaluations: int                    # right-hand-side evaluations of the ODE
    clamped_trial_evaluations_count: int | None  # trial states clamped to the table
    clamped_hot_state_evaluations_count: int | None  # visited states past its top
    wall_time_s: float                      # computing time
    # crank effort (Marks Art. 57)
    max_torque_N_m: float
    min_torque_N_m: float
    mean_torque_N_m: float
    energy_fluctuation_J: float             # largest excess of work over the mean's
    fluctuation_coefficient_c: float | None  # of one stroke's work; None without work
    fluctuation_coefficient_note: str       # why the coefficient is None
    # friction
    friction_torque_N_m: float
    friction_power_W: float
    friction_work_J_per_cycle: float
    brake_power_W: float
    brake_power_hp: float
    mechanical_efficiency: float | None     # brake / indicated; None without work
    # leakage
    valve_leakage_kg_per_h: float           # past every valve path
    valve_leakage_fraction_of_steam: float  # the leak leaving the steam side / supply
    piston_leakage_net_kg_per_cycle: float  # head end to crank end, net
    valve_leak_exhaust_kg_per_h: float      # the period's law: chest to exhaust
    valve_leak_receiver_kg_per_h: float     # a compound's HP valve into the receiver
    valve_leak_head_kg_per_h: float  # valve into the end
    valve_leak_crank_kg_per_h: float
    valve_leak_c2_head_kg_per_h: float
    valve_leak_c2_crank_kg_per_h: float
    valve_leak_c3_head_kg_per_h: float
    valve_leak_c3_crank_kg_per_h: float
    valve_leak_c4_head_kg_per_h: float
    valve_leak_c4_crank_kg_per_h: float
    valve_leak_c5_head_kg_per_h: float
    valve_leak_c5_crank_kg_per_h: float
    valve_leak_c6_head_kg_per_h: float
    valve_leak_c6_crank_kg_per_h: float
    valve_leak_lp_head_kg_per_h: float      # a compound LP's valve, receiver into the end
    valve_leak_lp_crank_kg_per_h: float
    # the period's law past each closed exhaust edge, the end to the exhaust
    valve_leak_head_exhaust_kg_per_h: float
    valve_leak_crank_exhaust_kg_per_h: float
    valve_leak_c2_head_exhaust_kg_per_h: float
    valve_leak_c2_crank_exhaust_kg_per_h: float
    valve_leak_c3_head_exhaust_kg_per_h: float
    valve_leak_c3_crank_exhaust_kg_per_h: float
    valve_leak_c4_head_exhaust_kg_per_h: float
    valve_leak_c4_crank_exhaust_kg_per_h: float
    valve_leak_c5_head_exhaust_kg_per_h: float
    valve_leak_c5_crank_exhaust_kg_per_h: float
    valve_leak_c6_head_exhaust_kg_per_h: float
    valve_leak_c6_crank_exhaust_kg_per_h: float
    valve_leak_lp_head_exhaust_kg_per_h: float
    valve_leak_lp_crank_exhaust_kg_per_h: float
    # every leak path by name (valve_leak_<...>, <cylinder>piston_leak): kg_per_cycle
    # [kg] (from end a to end b, net), kg_per_h [kg/h], fraction_of_steam (of the
    # steam supplied) [-]
    leak_paths: dict[str, dict[str, float]]
    # the steam chest
    chest_pressure_mean_Pa: float
    chest_pressure_min_Pa: float
    # several cylinders
    cylinder_powers_W: list[float]          # each identical cylinder's indicated power
    hp_power_W: float                       # a compound's high-pressure cylinder
    lp_power_W: float                       # ... its low-pressure cylinder
    lp_mep_head_Pa: float                   # the LP cylinder's mean effective pressures
    lp_mep_crank_Pa: float
    receiver_pressure_mean_Pa: float
    receiver_pressure_min_Pa: float
    receiver_pressure_max_Pa: float
    # wall heat and initial condensation (Marks Art. 74), per end:
    # heat_to_walls: heat the steam gave the walls over a cycle [J];
    # wall_temperature: the wall's (one-node model) or None; wall_surface_*: the skin
    # model's surface temperature over the cycle; heat_into_steam_<phase>: heat into the
    # steam from admission to cut-off, cut-off to release, release to compression,
    # compression to admission; wet_fraction_at_cutoff(_with_film): water in the
    # contents at cut-off (with the wall's film); missing_water_fraction: steam supplied
    # less steam held at cut-off, of the steam supplied; card_missing_water_fraction:
    # the same read from the card; marks_missing_water_fraction: Marks eq. 221's
    # prediction for that card; missing_water_per_stroke: condensation per stroke
    heat_to_walls_head_J_per_cycle: float
    wall_temperature_head_K: float | None
    wall_surface_swing_head_K: float
    wall_surface_mean_head_K: float
    heat_into_steam_admission_head_J: float
    heat_into_steam_expansion_head_J: float
    heat_into_steam_exhaust_head_J: float
    heat_into_steam_compression_head_J: float
    wet_fraction_at_cutoff_head: float
    wet_fraction_at_cutoff_with_film_head: float
    card_missing_water_fraction_head: float
    missing_water_fraction_head: float
    missing_water_per_stroke_head_kg: float
    marks_missing_water_fraction_head: float
    heat_to_walls_crank_J_per_cycle: float
    wall_temperature_crank_K: float | None
    wall_surface_swing_crank_K: float
    wall_surface_mean_crank_K: float
    heat_into_steam_admission_crank_J: float
    heat_into_steam_expansion_crank_J: float
    heat_into_steam_exhaust_crank_J: float
    heat_into_steam_compression_crank_J: float
    wet_fraction_at_cutoff_crank: float
    wet_fraction_at_cutoff_with_film_crank: float
    card_missing_water_fraction_crank: float
    missing_water_fraction_crank: float
    missing_water_per_stroke_crank_kg: float
    marks_missing_water_fraction_crank: float
    heat_to_walls_c2_head_J_per_cycle: float
    wall_temperature_c2_head_K: float | None
    wall_surface_swing_c2_head_K: float
    wall_surface_mean_c2_head_K: float
    heat_into_steam_admission_c2_head_J: float
    heat_into_steam_expansion_c2_head_J: float
    heat_into_steam_exhaust_c2_head_J: float
    heat_into_steam_compression_c2_head_J: float
    wet_fraction_at_cutoff_c2_head: float
    wet_fraction_at_cutoff_with_film_c2_head: float
    card_missing_water_fraction_c2_head: float
    missing_water_fraction_c2_head: float
    missing_water_per_stroke_c2_head_kg: float
    marks_missing_water_fraction_c2_head: float
    heat_to_walls_c2_crank_J_per_cycle: float
    wall_temperature_c2_crank_K: float | None
    wall_surface_swing_c2_crank_K: float
    wall_surface_mean_c2_crank_K: float
    heat_into_steam_admission_c2_crank_J: float
    heat_into_steam_expansion_c2_crank_J: float
    heat_into_steam_exhaust_c2_crank_J: float
    heat_into_steam_compression_c2_crank_J: float
    wet_fraction_at_cutoff_c2_crank: float
    wet_fraction_at_cutoff_with_film_c2_crank: float
    card_missing_water_fraction_c2_crank: float
    missing_water_fraction_c2_crank: float
    missing_water_per_stroke_c2_crank_kg: float
    marks_missing_water_fraction_c2_crank: float
    heat_to_walls_c3_head_J_per_cycle: float
    wall_temperature_c3_head_K: float | None
    wall_surface_swing_c3_head_K: float
    wall_surface_mean_c3_head_K: float
    heat_into_steam_admission_c3_head_J: float
    heat_into_steam_expansion_c3_head_J: float
    heat_into_steam_exhaust_c3_head_J: float
    heat_into_steam_compression_c3_head_J: float
    wet_fraction_at_cutoff_c3_head: float
    wet_fraction_at_cutoff_with_film_c3_head: float
    card_missing_water_fraction_c3_head: float
    missing_water_fraction_c3_head: float
    missing_water_per_stroke_c3_head_kg: float
    marks_missing_water_fraction_c3_head: float
    heat_to_walls_c3_crank_J_per_cycle: float
    wall_temperature_c3_crank_K: float | None
    wall_surface_swing_c3_crank_K: float
    wall_surface_mean_c3_crank_K: float
    heat_into_steam_admission_c3_crank_J: float
    heat_into_steam_expansion_c3_crank_J: float
    heat_into_steam_exhaust_c3_crank_J: float
    heat_into_steam_compression_c3_crank_J: float
    wet_fraction_at_cutoff_c3_crank: float
    wet_fraction_at_cutoff_with_film_c3_crank: float
    card_missing_water_fraction_c3_crank: float
    missing_water_fraction_c3_crank: float
    missing_water_per_stroke_c3_crank_kg: float
    marks_missing_water_fraction_c3_crank: float
    heat_to_walls_c4_head_J_per_cycle: float
    wall_temperature_c4_head_K: float | None
    wall_surface_swing_c4_head_K: float
    wall_surface_mean_c4_head_K: float
    heat_into_steam_admission_c4_head_J: float
    heat_into_steam_expansion_c4_head_J: float
    heat_into_steam_exhaust_c4_head_J: float
    heat_into_steam_compression_c4_head_J: float
    wet_fraction_at_cutoff_c4_head: float
    wet_fraction_at_cutoff_with_film_c4_head: float
    card_missing_water_fraction_c4_head: float
    missing_water_fraction_c4_head: float
    missing_water_per_stroke_c4_head_kg: float
    marks_missing_water_fraction_c4_head: float
    heat_to_walls_c4_crank_J_per_cycle: float
    wall_temperature_c4_crank_K: float | None
    wall_surface_swing_c4_crank_K: float
    wall_surface_mean_c4_crank_K: float
    heat_into_steam_admission_c4_crank_J: float
    heat_into_steam_expansion_c4_crank_J: float
    heat_into_steam_exhaust_c4_crank_J: float
    heat_into_steam_compression_c4_crank_J: float
    wet_fraction_at_cutoff_c4_crank: float
    wet_fraction_at_cutoff_with_film_c4_crank: float
    card_missing_water_fraction_c4_crank: float
    missing_water_fraction_c4_crank: float
    missing_water_per_stroke_c4_crank_kg: float
    marks_missing_water_fraction_c4_crank: float
    heat_to_walls_c5_head_J_per_cycle: float
    wall_temperature_c5_head_K: float | None
    wall_surface_swing_c5_head_K: float
    wall_surface_mean_c5_head_K: float
    heat_into_steam_admission_c5_head_J: float
    heat_into_steam_expansion_c5_head_J: float
    heat_into_steam_exhaust_c5_head_J: float
    heat_into_steam_compression_c5_head_J: float
    wet_fraction_at_cutoff_c5_head: float
    wet_fraction_at_cutoff_with_film_c5_head: float
    card_missing_water_fraction_c5_head: float
    missing_water_fraction_c5_head: float
    missing_water_per_stroke_c5_head_kg: float
    marks_missing_water_fraction_c5_head: float
    heat_to_walls_c5_crank_J_per_cycle: float
    wall_temperature_c5_crank_K: float | None
    wall_surface_swing_c5_crank_K: float
    wall_surface_mean_c5_crank_K: float
    heat_into_steam_admission_c5_crank_J: float
    heat_into_steam_expansion_c5_crank_J: float
    heat_into_steam_exhaust_c5_crank_J: float
    heat_into_steam_compression_c5_crank_J: float
    wet_fraction_at_cutoff_c5_crank: float
    wet_fraction_at_cutoff_with_film_c5_crank: float
    card_missing_water_fraction_c5_crank: float
    missing_water_fraction_c5_crank: float
    missing_water_per_stroke_c5_crank_kg: float
    marks_missing_water_fraction_c5_crank: float
    heat_to_walls_c6_head_J_per_cycle: float
    wall_temperature_c6_head_K: float | None
    wall_surface_swing_c6_head_K: float
    wall_surface_mean_c6_head_K: float
    heat_into_steam_admission_c6_head_J: float
    heat_into_steam_expansion_c6_head_J: float
    heat_into_steam_exhaust_c6_head_J: float
    heat_into_steam_compression_c6_head_J: float
    wet_fraction_at_cutoff_c6_head: float
    wet_fraction_at_cutoff_with_film_c6_head: float
    card_missing_water_fraction_c6_head: float
    missing_water_fraction_c6_head: float
    missing_water_per_stroke_c6_head_kg: float
    marks_missing_water_fraction_c6_head: float
    heat_to_walls_c6_crank_J_per_cycle: float
    wall_temperature_c6_crank_K: float | None
    wall_surface_swing_c6_crank_K: float
    wall_surface_mean_c6_crank_K: float
    heat_into_steam_admission_c6_crank_J: float
    heat_into_steam_expansion_c6_crank_J: float
    heat_into_steam_exhaust_c6_crank_J: float
    heat_into_steam_compression_c6_crank_J: float
    wet_fraction_at_cutoff_c6_crank: float
    wet_fraction_at_cutoff_with_film_c6_crank: float
    card_missing_water_fraction_c6_crank: float
    missing_water_fraction_c6_crank: float
    missing_water_per_stroke_c6_crank_kg: float
    marks_missing_water_fraction_c6_crank: float
    heat_to_walls_lp_head_J_per_cycle: float
    wall_temperature_lp_head_K: float | None
    wall_surface_swing_lp_head_K: float
    wall_surface_mean_lp_head_K: float
    heat_into_steam_admission_lp_head_J: float
    heat_into_steam_expansion_lp_head_J: float
    heat_into_steam_exhaust_lp_head_J: float
    heat_into_steam_compression_lp_head_J: float
    wet_fraction_at_cutoff_lp_head: float
    wet_fraction_at_cutoff_with_film_lp_head: float
    card_missing_water_fraction_lp_head: float
    missing_water_fraction_lp_head: float
    missing_water_per_stroke_lp_head_kg: float
    marks_missing_water_fraction_lp_head: float
    heat_to_walls_lp_crank_J_per_cycle: float
    wall_temperature_lp_crank_K: float | None
    wall_surface_swing_lp_crank_K: float
    wall_surface_mean_lp_crank_K: float
    heat_into_steam_admission_lp_crank_J: float
    heat_into_steam_expansion_lp_crank_J: float
    heat_into_steam_exhaust_lp_crank_J: float
    heat_into_steam_compression_lp_crank_J: float
    wet_fraction_at_cutoff_lp_crank: float
    wet_fraction_at_cutoff_with_film_lp_crank: float
    card_missing_water_fraction_lp_crank: float
    missing_water_fraction_lp_crank: float
    missing_water_per_stroke_lp_crank_kg: float
    marks_missing_water_fraction_lp_crank: float
    missing_water_fraction_of_feed: float   # the HP cylinders' together (Willans 1888)
    # the steam jacket (Marks Art. 79)
    jacket_heat_W: float
    jacket_steam_kg_per_h: float
    water_rate_with_jacket_kg_per_kWh: float | None  # jacket's water with the feed
    # the valve events and the verdict
    events: dict[str, dict[str, float | None]]  # each end's valve events [deg], [-], [m]
    lp_events: dict[str, dict[str, float | None]]  # a compound's LP cylinder's
    failures: list[dict[str, str]]          # how the completed run failed physically


class TransientSummary(TypedDict, total=False):
    """The summary of a transient run (:attr:`corliss.engine.result.TransientResult.summary`).

    SI unless a key names its unit.  The steady contract's keys (``indicated_power_W``,
    ``mep_head_Pa``, ...) are the run's final state, over its final turns.
    """

    # the run
    title: str
    kind: str                               # "transient"
    mode: str                               # "transient"
    model: str                              # "crank_resolved" or "mean_value"
    effects: list[str]
    fidelity: str
    property_tier: str
    initial_speed_rpm: float
    duration_s: float | None                # None for a run until settled
    simulated_s: float                      # the time the run reached
    turns: int                              # turns simulated
    flywheel_inertia_kg_m2: float
    load_torque_N_m: float                  # the load's torque at the start
    load_kind: str                          # the load's schedule: "constant", "step", ...
    load_speed_law: str                     # how the load's torque varies with speed
    step_time_s: float | None               # when the load changes; None without a change
    governor: dict[str, object] | None      # type, acts_on, z_at_start; None without
    start: dict[str, object] | None         # the governed start's operating point
    until_settled: bool
    record: str | None                      # what the time series records
    stalled: bool
    # the speed's response (corliss.engine.speed_metrics)
    final_speed_rpm: float
    settled: bool
    settled_swing_frac: float | None
    hunting: bool
    hunting_period_s: float | None
    governor_swing_frac: float              # the governor's swing while hunting
    hunting_read_from: str | None           # "crank_angle" or "turn_means"
    speed_before_rpm: float | None
    settled_before: bool
    regulation_frac: float | None
    max_deviation_rpm: float | None
    max_deviation_frac: float | None
    time_of_max_deviation_s: float | None   # after the step
    settling_time_s: float | None           # after the step
    final_indicated_power_W: float
    final_steam_rate_kg_per_h: float
    # the steady contract's keys, for the final state
    indicated_power_W: float
    indicated_power_hp: float
    steam_rate_kg_per_h: float
    water_rate_kg_per_kWh: float | None
    water_rate_lb_per_ihp_h: float | None
    mep_head_Pa: float | None               # from the last turn's card; None without
    mep_crank_Pa: float | None              # pressures recorded
    mep_mean_Pa: float
    # the computation
    clamped_trial_evaluations_count: int | None
    clamped_hot_state_evaluations_count: int | None
    rhs_evaluations: int
    wall_time_s: float
    failures: list[dict[str, str]]


def end_value(summary: SteadySummary | TransientSummary, quantity: str, end: SummaryEnd,
              unit: str = "") -> float | None:
    """The number under a per-end key, ``<quantity>_<end>_<unit>`` (``"mep"``,
    ``"head"``, ``"Pa"`` read ``mep_head_Pa``), or None where the summary has none.

    The per-end keys are declared one by one in :class:`SteadySummary` and
    :class:`TransientSummary` (each a number, or None where the run could not measure
    it); a key made from its parts is not a literal a type checker can follow, so this
    is the one place that reads such a key.

    Parameters
    ----------
    summary : SteadySummary or TransientSummary
        A run's summary.
    quantity : str
        The key's name before the end.
    end : str
        The end, with its cylinder's prefix (:data:`END_NAMES`).
    unit : str, optional
        The key's unit after the end (none for a fraction).

    Returns
    -------
    float or None
        The value; None when the key is absent (the scene's effects do not make it) or
        its value is None.

    Raises
    ------
    TypeError
        When the key holds something other than a number (a key that is not per-end).
    """
    key = f"{quantity}_{end}" + (f"_{unit}" if unit else "")
    value = cast("Mapping[str, object]", summary).get(key)
    if value is None or isinstance(value, float):
        return value
    if isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    raise TypeError(f"summary key {key!r} holds {type(value).__name__}, not a number")
