"""The kernels' data is read by name, their functions take few arguments, and the named
structures come back from numba's cache.

The network, the steam table and the governed loop's tables reach the compiled kernels
as :class:`typing.NamedTuple` s (:class:`corliss.engine.kernels.data.NetworkArrays`,
:class:`~corliss.engine.kernels.data.LoopArrays`,
:class:`corliss.thermo.steam_table.TableArrays`).  A newcomer reading ``net.heat``
knows what it is; reading ``net[19]`` they had to count.  These tests hold that:

- no kernel tuple is read by an integer index (``net[19]``, ``tables.tr[7]``,
  ``tab[15]``) in the package, the benchmarks or the tests, outside the module that
  defines it, and the reader sees such a read when one is planted;
- no row or column of the kernels' 2-D data (node properties, wall-heat rows,
  geometry, the trip gear's tables) is read at a literal number in the engine: the
  wall-heat row's columns mean other things under each model code (``WALL_*``);
- no compiled function takes more than :data:`MAX_ARGUMENTS` arguments (the step
  loops take their control, physics, tableau and scratch as named structures: the
  ode23s loop took 35);
- the step loops shared by the steady cycle and the loop's turn guard each kind's code
  by that kind's own None-able marker, which numba prunes in the other's version;
- a second process loads kernels typed on each structure from numba's disk cache
  without compiling them again (a class numba could not find again by its module and
  name would be compiled afresh in every process).
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import corliss

ROOT = Path(corliss.__file__).resolve().parent.parent
#: Where kernel tuples are read: the package, its benchmarks and its tests.
SCANNED = (ROOT / "corliss", ROOT / "benchmarks", ROOT / "tests")
#: The names a kernel tuple goes by, as a variable or an attribute (``tables.tr``).
TUPLE_NAMES = frozenset({"net", "tab", "tr"})
#: Modules that define a kernel tuple (they may index their own).
DEFINING = ("corliss/engine/kernels/data.py", "corliss/thermo/steam_table.py")
#: Modules whose ``tr`` is something else (a point of the animation's drawing).
OTHER_MEANING = ("corliss/plot/animation.py",)
#: The most arguments a compiled function takes ("about a dozen", issue 26).
MAX_ARGUMENTS = 12
#: Compiled functions allowed over it, with their count: the governor's equation of
#: motion, thirteen scalars (its state, its tables' values at z, its constants, the
#: shaft's speed and acceleration), called alike from the compiled loop and from Python;
#: the Rosenbrock step loop, whose four version markers (``pair``, ``finite``,
#: ``cycle``, ``turn``) must be plain arguments: numba prunes a branch on ``x is None``
#: only for an argument, not for a field of a structure, and without the pruning a
#: turn's first run compiled the steady cycle's right-hand side and Jacobians too.
LONG_ARGUMENT_LISTS = {"corliss/engine/kernels/governor.py:governor_motion": 13,
                       "corliss/engine/kernels/rosenbrock.py:_ros_steps": 13}


def positional_reads(source: str) -> list[str]:
    """The integer-index reads of a kernel tuple in ``source``, as ``line: text``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.Subscript):
            continue
        v = node.value
        name = v.id if isinstance(v, ast.Name) else v.attr if isinstance(v, ast.Attribute) else None
        s = node.slice
        if (name in TUPLE_NAMES and isinstance(s, ast.Constant) and type(s.value) is int):
            found.append(f"{node.lineno}: {ast.unparse(node)}")
    return found


def _files():
    for top in SCANNED:
        for path in sorted(top.rglob("*.py")):
            rel = path.relative_to(ROOT).as_posix()
            if rel not in DEFINING and rel not in OTHER_MEANING:
                yield rel, path


def test_no_kernel_tuple_is_read_by_position():
    reads = [f"{rel}:{r}" for rel, path in _files()
             for r in positional_reads(path.read_text(encoding="utf-8"))]
    assert not reads, "read the field by name instead:\n" + "\n".join(reads)


#: The kernels' 2-D data whose rows or columns have names (``PR_*``, ``H_*``, ``GEO_*``,
#: ``TRIP_*``/``TS_*``, ``PERF_*``): node properties, wall-heat rows, geometry, the trip
#: gear's tables, the perfect tier's parameters.
NAMED_ROWS = frozenset({"pr", "heat", "node_heat", "geo", "trip", "perf"})


def literal_rows(source: str) -> list[str]:
    """Reads of :data:`NAMED_ROWS` data at a literal row or column (``heat[i, 8]``,
    ``pr[4, i]``, ``node_heat[i][9]``, ``perf[0]``), as ``line: text``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.Subscript):
            continue
        v = node.value
        if isinstance(v, ast.Subscript):            # node_heat[i][9]
            v = v.value
        name = v.id if isinstance(v, ast.Name) else v.attr if isinstance(v, ast.Attribute) else None
        if name not in NAMED_ROWS:
            continue
        s = node.slice
        idx = s.elts if isinstance(s, ast.Tuple) else [s]
        if any(isinstance(e, ast.Constant) and type(e.value) is int for e in idx):
            found.append(f"{node.lineno}: {ast.unparse(node)}")
    return found


def test_no_row_or_column_of_the_kernels_data_is_a_literal():
    """Rows and columns by name: the wall-heat row's columns mean other things under
    each model code, which a literal hid."""
    reads = [f"{rel}:{r}" for rel, path in _files() if rel.startswith("corliss/engine/")
             for r in literal_rows(path.read_text(encoding="utf-8"))]
    assert not reads, "name the row or column (corliss.engine.kernels.data):\n" + "\n".join(reads)


def test_the_reader_sees_a_literal_row():
    planted = "a = heat[i, 8]\nb = pr[4, i]\nc = net.node_heat[i][9]\nd = heat[i, H_MODEL]\n"
    assert [r.split(": ")[1] for r in literal_rows(planted)] == [
        "heat[i, 8]", "pr[4, i]", "net.node_heat[i][9]"]


def test_the_reader_sees_a_positional_read():
    """Planted reads are found (each form the code used), a named one is not."""
    planted = "heat = net[19]\nsc = tables.tr[0]\nk = tab[15]\nok = net.heat[0, 1]\n"
    assert [r.split(": ")[1] for r in positional_reads(planted)] == [
        "net[19]", "tables.tr[0]", "tab[15]"]


def _compiled_functions():
    """(module path, name, argument count) of every ``@njit`` function in the package."""
    for path in sorted((ROOT / "corliss").rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef) and any(
                    "njit" in ast.unparse(d) for d in node.decorator_list):
                a = node.args
                n = len(a.posonlyargs) + len(a.args) + len(a.kwonlyargs)
                yield path.relative_to(ROOT).as_posix(), node.name, n


def test_no_compiled_function_takes_more_than_a_dozen_arguments():
    over = {f"{rel}:{name}": n for rel, name, n in _compiled_functions() if n > MAX_ARGUMENTS}
    assert over == LONG_ARGUMENT_LISTS, (
        "bundle the arguments into the kernels' named structures "
        "(corliss.engine.kernels.data); over the limit now: " + repr(over))



#: The version markers of the step loops shared by the steady cycle and the loop's
#: turn: ``cycle`` is None in a turn's version, ``turn`` in a cycle's.
KIND_MARKERS = frozenset({"cycle", "turn"})


def unprunable_kind_tests(source: str) -> list[str]:
    """The tests of a kind marker numba cannot prune in every version, as ``line: text``:
    any but ``if <marker> is not None:`` with no ``else`` (nor ``elif``)."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, (ast.If, ast.IfExp)):
            continue
        t = node.test
        if not (isinstance(t, ast.Compare) and isinstance(t.left, ast.Name)
                and t.left.id in KIND_MARKERS and len(t.ops) == 1
                and isinstance(t.comparators[0], ast.Constant)
                and t.comparators[0].value is None):
            continue
        if not isinstance(t.ops[0], ast.IsNot) or isinstance(node, ast.IfExp) or node.orelse:
            found.append(f"{node.lineno}: {ast.unparse(t)}")
    return found


def test_each_kind_of_step_loop_is_guarded_by_its_own_marker():
    """numba prunes a branch on ``x is None`` before typing only in the version where
    ``x`` is None; where ``x`` is a tuple it types both branches and compiles all they
    call.  Under ``if turn is None: <cycle> else: <turn>`` a first transient run
    compiled the steady cycle's right-hand side and Jacobians it never runs (37.4 s
    against 21.7 s for the ``fast`` preset, docs/accuracy.md).  So the cycle's code is
    guarded by ``cycle is not None`` and the turn's by ``turn is not None``, alone."""
    bad = [f"{rel}:{r}" for rel, path in _files() if rel.startswith("corliss/engine/kernels/")
           for r in unprunable_kind_tests(path.read_text(encoding="utf-8"))]
    assert not bad, ("guard a kind's code by its own marker, 'if cycle is not None:' or "
                     "'if turn is not None:', with no else:\n" + "\n".join(bad))


def test_the_reader_sees_an_unprunable_kind_test():
    planted = ("if turn is None:\n    a = 1\n"
               "if turn is not None:\n    a = 2\nelse:\n    a = 3\n"
               "h = 1e-12 if cycle is None else 1e-10\n"
               "if cycle is not None:\n    a = 4\n"
               "if pair is None:\n    a = 5\n")
    assert [r.split(": ")[1] for r in unprunable_kind_tests(planted)] == [
        "turn is None", "turn is not None", "cycle is None"]

CHILD = textwrap.dedent(r"""
    import json, sys
    from pathlib import Path
    import numpy as np
    from numba.core import event
    import corliss
    from corliss.engine.kernels.loop import governed_areas
    from corliss.engine.kernels.mechanism import port_areas
    from corliss.engine.model import build_gear, build_network, geometry_of, reservoir_states
    from corliss.engine.transient import build_tables
    from corliss.thermo.steam import make_steam
    from corliss.thermo.steam_table import lookup
    from corliss.valves import tabulate

    compiled = []
    class Seen(event.Listener):
        def on_start(self, ev):
            compiled.append(ev.data["dispatcher"].py_func.__qualname__)
        def on_end(self, ev):
            pass
    scene = corliss.load_scene(sys.argv[1])
    steam = make_steam("table")
    chest, exhaust = reservoir_states(scene, steam)
    geo = geometry_of(scene)
    gear = build_gear(scene)
    network = build_network(scene, geo, tabulate(gear, 90), steam, chest, exhaust)
    tables = build_tables(scene, network, gear, geo)
    net, tab = network.arrays(), steam.table.arrays()
    pa = np.zeros((net.port_npts.shape[0], 4))
    with event.install_listener("numba:compile", Seen()):
        port_areas(0.3, net, pa)
        governed_areas(0.3, 0.5, 8.0, net, tables.tr, pa)
        lookup(tab, 5.0, 2.5e6)
    hits = {f.__name__: sum(f.stats.cache_hits.values())
            for f in (port_areas, governed_areas, lookup)}
    print(json.dumps({"compiled": compiled, "hits": hits,
                      "types": [type(net).__name__, type(tables.tr).__name__,
                                type(tab).__name__]}))
""")


def _run_child(cache: Path) -> dict:
    import json
    scene = ROOT / "scenes" / "corliss-governor.toml"
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    out = subprocess.run([sys.executable, "-c", CHILD, str(scene)], env=env, check=True,
                         capture_output=True, text=True, cwd=ROOT)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_a_second_process_loads_the_named_structures_from_the_cache(tmp_path):
    """The first process compiles the kernels for the three structures into an empty
    cache; the second compiles nothing and reads each from the cache."""
    first = _run_child(tmp_path)
    assert first["types"] == ["NetworkArrays", "LoopArrays", "TableArrays"]
    assert "lookup" in first["compiled"]          # the cache was empty: it did compile
    second = _run_child(tmp_path)
    assert second["compiled"] == []
    assert all(n >= 1 for n in second["hits"].values()), second["hits"]
