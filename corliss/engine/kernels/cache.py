"""Numba's on-disk cache of the kernels: whether a kernel is compiled for the types a run
will pass (:func:`uncached`), and the notice that a run is about to compile.
"""

from __future__ import annotations

import logging
import os

from corliss.engine.kernels.cycle import CYCLE_KERNELS
from corliss.engine.kernels.dopri5 import DOPRI_TURN_ARG, _dopri5_steps
from corliss.engine.kernels.rosenbrock import (ROS_FINITE_ARG, ROS_PAIR_ARG, ROS_TURN_ARG,
                                               _ros_steps)
from corliss.logs import NOTICE

log = logging.getLogger(__name__)


def uncached(dispatcher, nones: dict[int, bool] | None = None) -> bool | None:
    """Whether a compiled function's first call will compile it.

    Parameters
    ----------
    dispatcher : numba Dispatcher
        The compiled function (``@njit(cache=True)``).
    nones : dict of int to bool, optional
        For a function compiled in versions by whether arguments are None: each such
        argument's position, and whether the version wanted takes None there; only
        that version counts.

    Returns
    -------
    bool or None
        True when it is neither compiled in this process nor in numba's disk cache;
        None when this numba does not show its cache (internals this reads are gone).
    """
    memo = (id(dispatcher), tuple(sorted((nones or {}).items())))
    if memo in _KNOWN_CACHED:
        return False
    state = _uncached(dispatcher, nones)
    if state is False:        # compiled or on disk: so it stays for this process
        _KNOWN_CACHED.add(memo)
    return state


#: The (dispatcher, version) pairs found compiled or cached: a study's runs ask each
#: time, and reading the dispatcher's signatures costs a tenth of a millisecond.
_KNOWN_CACHED: set = set()


def _uncached(dispatcher, nones: dict[int, bool] | None) -> bool | None:
    def counts(sig) -> bool:
        return all((str(sig[k]) == "none") == v for k, v in (nones or {}).items())
    try:
        if any(counts(sig) for sig in dispatcher.signatures):
            return False
        cache_file = dispatcher._cache._cache_file
        if not os.path.exists(cache_file._index_path):
            return True
        if not nones:
            return False
        return not any(counts(key[0]) for key in cache_file._load_index())
    except (AttributeError, IndexError, TypeError):
        return None


def cycle_kernel_uncached(code: int, exact: bool = True) -> bool | None:
    """:func:`uncached` of the compiled cycle integrator of a method code, in the
    version that method runs on the network (:data:`ROS_PAIR_ARG`,
    :data:`ROS_FINITE_ARG`) and for a steady cycle (:data:`DOPRI_TURN_ARG` and
    :data:`ROS_TURN_ARG` None: the step loops also serve the governed loop's turn).

    Parameters
    ----------
    code : int
        The method's code (:data:`CYCLE_KERNELS`).
    exact : bool
        Whether the network's Jacobian is analytic (:func:`exact_jacobian_covers`).

    Returns
    -------
    bool or None
        As :func:`uncached`.
    """
    dispatcher = CYCLE_KERNELS[code]
    if dispatcher is _dopri5_steps:
        # the version of a steady cycle (its step loop also serves the loop's turn)
        return uncached(dispatcher, {DOPRI_TURN_ARG: True})
    if dispatcher is _ros_steps:
        return uncached(dispatcher, {ROS_PAIR_ARG: code != 2, ROS_FINITE_ARG: exact,
                                     ROS_TURN_ARG: True})
    return uncached(dispatcher)


def turn_kernel_uncached(method: str) -> bool | None:
    """:func:`uncached` of the step loop a turn of the governed loop runs on, in the
    turn's version (:data:`DOPRI_TURN_ARG`, :data:`ROS_TURN_ARG` not None; a Rosenbrock
    turn takes a tableau and the finite-difference Jacobian).

    Parameters
    ----------
    method : str
        The transient loop's method: ``"dopri5"`` or a Rosenbrock tableau's name.

    Returns
    -------
    bool or None
        As :func:`uncached`.
    """
    if method == "dopri5":
        return uncached(_dopri5_steps, {DOPRI_TURN_ARG: False})
    return uncached(_ros_steps, {ROS_PAIR_ARG: True, ROS_FINITE_ARG: False,
                                 ROS_TURN_ARG: False})


#: How long a first run takes, as the notice says it: measured from a fresh numba
#: cache and steam table, the whole run of the default scene (start to exit): 22 s on
#: an idle 16-core machine, 29 to 50 s on two cores at a load of 1.5 to 2.8, 43 s
#: from an installed wheel at 1.3; 54 to 208 s (median 140 s, four runs) on two cores
#: shared at a load of 6 to 15.
FIRST_RUN_TEXT = "half a minute to a minute on two free cores, a few minutes on a busy machine"


def announce_compile(*dispatchers, cycle: int | None = None, exact: bool = True,
                     turn: str | None = None) -> None:
    """Say so before compiled functions not yet in numba's disk cache are first called.

    The first run on a machine spends some seconds compiling them; a NOTICE names the
    functions to be compiled (nothing when all are cached, or this numba does not show
    its cache).

    Parameters
    ----------
    *dispatchers : numba Dispatcher
        The compiled functions about to be called.
    cycle : int, optional
        A method's code (:data:`CYCLE_KERNELS`) whose cycle integrator is about to be
        called, in that method's version (:func:`cycle_kernel_uncached`).
    exact : bool
        With ``cycle``: whether the network's Jacobian is analytic.
    turn : str, optional
        A transient loop's method whose turn is about to be integrated
        (:func:`turn_kernel_uncached`).
    """
    state = [uncached(d) for d in dispatchers]
    if cycle is not None:
        dispatchers = dispatchers + (CYCLE_KERNELS[cycle],)
        state.append(cycle_kernel_uncached(cycle, exact))
    if turn is not None:
        dispatchers = dispatchers + (_dopri5_steps if turn == "dopri5" else _ros_steps,)
        state.append(turn_kernel_uncached(turn))
    if None in state:          # a numba without these internals: say nothing
        return
    missing = [d.__name__ for d, m in zip(dispatchers, state) if m]
    if missing:
        log.log(NOTICE, "compiling the kernels once for this machine (%s; %s); "
                "later runs load them from the cache", ", ".join(missing), FIRST_RUN_TEXT)
