"""The package's layers point only down (DESIGN: thermo, valves and governors know no
engine; the engine knows no results, plots or command line), no module imports a
private name of another, and the import graph has no circle.

The graph is read from the package's own source with ``ast``: every ``import`` and
``from ... import`` anywhere in a module, inside functions too (an import hidden in a
function to dodge a circle is still an edge).
"""

from __future__ import annotations

import ast
from pathlib import Path

import corliss

ROOT = Path(corliss.__file__).parent

#: Layer of each module by its dotted name's prefix (most specific first), bottom up.
#: A module may import its own layer and the layers below it, never one above.
LAYERS = [
    ("corliss.errors", 0), ("corliss.logs", 0), ("corliss.progress", 0), ("corliss.versions", 0),
    ("corliss.keys", 0), ("corliss.frames", 0),
    ("corliss.thermo", 1), ("corliss.valves", 1), ("corliss.governors", 1),
    ("corliss.engine", 2),
    ("corliss.scene", 3), ("corliss.studies", 3), ("corliss.fitting", 3),
    ("corliss.plot", 4),
    ("corliss.files", 5), ("corliss.workbench", 5),
    ("corliss.cli", 6), ("corliss.__main__", 6),
]
#: The three physics packages of layer 1 are independent of each other.
INDEPENDENT = {"corliss.thermo", "corliss.valves", "corliss.governors"}


def _layer(module: str) -> int | None:
    if module == "corliss":
        return None          # the package's front door may import anything
    for prefix, layer in LAYERS:
        if module == prefix or module.startswith(prefix + "."):
            return layer
    raise AssertionError(f"module {module} has no layer in the test's table")


def _package(module: str) -> str:
    return ".".join(module.split(".")[:2])


def _modules() -> dict[str, Path]:
    out = {}
    for path in ROOT.rglob("*.py"):
        rel = path.relative_to(ROOT.parent).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def _imports(module: str, path: Path) -> list[tuple[str, str | None, int]]:
    """(imported module, imported name or None, line) of every corliss import."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(a.name, None, node.lineno) for a in node.names
                      if a.name.split(".")[0] == "corliss"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "corliss":
                continue
            for a in node.names:
                found.append((target, a.name, node.lineno))
    return found


def _edges():
    mods = _modules()
    edges = []
    for mod, path in mods.items():
        for target, name, line in _imports(mod, path):
            # "from corliss.engine import crank_effort" imports a module
            sub = f"{target}.{name}" if name else None
            dest = sub if sub in mods else target
            edges.append((mod, dest, name if dest == target else None, line))
    return mods, edges


def test_no_import_crosses_a_layer_boundary_upwards():
    _, edges = _edges()
    wrong = []
    for src, dest, _, line in edges:
        ls, ld = _layer(src), _layer(dest)
        if ls is None or ld is None:
            continue
        if ld > ls:
            wrong.append(f"{src}:{line} imports {dest} (layer {ld} above {ls})")
        ps, pd_ = _package(src), _package(dest)
        if ps in INDEPENDENT and pd_ in INDEPENDENT and ps != pd_:
            wrong.append(f"{src}:{line} imports {dest} ({ps} and {pd_} are independent)")
    assert not wrong, "\n".join(wrong)


def _in_kernels(module: str) -> bool:
    """Whether ``module`` is one of the compiled kernels' room, whose modules share their
    private helpers (one compiled unit split by concern; its callers outside use the
    public names)."""
    return module.startswith("corliss.engine.kernels.")


def test_no_module_imports_a_private_name_of_another():
    _, edges = _edges()
    wrong = [f"{src}:{line} imports {name} from {dest}" for src, dest, name, line in edges
             if name and name.startswith("_") and not name.endswith("__") and dest != src
             and not (_in_kernels(src) and _in_kernels(dest))]
    assert not wrong, "\n".join(wrong)


def test_the_import_graph_has_no_circle():
    mods, edges = _edges()
    graph: dict[str, set[str]] = {m: set() for m in mods}
    for src, dest, _, _ in edges:
        if dest in graph and dest != src and src != "corliss":
            graph[src].add(dest)
    # a module imports its package's __init__ implicitly; only explicit edges count
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(m: str) -> list[str] | None:
        state[m] = 1
        stack.append(m)
        for n in sorted(graph[m]):
            if state.get(n) == 1:
                return stack[stack.index(n):] + [n]
            if n not in state:
                cyc = visit(n)
                if cyc:
                    return cyc
        stack.pop()
        state[m] = 2
        return None

    for m in sorted(graph):
        if m not in state:
            cycle = visit(m)
            assert cycle is None, "import circle: " + " -> ".join(cycle)


def test_the_graph_reader_sees_a_hidden_upward_import(tmp_path):
    """The reader itself: an import inside a function is an edge like any other."""
    src = tmp_path / "mod.py"
    src.write_text("def f():\n    from corliss.files.run_output import write\n    return write\n")
    assert _imports("corliss.engine.mod", src) == [("corliss.files.run_output", "write", 2)]


#: What the compiled kernels (:mod:`corliss.engine.kernels`) may import of the package:
#: each other, the steam properties and port flow they inline, and the error and log
#: helpers; never the model, the runners or the results of the engine around them.
KERNEL_ROOM = ("corliss.engine.kernels", "corliss.thermo", "corliss.errors", "corliss.logs")


def test_the_kernels_room_knows_nothing_of_the_engine_around_it():
    _, edges = _edges()
    wrong = [f"{src}:{line} imports {dest}" for src, dest, _, line in edges
             if (src == "corliss.engine.kernels" or _in_kernels(src))
             and not any(dest == r or dest.startswith(r + ".") for r in KERNEL_ROOM)]
    assert not wrong, "\n".join(wrong)
