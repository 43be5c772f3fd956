"""A process's studies share one pool of workers, forked lean from a warm server.

The workers of a study on several processes are kept for the next (corliss.studies.pool):
a second study finds the same processes, and its rows are those of the same study run
here on one process, bit for bit (a run depends only on its inputs, never on the
worker or what it ran before).  Where the platform has multiprocessing's forkserver,
the workers are its forks, not this process's: they hold none of this process's
memory, in particular neither pandas nor pyarrow, which a run does not need (read from
the worker's memory map: a module imported is a shared library mapped).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

VARY = ["valve_gear.lap=0.8:1.2in", "run.speed=90:150rpm"]
RESPONSES = ["indicated_power_W", "steam_rate_kg_per_h", "events.head.cutoff_frac"]


#: The check runs in a fresh interpreter: the forkserver is one a process, started with
#: the modules of the first parallel caller (a compare's imports pandas), so in the
#: suite's worker it would be whatever an earlier test left.
_CHILD = r"""
import copy, os, sys
from pathlib import Path
sys.path.insert(0, sys.argv[1])
import pandas as pd
import corliss
from corliss.studies import pool as study_pool
from conftest import BASE
VARY = %r
RESPONSES = %r
kw = dict(fidelity="fast", responses=RESPONSES)
one = corliss.study(copy.deepcopy(BASE), VARY, lhs=6, seed=2, jobs=1, **kw)
first = corliss.study(copy.deepcopy(BASE), VARY, lhs=6, seed=2, jobs=2, chunk_size=1, **kw)
workers = study_pool.worker_pids()
assert len(workers) == 2, workers
second = corliss.study(copy.deepcopy(BASE), VARY, lhs=6, seed=2, jobs=2, chunk_size=1, **kw)
assert study_pool.worker_pids() == workers, "not the same processes: not kept"
pd.testing.assert_frame_equal(first.points, one.points, check_exact=True)
pd.testing.assert_frame_equal(second.points, one.points, check_exact=True)
if study_pool.start_method() == "forkserver":
    for pid in workers:
        stat = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        assert int(stat[1]) != os.getpid(), "forked here, not by the server"
        maps = Path(f"/proc/{pid}/maps").read_text()
        assert "pyarrow" not in maps and "/pandas/" not in maps, f"worker {pid} holds pandas"
print("ok")
""" % (VARY, RESPONSES)


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/proc as Linux has it")
def test_the_pool_is_kept_between_studies_and_its_workers_hold_no_pandas():
    """Two studies on two processes in a fresh interpreter: the second finds the first's
    workers; both give the one-process rows bit for bit; the workers are the server's
    forks and hold neither pandas nor pyarrow."""
    p = subprocess.run([sys.executable, "-c", _CHILD, str(Path(__file__).parent)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0 and p.stdout.strip().endswith("ok"), p.stdout + p.stderr
