"""The commands of many runs: ``corliss sweep``, ``compare``, ``study`` and ``fit``."""

from __future__ import annotations

import contextlib
import math
from pathlib import Path

from corliss.cli.common import (add_options, fmt, load_scene_for, numbers, output_dir,
                                print_files, progress_bar, subcommand)
from corliss.errors import InputError
from corliss.files.run_output import summary_json
from corliss.frames.columns import convert_record
from corliss.keys import units
from corliss.studies.journal import check_writable


def cmd_sweep(args) -> int:
    """``corliss sweep``: steady runs across the load range at each setting or opening.

    Writes the table and the Willans lines, then prints the table in the scene's
    units (the summary as JSON with ``--json``).

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
    from corliss.frames.columns import convert_frame
    from corliss.studies.load_range import load_ranges
    scene = load_scene_for(args.scene, args.units)
    if args.fidelity:
        scene = scene.with_fidelity(args.fidelity)
    if args.settings is None and args.throttle is None:
        raise InputError("--settings", args.settings, "--settings, --throttle or both, e.g. "
                         "--settings 0,0.25,0.5,0.75,1 or --throttle 0.2,0.4,0.6,0.8,1")
    values = {}
    for knob, flag, text in (("setting", "--settings", args.settings),
                             ("throttle", "--throttle", args.throttle)):
        if text is not None:
            values[knob] = numbers(flag, text)
            if len(values[knob]) < 2:
                raise InputError(flag, text, "two values or more")
    # values checked before work
    result, files = _study(args, scene, lambda bar, out: load_ranges(scene, values, progress=bar))
    if files is None:
        return 0
    frame = convert_frame(result.points, scene.output.units, scene.supply.barometer_Pa)[0]
    print(frame.to_string(index=False))
    print_files(files)
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
    bar = None if args.json else progress_bar("runs")
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
        try:
            a, b, step = (float(v) for v in text.split(":"))
        except ValueError:      # not three parts, or a part not a number
            a = b = step = math.nan
        if not (step > 0 and b >= a):
            raise InputError("--loads", text, "start:stop:step with step > 0, e.g. 0.1:1.1:0.1")
        n = int(math.floor((b - a) / step + 1e-9)) + 1
        if n > 200:
            raise InputError("--loads", text, "at most 200 loads")
        return [round(a + i * step, 10) for i in range(n)]
    return numbers("--loads", text)


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
        The parsed options of the subcommand (:func:`~corliss.cli.commands.build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`~corliss.cli.commands.main` turns into 2).
    """
    from corliss.studies.compare import DEFAULT_LOADS, compare
    if args.droop and args.no_droop:
        raise InputError("--droop", True, "--droop or --no-droop, not both")
    scene = load_scene_for(args.scene, args.units)
    loads = _loads(args.loads) if args.loads else list(DEFAULT_LOADS)
    result, files = _study(args, scene, lambda bar, out: compare(
        scene, loads, condensation=args.with_condensation, fidelity=args.fidelity,
        droop=args.droop, workers=args.jobs, progress=bar))
    if files is None:
        return 0
    print_verdict(result)
    print_files(files)
    return 0


def cmd_study(args) -> int:
    """``corliss study``: steady runs over a design of scene keys.

    Writes the study's files (:func:`corliss.studies.study`), then prints each
    response's range over the runs (the summary as JSON with ``--json``).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of the subcommand (:func:`~corliss.cli.commands.build_parser`).

    Returns
    -------
    int
        The exit status, 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`~corliss.cli.commands.main` turns into 2).
    """
    from corliss.studies import study
    scene = load_scene_for(args.scene)
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
    print_files(files)
    return 0


def cmd_fit(args) -> int:
    """``corliss fit``: calibrate scene keys to a measured card.

    Writes ``SCENE.fit.json``, ``SCENE.fit.toml`` and the figure (a folder holding
    another fit of the scene refused before any work), then prints
    :func:`corliss.files.fit_output.print_fit` (the fit as JSON with ``--json``).

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
    from corliss.files.fit_output import check_out, fit, print_fit
    scene = load_scene_for(args.scene, args.units)
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


def _sweep_parser(sub) -> None:
    """``corliss sweep`` and its options."""
    sw = subcommand(sub, "sweep", help="steady cards across the load range: Willans line")
    sw.add_argument("scene", help="scene TOML or a bundled scene's name (a transient one "
                    "runs steady at its speed)")
    sw.add_argument("--settings", help="gear settings, e.g. 0,0.25,0.5,0.75,1")
    sw.add_argument("--throttle", help="throttle openings, e.g. 0.2,0.4,0.6,0.8,1")
    add_options(sw, "out", "units", "fidelity", "json")
    sw.set_defaults(func=cmd_sweep)


def _compare_parser(sub) -> None:
    """``corliss compare`` and its options."""
    cp = subcommand(sub, "compare", help="throttling against cut-off governing across the "
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
    add_options(cp, "out", "units", "json")
    cp.set_defaults(func=cmd_compare)


def _study_parser(sub) -> None:
    """``corliss study`` and its options."""
    st = subcommand(sub, "study", help="steady runs over a grid, Latin hypercube or Monte "
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
    add_options(st, "json")
    st.add_argument("--units", choices=("US", "SI"), help="units of the responses' ranges "
                    "printed (default: the scene's [output] units; the files and --json "
                    "keep the names the summary gives, SI unless they say otherwise)")
    st.set_defaults(func=cmd_study)


def _fit_parser(sub) -> None:
    """``corliss fit`` and its options."""
    ft = subcommand(sub, "fit", help="calibrate scene keys to a measured indicator card")
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
    add_options(ft, "out", "units")
    ft.add_argument("--no-plots", action="store_true", help="no SCENE.fit.card.png")
    ft.add_argument("--json", action="store_true", help="print the fit as JSON")
    ft.set_defaults(func=cmd_fit)


#: The subcommands this module adds, in the order ``corliss --help`` lists them.
PARSERS = (_sweep_parser, _compare_parser, _study_parser, _fit_parser)
