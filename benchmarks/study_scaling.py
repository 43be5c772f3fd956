"""How ``corliss study`` scales: runs per second on one core and on every core, and what
a Dask cluster costs per task.

Measured, each ``--repeats`` times after one warm-up (the kernels loaded from numba's
cache, the steam table built), medians reported with the fastest and slowest:

* the Latin hypercube of the issue: ``--lhs 1000`` over the default engine's port
  width, clearance, lap and speed at the ``fast`` tier, on one process (in this one)
  and on every core (a process pool, its start-up counted: a study pays it);
* the same study's first ``--dask-runs`` runs on a local Dask cluster (one worker
  process per core, one thread each), one run a task, against the local process pool
  with one run a task: the difference per task is what Dask adds to a task over a
  process pool;
* CPU time per run of the local studies (this process and its pool's workers): on a
  machine whose cores other work keeps busy the wall times cannot show the scaling,
  and equal CPU per run on one process and on several says the parallel path adds no
  work of its own;
* Dask's own round trip: ``--noop-tasks`` tasks that carry a real task's arguments (the
  base scene's tables) and run nothing, per task, on the same cluster.

Usage::

    python benchmarks/study_scaling.py [--repeats 3] [--runs 1000] [--out benchmarks/results]

Writes ``study_scaling.csv`` and the 1000-run study's figure ``study_lhs_1000.png``.
The machine's load average before and after is recorded, since a shared machine is
noisy.
"""

from __future__ import annotations

import argparse
import csv
import os
import resource
import statistics
import time
from pathlib import Path

import numpy as np

import corliss
from corliss.studies import runner

HERE = Path(__file__).resolve().parent
#: The study of the issue: the default engine's port width, clearance, lap and speed.
VARY = ["valve_gear.port_width=1.0:1.5in", "engine.clearance=0.04:0.12",
        "valve_gear.lap=0.8:1.2in", "run.speed=90:150rpm"]
RESPONSES = ["indicated_power_W", "mep_mean_Pa", "steam_rate_kg_per_h",
             "water_rate_kg_per_kWh", "events.head.cutoff_frac"]


def _cpu_s() -> float:
    """CPU time [s] of this process and of its children that have ended (a study's
    process pool is shut down, its workers reaped, when the study returns)."""
    a, b = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return a.ru_utime + a.ru_stime + b.ru_utime + b.ru_stime


def _timed(fn, repeats: int):
    """Wall times [s] of ``repeats`` calls after a warm-up, the CPU seconds of each
    (this process and the pools it started) and the last call's result."""
    fn()                                        # warm-up, not counted
    times, cpu, last = [], [], None
    for _ in range(repeats):
        c0, t0 = _cpu_s(), time.perf_counter()
        last = fn()
        times.append(time.perf_counter() - t0)
        cpu.append(_cpu_s() - c0)
    return times, cpu, last


def _study(n, **kw):
    return corliss.study("default", VARY, lhs=n, seed=0, fidelity="fast",
                         responses=RESPONSES, **kw)


def _noop(n_tasks: int, client):
    base = corliss.load_scene(corliss.default_scene_path()).data
    keys = (("valve_gear.lap", "in"),)
    futs = client.map(runner.run_chunk, [base] * n_tasks, ["default"] * n_tasks,
                      ["fast"] * n_tasks, [tuple(RESPONSES)] * n_tasks, [keys] * n_tasks,
                      [range(0)] * n_tasks, [np.zeros((0, 1))] * n_tasks, pure=False)
    client.gather(futs)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--dask-runs", type=int, default=200)
    ap.add_argument("--noop-tasks", type=int, default=500)
    ap.add_argument("--out", default=str(HERE / "results"))
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    cores = os.cpu_count() or 1
    load0 = os.getloadavg()
    rows = []

    def record(what, workers, runs, times, cpu=None, note=""):
        med = statistics.median(times)
        rows.append({"measurement": what, "workers": workers, "runs": runs,
                     "median_s": round(med, 3), "min_s": round(min(times), 3),
                     "max_s": round(max(times), 3),
                     "runs_per_s": round(runs / med, 1) if runs else "",
                     "per_task_ms": round(1e3 * med / runs, 2) if runs else "",
                     "cpu_ms_per_run": (round(1e3 * statistics.median(cpu) / runs, 2)
                                        if cpu else ""),
                     "repeats": len(times), "note": note})
        print(rows[-1], flush=True)

    n = args.runs
    for jobs in (1, cores):
        times, cpu, res = _timed(lambda j=jobs: _study(n, jobs=j), args.repeats)
        record(f"lhs {n} runs, fast, local", jobs, n, times, cpu,
               f"{res.failed} failed; {res.rhs_evaluations / n:.0f} rhs evaluations a run")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig = res.plot()["figure"]
    fig.savefig(out / f"study_lhs_{n}.png", dpi=60, bbox_inches="tight")
    plt.close(fig)

    try:
        import distributed
    except ImportError:
        print("dask.distributed is not installed: the Dask measurements are left out")
    else:
        m = args.dask_runs
        times, cpu, _ = _timed(lambda: _study(m, jobs=cores, chunk_size=1), args.repeats)
        record(f"lhs {m} runs, one a task, local pool", cores, m, times, cpu)
        with distributed.LocalCluster(n_workers=cores, processes=True, threads_per_worker=1,
                                      dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            times, _, _ = _timed(lambda: _study(m, scheduler=client, chunk_size=1),
                                 args.repeats)
            record(f"lhs {m} runs, one a task, Dask LocalCluster", cores, m, times)
            times, _, _ = _timed(lambda: _study(m, scheduler=client), args.repeats)
            record(f"lhs {m} runs, default chunks, Dask LocalCluster", cores, m, times)
            k = args.noop_tasks
            times, _, _ = _timed(lambda: _noop(k, client), args.repeats)
            record(f"{k} tasks that run nothing, Dask LocalCluster", cores, k, times,
                   note="each carries the base scene's tables, as a real task")
    load1 = os.getloadavg()
    for r in rows:
        r["load_before"] = f"{load0[0]:.2f}"
        r["load_after"] = f"{load1[0]:.2f}"
    path = out / "study_scaling.csv"
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}; load average {load0[0]:.2f} before, {load1[0]:.2f} after, "
          f"{cores} cores")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
