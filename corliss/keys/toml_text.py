"""A scene's tables as TOML text (the standard library reads TOML but does not write
it): enough of TOML for a scene, checked by reading the text back.  ``corliss study``'s
base scene comes from :func:`dumps`; ``corliss design`` and ``corliss fit`` edit the
source scene's text instead (:mod:`corliss.keys.scene_system`), and use :func:`dumps`
for a scene that has no text."""

from __future__ import annotations

import json
import math
import re
import tomllib

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k: str) -> str:
    return k if _BARE.match(k) else json.dumps(k)


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(f"no TOML form for {type(v).__name__}")


def _table(data: dict, path: list[str], lines: list[str]) -> None:
    subs: list[tuple[str, dict | list]] = []
    for k, v in data.items():
        if isinstance(v, dict):
            subs.append((k, v))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            subs.append((k, v))
        else:
            lines.append(f"{_key(k)} = {_value(v)}")
    for k, v in subs:
        name = ".".join(_key(p) for p in path + [k])
        if isinstance(v, dict):
            lines.append("")
            lines.append(f"[{name}]")
            _table(v, path + [k], lines)
        else:
            for item in v:
                lines.append("")
                lines.append(f"[[{name}]]")
                _table(item, path + [k], lines)


def dumps(data: dict, header: str = "") -> str:
    """TOML text of a scene's tables, checked by reading it back.

    Parameters
    ----------
    data : dict
        Tables, arrays of tables, strings, numbers (NaN and infinities included),
        booleans and arrays, as :func:`tomllib.loads` gives them.
    header : str, optional
        Text written first as comment lines, one ``#`` line per line of it.

    Returns
    -------
    str
        The TOML text, plain keys before sub-tables, ending in a newline.

    Raises
    ------
    TypeError
        If a value has no TOML form (a date is not written either).
    ValueError
        If the text does not read back as ``data``.
    """
    lines = [f"# {h}".rstrip() for h in header.splitlines()] + [""] if header else []
    _table(data, [], lines)
    text = "\n".join(lines).lstrip("\n") + "\n"
    if tomllib.loads(text) != data:
        raise ValueError("the scene's tables do not survive as TOML text")
    return text
