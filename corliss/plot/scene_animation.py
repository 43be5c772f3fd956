"""A scene's gear in motion, as ``corliss animate`` draws it and the workbench shows it.

:func:`animate_scene` takes a loaded scene to the drawn animation: the gear solved as
its exact linkage (:func:`~corliss.plot.animation.exact_linkage_spec`), and, with the
card, a steady run of the scene at its speed (a mean-value scene run crank-resolved, so
that it has a card) traced as the crank turns.  The command line and the workbench
call this one function, so the page's frames are the command's.
"""

from __future__ import annotations

import dataclasses

from corliss.engine.model import build_gear, steady_scene
from corliss.engine.simulate import simulate
from corliss.errors import InputError
from corliss.plot.animation import animate_gear, exact_linkage_spec, linkage_kind


def animate_scene(scene, *, frames: int = 72, card: bool = True) -> dict:
    """The animation of a scene's gear over one turn of the crank.

    Parameters
    ----------
    scene : Scene
        The loaded scene (its fidelity is that of the steady run traced).
    frames : int, optional
        Frames in one turn [-], from 2 to 720.
    card : bool, optional
        Run the scene steady and trace its card (False: the gear alone).

    Returns
    -------
    dict
        What :func:`~corliss.plot.animation.animate_gear` returns, with ``title`` (the
        scene's title, its gear, and whether its motion was solved as the exact
        linkage for the drawing) and ``exact_changed`` (True where it was).

    Raises
    ------
    InputError
        ``--frames`` out of range, or a gear with no single valve to animate (the
        double valves).
    """
    if not 2 <= frames <= 720:
        raise InputError("--frames", frames, "a whole number of frames from 2 to 720")
    spec, changed = exact_linkage_spec(scene.gear)
    scene = dataclasses.replace(scene, gear=spec)
    gear = build_gear(scene)
    try:
        linkage_kind(gear)
    except ValueError as exc:
        raise InputError("valve_gear.type", scene.gear_type,
                         f"a gear with one valve to animate ({exc})") from None
    result = None
    if card:
        run = steady_scene(scene)
        if run.run.model == "mean_value":
            run = run.replace_run(model="crank_resolved")
        result = simulate(run)
    title = f"{scene.title}: {scene.gear_type}" + (" (the exact linkage)" if changed else "")
    drawn = animate_gear(gear, result, frames=frames, units_system=scene.output.units,
                         stroke_m=scene.engine.stroke_m, title=title)
    drawn["title"], drawn["exact_changed"] = title, changed
    return drawn
