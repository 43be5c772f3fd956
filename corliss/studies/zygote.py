"""What the pool's forkserver loads before its first fork (:mod:`corliss.studies.pool`).

Imported by the forkserver as it starts: the modules of a steady run (the compiled
kernels' dispatchers, the steam table's reader) and, when the starting caller named
a file in :data:`corliss.studies.pool.WARM_ENV`, the modules of its tasks' functions
imported and each steady scene in it run once,
so the kernels of its version are loaded from numba's cache and the steam table read
before any worker is forked from this process: each worker starts with them, as a
fork of a warm process, without this module's caller's memory.  A run that stops
here is no matter (the worker runs it again and reports it).  Nothing else is
imported: no pandas (unless a task's module needs it), no plotting.
"""

from __future__ import annotations

import importlib
import logging
import os
import pickle

from corliss.engine.steady import run_steady
from corliss.studies import runner  # noqa: F401  the study's task functions
from corliss.studies.pool import WARM_ENV

log = logging.getLogger(__name__)

__all__ = ["warm"]


def warm(path: str | None) -> int:
    """Import the modules named, and run once each steady scene, pickled in the file at
    ``path``.

    Parameters
    ----------
    path : str or None
        The file (None or missing: nothing is run).

    Returns
    -------
    int
        The scenes that ran to their end [-].
    """
    if not path:
        return 0
    try:
        with open(path, "rb") as f:
            modules, scenes = pickle.load(f)
    except (OSError, EOFError, ValueError, pickle.UnpicklingError):
        return 0
    for name in modules:
        if name.startswith("corliss."):
            try:
                importlib.import_module(name)
            except ImportError as exc:
                log.debug("warm-up import of %s failed: %s", name, exc)
    ran = 0
    for sc in scenes:
        try:
            run_steady(sc)
            ran += 1
        except Exception as exc:      # noqa: BLE001  a worker meets it again, and says so
            log.debug("warm-up run of %s stopped: %s", getattr(sc, "name", sc), exc)
    return ran


warm(os.environ.get(WARM_ENV))
