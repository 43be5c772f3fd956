"""The scene reference, printed from the declarations the loader reads with.

Every section's keys (:mod:`corliss.scene.sections`) and every gear's and governor's
(their registry entries' :class:`~corliss.keys.declared.KeyGroup`), with kind, accepted
units, default, range or choices, and which gear, governor or effect reads each key:
as Markdown (:func:`reference_markdown`, committed as ``docs/scene-reference.md``; a
test keeps the two equal) and as text for ``corliss explain`` and ``corliss list keys``.

Regenerate the page with ``python -m corliss.scene.reference > docs/scene-reference.md``.
"""

from __future__ import annotations

import difflib

from corliss.keys import units
from corliss.engine.options import EFFECTS
from corliss.errors import InputError
from corliss.governors import GOVERNORS
from corliss.keys.declared import Key, KeyGroup
from corliss.scene.loader import SECTIONS
from corliss.scene.sections import SECTION_KEYS
from corliss.valves import GEARS

#: The command that writes the committed page.
REGENERATE = "python -m corliss.scene.reference > docs/scene-reference.md"
#: Figures of a type's keys, drawn from its geometry by ``docs/figures.py`` at every
#: documentation build and shown beside its keys: (section, type) -> (file in docs/,
#: caption).
SKETCHES = {("valve_gear", "corliss"): ("corliss-gear-keys.png",
                        "The Corliss gear's keys on the bundled corliss-trip-gear scene's "
                        "geometry at the wrist plate's mid position; each angle's arc has "
                        "its arrow in the positive sense")}
#: Sections whose keys are those of the type they name.
TYPED = {"valve_gear": GEARS, "lp_valve_gear": GEARS, "governor": GOVERNORS}
_SECTION_DOC = {
    "title": "A string naming the scene (default: the scene file's name).",
    "valve_gear": "The valve gear: `type` names it, the other keys are its own "
                  "(corliss list keys GEAR; below, Valve gears).",
    "lp_valve_gear": "A compound's LP valve gear, keys as [valve_gear] (default: the HP "
                     "gear with its port lengths scaled to the LP bore).",
    "governor": "The governor of a transient run: `type` names it, the other keys are its "
                "own (corliss list keys GOVERNOR; below, Governors).",
}


def entries() -> dict[str, list]:
    """Every registry entry with declared keys, by section.

    Returns
    -------
    dict
        ``{"valve_gear": [RegistryEntry, ...], "governor": [...]}``, sorted by name.
    """
    return {"valve_gear": [GEARS[n] for n in sorted(GEARS)],
            "governor": [GOVERNORS[n] for n in sorted(GOVERNORS)]}


def _md(text: str) -> str:
    return str(text).replace("|", "\\|")


def _read(k: Key) -> str:
    parts = [k.when] if k.when else []
    if k.effect:
        parts.append(f"effect `{k.effect}`")
    return "; ".join(parts) or "always"


def _table(g: KeyGroup) -> list[str]:
    out = ["| Key | Kind | Default | Range or choices | Read | What it is |",
           "|---|---|---|---|---|---|"]
    for k in g.keys:
        kind = k.kind.replace("_", " ") + (", once or [head, crank]" if k.ends else "")
        out.append(f"| `{k.name}` | {_md(kind)} | {_md(k.default_text())} | "
                   f"{_md(k.range_text())} | {_md(_read(k))} | {_md(k.doc)} |")
    return out


def _index(section: str, es: list) -> list[str]:
    by_key: dict[str, list[str]] = {}
    for e in es:
        for k in e.keys.keys:
            by_key.setdefault(k.name, []).append(e.name)
    out = ["| Key | Read by |", "|---|---|"]
    for name in sorted(by_key):
        out.append(f"| `{section}.{name}` | {', '.join(by_key[name])} |")
    return out


def reference_markdown() -> str:
    """The scene reference as Markdown: sections, gears, governors, effects, units.

    Returns
    -------
    str
        The page committed as ``docs/scene-reference.md``.
    """
    out = ["# Scene reference", "",
           "<!-- Generated from the loader's key declarations: do not edit. Regenerate with",
           f"     {REGENERATE} -->", "",
           "Every key a scene may hold, as the loader reads it: its kind (with the units a "
           "quantity accepts, listed under [Units](#units)), its default, its valid range or "
           "choices, and when it is read. A quantity is a string with its unit "
           "(`\"12 in\"`, `\"100 psig\"`); pressures say absolute or gauge. "
           "`corliss explain KEY` prints the same at the terminal.", "",
           "## Sections", ""]
    for sec in SECTIONS:
        out.append(f"### [{sec}]" if sec != "title" else "### title")
        out.append("")
        if sec in SECTION_KEYS:
            out += [SECTION_KEYS[sec].doc, ""] + _table(SECTION_KEYS[sec]) + [""]
        else:
            out += [_SECTION_DOC[sec], ""]
    es = entries()
    for section, title, noun in (("valve_gear", "Valve gears", "gear"),
                                 ("governor", "Governors", "governor")):
        out += [f"## {title}", "",
                f"The keys of `[{section}]` by its `type`; every {noun} also takes `type`.", ""]
        for e in es[section]:
            out += [f"### {noun.capitalize()}: {e.name}", "", _md(e.summary), "",
                    e.keys.doc, ""]
            if (section, e.name) in SKETCHES:
                file, caption = SKETCHES[(section, e.name)]
                out += [f"![{caption}]({file})", "", f"*{caption}.*", ""]
            out += _table(_without_type(e.keys)) + [""]
        out += [f"### Which {noun} reads which key", ""] + _index(section, es[section]) + [""]
    out += ["## Effects", "", "Named in `run.effects`; each key listed is read with it.", "",
            "| Effect | What it models | Keys |", "|---|---|---|"]
    for name, what in EFFECTS.items():
        keys = [f"`{s}.{k.name}`" for s, g in SECTION_KEYS.items() for k in g.keys
                if k.effect == name]
        out.append(f"| `{name}` | {_md(what)} | {', '.join(keys) or '-'} |")
    out += ["", "## Units", "", "| Kind | Units accepted |", "|---|---|"]
    for kind in units.KINDS:
        out.append(f"| {kind.replace('_', ' ')} | {_md(', '.join(units.units_of(kind)))} |")
    out += ["", "Pressure: `psi`, `bar`, `kPa` and `MPa` take `a`, `(a)`, ` abs` or "
            "` absolute` for absolute, `g`, `(g)`, ` gauge` or ` gage` for gauge (read "
            "against `supply.barometer`); `Pa`, `atm`, `inHg` and `mmHg` are absolute; "
            "`inHg vacuum` is below the barometer.", "",
            "Length: `thou` is a thousandth of an inch (`\"15 thou\"` = 0.015 in), the unit "
            "in which live-steam builders give laps, leads and clearances.", ""]
    return "\n".join(out)


def _without_type(g: KeyGroup) -> KeyGroup:
    return KeyGroup(g.name, tuple(k for k in g.keys if k.name != "type"), g.doc)


# --- the terminal: corliss explain and corliss list keys ---------------------------------

def _block(where: str, k: Key, owners: list[str]) -> str:
    lines = [f"{where}" + (f"  ({', '.join(owners)})" if owners else ""), f"  {k.doc}",
             f"  kind:    {k.kind_text()}", f"  default: {k.default_text()}"]
    rng = k.range_text()
    if rng:
        lines.append(f"  {'choices: ' if k.kind in ('choice', 'list') else 'range:   '}{rng}")
    lines.append(f"  read:    {_read(k)}")
    return "\n".join(lines)


def _known() -> dict[str, str]:
    """Every name ``corliss explain`` takes, with what it is."""
    names = {}
    for sec in SECTIONS:
        names[sec] = "section"
        if sec in SECTION_KEYS:
            for k in SECTION_KEYS[sec].keys:
                names[f"{sec}.{k.name}"] = "key"
    for section, es in entries().items():
        for e in es:
            names[e.name] = "type"
            for k in e.keys.keys:
                names[f"{section}.{k.name}"] = "key"
                if section == "valve_gear":
                    names[f"lp_valve_gear.{k.name}"] = "key"
    for effect in EFFECTS:
        names[effect] = "effect"
    return names


def type_keys(name: str) -> str:
    """The keys of a gear or governor (both, when a name is each), as text.

    Parameters
    ----------
    name : str
        A registry name of a gear or governor (``"slide_valve"``, ``"porter"``).

    Returns
    -------
    str
        Each key with its kind, default, range and doc.

    Raises
    ------
    InputError
        If no gear or governor has that name; the message names the closest.
    """
    out = []
    for section, reg in (("valve_gear", GEARS), ("governor", GOVERNORS)):
        if name in reg:
            e = reg[name]
            out.append(f"[{section}] type = \"{name}\": {e.summary}\n{e.keys.doc}\n")
            out += [_block(f"{section}.{k.name}", k, []) for k in e.keys.keys]
            out.append("")
    if not out:
        names = sorted(GEARS) + sorted(GOVERNORS)
        raise InputError("list keys", name, "a gear or governor: " + ", ".join(
            dict.fromkeys(names)) + _hint(name, names))
    return "\n".join(out).rstrip() + "\n"


def _hint(name: str, candidates) -> str:
    near = difflib.get_close_matches(str(name), list(candidates), n=3, cutoff=0.6)
    return f" (closest: {', '.join(near)})" if near else ""


def explain(name: str) -> str:
    """What a scene key, section, gear, governor or effect is, as text.

    Parameters
    ----------
    name : str
        A dotted key (``"valve_gear.lap"``, ``"governor.ball_mass"``, ``"run.effects"``),
        a section (``"engine"``), a gear or governor (``"slide_valve"``), an effect
        (``"wall_heat"``), or a key without its section (``"lap"``: every table's key of
        that name).

    Returns
    -------
    str
        Its kind, accepted units, default, range or choices and who reads it.

    Raises
    ------
    InputError
        For a name that is none of these; the message names the closest valid ones.
    """
    known = _known()
    what = known.get(name)
    if what is None and "." not in name:
        # a bare key (``lap``): the same key in every section and table that has it
        full = sorted((k for k, w in known.items() if w == "key" and k.partition(".")[2] == name),
                      key=lambda k: (k.startswith("lp_"), k))
        if full:
            return "\n".join(explain(k).rstrip("\n") for k in full) + "\n"
    if what is None:
        raise InputError("explain", name, "a scene key (section.key), a section, a gear, a "
                         "governor or an effect (corliss list keys TYPE lists a type's keys)"
                         + _hint(name, known))
    if what == "type":
        return type_keys(name)
    if what == "effect":
        keys = [f"{s}.{k.name}" for s, g in SECTION_KEYS.items() for k in g.keys
                if k.effect == name]
        return (f"effect {name} (run.effects): {EFFECTS[name]}\n  keys: "
                f"{', '.join(keys) or '-'}\n")
    if what == "section":
        if name in SECTION_KEYS:
            g = SECTION_KEYS[name]
            return "\n".join([f"[{name}]: {g.doc}"]
                             + [_block(f"{name}.{k.name}", k, []) for k in g.keys]) + "\n"
        return f"[{name}]: {_SECTION_DOC[name]}\n"
    section, _, key = name.partition(".")
    if section in SECTION_KEYS:
        out = _block(name, SECTION_KEYS[section][key], []) + "\n"
        if name == "run.effects":
            out += "  effects:\n" + "".join(f"    {e}: {d}\n" for e, d in EFFECTS.items())
        return out
    reg = TYPED[section]
    blocks: list[tuple[Key, list[str]]] = []
    for n in sorted(reg):
        g = reg[n].keys
        if key in g:
            for k, owners in blocks:
                if k == g[key]:
                    owners.append(n)
                    break
            else:
                blocks.append((g[key], [n]))
    return "\n".join(_block(name, k, owners) for k, owners in blocks) + "\n"


if __name__ == "__main__":      # pragma: no cover
    print(reference_markdown(), end="")
