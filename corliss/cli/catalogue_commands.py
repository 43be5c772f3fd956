"""What the package holds: ``corliss list`` and ``corliss explain``."""

from __future__ import annotations

import tomllib

from corliss.cli.common import subcommand
from corliss.errors import InputError
from corliss.scene.loader import bundled_scenes


def cmd_list(args) -> int:
    """``corliss list``: the bundled scenes, or the gears, governors or effects known.

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


def _list_parser(sub) -> None:
    """``corliss list`` and its options."""
    ls = subcommand(sub, "list", help="list bundled scenes and the registries")
    ls.add_argument("what", choices=("scenes", "gears", "effects", "governors", "keys"))
    ls.add_argument("name", nargs="?", help="with keys: the gear or governor")
    ls.set_defaults(func=cmd_list_keys)


def _explain_parser(sub) -> None:
    """``corliss explain`` and its options."""
    ex = subcommand(sub, "explain", help="what a scene key, section, gear, governor or "
                        "effect is: kind, units, default, range, who reads it")
    ex.add_argument("key", help="e.g. valve_gear.lap, governor.ball_mass, run.effects, "
                    "slide_valve, engine")
    ex.set_defaults(func=cmd_explain)


#: The subcommands this module adds, in the order ``corliss --help`` lists them.
PARSERS = (_list_parser, _explain_parser)
