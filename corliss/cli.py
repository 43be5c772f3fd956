"""The ``corliss`` command.

``corliss run [SCENE] [--out DIR] [--json]``
    Simulate a scene (the bundled default without SCENE); write the card PNG, the
    CSVs with their meta files and the summary JSON; print a short summary, or the
    summary as JSON with ``--json``.  A transient scene writes the speed and governor
    histories, the per-turn table, the load-step figure and its metrics, with a
    progress bar on stderr when the run takes more than a few seconds.
``corliss events SCENE [--json] [--settings 0,0.5,1]``
    The valve events of each end, without simulating; at several gear settings.
``corliss gear SCENE [--out DIR]``
    Valve travel, port openings and the Zeuner diagram, as PNG.
``corliss sweep SCENE --settings 0,0.5,1 | --throttle 0.2,0.6,1 [--out DIR]``
    Steady cards across the load range at each gear setting or throttle opening: a
    CSV with its meta file and the Willans line as PNG.
``corliss bench [--repeats N] [--out DIR]``
    The accuracy-versus-time study of ``benchmarks/`` (from a source checkout).
``corliss list gears|effects|governors``
    What the registries hold.

A user's mistake exits with code 2 and a one-paragraph message, no traceback.
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import sys
from pathlib import Path

from corliss import units
from corliss.errors import InputError


def _load(path: str | None):
    from corliss.scene import default_scene_path, load_scene
    return load_scene(path if path is not None else default_scene_path())


def _fmt(v, unit, digits=4):
    return "never" if v is None else f"{v:.{digits}g} {unit}"


def _print_summary(result, files) -> None:
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
    for end, ev in s["events"].items():
        print(f"  {end:5s} end        cut-off {_fmt(ev['cutoff_frac'], '', 3)}, release "
              f"{_fmt(ev['release_frac'], '', 3)}, compression {_fmt(ev['compression_frac'], '', 3)}"
              " (fractions of stroke)")
    conv = s["cycles_to_converge"]
    print(f"  cycles           {s['cycles_simulated']} simulated"
          + (f", periodic after {conv}" if conv else "") + f"; {s['wall_time_s']:.2f} s")
    for kind, path in files.items():
        print(f"  wrote {kind:10s} {path}")


def cmd_run(args) -> int:
    from corliss.engine.simulate import simulate
    from corliss.results import summary_json
    scene = _load(args.scene)
    if args.fidelity:
        scene = scene.with_fidelity(args.fidelity)
    transient = scene.run.mode == "transient"
    if args.cycles is not None:
        if transient:
            raise InputError("--cycles", args.cycles, "no cycle count for a transient scene: "
                             "give --duration (e.g. \"5 s\")")
        if args.cycles < 1:
            raise InputError("--cycles", args.cycles, "a whole number of cycles >= 1")
        scene = scene.replace_run(cycles=args.cycles)
    if args.duration is not None:
        if not transient:
            raise InputError("--duration", args.duration, "a steady scene has no duration: "
                             "give --cycles, or run a transient scene")
        d = units.parse(args.duration, "time", "--duration")
        if not 0.0 < d <= 3600.0:
            raise InputError("--duration", args.duration, "a time above 0, up to 1 h")
        scene = scene.replace_run(duration_s=d)
    out = Path(args.out if args.out is not None else scene.output.dir)
    bar = ProgressBar() if scene.run.mode == "transient" and not args.json else None
    result = simulate(scene, progress=bar)
    if bar:
        bar.close()
    files = result.write(out)
    if args.json:
        print(summary_json(result.summary))
    elif scene.run.mode == "transient":
        from corliss.load_step import print_summary
        print_summary(result, files)
    else:
        _print_summary(result, files)
    return 0


class ProgressBar:
    """A progress bar on stderr for transient runs, shown on a terminal once a run has
    taken more than a couple of seconds (short runs and logs get nothing)."""

    def __init__(self, delay_s: float = 2.0, width: int = 40):
        import time
        self._clock = time.perf_counter
        self.t0 = self._clock()
        self.delay = delay_s
        self.width = width
        self.shown = False

    def __call__(self, done: float, total: float) -> None:
        elapsed = self._clock() - self.t0
        if elapsed < self.delay or not sys.stderr.isatty():
            return
        frac = min(max(done / total, 0.0), 1.0) if total > 0 else 1.0
        n = int(round(frac * self.width))
        eta = elapsed * (1.0 - frac) / frac if frac > 0 else float("nan")
        sys.stderr.write(f"\r  [{'#' * n}{'.' * (self.width - n)}] {done:7.2f} of {total:g} s "
                         f"simulated, {elapsed:5.1f} s elapsed, ~{eta:4.0f} s to go ")
        sys.stderr.flush()
        self.shown = True

    def close(self) -> None:
        if self.shown:
            sys.stderr.write("\n")
            sys.stderr.flush()


def cmd_events(args) -> int:
    from corliss.engine.simulate import scene_events
    scene = _load(args.scene)
    settings = None
    if args.settings is not None:
        try:
            settings = [float(v) for v in args.settings.split(",") if v.strip()]
        except ValueError:
            raise InputError("--settings", args.settings, "numbers separated by commas, "
                             "e.g. 0,0.5,1") from None
    ev = scene_events(scene, settings)
    if args.json or settings is not None:
        print(json.dumps(ev, indent=2))
        return 0
    for end, e in ev.items():
        print(f"{end} end")
        for k, v in e.items():
            print(f"  {k:20s} {v if v is None else round(v, 6)}")
    return 0


def cmd_gear(args) -> int:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from corliss.engine.simulate import build_gear
    from corliss.plot import plot_gear
    from corliss.results import _write_atomic
    scene = _load(args.scene)
    gear = build_gear(scene)
    system = scene.output.units
    fig = plot_gear(gear, units_system=system)["figure"]
    fig.suptitle(f"{scene.title}: {scene.gear_type}", fontsize=11)
    out = Path(args.out if args.out is not None else scene.output.dir) / f"{scene.name}.gear.png"
    out.parent.mkdir(parents=True, exist_ok=True)
    _write_atomic(out, lambda p: fig.savefig(p, dpi=120, bbox_inches="tight", format="png"))
    plt.close(fig)
    print(f"wrote {out}")
    return 0


def cmd_sweep(args) -> int:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from types import SimpleNamespace

    from corliss.engine.load_range import load_range
    from corliss.plot import plot_willans
    from corliss.results import _write_atomic, convert_frame, write_csv
    scene = _load(args.scene)
    if (args.settings is None) == (args.throttle is None):
        raise InputError("--settings", args.settings, "either --settings or --throttle, e.g. "
                         "--settings 0,0.25,0.5,0.75,1 or --throttle 0.2,0.4,0.6,0.8,1")
    knob, text = ("setting", args.settings) if args.settings is not None else ("throttle", args.throttle)
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise InputError(f"--{knob}s" if knob == "setting" else "--throttle", text,
                         "numbers separated by commas") from None
    if len(values) < 2:
        raise InputError("--settings" if knob == "setting" else "--throttle", text,
                         "two values or more")
    frame = load_range(scene, knob, values)      # every value is checked before any run
    out = Path(args.out if args.out is not None else scene.output.dir)
    system = scene.output.units
    # the CSV and its meta file as for a run's tables (write_csv reads these three)
    sweep = SimpleNamespace(scene=scene, property_tier=scene.run.fidelity.properties,
                            summary={"knob": knob, "values": values})
    csv_path = write_csv(sweep, frame, out / f"{scene.name}.sweep.csv")
    fig, ax = plt.subplots(figsize=(8, 5.5))
    plot_willans({f"{scene.title} ({knob})": frame}, ax, system)
    png = out / f"{scene.name}.willans.png"
    _write_atomic(png, lambda p: fig.savefig(p, dpi=120, bbox_inches="tight", format="png"))
    plt.close(fig)
    print(convert_frame(frame, system, scene.supply.barometer_Pa)[0].to_string(index=False))
    print(f"wrote {csv_path}\nwrote {png}")
    return 0


def cmd_list(args) -> int:
    if args.what == "gears":
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
    import importlib.util
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


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="corliss", description="Steam-engine cycle and governing "
                                "simulator: indicator cards, valve events, governing.")
    p.add_argument("-v", "--verbose", action="store_true", help="log progress to stderr")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="simulate a scene and write its card, CSV and meta")
    r.add_argument("scene", nargs="?", help="scene TOML (default: the bundled default scene)")
    r.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    r.add_argument("--json", action="store_true", help="print the summary as JSON")
    r.add_argument("--fidelity", choices=("reference", "standard", "fast"),
                   help="override the scene's fidelity preset")
    r.add_argument("--cycles", type=int, help="simulate exactly N cycles (steady scenes)")
    r.add_argument("--duration", help="simulated time of a transient scene, e.g. \"5 s\"")
    r.set_defaults(func=cmd_run)
    e = sub.add_parser("events", help="valve events of each end, without simulating")
    e.add_argument("scene", help="scene TOML")
    e.add_argument("--json", action="store_true", help="print JSON")
    e.add_argument("--settings", help="gear settings to list, e.g. 0,0.5,1 (link block u/c)")
    e.set_defaults(func=cmd_events)
    gp = sub.add_parser("gear", help="valve travel and Zeuner diagram of a scene's gear")
    gp.add_argument("scene", help="scene TOML")
    gp.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    gp.set_defaults(func=cmd_gear)
    sw = sub.add_parser("sweep", help="steady cards across the load range: Willans line")
    sw.add_argument("scene", help="scene TOML (a transient one runs steady at its speed)")
    sw.add_argument("--settings", help="gear settings, e.g. 0,0.25,0.5,0.75,1")
    sw.add_argument("--throttle", help="throttle openings, e.g. 0.2,0.4,0.6,0.8,1")
    sw.add_argument("--out", help="output directory (default: the scene's [output] dir)")
    sw.set_defaults(func=cmd_sweep)
    b = sub.add_parser("bench", help="run the accuracy-versus-time study (source checkout)")
    b.add_argument("--repeats", type=int, default=3, help="repeats per setting (median)")
    b.add_argument("--out", help="directory for the CSV and plot (default benchmarks/results)")
    b.set_defaults(func=cmd_bench)
    ls = sub.add_parser("list", help="list registries")
    ls.add_argument("what", choices=("gears", "effects", "governors"))
    ls.set_defaults(func=cmd_list)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        return args.func(args)
    except InputError as exc:
        print(f"corliss: {exc} Nothing was simulated and no files were written.",
              file=sys.stderr)
        return 2
    except BrokenPipeError:  # output piped into `head` and the like
        sys.stdout = open(os.devnull, "w")
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
