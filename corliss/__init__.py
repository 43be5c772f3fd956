"""corliss: a steam-engine cycle and governing simulator.

>>> import corliss
>>> scene = corliss.load_scene(corliss.default_scene_path())
>>> result = corliss.simulate(scene)          # doctest: +SKIP
>>> result.summary["indicated_power_hp"]      # doctest: +SKIP
"""

__version__ = "0.2.0"

from corliss import results as _export  # noqa: E402,F401  (registers the export layer)
from corliss.engine.model import scene_events  # noqa: E402
from corliss.engine.result import Result, SteadyResult, SweepResult, TransientResult  # noqa: E402
from corliss.engine.simulate import simulate  # noqa: E402
from corliss.errors import InputError  # noqa: E402
from corliss.fit_output import fit  # noqa: E402
from corliss.fitting.solver import FitResult  # noqa: E402
from corliss.scene import Scene, bundled_scenes, default_scene_path, load_scene, scene_from_dict  # noqa: E402

__all__ = ["FitResult", "InputError", "Result", "Scene", "SteadyResult", "SweepResult", "TransientResult",
           "__version__", "bundled_scenes", "default_scene_path", "fit", "load_scene", "scene_events",
           "scene_from_dict", "simulate"]
