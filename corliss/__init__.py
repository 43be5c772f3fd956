"""corliss: a steam-engine cycle and governing simulator.

The package's front door holds what a user calls: :func:`load_scene` (and
:func:`scene_from_dict`, :func:`bundled_scenes`, :func:`default_scene_path`) to read a
scene, :func:`simulate` to run it (a :class:`SteadyResult`, :class:`TransientResult`
or :class:`SweepResult`), :func:`scene_events` for its valve events without a run,
:func:`design` for a valve designed for the events asked, :func:`fit` for scene keys
calibrated to a measured card, and :func:`study` for runs over a design of keys.  Bad
input raises :class:`InputError`, naming the key, the value and what is valid.

Its rooms, bottom up (a module imports its own layer and those below, never above):

- :mod:`corliss.errors`, :mod:`corliss.keys` (units, the declared keys, typed TOML
  getters, text in and out) and :mod:`corliss.frames` (a run's tables and their column
  names);
- the physics, independent of each other: :mod:`corliss.thermo` (steam properties and
  flow through ports), :mod:`corliss.valves` (valve gears) and
  :mod:`corliss.governors`;
- :mod:`corliss.engine`: the engine's model, its integration and its results;
- :mod:`corliss.scene`, :mod:`corliss.studies`, :mod:`corliss.fitting`: scenes, studies
  (load ranges and throttling against cut-off among them) and fits;
- :mod:`corliss.plot`: the figures;
- :mod:`corliss.files`: the files a run, a study, a fit or a design writes;
- :mod:`corliss.cli`: the command (``corliss`` or ``python -m corliss``).

``import corliss`` loads none of them: each name below is loaded from its module the
first time it is asked for (PEP 562), so a script pays only for what it uses.

>>> import corliss
>>> scene = corliss.load_scene(corliss.default_scene_path())
>>> result = corliss.simulate(scene)          # doctest: +SKIP
>>> result.summary["indicated_power_hp"]      # doctest: +SKIP
"""

__version__ = "0.2.0"

import importlib  # noqa: E402

from corliss.errors import InputError  # noqa: E402

#: Each name of the front door and the module that defines it, loaded on first use.
_ON_USE = {
    "Scene": "corliss.scene.loader", "bundled_scenes": "corliss.scene.loader",
    "default_scene_path": "corliss.scene.loader", "load_scene": "corliss.scene.loader",
    "scene_from_dict": "corliss.scene.loader",
    "simulate": "corliss.engine.simulate", "scene_events": "corliss.engine.model",
    "Result": "corliss.engine.result", "SteadyResult": "corliss.engine.result",
    "SweepResult": "corliss.engine.result", "TransientResult": "corliss.engine.result",
    "study": "corliss.studies.runner", "StudyResult": "corliss.studies.study_result",
    "fit": "corliss.files.fit_output", "FitResult": "corliss.fitting.solver",
    "design": "corliss.files.design_output", "Design": "corliss.files.design_output",
}
#: The package's modules by the names they had at the top level before the rooms
#: (``corliss.units`` is :mod:`corliss.keys.units`), for scripts written against 0.2.
_MOVED = {
    "units": "corliss.keys.units", "columns": "corliss.frames.columns",
    "results": "corliss.files.run_output", "study_output": "corliss.files.study_output",
    "fit_output": "corliss.files.fit_output", "design_scene": "corliss.files.design_output",
    "scene_reference": "corliss.scene.reference", "scene_keys": "corliss.keys.edits",
}

__all__ = ["Design", "FitResult", "InputError", "Result", "Scene", "SteadyResult", "StudyResult",
           "SweepResult", "TransientResult", "__version__", "bundled_scenes", "default_scene_path",
           "design", "fit", "load_scene", "scene_events", "scene_from_dict", "simulate", "study"]


def __getattr__(name: str):
    """Load a name of the front door from its module the first time it is asked for.

    Parameters
    ----------
    name : str
        The attribute asked for: a name of :data:`_ON_USE`, or a module's name of
        :data:`_MOVED`.

    Returns
    -------
    object
        The module's attribute of that name, or the module.
    """
    if name in _ON_USE:
        value = getattr(importlib.import_module(_ON_USE[name]), name)
    elif name in _MOVED:
        value = importlib.import_module(_MOVED[name])
    else:
        raise AttributeError(f"module 'corliss' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The module's names, those loaded on use included.

    Returns
    -------
    list of str
        Sorted names.
    """
    return sorted(set(globals()) | set(_ON_USE))
