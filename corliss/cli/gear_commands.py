"""The valve gear's commands: ``corliss events``, ``gear``, ``animate`` and ``design``."""

from __future__ import annotations

import json
import math

from corliss.cli.common import (add_options, fmt, load_scene_for, numbers, output_dir,
                                print_files, subcommand)
from corliss.engine.model import build_gear, scene_events
from corliss.errors import InputError
from corliss.files.run_output import OutputFiles, output_stem, plain_text
from corliss.frames.columns import convert_record
from corliss.keys import units
from corliss.valves.design import SlideValveDesign


def cmd_events(args) -> int:
    """``corliss events``: the valve events of each end, without simulating.

    Printed as a list, or as JSON with ``--json`` or ``--settings`` (the events at
    each gear setting given).

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
    scene = load_scene_for(args.scene, args.units)
    settings = None if args.settings is None else numbers("--settings", args.settings)
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
        The parsed options of the subcommand (:func:`~corliss.cli.commands.build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`~corliss.cli.commands.main` turns into 2).
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from corliss.plot import plot_gear
    scene = load_scene_for(args.scene, args.units)
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
        The parsed options of the subcommand (:func:`~corliss.cli.commands.build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`~corliss.cli.commands.main` turns into 2).
    """
    if not 2 <= args.frames <= 720:         # before any work, as animate_scene says it
        raise InputError("--frames", args.frames, "a whole number of frames from 2 to 720")
    scene = load_scene_for(args.scene, args.units)
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
        The parsed options of the subcommand (:func:`~corliss.cli.commands.build_parser`).

    Returns
    -------
    int
        The exit status: 0 (a user's mistake raises
        :class:`~corliss.errors.InputError`, which :func:`~corliss.cli.commands.main` turns into 2).
    """
    from corliss.files.design_output import design
    scene = load_scene_for(args.scene, args.units)
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
    if isinstance(v, SlideValveDesign):
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
        print(f"  {end:5s} events     cut-off {fmt(ev['cutoff_frac'], '', 4)}, release "
              f"{fmt(ev['release_frac'], '', 4)}, compression {fmt(ev['compression_frac'], '', 4)}"
              " (fractions of stroke)")
    print_files(files)
    return 0


def _events_parser(sub) -> None:
    """``corliss events`` and its options."""
    e = subcommand(sub, "events", help="valve events of each end, without simulating")
    e.add_argument("scene", help="scene TOML or a bundled scene's name")
    e.add_argument("--json", action="store_true", help="print JSON")
    e.add_argument("--settings", help="gear settings to list, e.g. 0,0.5,1 (link block u/c)")
    e.add_argument("--units", choices=("US", "SI"),
                   help="lengths in inches (US) or millimetres (SI), each key named by its "
                        "unit (lead_in, lead_mm); default: metres, lead_m")
    e.set_defaults(func=cmd_events)


def _gear_parser(sub) -> None:
    """``corliss gear`` and its options."""
    gp = subcommand(sub, "gear", help="valve travel and Zeuner diagram of a scene's gear")
    gp.add_argument("scene", help="scene TOML or a bundled scene's name")
    add_options(gp, "out", "units")
    gp.set_defaults(func=cmd_gear)


def _animate_parser(sub) -> None:
    """``corliss animate`` and its options."""
    an = subcommand(sub, "animate", help="the gear in motion, its valve over the ports, "
                        "the port openings and the card traced, as GIF or HTML")
    an.add_argument("scene", help="scene TOML or a bundled scene's name")
    add_options(an, "out")
    an.add_argument("--frames", type=int, default=72, help="frames in one turn (default 72)")
    an.add_argument("--format", choices=("gif", "html"), default="gif",
                    help="a GIF (default) or an HTML page with a player")
    an.add_argument("--no-card", action="store_true",
                    help="no steady run, no indicator card")
    an.add_argument("--fidelity", choices=("reference", "standard", "fast"), default="fast",
                    help="fidelity of the steady run whose card is traced (default fast)")
    add_options(an, "units")
    an.set_defaults(func=cmd_animate)


def _design_parser(sub) -> None:
    """``corliss design`` and its options."""
    ds = subcommand(sub, "design", help="a valve (or a gear's setting) for the events asked: "
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
    add_options(ds, "out")
    ds.add_argument("--units", choices=("US", "SI"), help="units of the scene written (every "
                    "quantity of it, rounded as a drawing is: 0.001 in or 0.01 mm, 0.01 deg, "
                    "four figures) and of the figures (default: the scene's)")
    ds.add_argument("--json", action="store_true", help="print the design as JSON")
    ds.set_defaults(func=cmd_design)


#: The subcommands this module adds, in the order ``corliss --help`` lists them.
PARSERS = (_events_parser, _gear_parser, _animate_parser, _design_parser)
