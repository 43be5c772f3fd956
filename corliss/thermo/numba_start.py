"""numba's start, without the import of ``scipy.linalg`` it makes for its BLAS check.

The first compiled function a process calls, even one loaded from numba's disk cache,
makes numba load its implementation registries once; one of them checks that BLAS is
there by ``import scipy.linalg.cython_blas``.  That statement imports the package
``scipy.linalg`` first, whose ``__init__`` imports most of scipy's linear algebra and its
array-API layer: about 0.12 s of a warm ``corliss run`` on a quiet machine (0.15 to
0.25 s on a loaded one), for a module none of the kernels calls.

:func:`preload_cython_blas` loads the extension module ``scipy.linalg.cython_blas``
itself, by its file, and puts it in ``sys.modules`` under its name, so numba's check
(and numba's use of the BLAS routines, which it looks up in that module's C API by the
module's name) finds it there and the package ``scipy.linalg`` is imported only by code
that uses it.  A later ``import scipy.linalg`` works as usual and finds the same module
(``from scipy.linalg import cython_blas`` too).  Nothing is done when ``scipy.linalg``
is already imported, or when the extension's file cannot be found: numba then imports
it as it always did.  The package :mod:`corliss.thermo` calls it
first, on import, before any compiled function can be called.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import sys

#: The extension module numba's BLAS check imports.
CYTHON_BLAS = "scipy.linalg.cython_blas"


def preload_cython_blas() -> bool:
    """Load ``scipy.linalg.cython_blas`` by its file, without the package's ``__init__``.

    Returns
    -------
    bool
        True when the module is in ``sys.modules`` afterwards without this call having
        imported ``scipy.linalg``; False when it left the import to numba (scipy missing,
        the file not found, or ``scipy.linalg`` imported already).
    """
    if CYTHON_BLAS in sys.modules:
        return "scipy.linalg" not in sys.modules
    if "scipy.linalg" in sys.modules:
        return False
    try:
        scipy_spec = importlib.util.find_spec("scipy")     # the top package only
        if scipy_spec is None or not scipy_spec.submodule_search_locations:
            return False
        where = [f"{p}/linalg" for p in scipy_spec.submodule_search_locations]
        spec = importlib.machinery.PathFinder.find_spec(CYTHON_BLAS, where)
        if spec is None or not isinstance(spec.loader, importlib.machinery.ExtensionFileLoader):
            return False
        module = importlib.util.module_from_spec(spec)
        sys.modules[CYTHON_BLAS] = module
        try:
            spec.loader.exec_module(module)
        except BaseException:
            del sys.modules[CYTHON_BLAS]
            raise
    except (ImportError, OSError, ValueError):
        return False
    return True
