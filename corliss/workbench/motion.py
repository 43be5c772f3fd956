"""The gear in motion on the workbench's page: the frames ``corliss animate`` draws.

:func:`motion_view` loads the page's scene and draws its gear over one turn by
:func:`corliss.plot.scene_animation.animate_scene`, the function ``corliss animate``
calls (the exact linkage, the valve over its ports, the port openings, the card
traced), and returns the frames as one looping GIF (the command's own writer), which
the page shows as an image: it needs no script and nothing from the network.  It runs
in a worker process of its own, so a slider moved meanwhile is redrawn as usual.
"""

from __future__ import annotations

import base64
import io
import time

import matplotlib.pyplot as plt

from corliss.errors import InputError, RunError
from corliss.plot.animation import write_animation
from corliss.plot.scene_animation import animate_scene
from corliss.scene.loader import scene_from_dict

#: Frames in one turn: ``corliss animate``'s default.
FRAMES = 72


def gif_bytes(drawn: dict) -> bytes:
    """An animation's frames as the GIF ``corliss animate`` writes.

    Parameters
    ----------
    drawn : dict
        What :func:`~corliss.plot.scene_animation.animate_scene` returned.

    Returns
    -------
    bytes
        The GIF file's bytes.
    """
    buf = io.BytesIO()
    write_animation(drawn, buf, "gif")
    return buf.getvalue()


def motion_view(data: dict, name: str = "scene", source: str | None = None,
                frames: int = FRAMES) -> dict:
    """The page's scene's gear in motion.

    Parameters
    ----------
    data : dict
        The scene's tables with the page's settings.
    name : str, optional
        The scene's name.
    source : str, optional
        The file it came from.
    frames : int, optional
        Frames in one turn [-].

    Returns
    -------
    dict
        ``{"ok": True, "gif": base64 text of the GIF, "frames", "title",
        "compute_s"}``, or ``{"ok": False, "message", "key"}`` where the scene is
        refused or its gear has no single valve to draw.
    """
    t0 = time.perf_counter()
    try:
        scene = scene_from_dict(data, name=name, source=source)
        drawn = animate_scene(scene, frames=frames)
    except InputError as exc:
        return {"ok": False, "message": str(exc), "key": exc.key}
    except RunError as exc:
        return {"ok": False, "message": f"the run stopped: {exc}", "key": None}
    try:
        gif = gif_bytes(drawn)
    finally:
        plt.close(drawn["figure"])
    return {"ok": True, "gif": base64.b64encode(gif).decode("ascii"), "frames": frames,
            "title": drawn["title"], "compute_s": time.perf_counter() - t0}
