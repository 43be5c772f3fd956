"""The wheel ``pip install .`` builds holds the whole library (issue 16: "``pip install .``
builds a wheel with the scenes and any package data").

The packages are listed by hand in pyproject.toml, so a new subpackage left off the list
would install from a source checkout (``pip install -e``) and be missing from the wheel
a user installs; these tests build the wheel from a copy of the sources and read it.
"""

from __future__ import annotations

import email
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import corliss

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> zipfile.ZipFile:
    src = tmp_path_factory.mktemp("src")
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy(ROOT / name, src / name)
    ignore = shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc", "*.pyc")
    for name in ("corliss", "scenes"):
        shutil.copytree(ROOT / name, src / name, ignore=ignore)
    out = tmp_path_factory.mktemp("dist")
    proc = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w",
                           str(out), str(src)], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-3000:]
    (path,) = out.glob("corliss-*.whl")
    with zipfile.ZipFile(path) as z:
        yield z


def test_the_wheel_holds_every_module_scene_and_data_file(wheel):
    names = set(wheel.namelist())
    package = ROOT / "corliss"
    expected = {f"corliss/{p.relative_to(package).as_posix()}" for p in package.rglob("*")
                if p.suffix in (".py", ".npz", ".typed") and "__pycache__" not in p.parts}
    expected |= {f"corliss/scenes/{p.name}" for p in (ROOT / "scenes").glob("*.toml")}
    missing = sorted(expected - names)
    assert not missing, f"left out of the wheel (pyproject.toml's packages?): {missing}"
    assert len([n for n in names if n.startswith("corliss/scenes/")]) >= 20


def test_the_wheel_carries_its_version_licence_and_classifiers(wheel):
    (meta_name,) = [n for n in wheel.namelist() if n.endswith(".dist-info/METADATA")]
    meta = email.message_from_bytes(wheel.read(meta_name))
    assert meta["Version"] == corliss.__version__      # single-sourced
    # the licence as a PEP 639 SPDX expression (the classifier and the table form are
    # deprecated by setuptools, an error from 2027-02-18)
    assert meta["License-Expression"] == "MIT"
    assert meta.get_all("License-File") == ["LICENSE"]
    assert not [c for c in meta.get_all("Classifier") if c.startswith("License ::")]
    assert any(n.endswith(".dist-info/LICENSE") or "/licenses/LICENSE" in n
               for n in wheel.namelist())
