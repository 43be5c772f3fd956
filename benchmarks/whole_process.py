"""Whole-process times of the command line on a warm machine (kernels compiled, steam
table built): from starting ``corliss`` to its exit, imports and writing included, as
a user waits for it.

Each command is run once to warm the caches (not counted), then ``--repeats`` times,
with Python's bytecode cache on as on a user's machine (``PYTHONDONTWRITEBYTECODE`` is
removed from the commands' environment: with it set, as some shells and tools do, every
run compiles corliss's source again, about 0.2 s more);
the median wall time is reported with the fastest and slowest, since a shared machine
is noisy.  The commands:

* ``corliss run``: the default scene, its CSVs with their meta files, the two PNGs and
  the summary;
* ``corliss run --json --no-plots``: the same run, no figures, the summary as JSON;
* ``import corliss.cli.commands``: what the command costs before it does anything.

Usage::

    python benchmarks/whole_process.py [--repeats 7] [--out benchmarks/results]

Writes ``whole_process.csv`` in the output directory, with the machine's load average
(one minute) before and after each command's runs: on a shared machine the figures are
upper bounds, and the load says how far to trust them.  The same figures with the
shell's ``time``: ``time corliss run --out /tmp/x``.
"""

from __future__ import annotations

import argparse
import csv
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def _corliss() -> list[str]:
    """The ``corliss`` command as installed, or the same entry point through Python."""
    exe = shutil.which("corliss")
    return [exe] if exe else [sys.executable, "-c",
                              "import sys; from corliss.cli.commands import main; sys.exit(main())"]


def commands(out: str) -> dict[str, list[str]]:
    c = _corliss()
    return {
        "corliss run (default scene, CSVs and PNGs)": c + ["run", "--out", out],
        "corliss run --json --no-plots": c + ["run", "--json", "--no-plots", "--out", out],
        "python -c 'import corliss.cli.commands'": [sys.executable, "-c", "import corliss.cli.commands"],
    }


def time_command(cmd: list[str], repeats: int) -> list[float]:
    """Wall times [s] of ``repeats`` runs of ``cmd`` after one warm-up run."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   env=env)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       env=env)
        times.append(time.perf_counter() - t0)
    return times


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=7, help="timed runs per command (median)")
    ap.add_argument("--out", default=str(HERE / "results"), help="directory for the CSV")
    args = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, cmd in commands(tmp).items():
            load_before = os.getloadavg()[0]
            t = time_command(cmd, args.repeats)
            rows.append({"command": name, "median_s": round(statistics.median(t), 3),
                         "min_s": round(min(t), 3), "max_s": round(max(t), 3),
                         "runs": len(t), "load_before": round(load_before, 2),
                         "load_after": round(os.getloadavg()[0], 2)})
            print(f"{name:45s} median {rows[-1]['median_s']:6.2f} s  (min {rows[-1]['min_s']:.2f}, "
                  f"max {rows[-1]['max_s']:.2f}, {len(t)} runs; load {load_before:.1f} to "
                  f"{rows[-1]['load_after']:.1f})", flush=True)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "whole_process.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
