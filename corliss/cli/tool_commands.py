"""The tools beside the simulation: ``corliss bench`` (the accuracy-versus-time study)
and ``corliss workbench`` (the page to set a gear by hand)."""

from __future__ import annotations

from pathlib import Path

from corliss.cli.common import subcommand
from corliss.errors import InputError
from corliss.keys import limits


def cmd_bench(args) -> int:
    """``corliss bench``: the accuracy-versus-time study of ``benchmarks/``.

    Needs a source checkout (the study and its baseline live beside the
    package).

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
    if spec is None or spec.loader is None:
        raise InputError("bench", str(script), "a Python file the accuracy-versus-time study "
                         "can be loaded from")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    argv = ["--repeats", str(args.repeats)] + (["--out", args.out] if args.out else [])
    return module.main(argv)


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


def _bench_parser(sub) -> None:
    """``corliss bench`` and its options."""
    b = subcommand(sub, "bench", help="run the accuracy-versus-time study (source checkout)")
    b.add_argument("--repeats", type=int, default=3, help="repeats per setting (median)")
    b.add_argument("--out", help="directory for the CSV and plot (default benchmarks/results)")
    b.set_defaults(func=cmd_bench)


def _workbench_parser(sub) -> None:
    """``corliss workbench`` and its options."""
    wb = subcommand(sub, "workbench", help="a local page to set the gear and steam by hand "
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


#: The subcommands this module adds, in the order ``corliss --help`` lists them.
PARSERS = (_bench_parser, _workbench_parser)
