"""The scene: a TOML file of an engine, its gear, governor, load and run, read into specs.

- :mod:`corliss.scene.loader`: a scene's text into frozen, validated specs in SI
  (:func:`~corliss.scene.loader.load_scene`, :class:`~corliss.scene.loader.Scene`);
- :mod:`corliss.scene.sections`: the declared keys of the scene's sections;
- :mod:`corliss.scene.reference`: the scene reference, printed from those declarations.

The loader's public names are offered here too (``corliss.scene.load_scene``).
"""

from corliss.scene.loader import (Scene, bundled_scenes, default_scene_path, find_scene,
                                  load_scene, scene_from_dict)

__all__ = ["Scene", "bundled_scenes", "default_scene_path", "find_scene", "load_scene",
           "scene_from_dict"]
