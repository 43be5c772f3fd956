"""How ``corliss study`` scales: runs a second on one process, the parent's share of the
work, two processes against one, and the speed-up the serial share allows on many.

The study is the issue's: a Latin hypercube over the default engine's port width,
clearance, lap and speed at the ``fast`` fidelity (``--runs``, default 1000).  Each
measurement runs in a fresh Python process (``--worker``), after a warm-up study of 8
runs on as many processes in that process (kernels loaded from numba's cache, the
steam table read, and where the code keeps its pool, the pool started), so each
sitting pays what a user's second study in one process pays; the warm-up's own wall
time is recorded too (``first_wall_s``: a first study in a fresh process, a command
line's).  Given ``--baseline DIR`` (a checkout of
another version, e.g. ``git worktree add ../base main``), the same measurements run on
that code too, alternating with this tree's, ``--repeats`` times each: an A/B in one
sitting on a machine whose load moves.

Measured per study:

* wall time and runs a second on one process (``jobs=1``) and on two (``jobs=2``);
* CPU per run: this process's (the parent: checks, set-up, sending chunks,
  collecting rows) and its pool's workers' (read when the pool is shut down and its
  workers reaped, or, for workers kept for the process and forked by its forkserver,
  from ``/proc`` before and after the study);
* the serial fraction ``s``: the parent's CPU over the parent's and the workers'
  (the workers' start-up counted in theirs), and the parent's CPU to start one more
  worker ``F`` (the code's own way: where it keeps a pool
  (``corliss.studies.pool``), the CPU of starting :data:`START` workers on it from
  its forkserver, over their number, and the forkserver's CPU for them beside it;
  else a fork of the process as it is after the study); from them Amdahl's speed-up
  on N processes, ``(P + W) / (P + (N - 2) F + W / N)`` (:func:`amdahl`), for 16 and
  64 (derived, not measured: no machine with that many free cores was at hand).

On a machine shared with other work, two processes cannot show their speed-up in
wall time alone: the CPU figures say whether the parallel path adds work of its own.
The load average before and after is recorded.

Usage::

    python benchmarks/study_scaling.py [--runs 1000] [--repeats 3] [--baseline DIR]
                                       [--out benchmarks/results]

Writes ``study_scaling.csv`` (one row per study run) and prints the medians.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
#: The study of the issue: the default engine's port width, clearance, lap and speed.
VARY = ["valve_gear.port_width=1.0:1.5in", "engine.clearance=0.04:0.12",
        "valve_gear.lap=0.8:1.2in", "run.speed=90:150rpm"]
RESPONSES = ["indicated_power_W", "mep_mean_Pa", "steam_rate_kg_per_h",
             "water_rate_kg_per_kWh", "events.head.cutoff_frac"]
#: Forks timed to find what one more worker's start costs the parent.
FORKS = 5
#: Workers started on a kept pool to find what one more costs the parent.
START = 4


def _cpu(who) -> float:
    r = resource.getrusage(who)
    return r.ru_utime + r.ru_stime


def _proc_cpu(pid: int) -> float:
    """A live process's CPU [s] (user and system), from ``/proc`` (0 when gone)."""
    try:
        f = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (FileNotFoundError, ProcessLookupError):
        return 0.0
    return (int(f[11]) + int(f[12])) / os.sysconf("SC_CLK_TCK")


def _kept_pool():
    """The code's kept pool module and its forkserver's pid (None, None without)."""
    try:
        from corliss.studies import pool
    except ImportError:
        return None, None
    try:
        from multiprocessing import forkserver
        server = forkserver._forkserver._forkserver_pid
    except (ImportError, AttributeError):
        server = None
    return pool, server


def _kept_cpu(pool) -> dict:
    return {} if pool is None else {pid: _proc_cpu(pid) for pid in pool.worker_pids()}


def measure(runs: int, jobs: int) -> dict:
    """One study in this process, after a warm-up: its wall time and CPU [s].

    Parameters
    ----------
    runs : int
        Runs of the Latin hypercube.
    jobs : int
        Local processes.

    Returns
    -------
    dict
        ``wall_s``, ``first_wall_s``, ``parent_cpu_s``, ``workers_cpu_s``,
        ``server_cpu_s``, ``failed``, ``fork_cpu_s``, ``server_fork_cpu_s``.
    """
    import corliss
    t0 = time.perf_counter()
    corliss.study("default", VARY, lhs=8, seed=1, fidelity="fast", responses=RESPONSES,
                  jobs=jobs)
    first = time.perf_counter() - t0
    pool, server = _kept_pool()
    k0, s0 = _kept_cpu(pool), (_proc_cpu(server) if server else 0.0)
    p0, c0, t0 = _cpu(resource.RUSAGE_SELF), _cpu(resource.RUSAGE_CHILDREN), time.perf_counter()
    res = corliss.study("default", VARY, lhs=runs, seed=0, fidelity="fast",
                        responses=RESPONSES, jobs=jobs)
    wall = time.perf_counter() - t0
    parent = _cpu(resource.RUSAGE_SELF) - p0
    k1 = _kept_cpu(pool)
    kept = sum(k1[p] - k0.get(p, 0.0) for p in k1)
    out = {"wall_s": wall, "first_wall_s": first, "parent_cpu_s": parent,
           "workers_cpu_s": _cpu(resource.RUSAGE_CHILDREN) - c0 + kept,
           "server_cpu_s": (_proc_cpu(server) - s0) if server else 0.0,
           "failed": int(res.failed)}
    # what starting one more worker costs this process: the code's own way
    if pool is not None and server is not None:
        pool.close()
        s0, f0 = _proc_cpu(server), _cpu(resource.RUSAGE_SELF)
        pool.run_tasks([(time.sleep, (0.2,)) for _ in range(START)], START,
                       lambda i, r: None)
        out["fork_cpu_s"] = (_cpu(resource.RUSAGE_SELF) - f0) / START
        out["server_fork_cpu_s"] = (_proc_cpu(server) - s0) / START
        pool.close()
        return out
    f0 = _cpu(resource.RUSAGE_SELF)
    for _ in range(FORKS):
        pid = os.fork()
        if pid == 0:
            os._exit(0)
        os.waitpid(pid, 0)
    out["fork_cpu_s"] = (_cpu(resource.RUSAGE_SELF) - f0) / FORKS
    out["server_fork_cpu_s"] = 0.0
    return out


def _sitting(code: Path, runs: int, jobs: int) -> dict:
    """:func:`measure` in a fresh process importing corliss from ``code``."""
    env = dict(os.environ, PYTHONPATH=str(code))
    out = subprocess.run([sys.executable, str(Path(__file__).resolve()), "--worker",
                          "--runs", str(runs), "--jobs", str(jobs)],
                         capture_output=True, text=True, env=env, cwd=str(code), check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def amdahl(parent_s: float, workers_s: float, fork_s: float, n: int) -> float:
    """Speed-up on ``n`` processes (Amdahl) of a study whose parent spent
    ``parent_s`` [s] of CPU with two workers, its workers ``workers_s`` [s], and whose
    every further worker costs the parent ``fork_s`` [s] to start.

    ``(P + W) / (P + (n - 2) F + W / n)``: the parent's work is serial, the workers'
    divides among them, and a worker's start (a fork) is serial in the parent.
    """
    return (parent_s + workers_s) / (parent_s + (n - 2) * fork_s + workers_s / n)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--baseline", help="a checkout of the code to compare against")
    ap.add_argument("--out", default=str(HERE / "results"))
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--jobs", type=int, default=1, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        print(json.dumps(measure(args.runs, args.jobs)))
        return 0
    trees = {"this": HERE.parent}
    if args.baseline:
        trees["baseline"] = Path(args.baseline).resolve()
    load0 = os.getloadavg()
    rows = []
    for rep in range(args.repeats):
        for jobs in (1, 2):
            for name, code in trees.items():
                m = _sitting(code, args.runs, jobs)
                row = {"code": name, "jobs": jobs, "repeat": rep, "runs": args.runs, **m,
                       "load": round(os.getloadavg()[0], 2)}
                rows.append(row)
                print(json.dumps(row), flush=True)
    load1 = os.getloadavg()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "study_scaling.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    def med(code, jobs, key):
        return statistics.median(r[key] for r in rows if r["code"] == code and r["jobs"] == jobs)

    n = args.runs
    print(f"\n{n} runs a study, fast, medians of {args.repeats}; load average "
          f"{load0[0]:.2f} before, {load1[0]:.2f} after, {os.cpu_count()} cores")
    summary = {}
    for name in trees:
        w1, w2 = med(name, 1, "wall_s"), med(name, 2, "wall_s")
        cpu1 = med(name, 1, "parent_cpu_s") / n
        par, wrk = med(name, 2, "parent_cpu_s"), med(name, 2, "workers_cpu_s")
        fork = med(name, 2, "fork_cpu_s")
        first1, first2 = med(name, 1, "first_wall_s"), med(name, 2, "first_wall_s")
        s = par / (par + wrk)
        summary[name] = {"runs_per_s_1": n / w1, "cpu_ms_per_run_1": 1e3 * cpu1,
                         "two_over_one": w1 / w2, "parent_ms_per_run": 1e3 * par / n,
                         "workers_ms_per_run": 1e3 * wrk / n, "serial_fraction": s,
                         "parent_share_of_run": (par / n) / cpu1,
                         "fork_ms": 1e3 * fork,
                         "server_fork_ms": 1e3 * med(name, 2, "server_fork_cpu_s"),
                         "first_wall_s_1": first1, "first_wall_s_2": first2,
                         "speedup_16": amdahl(par, wrk, fork, 16),
                         "speedup_64": amdahl(par, wrk, fork, 64)}
        x = summary[name]
        print(f"{name:9s} 1 process: {x['runs_per_s_1']:6.1f} runs/s, "
              f"{x['cpu_ms_per_run_1']:.2f} ms CPU a run | 2 processes: "
              f"{x['two_over_one']:.2f} x one (wall) | parent {x['parent_ms_per_run']:.3f} ms "
              f"a run = {100 * x['parent_share_of_run']:.1f} % of a run, workers "
              f"{x['workers_ms_per_run']:.2f} ms a run | serial fraction {s:.4f}, "
              f"{x['fork_ms']:.2f} ms a worker's start (its forkserver "
              f"{x['server_fork_ms']:.2f} ms): {x['speedup_16']:.1f} x on 16, "
              f"{x['speedup_64']:.1f} x on 64 (Amdahl, derived) | a first study of 8 runs "
              f"in a fresh process: {x['first_wall_s_1']:.2f} s on 1, "
              f"{x['first_wall_s_2']:.2f} s on 2")
    if "baseline" in summary:
        a, b = summary["this"], summary["baseline"]
        print(f"this / baseline, runs a second on one process: "
              f"{a['runs_per_s_1'] / b['runs_per_s_1']:.2f}; CPU a run: "
              f"{b['cpu_ms_per_run_1'] / a['cpu_ms_per_run_1']:.2f} x less")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
