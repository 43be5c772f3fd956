"""Bad input never reaches the physics, by random search over the scene grammar.

Every bundled scene (steady and transient) is parsed, one key (or a whole section) is
drawn from it and mutated: deleted, replaced by a value of the wrong type, given a unit
of another kind, made non-finite, scaled by 1e12 or 1e-12, negated, or replaced by a
random string; the scene is written back as TOML and given to the command line as a
user would.  The answer must be exit 0 with finite results, or exit 2 with a message
naming the mutated key (or its section), no traceback, no file written, within seconds.
Mutations that can never be valid (wrong types, wrong units, non-finite and huge
values) must give exit 2.  Whole files of random bytes must be refused naming
``scene``; a scene with random bytes spliced in must be read or refused, never crash.
Random valid scenes (a few bundled scenes scaled within plausible proportions) must
run to finite results.

The examples are derandomised and no example database is kept, so a run in CI is the
same run as on a desk.  Most examples are ``corliss events``, which parses the scene
and builds its gear without simulating (milliseconds each); the counts below make
some 3,800 examples and keep the file under a minute on two cores (40 s measured,
after the kernels are compiled).
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import re
import signal
import tempfile
import time
import tomllib
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from corliss.cli import commands as cli
from corliss.keys import units
from corliss.scene.loader import SECTIONS, bundled_scenes

SCENES = bundled_scenes()
DATA = {name: tomllib.loads(path.read_text(encoding="utf-8")) for name, path in SCENES.items()}
TRANSIENT = sorted(n for n, d in DATA.items() if d["run"].get("mode") == "transient")
STEADY = sorted(n for n in DATA if n not in TRANSIENT)

#: A refusal comes before any work (milliseconds); an accepted ``events`` builds one
#: gear (under half a second for the slowest bundled gear); an accepted ``run`` is
#: two fast cycles or a 0.2 s transient (about a second).  The bounds are some ten
#: times that, for a loaded CI machine, and catch a hang.
EVENTS_S = 10.0
RUN_S = 30.0

# --- writing TOML -------------------------------------------------------------------------

_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f",
            "\r": "\\r"}


class Raw(str):
    """TOML text written as it is (``1e999``, which no Python float prints as)."""


def _toml_value(v) -> str:
    if isinstance(v, Raw):
        return str(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v)          # inf, nan, 1e+300 and 0.5 are all TOML as Python prints them
    if isinstance(v, str):
        return '"' + "".join(_ESCAPES.get(c) or (f"\\u{ord(c):04x}" if ord(c) < 0x20
                                                 or ord(c) == 0x7F else c) for c in v) + '"'
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def to_toml(data: dict) -> str:
    """A scene dict (top-level values, then one level of tables) as TOML text."""
    lines = [f"{k} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for sec, table in data.items():
        if isinstance(table, dict):
            lines.append(f"\n[{sec}]")
            lines += [f"{k} = {_toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


# --- mutations ----------------------------------------------------------------------------

DELETE = object()
#: A unit of each kind, to give a quantity a unit of the wrong kind.
UNIT_OF_KIND = {"length": "in", "pressure": "psia", "speed": "rpm", "time": "s",
                "force": "lbf", "angle": "deg", "mass": "lb", "area": "in2", "volume": "ft3",
                "power": "hp", "torque": "lbf ft", "temperature": "degF",
                "damping": "lbf s/in", "stiffness": "lbf/in", "inertia": "lb ft2"}


def kind_of_unit(unit: str) -> str | None:
    for kind in units.KINDS:
        if unit in units.units_of(kind):
            return kind
    return None


def quantity(value) -> tuple[float, str] | None:
    """``(number, unit)`` of a quantity string with a known unit, else None."""
    if not isinstance(value, str):
        return None
    try:
        q = units._parse_text(value, "value")
    except ValueError:
        return None
    return (q.value, q.unit) if q.unit and kind_of_unit(q.unit) else None


def _scaled(value, factor: float):
    """``value`` (a quantity string, a number, or a list of them) times ``factor``; None
    when it has no number."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int):
        return int(value * factor) if abs(factor) >= 1 or factor == -1 else value * factor
    if isinstance(value, float):
        return value * factor
    if isinstance(value, list):
        out = [_scaled(v, factor) for v in value]
        return None if all(o is None for o in out) else [
            o if o is not None else v for o, v in zip(out, value)]
    q = quantity(value)
    if q is None:
        return None
    return f"{q[0] * factor!r} {q[1]}"


def _magnitude(value) -> float:
    """The largest number in ``value`` (0 when it has none)."""
    if isinstance(value, bool):
        return 0.0
    if isinstance(value, (int, float)):
        return abs(float(value))
    if isinstance(value, list):
        return max((_magnitude(v) for v in value), default=0.0)
    q = quantity(value)
    return abs(q[0]) if q else 0.0


def _non_finite(value, text: str):
    """The number of ``value`` replaced by ``text`` (nan, inf, 1e999)."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return Raw(text)
    if isinstance(value, list):
        return [_non_finite(v, text) or v for v in value] if any(
            _non_finite(v, text) for v in value) else None
    q = quantity(value)
    return None if q is None else f"{text} {q[1]}"


def _wrong_types(value) -> list:
    """Values of a type the key never takes."""
    table = {"a": 1}
    if isinstance(value, str):      # (a pair of quantities is a lap's [head, crank])
        return [7, 2.5, True, [1, 2, 3], table]
    if isinstance(value, bool):
        return [7, "true", [True], table]
    if isinstance(value, int):
        return [2.5, True, "2", [2], table]
    if isinstance(value, float):
        return [True, f"{value}", [value], table]
    if isinstance(value, list):
        return [7, True, "a", table]
    return [7, "a", [1], True]  # a table


def _wrong_units(value, also: tuple[str, ...] = ()) -> list[str]:
    """The number of ``value`` with a unit of each other kind (but ``also``: kinds the
    key takes besides its own)."""
    q = quantity(value)
    if q is None:
        return []
    kind = kind_of_unit(q[1])
    return [f"{q[0]!r} {u}" for k, u in UNIT_OF_KIND.items() if k != kind and k not in also
            and u not in units.units_of(kind)]


#: Keys that take a quantity of a second kind: the Corliss gear's laps are arcs on the
#: valve face or the spindle angles that subtend them.
ALSO_KINDS = {("corliss", "valve_gear.steam_lap"): ("angle",),
              ("corliss", "valve_gear.exhaust_lap"): ("angle",)}


def mutations_of(value, also: tuple[str, ...] = ()) -> list[tuple[str, bool, object]]:
    """Every mutation of ``value``: ``(name, must_refuse, new_value)``; ``DELETE`` deletes.

    Refusal is required when no scene could take the new value: the wrong type, the
    wrong unit, a number that is not finite, or one 1e12 times a value that was not
    zero (no quantity of an engine spans twelve orders of magnitude).  A deletion, a
    tiny or negated value and a random string may be valid (a default, a zero lap, a
    negative lead, a title)."""
    out: list[tuple[str, bool, object]] = [("delete", False, DELETE)]
    out += [(f"type:{type(v).__name__}", True, v) for v in _wrong_types(value)]
    out += [("unit", True, v) for v in _wrong_units(value, also)]
    for text in ("nan", "inf", "-inf", "1e999"):
        v = _non_finite(value, text)
        if v is not None:
            out.append((f"non-finite:{text}", True, v))
    for name, factor in (("huge", 1e12), ("tiny", 1e-12), ("negative", -1.0)):
        v = _scaled(value, factor)
        if v is not None:
            out.append((name, name == "huge" and _magnitude(value) > 0.0, v))
    return out


def key_paths(data: dict) -> list[tuple[str, ...]]:
    """Every key of a scene as a path: ``("title",)``, ``("engine",)`` (the section),
    ``("engine", "bore")``."""
    paths = []
    for k, v in data.items():
        paths.append((k,))
        if isinstance(v, dict):
            paths += [(k, kk) for kk in v]
    return paths


def mutated(data: dict, path: tuple[str, ...], new) -> dict:
    out = {k: (dict(v) if isinstance(v, dict) else v) for k, v in data.items()}
    holder = out if len(path) == 1 else out[path[0]]
    if new is DELETE:
        del holder[path[-1]]
    else:
        holder[path[-1]] = new
    return out


# --- running the command line -------------------------------------------------------------

@contextlib.contextmanager
def time_limit(seconds: float):
    """Raise TimeoutError in the test if the block has not returned within ``seconds``
    (where the platform has an interval timer; the elapsed time is asserted anyway).
    The alarm repeats each second: one that lands in a callback whose exceptions are
    ignored (a garbage-collector hook) is followed by another."""
    if not hasattr(signal, "setitimer"):
        yield
        return

    def on_alarm(signum, frame):
        raise TimeoutError(f"no answer within {seconds} s")

    old = signal.signal(signal.SIGALRM, on_alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds, 1.0)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def run_cli(args: list[str], bound_s: float) -> tuple[int, str, str, float]:
    """``corliss ARGS`` in this process: exit code, stdout, stderr and wall time."""
    out, err = io.StringIO(), io.StringIO()
    t0 = time.perf_counter()
    with time_limit(bound_s), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = cli.main(args)
    return code, out.getvalue(), err.getvalue(), time.perf_counter() - t0


_NAMED = re.compile(r"^corliss: (\S+)(?: = | is missing:)", re.M)


def named_key(stderr: str) -> str | None:
    """The key an InputError message names."""
    m = _NAMED.search(stderr)
    return m.group(1) if m else None


def finite_tree(obj) -> bool:
    """Every number in a JSON tree finite (None is allowed: an event that never happens)."""
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return True
    if isinstance(obj, (int, float)):
        return math.isfinite(obj)
    if isinstance(obj, dict):
        return all(finite_tree(v) for v in obj.values())
    if isinstance(obj, list):
        return all(finite_tree(v) for v in obj)
    return False


# --- drawing mutated scenes ------------------------------------------------------------------

def value_at(data: dict, path: tuple[str, ...]):
    return data[path[0]] if len(path) == 1 else data[path[0]][path[1]]


#: The mutations a scene may take (a default, a zero lap, a negative lead).
MAYBE_VALID = ("delete", "tiny", "negative")


@st.composite
def mutated_scenes(draw, kinds: tuple[str, ...] | None = None):
    """``(scene name, key path, mutation name, must refuse, mutated scene dict)``, the
    mutation one of ``kinds`` if given (else any, or a random string)."""
    name = draw(st.sampled_from(tuple(SCENES)))
    data = DATA[name]
    path = draw(st.sampled_from(key_paths(data)))
    value = value_at(data, path)
    also = ALSO_KINDS.get((data["valve_gear"].get("type"), ".".join(path)), ())
    options = mutations_of(value, also) + [("garbage", None, None)]
    if kinds is not None:
        options = [m for m in options if m[0] in kinds] or [("delete", False, DELETE)]
    mname, must, new = draw(st.sampled_from(options))
    if mname == "garbage":
        new = draw(st.text(max_size=40))
        # a quantity or a number can be no string but its own form
        must = isinstance(value, (int, float)) or quantity(value) is not None
    return name, path, mname, must, mutated(data, path, new)


def check_answer(path: tuple[str, ...], mname: str, must: bool, code: int, err: str,
                 elapsed: float, bound_s: float, out_dir: Path | None = None) -> None:
    """The contract of an answer to a mutated scene (see the module's docstring)."""
    key = ".".join(path)
    # 4: a run that completed but failed physically (a negative card), files written
    assert code in (0, 2, 4), err
    assert "Traceback" not in err, err
    assert elapsed < bound_s, (key, mname, elapsed)
    if code == 2:
        named = named_key(err)
        assert named is not None, err                 # a message naming a key, not a crash
        if must:
            assert named == key, err                  # this value, so this key
        else:   # a deleted or legal-looking value may clash with a neighbour instead,
            # which the message names beside this key or its section
            assert key in err or re.search(rf"\b{path[0]}\b", err), err
        assert out_dir is None or not out_dir.exists() or not any(out_dir.iterdir())
    else:
        assert not must, f"{key} ({mname}) was accepted"


# --- the properties -------------------------------------------------------------------------

#: ``corliss events`` on a mutated scene: milliseconds each, so many (the bundled
#: scenes hold some 24,000 mutations besides the random strings).
EVENTS_EXAMPLES = 3000
#: ``corliss run`` on a mutated scene: an accepted one simulates (0.1 s steady, 0.5 to
#: 3 s for a governed transient's start and a fifth of a second).
RUN_EXAMPLES = 120
#: Files of random bytes: refused in a millisecond.
BYTES_EXAMPLES = 300
#: Valid scenes with their numbers scaled: a short run each (about 0.1 s).
VALID_EXAMPLES = 100

_SETTINGS = dict(derandomize=True, database=None, deadline=None,
                 suppress_health_check=[HealthCheck.too_slow])


def test_the_toml_writer_gives_back_every_bundled_scene():
    """The fuzzing writes its scenes with :func:`to_toml`; it must write every bundled
    scene so that TOML reads back the same tables, or the mutations would test the
    writer."""
    for name, data in DATA.items():
        assert tomllib.loads(to_toml(data)) == data, name


def test_every_kind_of_mutation_is_drawn_from_the_bundled_scenes():
    """The mutations the properties draw from include each kind the issue names, for
    steady and transient scenes alike (a guard against a harness that silently stopped
    mutating)."""
    kinds = set()
    for name in SCENES:
        for path in key_paths(DATA[name]):
            kinds |= {m.split(":")[0] for m, _, _ in mutations_of(value_at(DATA[name], path))}
    assert kinds == {"delete", "type", "unit", "non-finite", "huge", "tiny", "negative"}
    assert TRANSIENT and STEADY


@settings(max_examples=EVENTS_EXAMPLES, **_SETTINGS)
@given(mutated_scenes())
def test_mutated_scenes_are_answered_or_refused_naming_the_key_by_events(case):
    """``corliss events`` parses the whole scene and builds its gear (and governor)
    without simulating: every mutation is answered with finite events, or refused with
    exit 2 naming the key, before any work."""
    name, path, mname, must, data = case
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / f"{name}.toml"
        scene.write_text(to_toml(data), encoding="utf-8")
        code, out, err, elapsed = run_cli(["events", str(scene), "--json"], EVENTS_S)
    check_answer(path, mname, must, code, err, elapsed, EVENTS_S)
    if code == 0:
        assert finite_tree(json.loads(out)), out


@settings(max_examples=RUN_EXAMPLES, **_SETTINGS)
@given(st.one_of(mutated_scenes(), mutated_scenes(MAYBE_VALID)))
def test_mutated_scenes_are_run_or_refused_writing_nothing(case):
    """``corliss run`` on a mutated scene (two fast cycles, or a fifth of a second of a
    transient): results with a finite summary, or exit 2 naming the key and an empty
    output folder.  Half the draws are mutations a scene may take, so that many of
    the runs simulate."""
    name, path, mname, must, data = case
    extra = ["--duration", "0.2 s"] if name in TRANSIENT else ["--cycles", "2"]
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / f"{name}.toml"
        scene.write_text(to_toml(data), encoding="utf-8")
        out_dir = Path(tmp) / "out"
        code, out, err, elapsed = run_cli(["run", str(scene), "--out", str(out_dir),
                                           "--fidelity", "fast", "--no-plots", *extra], RUN_S)
        check_answer(path, mname, must, code, err, elapsed, RUN_S, out_dir)
        if code == 0:
            summary = json.loads((out_dir / f"{name}.summary.json").read_text())
            assert finite_tree(summary), summary


@settings(max_examples=BYTES_EXAMPLES, **_SETTINGS)
@given(st.binary(min_size=1, max_size=2000))
def test_a_file_of_random_bytes_is_refused_naming_the_scene(content):
    """Random bytes are no scene: refused with exit 2 naming ``scene`` (not UTF-8, not
    TOML), or, for the rare bytes that are TOML, the first section it lacks."""
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / "random.toml"
        scene.write_bytes(content)
        out_dir = Path(tmp) / "out"
        code, out, err, elapsed = run_cli(["run", str(scene), "--out", str(out_dir)], EVENTS_S)
        assert code == 2, err
        assert "Traceback" not in err
        assert named_key(err) in ("scene", *SECTIONS), err
        assert not out_dir.exists()
        assert elapsed < EVENTS_S


@settings(max_examples=BYTES_EXAMPLES, **_SETTINGS)
@given(st.sampled_from(tuple(SCENES)), st.floats(0.0, 1.0), st.integers(0, 40),
       st.binary(max_size=40))
def test_a_scene_with_random_bytes_spliced_in_is_answered_or_refused(name, where, cut,
                                                                     junk):
    """A bundled scene with ``cut`` bytes at a random place replaced by random bytes (a
    damaged file, a bad paste): the scene still reads (the damage fell in a comment), or
    is refused with exit 2 and a message naming a key or ``scene``, never a crash."""
    text = SCENES[name].read_bytes()
    at = int(where * len(text))
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / f"{name}.toml"
        scene.write_bytes(text[:at] + junk + text[at + cut:])
        code, out, err, elapsed = run_cli(["events", str(scene), "--json"], EVENTS_S)
    assert code in (0, 2), err
    assert "Traceback" not in err
    assert elapsed < EVENTS_S
    if code == 2:
        assert named_key(err) is not None, err
    else:
        assert finite_tree(json.loads(out)), out


# --- random valid scenes ------------------------------------------------------------------

#: Steady scenes whose numbers the valid-scene property scales: plain slide valves from
#: a 10 x 12 in high-speed engine to Marks's 32 x 48 in at 20 rpm, a twin with its steam
#: chest, and a locomotive's link motion.
VALID_BASES = ("default", "high-speed-condensing", "marks-32x48-stationary", "twin-90-degrees",
               "walschaerts-locomotive")
_POWER_OF_KIND = {"length": 1, "area": 2, "volume": 3}


def _scaled_quantity(value, factor: float, kinds=("length", "area", "volume")):
    """A quantity string scaled as a body ``factor`` times as large (lengths by the
    factor, areas by its square, volumes by its cube); other values as they are."""
    q = quantity(value)
    if q is None or kind_of_unit(q[1]) not in kinds:
        return value
    return f"{q[0] * factor ** _POWER_OF_KIND[kind_of_unit(q[1])]:.6g} {q[1]}"


@st.composite
def valid_scenes(draw):
    """A bundled steady scene made ``size`` times as large throughout (the engine, its
    gear and its chest: every proportion kept, so the gear still works), then its bore
    changed by up to a quarter, its speed by half, its supply's gauge pressure by -40 to
    +50 % and its clearance by half: engines of the period's proportions."""
    name = draw(st.sampled_from(VALID_BASES))
    data = {k: (dict(v) if isinstance(v, dict) else v) for k, v in DATA[name].items()}
    size = draw(st.floats(0.5, 2.0))
    for sec in ("engine", "valve_gear", "supply"):
        for k, v in data[sec].items():
            if k != "barometer":
                data[sec][k] = _scaled_quantity(v, size)
    eng = data["engine"]
    eng["bore"] = _scaled_quantity(eng["bore"], draw(st.floats(0.8, 1.25)), ("length",))
    speed, unit = quantity(data["run"]["speed"])
    data["run"]["speed"] = f"{speed * draw(st.floats(0.5, 1.5)):.6g} {unit}"
    p, unit = quantity(data["supply"]["pressure"])
    assert unit == "psig"
    data["supply"]["pressure"] = f"{p * draw(st.floats(0.6, 1.5)):.6g} {unit}"
    c = draw(st.floats(0.5, 1.5))
    eng["clearance"] = ([x * c for x in eng["clearance"]] if isinstance(eng["clearance"], list)
                        else eng["clearance"] * c)
    return name, data


@settings(max_examples=VALID_EXAMPLES, **_SETTINGS)
@given(valid_scenes())
def test_random_valid_scenes_run_to_finite_results(case):
    """Engines of the bundled scenes' proportions at other sizes, bores, speeds,
    pressures and clearances are accepted and run (three fast cycles) to a summary whose
    every number is finite, with steam through the engine and positive indicated power
    (steam above back pressure on a working gear does work)."""
    name, data = case
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / f"{name}.toml"
        scene.write_text(to_toml(data), encoding="utf-8")
        out_dir = Path(tmp) / "out"
        code, out, err, elapsed = run_cli(["run", str(scene), "--out", str(out_dir), "--cycles",
                                           "3", "--fidelity", "fast", "--no-plots"], RUN_S)
        assert code == 0, err
        summary = json.loads((out_dir / f"{name}.summary.json").read_text())
    assert finite_tree(summary), summary
    assert summary["steam_rate_kg_per_h"] > 0.0
    assert summary["indicated_power_W"] > 0.0
    assert elapsed < RUN_S
