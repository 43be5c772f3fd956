"""The input fuzzer's long run: ``tests/test_fuzz_inputs.py`` (meta files, cards,
command lines, spliced scenes) with more cases and other seeds than CI's.

    python benchmarks/fuzz_inputs.py [--cases 300] [--seeds 1,2,3]

Each seed is one pytest run of the module with ``CORLISS_FUZZ_CASES`` and
``CORLISS_FUZZ_SEED`` set; the script prints each run's outcome and time and exits
non-zero if any found a traceback, an exit status other than 0, 2 or 3, a write
outside ``--out`` or a staging folder left behind (pytest's report names the case).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cases", type=int, default=300, help="cases of each kind per seed")
    p.add_argument("--seeds", default="1,2,3", help="seeds, comma-separated")
    args = p.parse_args(argv)
    worst = 0
    for seed in [int(s) for s in args.seeds.split(",")]:
        env = dict(os.environ, CORLISS_FUZZ_CASES=str(args.cases), CORLISS_FUZZ_SEED=str(seed))
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                               "-n", "0", str(ROOT / "tests" / "test_fuzz_inputs.py")],
                              env=env, capture_output=True, text=True)
        tail = (proc.stdout.strip().splitlines() or [""])[-1]
        print(f"seed {seed}: {args.cases} cases of each kind, {tail} "
              f"({time.perf_counter() - t0:.0f} s)")
        if proc.returncode:
            print(proc.stdout[-6000:])
            worst = max(worst, proc.returncode)
    return worst


if __name__ == "__main__":
    sys.exit(main())
