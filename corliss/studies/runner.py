"""A study: steady runs of one scene over a design of its keys, on local processes or a
Dask cluster.

Each run is the base scene's tables with the run's keys set
(:func:`corliss.keys.edits.with_keys`), loaded and checked by the scene loader, made
steady at its speed and run at the study's fidelity; its row holds the responses
asked for.  Every run's scene is checked before any run (up to
:data:`CHECK_ALL_UP_TO` runs), so a key or a value the loader refuses is an
:class:`~corliss.errors.InputError` naming it and nothing runs; a run that stops
inside (a solver that does not converge, a state beyond the steam properties) is a
row with ``status = "failed"`` and its error, not a stopped study.

Runs go in chunks (:func:`run_chunk`, one task: the base tables once and each run's
values of the varied keys) to a local process pool on every core, or, given a scheduler's address,
to a Dask cluster (:mod:`dask.distributed`, the optional extra ``corliss[dask]``).  A
worker process imports corliss once, loads the compiled kernels from numba's cache
and the steam table from its file once, and keeps them for every later task; the
same inputs give the same numbers on any worker, so a study's table does not depend
on where it ran.
"""

from __future__ import annotations

import logging
import math
import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any

import numpy as np

from corliss.engine.balance import balance_failure
from corliss.engine.model import steady_scene
from corliss.engine.steady import run_steady
from corliss.logs import at_point
from corliss.progress import progress_for
from corliss.errors import InputError
from corliss.scene.loader import Scene, find_scene, load_scene, scene_from_dict
from corliss.keys.edits import KeyValue, with_keys
from corliss.studies.sampling import make_design
from corliss.studies.responses import check_responses, flatten, response_value
from corliss.studies.study_result import ERROR, RUN_ID, STATUS, StudyResult

log = logging.getLogger(__name__)

__all__ = ["study", "run_chunk", "CHECK_ALL_UP_TO"]

#: Studies of up to this many runs have every run's scene checked before any run
#: (0.5 ms each); a larger one has these first runs and the runs at each key's least
#: and greatest value checked, and a later scene the loader refuses is a failed row.
CHECK_ALL_UP_TO = 20_000
#: Most runs in one task: few enough that the work spreads over the workers and the
#: progress moves, enough that a task's overhead is small beside its runs.
MAX_CHUNK = 50
#: Chunks per worker, at least, when the runs allow (for balance: runs differ in cost).
CHUNKS_PER_WORKER = 4


def _scene(base: dict, name: str, fidelity: str | None, changes: dict):
    """One run's steady scene, loaded and checked."""
    sc = scene_from_dict(with_keys(base, changes), name=name)
    if fidelity is not None:
        sc = sc.with_fidelity(fidelity)
    return steady_scene(sc)


def run_chunk(base: dict, name: str, fidelity: str | None, responses: tuple,
              keys: tuple, run_ids, values) -> tuple[list, int, str | None]:
    """Run one task's runs (in a worker process, or here).

    Parameters
    ----------
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
    for run_id, vals in zip(run_ids, values):
        changes = {k: KeyValue(float(v), unit).text() for (k, unit), v in zip(keys, vals)}
        try:
            with at_point(f"run {int(run_id)}: " + ", ".join(f"{k} {v}" for k, v in changes.items())):
                r = run_steady(_scene(base, name, fidelity, changes))
                flat = flatten(r.summary)
            nfev += r.rhs_evaluations
            tier = r.property_tier
            why = run_failure(r)
            rows.append((int(run_id), "failed" if why else "ok", why,
                         *(response_value(flat.get(k)) for k in responses)))
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
    s = result.summary
    if result.scene.run.cycles is None and s.get("cycles_to_converge") is None:
        res = s.get("periodicity_residuals") or {}
        worst = max(res, key=res.get) if res else "work"
        return (f"not converged: not periodic after {s['cycles_simulated']} cycles (largest "
                f"residual {res.get(worst, float('nan')):.3g}, {worst})")
    why = balance_failure(s)
    return f"not converged: {why}" if why else ""


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
        return sc.data, sc
    raise InputError("scene", scene, "a Scene, its tables (dict), a scene file or a bundled "
                     "scene's name")


def _check_scenes(design, base, name, fidelity) -> None:
    """Load every run's scene (or, for a large study, a sample) before any run."""
    n = design.runs
    if n <= CHECK_ALL_UP_TO:
        ids = range(n)
    else:
        ext = {int(i) for j in range(design.values.shape[1])
               for i in (np.argmin(design.values[:, j]), np.argmax(design.values[:, j]))}
        ids = sorted(set(range(CHECK_ALL_UP_TO)) | ext)
    for i in ids:
        changes = design.changes(i)
        try:
            _scene(base, name, fidelity, changes)
        except InputError as exc:
            raise InputError(exc.key, exc.value, f"{exc.expected} (run {i} of the study "
                             "sets " + ", ".join(f"{k} = {v!r}" for k, v in changes.items())
                             + ")") from None


def _chunks(design, size: int) -> list[tuple]:
    """``(run_ids, values)`` of each task: ``size`` consecutive runs."""
    return [(range(a, min(a + size, design.runs)), design.values[a:a + size])
            for a in range(0, design.runs, size)]


def _chunk_size(n: int, workers: int, chunk_size: int | None) -> int:
    if chunk_size is not None:
        if isinstance(chunk_size, bool) or not isinstance(chunk_size, int) or chunk_size < 1:
            raise InputError("chunk_size", chunk_size, "a whole number of runs per task, 1 or more")
        return chunk_size
    return max(1, min(MAX_CHUNK, math.ceil(n / (workers * CHUNKS_PER_WORKER))))


def _run_local(args, chunks, jobs, progress, total):
    out = [None] * len(chunks)
    done = 0
    if jobs == 1:
        for i, c in enumerate(chunks):
            out[i] = run_chunk(*args, *c)
            done += len(c[0])
            if progress:
                progress(done, total)
        return out
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        futs = {pool.submit(run_chunk, *args, *c): i for i, c in enumerate(chunks)}
        for fut in as_completed(futs):
            i = futs[fut]
            out[i] = fut.result()
            done += len(chunks[i][0])
            if progress:
                progress(done, total)
    return out


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


def _run_dask(client, args, chunks, progress, total):
    from distributed import as_completed as dask_completed
    n = len(chunks)
    futs = client.map(run_chunk, *([a] * n for a in args), [c[0] for c in chunks],
                      [c[1] for c in chunks], pure=False)
    index = {f.key: i for i, f in enumerate(futs)}
    out = [None] * len(chunks)
    done = 0
    for fut in dask_completed(futs):
        i = index[fut.key]
        out[i] = fut.result()
        done += len(chunks[i][0])
        if progress:
            progress(done, total)
    return out


def study(scene=None, vary=(), *, grid: bool = False, levels: int = 3,
          lhs: int | None = None, monte_carlo: int | None = None, seed: int | None = 0,
          responses=None, fidelity: str | None = None, jobs: int | None = None,
          scheduler=None, chunk_size: int | None = None,
          progress: Any = None) -> StudyResult:
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
        address.
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
    _check_scenes(design, base, name, fidelity)
    client, own = (dask_client(scheduler) if scheduler is not None else (None, False))
    try:
        if client is not None:
            address = str(client.scheduler.address)
            workers = max(1, sum(client.nthreads().values()))
        else:
            workers = jobs if jobs is not None else (os.cpu_count() or 1)
            if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
                raise InputError("--jobs", jobs, "a whole number of processes, 1 or more")
            workers = min(workers, design.runs)
        chunks = _chunks(design, _chunk_size(design.runs, workers, chunk_size))
        args = (base, name, fidelity, responses,
                tuple((spec.key, spec.unit) for spec in design.specs))
        with progress_for(progress, "runs") as bar:
            if client is not None:
                parts = _run_dask(client, args, chunks, bar, design.runs)
            else:
                parts = _run_local(args, chunks, workers, bar, design.runs)
    finally:
        if own:
            client.close()
    rows = [row for rws, _, _ in parts for row in rws]
    nfev = sum(p[1] for p in parts)
    tier = next((p[2] for p in parts if p[2] is not None), probe.run.fidelity.properties)
    import pandas as pd     # a study's table; not imported by the package (a run needs none)
    got = pd.DataFrame(rows, columns=[RUN_ID, STATUS, ERROR, *responses])
    table = pd.concat([got[[RUN_ID]],
                       pd.DataFrame(design.values, columns=columns),
                       got[list(responses)], got[[STATUS, ERROR]]], axis=1)
    table[RUN_ID] = table[RUN_ID].astype("int64")
    failed = int((table[STATUS] != "ok").sum())
    if failed:
        log.warning("%d of %d runs stopped (status 'failed', the reason in 'error')",
                    failed, design.runs)
    return StudyResult(scene=scene0, property_tier=tier, timeseries=table, cycles=table,
                       rhs_evaluations=nfev, wall_time_s=time.perf_counter() - t0,
                       design=design.kind, varied=design.describe(),
                       responses=list(responses), seed=design.seed, base_data=base,
                       fidelity=fidelity or scene_from_dict(base).run.fidelity.name,
                       runs=design.runs, failed=failed, workers=workers,
                       scheduler=None if client is None else address)
