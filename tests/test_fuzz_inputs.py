"""Nothing a user hands corliss gives a traceback or writes outside ``--out``: a fuzzer
over meta files, cards, whole command lines and scenes.

(The scene grammar's own fuzzer, mutating every key of every bundled scene, is
``test_scene_fuzz.py``.)  Here the inputs people send each other or type:

- **meta files**: a real one, each field (top level, the run's knobs, a scene table's
  key) replaced by a value of another kind, huge, negative, a path, nested, or its
  bytes cut and spliced; run with ``corliss run --from-meta``;
- **cards**: a real card's text mutated (a number replaced, a line repeated or cut,
  bytes spliced) and read as a fit reads it;
- **command lines**: a subcommand with options drawn from every flag the parser has,
  given good, bad and hostile values (the work each command would start is replaced
  by a marker, so an accepted line costs nothing);
- **scenes**: every bundled scene with random bytes spliced in, run with ``events``.

Each case runs with the working directory in a sandbox and ``--out`` inside it: the
answer must be an exit status (0, 2 or the balance's 3), never an exception; stderr
without a traceback; no file changed outside ``--out`` (the sandbox and a folder of
the user's own beside it, snapshotted); no staging folder left in ``--out``.

The cases are drawn from ``random.Random(seed)``: CI runs :data:`CI_CASES` of each kind
with seed 0 in seconds; ``benchmarks/fuzz_inputs.py`` runs more, with other seeds
(``CORLISS_FUZZ_CASES``, ``CORLISS_FUZZ_SEED``).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import random
import shutil
from pathlib import Path

import pytest

import corliss.files.design_output
import corliss.files.fit_output
import corliss.studies
import corliss.studies.compare
import corliss.studies.load_range
from corliss.cli import commands as cli
from corliss.cli import gear_commands, run_command
from corliss.engine.verdict import EXIT_PHYSICAL
from corliss.errors import EXIT_BALANCE_FAILED, InputError
from corliss.files.run_output import STAGING_PREFIX
from corliss.fitting.card import parse_card
from corliss.scene.loader import bundled_scenes

SCENES = bundled_scenes()
#: Cases of each kind in CI (seconds in all once the kernels are compiled).
CI_CASES = 40
CASES = int(os.environ.get("CORLISS_FUZZ_CASES", CI_CASES))
SEED = int(os.environ.get("CORLISS_FUZZ_SEED", 0))
#: Exit statuses a command may give: done, refused, a run whose balances fail, a run
#: that failed physically, a run that stopped (docs/exit-codes.md).
STATUSES = {0, 2, EXIT_BALANCE_FAILED, EXIT_PHYSICAL, cli.EXIT_RUN_STOPPED}

#: Hostile values: huge, tiny, not finite, wrong kinds, paths out, control characters,
#: deep nesting, long text.
HOSTILE = [None, True, -1, 0, 10 ** 30, 1e300, -1e300, 1e-300, "nan", "inf", "",
           "/etc/passwd", "../../victim", "a/b", "..", ".corliss-x", "x" * 5000, "\x00",
           "\u202e", "$\\frac{1}{0}$", "1e999 in", "12 furlongs", [], {}, [[[[[]]]]],
           {"a": {"b": {"c": {}}}}, "12 in", "100 psig", 3.5, ["port_flow"]]


def _snapshot(*folders: Path) -> dict[str, tuple[int, int]]:
    out = {}
    for folder in folders:
        for p in folder.rglob("*"):
            if p.is_file() or p.is_symlink():
                st = p.lstat()
                out[str(p)] = (st.st_size, st.st_mtime_ns)
    return out


class _Reached(Exception):
    """The work a command would start (a study, a fit): its input was accepted."""


@pytest.fixture(scope="module")
def sandbox(tmp_path_factory):
    """A sandbox (the working directory of every case), a folder of the user's own
    beside it (a victim for a write outside), a meta file and a card from a real run."""
    root = tmp_path_factory.mktemp("fuzz")
    box, own = root / "box", root / "own"
    box.mkdir()
    own.mkdir()
    (own / "victim.timeseries.csv").write_text("the user's own file")
    (box / "notes.txt").write_text("the user's own notes")
    real = root / "real"
    with contextlib.redirect_stdout(io.StringIO()):
        assert cli.main(["run", "--out", str(real), "--cycles", "2", "--fidelity", "fast",
                         "--no-plots"]) == 0
    return {"root": root, "box": box, "own": own,
            "meta": json.loads((real / "default.cycles.meta.json").read_text()),
            "card": (real / "default.cards.csv").read_text()}


def _answer(argv: list[str], sandbox, monkeypatch, capsys, case) -> int:
    """Run one command line in the sandbox and check the answer: an exit status, no
    traceback, nothing written outside ``--out``, no staging folder left."""
    box, out = sandbox["box"], sandbox["box"] / "out"
    monkeypatch.chdir(box)
    before = _snapshot(sandbox["own"], box)
    try:
        code = cli.main(argv)
    except SystemExit as exc:           # argparse's refusal of a malformed line
        code = exc.code
    except _Reached:
        code = 0
    finally:
        err = capsys.readouterr().err
    assert code in STATUSES, (case, code, err)
    assert "Traceback" not in err, (case, err)
    after = _snapshot(sandbox["own"], box)
    changed = {p for p in set(before) | set(after) if before.get(p) != after.get(p)
               and not Path(p).is_relative_to(out)}
    assert not changed, (case, changed)
    if out.exists():
        assert not [p for p in out.iterdir() if p.name.startswith(STAGING_PREFIX)], case
        shutil.rmtree(out)
    return code


# --- meta files ------------------------------------------------------------------------

def _paths(m: dict) -> list[tuple[str, ...]]:
    """Every field a mutation may change: top level, the run's, each scene table's key."""
    paths = [(k,) for k in m]
    paths += [("run", k) for k in m["run"]]
    paths += [("run", "fidelity", k) for k in m["run"]["fidelity"]]
    paths += [("scene_data", s, k) for s, t in m["scene_data"].items() if isinstance(t, dict)
              for k in t]
    return paths


def meta_case(rng: random.Random, meta: dict) -> tuple[str, str]:
    """A mutated meta file's text and what was done."""
    m = json.loads(json.dumps(meta))
    how = rng.choice(["field", "field", "field", "bytes", "sha"])
    if how == "bytes":
        text = json.dumps(m)
        i = rng.randrange(len(text))
        junk = "".join(chr(rng.randrange(1, 0x250)) for _ in range(rng.randrange(1, 8)))
        return text[:i] + junk + text[i + rng.randrange(0, 8):], f"bytes at {i}"
    path = rng.choice(_paths(m))
    node = m
    for k in path[:-1]:
        node = node[k]
    value = rng.choice(HOSTILE)
    if how == "sha" and isinstance(m.get("scene_toml"), str) and path[0] == "scene_data":
        node[path[-1]] = value      # the tables edited and the hash with them
        m["scene_toml"] = None
        m["scene_sha256"] = None
    else:
        node[path[-1]] = value
    return json.dumps(m), f"{'.'.join(path)} = {value!r:.60}"


def test_mutated_meta_files_are_run_or_refused_never_written_outside(sandbox, monkeypatch,
                                                                    capsys):
    rng = random.Random(SEED)
    codes = []
    for i in range(CASES):
        text, what = meta_case(rng, sandbox["meta"])
        meta = sandbox["box"] / "case.meta.json"
        meta.write_text(text, encoding="utf-8", errors="surrogatepass")
        codes.append(_answer(["run", "--from-meta", "case.meta.json", "--out", "out"],
                             sandbox, monkeypatch, capsys, (i, what)))
        meta.unlink()
    assert 2 in codes          # the fuzzer reaches refusals (it cannot pass vacuously)


# --- cards ------------------------------------------------------------------------------

def card_case(rng: random.Random, card: str) -> tuple[str, str]:
    """A mutated card's text and what was done."""
    lines = card.splitlines()
    how = rng.choice(["number", "repeat", "cut", "bytes", "scale"])
    if how == "number":
        i = rng.randrange(1, len(lines))
        fields = lines[i].split(",")
        j = rng.randrange(len(fields))
        fields[j] = str(rng.choice(HOSTILE))
        lines[i] = ",".join(fields)
    elif how == "repeat":
        lines = lines[:1] + lines[1:] * rng.randrange(2, 12)
    elif how == "cut":
        a = rng.randrange(len(lines))
        lines = lines[:a] + lines[a + rng.randrange(1, 400):]
    elif how == "scale":
        f = rng.choice([1e300, -1, 10, 1e-300, 0])
        head, *body = lines
        col = rng.randrange(len(head.split(",")))
        lines = [head] + [",".join(str(float(v) * f) if k == col and v[:1].isdigit() else v
                                   for k, v in enumerate(row.split(","))) for row in body]
    else:
        text = "\n".join(lines)
        i = rng.randrange(len(text))
        return text[:i] + rng.choice(HOSTILE[11:20]) + text[i:], f"bytes at {i}"
    return "\n".join(lines) + "\n", how


def test_mutated_cards_are_read_or_refused_naming_the_card(sandbox):
    """A fit reads a card before any work: each mutated card is read whole or refused
    with an InputError naming the card; nothing else escapes."""
    rng = random.Random(SEED)
    refused = 0
    base = sandbox["card"]
    for i in range(CASES * 3):
        text, what = card_case(rng, base)
        try:
            parse_card(text, source="card.csv")
        except InputError as exc:
            assert "card" in str(exc), (i, what, exc)
            refused += 1
    assert refused




# --- command lines ---------------------------------------------------------------------

def _flags() -> dict[str, list[str]]:
    """Every subcommand's option strings, from the parser itself."""
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    return {name: [o for a in p._actions for o in a.option_strings if o.startswith("--")
                   and o not in ("--help", "--version")]
            for name, p in sub.choices.items()}


VALUES = ["0", "1", "2", "-1", "1000000000", "1e9", "nan", "inf", "0.5", "0,0.5,1", "a,b",
          "0.1:1.1:0.1", "1:0:1", "valve_gear.lap=0.7:1.3in", "nope=1:2", "engine.bore=",
          "tls://127.0.0.1:1", "ucx://x", "tcp://", "US", "SI", "gif", "fast", "12 in",
          "5 s", "1e300 s", "out", "../escape", "/", "x" * 3000, "$x^2$", "\x01"]
SUBCOMMANDS = ["run", "events", "gear", "animate", "design", "sweep", "compare", "study",
               "fit", "list", "explain"]


def command_case(rng: random.Random, flags: dict[str, list[str]]) -> list[str]:
    """A random command line: a subcommand, a scene, a few of its flags with values."""
    cmd = rng.choice(SUBCOMMANDS)
    argv = [cmd]
    if cmd == "list":
        argv.append(rng.choice(["scenes", "gears", "keys", "nothing"]))
    elif cmd == "explain":
        argv.append(rng.choice(["valve_gear.lap", "run.effects", "x" * 500, "..", "\x01"]))
    else:
        argv.append(rng.choice(list(SCENES)[:6] + ["missing.toml", "/", "..", "\x00x"]))
    if cmd == "fit":
        argv.append(rng.choice(["card.csv", "missing.csv", "/dev/null"]))
    for _ in range(rng.randrange(0, 4)):
        flag = rng.choice(flags[cmd] or ["--json"])
        argv.append(flag)
        if rng.random() < 0.8:
            argv.append(rng.choice(VALUES))
    if "--out" not in argv:
        argv += ["--out", "out"] if "--out" in flags[cmd] else []
    return argv


def test_random_command_lines_are_answered_never_a_traceback(sandbox, monkeypatch, capsys):
    """Every subcommand with random flags and hostile values: an exit status, a
    message, nothing outside ``--out``.  The work an accepted line would start (a run,
    a study, a fit, a design, a sweep, a comparison, an animation) is replaced by a
    marker, so the parser's and the checks' answers are what is tested."""
    def reached(*a, **k):
        raise _Reached()
    (sandbox["box"] / "card.csv").write_text(sandbox["card"])
    for module, name in [(run_command, "simulate"), (corliss.studies, "study"),
                         (corliss.files.fit_output, "fit"),
                         (corliss.files.design_output, "design"),
                         (corliss.studies.load_range, "load_ranges"),
                         (corliss.studies.compare, "compare"), (gear_commands, "build_gear")]:
        monkeypatch.setattr(module, name, reached)
    rng = random.Random(SEED)
    flags = _flags()
    codes = []
    for i in range(CASES * 3):
        argv = command_case(rng, flags)
        codes.append(_answer(argv, sandbox, monkeypatch, capsys, (i, argv)))
    assert 2 in codes and 0 in codes


# --- scenes -----------------------------------------------------------------------------

def test_scenes_with_bytes_spliced_in_are_answered(sandbox, monkeypatch, capsys):
    """Every bundled scene, random bytes (hostile values, control characters, TOML
    syntax) spliced in, through ``events``: an answer, never a traceback."""
    rng = random.Random(SEED)
    names = sorted(SCENES)
    junk = ['"', "[", "]", "=", "\n[run]\n", "\x00", "\x7f", "\ufeff", "1e999", "{a={b={",
            "[[x]]", "'''", "\\u0000"]
    for i in range(CASES):
        name = names[i % len(names)]
        text = SCENES[name].read_text(encoding="utf-8")
        at = rng.randrange(len(text))
        text = text[:at] + "".join(rng.choice(junk) for _ in range(rng.randrange(1, 5))) + \
            text[at + rng.randrange(0, 5):]
        path = sandbox["box"] / "case.toml"
        path.write_text(text, encoding="utf-8")
        _answer(["events", "case.toml"], sandbox, monkeypatch, capsys, (i, name, at))
        path.unlink()
