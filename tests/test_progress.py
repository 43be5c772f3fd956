"""Progress through tqdm: a bar a script or notebook asks for with ``progress=True``,
the command line's bar on a terminal only, and the runs' messages written above the
bar, each naming the point of the study it came from."""

from __future__ import annotations

import logging
import re
import tomllib
from pathlib import Path

import pytest

import corliss
from corliss.progress import ProgressBar, progress_for
from corliss.studies.load_range import load_range

SCENE = Path(__file__).resolve().parents[1] / "scenes" / "corliss-trip-gear.toml"


class _Terminal:
    """A stream that says it is a terminal (or not), keeping what was written."""

    def __init__(self, tty=True):
        self.text, self.tty = "", tty

    def isatty(self):
        return self.tty

    def write(self, s):
        self.text += s

    def flush(self):
        pass


def _bare_logger(monkeypatch):
    """The ``corliss`` logger as a script finds it: no handler of its own (a command
    line test earlier in the process may have set some, and the test runner adds its
    capture once the test has begun, hence called in the test's body)."""
    log = logging.getLogger("corliss")
    monkeypatch.setattr(log, "handlers", [])
    monkeypatch.setattr(log, "propagate", False)
    monkeypatch.setattr(log, "level", logging.WARNING)


def test_a_warning_during_a_sweep_names_its_point_and_is_written_above_the_bar(monkeypatch):
    """Three settings of the Corliss engine, each let run only two cycles, so each run
    warns that it is not periodic.  On a terminal the bar is drawn, and each warning
    is a line of its own (after the bar's last carriage return on that line nothing
    of the bar is left before it), naming the setting it came from."""
    d = tomllib.loads(SCENE.read_text())
    d["run"].update(max_cycles=2, fidelity="fast")
    scene = corliss.scene_from_dict(d, "progress")
    term = _Terminal()
    settings = [0.3, 0.5, 0.7]
    _bare_logger(monkeypatch)
    load_range(scene, "setting", settings, progress=ProgressBar("runs", file=term))
    assert re.search(r"\d/3", term.text), term.text          # the bar was drawn
    warned = [ln.split("\r")[-1] for ln in term.text.split("\n") if "not periodic" in ln]
    assert len(warned) == len(settings), term.text
    for line, v in zip(warned, settings):
        assert line.startswith(f"corliss: [setting {v:g}] not periodic after 2 cycles"), line


def test_the_command_lines_bar_is_drawn_on_a_terminal_and_not_into_a_log():
    """``disable=None`` (the command line's choice): a terminal gets the bar, a pipe
    or a log file nothing; a steady run's bar shows the cycle and the change of work,
    with no time to go (its total is unknown until it is periodic)."""
    term, piped = _Terminal(), _Terminal(tty=False)
    with progress_for(ProgressBar("runs", disable=None, file=term), "runs") as bar:
        bar(1, 4)
    with progress_for(ProgressBar("runs", disable=None, file=piped), "runs") as bar:
        bar(1, 4)
    assert "1/4" in term.text and piped.text == ""
    steady = _Terminal()
    with progress_for(ProgressBar("cycles", file=steady, tolerance=1e-6), "cycles") as bar:
        bar(3, 2e-4)
    assert "work changed 2.00e-04" in steady.text and "periodic at 1e-06" in steady.text


def test_progress_refuses_what_is_no_progress():
    with pytest.raises(TypeError, match="progress=3"):
        with progress_for(3, "runs"):
            pass
