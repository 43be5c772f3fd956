"""``corliss fit``: scene keys calibrated to a measured card, as a function and its
files.

:func:`fit` takes what the command takes (a scene, a card CSV, ``KEY=LOW:HIGH``
ranges, the fidelity, refine, bootstrap and seed, an output folder), checks all of it
before any simulation, runs :func:`corliss.fitting.solver.fit_card` and, given ``out``,
writes into it as one transaction (:class:`corliss.files.run_output.OutputFiles`),
each file named for the scene, the unit system when it is not the scene's own, and
the command (STEM = ``default.fit``, ``default.SI.fit``: :func:`fit_stem`):

- ``STEM.json``: the fitted values with their standard errors (or why a key is not
  determined), the correlations, the residual r.m.s. in the pressure unit of the
  units system, the m.e.p. of each end measured and fitted, and what reruns the fit:
  the scene's text and SHA-256, the card file's SHA-256, the ranges, the versions;
- ``STEM.toml``: the scene with the fitted values, runnable by ``corliss run``: the
  source scene's text with its comments, every quantity in the one unit system
  (:func:`corliss.keys.scene_system.scene_text`);
- ``STEM.card.png``: the measured card over the fitted one.

A folder that holds another fit of the same stem (other ranges, card or scene) is
refused before any simulation (:func:`check_out`): one fit never overwrites another.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
from pathlib import Path

from corliss.keys import units
from corliss.errors import InputError
from corliss.fitting import solver
from corliss.fitting.card import MeasuredCard, read_card
from corliss.fitting.solver import FitResult, fit_card
from corliss.keys.scene_system import scene_text
from corliss.keys.toml_text import dumps
from corliss.plot.fit_card import plot_fit_card
from corliss.plot.shape import one_shape
from corliss.files.run_output import (DPI, PNG_OPTIONS, OutputFiles, dependency_versions,
                                      jsonable, output_stem, package_version, plain_text)
from corliss.scene.loader import Scene, find_scene, load_scene
from corliss.keys.edits import KeyRange, get_key, parse_range

#: The fit's files by kind: their names after the stem (:func:`fit_stem`).
FILES = {"summary": "json", "scene": "toml", "card": "card.png"}


def fit_stem(scene: Scene, units_system: str | None = None) -> str:
    """The stem of a fit's files: ``default.fit``, ``default.SI.fit``.

    Parameters
    ----------
    scene : Scene
        The scene fitted.
    units_system : str, optional
        The files' units, when not the scene's ``[output] units``.

    Returns
    -------
    str
        :func:`corliss.files.run_output.output_stem` and ``.fit``.
    """
    return f"{output_stem(scene, units_system)}.fit"


def _vary_text(ranges) -> list[str]:
    return [f"{r.key}={r.low:g}:{r.high:g}{r.unit}" for r in ranges]


def _sha256(path) -> str | None:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except (OSError, TypeError):
        return None


def check_out(out_dir, scene: Scene, card, vary, units_system: str | None = None) -> None:
    """Refuse, before any simulation, an output folder that holds another fit of the
    same stem: other ranges, another card or another scene (the same fit again, at
    another fidelity or with a bootstrap, may replace its files).

    Parameters
    ----------
    out_dir : str or Path
        The output folder.
    scene : Scene
        The scene to fit.
    card : str, Path or MeasuredCard
        The card (its file's SHA-256 is compared).
    vary : str or list
        The ranges, as :func:`fit` takes them.
    units_system : str, optional
        The files' units, when not the scene's.

    Raises
    ------
    InputError
        Naming ``--out`` and the file, when it holds another fit.
    """
    path = Path(out_dir) / f"{fit_stem(scene, units_system)}.{FILES['summary']}"
    if not path.exists():
        return
    try:
        old = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        old = None
    src = card.source if isinstance(card, MeasuredCard) else card
    scene_sha = hashlib.sha256(scene.text.encode("utf-8")).hexdigest() if scene.text else None
    same = (isinstance(old, dict) and old.get("vary") == _vary_text(_ranges(vary))
            and old.get("card_sha256") == _sha256(src)
            and old.get("scene_sha256") == scene_sha)
    if not same:
        raise InputError("--out", str(path.parent), f"a folder without another fit of this "
                         f"scene: {path.name} there holds a fit of other ranges, card or "
                         "scene, which this would overwrite (give another --out, or remove "
                         "the file)")


def _ranges(vary) -> list[KeyRange]:
    if isinstance(vary, (str, KeyRange)):
        vary = [vary]
    out = []
    for v in vary or []:
        out.append(v if isinstance(v, KeyRange) else parse_range(v, "--vary"))
    if not out:
        raise InputError("--vary", None, "at least one KEY=LOW:HIGH, e.g. "
                         "--vary engine.clearance=0.04:0.14 --vary valve_gear.lap=0.7:1.3in")
    return out


def fit(scene, card, vary, *, fidelity: str = "fast", refine: bool = False,
        bootstrap: int = 0, seed: int = 0, jobs: int = 1, out=None,
        units_system: str | None = None, plots: bool = True, progress=None) -> FitResult:
    """Calibrate scene keys to a measured indicator card (``corliss fit``).

    Parameters
    ----------
    scene : str, Path or Scene
        A scene file, a bundled scene's name, or a loaded steady scene.
    card : str, Path or MeasuredCard
        A card CSV whose header names each column's quantity and unit (the card CSV
        ``corliss run`` writes, or a digitised card: see :mod:`corliss.fitting.card`);
        gauge pressures are read against the scene's barometer.
    vary : str or list
        ``KEY=LOW:HIGH`` ranges (or :class:`~corliss.keys.edits.KeyRange`), e.g.
        ``["engine.clearance=0.04:0.14", "valve_gear.lap=0.7:1.3in"]``.
    fidelity : str, optional
        Tier of the search (``fast``; ``standard``, ``reference``).
    refine : bool, optional
        Repeat the search on the ``standard`` tier from the optimum.
    bootstrap : int, optional
        Wild-bootstrap refits of the residuals (0: none).
    seed : int, optional
        The bootstrap's seed.
    jobs : int, optional
        Processes for the uncertainty's runs and the bootstrap's refits [-]
        (default 1).
    out : str or Path, optional
        Write ``STEM.json``, ``STEM.toml`` and ``STEM.card.png`` into this folder
        (:func:`fit_stem`); one holding another fit is refused first
        (:func:`check_out`).
    units_system : str, optional
        ``"US"`` or ``"SI"`` for the files and figure (default: the scene's).
    plots : bool, optional
        Draw ``STEM.card.png``.
    progress : callable, optional
        Called after each simulation with (simulations, residual r.m.s. [Pa]).

    Returns
    -------
    FitResult
        The fit (:func:`corliss.fitting.solver.fit_card`), written into ``out``
        first when it is given.

    Raises
    ------
    InputError
        Before any simulation: a bad scene, range, key or card.
    """
    if units_system not in (None, "US", "SI"):
        raise InputError("--units", units_system, "US or SI")
    if not isinstance(scene, Scene):
        scene = load_scene(find_scene(scene))
    ranges = _ranges(vary)
    if not isinstance(card, MeasuredCard):
        card = read_card(card, barometer_Pa=scene.supply.barometer_Pa)
    if out is not None:
        check_out(out, scene, card, ranges, units_system)
    result = fit_card(scene, card, ranges, fidelity=fidelity, refine=refine,
                      bootstrap=bootstrap, seed=seed, jobs=jobs, progress=progress)
    if out is not None:
        result.write(out, plots=plots, units_system=units_system)
    return result


def _pressure_unit(system: str) -> tuple[str, float]:
    """The unit of a pressure difference in ``system`` and its size [Pa]."""
    return ("psi", units.PSI_Pa) if system == "US" else ("kPa", 1e3)


def fit_json(fit_result: FitResult, units_system: str | None = None) -> dict:
    """The fit's summary with what reruns it (the content of ``STEM.json``).

    Parameters
    ----------
    fit_result : FitResult
        The fit.
    units_system : str, optional
        ``"US"`` (psi) or ``"SI"`` (kPa) for the residual and noise; default the
        scene's.

    Returns
    -------
    dict
        :attr:`corliss.fitting.solver.FitResult.summary` with the residual r.m.s.
        and noise estimate in the pressure unit, the card's columns and SHA-256, the
        ranges as ``vary`` options, the versions, the creation time (UTC) and the
        scene's name, file, SHA-256 and text; JSON values only.
    """
    s = fit_result.scene
    system = units_system or s.output.units
    unit, size = _pressure_unit(system)
    card_sha = _sha256(fit_result.card.source)
    out = dict(fit_result.summary)
    out.update({
        "units_system": system,
        "residual_rms": {"value": fit_result.residual_rms_Pa / size, "unit": unit},
        "noise_estimate": {"value": fit_result.s_Pa / size, "unit": unit},
        "card_columns": fit_result.card.columns,
        "card_sha256": card_sha,
        "vary": _vary_text(fit_result.ranges),
        "corliss_version": package_version(), "versions": dependency_versions(),
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "scene_name": s.name, "scene_file": s.source,
        "scene_sha256": hashlib.sha256(s.text.encode("utf-8")).hexdigest() if s.text else None,
        "scene_toml": s.text,
    })
    return jsonable(out)


def fitted_toml(fit_result: FitResult, units_system: str | None = None) -> str:
    """The fitted scene as TOML text, its header saying what was fitted and how well.

    Parameters
    ----------
    fit_result : FitResult
        The fit.
    units_system : str, optional
        ``"US"`` or ``"SI"``: every quantity of the scene written in it (default the
        scene's).

    Returns
    -------
    str
        The text of ``STEM.toml``: comment lines with each key's fitted value and
        standard error (or why it is not determined), then the source scene's text
        with the fitted keys set, its comments kept, in one unit system
        (:func:`corliss.keys.scene_system.scene_text`; a fitted value already in
        that system is written at the fit's six figures, a converted one rounded as a
        drawing is).
    """
    lines = [f"{fit_result.scene.title}: fitted by corliss fit to {fit_result.card.source}"]
    for r in fit_result.ranges:
        k = r.key
        se = fit_result.standard_errors[k]
        unit = f" {r.unit}" if r.unit else ""
        lines.append(f"  {k} = {fit_result.values[k]:.6g}{unit} " +
                     (f"+- {se:.2g}{unit}" if se is not None else
                      "(NOT determined by the card: " + fit_result.unidentifiable[k] + ")"))
    s = fit_result.scene
    values = {r.key: get_key(fit_result.fitted_data, r.key) for r in fit_result.ranges}
    return scene_text(s.text if s.text is not None else dumps(s.data or {}),
                      units_system or s.output.units, values, header="\n".join(lines))


def write(fit_result: FitResult, out_dir, plots: bool = True,
          units_system: str | None = None) -> dict[str, Path]:
    """Write the fit's files into a folder, all or none.

    Parameters
    ----------
    fit_result : FitResult
        The fit.
    out_dir : str or Path
        The output folder (made if missing).
    plots : bool, optional
        Whether to draw ``STEM.card.png``.
    units_system : str, optional
        ``"US"`` or ``"SI"`` for the files and the figure; default the scene's.

    Returns
    -------
    dict of str to Path
        ``{kind: path}`` of :data:`FILES` written (STEM :func:`fit_stem`):
        ``summary``, ``scene`` and ``card`` (when drawn).
    """
    files = {}
    toml_text = fitted_toml(fit_result, units_system)
    stem = fit_stem(fit_result.scene, units_system)
    name = {kind: f"{stem}.{suffix}" for kind, suffix in FILES.items()}
    with OutputFiles(out_dir) as out, plain_text(plots):
        out.stage(name["summary"]).write_text(json.dumps(fit_json(fit_result, units_system),
                                                         indent=2))
        files["summary"] = out.files[name["summary"]]
        out.stage(name["scene"]).write_text(toml_text, encoding="utf-8")
        files["scene"] = out.files[name["scene"]]
        if plots:
            from matplotlib.figure import Figure  # only when drawing
            fig = Figure(figsize=(9, 5.8))        # no pyplot: the user's backend untouched
            plot_fit_card(fit_result, ax=fig.add_subplot(), units_system=units_system)
            fig.savefig(out.stage(name["card"]), dpi=DPI, bbox_inches="tight",
                        format="png", pil_kwargs=PNG_OPTIONS)
            files["card"] = out.files[name["card"]]
    return files


def print_fit(fit_result: FitResult, files: dict | None = None,
              units_system: str | None = None) -> None:
    """Print the short account of a fit to standard output (``corliss fit``).

    Each key's start, fitted value, standard error and range (and bootstrap interval),
    the keys not determined, the correlations, the residual r.m.s. and noise
    estimate, each end's measured and fitted m.e.p., the simulations run, and the
    files written.

    Parameters
    ----------
    fit_result : FitResult
        The fit.
    files : dict of str to Path, optional
        ``{kind: path}`` of the files written, listed last.
    units_system : str, optional
        ``"US"`` (psi) or ``"SI"`` (kPa) for the pressures; default the scene's.
    """
    f = fit_result
    system = units_system or f.scene.output.units
    unit, size = _pressure_unit(system)
    print(f"{f.scene.title}: fitted to {f.card.source} ({', '.join(f.card.ends)} end; "
          f"{f.n_points} points)")
    w = max(len(r.label) for r in f.ranges)
    print(f"  {'key':{w}s} {'start':>10s} {'fitted':>10s} {'std error':>10s}  range")
    for r in f.ranges:
        k = r.key
        se = f.standard_errors[k]
        u = f" {r.unit}" if r.unit else ""
        line = (f"  {r.label:{w}s} {f.start[k]:10.5g} {f.values[k]:10.5g} "
                + (f"{se:10.2g}" if se is not None else f"{'-':>10s}")
                + f"  {r.low:g} to {r.high:g}{u}")
        if f.bootstrap is not None and k in f.bootstrap["standard_errors"]:
            b = f.bootstrap
            line += (f"; bootstrap {b['standard_errors'][k]:.2g}, 95 % "
                     f"{b['low'][k]:.6g} to {b['high'][k]:.6g}")
        if f.at_bound.get(k):
            line += f"  (at the {f.at_bound[k]} end of its range)"
        print(line)
    for k, why in f.unidentifiable.items():
        print(f"  NOT DETERMINED   {k}: {why}")
    keys = f.keys
    for i in range(len(keys)):
        for j in range(i + 1, len(keys)):
            c = f.correlation[i, j]
            if c == c:
                print(f"  correlation      {keys[i]} / {keys[j]}: {c:+.3f}")
    print(f"  residual r.m.s.  {f.residual_rms_Pa / size:.3g} {unit} (noise estimate "
          f"{f.s_Pa / size:.3g} {unit}); {f.n_residuals} residuals")
    for end, w in f.end_work.items():
        print(f"  m.e.p. {end:9s} measured {w['measured_mep_Pa'] / size:.4g} {unit}, fitted "
              f"{w['fitted_mep_Pa'] / size:.4g} {unit}")
    tier = f.fidelity + (f" at rtol {solver.SEARCH_RTOL[f.fidelity]:g}"
                         if f.fidelity in solver.SEARCH_RTOL else "")
    print(f"  {f.simulations} simulations ({tier}, {f.cycles} cycles each) in "
          f"{f.wall_time_s:.1f} s; {f.status}")
    for kind, path in (files or {}).items():
        print(f"  wrote {kind:12s} {path}")


def plot(fit_result: FitResult, ax=None, units_system: str | None = None) -> dict:
    """Draw a fit's card: the measured card against the fitted one (what
    :meth:`FitResult.plot <corliss.fitting.solver.FitResult.plot>` calls).

    Parameters
    ----------
    fit_result : FitResult
        The fit.
    ax : matplotlib Axes, optional
        The axes to draw on (default: a new figure).
    units_system : str, optional
        ``"US"`` or ``"SI"`` (default: the scene's output units).

    Returns
    -------
    dict
        The matplotlib objects drawn, in the one shape of every ``plot()``
        (:func:`corliss.plot.shape.one_shape`: ``figure``, ``axes``, ``ax``,
        ``lines``; and ``measured`` and ``fitted``).
    """
    return one_shape(plot_fit_card(fit_result, ax=ax, units_system=units_system))


__all__ = ["FILES", "check_out", "fit", "fit_json", "fit_stem", "fitted_toml", "plot",
           "print_fit", "write"]
