"""A study: steady runs of one scene over a design of its keys, on local processes or a
Dask cluster.

Each run is the base scene's tables with the run's keys set
(:func:`corliss.keys.edits.edited`), loaded and checked by the scene loader (the
sections it edits read and every rule across sections checked; the others' specs
taken from the base scene, loaded once a process), made steady at its speed and run
at the study's fidelity; its row holds the responses asked for.  Before any run the scenes of the first runs and of the runs at each key's
least and greatest value are loaded (every run's, up to :data:`CHECK_ALL_UP_TO`
runs), so a key or a value the loader refuses is an
:class:`~corliss.errors.InputError` naming it and nothing runs; a later run whose
scene the loader refuses, or that stops inside (a solver that does not converge, a
state beyond the steam properties), is a row with ``status = "failed"`` and its
error, not a stopped study.

What every run shares (:class:`StudySpec`: the base tables, the fidelity, the
responses, the varied keys) is pickled once here and unpickled once by each worker
(a local pool's), or scattered once to a Dask cluster's workers.  A task carries
only its runs' numbers and their keys' values (:func:`run_chunk`).  The local
workers are the process's kept pool (:mod:`corliss.studies.pool`): started once,
from a server process that ran the study's base scene before its first fork (the
compiled kernels and the steam table loaded), and kept for the next study; this
process runs nothing itself.  Rows come back a chunk at a time; given an output
directory they are appended to its journal (:mod:`corliss.studies.journal`) as they
come.

A study stopped by Ctrl-C or SIGTERM ends its workers at once and raises
:class:`~corliss.errors.StudyStopped` naming the rows kept; a pool's workers also
end when this process is killed outright.  ``resume=True`` reads the journal back
and runs only the rows it lacks.  A local worker that is lost (killed, out of
memory) breaks its pool: a new pool runs the unfinished chunks again (up to
:data:`corliss.studies.pool.POOL_RESTARTS` times).  On Dask, a lost worker's tasks
run again on another (Dask's own rescheduling); a cluster left with no worker for
:data:`NO_WORKERS_GRACE_S` is an error, not a wait for ever.

The same inputs give the same numbers on any worker, so a study's table does not
depend on where, in what order or in how many sittings it ran.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import os
import pickle
import signal
import threading
import time
from concurrent.futures import CancelledError
from pathlib import Path
from typing import Any

import numpy as np

from corliss.engine.balance import balance_failure
from corliss.engine.model import steady_scene
from corliss.engine.steady import run_steady
from corliss.errors import InputError, RunError, StudyStopped
from corliss.logs import at_point
from corliss.progress import progress_for
from corliss.scene.loader import Scene, find_scene, load_scene, scene_from_dict
from corliss.keys.edits import KeyValue, edited
from corliss.studies.sampling import make_design
from corliss.studies.journal import Journal, check_writable, fingerprint, journal_path, read_rows
from corliss.studies.pool import (Interrupt, SigtermRaises, prestart, run_tasks,
                                  unpickled_once)
from corliss.studies.responses import check_responses, picked, response_value
from corliss.studies.study_result import ERROR, RUN_ID, STATUS, StudyResult

log = logging.getLogger(__name__)

__all__ = ["study", "run_chunk", "StudySpec", "CHECK_ALL_UP_TO", "NO_WORKERS_GRACE_S"]

#: Studies of up to this many runs have every run's scene checked before any run
#: (a fraction of a run's cost each, in this process); a larger one has its first
#: runs and the runs at each key's least and greatest value checked, and a later
#: scene the loader refuses is a failed row (checking all would cost this process a
#: share of every run, and the workers wait for it).
CHECK_ALL_UP_TO = 32
#: Most runs in one task: few enough that the work spreads over the workers and the
#: progress moves, enough that a task's overhead is small beside its runs.
MAX_CHUNK = 50
#: Chunks per worker, at least, when the runs allow (for balance: runs differ in cost).
CHUNKS_PER_WORKER = 4
#: Seconds a Dask cluster may have no worker before the study stops with an error.
NO_WORKERS_GRACE_S = 30.0
#: Seconds between looks at a Dask cluster's workers while tasks are out.
POLL_S = 1.0


@dataclasses.dataclass(frozen=True)
class StudySpec:
    """What every run of a study shares: sent to each worker once.

    Parameters
    ----------
    token : str
        The study's fingerprint (:func:`corliss.studies.journal.fingerprint`).
    base : dict
        The base scene's tables.
    name : str
        The scene's name.
    fidelity : str or None
        The fidelity preset of every run (None: the scene's own knobs).
    responses : tuple of str
        Dotted summary keys to return.
    keys : tuple of (str, str)
        Each varied key and its unit.
    """

    token: str
    base: dict
    name: str
    fidelity: str | None
    responses: tuple
    keys: tuple


def _scene(base: dict, name: str, fidelity: str | None, changes: dict,
           token: str | None = None):
    """One run's steady scene, loaded and checked: the base's tables with the run's keys
    set; given the study's ``token``, the specs of the sections the run does not edit
    are taken from the base scene, loaded once
    (:func:`~corliss.scene.loader.scene_from_dict`'s ``like``)."""
    like = _base_scene(base, name, token) if token is not None else None
    return steady_scene(scene_from_dict(edited(base, changes), name=name, like=like),
                        fidelity)


#: Base scenes loaded (:func:`_base_scene`) by their study's fingerprint, each with its
#: tables (the very object the runs' tables share sections with); and how many.
_BASES: dict = {}
_KEEP_BASES = 4


def _base_scene(base: dict, name: str, token: str) -> Scene | None:
    """The study's base scene, loaded once a process (None when the base alone is
    refused: a study may set the key that mends it, and its runs are loaded whole).

    Kept by the study's fingerprint, a hash of the base's tables (tables changed in
    place between two studies are another study's, loaded again), and taken only for
    the same tables object, whose sections the runs' tables share."""
    got = _BASES.get(token)
    if got is not None and got[0] is base:
        return got[1]
    try:
        scene = scene_from_dict(base, name=name)
    except InputError:
        scene = None
    while len(_BASES) >= _KEEP_BASES:
        _BASES.pop(next(iter(_BASES)))
    _BASES[token] = (base, scene)
    return scene


def run_chunk(spec: StudySpec, run_ids, values) -> tuple[list, int, str | None]:
    """Run one task's runs (in a worker process, or here).

    Parameters
    ----------
    spec : StudySpec
        What the study's runs share.
    run_ids : sequence of int
        The runs' numbers in the design.
    values : ndarray
        Runs x keys: each run's values in its key's unit (a task carries numbers, not
        scenes: a million runs' scenes would not fit the client's memory).

    Returns
    -------
    rows : list of tuple
        ``(run_id, status, error, *responses)`` per run: status ``"ok"`` or
        ``"failed"``, the error's type and message (empty when none) and each
        response as a float (NaN for a failed run).
    rhs_evaluations : int
        Evaluations of the right-hand side over the chunk [-].
    property_tier : str or None
        The property tier of its runs (None when every run failed).
    """
    rows, nfev, tier = [], 0, None
    responses = spec.responses
    for run_id, vals in zip(run_ids, values):
        changes = {k: KeyValue(float(v), unit).text() for (k, unit), v in zip(spec.keys, vals)}
        try:
            with at_point(f"run {int(run_id)}: "
                          + ", ".join(f"{k} {v}" for k, v in changes.items())):
                r = run_steady(_scene(spec.base, spec.name, spec.fidelity, changes,
                                      spec.token))
                part = r.summary_with(responses)
            nfev += r.rhs_evaluations
            tier = r.property_tier
            why = run_failure(r)
            rows.append((int(run_id), "failed" if why else "ok", why,
                         *(response_value(picked(part, k)) for k in responses)))
        except Exception as exc:      # noqa: BLE001  a stopped run is a row, not a stopped study
            log.debug("run %d (%s) stopped: %s", run_id, changes, exc)
            rows.append((int(run_id), "failed", f"{type(exc).__name__}: {exc}",
                         *(math.nan for _ in responses)))
    return rows, nfev, tier


def run_failure(result) -> str:
    """Why a study's steady run is not a result, or ``""`` when it is one.

    A run that was to go until periodic and did not get there, or whose mass or
    energy balance does not close (:func:`corliss.engine.balance.balance_failure`),
    whatever its cycles: a study's row has no warning beside it, so its status says.
    Its responses are kept in the row, for a look.

    Parameters
    ----------
    result : SteadyResult
        The run.

    Returns
    -------
    str
        ``"not converged: ..."`` with the reason, or ``""``.
    """
    s = result.summary_with(FAILURE_KEYS)
    if result.scene.run.cycles is None and s.get("cycles_to_converge") is None:
        res: dict[str, float] = s.get("periodicity_residuals") or {}
        worst = max(res, key=lambda k: res[k]) if res else "work"
        return (f"not converged: not periodic after {s['cycles_simulated']} cycles (largest "
                f"residual {res.get(worst, float('nan')):.3g}, {worst})")
    why = balance_failure(s)
    return f"not converged: {why}" if why else ""


#: The summary's keys :func:`run_failure` reads.
FAILURE_KEYS = ("cycles_to_converge", "periodicity_residuals", "cycles_simulated",
                "steam_per_cycle_kg", "convergence_tolerance", "mass_balance_error",
                "energy_balance_error")


# --- a local pool's workers ----------------------------------------------------------------

#: Specs a worker keeps (the latest studies').
_KEEP_SPECS = 4


def _pool_chunk(token: str, blob: bytes, run_ids, values):
    """A pool worker's task: :func:`run_chunk` of the study whose spec, pickled, is
    ``blob`` (unpickled the first time this worker meets ``token``)."""
    spec = unpickled_once("study", token, blob, _KEEP_SPECS)
    return run_chunk(spec, run_ids, values)


def _run_local(spec, chunks, jobs, collect):
    if jobs == 1 or len(chunks) <= 1:
        for ids, vals in chunks:
            collect(ids, run_chunk(spec, ids, vals))
        return
    # the spec pickled once here, sent with each task, unpickled once a worker; the
    # forkserver runs the base scene once before its first fork (its workers start warm)
    blob = pickle.dumps(spec, protocol=pickle.HIGHEST_PROTOCOL)
    tasks = [(_pool_chunk, (spec.token, blob, ids, vals)) for ids, vals in chunks]

    def warm():
        return (_scene(spec.base, spec.name, spec.fidelity, {}),)

    run_tasks(tasks, jobs, lambda i, part: collect(chunks[i][0], part), warm=warm)


def dask_client(scheduler):
    """A Dask client for a scheduler, and whether the caller owns it.

    Parameters
    ----------
    scheduler : str or distributed.Client
        A scheduler's address (``tcp://host:8786``), or a client, which is returned
        as it is.

    Returns
    -------
    client : distributed.Client
        Connected to the scheduler.
    own : bool
        True when the client was made here (the caller must close it), False for a
        client passed in.

    Raises
    ------
    InputError
        If dask.distributed is not installed, or no scheduler answers at the address.
    """
    try:
        from distributed import Client
    except ImportError:
        raise InputError("--scheduler", scheduler, "dask.distributed installed to run on a "
                         "Dask cluster: pip install 'corliss[dask]' (or run without "
                         "--scheduler, on this machine's cores)") from None
    if isinstance(scheduler, Client):
        return scheduler, False
    if not isinstance(scheduler, str) or not scheduler.startswith("tcp://") \
            or len(scheduler) <= len("tcp://"):
        raise InputError("--scheduler", scheduler, "a Dask scheduler's address over TCP, e.g. "
                         "tcp://10.0.0.5:8786 (tls:// needs security settings and ucx:// "
                         "ucx-py, neither of which corliss sets up)")
    try:
        return Client(scheduler, timeout="10s"), True
    except (OSError, TimeoutError, ValueError, TypeError) as exc:
        raise InputError("--scheduler", scheduler, "the address of a running Dask scheduler "
                         f"(none answered: {type(exc).__name__}: {exc})") from None


def _dask_chunk(spec, run_ids, values):
    """A Dask task: :func:`run_chunk` of the scattered spec."""
    return run_chunk(spec, run_ids, values)


def _hold(spec):
    """A Dask task that gives the study's spec: its tasks depend on it, so the spec
    goes to each worker once, and is made again if every worker holding it is lost
    (data scattered to the workers would be lost with them)."""
    return spec


def _run_dask(client, spec, chunks, collect):
    import distributed
    shared = client.submit(_hold, spec, pure=False)
    futs = client.map(_dask_chunk, [shared] * len(chunks), [c[0] for c in chunks],
                      [c[1] for c in chunks], pure=False)
    ids = {f.key: c[0] for f, c in zip(futs, chunks)}
    pending = set(futs)
    alone_since = None
    try:
        while pending:
            try:
                res = distributed.wait(pending, timeout=POLL_S, return_when="FIRST_COMPLETED")
                done, pending = set(res.done), set(res.not_done)
                for fut in done:
                    collect(ids[fut.key], fut.result())
            except (TimeoutError, distributed.TimeoutError):
                done = set()
            except CancelledError as exc:      # dask.distributed's are these
                raise RunError(f"the Dask cluster at {client.scheduler.address} dropped the "
                               f"study's tasks ({type(exc).__name__}), with {len(pending)} "
                               "left: were its workers lost?") from None
            if done:
                alone_since = None
                continue
            if client.nthreads():
                alone_since = None
            elif alone_since is None:
                alone_since = time.monotonic()
            elif time.monotonic() - alone_since > NO_WORKERS_GRACE_S:
                raise RunError(f"the Dask cluster at {client.scheduler.address} has had no "
                               f"worker for {NO_WORKERS_GRACE_S:.0f} s, with {len(pending)} "
                               "task(s) left (start workers, or run without --scheduler)")
    finally:
        client.cancel(list(pending) + [shared])


# --- the study ------------------------------------------------------------------------------

def _base_of(scene) -> tuple[dict, Scene]:
    """The base scene's tables and the scene, from a Scene, tables, a file or a name."""
    if isinstance(scene, Scene):
        if scene.data is None:
            raise InputError("scene", scene.name, "a scene loaded from tables or a file (a "
                             "study changes its tables)")
        return scene.data, scene
    if isinstance(scene, dict):
        return scene, scene_from_dict(scene, name="scene")
    if scene is None or isinstance(scene, (str, Path)):
        from corliss.scene.loader import default_scene_path
        sc = load_scene(find_scene(scene) if scene is not None else default_scene_path())
        assert sc.data is not None      # a scene read from a file keeps its tables
        return sc.data, sc
    raise InputError("scene", scene, "a Scene, its tables (dict), a scene file or a bundled "
                     "scene's name")


def _check_scenes(design, base, name, fidelity, token) -> None:
    """Load the scenes of the runs most likely refused before any run: every run's in
    a small study; in a larger one the first runs' and those at each key's extremes."""
    n = design.runs
    ids: range | list[int]
    if n <= CHECK_ALL_UP_TO:
        ids = range(n)
    else:
        ext = {int(i) for j in range(design.values.shape[1])
               for i in (np.argmin(design.values[:, j]), np.argmax(design.values[:, j]))}
        ids = sorted(set(range(min(n, 4))) | ext)
    for i in ids:
        changes = design.changes(i)
        try:
            _scene(base, name, fidelity, changes, token)
        except InputError as exc:
            raise InputError(exc.key, exc.value, f"{exc.expected} (run {i} of the study "
                             "sets " + ", ".join(f"{k} = {v!r}" for k, v in changes.items())
                             + ")") from None


def _chunks(ids: np.ndarray, values: np.ndarray, size: int) -> list[tuple]:
    """``(run_ids, values)`` of each task: ``size`` runs of ``ids`` in order."""
    return [(ids[a:a + size], values[a:a + size]) for a in range(0, len(ids), size)]


def _chunk_size(n: int, workers: int, chunk_size: int | None) -> int:
    if chunk_size is not None:
        if isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 1:
            raise InputError("chunk_size", chunk_size, "a whole number of runs per task, 1 or more")
        return chunk_size
    return max(1, min(MAX_CHUNK, math.ceil(n / (workers * CHUNKS_PER_WORKER))))


def study(scene=None, vary=(), *, grid: bool = False, levels: int = 3,
          lhs: int | None = None, monte_carlo: int | None = None, seed: int | None = 0,
          responses=None, fidelity: str | None = None, jobs: int | None = None,
          scheduler=None, chunk_size: int | None = None,
          progress: Any = None,
          out=None, resume: bool = False) -> StudyResult:
    """Steady runs of ``scene`` over a design of its keys: ``corliss study``.

    Parameters
    ----------
    scene : Scene, dict, str or Path, optional
        The base scene: a loaded scene (its tables are varied), its tables, a scene
        file or a bundled scene's name (default: the bundled default scene).  A
        transient scene runs steady at its speed.
    vary : sequence of str, optional
        One option per key: ``KEY=LOW:HIGH`` (in one unit, ``valve_gear.lap=0.8:1.2in``),
        for a grid also ``KEY=a,b,c``, for the random designs also
        ``KEY=normal(MEAN,SD)UNIT`` and ``KEY=triangular(LOW,MODE,HIGH)UNIT``.
    grid : bool, optional
        Full factorial design, ``levels`` values of every ``LOW:HIGH`` key.
    levels : int, optional
        Levels of a grid's ranges [-] (ends included).
    lhs, monte_carlo : int, optional
        Runs of a Latin hypercube, or of a Monte Carlo design [-] (exactly one of
        ``grid``, ``lhs``, ``monte_carlo``).
    seed : int, optional
        Seed of the random designs (default 0).
    responses : sequence of str, optional
        Summary keys to record (dotted for nested ones, ``events.head.cutoff_frac``);
        default :data:`~corliss.studies.responses.DEFAULT_RESPONSES`.
    fidelity : str, optional
        Fidelity preset of every run (default: the scene's).
    jobs : int, optional
        Local processes (default: every core; 1 runs here, in this process).
    scheduler : str or distributed.Client, optional
        A Dask scheduler's address (``tcp://host:8786``) or client: run there instead.
    chunk_size : int, optional
        Runs per task (default: about four tasks per worker, at most
        :data:`MAX_CHUNK` runs).
    progress : None, True, ProgressBar or callable, optional
        True draws a bar (:mod:`corliss.progress`); a callable is called with (runs
        done, runs in all) as tasks finish.  Each run's messages name its run and
        settings.
    out : str or Path, optional
        The output directory: checked (made, and a file written in it) before any
        run, and the rows appended to its journal
        (``<scene>.study.partial.jsonl``) as they finish, so a stopped study keeps
        them; :meth:`StudyResult.write` into it replaces the journal.
    resume : bool, optional
        With ``out``: read the journal there back and run only the rows it lacks
        (a journal of another study is refused; none there runs them all).

    Returns
    -------
    StudyResult
        The table of the runs, a row a run (a failed run's row has its error and NaN
        responses), with the design and the base scene to rebuild any row's scene.

    Raises
    ------
    InputError
        Before any run: a bad option, an unknown response (the valid ones listed), a
        run's scene the loader refuses (its key and value named), no scheduler at the
        address, an output directory that cannot be written, a journal of another
        study to resume.
    StudyStopped
        Ctrl-C or SIGTERM during the runs: the workers are ended, the rows done kept
        in the journal (with ``out``).
    RunError
        A Dask cluster left without workers.
    """
    t0 = time.perf_counter()
    base, scene0 = _base_of(scene)
    design = make_design(vary, grid=grid, levels=levels, lhs=lhs, monte_carlo=monte_carlo,
                         seed=seed)
    name = scene0.name
    if fidelity is None and scene0.run.fidelity != scene_from_dict(base).run.fidelity:
        fidelity = scene0.run.fidelity.name         # a scene set to a preset after loading
    probe = scene0.with_fidelity(fidelity) if fidelity is not None else scene0
    responses = check_responses(responses, steady_scene(probe))
    columns = design.columns
    clash = set(columns) & (set(responses) | {RUN_ID, STATUS, ERROR})
    if clash:
        raise InputError("--response", sorted(clash)[0], "a response other than a varied "
                         "key's column")
    if scheduler is not None and jobs is not None:
        raise InputError("--jobs", jobs, "no --jobs with --scheduler: the cluster's workers "
                         "run the study")
    if resume and out is None:
        raise InputError("--resume", True, "an output directory (--out) whose partial file "
                         "to resume")
    if scheduler is None:
        workers = jobs if jobs is not None else (os.cpu_count() or 1)
        if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
            raise InputError("--jobs", jobs, "a whole number of processes, 1 or more")
    if scheduler is None and design.runs > 1:
        # the workers' forkserver loads (the base scene's run) while the scenes are checked
        prestart(workers, lambda: (_scene(base, name, fidelity, {}),), (__name__,))
    token = fingerprint(base, name, fidelity, responses, design)
    _check_scenes(design, base, name, fidelity, token)
    rows: dict[int, tuple] = {}
    journal = None
    client, own, address = None, False, None
    if scheduler is not None:           # a scheduler that does not answer: before any file
        client, own = dask_client(scheduler)
    if out is not None:
        try:
            jpath = journal_path(check_writable(out), name)
            if resume and jpath.exists():
                rows = read_rows(jpath, token, 3 + len(responses))
                log.info("resuming: %d of %d runs read back from %s", len(rows),
                         design.runs, jpath)
            elif resume:
                log.info("nothing to resume in %s: every run is made", jpath.parent)
            journal = Journal(jpath, {"fingerprint": token, "scene": name,
                                      "design": design.kind, "seed": design.seed,
                                      "runs": design.runs,
                                      "columns": [RUN_ID, STATUS, ERROR, *responses]},
                              keep=resume)
        except BaseException:
            if own and client is not None:
                client.close()
            raise
    todo = np.array([i for i in range(design.runs) if i not in rows], dtype=np.int64)
    spec = StudySpec(token, base, name, fidelity, tuple(responses),
                     tuple((s.key, s.unit) for s in design.specs))
    nfev, tiers = [0], []

    def collect(ids, part):
        got, n, tier = part
        if journal is not None:
            journal.append(got)
        for r in got:
            rows[r[0]] = r
        nfev[0] += n
        if tier is not None:
            tiers.append(tier)
        if bar[0]:
            bar[0](len(rows), design.runs)

    bar: list = [None]
    try:
        if client is not None:
            address = str(client.scheduler.address)
            workers = max(1, sum(client.nthreads().values()))
        else:
            workers = max(1, min(workers, len(todo)))
        chunks = _chunks(todo, design.values[todo], _chunk_size(len(todo), workers, chunk_size))
        with SigtermRaises(), progress_for(progress, "runs") as bar[0]:
            try:
                if not chunks:
                    pass
                elif client is not None:
                    _run_dask(client, spec, chunks, collect)
                else:
                    _run_local(spec, chunks, workers, collect)
            except (KeyboardInterrupt, Interrupt) as exc:
                why = "Ctrl-C" if isinstance(exc, KeyboardInterrupt) else "SIGTERM"
                kept = (f"kept in {journal.path}; the same command with --resume finishes it"
                        if journal is not None else "not kept (give an output directory to "
                        "keep them)")
                raise StudyStopped(f"the study stopped ({why}) after {len(rows)} of "
                                   f"{design.runs} runs: their rows are {kept}",
                                   done=len(rows), runs=design.runs,
                                   journal=None if journal is None else journal.path,
                                   signal_name=why) from None
    except BaseException:
        if journal is not None and not rows:
            journal.remove()            # nothing done: no partial file
        raise
    finally:
        if journal is not None:
            journal.close()
        if own and client is not None:
            client.close()
    ordered = [rows[i] for i in range(design.runs)]
    tier = tiers[0] if tiers else probe.run.fidelity.properties
    import pandas as pd     # a study's table; not imported by the package (a run needs none)
    got = pd.DataFrame(ordered, columns=[RUN_ID, STATUS, ERROR, *responses])
    table = pd.concat([got[[RUN_ID]],
                       pd.DataFrame(design.values, columns=columns),
                       got[list(responses)], got[[STATUS, ERROR]]], axis=1)
    table[RUN_ID] = table[RUN_ID].astype("int64")
    failed = int((table[STATUS] != "ok").sum())
    if failed:
        log.warning("%d of %d runs stopped (status 'failed', the reason in 'error')",
                    failed, design.runs)
    return StudyResult(scene=scene0, property_tier=tier, timeseries=table, cycles=table,
                       rhs_evaluations=nfev[0], wall_time_s=time.perf_counter() - t0,
                       design=design.kind, varied=design.describe(),
                       responses=list(responses), seed=design.seed, base_data=base,
                       fidelity=fidelity or scene_from_dict(base).run.fidelity.name,
                       runs=design.runs, failed=failed, workers=workers,
                       scheduler=address,
                       journal=None if journal is None else str(journal.path))
