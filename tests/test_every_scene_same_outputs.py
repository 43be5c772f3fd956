"""Every bundled scene, steady and transient, computes what it computed before.

The kernels are reorganised (split by concern, their data named, each law written once)
by moves that must not change one number.  This test holds it on every scene that comes
with the package, on each step loop the presets use: a steady scene runs one cycle at
``fast`` (the ode23s Rosenbrock pair) and one at ``standard`` (RODAS4 on the analytic
Jacobian, or dopri5 where the wall heat depends on the state); a transient scene runs
0.1 s (a few turns, the start from rest included) at ``fast`` (``ros4``) and at
``standard`` (dopri5).  Settings this short prove no physics (the physics tests do that);
they exercise every compiled right-hand side, Jacobian and step loop in a few seconds.

What is compared of each run: the number of right-hand-side evaluations, and for each
numeric column of the time series and the cycle table a SHA-256 of its IEEE-754 bytes
together with its exactly rounded sum and sum of squares.

- On the platform the fingerprint was taken on (the same machine type, processor name
  as LLVM sees it, numba and numpy versions), the bytes must agree: a change of one unit
  in the last place of one kernel operation moves them (the test
  ``test_one_ulp_is_seen`` shows it), where a tolerance on sums would not.
- Elsewhere (another processor may fuse multiply-adds, or vectorise a sum in another
  order, moving the last bits, about 1e-12 relative after an adaptive run), the sums are
  compared within 1e-9 relative, the tolerance of tests/test_same_outputs.py and for
  its reason, and the evaluation counts within 1 %: a different step accepted in one
  place of thousands moves them that much, where a change of tolerance, method or table
  moves them by more.

A change meant to alter the numbers replaces ``tests/data/every_scene_outputs.json``,
saying why in its commit, with::

    python tests/test_every_scene_same_outputs.py > tests/data/every_scene_outputs.json
"""

from __future__ import annotations

import hashlib
import json
import math
import platform
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from corliss.engine.simulate import simulate
from corliss.scene import bundled_scenes, load_scene

FINGERPRINT_PATH = Path(__file__).parent / "data" / "every_scene_outputs.json"
#: Agreement of sums asked off the fingerprint's platform [-] (see the module docstring).
RTOL_OTHER_PLATFORM = 1e-9
#: Agreement of evaluation counts asked off the fingerprint's platform [-].
EVALS_RTOL_OTHER_PLATFORM = 0.01
#: A transient scene's simulated time [s].
TRANSIENT_S = 0.1
FIDELITIES = ("fast", "standard")


def platform_key() -> dict:
    """What must match for the bytes to be compared: machine, processor, versions."""
    import llvmlite.binding
    import numba
    return {"machine": platform.machine(), "cpu": llvmlite.binding.get_host_cpu_name(),
            "numba": numba.__version__, "numpy": np.__version__}


def cheap(scene, fidelity: str):
    """The scene at ``fidelity``, one cycle (steady) or :data:`TRANSIENT_S` (transient)."""
    scene = scene.with_fidelity(fidelity)
    if scene.run.mode == "transient":
        return scene.replace_run(duration_s=TRANSIENT_S)
    return scene.replace_run(cycles=1)


def _frame_print(frame) -> dict:
    out = {}
    for col in frame.columns:
        values = frame[col].to_numpy()
        if values.dtype.kind not in "fiu":
            out[str(col)] = {"text": sorted({str(v) for v in values})}
            continue
        values = np.ascontiguousarray(values, dtype=np.float64)
        finite = values[np.isfinite(values)]
        out[str(col)] = {"sha256": hashlib.sha256(values.tobytes()).hexdigest(),
                         "sum": math.fsum(finite), "sumsq": math.fsum(finite * finite)}
    return out


def run_print(name: str, fidelity: str) -> dict:
    """The fingerprint of one bundled scene run cheaply at ``fidelity``."""
    result = simulate(cheap(load_scene(bundled_scenes()[name]), fidelity))
    return {"rhs_evaluations": int(result.rhs_evaluations),
            "timeseries": _frame_print(result.timeseries),
            "cycles": _frame_print(result.cycles)}


def compare(before: dict, now: dict, exact: bool, where: str) -> None:
    """Assert ``now`` is ``before``: bytes when ``exact``, else sums to a tolerance."""
    assert before.keys() == now.keys(), where
    if exact:
        assert now["rhs_evaluations"] == before["rhs_evaluations"], where
    else:
        assert now["rhs_evaluations"] == pytest.approx(
            before["rhs_evaluations"], rel=EVALS_RTOL_OTHER_PLATFORM), where
    for table in ("timeseries", "cycles"):
        assert before[table].keys() == now[table].keys(), f"{where}.{table}"
        for col, b in before[table].items():
            n, here = now[table][col], f"{where}.{table}.{col}"
            if "text" in b:
                assert n == b, here
            elif exact:
                assert n["sha256"] == b["sha256"], (here, b["sum"], n["sum"])
            else:
                for k in ("sum", "sumsq"):
                    assert n[k] == pytest.approx(b[k], rel=RTOL_OTHER_PLATFORM,
                                                 abs=1e-300), here


def _saved() -> dict:
    return json.loads(FINGERPRINT_PATH.read_text())


@pytest.fixture(scope="module")
def prints_now() -> dict:
    """Every scene's fingerprint now, taken in a fresh process, in the order and the way
    the saved one was taken (this file run as a script).

    A fresh process, so that the sequence of runs is the saved one's.  (A run in the
    test's worker once took another number of steps after other test files ran there:
    the compiled loops read their property scratch before writing it, and it was
    allocated uninitialised; tests/test_scratch_determinism.py now holds that a run
    does not depend on what ran before it.)
    """
    out = subprocess.run([sys.executable, str(Path(__file__))], capture_output=True,
                         text=True, check=True, cwd=Path(__file__).parent.parent)
    return json.loads(out.stdout)


@pytest.mark.parametrize("fidelity", FIDELITIES)
@pytest.mark.parametrize("name", sorted(bundled_scenes()))
def test_scene_computes_what_it_computed_before(name, fidelity, prints_now):
    saved = _saved()
    exact = saved["platform"] == prints_now["platform"]
    compare(saved["runs"][f"{name}/{fidelity}"], prints_now["runs"][f"{name}/{fidelity}"],
            exact, f"{name}/{fidelity}")


def test_every_bundled_scene_is_fingerprinted():
    """A scene added to the package is added here too (its fingerprint recorded)."""
    assert sorted(_saved()["runs"]) == sorted(
        f"{n}/{f}" for n in bundled_scenes() for f in FIDELITIES)


def test_one_ulp_is_seen():
    """The exact comparison sees one column's one value moved by one unit in the last place."""
    before = run_print("default", "fast")
    ts = simulate(cheap(load_scene(bundled_scenes()["default"]), "fast")).timeseries
    col = next(c for c in ts.columns if ts[c].dtype.kind == "f")
    moved = ts.copy()
    moved.loc[moved.index[len(moved) // 2], col] = np.nextafter(
        moved[col].iloc[len(moved) // 2], np.inf)
    now = dict(before, timeseries=_frame_print(moved))
    with pytest.raises(AssertionError):
        compare(before, now, True, "default/fast")
    compare(before, before, True, "default/fast")


if __name__ == "__main__":
    runs = {f"{n}/{f}": run_print(n, f) for n in bundled_scenes() for f in FIDELITIES}
    json.dump({"platform": platform_key(), "runs": runs}, sys.stdout, indent=1,
              sort_keys=True)
    print()
