"""What every ``corliss`` command shares: exit statuses, the scene as a command loads it,
the output folder checked before work, the progress bar, number lists and formatting."""

from __future__ import annotations

import argparse
import dataclasses
import logging
import os
from pathlib import Path

from corliss.errors import InputError
from corliss.files.run_output import plain_name
from corliss.progress import ProgressBar
from corliss.scene.loader import default_scene_path, find_scene, load_scene


log = logging.getLogger("corliss")

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


#: What ``--units`` means on a command that writes files.
UNITS_HELP = "units of the CSVs and figures (default: the scene's [output] units)"

#: ``-v`` also after the subcommand (``corliss run -v``); SUPPRESS keeps the top level's
#: value when it is not given there.
_VERBOSE = argparse.ArgumentParser(add_help=False)
_VERBOSE.add_argument("-v", "--verbose", action="store_true", default=argparse.SUPPRESS,
                      help="log corliss's progress messages to stderr")


#: The options several commands take, with the same meaning and help everywhere.
_OPTIONS: dict[str, dict] = {
    "out": {"help": "output directory (default: the scene's [output] dir)"},
    "units": {"choices": ("US", "SI"), "help": UNITS_HELP},
    "json": {"action": "store_true", "help": "print the summary as JSON"},
    "fidelity": {"choices": ("reference", "standard", "fast"),
                 "help": "override the scene's fidelity preset"},
}


def add_options(parser: argparse.ArgumentParser, *names: str) -> None:
    """Add options several commands share, in the order named.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        A subcommand's parser (:func:`subcommand`).
    *names : {"out", "units", "json", "fidelity"}
        The options: ``--out`` (the output folder), ``--units`` (of the files and
        figures), ``--json`` (the summary printed as JSON), ``--fidelity`` (the scene's
        preset overridden).
    """
    for name in names:
        parser.add_argument(f"--{name}", **_OPTIONS[name])


def subcommand(sub, name: str, **kw) -> argparse.ArgumentParser:
    """A subcommand of ``corliss`` that also takes ``-v`` after its name.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``corliss`` parser's subcommands.
    name : str
        The subcommand's name.
    **kw
        Passed to ``add_parser`` (``help``).

    Returns
    -------
    argparse.ArgumentParser
        The subcommand's parser.
    """
    return sub.add_parser(name, parents=[_VERBOSE], **kw)


def load_scene_for(path: str | None, units_system: str | None = None):
    """The scene a command names, loaded and checked before any work.

    Parameters
    ----------
    path : str or None
        A scene file or a bundled scene's name; None for the bundled default scene.
    units_system : {"US", "SI"} or None
        ``--units``: the unit system of the files written, in place of the scene's
        ``[output] units``.

    Returns
    -------
    Scene
        The scene, its name checked as the stem of every file written.

    Raises
    ------
    InputError
        A scene that cannot be found or read, or whose name cannot name a file.
    """
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


def fmt(v, unit, digits=4):
    """A number and its unit for a printed account, or "never".

    Parameters
    ----------
    v : float or None
        The value, already in ``unit``; None for an event that never happens.
    unit : str
        The unit written after it.
    digits : int
        Significant figures.

    Returns
    -------
    str
        E.g. ``"153.9 ihp"``, or ``"never"``.
    """
    if v is None:
        return "never"
    return f"{v:.{digits}g} {unit}" if unit else f"{v:.{digits}g}"


def print_files(files) -> None:
    """List the files a command wrote on standard output, one a line.

    Parameters
    ----------
    files : dict of str to Path
        ``{kind: path}`` of the files written.
    """
    for kind, path in files.items():
        print(f"  wrote {kind:12s} {path}")


def progress_bar(kind: str, tolerance: float | None = None) -> ProgressBar:
    """The command line's progress bar: on a terminal only (a log gets none), and only
    once the work has taken two seconds.

    Parameters
    ----------
    kind : {"cycles", "time", "runs"}
        What the bar counts.
    tolerance : float, optional
        A steady run's convergence tolerance [-], against which the bar shows the
        periodicity error.

    Returns
    -------
    ProgressBar
        The bar (close it when the work ends).
    """
    return ProgressBar(kind, delay_s=2.0, disable=None, tolerance=tolerance)


def numbers(flag: str, text: str) -> list[float]:
    """A comma-separated list of finite numbers given to an option.

    Parameters
    ----------
    flag : str
        The option, named in the error (``--settings``).
    text : str
        Its value, e.g. ``"0,0.5,1"``.

    Returns
    -------
    list of float
        The numbers.

    Raises
    ------
    InputError
        Naming the option, when a part is not a number or not finite.
    """
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        raise InputError(flag, text, "numbers separated by commas, e.g. 0,0.5,1") from None
    if not all(v == v and abs(v) != float("inf") for v in values):
        raise InputError(flag, text, "finite numbers")
    return values
