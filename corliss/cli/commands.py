"""The ``corliss`` command.

``corliss run [SCENE] [--out DIR] [--json] [--no-plots] [--units US|SI]``
    Simulate a scene (a file, or a bundled scene by name; the default without SCENE);
    write the CSVs with their meta files, the figures and the summary JSON, all or
    nothing; print a short summary, or the summary as JSON with ``--json``.
    ``--from-meta FILE`` reruns the run a meta file records.
``corliss events SCENE [--json] [--settings 0,0.5,1]``
    The valve events of each end, without simulating; at several gear settings.
``corliss gear SCENE [--out DIR]``
    Valve travel, port openings and the Zeuner diagram, as PNG.
``corliss animate SCENE [--out DIR] [--frames N] [--format gif|html] [--no-card] [--fidelity F]``
    The gear in motion (its linkage from the exact solve, the valve over its ports,
    the port openings and the card traced as the crank turns), as GIF or HTML.
``corliss design [SCENE] --cutoff F [--lead Q --max-opening Q ...] [--release F | --compression F | --exhaust-lap Q] [--equalise cutoff|laps] [--out DIR] [--json]``
    A plain slide valve (eccentricity, advance, laps per end), or a gear's setting,
    for the events asked; writes ``SCENE.design.toml`` (runnable, in one unit system,
    the source's comments kept) and its diagrams.
``corliss sweep SCENE [--settings 0,0.5,1] [--throttle 0.2,0.6,1] [--fidelity F] [--json] [--out DIR]``
    Steady cards across the load range at each gear setting and/or throttle opening:
    a CSV with its meta file and the Willans lines as PNG.
``corliss compare SCENE [--loads 0.1:1.1:0.1] [--with-condensation both|on|off] [--fidelity F] [--jobs N] [--json] [--out DIR]``
    Throttling against cut-off governing of one engine across its load range, with
    and without condensation: the table (CSV with its meta), the Willans lines and
    steam rates (PNG), and a verdict printed: which governing uses less steam where.
``corliss study SCENE --vary KEY=LOW:HIGH ... (--grid [--levels N] | --lhs N | --monte-carlo N) [--response KEY] [--jobs N | --scheduler ADDR] [--json] [--out DIR] [--resume]``
    Steady runs over a design of scene keys: one tidy table (CSV with its meta, and
    Parquet), the base scene, the figure of responses against keys.
``corliss fit SCENE CARD.csv --vary KEY=LOW:HIGH ... [--refine] [--bootstrap N] [--out DIR]``
    Calibrate scene keys to a measured card by least squares: the fitted values with
    their standard errors (or that the card does not determine a key),
    ``SCENE.fit.json``, the runnable ``SCENE.fit.toml`` and the measured card over
    the fitted one (``SCENE.fit.card.png``).
``corliss bench [--repeats N] [--out DIR]``
    The accuracy-versus-time study of ``benchmarks/`` (from a source checkout).
``corliss workbench [SCENE] [--port N] [--no-browser] [--fidelity F]``
    A local page (127.0.0.1) to set the gear, speed, steam and clearance by hand and
    watch the card, the events, the Zeuner diagram and the port openings redrawn
    (needs ``corliss[workbench]``; every asset served locally).
``corliss list scenes|gears|effects|governors``
    What the package holds.
``corliss list keys GEAR_OR_GOVERNOR``
    A gear's or governor's scene keys: kind, units, default, range, what each is.
``corliss explain KEY``
    A scene key (``valve_gear.lap``, ``governor.ball_mass``, ``run.effects``), section,
    gear, governor or effect, as the scene reference (``docs/scene-reference.md``) has it.

Exit statuses (``docs/exit-codes.md``): 0 a good result; 1 an error in corliss itself
(a traceback); 2 a user's mistake (scene, options, an unusable output folder), with a
one-paragraph message, no traceback, nothing simulated and nothing written; 3 a steady
run whose mass or energy balance does not close, its files written; 4 a run that
completed but failed physically (negative work, not periodic, stalled, run away,
hunting, not settled when ``--until-settled`` was asked), every file written and the
reasons in the summary's ``failures`` and on stderr; 5 a run that stopped before its
end, nothing written; 130 and 143 interrupted or terminated.  Messages go through the ``corliss`` logger: once-per-machine notices
(compiling the kernels, building the steam table) by default, everything with ``-v``;
other libraries' logs stay quiet.  While such a step runs, a line says what it is doing
and for how long (:mod:`corliss.cli.heartbeat`), so a first run is never silent for long.
Runs that take more than a couple of seconds show a progress line on a terminal.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import logging
import math
import os
import signal
import sys
import threading
import time
import tomllib
from pathlib import Path

import corliss
from corliss.cli.heartbeat import Heartbeat
from corliss.engine import first_run
from corliss.engine.balance import balance_failure
from corliss.engine.model import build_gear, scene_events
from corliss.engine.output_size import check_output_samples
from corliss.engine.simulate import simulate
from corliss.engine.verdict import EXIT_PHYSICAL
from corliss.errors import (EXIT_BALANCE_FAILED, EXIT_INTERRUPTED, EXIT_TERMINATED, InputError,
                            RunError, StudyStopped, Terminated)
from corliss.files.run_output import (OutputFiles, output_stem, plain_name, plain_text,
                                      scene_from_meta, summary_json)
from corliss.frames.columns import convert_record
from corliss.keys import limits, units
from corliss.logs import NOTICE
from corliss.progress import ProgressBar, TqdmHandler
from corliss.scene.loader import bundled_scenes, default_scene_path, find_scene, load_scene
from corliss.studies.journal import check_writable

log = logging.getLogger("corliss")


def _governed_scene():
    """The bundled governed scene whose transient turn a first run's background process
    compiles (:data:`corliss.engine.first_run.TRANSIENT_SCENE`): the command line's
    first run leaves the transient loop compiled too."""
    return load_scene(find_scene(first_run.TRANSIENT_SCENE))


first_run.transient_probe = _governed_scene

#: Exit statuses (``docs/exit-codes.md``).  1 is left to Python: an error in corliss
#: itself, with its traceback.
EXIT_OK = 0
#: A mistake in the input (scene, options, an unusable output folder): nothing was
#: simulated and nothing written.  argparse's own mistakes exit 2 too.
EXIT_INPUT = 2
#: The run stopped before its end (:class:`~corliss.errors.RunError`): nothing written.
#: (3 is a steady run whose balances do not close, EXIT_BALANCE_FAILED; 4 a run that
#: completed but failed physically, EXIT_PHYSICAL; 130 and 143 an interrupt.)
EXIT_RUN_STOPPED = 5


def _load(path: str | None, units_system: str | None = None):
    scene = load_scene(find_scene(path) if path is not None else default_scene_path())
    plain_name(scene.name, "scene")     # the stem of every file written, checked before work
    if units_system is not None:
        scene = dataclasses.replace(scene, output=dataclasses.replace(scene.output,
                                                                      units=units_system))
    return scene


def output_dir(args, scene) -> Path:
    """The output folder of a command (``--out``, or the scene's ``[output] dir``),
    checked before any work: every part of it that exists is a folder, and the deepest
    existing one can be written into (so a simulation never ends in a traceback about
    its folder).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options (``out``).
    scene : Scene
        The scene (its ``output.dir``).

    Returns
    -------
    Path
        The folder.

    Raises
    ------
    InputError
        Naming ``--out`` (or ``output.dir``) when a part of the path is a file or the
        folder cannot be made or written.
    """
    given = getattr(args, "out", None)
    key, value = ("--out", given) if given is not None else ("output.dir", scene.output.dir)
    out = Path(value)
    d = out.absolute()
    while not d.exists():
        if d.is_symlink():
            raise InputError(key, value, f"a folder that can be made ({d} is a broken link)")
        d = d.parent
    if not d.is_dir():
        raise InputError(key, value, f"a folder ({d} is a file)")
    if not os.access(d, os.W_OK | os.X_OK):
        raise InputError(key, value, f"a folder this user can write into ({d} is read-only)")
    return out


def _fmt(v, unit, digits=4):
    return "never" if v is None else f"{v:.{digits}g} {unit}"


def print_steady(result, files) -> None:
    """Print the short account of a steady run to standard output.

    Power, m.e.p., steam, condensation, each end's events, the cycles run and the
    files written, in the scene's units.

    Parameters
    ----------
    result : SteadyResult
        The run.
    files : dict of str to Path
        ``{kind: path}`` of the files written, listed last.
    """
    s = result.summary
    us = result.scene.output.units == "US"
    P = units.to_unit
    print(f"{s['title']}")
    print(f"  model {s['model']}, effects {', '.join(s['effects']) or 'none'}, "
          f"fidelity {s['fidelity']}, {s['speed_rpm']:.1f} rpm")
    if us:
        print(f"  indicated power  {s['indicated_power_hp']:.2f} ihp")
        print(f"  m.e.p.           head {P(s['mep_head_Pa'], 'psia'):.2f}, crank "
              f"{P(s['mep_crank_Pa'], 'psia'):.2f}, mean {P(s['mep_mean_Pa'], 'psia'):.2f} psi")
        wr = s["water_rate_lb_per_ihp_h"]
        print(f"  steam            {s['steam_rate_kg_per_h'] / units.POUND_kg:.1f} lb/h, "
              f"{_fmt(wr, 'lb per ihp-hour')}")
    else:
        print(f"  indicated power  {s['indicated_power_W'] / 1e3:.2f} kW")
        print(f"  m.e.p.           head {s['mep_head_Pa'] / 1e5:.3f}, crank "
              f"{s['mep_crank_Pa'] / 1e5:.3f}, mean {s['mep_mean_Pa'] / 1e5:.3f} bar")
        print(f"  steam            {s['steam_rate_kg_per_h']:.1f} kg/h, "
              f"{_fmt(s['water_rate_kg_per_kWh'], 'kg/kWh')}")
    _print_walls(s, us)
    for end, ev in s["events"].items():
        print(f"  {end:5s} end        cut-off {_fmt(ev['cutoff_frac'], '', 3)}, release "
              f"{_fmt(ev['release_frac'], '', 3)}, compression {_fmt(ev['compression_frac'], '', 3)}"
              " (fractions of stroke)")
    if s["fluctuation_coefficient_c"] is None:
        print("  crank effort     fluctuation coefficient undefined: the card does no net work")
    conv = s["cycles_to_converge"]
    res = s.get("periodicity_residuals") or {}
    fixed = result.scene.run.cycles is not None
    print(f"  cycles           {s['cycles_simulated']} simulated"
          + (f", periodic after {conv}" if conv else
             "" if fixed or not res else
             f", NOT periodic (largest residual {max(res.values()):.2g}, tolerance "
             f"{s['convergence_tolerance']:.2g})") + f"; {s['wall_time_s']:.2f} s")
    _print_files(files)


def _print_walls(s: dict, us: bool) -> None:
    """Initial condensation and the jacket's steam, when the walls exchange heat."""
    if "valve_leakage_fraction_of_steam" in s:
        leak = s["valve_leakage_kg_per_h"]
        print(f"  valve leakage    "
              + (f"{leak / units.POUND_kg:.1f} lb/h" if us else f"{leak:.1f} kg/h")
              + f", {s['valve_leakage_fraction_of_steam']:.3f} of the steam")
    ends = [e for e in ("head", "crank") if s.get(f"missing_water_fraction_{e}") is not None]
    if ends:
        print("  missing water    " + ", ".join(f"{s[f'missing_water_fraction_{e}']:.3f}"
                                              for e in ends)
              + f" of the steam at cut-off ({', '.join(ends)})")
    if s.get("missing_water_fraction_of_feed") is not None:
        print(f"  of the feed      {s['missing_water_fraction_of_feed']:.3f} missing at "
              "cut-off (condensation and leakage)")
    if "jacket_steam_kg_per_h" in s:
        wr = s["water_rate_with_jacket_kg_per_kWh"]
        if us:
            print(f"  jacket           {s['jacket_steam_kg_per_h'] / units.POUND_kg:.1f} lb/h of "
                  "steam; with it "
                  + _fmt(None if wr is None else wr / units.POUND_kg * units.HP_W / 1e3,
                         "lb per ihp-hour"))
        else:
            print(f"  jacket           {s['jacket_steam_kg_per_h']:.1f} kg/h of steam; with "
                  f"it {_fmt(wr, 'kg/kWh')}")


def print_transient(result, files) -> None:
    """Print the short account of a transient run to standard output.

    The governor, final speed and power, the start, the load step's regulation,
    largest change and settling, and any hunting or stall, then the files written.

    Parameters
    ----------
    result : TransientResult
        The run.
    files : dict of str to Path
        ``{kind: path}`` of the files written, listed last.
    """
    s = result.summary
    us = result.scene.output.units == "US"
    print(s["title"])
    gov = s["governor"]
    print(f"  transient, {s['simulated_s']:.2f} s in {s['turns']} turns, "
          f"governor {gov['type'] + ' (' + gov['acts_on'] + ')' if gov else 'none'}, "
          f"fidelity {s['fidelity']}")
    pw = s["final_indicated_power_W"]
    print(f"  final speed      {s['final_speed_rpm']:.2f} rpm, "
          + (f"{pw / units.HP_W:.1f} ihp" if us else f"{pw / 1e3:.1f} kW"))
    start = s.get("start") or {}
    if start.get("status"):
        where = {"balanced": "where the governor balances the load",
                 "load_too_heavy": "with the governor down: the load is more than the engine "
                                   "carries in the governor's range",
                 "load_too_light": "at the governor's top stop: the load is too light to pull "
                                   "the speed into the governor's range",
                 "run_speed": "at run.speed, the governor balanced for it",
                 "rest": "from rest"}[start["status"]]
        print(f"  start            {start['speed_rpm']:.2f} rpm, governor z "
              f"{start['governor_z_frac']:.3f}, {where}")
    if s.get("speed_before_rpm") is not None:
        reg = s["regulation_frac"]
        print(f"  load step at     {s['step_time_s']:.3g} s: speed before "
              f"{s['speed_before_rpm']:.2f} rpm, regulation "
              + ("not measured (not settled)" if reg is None else f"{100 * reg:+.2f} %"))
        print(f"  largest change   {s['max_deviation_rpm']:+.2f} rpm "
              f"({100 * s['max_deviation_frac']:+.2f} %) at {s['time_of_max_deviation_s']:.2f} s "
              "after the step")
        st = s["settling_time_s"]
        if st is not None:
            print(f"  settling         {st:.2f} s to within "
                  f"{100 * result.scene.run.settling_band:g} %")
    if not s["settled"]:
        swing = s["settled_swing_frac"]
        print("  NOT SETTLED      the speed still swings "
              + ("" if swing is None else f"by {100 * swing:.3f} % ")
              + "at the end of the run: its speeds are not steady-state speeds (run longer, "
              "or --until-settled)")
    if s["hunting"]:
        print(f"  HUNTING          period {s['hunting_period_s']:.2f} s, governor swing "
              f"{100 * s['governor_swing_frac']:.1f} % of travel")
    if s["stalled"]:
        print("  STALLED          the load stopped the engine")
    print(f"  wall time        {s['wall_time_s']:.2f} s")
    _print_files(files)


def _print_files(files) -> None:
    for kind, path in files.items():
        print(f"  wrote {kind:12s} {path}")


def _bar(kind: str, tolerance: float | None = None) -> ProgressBar:
    """The command line's progress bar: on a terminal only (a log gets none), and only
    once the work has taken two seconds."""
    return ProgressBar(kind, delay_s=2.0, disable=None, tolerance=tolerance)


def cmd_run(args) -> int:
    """``corliss run``: simulate a scene, write its files and print its account.

    A scene file or bundled name, or ``--from-meta``; ``--fidelity``, ``--cycles``,
    ``--duration`` and ``--until-settled`` change the run before it starts, and
    every option is checked before any simulation.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    if args.from_meta is not None:
        if args.scene is not None:
            raise InputError("--from-meta", args.from_meta, "either a scene or --from-meta, "
                             "not both")
        scene = scene_from_meta(args.from_meta, edited=args.as_edited)
        if args.out is None:
            _inside_working_directory(scene.output.dir)
        if args.units:
            scene = dataclasses.replace(scene, output=dataclasses.replace(scene.output,
                                                                          units=args.units))
    else:
        if args.as_edited:
            raise InputError("--as-edited", True, "with --from-meta only")
        scene = _load(args.scene, args.units)
    if args.fidelity:
        scene = scene.with_fidelity(args.fidelity)
    transient = scene.run.mode == "transient"
    if args.cycles is not None:
        if transient:
            raise InputError("--cycles", args.cycles, "no cycle count for a transient scene: "
                             "give --duration (e.g. \"5 s\")")
        if not 1 <= args.cycles <= limits.MAX_CYCLES:
            raise InputError("--cycles", args.cycles, "a whole number of cycles from 1 to "
                             f"{limits.MAX_CYCLES}")
        scene = scene.replace_run(cycles=args.cycles)
    if args.duration is not None:
        if not transient:
            raise InputError("--duration", args.duration, "a steady scene has no duration: "
                             "give --cycles, or run a transient scene")
        d = units.parse(args.duration, "time", "--duration")
        if not 0.0 < d <= limits.MAX_DURATION_S:
            raise InputError("--duration", args.duration, "a time above 0, up to 1 h")
        scene = scene.replace_run(duration_s=d)
    if transient and (args.until_settled or scene.run.until_settled):
        d = scene.run.duration_s
        longest = max(scene.run.max_duration_s or 0.0, min(10.0 * d, limits.MAX_DURATION_S), d)
        scene = scene.replace_run(until_settled=True, max_duration_s=longest)
    elif args.until_settled:
        raise InputError("--until-settled", True, "a transient scene: a steady run always "
                         "runs until periodic")
    check_output_samples(scene.run, {"cycles": "--cycles" if args.cycles is not None
                                     else "run.cycles",
                                     "duration": "--duration" if args.duration is not None
                                     else "run.duration"})
    out = output_dir(args, scene)
    bar = None if args.json else (
        _bar("time") if transient else
        _bar("cycles", tolerance=scene.run.fidelity.convergence_tolerance))
    try:
        result = simulate(scene, progress=bar)
    finally:
        if bar:
            bar.close()
    files = result.write(out, plots=not args.no_plots)
    if args.json:
        print(summary_json(result.summary))
    elif transient:
        print_transient(result, files)
    else:
        print_steady(result, files)
    physical = report_failures(result.summary.get("failures") or [])
    failed = None if transient else balance_failure(result.summary)
    if failed and scene.run.cycles is None:
        print(f"corliss: the run is NOT a result: {failed}; it did not converge (a tighter "
              "fidelity, or more max_cycles, may settle it). Its files are written, for a "
              "look.", file=sys.stderr)
        return EXIT_BALANCE_FAILED
    if failed:
        log.warning("%s after the %d cycles asked for (--cycles): the run is not periodic",
                    failed, scene.run.cycles)
    return physical


def report_failures(failures: list[dict]) -> int:
    """Say on stderr how a completed run failed physically, and give its exit status.

    Parameters
    ----------
    failures : list of dict
        The summary's ``failures`` (:mod:`corliss.engine.verdict`).

    Returns
    -------
    int
        0 with none, else :data:`~corliss.engine.verdict.EXIT_PHYSICAL`.
    """
    if not failures:
        return EXIT_OK
    for f in failures:
        print(f"corliss: the run completed but failed ({f['failure']}): {f['reason']}. "
              "Its files were written.", file=sys.stderr)
    return EXIT_PHYSICAL


def _inside_working_directory(folder: str) -> None:
    """A meta file's output folder, used when no --out is given, must be a relative
    path inside the working directory: a meta file is a thing people send each other."""
    p = Path(folder)
    if p.is_absolute() or ".." in p.parts or (p.exists() and not p.resolve().is_relative_to(
            Path.cwd().resolve())):
        raise InputError("output.dir", folder, "a folder inside the working directory when "
                         "the scene comes from a meta file; give --out to write elsewhere")


def _numbers(flag: str, text: str) -> list[float]:
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise InputError(flag, text, "numbers separated by commas, e.g. 0,0.5,1") from None
    if not all(v == v and abs(v) != float("inf") for v in values):
        raise InputError(flag, text, "finite numbers")
    return values


def cmd_events(args) -> int:
    """``corliss events``: the valve events of each end, without simulating.

    Printed as a list, or as JSON with ``--json`` or ``--settings`` (the events at
    each gear setting given).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    scene = _load(args.scene, args.units)
    settings = None if args.settings is None else _numbers("--settings", args.settings)
    ev = scene_events(scene, settings)
    if args.units is not None:      # lengths in the system's unit, named by it (lead_in)
        baro = scene.supply.barometer_Pa
        ev = ([{**row, **{end: convert_record(row[end], args.units, baro)
                          for end in row if isinstance(row[end], dict)}} for row in ev]
              if isinstance(ev, list) else
              {end: convert_record(e, args.units, baro) for end, e in ev.items()})
    if args.json or settings is not None:
        print(json.dumps(ev, indent=2))
        return 0
    for end, e in ev.items():
        print(f"{end} end")
        for k, v in e.items():
            print(f"  {k:20s} {v if v is None else round(v, 6)}")
    return 0


def cmd_gear(args) -> int:
    """``corliss gear``: the panels of the scene's valve gear as ``<scene>.gear.png``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from corliss.plot import plot_gear
    scene = _load(args.scene, args.units)
    out_dir = output_dir(args, scene)
    gear = build_gear(scene)
    name = f"{output_stem(scene)}.gear.png"
    with OutputFiles(out_dir) as out, plain_text():
        fig = plot_gear(gear, units_system=scene.output.units)["figure"]
        try:
            fig.suptitle(f"{scene.title}: {scene.gear_type}", fontsize=11)
            fig.savefig(out.stage(name), dpi=120, bbox_inches="tight", format="png")
        finally:
            plt.close(fig)
    print(f"wrote {out_dir / name}")
    return 0


def cmd_animate(args) -> int:
    """``corliss animate``: the scene's gear in motion as ``<scene>.animation.gif`` (or
    ``.html``): its linkage from the exact solve (a Zeuner-form Stephenson link or
    Walschaerts gear, or a harmonic Corliss gear, solved as its linkage), the valve over
    its ports, the port openings and, unless ``--no-card``, the card of a steady run
    traced as the crank turns.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    if not 2 <= args.frames <= 720:         # before any work, as animate_scene says it
        raise InputError("--frames", args.frames, "a whole number of frames from 2 to 720")
    scene = _load(args.scene, args.units)
    if args.fidelity:
        scene = scene.with_fidelity(args.fidelity)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from corliss.plot.animation import write_animation
    from corliss.plot.scene_animation import animate_scene
    out_dir = output_dir(args, scene)
    name = f"{output_stem(scene)}.animation.{args.format}"
    with plain_text():
        drawn = animate_scene(scene, frames=args.frames, card=not args.no_card)
    try:
        with OutputFiles(out_dir) as out:
            write_animation(drawn, out.stage(name), args.format)
    finally:
        plt.close(drawn["figure"])
    print(f"wrote {out_dir / name}")
    return 0


def cmd_design(args) -> int:
    """``corliss design``: a valve (or a gear's setting) for the events asked.

    Writes ``SCENE.design.toml`` and its diagrams (``SCENE.SI.design.toml`` with
    ``--units SI`` on a US scene; :func:`corliss.files.design_output.design`),
    then prints the design, or its summary as JSON with ``--json``.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    from corliss.files.design_output import design
    scene = _load(args.scene, args.units)
    out_dir = output_dir(args, scene)
    d = design(scene, cutoff=args.cutoff, cutoff_crank=args.cutoff_crank, lead=args.lead,
               max_opening=args.max_opening, eccentricity=args.eccentricity, lap=args.lap,
               angular_advance=args.angular_advance, lead_angle=args.lead_angle,
               overtravel=args.overtravel,
               release=args.release,
               compression=args.compression, exhaust_lap=args.exhaust_lap,
               equalise=args.equalise, reference_end=args.reference_end, end=args.end)
    files = d.write(out_dir)
    if args.json:
        print(json.dumps({"title": d.scene.title, "kind": "design", **d.summary()}, indent=2))
        return 0
    u = "in" if scene.output.units == "US" else "mm"
    q = lambda v: f"{units.to_unit(v, u):.4f} {u}"  # noqa: E731
    v = d.valve
    print(f"{d.scene.title}: {d.scene.gear_type}")
    if hasattr(v, "eccentricity_m"):
        print(f"  eccentricity     {q(v.eccentricity_m)}, angular advance "
              f"{math.degrees(v.angular_advance_rad):.3f} deg")
        for k, end in enumerate(("head", "crank")):
            print(f"  {end:5s} end        lap {q(v.lap_m[k])}, exhaust lap {q(v.exhaust_lap_m[k])}, "
                  f"lead {q(v.lead_m[k])}, greatest opening {q(v.max_opening_m[k])}")
    else:
        print(f"  setting          {v.setting:.6f} ({v.setting_name})")
    for w in d.warnings:
        print(f"  WARNING          {w}")
    for end, ev in d.events.items():
        print(f"  {end:5s} events     cut-off {_fmt(ev['cutoff_frac'], '', 4)}, release "
              f"{_fmt(ev['release_frac'], '', 4)}, compression {_fmt(ev['compression_frac'], '', 4)}"
              " (fractions of stroke)")
    _print_files(files)
    return 0


def cmd_sweep(args) -> int:
    """``corliss sweep``: steady runs across the load range at each setting or opening.

    Writes the table and the Willans lines, then prints the table in the scene's
    units (the summary as JSON with ``--json``).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    from corliss.frames.columns import convert_frame
    from corliss.studies.load_range import load_ranges
    scene = _load(args.scene, args.units)
    if args.fidelity:
        scene = scene.with_fidelity(args.fidelity)
    if args.settings is None and args.throttle is None:
        raise InputError("--settings", args.settings, "--settings, --throttle or both, e.g. "
                         "--settings 0,0.25,0.5,0.75,1 or --throttle 0.2,0.4,0.6,0.8,1")
    values = {}
    for knob, flag, text in (("setting", "--settings", args.settings),
                             ("throttle", "--throttle", args.throttle)):
        if text is not None:
            values[knob] = _numbers(flag, text)
            if len(values[knob]) < 2:
                raise InputError(flag, text, "two values or more")
    # values checked before work
    result, files = _study(args, scene, lambda bar, out: load_ranges(scene, values, progress=bar))
    if files is None:
        return 0
    frame = convert_frame(result.points, scene.output.units, scene.supply.barometer_Pa)[0]
    print(frame.to_string(index=False))
    _print_files(files)
    return 0


@contextlib.contextmanager
def _out_dir(path):
    """The output directory (checked by :func:`output_dir`), made and a file written in
    it before the work, as a study keeps its rows there as they finish; made here and
    left empty by a refused or failed command, it is removed again."""
    out = Path(path)
    made = not out.exists()
    check_writable(out)
    try:
        yield out
    except BaseException:
        if made and out.is_dir() and not any(out.iterdir()):
            out.rmdir()
        raise


def _study(args, scene, run):
    """Run a study of many steady runs, ``run(progress, out)``, with a progress bar unless
    ``--json``; write its files; with ``--json`` print its summary instead and return
    no files."""
    out_dir = output_dir(args, scene)
    bar = None if args.json else _bar("runs")
    with _out_dir(out_dir) as out:
        try:
            result = run(bar, out)
        finally:
            if bar:
                bar.close()
        files = result.write(out)
    if args.json:
        print(summary_json(result.summary))
        return result, None
    return result, files


def _loads(text: str) -> list[float]:
    """``0.1:1.1:0.1`` (start:stop:step, stop included) or ``0.25,0.5,1``."""
    if ":" in text:
        parts = text.split(":")
        try:
            a, b, step = (float(v) for v in parts) if len(parts) == 3 else (None,) * 3
        except ValueError:
            a = None
        if a is None or not step > 0 or b < a:
            raise InputError("--loads", text, "start:stop:step with step > 0, e.g. 0.1:1.1:0.1")
        n = int(math.floor((b - a) / step + 1e-9)) + 1
        if n > 200:
            raise InputError("--loads", text, "at most 200 loads")
        return [round(a + i * step, 10) for i in range(n)]
    return _numbers("--loads", text)


def print_verdict(result) -> None:
    """Print the verdict of ``corliss compare`` to standard output.

    Per load and condensation, the steam of each governing, the saving of cut-off
    governing and the winner; the Willans line of each variant; the runs made.

    Parameters
    ----------
    result : CompareResult
        The throttling-versus-cut-off study (:func:`corliss.studies.compare.compare`).
    """
    from corliss.studies.compare import DEFAULT_CHEST_OF_SWEPT
    us = result.scene.output.units == "US"
    rate = (lambda v: v / units.POUND_kg) if us else (lambda v: v)
    unit = "lb/h" if us else "kg/h"
    s = result.summary
    print(f"{s['title']}: throttling or cut-off?")
    pts = result.points
    lo, hi = min(s["loads"]), max(s["loads"])
    if s["governor_droop_applied"]:
        by_load = pts.groupby("load_frac")["speed_rpm"].first()
        print(f"  {by_load.loc[lo]:.1f} rpm at {100 * lo:.0f} % load to {by_load.loc[hi]:.1f} "
              f"rpm at {100 * hi:.0f} %: speeds on the governor's static characteristic, "
              "full load at the bottom of its travel (--droop)")
    else:
        print(f"  every load at {s['speed_rpm']:.1f} rpm, the scene's speed: the two "
              "governings compared at one speed (--droop runs each load on the governor's "
              "static characteristic instead)")
    chest_from = {"scene": "the scene's", "compare": "the [compare] section's",
                  "default": f"none in the scene: {DEFAULT_CHEST_OF_SWEPT:g} of the swept "
                             "volume, which the throttled engine draws down between "
                             "admissions"}[s["chest_volume_source"]]
    print(f"  rated {s['rated_power_W'] / (units.HP_W if us else 1e3):.1f} "
          f"{'hp' if us else 'kW'} ({s['power_basis']}), chest "
          f"{s['chest_volume_m3'] / (units.FOOT_m ** 3 if us else 1.0):.3g} {'ft3' if us else 'm3'} "
          f"({chest_from}); throttled at setting {s['variants']['throttling']['fixed']:.3g}, cut-off over "
          f"settings {s['variants']['cutoff']['knob_range'][0]:.3g} to "
          f"{s['variants']['cutoff']['knob_range'][1]:.3g}; fidelity {s['fidelity']}")
    print(f"  {'load':>5s} {'condensation':>12s} {'throttled':>10s} {'cut-off':>10s} "
          f"{'saving':>8s}  less steam [{unit}]")
    for r in result.verdict.itertuples():
        fmt = lambda v: "       -" if v != v else f"{rate(v):10.1f}"  # noqa: E731
        sv = "      -" if r.cutoff_saving_frac != r.cutoff_saving_frac else \
            f"{100 * r.cutoff_saving_frac:+7.1f}%"
        print(f"  {100 * r.load_frac:4.0f}% {r.condensation:>12s} {fmt(r.throttling_steam_rate_kg_per_h)}"
              f" {fmt(r.cutoff_steam_rate_kg_per_h)} {sv}  {r.winner}")
    for r in result.willans.itertuples():
        print(f"  Willans line, {r.variant}, condensation {r.condensation}: "
              f"{rate(r.willans_intercept_kg_per_h):.1f} {unit} + "
              + (f"{r.willans_slope_kg_per_kWh * units.HP_W / 1e3 / units.POUND_kg:.2f} lb/h per ihp"
                 if us else f"{r.willans_slope_kg_per_kWh:.2f} kg/h per kW")
              + f" (R2 {r.willans_r2_frac:.5f})")
    if s["willans_negative_intercepts"]:
        print(f"  NEGATIVE INTERCEPT  {', '.join(s['willans_negative_intercepts'])}: no steam "
              "at no load is less than none, so those points do not lie on a straight "
              "Willans line (see the table)")
    if s["unreached_points"]:
        print(f"  {s['unreached_points']} operating point(s) beyond the engine's reach "
              "(status 'unreached' in the table)")
    print(f"  {s['runs']} steady runs on {s['workers']} process(es) in {s['wall_time_s']:.1f} s")


def cmd_compare(args) -> int:
    """``corliss compare``: throttling against cut-off governing across the load range.

    Writes the study's files, then prints :func:`print_verdict` (the summary as
    JSON with ``--json``).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    from corliss.studies.compare import DEFAULT_LOADS, compare
    if args.droop and args.no_droop:
        raise InputError("--droop", True, "--droop or --no-droop, not both")
    scene = _load(args.scene, args.units)
    loads = _loads(args.loads) if args.loads else list(DEFAULT_LOADS)
    result, files = _study(args, scene, lambda bar, out: compare(
        scene, loads, condensation=args.with_condensation, fidelity=args.fidelity,
        droop=args.droop, workers=args.jobs, progress=bar))
    if files is None:
        return 0
    print_verdict(result)
    _print_files(files)
    return 0


def cmd_study(args) -> int:
    """``corliss study``: steady runs over a design of scene keys.

    Writes the study's files (:func:`corliss.studies.study`), then prints each
    response's range over the runs (the summary as JSON with ``--json``).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status, 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    from corliss.studies import study
    scene = _load(args.scene)
    result, files = _study(args, scene, lambda bar, out: study(
        scene, args.vary, grid=args.grid, levels=args.levels, lhs=args.lhs,
        monte_carlo=args.monte_carlo, seed=args.seed, responses=args.response,
        fidelity=args.fidelity, jobs=args.jobs, scheduler=args.scheduler, progress=bar,
        out=out, resume=args.resume))
    if files is None:
        return 0
    s = result.summary
    print(f"{s['title']}: {s['design']} of {s['runs']} runs over "
          + ", ".join(v["key"] for v in s["varied"]) + f", fidelity {s['fidelity']}")
    system = args.units or scene.output.units
    for r, rng in s["response_ranges"].items():
        if rng is None:
            print(f"  {r:32s} no run gave it")
            continue
        # each response in the asked units, named by them (a name without a unit as it is)
        conv = {q: convert_record({r: rng[q]}, system, scene.supply.barometer_Pa)
                for q in ("min", "max", "median")}
        name = next(iter(conv["min"]))
        print(f"  {name:32s} {conv['min'][name]:.5g} to {conv['max'][name]:.5g} "
              f"(median {conv['median'][name]:.5g})")
    if s["failed"]:
        print(f"  {s['failed']} run(s) stopped: status 'failed', the reason in 'error'")
    where = s["scheduler"] or f"{s['workers']} local process(es)"
    print(f"  {s['runs']} runs on {where} in {s['wall_time_s']:.1f} s "
          f"({s['runs_per_s']:.1f} runs/s)")
    _print_files(files)
    return 0
def cmd_fit(args) -> int:
    """``corliss fit``: calibrate scene keys to a measured card.

    Writes ``SCENE.fit.json``, ``SCENE.fit.toml`` and the figure (a folder holding
    another fit of the scene refused before any work), then prints
    :func:`corliss.files.fit_output.print_fit` (the fit as JSON with ``--json``).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    from corliss.files.fit_output import check_out, fit, print_fit
    scene = _load(args.scene, args.units)
    out_dir = output_dir(args, scene)
    check_out(out_dir, scene, args.card, args.vary)
    result = fit(scene, args.card, args.vary, fidelity=args.fidelity, refine=args.refine,
                 bootstrap=args.bootstrap, seed=args.seed, jobs=args.jobs)
    files = result.write(out_dir, plots=not args.no_plots)
    if args.json:
        print(summary_json(result.summary))
    else:
        print_fit(result, files)
    return 0


def cmd_list(args) -> int:
    """``corliss list``: the bundled scenes, or the gears, governors or effects known.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    if args.what == "scenes":
        for name, path in bundled_scenes().items():
            try:
                title = tomllib.loads(path.read_text(encoding="utf-8")).get("title", "")
            except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
                title = "(unreadable)"
            print(f"{name:32s} {title}")
    elif args.what == "gears":
        from corliss.valves import GEARS
        for name, g in sorted(GEARS.items()):
            print(f"{name:20s} {g.summary}")
    elif args.what == "governors":
        from corliss.governors import GOVERNORS
        for name, g in sorted(GOVERNORS.items()):
            print(f"{name:20s} {g.summary}")
    else:
        from corliss.engine.options import EFFECTS, PLANNED_EFFECTS
        for name, text in EFFECTS.items():
            print(f"{name:20s} {text}")
        for name in PLANNED_EFFECTS:
            print(f"{name:20s} (planned, not in this version)")
    return 0


def cmd_bench(args) -> int:
    """``corliss bench``: the accuracy-versus-time study of ``benchmarks/``.

    Needs a source checkout (the study and its baseline live beside the
    package).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`main` turns into 2).
    """
    import importlib.util
    if not 1 <= args.repeats <= limits.MAX_BENCH_REPEATS:
        raise InputError("--repeats", args.repeats, "a whole number of repeats from 1 to "
                         f"{limits.MAX_BENCH_REPEATS}")
    here = Path(__file__).resolve().parent.parent
    for root in (Path.cwd(), here):
        script = root / "benchmarks" / "accuracy_vs_time.py"
        if script.is_file():
            break
    else:
        raise InputError("bench", str(Path.cwd()), "a source checkout of corliss: the study and "
                         "its baseline live in benchmarks/ beside the package")
    spec = importlib.util.spec_from_file_location("corliss_accuracy_vs_time", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    argv = ["--repeats", str(args.repeats)] + (["--out", args.out] if args.out else [])
    return module.main(argv)


def cmd_explain(args) -> int:
    """``corliss explain KEY``: print what a scene key (section, gear, governor, effect)
    is, from the loader's declarations.

    Parameters
    ----------
    args : argparse.Namespace
        ``key``: the name asked about.

    Returns
    -------
    int
        0 (an unknown name is an InputError: exit 2).
    """
    from corliss.scene.reference import explain
    print(explain(args.key), end="")
    return 0


def cmd_workbench(args) -> int:
    """``corliss workbench``: serve the workbench page until interrupted.

    Parameters
    ----------
    args : argparse.Namespace
        ``scene``, ``port``, ``address``, ``no_browser`` and ``fidelity``.

    Returns
    -------
    int
        0 once stopped (a bad scene or option is an InputError: exit 2).
    """
    try:
        from corliss.workbench.server import serve
    except ImportError as exc:      # the optional extra is not installed
        raise InputError("workbench", str(exc), 'the workbench extra: pip install '
                         '"corliss[workbench]"') from None
    serve(args.scene, port=args.port, address=args.address,
          open_browser=not args.no_browser, fidelity=args.fidelity)
    return 0


def cmd_list_keys(args) -> int:
    """``corliss list keys GEAR_OR_GOVERNOR``: a type's scene keys; any other ``list``
    goes to :func:`cmd_list`.

    Parameters
    ----------
    args : argparse.Namespace
        ``what`` and, for keys, ``name``: the gear or governor.

    Returns
    -------
    int
        0 (a missing or unknown name is an InputError: exit 2).
    """
    if args.what != "keys":
        if args.name is not None:
            raise InputError(f"list {args.what}", args.name, f"nothing after {args.what} (a "
                             "name follows only list keys)")
        return cmd_list(args)
    from corliss.scene.reference import type_keys
    if args.name is None:
        raise InputError("list keys", None, "a gear or governor after it, e.g. corliss list "
                         "keys slide_valve (corliss list gears, corliss list governors)")
    print(type_keys(args.name), end="")
    return 0


def build_parser() -> argparse.ArgumentParser:
    """The ``corliss`` command's argument parser, a subcommand per ``cmd_*`` function.

    Returns
    -------
    argparse.ArgumentParser
        The parser; each subcommand's ``func`` default is its ``cmd_*`` function.
    """
    p = argparse.ArgumentParser(prog="corliss", description="Steam-engine cycle and governing "
                                "simulator: indicator cards, valve events, governing.")
    p.add_argument("--version", action="version", version=f"corliss {corliss.__version__}")
    p.add_argument("-v", "--verbose", action="store_true",
                   help="log corliss's progress messages to stderr")
    sub = p.add_subparsers(dest="command", required=True)
    # -v also after the subcommand (``corliss run -v``); SUPPRESS keeps the top
    # level's value when it is not given there
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("-v", "--verbose", action="store_true", default=argparse.SUPPRESS,
                        help="log corliss's progress messages to stderr")

    def _subcommand(subparsers, name, **kw):
        return subparsers.add_parser(name, parents=[common], **kw)

    units_help = "units of the CSVs and figures (default: the scene's [output] units)"
    r = _subcommand(sub, "run", help="simulate a scene and write its card, CSV and meta")
    r.add_argument("scene", nargs="?", help="scene TOML, or a bundled scene's name "
                   "(default: the bundled default scene)")
    r.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    r.add_argument("--json", action="store_true", help="print the summary as JSON")
    r.add_argument("--no-plots", action="store_true", help="write the tables and summary only")
    r.add_argument("--units", choices=("US", "SI"), help=units_help)
    r.add_argument("--fidelity", choices=("reference", "standard", "fast"),
                   help="override the scene's fidelity preset")
    r.add_argument("--cycles", type=int, help="simulate exactly N cycles (steady scenes; "
                   f"at most {limits.MAX_CYCLES})")
    r.add_argument("--duration", help="simulated time of a transient scene, e.g. \"5 s\"")
    r.add_argument("--until-settled", action="store_true",
                   help="a transient scene: run past its duration until the speed has settled "
                        "(up to run.max_duration, by default ten times the duration)")
    r.add_argument("--from-meta", metavar="FILE",
                   help="rerun the run a .meta.json file records, exactly")
    r.add_argument("--as-edited", action="store_true",
                   help="with --from-meta: run the meta file's scene text as it is now, "
                        "though it no longer matches the SHA-256 and tables recorded")
    r.set_defaults(func=cmd_run)
    e = _subcommand(sub, "events", help="valve events of each end, without simulating")
    e.add_argument("scene", help="scene TOML or a bundled scene's name")
    e.add_argument("--json", action="store_true", help="print JSON")
    e.add_argument("--settings", help="gear settings to list, e.g. 0,0.5,1 (link block u/c)")
    e.add_argument("--units", choices=("US", "SI"),
                   help="lengths in inches (US) or millimetres (SI), each key named by its "
                        "unit (lead_in, lead_mm); default: metres, lead_m")
    e.set_defaults(func=cmd_events)
    gp = _subcommand(sub, "gear", help="valve travel and Zeuner diagram of a scene's gear")
    gp.add_argument("scene", help="scene TOML or a bundled scene's name")
    gp.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    gp.add_argument("--units", choices=("US", "SI"), help=units_help)
    gp.set_defaults(func=cmd_gear)
    an = _subcommand(sub, "animate", help="the gear in motion, its valve over the ports, "
                        "the port openings and the card traced, as GIF or HTML")
    an.add_argument("scene", help="scene TOML or a bundled scene's name")
    an.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    an.add_argument("--frames", type=int, default=72, help="frames in one turn (default 72)")
    an.add_argument("--format", choices=("gif", "html"), default="gif",
                    help="a GIF (default) or an HTML page with a player")
    an.add_argument("--no-card", action="store_true",
                    help="no steady run, no indicator card")
    an.add_argument("--fidelity", choices=("reference", "standard", "fast"), default="fast",
                    help="fidelity of the steady run whose card is traced (default fast)")
    an.add_argument("--units", choices=("US", "SI"), help=units_help)
    an.set_defaults(func=cmd_animate)
    ds = _subcommand(sub, "design", help="a valve (or a gear's setting) for the events asked: "
                        "a runnable scene and its Zeuner and Bilgram diagrams")
    ds.add_argument("scene", nargs="?", help="scene TOML or a bundled scene's name whose "
                    "engine, ports and rods are kept (default: the bundled default scene)")
    ds.add_argument("--cutoff", type=float, required=True, help="cut-off, fraction of stroke")
    ds.add_argument("--cutoff-crank", type=float, help="crank-end cut-off, if not the same")
    for flag, text in (("--lead", "lead, e.g. 0.25in"), ("--max-opening", "greatest port "
                       "opening"), ("--eccentricity", "eccentric throw"), ("--lap", "steam lap"),
                       ("--angular-advance", "angular advance, e.g. 30deg"),
                       ("--lead-angle", "angle of lead, the crank before dead centre at admission")):
        ds.add_argument(flag, help=text + " (two of lead, max-opening, eccentricity, lap, "
                        "angular-advance, lead-angle; slide valve)")
    ds.add_argument("--overtravel", help="instead of --max-opening: the valve's travel past "
                    "the port (the opening is the port width plus it)")
    ds.add_argument("--release", help="release, fraction of stroke (or head,crank)")
    ds.add_argument("--compression", help="compression, fraction of stroke from the end's "
                    "dead centre as `corliss events` gives it (or head,crank)")
    ds.add_argument("--exhaust-lap", help="exhaust lap instead of release or compression")
    ds.add_argument("--equalise", choices=("cutoff", "laps"), default="cutoff",
                    help="laps per end for equal cut-offs (default), or equal laps")
    ds.add_argument("--reference-end", choices=("head", "crank"), default="head",
                    help="end at which the lead and opening asked hold (default head)")
    ds.add_argument("--end", choices=("head", "crank", "mean"), default="head",
                    help="whose cut-off a gear's setting is found for (default head)")
    ds.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    ds.add_argument("--units", choices=("US", "SI"), help="units of the scene written (every "
                    "quantity of it, rounded as a drawing is: 0.001 in or 0.01 mm, 0.01 deg, "
                    "four figures) and of the figures (default: the scene's)")
    ds.add_argument("--json", action="store_true", help="print the design as JSON")
    ds.set_defaults(func=cmd_design)
    sw = _subcommand(sub, "sweep", help="steady cards across the load range: Willans line")
    sw.add_argument("scene", help="scene TOML or a bundled scene's name (a transient one "
                    "runs steady at its speed)")
    sw.add_argument("--settings", help="gear settings, e.g. 0,0.25,0.5,0.75,1")
    sw.add_argument("--throttle", help="throttle openings, e.g. 0.2,0.4,0.6,0.8,1")
    sw.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    sw.add_argument("--units", choices=("US", "SI"), help=units_help)
    sw.add_argument("--fidelity", choices=("reference", "standard", "fast"),
                    help="override the scene's fidelity preset")
    sw.add_argument("--json", action="store_true", help="print the summary as JSON")
    sw.set_defaults(func=cmd_sweep)
    cp = _subcommand(sub, "compare", help="throttling against cut-off governing across the "
                        "load range, with and without condensation")
    cp.add_argument("scene", help="scene TOML or a bundled scene's name (its gear needs a "
                    "setting)")
    cp.add_argument("--loads", help="loads as fractions of the rated power: start:stop:step "
                    "or a list (default 0.1:1.1:0.1)")
    cp.add_argument("--with-condensation", choices=("both", "on", "off"), default="both",
                    help="with the wall-heat effect, without, or both (default)")
    cp.add_argument("--fidelity", choices=("reference", "standard", "fast"),
                    help="the tier the operating points are refined on (default the scene's)")
    cp.add_argument("--droop", action="store_true", help="each load at a speed on the "
                    "governor's static characteristic, full load at the bottom of its travel "
                    "(default: every load at the scene's speed)")
    cp.add_argument("--no-droop", action="store_true", help="every load at the scene's speed "
                    "(the default; kept for scripts that ask for it)")
    cp.add_argument("--jobs", type=int, help="local processes (default: every core)")
    cp.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    cp.add_argument("--units", choices=("US", "SI"), help=units_help)
    cp.add_argument("--json", action="store_true", help="print the summary as JSON")
    cp.set_defaults(func=cmd_compare)
    st = _subcommand(sub, "study", help="steady runs over a grid, Latin hypercube or Monte "
                        "Carlo design of scene keys, locally or on a Dask cluster")
    st.add_argument("scene", help="scene TOML or a bundled scene's name (a transient one "
                    "runs steady at its speed)")
    st.add_argument("--vary", action="append", required=True, metavar="KEY=SPEC",
                    help="a scene key and its values: KEY=LOW:HIGH (one unit, e.g. "
                    "valve_gear.lap=0.8:1.2in), KEY=a,b,c (grid), KEY=normal(MEAN,SD)UNIT or "
                    "KEY=triangular(LOW,MODE,HIGH)UNIT (--lhs, --monte-carlo); repeat per key")
    dg = st.add_mutually_exclusive_group(required=True)
    dg.add_argument("--grid", action="store_true", help="full factorial design")
    dg.add_argument("--lhs", type=int, metavar="N", help="Latin hypercube of N runs")
    dg.add_argument("--monte-carlo", type=int, metavar="N", help="N random runs")
    st.add_argument("--levels", type=int, default=3, help="levels of each LOW:HIGH key of a "
                    "grid, ends included (default 3)")
    st.add_argument("--seed", type=int, default=0, help="seed of --lhs and --monte-carlo "
                    "(default 0)")
    st.add_argument("--response", action="append", metavar="KEY",
                    help="a summary key to record, e.g. indicated_power_hp or "
                    "events.head.cutoff_frac; repeat (default: power, m.e.p., steam and "
                    "water rates, head cut-off)")
    st.add_argument("--fidelity", choices=("reference", "standard", "fast"),
                    help="fidelity of every run (default the scene's; fast for large studies)")
    st.add_argument("--jobs", type=int, help="local processes (default: every core)")
    st.add_argument("--scheduler", metavar="ADDR", help="run on the Dask cluster whose "
                    "scheduler is at ADDR, e.g. tcp://10.0.0.5:8786 (needs corliss[dask])")
    st.add_argument("--out", help="output directory (default: the scene's [output] dir); "
                    "rows are kept in it as runs finish, so a stopped study keeps them")
    st.add_argument("--resume", action="store_true", help="finish a stopped study: run only "
                    "the rows its partial file in --out lacks")
    st.add_argument("--json", action="store_true", help="print the summary as JSON")
    st.add_argument("--units", choices=("US", "SI"), help="units of the responses' ranges "
                    "printed (default: the scene's [output] units; the files and --json "
                    "keep the names the summary gives, SI unless they say otherwise)")
    st.set_defaults(func=cmd_study)
    ft = _subcommand(sub, "fit", help="calibrate scene keys to a measured indicator card")
    ft.add_argument("scene", help="scene TOML or a bundled scene's name (steady)")
    ft.add_argument("card", help="card CSV, its header naming each column's unit (e.g. "
                    "end,piston_position [in],pressure [psig]; or a card corliss run wrote)")
    ft.add_argument("--vary", action="append", required=True, metavar="KEY=LOW:HIGH",
                    help="a scene key to fit and its range, e.g. valve_gear.lap=0.7:1.3in "
                    "(repeat for more keys)")
    ft.add_argument("--fidelity", choices=("fast", "standard", "reference"), default="fast",
                    help="tier of the search (default fast)")
    ft.add_argument("--refine", action="store_true", help="repeat the search on the "
                    "standard tier from the fast optimum")
    ft.add_argument("--bootstrap", type=int, default=0, metavar="N",
                    help="wild-bootstrap refits of the residuals, a second uncertainty (default 0)")
    ft.add_argument("--seed", type=int, default=0, help="the bootstrap's seed")
    ft.add_argument("--jobs", type=int, default=1, help="local processes for the "
                    "uncertainty's runs and the bootstrap's refits (default 1)")
    ft.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    ft.add_argument("--units", choices=("US", "SI"), help=units_help)
    ft.add_argument("--no-plots", action="store_true", help="no SCENE.fit.card.png")
    ft.add_argument("--json", action="store_true", help="print the fit as JSON")
    ft.set_defaults(func=cmd_fit)
    b = _subcommand(sub, "bench", help="run the accuracy-versus-time study (source checkout)")
    b.add_argument("--repeats", type=int, default=3, help="repeats per setting (median)")
    b.add_argument("--out", help="directory for the CSV and plot (default benchmarks/results)")
    b.set_defaults(func=cmd_bench)
    wb = _subcommand(sub, "workbench", help="a local page to set the gear and steam by hand "
                        "and watch the card redrawn")
    wb.add_argument("scene", nargs="?", help="scene TOML or a bundled scene's name "
                    "(default: the bundled default scene)")
    wb.add_argument("--port", type=int, help="port (default: a free one)")
    wb.add_argument("--address", default="127.0.0.1", help="address to listen on "
                    "(default 127.0.0.1, this machine only)")
    wb.add_argument("--no-browser", action="store_true", help="serve only; open no browser")
    wb.add_argument("--fidelity", choices=("reference", "standard", "fast"), default="fast",
                    help="fidelity the page starts at (default fast)")
    wb.set_defaults(func=cmd_workbench)
    ls = _subcommand(sub, "list", help="list bundled scenes and the registries")
    ls.add_argument("what", choices=("scenes", "gears", "effects", "governors", "keys"))
    ls.add_argument("name", nargs="?", help="with keys: the gear or governor")
    ls.set_defaults(func=cmd_list_keys)
    ex = _subcommand(sub, "explain", help="what a scene key, section, gear, governor or "
                        "effect is: kind, units, default, range, who reads it")
    ex.add_argument("key", help="e.g. valve_gear.lap, governor.ball_mass, run.effects, "
                    "slide_valve, engine")
    ex.set_defaults(func=cmd_explain)
    return p


class _Handler(TqdmHandler):
    """Writes to whatever ``sys.stderr`` is at the time (tests capture it), above any
    progress bar, naming the point of a study a message came from."""


def configure_logging(verbose: bool) -> Heartbeat:
    """Send the ``corliss`` logger to stderr: notices by default, debug with ``-v``.

    The root logger (and with it every other library) is left untouched.

    Parameters
    ----------
    verbose : bool
        Log everything (debug and up, with level and logger names), not only notices
        and warnings.

    Returns
    -------
    Heartbeat
        The started :class:`~corliss.cli.heartbeat.Heartbeat`, which says what a slow
        once-per-machine step is doing while it runs (stop it when the command ends).
    """
    handler = _Handler()
    handler.setLevel(logging.DEBUG if verbose else NOTICE)
    handler.setFormatter(logging.Formatter("corliss: %(message)s" if not verbose else
                                           "%(levelname)s %(name)s: %(message)s"))
    beat = Heartbeat(lambda: sys.stderr)
    log.handlers[:] = [beat, handler]       # the heartbeat ends its line first
    # INFO reaches the heartbeat (the end of a step: "built the steam table in ..."),
    # not the screen
    log.setLevel(logging.DEBUG if verbose else logging.INFO)
    log.propagate = False
    return beat.start()


def main(argv: list[str] | None = None) -> int:
    """Run the ``corliss`` command.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after the program's name (default ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status (``docs/exit-codes.md``): the subcommand's (0; 3 for a steady
        run whose balances do not close, 4 for a run that completed but failed
        physically, their files written), 2 for a user's mistake
        (:class:`~corliss.errors.InputError`), 5 for a run that cannot go on
        (:class:`~corliss.errors.RunError`), each reported in one paragraph on stderr
        with nothing written, 130 and 143 when interrupted or terminated, and 0 when
        the output pipe closes early.
    """
    args = build_parser().parse_args(argv)
    beat = configure_logging(args.verbose)
    main_thread = threading.current_thread() is threading.main_thread()
    old_term = signal.signal(signal.SIGTERM, _terminate) if main_thread else None
    try:
        return args.func(args)
    except KeyboardInterrupt:
        print("\ncorliss: interrupted; the output folder is as it was before the run (or "
              "holds the whole of its files, when they were being moved into place).",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    except Terminated:
        print("corliss: terminated; the output folder is as it was before the run (or holds "
              "the whole of its files, when they were being moved into place).",
              file=sys.stderr)
        return EXIT_TERMINATED
    except InputError as exc:
        print(f"corliss: {exc} Nothing was simulated and no files were written.",
              file=sys.stderr)
        return EXIT_INPUT
    except StudyStopped as exc:
        print(f"corliss: {exc}.", file=sys.stderr)
        return EXIT_TERMINATED if exc.signal_name == "SIGTERM" else EXIT_INTERRUPTED
    except RunError as exc:
        print(f"corliss: the run stopped: {exc}. No files were written.", file=sys.stderr)
        return EXIT_RUN_STOPPED
    except BrokenPipeError:  # output piped into `head` and the like
        sys.stdout = open(os.devnull, "w")
        return 0
    finally:
        beat.stop()
        if main_thread:
            signal.signal(signal.SIGTERM, signal.SIG_DFL if old_term is None else old_term)


def _terminate(signum, frame):
    raise Terminated()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
