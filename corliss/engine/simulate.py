"""``simulate``: run a scene by its mode and model level.

A dispatch only: the runners live in their own modules (:mod:`corliss.engine.steady`,
:mod:`corliss.engine.transient`, :mod:`corliss.engine.mean_value`), each building its
model in :mod:`corliss.engine.model` and returning a result of
:mod:`corliss.engine.result`.
"""

from __future__ import annotations

from typing import Any

from corliss.engine import first_run
from corliss.engine.model import scene_events
from corliss.engine.output_size import check_output_samples
from corliss.engine.result import Result
from corliss.engine.scene_specs import SceneSpec
from corliss.engine.steady import run_steady
from corliss.progress import progress_for

__all__ = ["scene_events", "simulate"]


def simulate(scene: SceneSpec, *, portmap_scale: float = 1.0,
             progress: Any = None) -> Result:
    """Run a scene.

    Parameters
    ----------
    scene : Scene
        A scene from :func:`corliss.load_scene`.
    portmap_scale : float
        Steady runs: multiply every port area by this factor [-].
    progress : None, True, ProgressBar or callable, optional
        True draws a bar (:mod:`corliss.progress`: a terminal or a notebook); a
        callable is called, for steady runs after each cycle with (cycle number,
        relative change of work [-]), for transient runs with (simulated time [s],
        duration [s]).

    Returns
    -------
    Result
        A :class:`~corliss.engine.result.SteadyResult` for a steady scene, a
        :class:`~corliss.engine.result.TransientResult` for a transient one.

    Raises
    ------
    InputError
        Before any work, if the run's time series would hold more rows than
        :data:`corliss.keys.limits.MAX_OUTPUT_SAMPLES` (a scene's run changed after it
        was loaded, by ``replace_run``, is checked here).
    """
    check_output_samples(scene.run)
    first_run.prepare(scene)
    transient = scene.run.mode == "transient"
    with progress_for(progress, "time" if transient else "cycles",
                      tolerance=None if transient else
                      scene.run.fidelity.convergence_tolerance) as bar:
        return _dispatch(scene, portmap_scale, bar)


def _dispatch(scene, portmap_scale, progress):
    if scene.run.mode == "transient":
        # the transient runners (and the governors they import) are loaded by the runs
        # that use them: a steady run's start is spared their import (no circle here)
        if scene.run.model == "mean_value":
            from corliss.engine.mean_value import run_mean_value
            return run_mean_value(scene, progress=progress)
        from corliss.engine.transient import run_transient
        return run_transient(scene, progress=progress)
    return run_steady(scene, portmap_scale=portmap_scale, progress=progress)
