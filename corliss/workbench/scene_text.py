"""A scene's TOML text with some keys set, its comments and layout kept.

The workbench saves the scene a person has set by hand.  Written again from its
tables (:func:`corliss.keys.toml_text.dumps`) it would lose the source's comments, which
cite where each dimension came from; so the source text is edited in place, by the same
round-trip editor ``design`` and ``fit`` write their scenes with
(:func:`corliss.keys.scene_system.edited`): a key that is there has its value replaced
(a comment after it kept), a key that is not is added at the end of its table.  The
text is read back and must give exactly the edited tables, else the tables are written
plainly.
"""

from __future__ import annotations

import tomllib

from corliss.keys.edits import with_keys
from corliss.keys.scene_system import edited
from corliss.keys.toml_text import dumps


def edited_text(text: str, values: dict) -> str:
    """The scene's TOML text with dotted keys set, its comments kept.

    Parameters
    ----------
    text : str
        The source scene's TOML text.
    values : dict
        ``{dotted key: value}``, each value as a scene writes it (a quantity string,
        a number, a list).

    Returns
    -------
    str
        The edited text; :func:`tomllib.loads` of it gives the source's tables with the
        keys set.  Where the edit does not read back as those tables, the whole scene
        is written from its tables instead, without its comments.
    """
    want = with_keys(tomllib.loads(text), values)
    try:
        out = edited(text, values)
        if tomllib.loads(out) == want:
            return out
    except (tomllib.TOMLDecodeError, ValueError, TypeError):
        pass
    return dumps(want)
