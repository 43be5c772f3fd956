"""The responses a study may record: numbers of a steady run's summary.

A response is a key of the summary (:class:`corliss.engine.result.SteadyResult`), a
nested one written with dots (``events.head.cutoff_frac``), whose value is a number.
Which keys a summary has depends on the scene (the effects it names, its wall model,
a jacket, a compound), so the valid keys are worked out from the base scene before any
run (:func:`response_keys`); a test holds this list to the summaries that runs
actually give.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from corliss.engine.model import build_lp_gear, lp_geometry_of, scene_events
from corliss.errors import InputError
from corliss.valves import events as valve_events

#: Responses of a study by default: power, mean effective pressure, steam and the
#: head end's cut-off.
DEFAULT_RESPONSES = ("indicated_power_W", "mep_mean_Pa", "steam_rate_kg_per_h",
                     "water_rate_kg_per_kWh", "events.head.cutoff_frac")

#: Keys of every steady summary (SteadyResult._make_summary and its crank effort).
BASE_KEYS = (
    "speed_rpm", "indicated_power_W", "indicated_power_hp", "indicated_work_J_per_cycle",
    "mep_head_Pa", "mep_crank_Pa", "mep_mean_Pa", "steam_per_cycle_kg",
    "steam_rate_kg_per_h", "water_rate_kg_per_kWh", "water_rate_lb_per_ihp_h",
    "peak_pressure_Pa", "supply_pressure_Pa", "exhaust_pressure_Pa", "cycles_simulated",
    "cycles_to_converge", "convergence_tolerance", "periodicity_residuals.work",
    "periodicity_residuals.mass", "periodicity_residuals.energy",
    "periodicity_residuals.mass_balance", "mass_balance_error", "energy_balance_error",
    "rhs_evaluations", "clamped_trial_evaluations_count",
    "clamped_hot_state_evaluations_count", "wall_time_s", "max_torque_N_m",
    "min_torque_N_m", "mean_torque_N_m", "energy_fluctuation_J",
    "fluctuation_coefficient_c")
FRICTION_KEYS = ("friction_torque_N_m", "friction_power_W", "friction_work_J_per_cycle",
                 "brake_power_W", "brake_power_hp", "mechanical_efficiency")
CHEST_KEYS = ("chest_pressure_mean_Pa", "chest_pressure_min_Pa")
COMPOUND_KEYS = ("hp_power_W", "lp_power_W", "lp_mep_head_Pa", "lp_mep_crank_Pa",
                 "receiver_pressure_mean_Pa", "receiver_pressure_min_Pa",
                 "receiver_pressure_max_Pa")
JACKET_KEYS = ("jacket_heat_W", "jacket_steam_kg_per_h", "water_rate_with_jacket_kg_per_kWh")
#: Per end with the wall-heat effect (``{end}`` head or crank, ``lp_`` ones too).
WALL_KEYS = ("heat_to_walls_{end}_J_per_cycle", "wall_temperature_{end}_K",
             "wet_fraction_at_cutoff_{end}", "card_missing_water_fraction_{end}",
             "missing_water_fraction_{end}", "missing_water_per_stroke_{end}_kg",
             "marks_missing_water_fraction_{end}")
#: Per end with the skin wall model, whose surface temperature is a state.
SKIN_KEYS = ("wall_surface_swing_{end}_K", "wall_surface_mean_{end}_K",
             "wet_fraction_at_cutoff_with_film_{end}",
             "heat_into_steam_admission_{end}_J", "heat_into_steam_expansion_{end}_J",
             "heat_into_steam_exhaust_{end}_J", "heat_into_steam_compression_{end}_J")


def flatten(summary: Mapping[str, Any], prefix: str = "") -> dict:
    """The summary's numbers by dotted key.

    Nested tables are joined with dots; text, lists and flags are left out; a null
    number is kept as None; a numpy scalar becomes a Python number.

    Parameters
    ----------
    summary : dict
        A run's summary (nested dicts).
    prefix : str, optional
        Prepended to every key (the dotted path of ``summary`` in its parent).

    Returns
    -------
    dict of str to (int, float or None)
        ``{dotted key: number}``, in the summary's order.
    """
    out = {}
    for k, v in summary.items():
        if isinstance(v, dict):
            out.update(flatten(v, f"{prefix}{k}."))
        elif v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)):
            out[prefix + k] = v
        elif hasattr(v, "dtype") and getattr(v, "ndim", 1) == 0 and v.dtype.kind in "fiu":
            out[prefix + k] = v.item()
    return out


def picked(summary: Mapping[str, Any], key: str):
    """One number of a summary by its dotted key, as :func:`flatten` gives it (without
    flattening the whole summary: a study's run reads a few keys of it).

    Parameters
    ----------
    summary : mapping
        A run's summary (nested dicts).
    key : str
        A dotted key (``events.head.cutoff_frac``).

    Returns
    -------
    int, float or None
        ``flatten(summary).get(key)``: the number (a numpy scalar as a Python one),
        None for a null, a key the summary lacks, or a value that is not a number.
    """
    node: Any = summary
    for name in key.split("."):
        if not isinstance(node, dict) or name not in node:
            return None
        node = node[name]
    if node is None or (isinstance(node, (int, float)) and not isinstance(node, bool)):
        return node
    if hasattr(node, "dtype") and getattr(node, "ndim", 1) == 0 and node.dtype.kind in "fiu":
        return node.item()
    return None


def response_keys(scene) -> tuple[str, ...]:
    """Every response a steady run of ``scene`` gives, in the summary's order.

    Parameters
    ----------
    scene : Scene
        The study's base scene (run steady).

    Returns
    -------
    tuple of str
        The dotted summary keys whose values are numbers, without repeats.
    """
    run = scene.run
    keys = list(BASE_KEYS)
    eng = scene.engine
    # a single-acting cylinder's idle end has no wall and no events
    ends = [e for e in ("head", "crank") if eng.steam_ends in ("both", e)]
    ends += ["lp_" + e for e in ends] if scene.compound is not None else []
    if run.has("leakage") and eng.leakage_model == "period":
        # each valve edge's leak (corliss.engine.leak_paths), per hour and of the steam
        paths = ([f"valve_leak_{e}" for e in ends] if eng.steam_edge_leak_rate_kg_s_Pa
                 else []) + ([f"valve_leak_{e}_exhaust" for e in ends]
                             if eng.exhaust_edge_leak_rate_kg_s_Pa else [])
        if paths:
            keys += ["valve_leakage_kg_per_h"] + (["valve_leakage_fraction_of_steam"]
                                                  if eng.steam_edge_leak_rate_kg_s_Pa else [])
        for path in paths:
            keys += [f"{path}_kg_per_h", f"leak_paths.{path}.fraction_of_steam"]
        if eng.valve_leak_rate_kg_s_Pa:
            keys += ["valve_leakage_kg_per_h", "valve_leak_exhaust_kg_per_h",
                     "valve_leakage_fraction_of_steam"]
            if scene.compound is not None:
                keys.append("valve_leak_receiver_kg_per_h")
        if eng.piston_leak_rate_kg_s_Pa:
            keys.append("piston_leakage_net_kg_per_cycle")
    elif run.has("leakage"):
        if eng.valve_leakage_area_m2:
            keys.append("valve_leakage_kg_per_h")
        if eng.piston_leakage_area_m2:
            keys.append("piston_leakage_net_kg_per_cycle")
    if run.has("wall_heat"):
        keys.append("missing_water_fraction_of_feed")
        for end in ends:
            keys += [k.format(end=end) for k in WALL_KEYS]
            if eng.wall_heat_model == "skin":
                keys += [k.format(end=end) for k in SKIN_KEYS]
        if eng.wall_heat_model == "skin":
            keys.append("periodicity_residuals.wall_temperature")
        if eng.jacket != "none":
            keys += list(JACKET_KEYS)
    if run.has("steam_chest"):
        keys += list(CHEST_KEYS)
    if run.has("friction"):
        keys += list(FRICTION_KEYS)
    if scene.compound is not None:
        keys += list(COMPOUND_KEYS)
    # the events a gear reports (a slide valve's overtravel, say) are found without a run
    keys += list(flatten({"events": scene_events(scene)}))
    if scene.compound is not None:
        lp_geo = lp_geometry_of(scene)
        assert lp_geo is not None       # a compound has its low-pressure cylinder
        keys += list(flatten({"lp_events": valve_events(build_lp_gear(scene),
                                                       lambda t: float(lp_geo.fraction(t)))}))
    return tuple(dict.fromkeys(keys))


def check_responses(responses, scene) -> tuple[str, ...]:
    """The responses a study records, checked against the scene's steady summary.

    Parameters
    ----------
    responses : sequence of str or str or None
        Dotted summary keys; None or empty for :data:`DEFAULT_RESPONSES` (those of
        them the scene gives).
    scene : Scene
        The study's base scene, made steady.

    Returns
    -------
    tuple of str
        The responses, in the order given, without repeats.

    Raises
    ------
    InputError
        Naming ``--response`` and the unknown key, and listing the valid ones.
    """
    valid = response_keys(scene)
    if responses is None or len(responses) == 0:
        responses = [k for k in DEFAULT_RESPONSES if k in valid]
    if isinstance(responses, str):
        responses = [responses]
    out = []
    for r in responses:
        if r not in valid:
            raise InputError("--response", r, "a number of this scene's steady summary: "
                             + ", ".join(valid))
        if r not in out:
            out.append(r)
    return tuple(out)


def response_value(value) -> float:
    """A response as a float.

    Parameters
    ----------
    value : float or int or None
        A number of a flattened summary.

    Returns
    -------
    float
        ``value`` as a float; NaN for a null (such as a water rate with no power).
    """
    if value is None:
        return math.nan
    return float(value)
