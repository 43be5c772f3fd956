"""Whole-process time of the default throttling-versus-cut-off comparison.

``corliss compare SCENE`` with its defaults (2 variants x 2 condensation settings x 11
loads, the scene's tier, the governor's droop, every core), from starting the command
to its exit, imports, figure and tables included, after one warm-up run (kernels
compiled, steam table cached).  The scenes: the 20 x 42 in Corliss engine
(``corliss-governor``) and the 10 x 12 in Armington & Sims high-speed engine
(``armington-sims-governor``).  The median of ``--repeats`` runs is reported with the
fastest and slowest, and the steady runs the command made (from its own report).

Usage::

    python benchmarks/compare_time.py [--repeats 5] [--out benchmarks/results]

Writes ``compare_time.csv`` in the output directory.
"""

from __future__ import annotations

import argparse
import csv
import os
import re
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

from whole_process import HERE, _corliss

SCENES = ("corliss-governor", "armington-sims-governor")


def time_compare(scene: str, repeats: int, out: str) -> tuple[list[float], int | None]:
    """Wall times [s] of ``repeats`` comparisons of ``scene`` after a warm-up, and the
    steady runs each made."""
    cmd = _corliss() + ["compare", scene, "--out", out]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    times, runs = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        p = subprocess.run(cmd, check=True, capture_output=True, text=True)
        times.append(time.perf_counter() - t0)
        m = re.search(r"(\d+) steady runs", p.stdout + p.stderr)
        runs = int(m.group(1)) if m else runs
    return times, runs


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=5, help="timed runs per scene (median)")
    ap.add_argument("--out", default=str(HERE / "results"), help="directory for the CSV")
    args = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in SCENES:
            t, runs = time_compare(scene, args.repeats, tmp)
            rows.append({"scene": scene, "median_s": round(statistics.median(t), 2),
                         "min_s": round(min(t), 2), "max_s": round(max(t), 2),
                         "repeats": len(t), "steady_runs": runs, "cores": os.cpu_count(),
                         "load_average_1min": round(os.getloadavg()[0], 2)})
            print(f"{scene:26s} median {rows[-1]['median_s']:6.2f} s  (min {rows[-1]['min_s']:.2f}, "
                  f"max {rows[-1]['max_s']:.2f}; {runs} steady runs)", flush=True)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "compare_time.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
