"""The kernels' compiler: numba's ``njit``, its disk cache keyed on every source it inlines.

Numba keys a compiled function's disk cache on the content of the file that defines it
and on the function's own bytecode, not on the compiled functions it calls or inlines
from other modules: a kernel that inlines :func:`corliss.thermo.orifice.port_flow` or
:func:`corliss.engine.kernels.balances.balances` would load its old machine code from
the cache after either changed.  :func:`njit` here compiles as numba's does, and gives
the function's cache the key :func:`source_key` of its module instead of that file's
hash: a hash of the content of the module and of every module of the package it
imports, directly or through another, that defines compiled code.  A change to any
of them recompiles the kernels that can inline it, and nothing else
(tests/test_kernel_cache_key.py holds both).

The key is read from the package's own files: one pass over the import statements of
the modules of the kernels' closure (a few milliseconds, once per process).
"""

from __future__ import annotations

import functools
import hashlib
import logging
import re
from pathlib import Path
from typing import Any, Callable, Generic, ParamSpec, TypeVar

import numba

log = logging.getLogger(__name__)

_P = ParamSpec("_P")
_R = TypeVar("_R")


class Kernel(Generic[_P, _R]):
    """What :func:`njit` returns, for the type checker: numba's dispatcher, called as
    the function it compiled, with the attributes of it the package reads.

    Never made: at run time the kernels are numba's dispatchers, called with the
    compiled function's arguments and returning its value.
    """

    #: The compiled function's name.
    __name__: str
    #: The Python function compiled (run as Python).
    py_func: Callable[_P, _R]
    #: numba's disk cache of the function (a private attribute of numba's).
    _cache: Any

    def __call__(self, *args: _P.args, **kwargs: _P.kwargs) -> _R:  # pragma: no cover
        raise NotImplementedError

#: The folder of the package ``corliss``.
PACKAGE_ROOT = Path(__file__).resolve().parents[2]

_IMPORT = re.compile(r"^[ \t]*(?:from[ \t]+(corliss(?:\.\w+)*)[ \t]+import[ \t]+"
                     r"(?:\(([^)]*)\)|([\w \t,]+))|import[ \t]+(corliss(?:\.\w+)*))", re.M)
#: What marks a module as defining compiled code (its functions may be inlined).
_COMPILED = re.compile(r"\bnjit\b")
#: Modules whose constants the kernels compile in without defining compiled code
#: (the named rows, columns and model codes of the kernels' data): hashed all the same.
_COMPILED_IN = ("corliss.engine.kernels.data",)


def module_file(module: str, root: Path = PACKAGE_ROOT) -> Path | None:
    """The source file of a module of the package, or None when there is none.

    Parameters
    ----------
    module : str
        Dotted name, ``"corliss.thermo.orifice"``.
    root : pathlib.Path
        The package's folder (``corliss/``).

    Returns
    -------
    pathlib.Path or None
        ``root/thermo/orifice.py`` or ``root/thermo/__init__.py``.
    """
    parts = module.split(".")[1:]
    base = root.joinpath(*parts)
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


@functools.lru_cache(maxsize=None)
def _read(module: str, root: Path) -> tuple[frozenset, bool]:
    """The package's modules ``module`` imports, and whether it defines compiled code
    (nothing and False for a module without a source file)."""
    path = module_file(module, root)
    if path is None:
        return frozenset(), False
    text = path.read_text(encoding="utf-8")
    return (frozenset(_imported(module, text, root)),
            bool(_COMPILED.search(text)) or module in _COMPILED_IN)


def _imported(module: str, text: str, root: Path) -> set[str]:
    found = set()
    for m in _IMPORT.finditer(text):
        target = m.group(1) or m.group(4)
        found.add(target)
        for name in (m.group(2) or m.group(3) or "").replace("\n", " ").split(","):
            name = name.strip()
            if name and module_file(f"{target}.{name}", root) is not None:
                found.add(f"{target}.{name}")        # "from corliss.x import module"
    return {t for t in found if module_file(t, root) is not None and t != module}


def inlined_modules(module: str, root: Path = PACKAGE_ROOT) -> list[str]:
    """The modules whose compiled code ``module``'s kernels may call or inline.

    ``module`` itself and every module of the package it imports, directly or through
    another, that defines compiled code (names ``njit``) or constants compiled in
    (:data:`_COMPILED_IN`), sorted.

    Parameters
    ----------
    module : str
        Dotted name of a kernels module.
    root : pathlib.Path
        The package's folder.

    Returns
    -------
    list of str
        Dotted names.
    """
    seen, todo = set(), [module]
    while todo:
        m = todo.pop()
        if m in seen:
            continue
        seen.add(m)
        todo.extend(_read(m, root)[0] - seen)
    return sorted(m for m in seen if m == module or _read(m, root)[1])


@functools.lru_cache(maxsize=None)
def _key(module: str, root: Path) -> str:
    h = hashlib.sha256()
    for m in inlined_modules(module, root):
        path = module_file(m, root)
        h.update(m.encode() + b"\0" + (path.read_bytes() if path else b"") + b"\0")
    return h.hexdigest()


def forget() -> None:
    """Drop the keys and import lists read so far (a test that edits a copy calls it)."""
    _key.cache_clear()
    _read.cache_clear()


def source_key(module: str, root: Path = PACKAGE_ROOT) -> str:
    """The cache key of ``module``'s compiled functions: a hash of what they may inline.

    Parameters
    ----------
    module : str
        Dotted name of a kernels module.
    root : pathlib.Path
        The package's folder (a copy of it in a test).

    Returns
    -------
    str
        SHA-256 (hex) over the names and content of :func:`inlined_modules`.
    """
    return _key(module, Path(root))


def stamp(dispatcher) -> bool:
    """Key a compiled function's disk cache on :func:`source_key` of its module.

    Parameters
    ----------
    dispatcher : numba Dispatcher
        A function compiled with ``cache=True``.

    Returns
    -------
    bool
        Whether the key was set; False where this numba keeps its cache otherwise (the
        internals read here are gone), and the file's own hash keys it as before.
    """
    cache_file = getattr(getattr(dispatcher, "_cache", None), "_cache_file", None)
    if cache_file is None or not hasattr(cache_file, "_source_stamp"):
        log.debug("numba's cache of %s keeps its own key", dispatcher)
        return False
    cache_file._source_stamp = source_key(dispatcher.py_func.__module__)
    return True


def njit(**options: Any) -> Callable[[Callable[_P, _R]], Kernel[_P, _R]]:
    """numba's ``njit(**options)``, the cache (``cache=True``) keyed by :func:`stamp`.

    Typed as returning a :class:`Kernel` of the function it compiles: numba's dispatcher
    takes the same arguments, so a type checker checks the kernels' calls against their
    signatures (numba itself is untyped here).

    Parameters
    ----------
    **options
        numba's options (``cache``, ``inline``, ``_nrt``, ...).

    Returns
    -------
    callable
        The decorator.
    """
    def decorate(func: Callable[_P, _R]) -> Kernel[_P, _R]:
        dispatcher: Kernel[_P, _R] = numba.njit(**options)(func)
        if options.get("cache"):
            stamp(dispatcher)
        return dispatcher
    return decorate
