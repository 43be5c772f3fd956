"""What a governed load step costs in time, and what the speed trace loses to speed.

The 60-second load step of a 200 rev/min engine, crank-resolved: the Porter-Allen
engine of ``scenes/porter-allen-governor.toml`` (14 1/2 x 24 in, Fink gear, Porter
governor, load halved at 10 s).  For each setting it reports the wall time of the run
(median of repeats, compilation excluded by a first run that is not timed; also the
CPU time of the run, the steadier on a shared machine) and the
error of its speed trace against a reference (table properties, dopri5 at rtol
1e-10): the largest difference of the turn-mean speed over the run, and of the final
speed and of the speed regulation.  The target is 0.5 s of CPU or less at
``standard``.  The mean-value model's time includes building its maps (45 steady runs).

The transient loop integrates with dopri5 at ``standard`` and with the Rosenbrock
method ``ros4`` at ``fast`` (``corliss.engine.options``, where the measurements that
chose them are summed up); the ``ros4`` rows show its price at other tolerances
(``method = "ros4"``, the loop's too).

Usage::

    python benchmarks/load_step.py [--repeats 5] [--out benchmarks/results]
                                   [--only "preset standard"]

Writes ``load_step.csv`` in the output directory (with ``--only``, the settings whose
label holds that text, and no CSV unless ``--out`` is given).  With
``PYTHONPATH=<another checkout>`` it times that checkout's code on the same settings.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

import corliss
from corliss.engine.options import PRESETS

HERE = Path(__file__).resolve().parent
SCENE = HERE.parent / "scenes" / "porter-allen-governor.toml"
DURATION_S = 60.0


def settings(scene):
    base = PRESETS["standard"]
    out = [("preset standard", scene.with_fidelity("standard")),
           ("preset fast", scene.with_fidelity("fast"))]
    for rtol in (1e-4, 1e-5, 1e-7, 1e-8):
        fid = dataclasses.replace(base, name="custom", rtol=rtol)
        out.append((f"table dopri5 rtol {rtol:.0e}", scene.replace_run(fidelity=fid)))
    for rtol in (5e-6, 5e-5):
        fid = dataclasses.replace(base, name="custom", method="ros4", rtol=rtol)
        out.append((f"table ros4 rtol {rtol:.0e}", scene.replace_run(fidelity=fid)))
    for rec in ("cycle", "step"):
        out.append((f"standard, record every {rec}", scene.replace_run(record=rec)))
    out.append(("mean-value model (maps built)", scene.replace_run(model="mean_value")))
    return out


def speed_trace(result):
    c = result.cycles
    t = 0.5 * (c["t_start_s"] + c["t_end_s"])
    return t.to_numpy(), c["mean_speed_rpm"].to_numpy()


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--out", default=None)
    p.add_argument("--only", default=None, help="time only the settings whose label holds "
                   "this text")
    args = p.parse_args(argv)
    if args.out is None and args.only is None:
        args.out = str(HERE / "results")
    scene = corliss.load_scene(SCENE).replace_run(duration_s=DURATION_S)
    ref_fid = dataclasses.replace(PRESETS["standard"], name="reference-table", rtol=1e-10)
    t0 = time.perf_counter()
    ref = corliss.simulate(scene.replace_run(fidelity=ref_fid))
    print(f"reference: {time.perf_counter() - t0:.2f} s, {len(ref.cycles)} turns, final "
          f"{ref.summary['final_speed_rpm']:.3f} rpm", file=sys.stderr)
    t_ref, n_ref = speed_trace(ref)
    rows = []
    for label, sc in settings(scene):
        if args.only is not None and args.only not in label:
            continue
        corliss.simulate(sc)                    # compile and warm up, not timed
        times, cpu = [], []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            c0 = time.process_time()
            r = corliss.simulate(sc)
            cpu.append(time.process_time() - c0)
            times.append(time.perf_counter() - t0)
        t, n = speed_trace(r)
        err = np.max(np.abs(np.interp(t_ref, t, n) - n_ref))
        s = r.summary
        rows.append({"setting": label, "wall_time_s": statistics.median(times),
                     "cpu_time_s": statistics.median(cpu),
                     "load_average_1min": os.getloadavg()[0],
                     "turns": len(r.cycles), "rhs_evaluations": r.rhs_evaluations,
                     "max_speed_error_rpm": err,
                     "final_speed_error_rpm": s["final_speed_rpm"] - ref.summary["final_speed_rpm"],
                     "regulation_error": s["regulation_frac"] - ref.summary["regulation_frac"],
                     "timeseries_rows": len(r.timeseries)})
        print(f"{label:32s} {rows[-1]['wall_time_s']:6.2f} s ({rows[-1]['cpu_time_s']:.2f} s "
              f"CPU)  speed error {err:.2e} rpm",
              file=sys.stderr)
    df = pd.DataFrame(rows)
    if args.out is None:
        print(df.to_string(index=False))
        return 0
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    df.to_csv(out / "load_step.csv", index=False, float_format="%.6g")
    print(df.to_string(index=False))
    return 0


if __name__ == "__main__":
    sys.exit(main())
