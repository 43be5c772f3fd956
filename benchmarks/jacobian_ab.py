"""Marginal cost of a cycle of the Rosenbrock settings, for an A/B of two versions.

For ``fast`` (the ode23s pair at rtol 5e-5), ``rodas4`` at rtol 1e-4 and ``ros4`` at
rtol 7e-6 on the accuracy study's default scene: the in-process marginal cost of one
more cycle through the public API (:func:`accuracy_vs_time.marginal_ms_per_cycle`: 6
cycles less 2, over 4), as the process's CPU time, median of ``--repeats``, with the
right-hand-side evaluations of that cycle.  Run it once per version (the version
imported is whichever ``corliss`` the interpreter finds), alternating the versions
between rounds, so that both see the same load.

With ``--stiff``, instead: each Rosenbrock method on the default card with ports 1000
times the gear's (the stiff case of tests/test_property_tiers.py), the PortMap at 720
points, periodic to 1e-4 in 40 cycles at most: the cycles it took, its evaluations a
cycle and its indicated work, or the error that stopped it.

Usage::

    python benchmarks/jacobian_ab.py [--repeats 5] [--label NAME] [--stiff]

Prints one line of JSON per setting.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os

import corliss
from corliss.engine.options import PRESETS
from accuracy_vs_time import SCENES, marginal_ms_per_cycle


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=5, help="repeats (median)")
    ap.add_argument("--label", default="", help="what to call this version in the output")
    ap.add_argument("--stiff", action="store_true", help="the stiff ports instead")
    args = ap.parse_args(argv)
    if args.stiff:
        return stiff(args.label)
    scene = corliss.load_scene(SCENES["default"])
    base = PRESETS["standard"]
    cases = [("fast", scene.with_fidelity("fast"))]
    for method, rtol in (("rodas4", 1e-4), ("ros4", 7e-6)):
        fid = dataclasses.replace(base, name="custom", method=method, rtol=rtol)
        cases.append((f"{method} {rtol:g}", scene.replace_run(fidelity=fid)))
    for name, sc in cases:
        corliss.simulate(sc.replace_run(cycles=2))          # compile or load the kernels
        wall, cpu, nfev = marginal_ms_per_cycle(sc, args.repeats)
        print(json.dumps({"version": args.label, "setting": name, "cpu_ms": round(cpu, 3),
                          "wall_ms": round(wall, 3), "rhs": nfev,
                          "load": round(os.getloadavg()[0], 2)}), flush=True)
    return 0


def stiff(label: str) -> int:
    """Each Rosenbrock method on ports 1000 times the gear's (module docstring)."""
    from corliss.errors import RunError
    scene = corliss.load_scene(SCENES["default"])
    base = PRESETS["standard"]
    for method, rtol in (("rosenbrock", 5e-5), ("rodas4", 1e-4), ("ros4", 7e-6),
                         ("rodas3", 1e-4)):
        fid = dataclasses.replace(base, name="custom", method=method, rtol=rtol,
                                  portmap_points=720)
        row = {"version": label, "method": method, "rtol": rtol}
        try:
            s = corliss.simulate(scene.replace_run(fidelity=fid), portmap_scale=1000.0).summary
            row.update(cycles=s["cycles_simulated"], converged=s["cycles_to_converge"] is not None,
                       rhs_per_cycle=round(s["rhs_evaluations"] / s["cycles_simulated"]),
                       work_J=round(s["indicated_work_J_per_cycle"], 1))
        except (RunError, RuntimeError) as err:
            row["stopped"] = str(err).split(":")[0][:80]
        print(json.dumps(row), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
