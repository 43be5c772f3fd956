"""The package type-checks: mypy, configured in pyproject.toml, finds no error.

The package ships ``py.typed`` and says "Typing :: Typed"; this holds it to that for
every module: no module of the package is excused (no ``ignore_errors`` override in
``pyproject.toml``; only the untyped scientific libraries are skipped).  mypy's cache
(``.mypy_cache``) makes a repeated run take seconds.
"""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

pytest.importorskip("mypy")


def test_mypy_finds_no_error_in_the_package():
    p = subprocess.run([sys.executable, "-m", "mypy"], cwd=ROOT, capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "Success" in p.stdout


def test_no_module_of_the_package_is_excused():
    """The typing debt is paid: no ``[[tool.mypy.overrides]]`` table turns mypy's errors
    off, so every module of the package is held to the check above."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    excused = [o["module"] for o in config["tool"]["mypy"].get("overrides", [])
               if o.get("ignore_errors")]
    assert not excused, f"modules excused from mypy: {excused}"
