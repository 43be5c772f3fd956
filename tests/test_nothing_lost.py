"""Nothing lost, nothing written where it should not be, no garbage called a result.

Each test reproduces a defect found by attacking the command line with bad input,
faults and load, and shows it gone:

- a meta file's ``scene_name`` wrote outside ``--out`` (an absolute stem, ``..``) and
  followed a symlink there; ``--from-meta`` ran edited text or edited tables under
  the recorded hash, dropped an unknown effect, and gave tracebacks for malformed
  fields;
- SIGINT at a rename of the commit deleted the earlier run's file; SIGKILL there
  left a folder mixing two runs and a hidden staging folder forever;
- two runs into one ``--out`` crashed or mixed their files;
- a compound with a 3000 ft3 receiver exited 0 with balance errors near 0.9;
- ``--cycles 1000000000``, a card of many megabytes, pressures of 1e300 psia, piston
  fractions up to 10 and a card holding ten loops were taken.

The runs are the default scene's fast tier for two or three cycles (a fraction of a
second each once the kernels are compiled).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import numpy as np

from corliss.cli import commands as cli
from corliss.cli import run_command
from corliss.engine.balance import BALANCE_FACTOR, balance_failure, balance_tolerance
from corliss.errors import EXIT_BALANCE_FAILED, RunError
from corliss.files.run_output import STAGING_PREFIX, OutputFiles
from corliss.fitting.card import count_loops, parse_card
from corliss.keys import limits
from corliss.scene.loader import bundled_scenes

SCENES = bundled_scenes()
ROOT = Path(__file__).resolve().parent.parent
FAST = ["--fidelity", "fast", "--no-plots"]
#: The files of a steady run without figures.
NAMES = {f"default.{t}.{x}" for t in ("timeseries", "cycles", "cards")
         for x in ("csv", "meta.json")} | {"default.summary.json"}


def _run(argv, capsys):
    code = cli.main(argv)
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return code, out, err


def _tree(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and not p.is_symlink()}


def _which_run(folder: Path) -> set[int]:
    """The cycle counts the files of a run in ``folder`` record: one number when every
    file is of one run (a run of N cycles writes N rows of cycles, N in its meta files'
    ``run.cycles`` and in its summary's ``cycles_simulated``)."""
    seen = set()
    for name in NAMES:
        p = folder / name
        if name.endswith(".meta.json"):
            seen.add(json.loads(p.read_text())["run"]["cycles"])
        elif name.endswith("summary.json"):
            seen.add(json.loads(p.read_text())["cycles_simulated"])
        elif name.endswith("cycles.csv"):
            seen.add(len(p.read_text().splitlines()) - 1)
        elif name.endswith("timeseries.csv"):
            seen.add(len({line.split(",")[0] for line in p.read_text().splitlines()[1:]}))
    return seen


@pytest.fixture()
def earlier(tmp_path, capsys):
    """A folder holding an earlier run's files (two cycles) and a meta file."""
    out = tmp_path / "out"
    assert _run(["run", "--out", str(out), "--cycles", "2", *FAST], capsys)[0] == 0
    assert {p.name for p in out.iterdir()} == NAMES and _which_run(out) == {2}
    return out


# --- meta files are untrusted input -----------------------------------------------------

def _edited_meta(src: Path, dst: Path, **changes) -> Path:
    m = json.loads(src.read_text())
    for k, v in changes.items():
        m[k] = v
    dst.write_text(json.dumps(m))
    return dst


@pytest.mark.parametrize("stem", ["/{victims}/victim", "../victim", "sub/victim", "..",
                                  ".hidden", "bad\nname", "x" * 300])
def test_a_meta_files_scene_name_never_writes_outside_out(stem, earlier, tmp_path, capsys):
    """The stem ``/some/dir/victim`` overwrote ``victim.timeseries.csv`` there; now
    every stem that is not a plain file name is refused before any work, naming
    ``scene_name``, and nothing anywhere changes."""
    victims = tmp_path / "victims"
    victims.mkdir()
    (victims / "victim.timeseries.csv").write_text("the user's own file")
    (tmp_path / "victim.timeseries.csv").write_text("the user's own file")
    meta = _edited_meta(earlier / "default.cycles.meta.json", tmp_path / "m.meta.json",
                        scene_name=stem.format(victims=victims))
    before = _tree(tmp_path)
    out = tmp_path / "new"
    code, _, err = _run(["run", "--from-meta", str(meta), "--out", str(out)], capsys)
    assert code == 2 and "scene_name" in err
    assert _tree(tmp_path) == before and not out.exists()


def test_a_symlink_in_out_is_replaced_not_followed(earlier, tmp_path, capsys):
    """A link in ``--out`` where a file of the run goes, pointing outside: the run puts
    its file in place of the link; the file outside is untouched."""
    outside = tmp_path / "outside.csv"
    outside.write_text("the user's own file")
    link = earlier / "default.cycles.csv"
    link.unlink()
    link.symlink_to(outside)
    assert _run(["run", "--out", str(earlier), "--cycles", "3", *FAST], capsys)[0] == 0
    assert outside.read_text() == "the user's own file"
    assert not link.is_symlink() and _which_run(earlier) == {3}


def test_edited_scene_text_or_tables_are_refused_unless_asked(earlier, tmp_path, capsys):
    """The text edited (a 14 in bore for 12 in) no longer has its recorded SHA-256; the
    tables edited no longer are the text's: each refused naming what differs.  With
    ``--as-edited`` the edited text runs, and its meta file records it with its own
    hash."""
    m = json.loads((earlier / "default.cycles.meta.json").read_text())
    assert 'bore = "12 in"' in m["scene_toml"]
    text = m["scene_toml"].replace('bore = "12 in"', 'bore = "14 in"')
    meta = _edited_meta(earlier / "default.cycles.meta.json", tmp_path / "t.meta.json",
                        scene_toml=text)
    code, _, err = _run(["run", "--from-meta", str(meta), "--out", str(tmp_path / "a")], capsys)
    assert code == 2 and "scene_sha256" in err and "--as-edited" in err
    data = json.loads(json.dumps(m["scene_data"]))
    data["engine"]["bore"] = "14 in"
    meta2 = _edited_meta(earlier / "default.cycles.meta.json", tmp_path / "d.meta.json",
                         scene_data=data)
    code, _, err = _run(["run", "--from-meta", str(meta2), "--out", str(tmp_path / "b")], capsys)
    assert code == 2 and "scene_data.engine.bore" in err and "'12 in'" in err
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()
    code, _, err = _run(["run", "--from-meta", str(meta), "--as-edited", "--out",
                         str(tmp_path / "c")], capsys)
    assert code == 0, err
    again = json.loads((tmp_path / "c" / "default.cycles.meta.json").read_text())
    assert again["scene_data"]["engine"]["bore"] == "14 in"
    import hashlib
    assert again["scene_sha256"] == hashlib.sha256(text.encode()).hexdigest()


def _deep(n: int) -> str:
    return "[" * n + "]" * n


@pytest.mark.parametrize("field, value, key", [
    ("run", {"effects": ["port_flow", "warp_drive"]}, "run.effects"),
    ("run", {"cycles": 10 ** 9}, "run.cycles"),
    ("run", {"cycles": "two"}, "run.cycles"),
    ("run", {"fidelity": {"name": "fast", "rtol": -1}}, "run.fidelity"),
    ("run", {"speed_rad_s": 1e300}, "run.speed_rad_s"),
    ("run", {"warp": 1}, "run.warp"),
    ("run", [], "run"),
    ("scene_name", 5, "scene_name"),
    ("scene_sha256", "zz", "scene_sha256"),
    ("scene_toml", ["not", "text"], "scene_toml"),
    ("scene_data", [], "scene_data"),
    ("scene_file", {"a": 1}, "scene_file"),
])
def test_every_malformed_field_of_a_meta_file_is_a_clear_error(field, value, key, earlier,
                                                              tmp_path, capsys):
    """Seven malformed fields gave tracebacks and an unknown effect was dropped: each
    is refused with exit 2 naming its key, nothing written."""
    src = earlier / "default.cycles.meta.json"
    m = json.loads(src.read_text())
    if isinstance(value, dict) and field == "run":
        run = dict(m["run"])
        for k, v in value.items():
            if isinstance(v, dict):
                run[k] = {**run[k], **v}
            else:
                run[k] = v
        value = run
    if field in ("scene_toml", "scene_data"):
        m["scene_sha256"] = None if field == "scene_toml" else m["scene_sha256"]
    m[field] = value
    meta = tmp_path / "bad.meta.json"
    meta.write_text(json.dumps(m))
    code, _, err = _run(["run", "--from-meta", str(meta), "--out", str(tmp_path / "o")], capsys)
    assert code == 2 and key in err, err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("content", [_deep(100_000), '{"run": ' + "9" * 5001 + "}",
                                     "\x00\x01", "[]", '{"scene_data": {}}'])
def test_a_meta_file_that_is_not_one_is_refused(content, tmp_path, capsys):
    """Deeply nested JSON (a RecursionError), a 5,001-digit integer, binary bytes: exit
    2, no traceback."""
    meta = tmp_path / "x.meta.json"
    meta.write_text(content)
    code, _, err = _run(["run", "--from-meta", str(meta), "--out", str(tmp_path / "o")], capsys)
    assert code == 2 and err.startswith("corliss: ")
    assert not (tmp_path / "o").exists()


def test_a_meta_files_output_folder_must_stay_in_the_working_directory(
        earlier, tmp_path, capsys, monkeypatch):
    """Without ``--out`` the output folder is the scene's ``[output] dir``: from a meta
    file, an absolute one or one with ``..`` is refused."""
    m = json.loads((earlier / "default.cycles.meta.json").read_text())
    text = m["scene_toml"].replace(f'dir = "{m["scene_data"]["output"]["dir"]}"',
                                   f'dir = "{tmp_path / "elsewhere"}"')
    assert text != m["scene_toml"]
    meta = _edited_meta(earlier / "default.cycles.meta.json", tmp_path / "o.meta.json",
                        scene_toml=text)
    monkeypatch.chdir(earlier)
    code, _, err = _run(["run", "--from-meta", str(meta), "--as-edited"], capsys)
    assert code == 2 and "output.dir" in err
    assert not (tmp_path / "elsewhere").exists()


# --- the commit: interrupts and kills -----------------------------------------------------

def _renames_of_a_commit(earlier, capsys, monkeypatch) -> int:
    real, calls = os.replace, []

    def counting(src, dst):
        if str(dst).startswith(str(earlier)):     # the commit's, not a cache's
            calls.append(dst)
        return real(src, dst)
    monkeypatch.setattr(os, "replace", counting)
    assert _run(["run", "--out", str(earlier), "--cycles", "2", *FAST], capsys)[0] == 0
    monkeypatch.setattr(os, "replace", real)
    return len(calls)


def test_sigint_at_every_rename_of_the_commit_leaves_one_whole_run(earlier, capsys,
                                                                   monkeypatch):
    """A SIGINT at the k-th rename (the journal's, then each file's) of a three-cycle
    run over a two-cycle one: exit 130, no traceback, every file there, all of one run
    (before: 8 of 9 files were left, the earlier time series gone), no staging folder.
    """
    n = _renames_of_a_commit(earlier, capsys, monkeypatch)
    assert n == len(NAMES) + 1           # the journal, then each file
    real = os.replace
    for k in range(1, n + 1):
        calls = []

        def interrupting(src, dst):
            if str(dst).startswith(str(earlier)):
                calls.append(dst)
            if len(calls) == k and str(dst).startswith(str(earlier)):
                os.kill(os.getpid(), signal.SIGINT)
            return real(src, dst)
        monkeypatch.setattr(os, "replace", interrupting)
        code, _, err = _run(["run", "--out", str(earlier), "--cycles", "3", *FAST], capsys)
        monkeypatch.setattr(os, "replace", real)
        assert code == 130 and "interrupted" in err
        assert {p.name for p in earlier.iterdir()} == NAMES
        # the journal's rename comes before the moves: interrupted there, the earlier
        # run stays; once the moves begin, they finish
        assert _which_run(earlier) == ({2} if k == 1 else {3}), k
        # back to the earlier run for the next k
        assert _run(["run", "--out", str(earlier), "--cycles", "2", *FAST], capsys)[0] == 0


_MAIN = "import sys; from corliss.cli import commands; sys.exit(commands.main(sys.argv[1:]))"
_KILLER = textwrap.dedent("""
    import os, signal, sys
    from corliss.cli import commands as cli
    k, out, real, calls = int(sys.argv[1]), sys.argv[2], os.replace, []
    def killing(src, dst):
        if str(dst).startswith(out):     # the commit's renames, not a cache's
            calls.append(dst)
            if len(calls) == k:
                os.kill(os.getpid(), signal.SIGKILL)
        return real(src, dst)
    os.replace = killing
    sys.exit(cli.main(sys.argv[3:]))
""")


@pytest.mark.parametrize("k", [2, 5, len(NAMES) + 1])
def test_sigkill_at_a_rename_loses_nothing_and_the_next_run_finishes_it(k, earlier, tmp_path,
                                                                       capsys):
    """SIGKILL at the k-th rename: every file is still there and whole (a rename
    replaces, nothing is removed first), the staging folder holds the journal, and the
    next run into the folder finishes the killed run's moves (one whole run) and
    removes its staging folder (before: a folder mixing two runs, and a hidden
    ``.corliss-*`` folder never cleaned)."""
    proc = subprocess.run([sys.executable, "-c", _KILLER, str(k), str(earlier), "run", "--out",
                           str(earlier), "--cycles", "3", *FAST], capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == -signal.SIGKILL, proc.stderr
    assert NAMES <= {p.name for p in earlier.iterdir()}
    staging = [p for p in earlier.iterdir() if p.name.startswith(STAGING_PREFIX)]
    assert len(staging) == 1
    with OutputFiles(earlier):
        pass                              # the next run into the folder
    assert {p.name for p in earlier.iterdir()} == NAMES
    assert _which_run(earlier) == {3}


def test_a_staging_folder_killed_before_its_commit_is_removed(earlier, capsys):
    """A staging folder without a journal (a run killed while drawing) is removed by
    the next run; the folder's files are the earlier run's, untouched."""
    stale = earlier / f"{STAGING_PREFIX}killed"
    stale.mkdir()
    (stale / "default.summary.json").write_text("half a file")
    before = _tree(earlier)
    with OutputFiles(earlier):
        pass
    assert not stale.exists()
    assert _tree(earlier) == {k: v for k, v in before.items() if not k.startswith(".")}


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_sigint_and_sigterm_during_a_run_leave_the_folder_as_it_was(sig, code, earlier,
                                                                    capsys, monkeypatch):
    """A signal while the run simulates: exit 130 or 143, one line, no traceback, the
    earlier run's files byte for byte."""
    before = _tree(earlier)
    real = run_command.simulate

    def signalled(*a, **k):
        os.kill(os.getpid(), sig)
        return real(*a, **k)
    monkeypatch.setattr(run_command, "simulate", signalled)
    got, _, err = _run(["run", "--out", str(earlier), "--cycles", "3", *FAST], capsys)
    assert got == code and err.count("\n") <= 2
    assert _tree(earlier) == before


# --- a folder describes one run -------------------------------------------------------------

#: The figures of a steady run of the default scene.
FIGURES = {"default.card.png", "default.effort.png"}


@pytest.fixture()
def plotted(tmp_path, capsys):
    """A folder holding an earlier run's files with its figures (two cycles)."""
    out = tmp_path / "plotted"
    assert _run(["run", "--out", str(out), "--cycles", "2", "--fidelity", "fast"], capsys)[0] == 0
    assert {p.name for p in out.iterdir()} == NAMES | FIGURES and _which_run(out) == {2}
    return out


def test_a_run_without_figures_takes_the_earlier_runs_figures_away(plotted, capsys):
    """``--no-plots`` after a plotted run into the same folder: before, the earlier
    run's figures stayed beside the new run's tables, a folder of two runs; now the
    commit moves them out with the rest, and the folder is the new run's alone."""
    assert _run(["run", "--out", str(plotted), "--cycles", "3", *FAST], capsys)[0] == 0
    assert {p.name for p in plotted.iterdir()} == NAMES and _which_run(plotted) == {3}
    # files of another stem, and of another kind of result, are not this run's to take
    other = plotted / "other.card.png"
    other.write_bytes(b"another scene's figure")
    sweep = plotted / "default.sweep.csv"
    sweep.write_text("a sweep of this scene\n")
    assert _run(["run", "--out", str(plotted), "--cycles", "2", *FAST], capsys)[0] == 0
    assert {p.name for p in plotted.iterdir()} == NAMES | {other.name, sweep.name}


def test_sigint_or_a_failure_as_the_figures_go_leaves_one_whole_run(plotted, capsys,
                                                                     monkeypatch):
    """The figures go in the commit, after the new files are in place, signals held: a
    SIGINT there still leaves the new run whole (exit 130); a failure there (a disk
    error moving the second) puts every earlier file back, the first figure too."""
    real = os.replace
    staged = []

    def interrupting(src, dst):
        if str(src).endswith(".png") and str(src).startswith(str(plotted)):
            staged.append(src)           # a figure moved aside, out of the folder
            os.kill(os.getpid(), signal.SIGINT)
        return real(src, dst)
    monkeypatch.setattr(os, "replace", interrupting)
    code, _, err = _run(["run", "--out", str(plotted), "--cycles", "3", *FAST], capsys)
    monkeypatch.setattr(os, "replace", real)
    assert code == 130 and len(staged) == len(FIGURES)
    assert {p.name for p in plotted.iterdir()} == NAMES and _which_run(plotted) == {3}

    assert _run(["run", "--out", str(plotted), "--cycles", "2", "--fidelity", "fast"],
                capsys)[0] == 0
    before = _tree(plotted)

    aside = []

    def failing(src, dst):              # the second figure's move fails
        if str(dst).endswith(".retired"):
            aside.append(dst)
            if len(aside) == 2:
                raise OSError(28, "No space left on device")
        return real(src, dst)
    monkeypatch.setattr(os, "replace", failing)
    code, _, err = _run(["run", "--out", str(plotted), "--cycles", "3", *FAST], capsys)
    monkeypatch.setattr(os, "replace", real)
    assert code != 0 and "as it was" in err
    assert _tree(plotted) == before


def test_sigkill_as_the_figures_go_and_the_next_run_finishes_it(plotted):
    """SIGKILL at the first figure's move: the new tables are in place, the journal
    names the figures to go, and the next run into the folder takes them away."""
    k = len(NAMES) + 2           # the journal, each new file, then the first figure
    proc = subprocess.run([sys.executable, "-c", _KILLER, str(k), str(plotted), "run",
                           "--out", str(plotted), "--cycles", "3", *FAST],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == -signal.SIGKILL, proc.stderr
    assert FIGURES <= {p.name for p in plotted.iterdir()}
    with OutputFiles(plotted):
        pass
    assert {p.name for p in plotted.iterdir()} == NAMES and _which_run(plotted) == {3}


def test_a_transient_run_after_a_steady_one_of_the_same_name_leaves_no_cards(earlier,
                                                                              capsys):
    """A steady run and a transient run share their tables' names: a transient run of a
    scene named as the steady one leaves no steady cards or figures beside its files."""
    text = SCENES["porter-throttling-governor"].read_text(encoding="utf-8")
    scene = earlier.parent / "default.toml"
    scene.write_text(text, encoding="utf-8")
    code, _, _ = _run(["run", str(scene), "--out", str(earlier), "--duration", "0.5 s",
                       "--no-plots"], capsys)
    assert code == 0
    assert {p.name for p in earlier.iterdir()} == {
        f"default.{t}.{x}" for t in ("timeseries", "cycles") for x in ("csv", "meta.json")
    } | {"default.summary.json"}


# --- one writer per folder ---------------------------------------------------------------

def test_a_second_writer_waits_for_the_first_and_gives_up_with_a_message(tmp_path):
    """While one run writes into a folder, a second one waits; past its wait it stops
    with a message naming the folder (a RunError: exit 2 from the command line)."""
    with OutputFiles(tmp_path) as first:
        first.stage("a.txt").write_text("first")
        with pytest.raises(RunError, match="another corliss run"):
            with OutputFiles(tmp_path, lock_wait_s=0.3):
                pass
    assert (tmp_path / "a.txt").read_text() == "first"


def test_two_runs_racing_into_one_folder_leave_one_whole_run(tmp_path):
    """Two runs of one scene and one unit system, of 2 and 3 cycles, started together
    into one folder: both exit 0 and the folder holds every file of one of them, none
    of the other (before: 4 of 440 processes crashed, and one pair left files of two
    runs mixed).  An SI and a US run no longer share a name (the SI files carry the
    system in their stem), so the race is between two of the same names."""
    out = tmp_path / "out"
    procs = [subprocess.Popen([sys.executable, "-c", _MAIN, "run", "--out", str(out),
                               "--cycles", n, *FAST],
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
             for n in ("2", "3")]
    errs = [p.communicate(timeout=300)[1] for p in procs]
    assert [p.returncode for p in procs] == [0, 0], errs
    assert {p.name for p in out.iterdir()} == NAMES
    assert len(_which_run(out)) == 1, _which_run(out)


# --- balances fail a run -----------------------------------------------------------------

def test_the_balance_tolerance_judges_the_errors_against_the_steam_through():
    """A closed-form check of the rule: errors within ``BALANCE_FACTOR`` times the
    periodicity tolerance pass; above, the message names the larger."""
    tol = balance_tolerance(1e-3)
    assert tol == BALANCE_FACTOR * 1e-3
    ok = {"convergence_tolerance": 1e-3, "steam_per_cycle_kg": 0.1,
          "mass_balance_error": 0.9 * tol, "energy_balance_error": None}
    assert balance_failure(ok) is None
    bad = dict(ok, mass_balance_error=0.89, energy_balance_error=0.93)
    assert "energy balance" in balance_failure(bad) and "0.93" in balance_failure(bad)


def test_a_compound_whose_receiver_never_fills_fails_its_run(tmp_path, capsys):
    """The nine-inch compound with a 3000 ft3 receiver (1.9 ft3 in Marks's): its work
    settles within 2.4e-4 while the receiver still swallows most of the steam, so
    steam in and steam out differ by 0.89 of the steam (before: exit 0, a water rate of
    15.7).  Now exit ``EXIT_BALANCE_FAILED`` naming the balance; with ``--cycles`` a
    warning names it.  The bundled compound passes (fast: errors 0.0025 and 0.0028)."""
    text = SCENES["marks-compound-9-14x14"].read_text()
    assert 'receiver_volume = "1.9 ft3"' in text
    big = tmp_path / "big.toml"
    big.write_text(text.replace('receiver_volume = "1.9 ft3"', 'receiver_volume = "3000 ft3"'))
    code, _, err = _run(["run", str(big), "--out", str(tmp_path / "a"), *FAST], capsys)
    assert code == EXIT_BALANCE_FAILED and "NOT a result" in err and "balance" in err
    s = json.loads((tmp_path / "a" / "big.summary.json").read_text())
    assert max(s["mass_balance_error"], s["energy_balance_error"]) > 0.5
    code, _, err = _run(["run", str(big), "--out", str(tmp_path / "b"), "--cycles", "4",
                         *FAST], capsys)
    assert code == 0 and "balance does not close" in err
    code, _, err = _run(["run", "marks-compound-9-14x14", "--out", str(tmp_path / "c"),
                         *FAST], capsys)
    assert code == 0, err


def test_a_study_row_that_did_not_converge_is_failed_not_ok(tmp_path):
    """The compound's receiver varied from Marks's 1.9 ft3 to 3000 ft3: the small one
    is ``ok``, the huge one ``failed`` with ``not converged`` and the reason (before:
    ``ok`` with a mass-balance error of 0.36 to 1.31)."""
    from corliss.studies import study
    r = study("marks-compound-9-14x14", ["compound.receiver_volume=1.9,3000ft3"], grid=True,
              fidelity="fast", jobs=1)
    pts = r.points.sort_values("compound.receiver_volume_ft3")
    assert list(pts["status"]) == ["ok", "failed"]
    assert pts["error"].iloc[1].startswith("not converged")
    assert r.summary["failed"] == 1


# --- ceilings on the inputs -------------------------------------------------------------

def test_a_cycle_count_beyond_the_ceiling_is_refused_before_work(tmp_path, capsys):
    """``--cycles 1000000000`` ran, its memory growing 11 MB/s: now refused naming the
    ceiling, nothing written."""
    code, _, err = _run(["run", "--out", str(tmp_path / "o"), "--cycles", "1000000000"], capsys)
    assert code == 2 and "--cycles" in err and f"{limits.MAX_CYCLES}" in err
    assert not (tmp_path / "o").exists()


def test_a_duration_beyond_the_ceiling_is_refused_before_work(tmp_path, capsys):
    """An hour of an engine's life is the most a transient runs: ``--duration 2 h`` and
    a scene's ``[run] duration = "2 h"`` are refused naming the key, nothing written."""
    code, _, err = _run(["run", "porter-throttling-governor", "--duration", "2 h", "--out",
                         str(tmp_path / "o")], capsys)
    assert code == 2 and "--duration" in err and "1 h" in err
    text = SCENES["porter-throttling-governor"].read_text()
    scene = tmp_path / "long.toml"
    assert 'duration = "30 s"' in text
    scene.write_text(text.replace('duration = "30 s"', 'duration = "2 h"'))
    code, _, err = _run(["run", str(scene), "--out", str(tmp_path / "o")], capsys)
    assert code == 2 and "run.duration" in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("how, key", [(["--lhs", "10000001"], "--lhs"),
                                      (["--monte-carlo", "10000001"], "--monte-carlo"),
                                      (["--grid", "--levels", "4000"], "--levels")])
def test_a_study_beyond_the_ceiling_is_refused_before_work(how, key, tmp_path, capsys):
    """A study's runs are at most ten million (a grid of two keys at 4,000 levels is
    sixteen million): refused naming the option, nothing written."""
    code, _, err = _run(["study", "default", "--vary", "valve_gear.lap=0.8:1.2in",
                         "--vary", "engine.bore=11:13in", *how, "--out", str(tmp_path / "o")],
                        capsys)
    assert code == 2 and key in err and "10,000,000" in err, err
    assert not (tmp_path / "o").exists()


def test_a_text_file_over_the_size_limit_is_refused_unread(tmp_path, capsys):
    """A scene is a few kilobytes: a file over the 20 MB of docs/limits.md (a valid
    scene with a comment making up the rest) is refused naming the scene and its size,
    before it is read."""
    big = tmp_path / "big.toml"
    big.write_text(SCENES["default"].read_text() + "#" * 20_000_000 + "\n")
    code, _, err = _run(["events", str(big)], capsys)
    assert code == 2 and "scene" in err and "MB" in err, err


def test_an_output_folder_that_cannot_be_made_or_written_is_a_message(tmp_path, capsys,
                                                                     monkeypatch):
    """``--out`` beneath a file (a folder that cannot be made): refused before any work
    naming ``--out`` (exit 2); a folder that fails as the run's files are staged (made
    unwritable after the check) is one line saying so (exit 5); no traceback, nothing
    written (before: a traceback)."""
    blocker = tmp_path / "a-file"
    blocker.write_text("the user's own file")
    code, _, err = _run(["run", "--out", str(blocker / "out"), "--cycles", "2", *FAST], capsys)
    assert code == 2 and "--out" in err and "is a file" in err
    assert blocker.read_text() == "the user's own file"
    out = tmp_path / "out"

    def unwritable(*a, **k):
        raise PermissionError(13, "Permission denied", str(out))
    import tempfile
    monkeypatch.setattr(tempfile, "mkdtemp", unwritable)
    code, _, err = _run(["run", "--out", str(out), "--cycles", "2", *FAST], capsys)
    monkeypatch.undo()
    assert code == cli.EXIT_RUN_STOPPED and "could not write into the output folder" in err
    assert not out.exists()


def _card_text(loops: int = 1, p_psia: float = 100.0, frac_max: float = 1.0,
               n: int = 72) -> str:
    """A head-end loop of ``n`` points: admission along the top, expansion, exhaust
    along the bottom (a plain card's outline), repeated ``loops`` times."""
    lines = ["end,piston_frac,p_psia"]
    for _ in range(loops):
        for i in range(n):
            t = 2 * np.pi * i / n
            x = frac_max * 0.5 * (1 - np.cos(t))
            p = p_psia * (1.0 if t < np.pi / 2 else 0.3 if t < np.pi else 0.16)
            lines.append(f"head,{x:.6f},{p:.6g}")
    return "\n".join(lines) + "\n"


def test_one_loop_is_one_and_ten_loops_are_ten():
    """The loop count of a card whose points go round once, started anywhere, and of
    the same points ten times over."""
    one = parse_card(_card_text())
    x = one.ends["head"].x
    assert count_loops(x) == 1 and count_loops(np.roll(x, 17)) == 1
    assert count_loops(np.tile(x, 10)) == 10


@pytest.mark.parametrize("text, words", [
    (_card_text(loops=10), "round 10 times"),
    (_card_text(p_psia=1e300), "critical pressure"),
    (_card_text(frac_max=10.0), "piston fractions"),
    ("end,piston_frac,p_psia\n" + "head,0.5,10\n" * (limits.MAX_CARD_POINTS + 1), "at most"),
    ("end,piston_frac,p_psia\nhead,0.5," + "9" * 200_000 + "\n", "CSV"),
])
def test_a_card_the_fit_cannot_believe_is_refused_before_work(text, words, tmp_path, capsys):
    """A card holding ten loops (it fitted a lap of 0.873 +/- 0.19 in for 1.1), pressures
    of 1e300 psia (exit 0 with a null residual), piston fractions to 10, more points
    than the ceiling, a field too long for the CSV reader: exit 2 naming the card."""
    card = tmp_path / "card.csv"
    card.write_text(text)
    code, _, err = _run(["fit", "default", str(card), "--vary", "valve_gear.lap=0.7:1.3in",
                         "--out", str(tmp_path / "o")], capsys)
    assert code == 2 and "card" in err and words in err, err
    assert not (tmp_path / "o").exists()


def test_a_card_file_over_the_size_limit_is_refused(tmp_path, capsys):
    """A 17.5 MB card took nine minutes and 6 GB in the fit: a file over
    ``MAX_CARD_BYTES`` is refused unread."""
    card = tmp_path / "card.csv"
    card.write_text("end,piston_frac,p_psia\n" + "#" * (limits.MAX_CARD_BYTES + 1) + "\n")
    code, _, err = _run(["fit", "default", str(card), "--vary", "valve_gear.lap=0.7:1.3in",
                         "--out", str(tmp_path / "o")], capsys)
    assert code == 2 and "MB" in err


# --- clean refusals where there were tracebacks ------------------------------------------

def _scene_with(tmp_path, name: str, title_line: str) -> Path:
    import re
    text = SCENES["default"].read_text()
    path = tmp_path / f"{name}.toml"
    new, n = re.subn(r"(?m)^title = .*$", lambda _: title_line, text, count=1)
    assert n == 1
    path.write_text(new)
    return path


@pytest.mark.parametrize("text, words", [
    ('title = "x"\na = ' + "[" * 5000 + "]" * 5000 + "\n", "recursion"),
    ("title = " + "9" * 5001 + "\n", "4300 digits"),
])
def test_toml_nested_too_deeply_or_a_huge_integer_is_refused(text, words, tmp_path, capsys):
    """Arrays nested 5,000 deep (tomllib's RecursionError) and a 5,001-digit integer
    (Python's ValueError): exit 2 naming the scene, no traceback."""
    path = tmp_path / "s.toml"
    path.write_text(text)
    code, _, err = _run(["events", str(path)], capsys)
    assert code == 2 and "scene" in err and words in err


def test_a_title_with_dollars_is_plain_text_and_control_characters_are_refused(tmp_path,
                                                                             capsys):
    """``$\\frac{a}{$`` in a title stopped the plot (matplotlib's mathtext): now drawn
    as it is; a control character (which broke ``fitted.toml``) or a title over the
    ceiling is refused naming ``title``."""
    path = _scene_with(tmp_path, "dollars", 'title = "costs $\\\\frac{a}{$"')
    code, _, err = _run(["run", str(path), "--out", str(tmp_path / "a"), "--cycles", "2",
                         "--fidelity", "fast"], capsys)
    assert code == 0, err
    assert (tmp_path / "a" / "dollars.card.png").stat().st_size > 0
    for i, title in enumerate(['title = "a\\u0007b"', f'title = "{"x" * 201}"']):
        path = _scene_with(tmp_path, f"bad{i}", title)
        code, _, err = _run(["events", str(path)], capsys)
        assert code == 2 and "title" in err


@pytest.mark.parametrize("argv, key", [
    (["study", "default", "--vary", "valve_gear.lap=0.8:1.2in", "--grid", "--levels", "2",
      "--scheduler", "tls://127.0.0.1:1"], "--scheduler"),
    (["study", "default", "--vary", "valve_gear.lap=0.8:1.2in", "--grid", "--levels", "2",
      "--scheduler", "ucx://x"], "--scheduler"),
    (["bench", "--repeats", "0"], "--repeats"),
])
def test_options_that_gave_tracebacks_are_refused(argv, key, tmp_path, capsys):
    """``--scheduler tls://...`` (a TypeError inside distributed), ``ucx://...`` (an
    abstract class), ``bench --repeats 0`` (ran): exit 2 naming the option."""
    code, _, err = _run(argv + ["--out", str(tmp_path / "o")], capsys)
    assert code == 2 and key in err
    assert not (tmp_path / "o").exists()


# --- caches ------------------------------------------------------------------------------

def test_the_steam_tables_temporary_file_is_removed_on_any_exit(tmp_path, monkeypatch):
    """A save interrupted (Ctrl-C while ``np.savez`` writes) leaves no temporary file; a
    temporary file of a process that is gone (killed while saving: 10 MB, never removed
    before) is removed by the next save; one of a live process is left alone."""
    from corliss.thermo import steam_table
    path = tmp_path / "table.npz"
    real = np.savez

    def interrupted(file, **data):
        real(file, **data)
        raise KeyboardInterrupt
    monkeypatch.setattr(steam_table.np, "savez", interrupted)
    with pytest.raises(KeyboardInterrupt):
        steam_table._save(path, {"a": np.zeros(3)})
    assert list(tmp_path.iterdir()) == []
    monkeypatch.setattr(steam_table.np, "savez", real)
    gone = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True).stdout.strip()
    stale = tmp_path / f"table.{gone}.tmp.npz"
    stale.write_bytes(b"half a table")
    live = tmp_path / f"table.{os.getppid()}.tmp.npz"
    live.write_bytes(b"another process's table, being written")
    steam_table._save(path, {"a": np.zeros(3)})
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["table.npz", live.name])
