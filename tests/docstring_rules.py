"""Which public callables lack numpydoc Parameters and Returns (issue 16).

Public: every name without a leading underscore defined in a corliss module whose dotted
path has no component with a leading underscore, and every such method or property of a
public class. Numba-compiled functions are checked through their Python function.

The rules are numpydoc's own validator (``numpydoc.validate``), restricted to the checks
that say a callable is documented:

- GL08: the object has a docstring;
- PR01 / PR02: every parameter is in Parameters (a class's constructor parameters in the
  class docstring), and nothing else is;
- RT01 / YD01: a function that returns or yields a value has a Returns or Yields section;

and one of ours: a parameter whose name ends in a unit suffix (``_m``, ``_Pa``, ...)
states that unit in brackets in its description.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import numpydoc.validate

CHECKS = ("GL08", "PR01", "PR02", "RT01", "YD01")
UNIT_SUFFIXES = ("_m", "_m2", "_m3", "_Pa", "_kPa", "_K", "_s", "_rad", "_kg", "_J", "_W",
                 "_N", "_Nm", "_rpm", "_Hz", "_deg", "_J_kg", "_kg_s", "_rad_s", "_m_s",
                 "_kg_m3", "_W_m2K")


def public_modules(package: str = "corliss") -> list[str]:
    """Dotted names of the package's public modules."""
    pkg = importlib.import_module(package)
    names = [package]
    for m in pkgutil.walk_packages(pkg.__path__, package + "."):
        if not any(part.startswith("_") for part in m.name.split(".")[1:]):
            names.append(m.name)
    return sorted(names)


def _defined_in(obj, module: str) -> bool:
    return getattr(getattr(obj, "py_func", obj), "__module__", None) == module


def public_callables(modules=None) -> list[str]:
    """Import paths of every public function, class, method and property."""
    out = []
    for name in modules or public_modules():
        mod = importlib.import_module(name)
        for attr, obj in vars(mod).items():
            if attr.startswith("_") or not _defined_in(obj, name):
                continue
            if inspect.isclass(obj):
                out.append(f"{name}.{attr}")
                for m, member in vars(obj).items():
                    if m.startswith("_"):
                        continue
                    if isinstance(member, (staticmethod, classmethod)):
                        member = member.__func__
                    if inspect.isfunction(member) or isinstance(member, property):
                        out.append(f"{name}.{attr}.{m}")
            elif inspect.isfunction(obj) or hasattr(obj, "py_func"):
                out.append(f"{name}.{attr}")
    return out


def _unit_problems(path: str, doc) -> list[str]:
    out = []
    for p in doc["Parameters"]:
        for pname in p.name.replace("*", "").split(","):
            pname = pname.strip()
            if pname.endswith(UNIT_SUFFIXES) and "[" not in " ".join(p.desc) + p.type:
                out.append(f"{path}: parameter {pname} names a unit; say it in brackets")
    return out


def problems(path: str) -> list[str]:
    """What the callable at ``path`` lacks, one line each (empty when documented)."""
    obj = numpydoc.validate.Validator._load_obj(path)
    if isinstance(obj, property):
        obj = obj.fget
    if getattr(obj, "__doc__", None) is None and inspect.getdoc(obj):
        # a method documented by the class it overrides (Sphinx shows that docstring);
        # the base class's own entry is checked where it is defined
        return []
    res = numpydoc.validate.validate(path)
    out = [f"{path}: {code} {msg}" for code, msg in res["errors"] if code in CHECKS]
    if not out and res.get("docstring"):
        from numpydoc.docscrape import NumpyDocString
        try:
            out += _unit_problems(path, NumpyDocString(res["docstring"]))
        except Exception as exc:  # a docstring numpydoc cannot read
            out.append(f"{path}: unreadable docstring ({exc})")
    return out


def all_problems(modules=None) -> list[str]:
    """Every problem of every public callable of ``modules`` (default: all)."""
    out = []
    for path in public_callables(modules):
        out += problems(path)
    return out


if __name__ == "__main__":
    import sys
    mods = sys.argv[1:] or None
    if mods:
        mods = [m for m in public_modules() if any(m == a or m.startswith(a + ".") for a in mods)]
    found = all_problems(mods)
    print("\n".join(found))
    print(f"{len(found)} problems in {len(public_callables(mods))} public callables",
          file=sys.stderr)
