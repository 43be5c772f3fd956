"""corliss: a steam-engine cycle and governing simulator.

The package's front door holds what a user calls: :func:`load_scene` (and
:func:`scene_from_dict`, :func:`bundled_scenes`, :func:`default_scene_path`) to read a
scene, :func:`simulate` to run it (a :class:`SteadyResult`, :class:`TransientResult`
or :class:`SweepResult`), :func:`scene_events` for its valve events without a run,
:func:`design` for a valve designed for the events asked, :func:`fit` for scene keys
calibrated to a measured card, and :func:`study` for runs over a design of keys.  Bad
input raises :class:`InputError`, naming the key, the value and what is valid.

Its layers, bottom up (a module imports its own layer and those below, never above):

- the vocabulary: :mod:`corliss.errors`, :mod:`corliss.keys.units`, :mod:`corliss.frames.columns`,
  :mod:`corliss.keys.edits` and the small readers and writers beside them;
- the physics, independent of each other: :mod:`corliss.thermo` (steam properties and
  flow through ports), :mod:`corliss.valves` (valve gears) and
  :mod:`corliss.governors`;
- :mod:`corliss.engine`: the engine's model, its integration and its results;
- :mod:`corliss.scene.loader`, :mod:`corliss.studies`, :mod:`corliss.fitting`: scenes, studies
  and fits;
- :mod:`corliss.plot`: the figures;
- the files: :mod:`corliss.files.run_output`, :mod:`corliss.files.study_output`,
  :mod:`corliss.files.design_output`, :mod:`corliss.files.fit_output`;
- the command: :mod:`corliss.cli.commands`.

>>> import corliss
>>> scene = corliss.load_scene(corliss.default_scene_path())
>>> result = corliss.simulate(scene)          # doctest: +SKIP
>>> result.summary["indicated_power_hp"]      # doctest: +SKIP
"""

__version__ = "0.2.0"

from corliss.files import run_output as _export  # noqa: E402,F401  (registers the export layer)
from corliss.files import study_output as _study_export  # noqa: E402,F401  (and the study's)
from corliss.engine.model import scene_events  # noqa: E402
from corliss.engine.result import Result, SteadyResult, SweepResult, TransientResult  # noqa: E402
from corliss.engine.simulate import simulate  # noqa: E402
from corliss.errors import InputError  # noqa: E402
from corliss.files.fit_output import fit  # noqa: E402
from corliss.fitting.solver import FitResult  # noqa: E402
from corliss.scene.loader import Scene, bundled_scenes, default_scene_path, load_scene, scene_from_dict  # noqa: E402
from corliss.studies import StudyResult, study  # noqa: E402

__all__ = ["Design", "FitResult", "InputError", "Result", "Scene", "SteadyResult", "StudyResult",
           "SweepResult", "TransientResult", "__version__", "bundled_scenes", "default_scene_path",
           "design", "fit", "load_scene", "scene_events", "scene_from_dict", "simulate", "study"]

#: Names of the front door loaded when first asked for (PEP 562): the valve design's
#: module is not imported by a run, so ``corliss run`` does not pay for it.
_ON_USE = {"Design": "corliss.files.design_output", "design": "corliss.files.design_output"}


def __getattr__(name: str):
    """Load a name of :data:`_ON_USE` from its module the first time it is asked for.

    Parameters
    ----------
    name : str
        The attribute asked for.

    Returns
    -------
    object
        The module's attribute of that name.
    """
    if name in _ON_USE:
        import importlib
        value = getattr(importlib.import_module(_ON_USE[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'corliss' has no attribute {name!r}")


def __dir__() -> list[str]:
    """The module's names, those loaded on use included.

    Returns
    -------
    list of str
        Sorted names.
    """
    return sorted(set(globals()) | set(_ON_USE))
