"""The package's front door: ``import corliss`` is light, every name it offers is there
when asked for, and the library leaves the user's matplotlib backend alone.

Each check that counts modules runs in a fresh interpreter (``sys.modules`` of the test
process holds whatever earlier tests imported).
"""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from pathlib import Path

import corliss

ROOT = Path(corliss.__file__).parent

#: The most of the package's own modules ``import corliss`` may load (issue 26).
MOST_MODULES = 30
#: Rooms ``import corliss`` must not load until one of their names is used.
ON_USE_ONLY = ("corliss.plot", "corliss.studies", "corliss.fitting", "corliss.files",
               "corliss.cli")


def _fresh(code: str) -> dict:
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.strip().splitlines()[-1])


def test_import_corliss_loads_few_modules_and_no_plot_study_or_fit():
    got = _fresh("import json, sys, corliss; "
                 "print(json.dumps(sorted(m for m in sys.modules "
                 "if m == 'corliss' or m.startswith('corliss.'))))")
    assert len(got) <= MOST_MODULES, got
    loaded = [m for m in got if m.startswith(ON_USE_ONLY)]
    assert not loaded, loaded


def test_every_front_door_name_comes_from_the_module_it_is_listed_under():
    """Each name of ``corliss.__all__`` resolves, and is the object its module defines
    (a wrong entry in the table of names loaded on use would fail here)."""
    got = _fresh("import importlib, json, corliss; "
                 "print(json.dumps({n: getattr(corliss, n) is "
                 "getattr(importlib.import_module(m), n) "
                 "for n, m in corliss._ON_USE.items()}))")
    assert set(got) | {"InputError", "__version__"} == set(corliss.__all__)
    assert all(got.values()), [n for n, same in got.items() if not same]


def test_python_dash_m_corliss_is_the_command():
    proc = subprocess.run([sys.executable, "-m", "corliss", "--version"],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert corliss.__version__ in proc.stdout + proc.stderr


def _matplotlib_use_calls(path: Path) -> list[int]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    lines = []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                and node.func.attr in ("use", "switch_backend")
                and isinstance(node.func.value, ast.Name)
                and node.func.value.id in ("matplotlib", "mpl", "plt", "pyplot")):
            lines.append(node.lineno)
    return lines


def test_only_the_command_line_sets_the_matplotlib_backend(tmp_path):
    wrong = {str(p.relative_to(ROOT)): _matplotlib_use_calls(p)
             for p in ROOT.rglob("*.py") if not p.relative_to(ROOT).parts[0] == "cli"}
    wrong = {p: lines for p, lines in wrong.items() if lines}
    assert not wrong, wrong
    # the reader sees such a call
    probe = tmp_path / "probe.py"
    probe.write_text("import matplotlib\n\ndef f():\n    matplotlib.use('Agg')\n")
    assert _matplotlib_use_calls(probe) == [4]


def test_writing_a_design_leaves_the_backend_as_the_user_chose(tmp_path):
    """A valve designed and written with its two diagrams, in a process whose backend
    the user set to ``svg``: the backend is ``svg`` after the files are written."""
    got = _fresh(
        "import json, matplotlib; matplotlib.use('svg'); import corliss; "
        "d = corliss.design(cutoff=0.6, lead='0.25 in', max_opening='1.25 in'); "
        f"files = d.write({str(tmp_path)!r}); "
        "print(json.dumps([matplotlib.get_backend(), sorted(files)]))")
    assert got[0] == "svg"
    assert {"zeuner", "bilgram"} <= set(got[1])
