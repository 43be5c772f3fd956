"""A fresh machine's first run: the steam table built beside the kernels' compilation.

The first run on a machine pays twice, and each on one core: the steam table is built
from CoolProp (some 7 s) and the compiled kernels are compiled by numba (some 11 s),
one after the other.  Neither needs the other's result: the kernels need only the
table's array types, not its values.  So when both are missing, the table is built
in a second process, which caches it on disk, while this one compiles the kernels by
running one cycle of the scene on a miniature table of the same arrays
(:data:`corliss.thermo.steam_table.MINI_PARAMS`, built in a fraction of a second);
then this process waits for the table and the run goes on from both caches.  On two
cores the first run takes the longer of the two instead of their sum.

The kernels compile in versions, by method and by whether the network's Jacobian is
analytic: a first run compiles only its own.  So that no later command compiles (a
``--fidelity fast`` run, ``corliss compare``, a transient run), the first run whose
kernels were not cached also starts a third process, detached, that compiles the
others (:func:`compile_reachable`: the scene's steady cycle at each preset with and
without a wall heat that depends on the state, and a governed scene's transient turn
at each preset, all on the miniature table) while this run goes on; it ends by
itself when they are cached, and only one runs at a time (a lock beside numba's
cache).

Nothing here changes a result: the miniature cycle is thrown away, and the run itself
is the run of a warm machine.  When either cache is already there, or the scene needs
no table (the ``heos`` tier) or no compiled kernel, nothing is done.
"""

from __future__ import annotations

import dataclasses
import fcntl
import logging
import os
import pickle
import subprocess
import sys
from collections.abc import Callable
from typing import Any

import numpy as np

from corliss.engine.kernels import cache, dopri5, jacobians, loop, properties, rosenbrock
from corliss.engine.condensation import SCHEDULED_LAWS
from corliss.engine.crank_resolved import COMPILED_CODES
from corliss.engine.model import steady_scene
from corliss.engine.steady import assemble, run_steady
from corliss.logs import NOTICE
from corliss.thermo import steam_table
from corliss.valves import travel_kernel

log = logging.getLogger(__name__)

#: The command that builds and caches the steam table in the second process.
BUILD_COMMAND = "from corliss.thermo.steam_table import load_table; load_table()"
#: For a Rosenbrock method, the second process first compiles (and caches) the
#: analytic Jacobian for the network's types, read pickled from its standard input.
JACOBIAN_COMMAND = ("import sys; from corliss.engine.first_run import compile_jacobian; "
                    "compile_jacobian(sys.stdin.buffer.read()); " + BUILD_COMMAND)


def _exact(scene) -> bool:
    """Whether the scene's network has an analytic Jacobian: no wall heat that depends
    on the state (:func:`corliss.engine.kernels.jacobians.exact_jacobian_covers`, from the scene)."""
    return not (scene.run.has("wall_heat")
                and scene.engine.wall_heat_model not in SCHEDULED_LAWS)


def _steady_method(scene) -> str:
    """The integrator the scene's steady run will take: a state-dependent wall heat
    keeps a preset's finite-difference method (``Fidelity.steady_integrator``)."""
    return scene.run.fidelity.steady_integrator(_exact(scene))[0]


def _kernels_missing(scene) -> bool:
    """True when the scene's compiled cycle integrator is not in numba's disk cache, in
    the version its run takes (False when this numba does not show its cache: then
    nothing is done)."""
    method = _steady_method(scene)
    if method not in COMPILED_CODES:
        return False
    return bool(cache.cycle_kernel_uncached(COMPILED_CODES[method], _exact(scene)))


#: The command of the detached process that compiles the kernels' other versions, the
#: scene read pickled from its standard input (:func:`compile_reachable`).
REACHABLE_COMMAND = ("import sys; from corliss.engine.first_run import compile_reachable; "
                     "compile_reachable(sys.stdin.buffer.read())")
#: The bundled governed scene whose transient turn compiles the transient loop's kernels.
TRANSIENT_SCENE = "corliss-governor"
#: Makes that scene (a callable of no argument returning a Scene), set by the command
#: line (:mod:`corliss.cli.commands`), which loads bundled scenes; None (a run from
#: Python): the transient loop is left to compile on its first use.
transient_probe: Callable[[], Any] | None = None
#: The presets a user reaches from the command line with the table tier.
PRESETS_REACHED = ("standard", "fast")
#: The lock file, beside numba's cache of the cycle kernels, held by the process that
#: compiles the other versions (a second such process, of a second run, leaves at once).
LOCK_NAME = "corliss-first-use.lock"
#: The niceness the background process adds to its own: on a machine with a core free
#: it takes that core, on a busy one it yields to the run that started it.
BACKGROUND_NICE = 10
#: The processes this one started to compile the other versions (kept so that they
#: are not reaped as garbage while they run; they end by themselves).
_background: list = []


def _steady_variants(scene) -> list:
    """The scene, steady, at each preset with a wall heat that depends on the state
    (the finite-difference Jacobian's versions) and without wall heat (the analytic
    Jacobian's): the versions ``run``, ``run --fidelity`` and ``compare`` reach."""
    sc = steady_scene(scene)
    eff = tuple(e for e in sc.run.effects if e != "wall_heat")
    out = []
    for name in PRESETS_REACHED:
        at = sc.with_fidelity(name)
        out.append(at.replace_run(effects=eff))
        if at.engine.wall_heat_model not in SCHEDULED_LAWS:
            out.append(at.replace_run(effects=eff + ("wall_heat",)))
    return out


def transient_uncached() -> list:
    """The transient loop's turn integrators, and the load schedule's lookup its start
    calls, not in numba's disk cache.

    Returns
    -------
    list of str
        Their names; empty when every one is cached, or when this numba does not show
        its cache.
    """
    return [name for name, missing in (
        (dopri5.integrate_turn.__name__, cache.turn_kernel_uncached("dopri5")),
        (rosenbrock.integrate_turn_ros.__name__, cache.turn_kernel_uncached("ros4")),
        (loop.load_factor.__name__, cache.uncached(loop.load_factor))) if missing]


def reachable_uncached(scene) -> list[str]:
    """What a command line can reach from ``scene`` that numba has not cached: the
    steady variants of :func:`_steady_variants` (named by preset and wall heat) and
    the transient turn integrators.

    Parameters
    ----------
    scene : Scene
        A scene of the crank-resolved model on the table tier.

    Returns
    -------
    list of str
        Empty when every version is cached (or this numba does not show its cache).
    """
    out = [f"{sc.run.fidelity.name}{' wall heat' if sc.run.has('wall_heat') else ''}"
           for sc in _others(scene)]
    return out + transient_uncached()


def _version(scene) -> tuple[str, bool]:
    """The cycle kernel's version a steady run of ``scene`` takes: method and whether
    its Jacobian is analytic."""
    return _steady_method(scene), _exact(scene)


def _others(scene) -> list:
    """The steady variants of ``scene`` whose version is not cached, but for its own
    version (its run compiles that one) and with one variant for each version."""
    seen = {_version(scene)}
    out = []
    for sc in _steady_variants(scene):
        if _version(sc) not in seen and _kernels_missing(sc):
            seen.add(_version(sc))
            out.append(sc)
    return out


def _lock_path() -> str | None:
    """The lock file's path, beside numba's cache of the cycle kernels (None where this
    numba does not show it)."""
    try:
        index = rosenbrock._ros_steps._cache._cache_file._index_path
    except AttributeError:
        return None
    return os.path.join(os.path.dirname(index), LOCK_NAME)


def compile_reachable(data: bytes) -> None:
    """Compile and cache the kernel versions a command line reaches that are not cached:
    the detached process of a first run.

    Each is compiled by running it once on the miniature table (its values are no
    result): one cycle of each steady variant (:func:`_steady_variants`), and a
    turn of :data:`TRANSIENT_SCENE` at each preset, from its own start.  Only one
    such process runs at a time: a second leaves at once.

    Parameters
    ----------
    data : bytes
        The pickle of the first run's scene and of the governed scene whose turn
        compiles the transient loop (None: none).
    """
    path = _lock_path()
    if path is None:
        return
    # beside the run that started it: the run's process goes first where cores are few
    os.nice(BACKGROUND_NICE)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "a+b") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:            # another process compiles them
            return
        scene, governed = pickle.loads(data)
        mini = steam_table.mini_table()
        for sc in _others(scene):
            _compile_on(mini, sc)
        _compile_valve_kernels()
        if governed is not None and transient_uncached():
            _compile_transient(mini, governed)


def _compile_valve_kernels() -> None:
    """Compile (and cache) the slide valve's travel kernels, which a first run of a
    scene with another gear does not reach: one call each on two angles (the values
    are no result)."""
    theta = np.zeros(2)
    args = (0.5, 0.05, 1.0, 1.0, 0.0, 1.0, True)
    travel_kernel.eccentric_travel(theta, *args)
    travel_kernel.eccentric_signed(theta, *args, np.zeros(4))


def _compile_transient(table, base) -> None:
    """A turn of ``base`` (a governed scene) at each preset on ``table``: numba compiles
    (and caches) the transient loop's kernels."""
    # the transient runner and the governors it imports are loaded only where a
    # transient runs, as simulate does (no circle here)
    from corliss.engine.transient import run_transient
    turn_s = 60.0 / base.run.speed_rpm
    for name in PRESETS_REACHED:
        # its own start (the governor's equilibrium: the load schedule's lookup compiles)
        sc = base.with_fidelity(name).replace_run(duration_s=2.0 * turn_s)
        with steam_table.stand_in(table):
            try:
                run_transient(sc)
            except Exception as exc:    # noqa: BLE001 - a coarse table may stop the run
                log.debug("the compiling transient on the miniature table stopped: %s", exc)


def _start_reachable(scene) -> None:
    """Start the detached process of :func:`compile_reachable` for ``scene``, when
    some version it reaches is not cached (a first run's; nothing otherwise)."""
    missing = reachable_uncached(scene)
    if not missing:
        return
    # INFO, not NOTICE: a NOTICE opens a step the command line's heartbeat reports as
    # running until the next record, and this one runs beside the run, not before it
    log.info("compiling the kernels' other versions in a background process (%s), "
             "so that later commands load them from the cache", ", ".join(missing))
    try:
        governed = (transient_probe() if transient_probe is not None and transient_uncached()
                    else None)
        data = pickle.dumps((scene, governed))
        proc = subprocess.Popen([sys.executable, "-c", REACHABLE_COMMAND],
                                stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL, start_new_session=True)
        stdin = proc.stdin
        assert stdin is not None        # opened as a pipe above
        stdin.write(data)
        stdin.close()
    except Exception as exc:       # noqa: BLE001 - a convenience: the run goes on without it
        log.debug("no background process for the other kernels: %s", exc)
        return
    _background.append(proc)


def _wanted(scene) -> bool:
    run = scene.run
    return (run.model == "crank_resolved" and run.has("port_flow")
            and run.fidelity.properties == "table")


def prepare(scene) -> None:
    """Build the steam table in a second process while the kernels compile here.

    Only when both are missing (see the module's text); otherwise do nothing.

    Parameters
    ----------
    scene : Scene
        The scene about to run; its first cycle, on a miniature table, compiles what
        its run will call.
    """
    if not _wanted(scene) or not _kernels_missing(scene):
        return
    if steam_table.table_path().is_file():
        # this run compiles its kernels as it goes; the others compile beside it
        _start_reachable(scene)
        return
    log.log(NOTICE, "first run on this machine: building the steam table in a second "
            "process while the kernels compile in this one")
    # a Rosenbrock method's analytic Jacobian (a third of its compile time) is compiled
    # in the second process first, while this one compiles the right-hand side, which
    # the step loop needs before the Jacobian: this one then loads it from the cache
    jacobian = (_steady_method(scene) in rosenbrock.ROSENBROCK_METHODS and _exact(scene)
                and bool(cache.uncached(jacobians._jacobian_exact)))
    try:
        # the second process, done with the table before this one is done compiling,
        # compiles and caches the table's lookup for its error check: this one then
        # loads it instead of compiling it (14.2 s against 15.1 s run as Python there)
        builder = subprocess.Popen([sys.executable, "-c",
                                    JACOBIAN_COMMAND if jacobian else BUILD_COMMAND],
                                   stdin=subprocess.PIPE if jacobian else subprocess.DEVNULL,
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    except OSError as exc:         # no second process: the run builds it itself
        log.debug("no second process for the steam table: %s", exc)
        return
    if jacobian:
        try:
            pipe = builder.stdin
            assert pipe is not None     # opened as a pipe when jacobian
            pipe.write(_network_pickle(scene))
            pipe.close()
        except OSError as exc:     # the second process gone: it builds no table either
            log.debug("the second process took no network: %s", exc)
    try:
        _compile_on(steam_table.mini_table(), scene)
    finally:
        if builder.wait() != 0:
            log.debug("the steam table's process ended with %s; this one builds it",
                      builder.returncode)
    # the table built and this run's kernels compiled: the others compile while it runs
    _start_reachable(scene)


def _network_pickle(scene) -> bytes:
    """The scene's network arrays on the miniature table, and its state's length,
    pickled for :func:`compile_jacobian` (the types are what it compiles for)."""
    with steam_table.stand_in(steam_table.mini_table()):
        model = assemble(steady_scene(scene), tabulated=True)
        network = model.network(model.portmap)
        return pickle.dumps((network.arrays(), network.n_state))


def compile_jacobian(data: bytes) -> None:
    """Compile and cache the analytic Jacobian for a network's types, in the second
    process of a first run.

    It is called once on the miniature table's arrays (its values are no result).

    Parameters
    ----------
    data : bytes
        The pickle of :func:`_network_pickle`: the network's arrays and the length of
        its state.
    """
    net, n = pickle.loads(data)
    nv = net.node_kind.shape[0]
    ncyl = net.port_npts.shape[0]
    y = np.ones(n)
    J = np.zeros((n, 2 * nv))
    jacobians._jacobian_exact(0.0, y, J, np.zeros(n), net, properties.TIER_TABLE,
                           steam_table.mini_table().arrays(), np.zeros(3),
                           np.empty((properties.PR_ROWS, nv)), np.empty((ncyl, 4)),
                           np.empty((12, nv)), np.empty((ncyl, 4)))


def _compile_on(table, scene) -> None:
    """One cycle of ``scene`` on ``table``: numba compiles (and caches) what it calls."""
    sc = steady_scene(scene)
    sc = dataclasses.replace(sc, run=dataclasses.replace(sc.run, cycles=1))
    with steam_table.stand_in(table):
        try:
            run_steady(sc)
        except Exception as exc:    # noqa: BLE001 - a coarse table may stop the cycle
            log.debug("the compiling cycle on the miniature table stopped: %s", exc)
