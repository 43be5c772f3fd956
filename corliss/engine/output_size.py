"""How many rows a run's time series will hold, counted from its knobs before any work,
and the refusal of a run whose count is over the ceiling
(:data:`corliss.keys.limits.MAX_OUTPUT_SAMPLES`).

A steady run records every output step of every cycle it runs (``[run] record =
"degree"``, the default), or one row a cycle and its last cycle whole (``"cycle"``);
a run until periodic is counted at its most cycles, ``max_cycles`` (three times as
many with ``wall_heat``, whose walls settle over cycles of their own).  A transient
run records per turn every output step (``"degree"``), one row (``"cycle"``) or every
integrator step (``"step"``, counted as one an output step: on the load step of
``benchmarks/load_step.py`` the standard preset takes about 1,640 evaluations a turn,
some 270 steps of dopri5, under the 360 output steps of a degree); its turns are
counted at the run's speed over its longest time.  A card is one cycle of an end, at
most as many points as a cycle's output steps.
"""

from __future__ import annotations

import math

from corliss.engine.options import PRESETS, record_of
from corliss.errors import InputError
from corliss.keys import limits

#: Crank-angle step of the ideal-port (equilibrium) stepping [deg]: its time series
#: holds every point of that grid, whatever the output step.
EQUILIBRIUM_STEP_DEG = 0.25
#: A steady run with a wall whose deep temperature settles over periodic cycles of its
#: own (the skin model) may run this many times the fidelity's ``max_cycles``.
WALL_CYCLES_FACTOR = 3
#: Points of the equilibrium grid a turn beyond its uniform ones: the port areas' kinks,
#: a few a turn (eight events of two ends); counted generously.
EQUILIBRIUM_KINKS = 64
#: Rows a turn of the mean-value model's time series (it samples its solution 50 times a
#: turn, at least 2,000 times a run).
MEAN_VALUE_PER_TURN = 50
MEAN_VALUE_LEAST = 2000


def samples_per_cycle(run) -> int:
    """Rows of one cycle in a run's time series (and most points of a card).

    Parameters
    ----------
    run : RunSpec
        The scene's ``[run]``.

    Returns
    -------
    int
        Output steps of a turn plus one for a steady crank-resolved run or the ideal
        card, the equilibrium grid's points for the ideal-port models, the output steps
        of a turn for a transient one [-].
    """
    steps = int(round(360.0 / run.fidelity.output_step_deg))
    if run.mode == "transient":
        return steps
    equilibrium = (run.model == "ideal" and run.expansion != "hyperbolic") or (
        run.model == "crank_resolved" and not run.has("port_flow"))
    if equilibrium:
        return int(math.ceil(360.0 / EQUILIBRIUM_STEP_DEG)) + 1 + EQUILIBRIUM_KINKS
    return steps + 1


def output_samples(run) -> tuple[int, str]:
    """The most rows a run's time series will hold, and how they are counted.

    Parameters
    ----------
    run : RunSpec
        The scene's ``[run]``.

    Returns
    -------
    samples : int
        Rows of the time series at most [-].
    how : str
        The count in words, for a message (``"361 a cycle times 40 cycles"``).
    """
    per = samples_per_cycle(run)
    record = record_of(run)
    if run.mode == "transient":
        longest = (run.max_duration_s if run.until_settled and run.max_duration_s
                   else run.duration_s) or 0.0
        turns = max(int(math.ceil(longest * run.speed_rad_s / (2.0 * math.pi))), 1)
        if run.model == "mean_value":
            return (max(MEAN_VALUE_LEAST, MEAN_VALUE_PER_TURN * turns),
                    f"{MEAN_VALUE_PER_TURN} a turn times {turns} turns")
        if record == "cycle":
            return turns, f"one a turn times {turns} turns"
        return per * turns, f"{per} a turn ({record} record) times {turns} turns"
    if run.model == "ideal" and run.expansion == "hyperbolic":
        return per, f"{per} of the one cycle of the ideal card"
    if run.cycles is not None:
        cycles = run.cycles
    else:
        cycles = run.fidelity.max_cycles * (WALL_CYCLES_FACTOR if run.has("wall_heat") else 1)
    if record == "cycle":
        return cycles - 1 + per, (f"one a cycle for {cycles - 1} cycles and {per} of the "
                                  "last")
    return per * cycles, f"{per} a cycle times {cycles} cycles"


def check_output_samples(run, keys: dict[str, str] | None = None) -> None:
    """Refuse a run whose time series would hold more than
    :data:`~corliss.keys.limits.MAX_OUTPUT_SAMPLES` rows, before any work.

    Parameters
    ----------
    run : RunSpec
        The scene's ``[run]``.
    keys : dict of str to str, optional
        The name to give each knob in the message where it did not come from the scene
        (``{"cycles": "--cycles", "duration": "--duration"}``).

    Raises
    ------
    InputError
        Naming the knob that sets the count (``run.cycles``, ``run.max_cycles``,
        ``run.duration`` or ``run.max_duration``), its value, the count and what would
        do: fewer cycles or a shorter time, a fidelity of a coarser output step, or
        ``record = "cycle"``.
    """
    n, how = output_samples(run)
    if n <= limits.MAX_OUTPUT_SAMPLES:
        return
    names = {"cycles": "run.cycles", "max_cycles": "run.max_cycles",
             "duration": "run.duration", "max_duration": "run.max_duration",
             **(keys or {})}
    step = (f"the {run.fidelity.name} fidelity's output step of "
            f"{run.fidelity.output_step_deg:g} deg")
    if run.mode == "transient":
        if run.until_settled and run.max_duration_s:
            key, value = names["max_duration"], f"{run.max_duration_s:g} s"
        else:
            key, value = names["duration"], f"{run.duration_s:g} s"
        fewer = "a shorter time"
    elif run.cycles is not None:
        key, value, fewer = names["cycles"], run.cycles, "fewer cycles"
    else:
        key, value, fewer = names["max_cycles"], run.fidelity.max_cycles, "fewer max_cycles"
    coarser = ", ".join(f"{n} {f.output_step_deg:g} deg" for n, f in PRESETS.items())
    ways = fewer if run.model == "mean_value" else (
        f"{fewer}, a fidelity of a coarser output step ({coarser}), or run.record = "
        "\"cycle\"")
    raise InputError(key, value, f"a run whose time series holds at most "
                     f"{limits.MAX_OUTPUT_SAMPLES:,} rows; this one would hold {n:,} ({how}, "
                     f"{step}): {ways}")
