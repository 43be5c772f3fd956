"""The kernels' disk cache is keyed on every source they inline, computed, not bumped.

Numba keys a compiled function's cache on its own file; a kernel inlining a function of
another module (the port flow, the steam table's lookup, the balances) kept its old
machine code when that function changed, unless someone remembered to bump a revision
number.  :mod:`corliss.engine.kernels.compiled` keys each kernel's cache on the content
of every module its compiled code can reach instead.  These tests hold that:

- every compiled function a kernel calls, followed through the functions it calls in
  turn, is defined in a module its key hashes;
- changing the source of an inlined function (in a copy of the package) changes the
  key of every kernel module that can inline it, and not of one that cannot;
- every compiled function of the kernels carries that key in its cache.
"""

from __future__ import annotations

import importlib
import pkgutil
import shutil

import pytest
from numba.core.registry import CPUDispatcher

import corliss.engine.kernels as kernels
from corliss.engine.kernels import compiled


def _kernel_modules():
    return [importlib.import_module(m.name)
            for m in pkgutil.iter_modules(kernels.__path__, kernels.__name__ + ".")]


def _dispatchers(module):
    return [v for v in vars(module).values()
            if isinstance(v, CPUDispatcher) and v.py_func.__module__ == module.__name__]


def _reached(dispatcher) -> set[str]:
    """Modules defining the compiled functions ``dispatcher`` can call, transitively
    (read from the globals its Python source names)."""
    seen, todo, mods = set(), [dispatcher], set()
    while todo:
        d = todo.pop()
        if id(d) in seen:
            continue
        seen.add(id(d))
        mods.add(d.py_func.__module__)
        names = d.py_func.__code__.co_names
        for code in d.py_func.__code__.co_consts:      # nested functions' names
            names += getattr(code, "co_names", ())
        for name in names:
            v = d.py_func.__globals__.get(name)
            if isinstance(v, CPUDispatcher):
                todo.append(v)
    return mods


def test_every_inlined_function_is_in_its_kernels_key():
    missing = []
    for module in _kernel_modules():
        hashed = set(compiled.inlined_modules(module.__name__))
        for d in _dispatchers(module):
            for m in _reached(d) - hashed:
                missing.append(f"{d.py_func.__qualname__} ({module.__name__}) reaches {m}")
    assert not missing, "\n".join(missing)
    # the reach is followed: the right-hand side reaches the port flow and the table
    from corliss.engine.kernels.balances import rhs
    assert {"corliss.thermo.orifice", "corliss.thermo.steam_table",
            "corliss.engine.kernels.mechanism"} <= _reached(rhs)


@pytest.fixture
def package_copy(tmp_path):
    root = tmp_path / "corliss"
    shutil.copytree(compiled.PACKAGE_ROOT, root,
                    ignore=shutil.ignore_patterns("__pycache__", "*.npz"))
    return root


def test_changing_an_inlined_function_changes_the_key(package_copy):
    before = {m: compiled.source_key(m, package_copy)
              for m in ("corliss.engine.kernels.balances", "corliss.engine.kernels.rosenbrock",
                        "corliss.engine.kernels.tableaus")}
    orifice = package_copy / "thermo" / "orifice.py"
    text = orifice.read_text()
    assert "def port_flow(" in text
    # one operation of the port flow changed: a kernel inlining it must recompile
    orifice.write_text(text.replace("def port_flow(", "def port_flow(  ", 1))
    compiled.forget()
    after = {m: compiled.source_key(m, package_copy) for m in before}
    assert after["corliss.engine.kernels.balances"] != before["corliss.engine.kernels.balances"]
    assert after["corliss.engine.kernels.rosenbrock"] != before[
        "corliss.engine.kernels.rosenbrock"]
    # the tableaus' arithmetic inlines no port flow: its cache stays
    assert after["corliss.engine.kernels.tableaus"] == before["corliss.engine.kernels.tableaus"]


def test_every_kernel_carries_its_key():
    for module in _kernel_modules():
        key = compiled.source_key(module.__name__)
        for d in _dispatchers(module):
            assert d._cache._cache_file._source_stamp == key, d.py_func.__qualname__
