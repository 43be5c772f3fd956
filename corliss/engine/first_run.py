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

Nothing here changes a result: the miniature cycle is thrown away, and the run itself
is the run of a warm machine.  When either cache is already there, or the scene needs
no table (the ``heos`` tier) or no compiled kernel, nothing is done.
"""

from __future__ import annotations

import dataclasses
import logging
import pickle
import subprocess
import sys

import numpy as np

from corliss.engine.kernels import cache, jacobians, properties, rosenbrock
from corliss.engine.crank_resolved import COMPILED_CODES
from corliss.engine.model import steady_scene
from corliss.engine.steady import assemble, run_steady
from corliss.logs import NOTICE
from corliss.thermo import steam_table

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
    return not (scene.run.has("wall_heat") and scene.engine.wall_heat_model != "marks")


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
    if not _wanted(scene):
        return
    if steam_table.table_path().is_file() or not _kernels_missing(scene):
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
            builder.stdin.write(_network_pickle(scene))
            builder.stdin.close()
        except OSError as exc:     # the second process gone: it builds no table either
            log.debug("the second process took no network: %s", exc)
    try:
        _compile_on(steam_table.mini_table(), scene)
    finally:
        if builder.wait() != 0:
            log.debug("the steam table's process ended with %s; this one builds it",
                      builder.returncode)


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
