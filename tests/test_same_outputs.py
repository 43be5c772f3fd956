"""The default scene's outputs, to nine significant figures: start-up work must not
change a result.

Making ``corliss run`` start faster (fewer imports, the steam table read uncompressed,
numba started without ``scipy.linalg``, tables held without pandas) changes nothing
that is computed: the cycle count, the tolerances and every number written stay as they
were.  This test holds it: the three CSVs and the summary JSON of ``corliss run --json
--no-plots`` on the bundled default scene are compared with what the run wrote before
(``tests/data/default_outputs.json``): the same files, columns, rows and text, and each column's sum and
sum of squares, and each summary number, within 1e-9 relative (the run's own numbers
carry ten significant figures; a processor whose compiled arithmetic differs in the last
bits, with or without fused multiply-adds, moves them by about 1e-12, where a change of
tolerance, integrator or table moves them by 1e-7 or more), the wall time excepted.

The fingerprint pins results, not physics: a change meant to alter the default scene's
numbers (a new integrator, a new table) writes new files, and its commit replaces the
fingerprint below, saying why, with what this file prints as a script::

    corliss run --json --no-plots --out d && python tests/test_same_outputs.py d

The physics tests say whether such a change matters.  Last replaced when the wet
lookup's Newton iteration started from each node's temperature at the evaluation
before, and the analytic Jacobian took the node properties of the right-hand side at
its state (the same numbers to the iteration's 2e-9 K, which the adaptive steps carry:
every column moved by 1.3e-8 relative at most; the summary's residuals, differences of
nearly equal numbers, by up to 1.3e-4 of themselves).  Before that, when the
``standard`` preset took RODAS4 at rtol 2e-6 with the exact Jacobian where dopri5 at
1e-6 had been (3 cycles to periodic instead of 4, 3,724 evaluations instead of 16,022;
indicated power moved by 7.5e-6 relative, steam by 2.2e-5, peak pressure by 4.1e-5,
each within the preset's 1e-4 of the converged card (tests/test_hard_cases.py); the
energy balance error, which holds the last cycle's drift, rose from 8e-7 to 2.9e-5,
within the periodicity tolerance of 1e-4).  Before that, when the wet-steam lookup's
Newton iteration stopped bisecting after it had converged (7e-11).
"""

from __future__ import annotations

import csv
import json
import math
import sys
from pathlib import Path

import pytest

from corliss.cli.commands import main

FILES = ("default.timeseries.csv", "default.cycles.csv", "default.cards.csv",
         "default.summary.json")
#: What the run wrote before (this file's output as a script).
FINGERPRINT_PATH = Path(__file__).parent / "data" / "default_outputs.json"
#: Agreement asked of every number [-] (see the module docstring).
RTOL = 1e-9


def fingerprint(out_dir: Path) -> dict:
    """What is compared of each file in ``out_dir``.

    Parameters
    ----------
    out_dir : pathlib.Path
        The folder ``corliss run`` wrote.

    Returns
    -------
    dict
        For each CSV its header, row count, text columns' values and each numeric
        column's sum and sum of squares; for the summary its keys and values, the wall
        time left out.
    """
    out = {}
    for name in FILES:
        path = out_dir / name
        if name.endswith(".json"):
            summary = json.loads(path.read_text())
            summary.pop("wall_time_s", None)
            out[name] = summary
            continue
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
        header, body = rows[0], rows[1:]
        cols = {}
        for j, col in enumerate(header):
            cells = [r[j] for r in body]
            try:
                vals = [float(c) if c else math.nan for c in cells]
            except ValueError:
                cols[col] = sorted(set(cells))
                continue
            finite = [v for v in vals if math.isfinite(v)]
            cols[col] = [len(finite), math.fsum(finite), math.fsum(v * v for v in finite)]
        out[name] = {"rows": len(body), "columns": cols}
    return out


def _same(a, b, where):
    if isinstance(a, dict):
        assert isinstance(b, dict) and a.keys() == b.keys(), where
        for k in a:
            _same(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}[{i}]")
    elif isinstance(a, float) and not isinstance(b, bool):
        assert b == pytest.approx(a, rel=RTOL, abs=1e-300, nan_ok=True), where
    else:
        assert a == b, where


def test_default_scene_writes_what_it_wrote_before(tmp_path, capsys):
    assert main(["run", "--json", "--no-plots", "--out", str(tmp_path)]) == 0
    printed = capsys.readouterr().out
    # --json prints the summary file's text
    assert printed.strip() == (tmp_path / "default.summary.json").read_text().strip()
    before = json.loads(FINGERPRINT_PATH.read_text())
    _same(before, json.loads(json.dumps(fingerprint(tmp_path))), "outputs")


def test_the_comparison_sees_a_change_of_one_part_in_a_hundred_million():
    """The check can fail: one summary number moved by 1e-8 of itself is caught."""
    before = json.loads(FINGERPRINT_PATH.read_text())
    moved = json.loads(FINGERPRINT_PATH.read_text())
    moved["default.summary.json"]["indicated_power_W"] *= 1 + 1e-8
    with pytest.raises(AssertionError):
        _same(before, moved, "outputs")


if __name__ == "__main__":
    print(json.dumps(fingerprint(Path(sys.argv[1])), indent=1, sort_keys=True))
