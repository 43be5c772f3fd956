"""Compile time of the steady kernels on an empty numba cache, per integrator.

For each method (dopri5 at rtol 1e-6, the ode23s pair ``rosenbrock`` at 5e-5, ``ros4``
at 1e-5, ``rodas4`` at 1e-4) a fresh Python process, with ``NUMBA_CACHE_DIR`` an empty
directory (the steam table's cache left as it is: build it once first), runs one cycle
of the default scene through :func:`corliss.simulate` and reports: the wall and CPU
time of that first call (which compiles everything the run calls), and numba's own
compile events per compiled function, inclusive (with the functions it compiles for
itself) and exclusive (without them), the largest first.

The child runs in the empty cache folder, so that the ``corliss`` it imports is the
one installed or on ``PYTHONPATH`` (with ``-c``, Python puts the working directory
first on its path).

Usage::

    python benchmarks/compile_time.py [--methods dopri5 ros4] [--top 6]

Prints one line of JSON per method.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
RTOL = {"dopri5": 1e-6, "rosenbrock": 5e-5, "ros4": 1e-5, "rodas4": 1e-4, "rodas3": 1e-4}

CHILD = r"""
import dataclasses, json, os, sys, time
from numba.core import event
import corliss
from corliss.engine.options import PRESETS
method, rtol, scene_path, top = sys.argv[1], float(sys.argv[2]), sys.argv[3], int(sys.argv[4])
scene = corliss.load_scene(scene_path)
fid = dataclasses.replace(PRESETS["standard"], name="custom", method=method, rtol=rtol)
scene = scene.replace_run(fidelity=fid, cycles=1)
stack, incl, excl = [], {}, {}
class Timer(event.Listener):
    def on_start(self, ev):
        stack.append([time.perf_counter(), 0.0])
    def on_end(self, ev):
        t0, inner = stack.pop()
        d = time.perf_counter() - t0
        name = ev.data["dispatcher"].py_func.__qualname__
        incl[name] = incl.get(name, 0.0) + d
        excl[name] = excl.get(name, 0.0) + d - inner
        if stack:
            stack[-1][1] += d
w0, c0 = time.perf_counter(), time.process_time()
with event.install_listener("numba:compile", Timer()):
    corliss.simulate(scene)
wall, cpu = time.perf_counter() - w0, time.process_time() - c0
order = sorted(excl, key=excl.get, reverse=True)[:top]
print(json.dumps({"method": method, "rtol": rtol, "first_call_wall_s": round(wall, 2),
                  "first_call_cpu_s": round(cpu, 2), "load": round(os.getloadavg()[0], 2),
                  "compiled": len(excl),
                  "exclusive_s": {k: round(excl[k], 2) for k in order},
                  "inclusive_s": {k: round(incl[k], 2) for k in order}}))
"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--methods", nargs="+", default=["dopri5", "rosenbrock", "ros4", "rodas4"])
    ap.add_argument("--top", type=int, default=6, help="functions listed per method")
    args = ap.parse_args(argv)
    scene = os.path.abspath(os.path.join(HERE, "..", "scenes", "default.toml"))
    for method in args.methods:
        with tempfile.TemporaryDirectory() as cache:
            env = dict(os.environ, NUMBA_CACHE_DIR=cache)
            out = subprocess.run([sys.executable, "-c", CHILD, method, str(RTOL[method]),
                                  scene, str(args.top)], env=env, check=True,
                                 capture_output=True, text=True, cwd=cache)
            print(out.stdout.strip().splitlines()[-1], flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
