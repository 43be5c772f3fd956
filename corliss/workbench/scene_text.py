"""A scene's TOML text with some keys set, its comments and layout kept.

The workbench saves the scene a person has set by hand.  Written again from its
tables (:func:`corliss.keys.toml_text.dumps`) it would lose the source's comments, which
cite where each dimension came from; so the source text is edited in place: a key
that is there has its value replaced (a comment after it kept), a key that is not is
added at the end of its table, a table that is not is added at the end.  The text is
read back and must give exactly the edited tables, else the tables are written plainly.
"""

from __future__ import annotations

import re
import tomllib

from corliss.keys.edits import with_keys
from corliss.keys.toml_text import dumps

_HEADER = re.compile(r"^\s*\[(?P<name>[^\[\]]+)\]\s*(#.*)?$")
_ANY_HEADER = re.compile(r"^\s*\[")


def _toml_value(value) -> str:
    """A value as TOML writes it (through :func:`dumps` of a one-key table)."""
    return dumps({"v": value}).strip()[len("v = "):]


def _key_line(name: str) -> re.Pattern:
    return re.compile(r"^(?P<lead>\s*" + re.escape(name) + r"\s*=\s*)(?P<rest>.*)$")


def _split_comment(rest: str) -> tuple[str, str]:
    """The value text and the trailing comment (with the spaces before it) of a line's
    remainder after ``=``; ``#`` inside a string is not a comment."""
    quote = None
    for i, ch in enumerate(rest):
        if quote:
            if ch == "\\" and quote == '"':
                continue
            if ch == quote:
                quote = None
        elif ch in "\"'":
            quote = ch
        elif ch == "#":
            j = i
            while j > 0 and rest[j - 1] in " \t":
                j -= 1
            return rest[:j], rest[j:]
    return rest.rstrip(), ""


def _set_line(lines: list[str], table: str, name: str, text: str) -> bool:
    """Set ``name = text`` in ``[table]`` of ``lines`` in place; False where the
    table is absent.  A one-line value only (a scene's values are one line each)."""
    inside, last, pattern = False, None, _key_line(name)
    for i, line in enumerate(lines):
        head = _HEADER.match(line)
        if head:
            if inside:
                break
            inside = head.group("name").strip() == table
            if inside:
                last = i
            continue
        if not inside:
            continue
        m = pattern.match(line)
        if m:
            _, comment = _split_comment(m.group("rest"))
            lines[i] = f"{m.group('lead')}{text}{comment}"
            return True
        if line.strip() and not line.lstrip().startswith("#"):
            last = i
    if last is None:
        return False
    lines.insert(last + 1, f"{name} = {text}")
    return True


def edited_text(text: str, values: dict) -> str:
    """The scene's TOML text with dotted keys set, its comments kept.

    Parameters
    ----------
    text : str
        The source scene's TOML text.
    values : dict
        ``{dotted key: value}``, each value as a scene writes it (a quantity string,
        a number, a list); keys of a section (``"valve_gear.lap"``), one level deep.

    Returns
    -------
    str
        The edited text; :func:`tomllib.loads` of it gives the source's tables with the
        keys set.  Where a value cannot be put in place (a key in a sub-table, an
        array of tables), the whole scene is written from its tables instead, without
        its comments.
    """
    data = tomllib.loads(text)
    want = with_keys(data, values)
    lines = text.splitlines()
    for key, value in values.items():
        table, _, name = key.rpartition(".")
        if "." in table or not table:
            break
        if not _set_line(lines, table, name, _toml_value(value)):
            lines += ["", f"[{table}]", f"{name} = {_toml_value(value)}"]
    else:
        out = "\n".join(lines) + "\n"
        try:
            if tomllib.loads(out) == want:
                return out
        except tomllib.TOMLDecodeError:
            pass
    return dumps(want)
