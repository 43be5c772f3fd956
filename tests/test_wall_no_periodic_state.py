"""A skin wall whose deep wall has no periodic state says so (issue 31).

The deep wall's temperature is the root of its balance over a cycle, found by a secant
inside a bracket (:class:`corliss.engine.wall.DeepWallSearch`).  On a superheated
supply the balance can change sign without a root: at one deep-wall temperature the
cycle has a dry periodic state (the wall loses heat over the cycle) and a wet one (it
gains), and the balance jumps across a narrow band (docs/validation/condensation.md,
"Superheated walls that do not settle").  A bracket closed across such a jump locates
no root; the run must not count it periodic, and must say that more cycles will not
settle it.

The balances below are the validation page's table: the Meyer engine's crank end on
40 psia of steam throttled from 140 psia (25 K of superheat), the deep wall held at
each temperature and the cycle run until periodic (fast preset), the heat into the
steam ``Q`` over a cycle [J] on the dry state and on the wet one.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from corliss.cli import commands as cli
from corliss.engine.verdict import EXIT_PHYSICAL
from corliss.engine.wall import DeepWallSearch, WallJump, wall_jump_text

#: Heat into the steam over a cycle [J] against the deep wall [K], crank end, on the
#: state a dry start reaches (docs/validation/condensation.md, the table of
#: "Superheated walls that do not settle"): at 371.3 K a dry start falls to the wet
#: state; from 371.6 K up the dry state exists.
DRY_T_K = np.array([371.6, 371.9, 373.0, 374.0, 376.0])
DRY_Q_J = np.array([401.0, 500.0, 604.0, 636.0, 666.0])
#: The same on the wet state (a 12 g film at the start), up to 374.5 K.
WET_T_K = np.array([371.3, 371.6, 371.9, 373.0, 374.5])
WET_Q_J = np.array([-6409.0, -6071.0, -5739.0, -4495.0, -2787.0])
#: Where the dry state first exists on the table: half-way between 371.3 and 371.6 K.
T_DRY_FROM_K = 371.45
#: The crank end's integrated ``h A`` over a cycle [J/K], the slope the search's first
#: step takes and the bound on a continuous balance's: 1.6 to 1.7 kJ/K on this run's
#: wet cycles (as the runner integrates it).
HA_J_K = 1650.0
#: The run's temperature scale, the supply's temperature less the exhaust's [K]:
#: 312.7 degF (429.1 K) against the saturation of 16.7 psia (219.4 degF, 377.3 K).
DT_SCALE_K = 51.8
#: The fast preset's periodicity tolerance [-].
TOL = 1e-3
#: The wall's heat scale [J] (the heat the steam gives it over a cycle): any below
#: 401 J / (10 TOL) = 40.1 kJ leaves each of the jump's edges above ten tolerances
#: (:data:`corliss.engine.wall.JUMP_TOLERANCES`, the noise of a trusted cycle's balance).
HEAT_SCALE_J = 10_000.0


def balance_J(T_K: float) -> float:
    """The wall's balance ``r = -Q`` [J] at ``T_K`` on the state a dry start reaches
    (the dry state where it exists, else the wet one), no jacket."""
    if T_K >= T_DRY_FROM_K:
        return -float(np.interp(T_K, DRY_T_K, DRY_Q_J))
    return -float(np.interp(T_K, WET_T_K, WET_Q_J))


def _search(r_of_T, T0_K: float, cycles: int):
    """Run the search ``cycles`` times on the balance ``r_of_T``, every cycle trusted
    (periodic at its deep wall); the imbalances it reported, and the search."""
    search, T, out = DeepWallSearch(), T0_K, []
    for _ in range(cycles):
        step, r = search.step(T, -r_of_T(T), HA_J_K, 0.0, 0.0, apply=True, trusted=True)
        out.append(search.imbalance(r, HEAT_SCALE_J, DT_SCALE_K))
        T += step
    return search, out


def test_a_bracket_closed_across_the_jump_is_not_periodic_and_names_it():
    """The search closes its bracket on the band where the dry state begins, to well
    within the tolerance of the temperature scale (``TOL * DT_SCALE_K`` = 0.05 K), yet
    no cycle counts as periodic: the edges' balances, +6,2xx J and -4xx J, differ by
    some 6,600 J where a continuous balance could change by at most ``h A`` times the
    band (under 100 J).  The jump is the band and those two balances."""
    search, imbalances = _search(balance_J, 380.0, 40)
    jump = search.jump(TOL)
    assert isinstance(jump, WallJump)
    assert jump.T_low_K < T_DRY_FROM_K <= jump.T_high_K
    # closed: narrower than the tolerance in temperature the runner accepts
    assert jump.T_high_K - jump.T_low_K <= TOL * DT_SCALE_K
    # the wet state's gain and the dry state's loss at the band's edges (the table's
    # 371.3 and 371.6 K rows bound them)
    assert 6071.0 <= jump.balance_low_J <= 6409.0
    assert -401.0 * 1.01 <= jump.balance_high_J <= -401.0 * 0.99
    assert min(imbalances) > TOL
    text = wall_jump_text({"crank": jump})
    assert "no periodic state of the wall" in text
    assert "more cycles will not settle it" in text
    assert f"{jump.T_low_K:.2f} and {jump.T_high_K:.2f} K" in text


def test_a_steep_balance_with_a_root_still_settles_on_its_bracket():
    """A continuous balance nearly as steep as the bound, ``r = 0.9 h A (372 K - T)``
    (the true slope is below ``h A``: water condensed on a cooler wall evaporates from
    it later in the cycle).  Run by the search it closes on its root and counts as
    periodic.  Measured 0.02 K either side of the root, +29.7 J and -29.7 J, each above
    ten tolerances of a wall taking 1.5 kJ a cycle (15 J) but 0.04 K
    apart, within the temperature's (0.05 K): the edges differ by no more than ``h A``
    times the width, so the bracket holds no jump and its width counts (periodic), as
    the runner counts a steep wall whose balance the cycles' noise leaves above a small
    heat's tolerance.  The saturated runs settle so (the every-scene fingerprint holds
    them unchanged)."""
    search, imbalances = _search(lambda T: 0.9 * HA_J_K * (372.0 - T), 380.0, 40)
    assert search.jump(TOL) is None and imbalances[-1] <= TOL
    search = DeepWallSearch()
    search.step(371.98, -0.9 * HA_J_K * 0.02, HA_J_K, 0.0, 0.0, apply=True)
    _, r = search.step(372.02, 0.9 * HA_J_K * 0.02, HA_J_K, 0.0, 0.0, apply=True)
    assert abs(r) > 10.0 * TOL * 1500.0
    assert search.imbalance(r, 1500.0, DT_SCALE_K) <= TOL
    assert search.jump(TOL) is None
    # the noise of trusted cycles: the Meyer engine through 4 times its ports (fast
    # preset) measured +19.8 J and -20.4 J at one deep wall, 396.66 K, where its wall
    # takes 12.6 kJ a cycle (1.6 tolerances): periodic, not a jump
    search = DeepWallSearch()
    search.step(396.66, -19.8, 1572.0, 0.0, 0.0, apply=True)
    _, r = search.step(396.66 + 1e-13, 20.4, 1575.0, 0.0, 0.0, apply=True)
    assert search.imbalance(r, 12.6e3, DT_SCALE_K) <= TOL
    assert search.jump(TOL) is None


def test_an_open_bracket_straddling_a_jump_decides_it_from_its_edges():
    """Two trusted cycles, wet at 371.3 K (the wall gains 6,409 J) and dry at 371.9 K
    (it loses 500 J): 6,909 J apart across 0.6 K, where a continuous balance could
    change by at most 1,650 J/K x 0.6 K = 990 J: a jump, decided before the bracket
    closes.  Wet at 371.3 K and dry at 376.0 K (-666 J), 7,075 J apart across 4.7 K
    (7,755 J possible): a root could lie between, so nothing is decided.  Nor where
    the dry edge's loss is within ten tolerances of the wall's heat (a heat scale of
    60 kJ: 600 J), the noise of a trusted cycle's balance: not a jump."""
    for T_dry, scale, decided in ((371.9, HEAT_SCALE_J, True), (376.0, HEAT_SCALE_J, False),
                                  (371.9, 60e3, False)):
        search = DeepWallSearch()
        search.step(371.3, -6409.0, HA_J_K, 0.0, 0.0, apply=True)
        _, r = search.step(T_dry, float(np.interp(T_dry, DRY_T_K, DRY_Q_J)), HA_J_K, 0.0,
                           0.0, apply=True)
        search.imbalance(r, scale, DT_SCALE_K)
        jump = search.jump(TOL)
        assert (jump is not None) == decided, (T_dry, scale)
        if decided:
            assert (jump.T_low_K, jump.T_high_K) == (371.3, T_dry)


SCENES = Path(__file__).resolve().parent.parent / "scenes"


def test_the_cli_names_the_jump_and_exits_as_a_run_that_is_not_periodic(
        tmp_path, monkeypatch, capsys):
    """Plumbing, not physics: no bundled scene's search closes a trusted bracket across
    a jump in the fast preset's cycles (the superheated runs step their wall before
    any cycle is periodic to the tolerance), so the jump is handed to the runner here,
    the table's band.  The saturated single-acting scene, stopped after 6 cycles (2 max_cycles, three times with the wall),
    warns with the jump instead of "may settle it", writes the summary's keys, and
    exits as any run that is not periodic does (docs/exit-codes.md: 4,
    ``not_periodic``)."""
    jump = WallJump(371.4, 371.45, 6240.0, -401.0)
    monkeypatch.setattr(DeepWallSearch, "jump", lambda self, tol: jump)
    text = (SCENES / "callendar-nicolson-single-acting.toml").read_text(encoding="utf-8")
    assert 'fidelity = "standard"\n' in text
    scene = tmp_path / "short.toml"
    scene.write_text(text.replace('fidelity = "standard"\n',
                                  'fidelity = "fast"\nmax_cycles = 2\n', 1), encoding="utf-8")
    rc = cli.main(["run", str(scene), "--out", str(tmp_path), "--no-plots"])
    err = capsys.readouterr().err
    s = json.loads((tmp_path / "short.summary.json").read_text(encoding="utf-8"))
    assert s["cycles_to_converge"] is None
    assert s["wall_periodic_state"] == "none: the balance jumps"
    assert {j["end"] for j in s["wall_balance_jumps"]} <= {"head", "crank"}
    assert s["wall_balance_jumps"][0]["T_low_K"] == pytest.approx(371.4)
    assert s["wall_balance_jumps"][0]["balance_high_J"] == pytest.approx(-401.0)
    assert "jumps from +6,240 J to -401 J between 371.40 and 371.45 K" in err
    assert "more cycles will not settle it" in err
    assert "may settle it" not in err
    assert rc == EXIT_PHYSICAL
    assert {f["failure"] for f in s["failures"]} == {"not_periodic"}
