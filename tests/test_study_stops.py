"""A study that is stopped keeps what it has done and finishes where it stopped.

``corliss study --out DIR`` appends each finished row to ``DIR/<scene>.study.partial.jsonl``;
Ctrl-C (SIGINT) and SIGTERM end the workers at once and keep those rows, a parent
killed outright (SIGKILL) takes its workers with it, and ``--resume`` runs only the
rows the journal lacks.  The table at the end must be the table of the same study
made in one sitting, row for row and bit for bit: a row's numbers depend only on its
scene (the same compiled kernels on the same inputs), never on the sitting, the
worker or the order.  On Dask, a worker killed mid-study has its tasks run again on
another, and the table is again the one-sitting table.

Kept small (a few hundred ``fast`` runs of the test engine): these tests prove the
plumbing a user leans on when a long study is interrupted, not the physics.
"""

from __future__ import annotations

import copy
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

import corliss
from corliss.errors import InputError, RunError
from corliss.studies import pool as study_pool
from corliss.studies import runner as study_runner
from corliss.keys.toml_text import dumps
from conftest import BASE

VARY = ["valve_gear.lap=0.8:1.2in", "run.speed=90:150rpm"]
RESPONSES = ["indicated_power_W", "steam_rate_kg_per_h", "events.head.cutoff_frac"]
#: Enough runs that two workers cannot finish them between the first rows coming back
#: and the signal, twice, on a loaded machine too: at 3 ms of CPU a ``fast`` run, 400
#: runs were once all done before the signal came (it then landed in the interpreter's
#: shutdown, exit 0), so four times that.
RUNS = 1600

linux_only = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                 reason="signals and /proc as Linux has them")


def _scene_file(tmp_path: Path) -> Path:
    data = copy.deepcopy(BASE)
    data["title"] = "stopped study"
    path = tmp_path / "engine.toml"
    path.write_text(dumps(data), encoding="utf-8")
    return path


def _command(scene: Path, out: Path, *extra) -> list[str]:
    args = [sys.executable, "-m", "corliss.cli.commands", "study", str(scene)]
    for v in VARY:
        args += ["--vary", v]
    for r in RESPONSES:
        args += ["--response", r]
    return args + ["--lhs", str(RUNS), "--seed", "5", "--fidelity", "fast", "--jobs", "2",
                   "--out", str(out), "--json", *extra]


def _rows(journal: Path) -> int:
    try:
        return max(0, journal.read_text().count("\n") - 1)
    except FileNotFoundError:
        return 0


def _wait_for_rows(proc, journal: Path, more_than: int, timeout_s: float = 120.0) -> int:
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout_s:
        n = _rows(journal)
        if n > more_than:
            return n
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.01)
    raise AssertionError(f"no rows in {journal} after {timeout_s} s")


def _children(pid: int) -> list[int]:
    kids = []
    for task in Path(f"/proc/{pid}/task").iterdir():
        kids += [int(k) for k in (task / "children").read_text().split()]
    return kids


def _descendants(pid: int) -> list[int]:
    """The processes under ``pid``: its children, theirs, and so on (a pool's workers
    are children of its forkserver, itself a child of the study's process)."""
    out, todo = [], [pid]
    while todo:
        try:
            kids = _children(todo.pop())
        except FileNotFoundError:
            continue
        out += kids
        todo += kids
    return out


def _gone(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except FileNotFoundError:
        return True
    return stat.rsplit(")", 1)[1].split()[0] == "Z"     # a zombie has ended


@linux_only
def test_a_study_stopped_by_sigint_then_killed_resumes_to_the_one_sitting_table(tmp_path):
    scene = _scene_file(tmp_path)
    out = tmp_path / "out"
    journal = out / "engine.study.partial.jsonl"
    env = dict(os.environ, PYTHONUNBUFFERED="1")

    # first sitting: Ctrl-C once the first rows are in; it ends at once, exit 130
    proc = subprocess.Popen(_command(scene, out), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env)
    _wait_for_rows(proc, journal, 0)
    t0 = time.monotonic()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    stopped_s = time.monotonic() - t0
    assert proc.returncode == 130, err
    # half a second here with the machine to itself (workers killed, the process gone);
    # the bound leaves room for a loaded machine, and a study that ran on to its end
    # (the 400 runs) or waited on a worker would fail the row count below anyway
    assert stopped_s < 15.0, stopped_s
    kept = _rows(journal)
    assert 0 < kept < RUNS, kept
    assert f"after {kept} of {RUNS} runs" in err and "--resume" in err
    head = json.loads(journal.read_text().split("\n")[0])
    assert head["corliss_study"].startswith("partial") and head["seed"] == 5
    assert not (out / "engine.study.csv").exists()

    # second sitting: resumed, then killed outright; its workers die with it
    proc = subprocess.Popen(_command(scene, out, "--resume"), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env)
    # a worker's chunks: the pool is up
    _wait_for_rows(proc, journal, kept + 2)
    workers = _descendants(proc.pid)
    assert len(workers) >= 3            # two workers, and the process that forked them
    proc.kill()
    proc.communicate(timeout=120)
    t0 = time.monotonic()
    while not all(_gone(w) for w in workers) and time.monotonic() - t0 < 10.0:
        time.sleep(0.05)
    assert all(_gone(w) for w in workers), "a worker outlived its killed parent"
    kept2 = _rows(journal)
    assert kept < kept2 < RUNS, (kept, kept2)
    lines = journal.read_text().split("\n")[1:]
    missing = set(range(RUNS)) - {json.loads(ln)[0] for ln in lines if ln.endswith("]")}

    # third sitting, here: only the rows the journal lacks are run
    ran = []
    real = study_runner.run_chunk

    def counted(spec, ids, values):
        ran.extend(int(i) for i in ids)
        return real(spec, ids, values)

    study_runner.run_chunk = counted
    try:
        done = corliss.study(corliss.load_scene(scene), VARY, lhs=RUNS, seed=5,
                             fidelity="fast", responses=RESPONSES, jobs=1, out=out,
                             resume=True)
    finally:
        study_runner.run_chunk = real
    assert sorted(ran) == sorted(missing)        # none run twice, none left out
    files = done.write(out, plots=False, parquet=False)
    assert not journal.exists() and files["points"].exists()

    whole = corliss.study(corliss.load_scene(scene), VARY, lhs=RUNS, seed=5,
                          fidelity="fast", responses=RESPONSES, jobs=1)
    assert (whole.points["status"] == "ok").all()
    pd.testing.assert_frame_equal(done.points, whole.points, check_exact=True)


def test_resuming_another_studys_journal_is_refused_before_any_run(tmp_path, monkeypatch):
    """A journal whose fingerprint is of another study (here another seed) is not mixed
    into this one."""
    out = tmp_path / "out"
    corliss.study(copy.deepcopy(BASE), ["run.speed=100,120rpm"], grid=True, fidelity="fast",
                  responses=RESPONSES, jobs=1, out=out)
    journal = out / "scene.study.partial.jsonl"
    assert _rows(journal) == 2

    def boom(*a, **k):
        raise AssertionError("a run started")
    monkeypatch.setattr(study_runner, "run_chunk", boom)
    with pytest.raises(InputError) as err:
        corliss.study(copy.deepcopy(BASE), ["run.speed=100,130rpm"], grid=True,
                      fidelity="fast", responses=RESPONSES, jobs=1, out=out, resume=True)
    assert err.value.key == "--resume"


def test_an_output_directory_that_cannot_be_written_is_refused_before_any_run(
        tmp_path, monkeypatch, capsys):
    """``--out`` under a plain file: refused, naming it, before the first run."""
    from corliss.cli.commands import main

    def boom(*a, **k):
        raise AssertionError("a run started")
    monkeypatch.setattr(study_runner, "run_chunk", boom)
    blocker = tmp_path / "a file"
    blocker.write_text("not a directory")
    rc = main(["study", "default", "--vary", "valve_gear.lap=0.8:1.2in", "--grid",
               "--fidelity", "fast", "--out", str(blocker / "out")])
    err = capsys.readouterr().err
    assert rc == 2 and "--out" in err and "Nothing was simulated" in err


@linux_only
def test_a_local_worker_killed_mid_study_has_its_tasks_run_again(caplog):
    """One of the pool's two workers killed (SIGKILL, as the kernel's out-of-memory
    killer does) after the first chunk comes back: the pool is started again, the
    unfinished chunks resent, and the table is the one-sitting table row for row."""
    kw = dict(lhs=24, seed=3, fidelity="fast", responses=RESPONSES)
    whole = corliss.study(copy.deepcopy(BASE), VARY, jobs=1, **kw)
    killed = []

    def progress(done, total):
        workers = study_pool.worker_pids()
        if not killed and done > 1 and workers:
            os.kill(workers[0], signal.SIGKILL)
            killed.append(workers[0])

    got = corliss.study(copy.deepcopy(BASE), VARY, jobs=2, chunk_size=2, progress=progress,
                        **kw)
    assert killed and "worker process was lost" in caplog.text
    pd.testing.assert_frame_equal(got.points, whole.points, check_exact=True)


def test_a_dask_worker_killed_mid_study_leaves_the_study_to_the_others(tmp_path):
    """Two worker processes under nannies; after the first chunk comes back one is
    killed (SIGKILL): its tasks run again elsewhere, and the table is the one-sitting
    table row for row."""
    distributed = pytest.importorskip("distributed")
    kw = dict(lhs=12, seed=3, fidelity="fast", responses=RESPONSES)
    whole = corliss.study(copy.deepcopy(BASE), VARY, jobs=1, **kw)
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        pids = client.run(os.getpid)
        killed = []

        def progress(done, total):
            if not killed:
                victim = sorted(pids.values())[0]
                os.kill(victim, signal.SIGKILL)
                killed.append(victim)

        got = corliss.study(copy.deepcopy(BASE), VARY, scheduler=client, chunk_size=1,
                            progress=progress, **kw)
    assert killed
    pd.testing.assert_frame_equal(got.points, whole.points, check_exact=True)


def test_a_dask_cluster_with_no_worker_left_is_an_error_not_a_wait(monkeypatch):
    """Every worker closed after the first chunk: the study raises, naming the cluster,
    once the grace period is over, instead of waiting for ever."""
    distributed = pytest.importorskip("distributed")
    monkeypatch.setattr(study_runner, "NO_WORKERS_GRACE_S", 1.0)
    monkeypatch.setattr(study_runner, "POLL_S", 0.2)
    with distributed.LocalCluster(n_workers=1, processes=False, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        def progress(done, total):
            if done == 1:
                for worker in list(cluster.workers.values()):
                    cluster.sync(worker.close)

        t0 = time.monotonic()
        with pytest.raises(RunError) as err:
            corliss.study(copy.deepcopy(BASE), VARY, lhs=200, seed=3, fidelity="fast",
                          responses=RESPONSES, scheduler=client, chunk_size=1,
                          progress=progress)
        assert time.monotonic() - t0 < 60.0
    assert "no worker" in str(err.value)
