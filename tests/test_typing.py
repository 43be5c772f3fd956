"""The package type-checks: mypy, configured in pyproject.toml, finds no error.

The package ships ``py.typed`` and says "Typing :: Typed"; this holds it to that for
every module outside the listed typing debt (``[[tool.mypy.overrides]]``), so new code
is typed and a module once cleaned stays clean.  mypy's cache (``.mypy_cache``) makes a
repeated run take seconds.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

pytest.importorskip("mypy")


def test_mypy_finds_no_error_in_the_package():
    p = subprocess.run([sys.executable, "-m", "mypy"], cwd=ROOT, capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "Success" in p.stdout
