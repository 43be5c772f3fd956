"""A warm run imports nothing it does not use.

``corliss run --json --no-plots`` on a machine whose kernels and steam table are cached
needs numpy, pandas and numba, and neither CoolProp (the table tier answers every state
of the run itself), matplotlib (no figure) nor scipy's solvers (the compiled integrator
does the work): together they cost about two seconds of start-up.  The run is a
subprocess, as a user starts it, so that nothing the test session imported counts.

scipy's top package and ``scipy.linalg`` are numba's own imports (its version check, and
the BLAS check it makes when it loads a compiled function), not corliss's: they are
allowed.
"""

from __future__ import annotations

import json
import subprocess
import sys

#: Runs the command line in a fresh interpreter and writes the modules loaded at exit.
PROBE = """
import json, sys
from corliss.cli import main
code = main(sys.argv[2:])
with open(sys.argv[1], "w") as f:
    json.dump({"code": code, "modules": sorted(sys.modules)}, f)
"""

#: Modules a run on the table tier must not import, by the prefix of their names.
NOT_WITHOUT_PLOTS = ("CoolProp", "matplotlib", "scipy.optimize", "scipy.integrate",
                     "scipy.interpolate")


def _modules_of_run(tmp_path, *args: str) -> list[str]:
    report = tmp_path / "modules.json"
    proc = subprocess.run([sys.executable, "-c", PROBE, str(report), "run", *args,
                           "--out", str(tmp_path / "out")],
                          capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0, proc.stderr
    got = json.loads(report.read_text())
    assert got["code"] == 0
    return got["modules"]


def _heavy(modules: list[str], prefixes) -> list[str]:
    return [m for m in modules if any(m == p or m.startswith(p + ".") for p in prefixes)]


def test_warm_json_run_imports_no_coolprop_matplotlib_or_scipy_solvers(tmp_path):
    _modules_of_run(tmp_path, "--json", "--no-plots")        # warms the caches
    modules = _modules_of_run(tmp_path, "--json", "--no-plots")
    assert "corliss.engine.kernel" in modules and "pandas" in modules   # it did run
    assert _heavy(modules, NOT_WITHOUT_PLOTS) == []


def test_warm_run_with_figures_imports_matplotlib_but_not_coolprop_or_scipy_solvers(tmp_path):
    modules = _modules_of_run(tmp_path)
    assert "matplotlib" in modules
    assert _heavy(modules, [p for p in NOT_WITHOUT_PLOTS if p != "matplotlib"]) == []
