"""What one evaluation of the compiled right-hand side costs, and where it goes.

The scene's network (the default scene by default, table properties) is run for three
cycles with dopri5 at rtol 1e-6; the states of the last cycle at 361 shaft angles
(every degree) are the inputs.  Each measurement is a compiled loop over those 361
states, repeated ``--reps`` times, timed ``--repeats`` times; the median per call is
reported in nanoseconds (and the least, the steadier on a shared machine):

* ``rhs``: :func:`corliss.engine.kernels.balances.rhs` as the integrators call it (a compiled
  call, the network and table tuples passed to it);
* ``rhs body inlined``: its two parts inlined into the loop (what the call itself
  costs is the difference);
* ``node_states``: every node's properties (volume, steam-table lookup, port-flow
  exponent, saturation temperature where a wall needs it);
* ``node_volume``, ``lookup_flagged``, ``kappa_at``, ``t_sat``: each for every node,
  on the states ``node_states`` computed;
* ``port_areas``: the PortMap interpolation of every cylinder;
* ``balances``: the mass and energy balances on given node properties and port areas;
* ``edge flows``: only :func:`corliss.thermo.orifice.port_flow` over every edge, as
  ``balances`` calls it.

The part loops are compiled without reference counting (as :func:`rhs` is), so that
they time the work and not numba's bookkeeping.  With ``--cycles`` it also reports the
marginal cost of a cycle of the ``standard`` and ``fast`` presets through the public
API on the accuracy study's default scene (:func:`accuracy_vs_time.marginal_ms_per_cycle`:
6 cycles less 2, over 4, process CPU time, median of ``--repeats``), with that cycle's
evaluations.

Usage::

    python benchmarks/rhs_cost.py [--scene scenes/default.toml] [--repeats 5]
                                  [--reps 40] [--cycles] [--label NAME]

Prints one line of JSON per measurement.  ``benchmarks/results/rhs_cost.csv`` holds
two rounds of it, in alternation, for the version before the right-hand side was
compiled without reference counting and after, with the load step's CPU time of the
``standard`` and ``fast`` presets (the 60 s Porter-Allen step of ``load_step.py``,
simulation only, median of 5).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import time
from pathlib import Path

import numpy as np
from numba import njit

import corliss
from corliss.engine.kernels import balances, mechanism, properties
from corliss.engine.crank_resolved import CrankResolved
from corliss.engine.kernels.balances import balances
from corliss.engine.kernels.mechanism import node_volume, port_areas
from corliss.engine.kernels.properties import node_states
from corliss.engine.steady import assemble
from corliss.thermo.orifice import port_flow
from corliss.thermo.steam_table import kappa_at, lookup_flagged, t_sat

HERE = Path(__file__).resolve().parent
DEFAULT_SCENE = HERE.parent / "scenes" / "default.toml"


def cycle_states(scene_path):
    """A converged cycle's states at every degree, and what the kernel takes with them."""
    scene = corliss.load_scene(scene_path).with_fidelity("standard")
    model = assemble(scene, tabulated=True)
    net = model.network(model.portmap)
    cr = CrankResolved(net, model.steam, "dopri5", 1e-6)
    y = cr.initial_state()
    theta = np.linspace(0.0, 2.0 * math.pi, 361)
    for _ in range(3):
        y, samples = cr.cycle(y, 0.0, theta)
    return theta, np.ascontiguousarray(samples.T), cr


@njit
def _loop_rhs(theta, Y, dy, net, tier, tab, perf, pr, cell, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(theta.size):
            balances.rhs(theta[k], Y[k], dy, net, tier, tab, perf, pr, cell)
            s += dy[0]
    return s


@njit(_nrt=False)
def _loop_inlined(theta, Y, dy, net, tier, tab, perf, pr, cell, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(theta.size):
            node_states(theta[k], Y[k], net, tier, tab, perf, pr)
            port_areas(theta[k], net, cell)
            balances(theta[k], Y[k], pr, dy, net, cell)
            s += dy[0]
    return s


@njit(_nrt=False)
def _loop_node_states(theta, Y, net, tier, tab, perf, pr, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(theta.size):
            node_states(theta[k], Y[k], net, tier, tab, perf, pr)
            s += pr[0, 0]
    return s


@njit(_nrt=False)
def _loop_volume(theta, net, nodes, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(theta.size):
            for i in range(nodes):
                V, dV = node_volume(theta[k], net, i)
                s += V + dV
    return s


@njit(_nrt=False)
def _loop_lookup(RHO, U, tab, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(RHO.shape[0]):
            for i in range(RHO.shape[1]):
                p, T, x, sup, c = lookup_flagged(tab, RHO[k, i], U[k, i])
                s += p + T + x
    return s


@njit(_nrt=False)
def _loop_kappa(RHO, U, tab, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(RHO.shape[0]):
            for i in range(RHO.shape[1]):
                s += kappa_at(tab, RHO[k, i], U[k, i])
    return s


@njit(_nrt=False)
def _loop_t_sat(P, tab, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(P.shape[0]):
            for i in range(P.shape[1]):
                s += t_sat(tab, P[k, i])
    return s


@njit(_nrt=False)
def _loop_port_areas(theta, net, cell, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(theta.size):
            port_areas(theta[k], net, cell)
            s += cell[0, 0]
    return s


@njit(_nrt=False)
def _loop_balances(theta, Y, dy, net, PR, PA, reps):
    s = 0.0
    for _ in range(reps):
        for k in range(theta.size):
            balances(theta[k], Y[k], PR[k], dy, net, PA[k])
            s += dy[0]
    return s


@njit(_nrt=False)
def _loop_edges(theta, net, PR, PA, reps):
    s = 0.0
    res, band, ea, eb = net.reservoirs, net.band, net.edge_a, net.edge_b
    ecd = net.edge_cd
    for _ in range(reps):
        for k in range(theta.size):
            pr = PR[k]
            for e in range(ea.shape[0]):
                a = ea[e]
                b = eb[e]
                if a >= 0:
                    pa, ra, ka = pr[0, a], pr[1, a], pr[3, a]
                else:
                    pa, ra, ka = res[-1 - a, 0], res[-1 - a, 1], res[-1 - a, 3]
                if b >= 0:
                    pb, rb, kb = pr[0, b], pr[1, b], pr[3, b]
                else:
                    pb, rb, kb = res[-1 - b, 0], res[-1 - b, 1], res[-1 - b, 3]
                s += port_flow(mechanism.edge_area(net, e, PA[k]), ecd[e], pa, ra, ka, pb, rb,
                               kb, band, True)
    return s


@njit
def _states_of(theta, Y, net, tier, tab, perf, PR, PA):
    pr = np.empty((PR.shape[1], PR.shape[2]))
    for k in range(theta.size):
        node_states(theta[k], Y[k], net, tier, tab, perf, pr)
        PR[k] = pr
        port_areas(theta[k], net, PA[k])


def timed(fn, args, reps, repeats, calls):
    """Median and least time per call [ns] of ``fn(*args, reps)``."""
    fn(*args, 1)
    per = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn(*args, reps)
        per.append((time.perf_counter() - t0) / (reps * calls) * 1e9)
    return statistics.median(per), min(per)


def per_call(scene_path, reps, repeats, label):
    """One line of JSON per measurement of the module's docstring."""
    theta, Y, cr = cycle_states(scene_path)
    net, tier, tab, perf, pr, cell = cr.net, cr._tier, cr._tab, cr._perf, cr._pr, cr._cell
    nodes = pr.shape[1]
    dy = np.zeros(Y.shape[1])
    PR = np.empty((theta.size, properties.PR_ROWS, nodes))
    PA = np.empty((theta.size,) + cell.shape)
    _states_of(theta, Y, net, tier, tab, perf, PR, PA)
    RHO = np.ascontiguousarray(PR[:, 1, :])
    U = np.ascontiguousarray(PR[:, 2, :] - PR[:, 0, :] / PR[:, 1, :])
    P = np.ascontiguousarray(PR[:, 0, :])
    cases = [
        ("rhs", _loop_rhs, (theta, Y, dy, net, tier, tab, perf, pr, cell)),
        ("rhs body inlined", _loop_inlined, (theta, Y, dy, net, tier, tab, perf, pr, cell)),
        ("node_states", _loop_node_states, (theta, Y, net, tier, tab, perf, pr)),
        ("node_volume, every node", _loop_volume, (theta, net, nodes)),
        ("lookup_flagged, every node", _loop_lookup, (RHO, U, tab)),
        ("kappa_at, every node", _loop_kappa, (RHO, U, tab)),
        ("t_sat, every node", _loop_t_sat, (P, tab)),
        ("port_areas", _loop_port_areas, (theta, net, cell)),
        ("balances", _loop_balances, (theta, Y, dy, net, PR, PA)),
        ("edge flows", _loop_edges, (theta, net, PR, PA)),
    ]
    for name, fn, args in cases:
        med, least = timed(fn, args, reps, repeats, theta.size)
        print(json.dumps({"version": label, "scene": Path(scene_path).stem, "part": name,
                          "ns_per_call": round(med, 1), "least_ns": round(least, 1),
                          "nodes": nodes, "edges": int(net.edge_a.shape[0]),
                          "load": round(os.getloadavg()[0], 2)}), flush=True)


def per_cycle(repeats, label):
    """Marginal CPU of a cycle of ``standard`` and ``fast`` (module docstring)."""
    from accuracy_vs_time import SCENES, marginal_ms_per_cycle
    scene = corliss.load_scene(SCENES["default"])
    for name in ("standard", "fast"):
        sc = scene.with_fidelity(name)
        corliss.simulate(sc.replace_run(cycles=2))          # compile or load the kernels
        wall, cpu, nfev = marginal_ms_per_cycle(sc, repeats)
        print(json.dumps({"version": label, "setting": name, "cpu_ms": round(cpu, 3),
                          "wall_ms": round(wall, 3), "rhs": nfev,
                          "load": round(os.getloadavg()[0], 2)}), flush=True)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default=str(DEFAULT_SCENE), help="scene file")
    ap.add_argument("--repeats", type=int, default=5, help="timings (median)")
    ap.add_argument("--reps", type=int, default=40, help="passes over the 361 states a timing")
    ap.add_argument("--cycles", action="store_true", help="also the marginal cost of a cycle")
    ap.add_argument("--label", default="", help="what to call this version in the output")
    args = ap.parse_args(argv)
    per_call(args.scene, args.reps, args.repeats, args.label)
    if args.cycles:
        per_cycle(args.repeats, args.label)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
