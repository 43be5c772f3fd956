"""Worker processes kept for this process's studies, compares and fits.

A study, a compare or a fit on more than one process runs its tasks here
(:func:`run_tasks`).  The workers are started once and kept: a second study in the
same process (``compare`` runs several rounds, a notebook many studies) finds them
started, warm, and sends them only its tasks.  A pool of another size replaces the
kept one.

Where the platform has it, a worker is not a fork of this process but of a small
server process (multiprocessing's *forkserver*) that imported the kernels' modules
and, before its first fork, ran the first caller's scene once
(:mod:`corliss.studies.zygote`: the compiled kernels and the steam table loaded): so
starting a worker costs this process a message, not a copy of its whole memory (the
table of a study, pandas and its pyarrow), and a worker starts with what a run needs
and nothing else.  Elsewhere the workers are forks of this process (or spawned).

A worker ignores Ctrl-C (the caller ends it), takes SIGTERM's default, and dies with
the process that started it however that one ends (Linux's ``PR_SET_PDEATHSIG``, and
a thread watching its parent): the forkserver ends when this process does, and its
workers with it.  Ctrl-C or SIGTERM in the caller (raised as
:class:`KeyboardInterrupt` or :class:`Interrupt`) ends the workers at once
(SIGKILL: their tasks are abandoned) and drops the pool; a worker that is lost
(killed, out of memory) breaks its pool: the tasks it left unfinished run again on a
new pool, up to :data:`POOL_RESTARTS` times.

A task is a function of the package and its arguments: the same inputs give the same
numbers in any worker, so where a task ran never shows in its result.
"""

from __future__ import annotations

import atexit
import contextlib
import ctypes
import logging
import multiprocessing
import os
import pickle
import signal
import sys
import tempfile
import threading
import time
import types
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Any, Callable, Sequence

from corliss.errors import RunError

_mp_forkserver: Any
try:
    from multiprocessing import forkserver as _mp_forkserver
except ImportError:             # a platform without it: forks or spawns
    _mp_forkserver = None

log = logging.getLogger(__name__)

__all__ = ["Interrupt", "POOL_RESTARTS", "WARM_ENV", "SigtermRaises", "close", "prestart",
           "run_tasks", "start_method", "unpickled_once", "worker_pids"]

#: Times a pool is started again when one of its workers is lost (killed, out of
#: memory), its unfinished tasks resent, before the caller gets an error.
POOL_RESTARTS = 2
#: The environment variable that names, to the forkserver as it starts, the file of
#: the scenes it runs once before its first fork (:mod:`corliss.studies.zygote`).
WARM_ENV = "CORLISS_POOL_WARM"
#: The module the forkserver imports before its first fork.
ZYGOTE = "corliss.studies.zygote"
#: The signals that stop a caller's tasks.
_STOPS = {signal.SIGINT, signal.SIGTERM}
#: prctl's option that sends the child a signal when its parent dies (Linux).
_PR_SET_PDEATHSIG = 1

#: The pool kept for this process (None until a caller needs one).
_POOL: ProcessPoolExecutor | None = None
#: Its number of workers.
_POOL_JOBS = 0
#: Whether this process's forkserver was started (by a pool here).
_SERVER_STARTED = False
#: The forkserver's warm-up file, until its first fork.
_WARM_PATH: str | None = None


class Interrupt(BaseException):
    """SIGTERM, raised in the main thread as Ctrl-C raises :class:`KeyboardInterrupt`."""


def _on_sigterm(signum, frame):
    raise Interrupt()


class SigtermRaises:
    """While in it (in the main thread): SIGTERM raises :class:`Interrupt`, so a caller's
    tasks stop as on Ctrl-C (the workers ended, the caller's ``finally`` run)."""

    def __enter__(self):
        self.old = None
        if threading.current_thread() is threading.main_thread():
            self.old = signal.signal(signal.SIGTERM, _on_sigterm)
        return self

    def __exit__(self, *exc):
        if self.old is not None:
            signal.signal(signal.SIGTERM, self.old)
        return False


#: In a worker: what its tasks were sent pickled, by the name the sender gave it
#: (:func:`unpickled_once`), per kind of thing.
_RECEIVED: dict[str, dict] = {}


def unpickled_once(kind: str, token: str, blob: bytes, keep: int):
    """In a pool's worker: a thing sent pickled with each task (a study's spec, a fit's
    problem), unpickled the first time this worker meets its ``token`` and kept for the
    next tasks, at most ``keep`` of a kind (the oldest dropped first).

    Parameters
    ----------
    kind : str
        What it is (``"study"``, ``"fit"``): each kind keeps its own.
    token : str
        The name the sender gave it (a hash of ``blob``).
    blob : bytes
        It, pickled.
    keep : int
        How many of this kind a worker keeps.

    Returns
    -------
    object
        It, unpickled (the same object for every task of this worker with ``token``).
    """
    kept = _RECEIVED.setdefault(kind, {})
    thing = kept.get(token)
    if thing is None:
        thing = pickle.loads(blob)
        while len(kept) >= keep:
            kept.pop(next(iter(kept)))
        kept[token] = thing
    return thing


def start_method() -> str:
    """How this platform's workers start: ``"forkserver"``, ``"fork"`` or ``"spawn"``.

    Returns
    -------
    str
        The :mod:`multiprocessing` start method of the pool's workers.
    """
    methods = multiprocessing.get_all_start_methods()
    for m in ("forkserver", "fork"):
        if m in methods:
            return m
    return "spawn"


def _context():
    method = start_method()
    ctx = multiprocessing.get_context(method)
    if method == "forkserver":
        # multiprocessing keeps one forkserver a process: the list is read when it starts
        ctx.set_forkserver_preload([ZYGOTE])
    return ctx


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True
    return True


def _watch_parent(parent_pid: int, caller_pid: int) -> None:
    """End this worker when the process that forked it, or the caller, is gone."""
    while True:
        if os.getppid() != parent_pid or not _alive(caller_pid):
            os._exit(1)
        time.sleep(0.5)


def _let_the_server_go() -> None:
    """Close this worker's copy of the forkserver's lifeline.

    The forkserver runs until every holder of the write end of its "alive" pipe has
    closed it, and multiprocessing hands a copy to each of its children, so that they
    could start processes of their own: a worker would keep the server (and itself,
    through ``PR_SET_PDEATHSIG``) alive after its caller was killed.  The workers start
    no process, so the caller holds the only copy and the server ends with it.
    """
    try:
        server: Any = _mp_forkserver._forkserver
        fd = server._forkserver_alive_fd
    except AttributeError:
        return
    if fd is not None:
        with contextlib.suppress(OSError):
            os.close(fd)
        server._forkserver_alive_fd = None


def _init_worker(caller_pid: int) -> None:
    """Start a pool worker: leave Ctrl-C to the caller (which ends the workers itself);
    die with the process that forked it (the forkserver, or the caller) and with the
    caller, however they end."""
    parent_pid = os.getppid()
    if parent_pid != caller_pid:
        _let_the_server_go()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, _STOPS)
    if sys.platform.startswith("linux"):
        try:
            ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent_pid:          # the parent died before the line above
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent_pid, caller_pid), daemon=True,
                     name="corliss-parent-watch").start()


@contextlib.contextmanager
def _main_hidden():
    """While workers start: no ``__main__`` to import in them.

    A spawned or forkserver worker imports the caller's main script first, as
    multiprocessing's spawn does; the tasks here are the package's functions and need
    none of it, and a script without an ``if __name__ == "__main__"`` guard would
    start its study again inside each worker.
    """
    if start_method() == "fork":
        yield
        return
    main = sys.modules.get("__main__")
    sys.modules["__main__"] = types.ModuleType("__main__")
    try:
        yield
    finally:
        if main is not None:
            sys.modules["__main__"] = main


def prestart(jobs: int, warm: Callable[[], Sequence] | None = None,
             modules: Sequence[str] = ()) -> None:
    """Start this process's forkserver now, so that it loads while the caller checks its
    inputs (its first workers wait for it), when ``jobs`` > 1 and none is started.

    Parameters
    ----------
    jobs : int
        The caller's processes [-] (1: nothing is started).
    warm : callable, optional
        Returns the steady scenes the forkserver runs once before its first fork (its
        workers then start with their kernels and steam table loaded).
    modules : sequence of str, optional
        Modules of the package the forkserver imports before its first fork (those of
        the caller's task functions).
    """
    global _SERVER_STARTED, _WARM_PATH
    if jobs <= 1 or _SERVER_STARTED or start_method() != "forkserver":
        return
    _SERVER_STARTED = True
    _context()
    try:
        scenes = tuple(warm()) if warm is not None else ()
    except Exception as exc:        # noqa: BLE001  a cold start, not a stopped caller
        log.debug("no warm-up for the workers: %s", exc)
        scenes = ()
    fd, path = tempfile.mkstemp(prefix="corliss-warm-", suffix=".pickle")
    old = os.environ.get(WARM_ENV)
    try:
        with os.fdopen(fd, "wb") as f:
            pickle.dump((tuple(modules), scenes), f, protocol=pickle.HIGHEST_PROTOCOL)
        _WARM_PATH = path
        os.environ[WARM_ENV] = path
        _mp_forkserver.ensure_running()
    except BaseException:
        _forget_warm_file()
        raise
    finally:
        if old is None:
            os.environ.pop(WARM_ENV, None)
        else:
            os.environ[WARM_ENV] = old


def _forget_warm_file() -> None:
    """Remove the forkserver's warm-up file (once it has forked: it has read it)."""
    global _WARM_PATH
    path, _WARM_PATH = _WARM_PATH, None
    if path is not None:
        with contextlib.suppress(OSError):
            os.unlink(path)


def _pool(jobs: int) -> ProcessPoolExecutor:
    """The kept pool, with ``jobs`` workers (a pool of another size is replaced)."""
    global _POOL, _POOL_JOBS
    if _POOL is not None and _POOL_JOBS != jobs:
        close()
    if _POOL is None:
        _POOL = ProcessPoolExecutor(max_workers=jobs, mp_context=_context(),
                                    initializer=_init_worker, initargs=(os.getpid(),))
        _POOL_JOBS = jobs
    return _POOL


def worker_pids() -> list[int]:
    """The process ids of the kept pool's workers (none when no pool is kept).

    Returns
    -------
    list of int
        The workers' pids.
    """
    procs = (getattr(_POOL, "_processes", None) or {}) if _POOL is not None else {}
    return sorted(procs)


def _kill(pool: ProcessPoolExecutor) -> None:
    """End a pool's workers now (SIGKILL: their tasks are abandoned, not finished)."""
    procs = list((getattr(pool, "_processes", None) or {}).values())
    for p in procs:
        try:
            p.kill()
        except (OSError, ValueError, AttributeError):
            pass
    pool.shutdown(wait=True, cancel_futures=True)
    for p in procs:
        with contextlib.suppress(Exception):
            p.join(timeout=5)


def close(kill: bool = False) -> None:
    """End the kept pool's workers (at the caller's exit, or to free their memory).

    Parameters
    ----------
    kill : bool, optional
        End them at once (SIGKILL) instead of letting their tasks finish.
    """
    global _POOL, _POOL_JOBS
    pool, _POOL, _POOL_JOBS = _POOL, None, 0
    if pool is None:
        return
    if kill:
        _kill(pool)
    else:
        pool.shutdown(wait=True)


atexit.register(_forget_warm_file)
atexit.register(close)


def run_tasks(tasks: Sequence[tuple[Callable, tuple]], jobs: int,
              collect: Callable[[int, Any], None], *,
              warm: Callable[[], Sequence] | None = None) -> None:
    """Run ``tasks`` on the kept pool of ``jobs`` workers, ``collect(i, result)`` called
    here as each task ``i`` finishes.

    Parameters
    ----------
    tasks : sequence of (callable, tuple)
        Each task's function (a module-level function of the package) and arguments.
    jobs : int
        Worker processes [-].
    collect : callable
        Called in this process with each task's index and result, in the order they
        finish.
    warm : callable, optional
        Returns the steady scenes the forkserver runs once before its first fork, when
        this call starts it (its workers then start with their kernels and steam table
        loaded); not called otherwise.

    Raises
    ------
    KeyboardInterrupt, Interrupt
        Ctrl-C or SIGTERM (the caller's :class:`Interrupt`): the workers are ended at
        once and the pool dropped.
    RunError
        The workers were lost :data:`POOL_RESTARTS` + 1 times.
    Exception
        A task's own exception, as it raised it (the pool is kept).
    """
    left = list(range(len(tasks)))
    for _ in range(POOL_RESTARTS + 1):
        left = _pass(tasks, left, jobs, collect, warm)
        if not left:
            return
        log.warning("a worker process was lost: %d task(s) run again on a new pool", len(left))
    raise RunError(f"the worker processes were lost {POOL_RESTARTS + 1} times, with "
                   f"{len(left)} task(s) left (out of memory? a run that crashes its "
                   "process?); run it with --jobs 1 to see")


def _pass(tasks, todo: list[int], jobs: int, collect, warm) -> list[int]:
    """Run the tasks ``todo`` on the kept pool; those left when a worker was lost."""
    # Ctrl-C and SIGTERM wait while the workers start (a signal in the middle of a fork
    # is lost in its handlers), and are taken at once after
    masked = hasattr(signal, "pthread_sigmask")
    old: set = signal.pthread_sigmask(signal.SIG_BLOCK, _STOPS) if masked else set()
    pool = None
    futs: dict = {}
    try:
        pool = _pool(jobs)
        prestart(jobs, warm, sorted({fn.__module__ for fn, _ in tasks}))
        try:
            with _main_hidden():
                futs = {pool.submit(tasks[i][0], *tasks[i][1]): i for i in todo}
        finally:
            _forget_warm_file()
        if masked:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)
            masked = False
        pending, lost = set(futs), set[Any]()
        while pending and not lost:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                exc = fut.exception()
                if isinstance(exc, BrokenProcessPool):
                    lost.add(fut)
                elif exc is not None:
                    raise exc
                else:
                    collect(futs[fut], fut.result())
        if lost:
            close(kill=True)
            return sorted(futs[f] for f in futs if f in lost or f in pending)
    except BrokenProcessPool:
        close(kill=True)            # broken as the tasks were sent: all of them again
        return [futs[f] for f in futs if not f.done()] or list(todo)
    except BaseException as exc:
        if pool is not None and not isinstance(exc, Exception):
            close(kill=True)        # stopped: the workers end now, their tasks abandoned
        else:
            for f in futs:
                f.cancel()
        raise
    finally:
        if masked:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)
    return []
