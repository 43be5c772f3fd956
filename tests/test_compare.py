"""Throttling against cut-off governing (`corliss compare`): the table's schema, the
operating points, and the period's statements about the two governings as tests.

The study runs on the small high-speed engine (10 x 12 in at 300 rev/min, the
Armington & Sims scene) at the ``fast`` tier and a few loads, to keep the tests short.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from corliss.cli.commands import main
from corliss.studies.compare import compare, variants
from corliss.studies.compare_result import POINT_COLUMNS
from corliss.studies import pool as study_pool
from corliss.engine.geometry import CylinderGeometry
from corliss.errors import InputError
from corliss.scene.loader import find_scene, load_scene

LOADS = (0.25, 0.5, 1.0)


@pytest.fixture(scope="module")
def small():
    return load_scene(find_scene("armington-sims-governor"))


@pytest.fixture(scope="module")
def study(small):
    # a small chest: 6 % of the swept volume (the least a scene may have is 5 %)
    chest = 0.06 * float(CylinderGeometry(small.engine).swept_m3[0])
    return compare(small, LOADS, fidelity="fast", chest_volume_m3=chest, droop=True)


def test_table_schema(study):
    pts = study.points
    expected = [c for c in POINT_COLUMNS]              # friction named: brake power too
    assert list(pts.columns) == expected
    assert len(pts) == 2 * 2 * len(LOADS)
    assert set(pts["variant"]) == {"throttling", "cutoff"}
    assert set(pts["condensation"]) == {"on", "off"}
    assert set(pts["knob"]) == {"throttle", "setting"}
    assert (pts["status"] == "found").all()
    # missing water only where the walls take heat
    assert pts.loc[pts["condensation"] == "off", "missing_water_frac"].isna().all()
    assert (pts.loc[pts["condensation"] == "on", "missing_water_frac"] > 0).all()
    # the throttled variant keeps its cut-off; the cut-off variant's shortens with load
    thr = pts[pts["variant"] == "throttling"]
    assert np.ptp(thr["cutoff_head_frac"]) < 1e-9
    cut = pts[(pts["variant"] == "cutoff") & (pts["condensation"] == "off")]
    assert np.all(np.diff(cut.sort_values("load_frac")["cutoff_head_frac"]) > 0)
    w = study.willans
    assert list(w.columns) == ["variant", "condensation", "willans_intercept_kg_per_h",
                               "willans_slope_kg_per_kWh", "willans_r2_frac"]
    assert len(w) == 4
    v = study.verdict
    assert len(v) == 2 * len(LOADS)
    assert set(v["winner"]) <= {"throttling", "cutoff", "even"}


def test_operating_points_deliver_the_asked_power(study):
    """Each variant's operating point gives the asked (brake) power within 1 %."""
    pts = study.points
    got = pts["brake_power_W"].to_numpy()
    asked = pts["load_frac"].to_numpy() * study.rated_power_W
    np.testing.assert_allclose(got, asked, rtol=0.01)
    assert np.all(np.abs(pts["power_error_frac"]) < 0.01)
    assert study.rated_power_W == pytest.approx(100 * 745.6999, rel=1e-4)   # the scene's load


def test_throttled_steam_against_power_is_a_straight_line(study):
    """Willans (Min. Proc. Inst. C.E. 93, 1888, "Steam-engine trials"): the steam per hour
    of a throttle-governed engine is a straight line against its indicated power; Marks
    (Relative Proportions, Art. 2) draws the same line.  With a small chest (6 % of the
    swept volume) the model's throttled points lie on a line within 3 % of the steam (it
    bends a little: wire-drawing at a small opening costs more than the line, 2.5 % at a
    quarter load on the fast tier without condensation)."""
    pts = study.points
    for cond in ("off", "on"):
        g = pts[(pts["variant"] == "throttling") & (pts["condensation"] == cond)]
        w = study.willans.set_index(["variant", "condensation"]).loc[("throttling", cond)]
        assert w["willans_r2_frac"] > 0.995
        assert w["willans_intercept_kg_per_h"] > 0     # steam to run the engine light
        line = (w["willans_intercept_kg_per_h"]
                + w["willans_slope_kg_per_kWh"] * g["indicated_power_W"] / 1e3)
        resid = (g["steam_rate_kg_per_h"] - line) / g["steam_rate_kg_per_h"]
        assert np.max(np.abs(resid)) < 0.03


def test_cutoff_governing_uses_less_steam_at_part_load_without_condensation(study):
    """Marks (Relative Proportions, Art. 2) and the period's argument: on the card,
    governing by cut-off expands the steam where throttling wire-draws it, so at part
    load the cut-off engine uses less steam per hour for the same power."""
    v = study.verdict
    part = v[(v["condensation"] == "off") & (v["load_frac"] < 1.0)]
    assert (part["winner"] == "cutoff").all()
    assert (part["cutoff_saving_frac"] > 0.1).all()
    # and its advantage grows as the load (and the cut-off) falls
    assert part.sort_values("load_frac")["cutoff_saving_frac"].is_monotonic_decreasing


def test_condensation_narrows_the_advantage_of_early_cutoff(study):
    """Marks (Arts. 74-75, the law of condensation): initial condensation grows as the
    cut-off shortens, so it takes back part of what early cut-off saves; at the lightest
    load the cut-off engine's saving over the throttled one is smaller with the walls'
    heat than without.  Marks gives the direction, not the size: the size is the wall's.
    With the skin wall at Callendar and Nicolson's measured condensing coefficient
    (16.7 kW/(m2 K), DPJ 312, 1899, p. 164) the walls take about 30 % of the saving at a
    quarter load (0.358 without them, 0.252 with them; the dropwise 3e5 they replaced took
    more than 40 %, which the old bound 0.6 held).  The bound 0.8 asks for a narrowing of
    at least a fifth: about 0.07 of saving here, several times the fast tier's
    operating-point error (each point within 1 % of its power, 0.02 of saving at most)."""
    v = study.verdict.set_index(["condensation", "load_frac"])["cutoff_saving_frac"]
    light = min(LOADS)
    assert v[("on", light)] < 0.8 * v[("off", light)]
    # the cut-off engine's missing water is the larger at light load (its cut-off the
    # earlier), the throttled engine's the same at its fixed cut-off
    pts = study.points.set_index(["variant", "condensation", "load_frac"])
    assert (pts.loc[("cutoff", "on", light), "missing_water_frac"]
            > pts.loc[("throttling", "on", light), "missing_water_frac"])


def test_bad_input_before_any_run(small):
    with pytest.raises(InputError):
        compare(small, [0.0, 0.5])
    with pytest.raises(InputError):
        compare(small, [0.5], condensation="sometimes")
    with pytest.raises(InputError):
        variants(small, throttled_setting=3.0)
    watt = load_scene(find_scene("watt-throttling-governor"))
    with pytest.raises(InputError):                    # a slide valve has no setting
        variants(watt)


def test_cli_compare_writes_table_figure_and_verdict(tmp_path, capsys):
    rc = main(["compare", "armington-sims-governor", "--loads", "0.5,1",
               "--with-condensation", "off", "--fidelity", "fast", "--out", str(tmp_path)])
    assert rc == 0
    out = capsys.readouterr().out
    assert "throttling or cut-off?" in out and "Willans line" in out
    stem = tmp_path / "armington-sims-governor"
    for suffix in ("compare.csv", "compare.meta.json", "compare.png", "compare.willans.csv",
                   "compare.verdict.csv", "compare.summary.json"):
        assert (tmp_path / f"{stem.name}.{suffix}").is_file(), suffix
    meta = json.loads((tmp_path / f"{stem.name}.compare.meta.json").read_text())
    assert meta["columns"]["water_rate_lb_per_hp_h"] == "lb/hp h"
    assert meta["columns"]["steam_rate_lb_per_h"] == "lb/h"
    rc = main(["compare", "armington-sims-governor", "--loads", "0.1:0.05:0.1",
               "--out", str(tmp_path / "no")])
    assert rc == 2 and not (tmp_path / "no").exists()


def test_sweep_takes_both_knobs_in_one_call(tmp_path, capsys):
    """`corliss sweep` runs gear settings and throttle openings in one call, at the
    fidelity asked, in units of one system (lb/h beside lb/hp-h)."""
    text = find_scene("armington-sims-governor").read_text()
    text = text.replace('barometer = "14.696 psia"', 'barometer = "14.696 psia"\n'
                        'chest_volume = "0.06 ft3"\npipe_diameter = "3 in"')
    text = text.replace('effects = ["port_flow", "rod_angularity", "friction"]',
                        'effects = ["port_flow", "rod_angularity", "friction", "steam_chest"]')
    scene = tmp_path / "small-with-chest.toml"
    scene.write_text(text)
    rc = main(["sweep", str(scene), "--settings", "0.6,0.9", "--throttle", "0.1,1",
               "--fidelity", "fast", "--json", "--out", str(tmp_path)])
    assert rc == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["knob"] == "both" and summary["fidelity"] == "fast"
    assert summary["setting_willans_intercept_kg_per_h"] is not None
    assert summary["throttle_willans_intercept_kg_per_h"] is not None
    meta = json.loads((tmp_path / "small-with-chest.sweep.meta.json").read_text())
    assert meta["columns"]["knob"].startswith("label")
    assert meta["columns"]["steam_rate_lb_per_h"] == "lb/h"
    assert meta["columns"]["water_rate_lb_per_hp_h"] == "lb/hp h"
    csv = (tmp_path / "small-with-chest.sweep.csv").read_text().splitlines()
    assert len(csv) == 5 and csv[0].startswith("knob,")


def test_scene_names_the_variants(tmp_path):
    """A scene's [compare] section names the throttled variant's setting, the cut-off
    governor's range and the chest; a bad one is refused when the scene is read."""
    text = find_scene("armington-sims-governor").read_text()
    good = tmp_path / "named.toml"
    good.write_text(text + '\n[compare]\nthrottled_setting = 0.2\nsetting_range = [0.1, 0.9]\n'
                    'chest_volume = "0.05 ft3"\npipe_diameter = "2.5 in"\n')
    scene = load_scene(good)
    assert scene.compare.throttled_setting == 0.2
    r = compare(scene, [1.0], condensation="off", fidelity="fast", workers=1)
    assert r.variants["throttling"]["fixed"] == 0.2
    assert r.variants["cutoff"]["knob_range"] == [0.1, 0.9]
    assert r.chest_volume_m3 == pytest.approx(0.05 * 0.3048 ** 3)
    assert r.pipe_diameter_m == pytest.approx(2.5 * 0.0254)
    bad = tmp_path / "bad.toml"
    bad.write_text(text + '\n[compare]\nsetting_range = [0.5, 1.5]\n')
    with pytest.raises(InputError, match="setting_range"):
        load_scene(bad)


def test_condensation_takes_much_of_early_cutoffs_advantage_on_a_small_engine(small):
    """Marks (*Relative Proportions of the Steam-Engine*) argues that a small engine may
    do better throttled: its walls are large for its steam, and the very short cut-off a
    cut-off governor gives it at light load condenses much of what it admits (Marks
    Arts. 74-75, 78).  The model (the skin wall, its default, at Callendar and Nicolson's
    measured condensing coefficient, 16.7 kW/(m2 K), DPJ 312, 1899, p. 164) bears out the
    mechanism but not the verdict: on the small high-speed engine at a tenth of its load,
    the cut-off governor's saving over throttling at a cut-off near half stroke (setting
    0.75) falls from 29 % without the walls to 16 % with them, its own missing water
    0.39 against the throttled engine's 0.31, and cut-off governing still wins.  Marks
    gives the direction, not the size, which is the wall's: with the dropwise 3e5
    W/(m2 K) the measured coefficient replaced, the walls took more than half (29 % ->
    12 %, missing water 0.84 against 0.49; the old bounds 0.5 and 1.3).  The test holds
    the mechanism with bounds the measured wall clears: the walls take at least two
    fifths of the saving (0.47 measured; 0.4 of 0.29 is 0.12 of saving, far above the
    fast tier's operating points, each within 1 % of its power), and the missing water
    is the greater at the short cut-off by more than a tenth (1.27 times measured)."""
    r = compare(small, [0.1], fidelity="fast", throttled_setting=0.75)
    pts = r.points.set_index(["variant", "condensation", "load_frac"])
    assert 0.4 < pts.loc[("throttling", "on", 0.1), "cutoff_head_frac"] < 0.6
    v = r.verdict.set_index(["condensation", "load_frac"])
    dry, wet = (v.loc[(c, 0.1), "cutoff_saving_frac"] for c in ("off", "on"))
    assert dry > 0.2 and wet < 0.6 * dry
    assert (pts.loc[("cutoff", "on", 0.1), "missing_water_frac"]
            > 1.1 * pts.loc[("throttling", "on", 0.1), "missing_water_frac"])


def test_governor_droop_sets_the_speed_of_each_load(study, small):
    """With a governor in the scene, each load runs at the speed its static
    characteristic balances at (Marks Art. 70): fastest at the lightest load; without
    droop, all at the scene's speed."""
    pts = study.points
    assert study.droop
    speed = pts.groupby("load_frac")["speed_rpm"].first()
    assert speed.is_monotonic_decreasing and speed.iloc[0] > small.run.speed_rpm > speed.iloc[-1]
    assert 0.02 < (speed.iloc[0] - speed.iloc[-1]) / small.run.speed_rpm < 0.1
    flat = compare(small, [1.0], condensation="off", fidelity="fast", droop=False, workers=1)
    assert list(flat.points["speed_rpm"]) == pytest.approx([small.run.speed_rpm] * 2)


def test_a_jacket_is_counted_in_the_studys_steam():
    """Marks Art. 79, p. 204: a jacket is paid for in steam, which the period's trials
    weighed with the feed.  A jacketed engine's point in the study carries the
    cylinder's steam and the jacket's (the steady summary's two figures), and its
    water rate is their sum over the indicated power."""
    import dataclasses

    import corliss
    from corliss.studies import compare as cmp
    sc = load_scene(find_scene("meyer-cutoff"))
    sc = dataclasses.replace(sc, engine=dataclasses.replace(sc.engine, jacket="barrel"))
    sc = sc.replace_run(effects=tuple(sc.run.effects) + ("wall_heat",)).with_fidelity("fast")
    row = cmp._run(sc, "setting", 0.4, None)
    s = corliss.simulate(cmp.at_knob(sc, "setting", 0.4)).summary
    assert s["jacket_steam_kg_per_h"] > 0.0
    assert row["steam_rate_kg_per_h"] == pytest.approx(
        s["steam_rate_kg_per_h"] + s["jacket_steam_kg_per_h"], rel=1e-9)
    assert row["water_rate_kg_per_kWh"] == pytest.approx(
        s["water_rate_with_jacket_kg_per_kWh"], rel=1e-9)


def test_constant_speed_is_the_default_said_and_matches_run_at_full_load(small):
    """By default every load runs at the scene's speed (the summary says so), and the
    chest's origin is stated.  A governed run of the same scene starts at full load
    (its load) where its governor balances that load: within 1 % of the speed the
    study's full-load point runs at (the bundled governor is set for its speed)."""
    import corliss
    r = compare(small, [1.0], condensation="off", fidelity="fast", workers=1)
    s = r.summary
    assert s["speed_basis"] == "constant" and not s["governor_droop_applied"]
    assert s["chest_volume_source"] == "default"
    assert s["willans_negative_intercepts"] == [] or all(
        w["willans_intercept_kg_per_h"] < 0 for w in s["willans"]
        if f"{w['variant']}/{w['condensation']}" in s["willans_negative_intercepts"])
    full = float(r.points["speed_rpm"].iloc[0])
    run = corliss.simulate(small.with_fidelity("fast").replace_run(duration_s=0.3)).summary
    assert run["start"]["status"] == "balanced"
    assert full == pytest.approx(run["start"]["speed_rpm"], rel=0.01)


def test_the_rated_power_is_the_full_load_not_the_first_of_a_step(small):
    """``[load]`` gives the reference load (fraction 1); a step "from 50 % to 100 %" is
    ``initial_fraction = 0.5``, ``step_fraction = 1``.  The rated power the study's
    loads are fractions of is the full load, 100 hp (745.69987 W each: 550 ft lbf/s),
    whatever the schedule starts at, not half of it; so with the scene as bundled
    (starting at full load)."""
    from corliss.scene.loader import scene_from_dict
    from corliss.studies.compare import rated_power_W

    data = {**small.data, "load": {**small.data["load"], "initial_fraction": 0.5,
                                   "step_fraction": 1.0}}
    stepped = scene_from_dict(data, name="stepped")
    assert stepped.load.fractions[0] == 0.5                                      # the premise
    for scene in (stepped, small):
        for brake in (False, True):
            # to 1e-6: the horsepower's watts written to eight figures
            assert rated_power_W(scene, brake) == pytest.approx(100 * 745.69987, rel=1e-6)


def test_compare_on_two_processes_gives_the_table_of_one_to_the_bit(small, tmp_path):
    """``compare`` on two processes runs its grid chains and operating points on the
    process's kept pool of workers (corliss.studies.pool); a task's numbers depend only
    on its inputs, so the table equals the one made here on one process, value for
    value and bit for bit (exact: no tolerance, a run is deterministic).  ``--jobs``
    reaches it from the command line, and a count of none is refused before any run."""
    kw = dict(condensation="off", fidelity="fast", droop=False)
    one = compare(small, [0.5, 1.0], workers=1, **kw)
    two = compare(small, [0.5, 1.0], workers=2, **kw)
    assert len(study_pool.worker_pids()) == 2 and two.workers == 2
    assert (one.points["status"] == "found").all()
    pd.testing.assert_frame_equal(one.points, two.points, check_exact=True)
    rc = main(["compare", "armington-sims-governor", "--loads", "0.5", "--jobs", "0",
               "--out", str(tmp_path / "none")])
    assert rc == 2 and not (tmp_path / "none").exists()
