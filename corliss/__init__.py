"""corliss: a steam-engine cycle and governing simulator.

>>> import corliss
>>> scene = corliss.load_scene(corliss.default_scene_path())
>>> result = corliss.simulate(scene)          # doctest: +SKIP
>>> result.summary["indicated_power_hp"]      # doctest: +SKIP
"""

from corliss.engine.simulate import scene_events, simulate
from corliss.errors import InputError
from corliss.results import Result
from corliss.scene import Scene, default_scene_path, load_scene, scene_from_dict

__all__ = ["InputError", "Result", "Scene", "default_scene_path", "load_scene", "scene_events",
           "scene_from_dict", "simulate"]
