"""``corliss run``: simulate a scene, write its files and print its account."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

from corliss.cli.common import (EXIT_OK, add_options, fmt, load_scene_for, log, output_dir,
                                print_files, progress_bar, subcommand)
from corliss.engine.balance import balance_failure
from corliss.engine.output_size import check_output_samples
from corliss.engine.simulate import simulate
from corliss.engine.verdict import EXIT_PHYSICAL
from corliss.errors import EXIT_BALANCE_FAILED, InputError
from corliss.files.run_output import scene_from_meta, summary_json
from corliss.keys import limits, units


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
              f"{fmt(wr, 'lb per ihp-hour')}")
    else:
        print(f"  indicated power  {s['indicated_power_W'] / 1e3:.2f} kW")
        print(f"  m.e.p.           head {s['mep_head_Pa'] / 1e5:.3f}, crank "
              f"{s['mep_crank_Pa'] / 1e5:.3f}, mean {s['mep_mean_Pa'] / 1e5:.3f} bar")
        print(f"  steam            {s['steam_rate_kg_per_h']:.1f} kg/h, "
              f"{fmt(s['water_rate_kg_per_kWh'], 'kg/kWh')}")
    _print_walls(s, us, result.scene.engine.wall_heat_model)
    for end, ev in s["events"].items():
        print(f"  {end:5s} end        cut-off {fmt(ev['cutoff_frac'], '', 3)}, release "
              f"{fmt(ev['release_frac'], '', 3)}, compression {fmt(ev['compression_frac'], '', 3)}"
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
             f"{s['convergence_tolerance']:.2g}"
             + ("; the wall has no periodic state" if s.get("wall_periodic_state") else "")
             + ")") + f"; {s['wall_time_s']:.2f} s")
    print_files(files)


#: How the run's text names a wall model whose heat is a period law's schedule.
SCHEDULE_NAMES = {"marks": "Marks's law (eq. 221)", "english": "English's law"}


def _print_walls(s: dict, us: bool, model: str = "skin") -> None:
    """Initial condensation and the jacket's steam, when the walls exchange heat; the
    heat a period law's schedule takes from each end's steam."""
    if "valve_leakage_fraction_of_steam" in s:
        leak = s["valve_leakage_kg_per_h"]
        print(f"  valve leakage    "
              + (f"{leak / units.POUND_kg:.1f} lb/h" if us else f"{leak:.1f} kg/h")
              + f" past every path; {s['valve_leakage_fraction_of_steam']:.3f} of the steam "
              "leaves the steam side")
    for path, v in (s.get("leak_paths") or {}).items():
        rate = v["kg_per_h"]
        frac = v.get("fraction_of_steam")
        print(f"    {path:<26}"
              + (f"{v['kg_per_cycle'] / units.POUND_kg:.4f} lb a cycle, "
                 f"{rate / units.POUND_kg:.1f} lb/h" if us else
                 f"{v['kg_per_cycle']:.4f} kg a cycle, {rate:.1f} kg/h")
              + ("" if frac is None else f", {frac:.3f} of the steam"))
    ends = [e for e in ("head", "crank") if s.get(f"missing_water_fraction_{e}") is not None]
    if ends:
        print("  missing water    " + ", ".join(f"{s[f'missing_water_fraction_{e}']:.3f}"
                                              for e in ends)
              + f" of the steam at cut-off ({', '.join(ends)})")
    wet = [e for e in ends if s.get(f"wet_fraction_at_cutoff_with_film_{e}") is not None]
    if wet:
        # both wetness figures: the mixture's own water, and all the water present
        # with the wall's film (English's "wetness at cut-off")
        print("  wet at cut-off   " + ", ".join(
            f"{s[f'wet_fraction_at_cutoff_{e}']:.3f} in the steam, "
            f"{s[f'wet_fraction_at_cutoff_with_film_{e}']:.3f} with the film" for e in wet)
              + f" ({', '.join(wet)})")
    heat = [k[len("heat_to_walls_"):-len("_J_per_cycle")] for k in s
            if k.startswith("heat_to_walls_") and s[k] is not None]
    if heat and model in SCHEDULE_NAMES:
        unit = "Btu" if us else "kJ"
        print("  wall heat        " + ", ".join(
            f"{units.to_unit(s[f'heat_to_walls_{e}_J_per_cycle'], unit):.2f}" for e in heat)
            + f" {unit} a cycle ({', '.join(heat)}) by {SCHEDULE_NAMES[model]}, taken in "
            "admission and given back by compression")
    if s.get("missing_water_fraction_of_feed") is not None:
        print(f"  of the feed      {s['missing_water_fraction_of_feed']:.3f} missing at "
              "cut-off (condensation and leakage)")
    if "jacket_steam_kg_per_h" in s:
        wr = s["water_rate_with_jacket_kg_per_kWh"]
        if us:
            print(f"  jacket           {s['jacket_steam_kg_per_h'] / units.POUND_kg:.1f} lb/h of "
                  "steam; with it "
                  + fmt(None if wr is None else wr / units.POUND_kg * units.HP_W / 1e3,
                         "lb per ihp-hour"))
        else:
            print(f"  jacket           {s['jacket_steam_kg_per_h']:.1f} kg/h of steam; with "
                  f"it {fmt(wr, 'kg/kWh')}")


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
    print_files(files)


def cmd_run(args) -> int:
    """``corliss run``: simulate a scene, write its files and print its account.

    A scene file or bundled name, or ``--from-meta``; ``--fidelity``, ``--cycles``,
    ``--duration`` and ``--until-settled`` change the run before it starts, and
    every option is checked before any simulation.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`~corliss.cli.commands.build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`~corliss.cli.commands.main` turns into 2).
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
        scene = load_scene_for(args.scene, args.units)
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
        progress_bar("time") if transient else
        progress_bar("cycles", tolerance=scene.run.fidelity.convergence_tolerance))
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
        why = ("its wall has no periodic state (its balance over a cycle jumps: more "
               "cycles will not settle it)" if result.summary.get("wall_periodic_state") else
               "a tighter fidelity, or more max_cycles, may settle it")
        print(f"corliss: the run is NOT a result: {failed}; it did not converge ({why}). "
              "Its files are written, for a look.", file=sys.stderr)
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


def _run_parser(sub) -> None:
    """``corliss run`` and its options."""
    r = subcommand(sub, "run", help="simulate a scene and write its card, CSV and meta")
    r.add_argument("scene", nargs="?", help="scene TOML, or a bundled scene's name "
                   "(default: the bundled default scene)")
    add_options(r, "out", "json")
    r.add_argument("--no-plots", action="store_true", help="write the tables and summary only")
    add_options(r, "units", "fidelity")
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


#: The subcommands this module adds, in the order ``corliss --help`` lists them.
PARSERS = (_run_parser,)
