"""The command line's heartbeat: while a slow step that happens once on a machine is
under way, a line says what it is and how long it has taken, so that the first run on
a new machine (a minute or two of compiling and building) is never silent for long.

A step is open from a notice (:data:`corliss.logs.NOTICE`: "building the steam table
once for this machine...") until the next record of the ``corliss`` logger, and while
numba compiles a function (its ``numba:compile`` events: only a function missing from
the disk cache is compiled; one loaded from it sends none).  A compile's end closes the
notice before it too (the notice of the kernels' compile is logged just before it).

On a terminal the line is rewritten in place every second; elsewhere (a log, a pipe) a
line is written every :data:`EVERY_S` seconds.  Nothing is written for a step shorter
than :data:`AFTER_S`.
"""

from __future__ import annotations

import logging
import threading
import time

from numba.core import event

from corliss.logs import NOTICE

#: A step is reported once it has taken this long [s] ...
AFTER_S = 3.0
#: ... and then every this many seconds off a terminal [s].
EVERY_S = 10.0


class Heartbeat(logging.Handler):
    """Watches the ``corliss`` logger's records and numba's compiles, and reports slow steps.

    A logging handler (add it to the ``corliss`` logger, then :meth:`start` it); the
    reports are written from a daemon thread.

    Parameters
    ----------
    stream_of : callable
        Called with no arguments for the stream to write to, as it is at that moment
        (``lambda: sys.stderr``, so a stream swapped later is followed).
    prefix : str, optional
        Put before every line written.
    """

    def __init__(self, stream_of, prefix: str = "corliss: "):
        super().__init__(logging.DEBUG)
        self._stream_of = stream_of          # a function: sys.stderr as it is now
        self._prefix = prefix
        self._lock = threading.Lock()
        self._notice: tuple[str, float] | None = None
        self._compile: tuple[str, float] | None = None
        self._depth = 0
        self._last_line = 0.0
        self._shown = False
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._listener: _CompileListener | None = None

    # --- what is going on --------------------------------------------------------------
    def emit(self, record: logging.LogRecord) -> None:
        with self._lock:
            self._end_line()
            if record.levelno == NOTICE:
                text = record.getMessage().split(" once for this machine")[0].split(";")[0]
                self._notice = (text, time.monotonic())
            else:
                self._notice = None

    def compile_started(self, name: str) -> None:
        """Open a compile step (numba's ``numba:compile`` start event).

        Nested compiles count as one step, named after the outermost.

        Parameters
        ----------
        name : str
            The compiled function's name, for the report.
        """
        with self._lock:
            self._depth += 1
            if self._depth == 1:
                self._compile = (name, time.monotonic())

    def compile_ended(self) -> None:
        """Close a compile step; the outermost's end also closes a notice logged before it."""
        with self._lock:
            self._depth = max(self._depth - 1, 0)
            if self._depth == 0 and self._compile is not None:
                started = self._compile[1]
                self._compile = None
                if self._notice is not None and self._notice[1] <= started:
                    self._notice = None
                self._end_line()

    # --- the thread ---------------------------------------------------------------------
    def start(self) -> "Heartbeat":
        """Listen to numba's compiles and start reporting.

        Returns
        -------
        Heartbeat
            This handler, started.
        """
        self._listener = _CompileListener(self)
        event.register("numba:compile", self._listener)
        self._thread = threading.Thread(target=self._run, name="corliss-heartbeat",
                                        daemon=True)
        self._thread.start()
        return self

    def stop(self) -> None:
        """Stop reporting and listening."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        if self._listener is not None:
            event.unregister("numba:compile", self._listener)
            self._listener = None
        with self._lock:
            self._end_line()

    def _run(self) -> None:
        while not self._stop.wait(1.0):
            with self._lock:
                self._beat()

    def _beat(self) -> None:
        now = time.monotonic()
        if self._compile is not None:
            what, since = f"compiling {self._compile[0]} (once for this machine)", self._compile[1]
        elif self._notice is not None:
            what, since = self._notice
        else:
            return
        age = now - since
        if age < AFTER_S:
            return
        stream = self._stream_of()
        tty = getattr(stream, "isatty", lambda: False)()
        if not tty and now - self._last_line < EVERY_S:
            return
        text = f"{self._prefix}still {what}: {age:.0f} s"
        try:
            if tty:
                stream.write("\r" + text + "   ")
                self._shown = True
            else:
                stream.write(text + "\n")
            stream.flush()
        except (OSError, ValueError):      # a closed stream: nothing to report to
            return
        self._last_line = now

    def _end_line(self) -> None:
        """Finish a line rewritten in place, before anything else is written."""
        if self._shown:
            try:
                stream = self._stream_of()
                stream.write("\n")
                stream.flush()
            except (OSError, ValueError):
                pass
            self._shown = False


class _CompileListener(event.Listener):
    """numba's ``numba:compile`` events, passed on to a :class:`Heartbeat`."""

    def __init__(self, beat: Heartbeat):
        self.beat = beat

    def on_start(self, ev):
        d = (ev.data or {}).get("dispatcher")
        self.beat.compile_started(getattr(getattr(d, "py_func", d), "__name__", "a kernel"))

    def on_end(self, ev):
        self.beat.compile_ended()
