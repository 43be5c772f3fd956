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
import logging
import os
import signal
import sys
import threading

import corliss
from corliss.cli import (catalogue_commands, gear_commands, run_command, study_commands,
                         tool_commands)
from corliss.cli.common import EXIT_INPUT, EXIT_RUN_STOPPED
from corliss.cli.heartbeat import Heartbeat
from corliss.engine import first_run
from corliss.errors import (EXIT_INTERRUPTED, EXIT_TERMINATED, InputError, RunError, StudyStopped,
                            Terminated)
from corliss.logs import NOTICE
from corliss.progress import TqdmHandler
from corliss.scene.loader import find_scene, load_scene

log = logging.getLogger("corliss")


def _governed_scene():
    """The bundled governed scene whose transient turn a first run's background process
    compiles (:data:`corliss.engine.first_run.TRANSIENT_SCENE`): the command line's
    first run leaves the transient loop compiled too."""
    return load_scene(find_scene(first_run.TRANSIENT_SCENE))


first_run.transient_probe = _governed_scene


def build_parser() -> argparse.ArgumentParser:
    """The ``corliss`` command's argument parser, a subcommand per ``cmd_*`` function
    (each family's module adds its own: ``PARSERS``).

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
    # each command's options are written beside it, in the module of its family
    for add in (*run_command.PARSERS, *gear_commands.PARSERS, *study_commands.PARSERS,
                *tool_commands.PARSERS, *catalogue_commands.PARSERS):
        add(sub)
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
