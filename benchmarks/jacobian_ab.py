"""Marginal cost of a cycle of the Rosenbrock settings, for an A/B of two versions.

For ``fast`` (the ode23s pair at rtol 5e-5), ``rodas4`` at rtol 1e-4 and ``ros4`` at
rtol 7e-6 on the accuracy study's default scene: the in-process marginal cost of one
more cycle through the public API (:func:`accuracy_vs_time.marginal_ms_per_cycle`: 6
cycles less 2, over 4), as the process's CPU time, median of ``--repeats``, with the
right-hand-side evaluations of that cycle.  Run it once per version (the version
imported is whichever ``corliss`` the interpreter finds), alternating the versions
between rounds, so that both see the same load.

Usage::

    python benchmarks/jacobian_ab.py [--repeats 5] [--label NAME]

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
    args = ap.parse_args(argv)
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


if __name__ == "__main__":
    raise SystemExit(main())
