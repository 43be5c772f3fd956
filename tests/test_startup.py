"""A warm run imports nothing it does not use.

``corliss run --json --no-plots`` on a machine whose kernels and steam table are cached
needs numpy and numba, and neither CoolProp (the table tier answers every state of the
run itself), matplotlib (no figure), scipy's solvers (the compiled integrator does the
work) nor pandas (a steady run's tables are :class:`corliss.frames.frame.Frame` until a user
asks for a DataFrame): together they cost over two seconds of start-up.  The run is a
subprocess, as a user starts it, so that nothing the test session imported counts.

scipy's top package is numba's own import (its version check), not corliss's: it is
allowed, and so is the extension ``scipy.linalg.cython_blas`` that numba's BLAS check
imports when it loads a compiled function; the package ``scipy.linalg`` around it, 0.12 s
of imports, is not (``corliss.thermo.numba_start`` loads the extension alone).  Nor are
the modules of the commands and runs a steady run does not make (transient runs, the
governors, valve design).
"""

from __future__ import annotations

import json
import subprocess
import sys

#: Runs the command line in a fresh interpreter and writes the modules loaded at exit.
PROBE = """
import json, sys
from corliss.cli.commands import main
code = main(sys.argv[2:])
with open(sys.argv[1], "w") as f:
    json.dump({"code": code, "modules": sorted(sys.modules)}, f)
"""

#: Modules a run on the table tier must not import, by the prefix of their names.
NOT_WITHOUT_PLOTS = ("CoolProp", "matplotlib", "scipy.optimize", "scipy.integrate",
                     "scipy.interpolate", "pandas")
#: Modules a steady run must not import, by their exact names.
NOT_IN_A_STEADY_RUN = ("scipy.linalg", "corliss.engine.transient", "corliss.engine.mean_value",
                       "corliss.governors", "corliss.files.design_output")


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


def test_warm_json_run_imports_no_coolprop_matplotlib_scipy_solvers_or_pandas(tmp_path):
    _modules_of_run(tmp_path, "--json", "--no-plots")        # warms the caches
    modules = _modules_of_run(tmp_path, "--json", "--no-plots")
    assert "corliss.engine.kernels" in modules and "numba" in modules   # it did run
    assert _heavy(modules, NOT_WITHOUT_PLOTS) == []
    assert [m for m in NOT_IN_A_STEADY_RUN if m in modules] == []


def test_warm_run_with_figures_imports_matplotlib_but_not_coolprop_scipy_solvers_or_pandas(
        tmp_path):
    modules = _modules_of_run(tmp_path)
    assert "matplotlib" in modules
    assert _heavy(modules, [p for p in NOT_WITHOUT_PLOTS if p != "matplotlib"]) == []


def _json_run(tmp_path, name: str, env: dict, *args: str) -> tuple[dict, str]:
    import os
    proc = subprocess.run([sys.executable, "-c", "import sys; from corliss.cli.commands import main; "
                           "sys.exit(main(sys.argv[1:]))", "-v", "run", "--json", "--no-plots",
                           "--out", str(tmp_path / name), *args],
                          capture_output=True, text=True, timeout=900, env={**os.environ, **env})
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout), proc.stderr


def test_a_fresh_machines_first_run_builds_the_table_beside_the_compilation(tmp_path):
    """With neither the steam table nor the compiled kernels cached (both caches pointed
    at empty folders), the first run builds the table in a second process while it
    compiles (``corliss.engine.first_run``), fills both caches, and reports exactly what
    a warm machine reports: the miniature table it compiles on is thrown away, so the
    indicated power, steam and events agree to the last bit.  The kernels compile in a
    version for each kind of method (the ``fast`` preset's ode23s pair, ``standard``'s
    RODAS4 tableau, dopri5 where a wall heat depends on the state, the transient
    loop's turns): the first run's background process compiles the versions it did
    not run, so that numba's cache index holds every one once it is done, and a first
    ``fast`` run on that machine compiles nothing."""
    warm, _ = _json_run(tmp_path, "warm", {})
    env = {"CORLISS_CACHE": str(tmp_path / "table"), "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    cold, log = _json_run(tmp_path, "cold", env)
    assert "building the steam table in a second process" in log
    assert list((tmp_path / "table").glob("steam-table-*.npz"))
    assert list((tmp_path / "numba").rglob("*.nbi"))
    for key in ("indicated_power_W", "steam_rate_kg_per_h", "mep_mean_Pa", "events"):
        assert cold[key] == warm[key], key
    assert "compiling the kernels' other versions in a background process" in log
    assert _uncached_after_first_use(env) == []
    _, log = _json_run(tmp_path, "fast", env, "--fidelity", "fast")
    assert "compiling" not in log


#: Waits for a first run's background process (it holds the lock beside numba's cache
#: while it compiles) and prints what numba's cache index still lacks of the versions a
#: command line reaches from the default scene: its own, the other presets' with and
#: without a wall heat that depends on the state, the transient turn integrators.
WAIT_FIRST_USE = """
import fcntl, json, sys, time
from corliss.engine import first_run
from corliss.scene.loader import find_scene, load_scene
scene = load_scene(find_scene("default"))
deadline = time.monotonic() + float(sys.argv[1])
while True:
    with open(first_run._lock_path(), "a+b") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        left = first_run.reachable_uncached(scene)
        left += ["its own"] if first_run._kernels_missing(scene) else []
    if not left or time.monotonic() > deadline:
        break
    time.sleep(2.0)
print(json.dumps(left))
"""


def _uncached_after_first_use(env: dict, wait_s: float = 900.0) -> list[str]:
    import os
    proc = subprocess.run([sys.executable, "-c", WAIT_FIRST_USE, str(wait_s)],
                          capture_output=True, text=True, timeout=wait_s + 120,
                          env={**os.environ, **env})
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)
