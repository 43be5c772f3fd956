"""``corliss design``: a scene's valve designed for the events asked, written back as a
runnable scene with its Zeuner and Bilgram diagrams.

The physics is :mod:`corliss.valves.design`; this module knows scenes: it takes the
engine (its connecting rod, when the scene names ``rod_angularity``) and the port and
rods of the scene's gear, designs the gear, writes its ``[valve_gear]`` table back
into the scene's tables in the scene's units, rebuilds the scene from them and checks
that the rebuilt scene's events (:func:`corliss.engine.model.scene_events`, what
``corliss events`` prints) are those asked.

A plain slide valve (``type = "slide_valve"``) is designed whole: eccentricity,
angular advance, steam and exhaust laps per end; so is a slip eccentric's valve, in the
direction it runs (the driving stop's advance).  A gear with a setting (link and
radial gears, shaft governors, riding cut-off valves, the Corliss cam) keeps its
linkage and gets the setting that gives the cut-off asked.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import matplotlib.pyplot as plt
from matplotlib.figure import Figure

from corliss.keys import units
from corliss.engine.model import build_gear, geometry_of, scene_events
from corliss.errors import InputError
from corliss.files.run_output import OutputFiles, output_stem
from corliss.plot import plot_gear
from corliss.plot.gears import plot_bilgram_diagram, plot_zeuner_diagram
from corliss.scene.loader import Scene, bundled_scenes, default_scene_path, find_scene, load_scene, scene_from_dict
from corliss.keys.edits import with_keys
from corliss.keys.scene_system import SYSTEMS, quantity, scene_text
from corliss.keys.toml_text import dumps
from corliss.valves.design import (SettingDesign, SlideValveDesign, design_setting,
                                   design_slide_valve)
from corliss.valves.fink_motion import FinkMotionSpec
from corliss.valves.link_motion import LinkMotionSpec
from corliss.valves.single_acting import working_gear
from corliss.valves.slide_valve import LappedValve, SlideValveSpec
from corliss.valves.slip_eccentric import SlipEccentricSpec

#: The scene keys that hold a gear's setting, when it is not the number ``setting``:
#: the block's offset as a length (setting x half link).
BLOCK_KEY = {"link_motion": "block", "fink_motion": "block"}
#: The gears designed whole as a plain slide valve: the slip eccentric in the direction it
#: runs (its advance on the stop that drives) is one.
SLIDE_VALVES = ("slide_valve", "slip_eccentric")
#: The designed scene's events must be the asked ones to this [deg] after the round
#: trip through the TOML text (12 significant digits).
SCENE_CHECK_DEG = 1e-4
#: The scene written is rounded as a drawing is (:mod:`corliss.keys.scene_system`:
#: lengths to 0.001 in or 0.01 mm, angles to 0.01 deg); an asked event it moves by
#: more than this [deg] is warned of.  A thou of lap on a 3 in eccentric moves an
#: event by some 0.02 deg, so the warning fires only on a small or nearly square valve.
ROUNDING_WARN_DEG = 0.05
#: Decimal places of a gear's setting written (a notch or a block to 1e-4 of its range).
SETTING_DECIMALS = 4
#: A gear set for the cut-off asked at one end warns when the other end's differs by
#: more than this fraction of the stroke: the greatest inequality of cut-off between the
#: strokes that the connecting rod's angularity alone gave Peabody's Stephenson link
#: (0.067 of the stroke, 1.6 in on a 24 in stroke at L/R 7.5; Peabody, *Link Motion*,
#: MIT thesis, 1877), so that a larger one is the linkage's own.
CUTOFF_WARN_FRAC = 0.067
#: The two ends, in the order of the gear's pairs.
ENDS = ("head", "crank")


@dataclass(frozen=True)
class Design:
    """A designed scene (made by :func:`design`).

    Parameters
    ----------
    scene : Scene
        The scene with the designed gear, built from ``text``.
    text : str
        The designed scene as TOML (what ``STEM.toml`` holds): the source scene's
        text, comments and key order kept, the designed keys set, every quantity in
        one unit system and rounded as a drawing is
        (:func:`corliss.keys.scene_system.scene_text`).
    valve : SlideValveDesign or SettingDesign
        The design (SI, unrounded).
    events : dict
        The written scene's events by :func:`corliss.engine.model.scene_events`
        (per end, crank angles [deg] and fractions of the stroke [-]).
    base : str
        The scene designed from (name or path).
    stem : str
        The stem of the files written: the source scene's name, the unit system when
        it is not the scene's own, and ``design`` (``default.design``,
        ``default.SI.design``).
    exact_events : dict or None
        The design's own events, of its keys at 12 figures (checked to
        :data:`SCENE_CHECK_DEG` against those asked), before the drawing's rounding.
    """

    scene: Scene
    text: str
    valve: SlideValveDesign | SettingDesign
    events: dict
    base: str
    stem: str = "design"
    exact_events: dict | None = None

    def write(self, out_dir) -> dict:
        """Write ``STEM.toml`` and the diagrams into a folder, all or nothing.

        Parameters
        ----------
        out_dir : str or Path
            The output folder (made if missing).

        Returns
        -------
        dict of str to Path
            ``{kind: path}`` of the files written (see :func:`write_design`).
        """
        return write_design(self, out_dir)

    @property
    def warnings(self) -> list[str]:
        """What the design gives at an end that was not asked for, in words.

        A slide valve is designed for the lead and opening asked at the reference end;
        equal cut-offs with a finite rod then give the other end laps of its own, and
        with them its own lead and opening.  A gear with a setting is set for the
        cut-off asked at one end (or their mean); its linkage gives the other end the
        cut-off, lead and opening it does.  Warned: an end whose lead is more than
        twice the reference end's (the one asked) and 1/16 in (1.6 mm) beyond it, or
        less than half of it; an end whose greatest opening passes the port's width by
        more than a quarter of it (the valve overtravels the port, its travel spent
        past the port's edge); with a setting, the other end's cut-off more than
        :data:`CUTOFF_WARN_FRAC` of the stroke from the one asked.  Lengths are
        quoted in the scene's unit system.

        Returns
        -------
        list of str
            One sentence per finding (empty for a design without one).
        """
        out = self._rounding_warnings()
        v = self.valve
        q = _length_quoter(self.scene.output.units)
        if isinstance(v, SlideValveDesign):
            ref = 0 if v.reference_end == "head" else 1
            leads = v.lead_m
            openings = v.max_opening_m
            width = getattr(self.scene.gear, "port_width_m", None)
            widths = (width, width)
            lead_why = (f"asked at the {v.reference_end} end (equal cut-offs give the ends "
                        "laps, and so leads, of their own; --equalise laps gives equal laps)")
        else:
            ref = 1 if v.end == "crank" else 0
            ev = (v.events["head"], v.events["crank"])
            leads = (ev[0]["lead_m"], ev[1]["lead_m"])
            # the signed opening's greatest: one edge's opening (the port's whole one
            # over its openings an edge) and the overtravel past it
            n = v.gear.openings_per_edge()
            openings = (ev[0]["max_port_opening_m"] / n[0] + ev[0]["overtravel_m"],
                        ev[1]["max_port_opening_m"] / n[2] + ev[1]["overtravel_m"])
            steam_ports = v.gear.port_widths()
            widths = (float(steam_ports[0]), float(steam_ports[2]))
            lead_why = (f"at the {ENDS[ref]} end (the gear's linkage gives each end its "
                        "own lead at a setting)")
            if v.end != "mean":
                k = 1 - ref
                cut = ev[k]["cutoff_frac"]
                if cut is not None and abs(cut - v.cutoff_frac) > CUTOFF_WARN_FRAC:
                    out.append(f"{ENDS[k]} end: cut-off {cut:.3f} of the stroke against the "
                               f"{v.cutoff_frac:.3f} asked at the {v.end} end (one setting "
                               "serves both ends; --end mean sets it for their mean)")
        lead0 = leads[ref]
        for k, end in enumerate(ENDS):
            if k != ref and lead0 > 0.0 and (
                    (leads[k] > 2.0 * lead0 and leads[k] - lead0 > units.INCH_m / 16.0)
                    or leads[k] < 0.5 * lead0):
                out.append(f"{end} end: lead {q(leads[k])} against the {q(lead0)} {lead_why}")
        for k, end in enumerate(ENDS):
            w = widths[k]
            if w and openings[k] > 1.25 * w:
                out.append(f"{end} end: greatest opening {q(openings[k])} on a {q(w)} port: "
                           f"the valve overtravels the port by {q(openings[k] - w)}")
        return out

    def _rounding_warnings(self) -> list[str]:
        """The asked events the written scene's rounding moves by more than
        :data:`ROUNDING_WARN_DEG`."""
        out = []
        for end, want in self.valve.asked_deg.items():
            if self.scene.engine.steam_ends not in ("both", end):
                continue
            for key, deg in want.items():
                got = self.events[end][key]
                if got is not None and abs((got - deg + 180.0) % 360.0 - 180.0) > ROUNDING_WARN_DEG:
                    out.append(f"{end} end: {key[:-4]} at {got:.3f} deg in the scene written "
                               f"against {deg:.3f} deg asked (the drawing's rounding: lengths "
                               "to 0.001 in or 0.01 mm, angles to 0.01 deg)")
        return out

    def summary(self) -> dict:
        """The design as plain JSON-able values (SI, unit in every name).

        Returns
        -------
        dict
            ``base_scene``, ``gear``, ``events`` (the written scene's),
            ``warnings`` (:attr:`warnings`) and ``units_system`` (the written scene's);
            for a slide valve its
            ``eccentricity_m``, ``angular_advance_deg``, ``lap_m``, ``exhaust_lap_m``,
            ``lead_m`` and ``max_opening_m`` (head, crank), ``equalise``,
            ``reference_end``, its Zeuner (infinite-rod) equivalent and the events
            asked (``asked_deg``); for a gear with a setting its ``setting``,
            ``setting_name``, ``end``, ``cutoff_frac`` and ``asked_deg``.
        """
        v = self.valve
        out: dict[str, object]      # names, numbers, lists and tables, by the gear
        out = {"base_scene": self.base, "gear": self.scene.gear_type, "events": self.events,
               "warnings": self.warnings, "units_system": self.scene.output.units}
        if isinstance(v, SlideValveDesign):
            out.update(eccentricity_m=v.eccentricity_m,
                       angular_advance_deg=math.degrees(v.angular_advance_rad),
                       lap_m=list(v.lap_m), exhaust_lap_m=list(v.exhaust_lap_m),
                       lead_m=list(v.lead_m), max_opening_m=list(v.max_opening_m),
                       equalise=v.equalise, reference_end=v.reference_end,
                       zeuner={"eccentricity_m": v.zeuner["eccentricity_m"],
                               "angular_advance_deg": math.degrees(v.zeuner["angular_advance_rad"]),
                               "lap_m": v.zeuner["lap_m"]},
                       asked_deg=v.asked_deg)
        else:
            out.update(setting=v.setting, setting_name=v.setting_name, end=v.end,
                       cutoff_frac=v.cutoff_frac, asked_deg=v.asked_deg)
        return out


def _length(key: str, v, kind: str = "length"):
    if v is None:
        return None
    if isinstance(v, (list, tuple)):
        if len(v) != 2:
            raise InputError(key, v, "one value, or a pair (head, crank)")
        return tuple(_length(key, x, kind) for x in v)
    if isinstance(v, str):
        return units.parse(v, kind, key)
    try:
        return float(v)
    except (TypeError, ValueError):
        raise InputError(key, v, f"a {kind} with its unit, e.g. "
                         + ("\"0.25 in\"" if kind == "length" else "\"30 deg\"")) from None


def _fractions(key: str, v):
    if isinstance(v, str):
        parts = [p for p in v.split(",") if p.strip()]
        try:
            vals = [float(p) for p in parts]
        except ValueError:
            raise InputError(key, v, "a fraction of the stroke, or two (head,crank)") from None
        if len(vals) not in (1, 2):
            raise InputError(key, v, "a fraction of the stroke, or two (head,crank)")
        return vals[0] if len(vals) == 1 else tuple(vals)
    return v


def _scene(scene) -> tuple[Scene, str]:
    if isinstance(scene, Scene):
        bundled = {str(v): k for k, v in bundled_scenes().items()}
        return scene, bundled.get(str(scene.source), scene.source or scene.name)
    path = find_scene(scene) if scene is not None else default_scene_path()
    return load_scene(path), str(scene if scene is not None else "default")


def design(scene=None, *, cutoff, cutoff_crank=None, lead=None, max_opening=None,
           eccentricity=None, lap=None, angular_advance=None, lead_angle=None,
           overtravel=None, release=None, compression=None,
           exhaust_lap=None, equalise: str = "cutoff", reference_end: str = "head",
           end: str = "head", units_system: str | None = None) -> Design:
    """Design a scene's valve for the events asked (the arguments of ``corliss design``).

    Parameters
    ----------
    scene : Scene, str or Path, optional
        The scene to design for (a file, a bundled scene's name, a Scene); the default
        scene when None.
    cutoff : float
        Cut-off, fraction of the stroke [-].
    cutoff_crank : float, optional
        The crank end's cut-off [-], when it differs (slide valve).
    lead, max_opening, eccentricity, lap : str or float, optional
        Quantity strings (``"0.25 in"``) or SI floats [m].  Of these four and
        ``angular_advance`` and ``lead_angle``, exactly two are given (slide valve;
        Spangler Arts. 19-22).
    angular_advance : str or float, optional
        The eccentric's angular advance, ``"30 deg"`` or [rad] (slide valve).
    lead_angle : str or float, optional
        The crank's angle before the dead point at admission (Spangler Art. 21),
        ``"2 deg"`` or [rad] (slide valve).
    overtravel : str or float, optional
        Instead of ``max_opening``: the valve's travel past the port, a quantity
        string or [m] (the opening is then the port width plus it, Art. 18).
    release, compression : float, (float, float) or str, optional
        Fractions of the stroke as ``corliss events`` gives them ("0.9" or "0.9,0.92"
        for head, crank) (slide valve).
    exhaust_lap : str, float or pair, optional
        Instead of release or compression, a quantity string or [m], or a pair
        (head, crank) (slide valve).
    equalise : str, optional
        ``"cutoff"`` (laps per end) or ``"laps"`` (equal laps) (slide valve).
    reference_end : str, optional
        ``"head"`` or ``"crank"``: where the lead and opening asked hold (slide valve).
    end : str, optional
        Whose cut-off a gear's setting is found for: ``"head"``, ``"crank"``,
        ``"mean"`` (gears with a setting).
    units_system : str, optional
        ``"US"`` or ``"SI"``: the unit system the scene is written in (every
        quantity of it); default the scene's ``[output] units``.

    Returns
    -------
    Design
        The designed scene, its TOML text, the design and the written scene's events.
        The design is checked to :data:`SCENE_CHECK_DEG` against the events asked
        through the scene's tables at 12 figures; the scene written is rounded as a
        drawing is, and an event its rounding moves by more than
        :data:`ROUNDING_WARN_DEG` is warned of (:attr:`Design.warnings`).

    Raises
    ------
    InputError
        Naming the event that no valve (or no setting) can give, and what is valid.
    """
    base, base_name = _scene(scene)
    if units_system is not None:
        if units_system not in SYSTEMS:
            raise InputError("--units", units_system, "US or SI")
        base = dataclasses.replace(base, output=dataclasses.replace(base.output,
                                                                    units=units_system))
    if base.compound is not None:
        raise InputError("scene", base_name, "a simple engine: a compound's two gears are "
                         "not designed here")
    geo = geometry_of(base)

    def frac(t):
        return float(geo.fraction(t))

    valve: SlideValveDesign | SettingDesign
    if base.gear_type in SLIDE_VALVES:
        assert isinstance(base.gear, SlideValveSpec)    # the registry's spec of either
        valve = design_slide_valve(
            base.gear, frac, cutoff=cutoff, cutoff_crank=cutoff_crank,
            lead_m=_length("lead", lead), max_opening_m=_length("max_opening", max_opening),
            eccentricity_m=_length("eccentricity", eccentricity), lap_m=_length("lap", lap),
            angular_advance_rad=_length("angular_advance", angular_advance, "angle"),
            lead_angle_rad=_length("lead_angle", lead_angle, "angle"),
            overtravel_m=_length("overtravel", overtravel),
            release=_fractions("release", release),
            compression=_fractions("compression", compression),
            exhaust_lap_m=_length("exhaust_lap", exhaust_lap), equalise=equalise,
            reference_end=reference_end, length_unit=_unit(base))
    else:
        slide_args = {"cutoff_crank": cutoff_crank, "lead": lead, "max_opening": max_opening,
                      "eccentricity": eccentricity, "lap": lap,
                      "angular_advance": angular_advance, "lead_angle": lead_angle,
                      "overtravel": overtravel,
                      "release": release,
                      "compression": compression, "exhaust_lap": exhaust_lap}
        for key, value in slide_args.items():
            if value is not None:
                raise InputError(key, value, f"only the cut-off (and the end): the "
                                 f"{base.gear_type} gear is designed by its setting, its linkage "
                                 "kept (a plain slide valve is designed whole)")
        gear = build_gear(base)
        if gear.setting_range is None:
            raise InputError("valve_gear.type", base.gear_type, "a plain slide valve or a gear "
                             "with a setting")
        valve = design_setting(gear, frac, cutoff, end=end)
    data = _designed_tables(base, valve)
    designed = scene_from_dict(tomllib.loads(dumps(data)), name="design")
    ev = scene_events(designed)
    for e, want in valve.asked_deg.items():
        if designed.engine.steam_ends not in ("both", e):
            continue        # a single-acting cylinder's idle end: no events to check
        for key, deg in want.items():
            got = ev[e][key]
            if got is None or abs((got - deg + 180.0) % 360.0 - 180.0) > SCENE_CHECK_DEG:
                raise RuntimeError(f"designed scene check failed: {e} {key} asked {deg:.6f} "
                                   f"deg, the scene gives {got}")
    system = base.output.units
    stem = f"{output_stem(base)}.design"
    text = scene_text(base.text if base.text is not None else dumps(_tables(base)), system,
                      _written_values(base, valve, system),
                      drop=("valve_gear.lead",) if isinstance(valve, SlideValveDesign) else (),
                      header=_header(base, base_name, valve))
    written = dataclasses.replace(scene_from_dict(tomllib.loads(text), name=stem), text=text)
    return Design(scene=written, text=text, valve=valve, events=scene_events(written),
                  base=base_name, stem=stem, exact_events=ev)


def _length_quoter(system: str):
    """A length [m] in words in a unit system's unit: inches (US) or millimetres (SI),
    to three figures."""
    unit = "in" if system == "US" else "mm"
    return lambda m: f"{units.to_unit(m, unit):.3g} {unit}"


# ---------------------------------------------------------------- the scene's tables
def _tables(scene: Scene) -> dict:
    """The scene's tables as read: every scene a design starts from has them."""
    if scene.data is None:
        raise InputError("scene", scene.name, "a scene loaded from tables or a file (a "
                         "design writes its tables back)")
    return scene.data


def _half_link_m(gear: object) -> float:
    """Half the link of a link motion's or a Fink motion's spec [m]: what the block's
    offset is in units of."""
    if isinstance(gear, FinkMotionSpec):
        return gear.link.half_link_m
    if isinstance(gear, LinkMotionSpec):
        return gear.half_link_m
    raise TypeError(f"{type(gear).__name__} is no link motion")


def _unit(scene: Scene) -> str:
    return "in" if scene.output.units == "US" else "mm"


def _q(v: float, unit: str) -> str:
    return f"{units.to_unit(v, unit):.12g} {unit}"


def _pair_q(pair, unit):
    a, b = pair
    return _q(a, unit) if a == b else [_q(a, unit), _q(b, unit)]


def _designed_tables(base: Scene, valve) -> dict:
    """The scene's tables with the designed keys of its gear set, in the scene's units
    (every other key as the scene wrote it)."""
    u = _unit(base)
    if isinstance(valve, SlideValveDesign):
        advance = "angular_advance"
        if base.gear_type == "slip_eccentric":
            # the driving stop's advance; the other stop's kept as the scene had it
            g = base.gear
            assert isinstance(g, SlipEccentricSpec)     # the registry's spec of the type
            ahead = g.direction == "ahead"
            advance = "forward_advance" if ahead else "backward_advance"
            other = g.backward_advance_rad if ahead else g.forward_advance_rad
            values_other = {f"valve_gear.{'backward' if ahead else 'forward'}_advance":
                            f"{math.degrees(other):.12g} deg"}
        else:
            values_other = {}
        values = {"valve_gear.eccentricity": _q(valve.eccentricity_m, u),
                  f"valve_gear.{advance}": f"{math.degrees(valve.angular_advance_rad):.12g} deg",
                  **values_other,
                  "valve_gear.lap": _pair_q(valve.lap_m, u),
                  "valve_gear.exhaust_lap": _pair_q(valve.exhaust_lap_m, u)}
    elif base.gear_type in BLOCK_KEY:
        half = _half_link_m(base.gear)
        values = {f"valve_gear.{BLOCK_KEY[base.gear_type]}": _q(valve.setting * half, u)}
    else:
        values = {"valve_gear.setting": float(f"{valve.setting:.12g}")}
    values["title"] = f"{_tables(base).get('title', base.title)} (designed)"
    data = with_keys(_tables(base), values)
    if isinstance(valve, SlideValveDesign):
        data["valve_gear"].pop("lead", None)     # the advance is written instead (exact)
    return data


def _pair_written(pair, system: str):
    a, b = (quantity(x, "length", system) for x in pair)
    return a if a == b else [a, b]


def _written_values(base: Scene, valve, system: str) -> dict:
    """The designed keys as the scene written gives them: in ``system``, rounded as a
    drawing is (:mod:`corliss.keys.scene_system`)."""
    if isinstance(valve, SlideValveDesign):
        advance, other = "angular_advance", {}
        if base.gear_type == "slip_eccentric":
            g = base.gear
            assert isinstance(g, SlipEccentricSpec)     # the registry's spec of the type
            ahead = g.direction == "ahead"
            advance = "forward_advance" if ahead else "backward_advance"
            other = {f"valve_gear.{'backward' if ahead else 'forward'}_advance": quantity(
                g.backward_advance_rad if ahead else g.forward_advance_rad, "angle", system)}
        values = {"valve_gear.eccentricity": quantity(valve.eccentricity_m, "length", system),
                  f"valve_gear.{advance}": quantity(valve.angular_advance_rad, "angle", system),
                  **other,
                  "valve_gear.lap": _pair_written(valve.lap_m, system),
                  "valve_gear.exhaust_lap": _pair_written(valve.exhaust_lap_m, system)}
    elif base.gear_type in BLOCK_KEY:
        half = _half_link_m(base.gear)
        values = {f"valve_gear.{BLOCK_KEY[base.gear_type]}": quantity(valve.setting * half,
                                                                      "length", system)}
    else:
        values = {"valve_gear.setting": round(valve.setting, SETTING_DECIMALS)}
    values["title"] = f"{(base.data or {}).get('title', base.title)} (designed)"
    return values


def _header(base: Scene, base_name: str, valve) -> str:
    system = base.output.units
    lines = [f"Designed by `corliss design` from the scene {base_name}.",
             f"Written in {system} units as a drawing is: lengths to the nearest "
             + ("0.001 in" if system == "US" else "0.01 mm")
             + ", angles to 0.01 deg, other quantities to four figures.",
             "Events asked (crank angle from head-end dead centre):"]
    for end, want in valve.asked_deg.items():
        for key, deg in want.items():
            lines.append(f"  {end:5s} {key[:-4]:12s} {deg:9.4f} deg")
    if isinstance(valve, SlideValveDesign):
        q = lambda m: quantity(m, "length", system)  # noqa: E731
        lines.append(f"Leads {q(valve.lead_m[0])} (head), {q(valve.lead_m[1])} (crank); "
                     f"greatest openings {q(valve.max_opening_m[0])}, "
                     f"{q(valve.max_opening_m[1])}.")
    else:
        lines.append(f"Setting {valve.setting:.6f}: {valve.setting_name}.")
    return "\n".join(lines)


# ---------------------------------------------------------------- files
def _mark_asked(ax, valve, radius: float, drawn_from: str) -> None:
    """Rays along the crank angles asked, each labelled."""
    import numpy as np
    colours = {"head": "tab:red", "crank": "tab:blue"}
    for end, want in valve.asked_deg.items():
        for key, deg in want.items():
            p = np.radians(deg)
            ax.plot([0, radius * np.cos(p)], [0, radius * np.sin(p)], color=colours[end],
                    lw=1.6, alpha=0.8, label=f"asked {end} {key[:-4]} {deg:.2f} deg")
    ax.legend(fontsize=7, frameon=False, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    ax.text(1.02, 0.0, "asked events: their exact crank angles (finite rods);\n"
            f"the diagram: {drawn_from}", transform=ax.transAxes, fontsize=7,
            color="0.3", va="bottom")


def refuse_overwrite(path: Path, text: str, what: str) -> None:
    """Refuse to write ``text`` over a file that holds something else.

    A command's files are named for the scene, the command and the unit system
    (:func:`corliss.files.run_output.output_stem`); two designs (or fits) of one scene
    into one folder would still share a name, and the second would silently replace
    the first.  The same command again writes the same text, and may.

    Parameters
    ----------
    path : Path
        The file about to be written.
    text : str
        What would be written into it.
    what : str
        What it is, for the message (``"design"``).

    Raises
    ------
    InputError
        Naming ``--out``, the file and what to do, when it exists with other content.
    """
    if path.exists() and (not path.is_file()
                          or path.read_text(encoding="utf-8", errors="replace") != text):
        raise InputError("--out", str(path.parent), f"a folder without another {what} of "
                         f"this scene: {path.name} there holds a different one, which "
                         "this would overwrite (give another --out, or remove the file)")


def write_design(design: Design, out_dir) -> dict:
    """Write ``STEM.toml`` and the diagrams with the asked events marked.

    ``STEM.zeuner.png`` and ``STEM.bilgram.png`` for a lapped valve (Spangler
    Arts. 10-18, 149), ``STEM.gear.png`` (the gear's own panels) for another, where
    STEM is :attr:`Design.stem` (``default.design``; ``default.SI.design`` for a
    design of an inch scene written in SI).  Staged and moved into place together; a
    failure leaves ``out_dir`` as it was.  A different design of the same stem
    already in ``out_dir`` is not overwritten (:func:`refuse_overwrite`).

    Parameters
    ----------
    design : Design
        The designed scene.
    out_dir : str or Path
        The output folder (made if missing).

    Returns
    -------
    dict of str to Path
        ``{kind: path}`` of the files written: ``scene``, and ``zeuner`` and
        ``bilgram`` or ``gear``.

    Raises
    ------
    InputError
        Before anything is written, when ``out_dir`` holds a different design of
        the same stem.
    """
    stem = design.stem
    refuse_overwrite(Path(out_dir) / f"{stem}.toml", design.text, "design")
    gear = build_gear(design.scene)
    units_system = design.scene.output.units
    files = {}
    with OutputFiles(out_dir) as out:
        out.stage(f"{stem}.toml").write_text(design.text, encoding="utf-8")
        files["scene"] = Path(out_dir) / f"{stem}.toml"
        if isinstance(working_gear(gear), LappedValve):
            gear = working_gear(gear)
            for kind, draw, drawn_from in (
                    ("zeuner", plot_zeuner_diagram, "the valve's exact travel"),
                    ("bilgram", plot_bilgram_diagram, "the gear's Zeuner form (infinite rods)")):
                fig = Figure(figsize=(7, 7))      # no pyplot: the user's backend untouched
                ax = fig.add_subplot()
                drawn = draw(gear, ax=ax, units_system=units_system)
                # the asked events as long as the diagram's own crank lines
                _mark_asked(ax, design.valve, drawn["crank_radius"], drawn_from)
                ax.set_title(f"{drawn['ax'].get_title()}: {design.scene.title}", fontsize=9)
                name = f"{stem}.{kind}.png"
                fig.savefig(out.stage(name), dpi=120, bbox_inches="tight", format="png")
                files[kind] = Path(out_dir) / name
        else:
            with plt.ioff():
                fig = plot_gear(gear, units_system=units_system)["figure"]
            # a gear that is no lapped valve was designed by its setting
            assert isinstance(design.valve, SettingDesign)
            try:
                fig.suptitle(f"{design.scene.title}: setting {design.valve.setting:.4f}", fontsize=10)
                name = f"{stem}.gear.png"
                fig.savefig(out.stage(name), dpi=120, bbox_inches="tight", format="png")
                files["gear"] = Path(out_dir) / name
            finally:
                plt.close(fig)
    return files
