"""``corliss study``: designs over scene keys, run locally or on a Dask cluster, one table.

The physics first (a study's rows follow the closed form of the card their scene
gives, and the crank-resolved engine the period's trends), then the designs, then the
plumbing a user leans on: the same table serially, on processes and on Dask; every
row's scene rebuilt from the files; bad input refused before any run, with nothing
written.
"""

from __future__ import annotations

import copy
import json
import math
import sys
import tomllib

import numpy as np
import pandas as pd
import pytest

import corliss
from corliss.files import study_output
from corliss.engine.model import steady_scene
from corliss.engine.steady import run_steady
from corliss.errors import InputError, RunError
from corliss.scene.loader import find_scene, scene_from_dict
from corliss.keys.edits import parse_distribution, with_keys
from corliss.studies import make_design, response_keys
from corliss.studies import runner as study_runner
from corliss.studies.responses import flatten
from conftest import BASE

#: psi in Pa (exact: 0.45359237 kg x 9.80665 m/s2 / 0.0254**2 m2).
PSI_Pa = 0.45359237 * 9.80665 / 0.0254 ** 2


def _base(**run):
    data = copy.deepcopy(BASE)
    data["run"].update(run)
    return data


def hyperbolic_mep(f_cut, f_rel, f_comp, c, p1, pb):
    """Mean effective pressure of one end's hyperbolic card [Pa] (Marks, *Relative
    Proportions of the Steam-Engine*, Arts. 72-73: expansion and compression along
    pV = const), over its own swept volume V_s, clearance c V_s.

    With V(f) = V_s (c + f): admission at p1 from f = 0 to f_cut does
    p1 V_s f_cut; expansion to release p1 V(f_cut) ln(V(f_rel) / V(f_cut)); the
    exhaust at pb from release to the end and back to compression -pb V_s (f_rel -
    f_comp); compression to dead centre -pb V(f_comp) ln(V(f_comp) / V(0)); release
    and admission are vertical lines and do no work.  Divided by V_s:
    """
    return (p1 * f_cut + p1 * (f_cut + c) * np.log((f_rel + c) / (f_cut + c))
            - pb * (f_rel - f_comp) - pb * (f_comp + c) * np.log((f_comp + c) / c))


# --- physics -------------------------------------------------------------------------------

def test_the_ideal_card_over_clearance_and_pressure_follows_its_closed_form():
    """A Latin hypercube over clearance (2 to 20 % of the stroke's volume) and supply
    pressure (60 to 140 psig) of the algebraic card: every row's m.e.p., both ends,
    is the hyperbolic card's closed form (:func:`hyperbolic_mep`) at that row's
    clearance and pressure, converted here from the row's numbers in their units
    (psig + the scene's 14.696 psia barometer).  So each row carries the scene it was
    run with: a row holding another run's keys misses by the 10-40 % the m.e.p.
    moves across the design.

    Tolerance 1e-5 relative: the model integrates its card as a polygon of 2000 points
    per process; the trapezoid rule's error on a hyperbola over steps of dV/V <= 4e-3
    is below 3e-6 of the work.
    """
    r = corliss.study(_base(model="ideal", expansion="hyperbolic"),
                      ["engine.clearance=0.02:0.2", "supply.pressure=60:140psig"], lhs=8,
                      seed=3, jobs=1,
                      responses=["mep_head_Pa", "mep_crank_Pa"]
                      + [f"events.{e}.{k}_frac" for e in ("head", "crank")
                         for k in ("cutoff", "release", "compression")])
    p = r.points
    assert (p["status"] == "ok").all()
    c = p["engine.clearance_frac"].to_numpy()
    p1 = (p["supply.pressure_psig"].to_numpy() + 14.696) * PSI_Pa
    pb = 14.696 * PSI_Pa
    for end in ("head", "crank"):
        ev = {k: p[f"events.{end}.{k}_frac"].to_numpy() for k in
              ("cutoff", "release", "compression")}
        want = hyperbolic_mep(ev["cutoff"], ev["release"], ev["compression"], c, p1, pb)
        got = p[f"mep_{end}_Pa"].to_numpy()
        assert got == pytest.approx(want, rel=1e-5)
        assert got.max() / got.min() > 1.4, "the design spans a real change of m.e.p."


def test_more_lap_cuts_off_earlier_for_less_power_and_less_steam_per_horse_power():
    """A grid over the steam lap of the default engine's plain slide valve (0.6 to
    1.4 in, lead held at 0.25 in) at 60 rpm, crank-resolved: more lap cuts off earlier
    (Spangler, *Valve-Gears*, Art. 25: a plain valve shortens its cut-off only by
    more lap), so the engine makes less power on less steam, and with the longer
    expansion each horse-power costs less steam (Marks Art. 2).  Strictly monotone,
    each step of 0.2 in moving the head end's cut-off by at least 0.02 of the stroke.

    And each card stays near Marks's hyperbolic card at its own events (Arts. 72-73:
    it "coincides, with great accuracy" with good cards): within 3 %, the difference
    being the real card's rounded release and compression and the steam's own
    expansion curve (1.0-2.7 % here, at the default's 8 % clearance).
    """
    r = corliss.study(_base(speed="60 rpm"), ["valve_gear.lap=0.6:1.4in"], grid=True,
                      levels=5, fidelity="fast", jobs=2,
                      responses=["indicated_power_W", "water_rate_kg_per_kWh",
                                 "mep_head_Pa", "supply_pressure_Pa", "exhaust_pressure_Pa"]
                      + [f"events.head.{k}_frac" for k in ("cutoff", "release", "compression")])
    p = r.points.sort_values("valve_gear.lap_in")
    assert p["valve_gear.lap_in"].tolist() == pytest.approx([0.6, 0.8, 1.0, 1.2, 1.4])
    cut = p["events.head.cutoff_frac"].to_numpy()
    assert np.all(np.diff(cut) < -0.02)
    assert np.all(np.diff(p["indicated_power_W"].to_numpy()) < 0)
    assert np.all(np.diff(p["water_rate_kg_per_kWh"].to_numpy()) < 0)
    want = hyperbolic_mep(cut, p["events.head.release_frac"].to_numpy(),
                          p["events.head.compression_frac"].to_numpy(), 0.08,
                          p["supply_pressure_Pa"].to_numpy(), p["exhaust_pressure_Pa"].to_numpy())
    assert p["mep_head_Pa"].to_numpy() == pytest.approx(want, rel=0.03)


# --- designs -------------------------------------------------------------------------------

def test_a_latin_hypercube_puts_one_run_in_each_stratum_of_every_key():
    """McKay et al. (1979): n runs, each key's range in n equal strata, one run in each;
    a normal key's strata are of equal probability (its inverse distribution)."""
    from scipy.special import ndtr
    n = 40
    d = make_design(["valve_gear.lap=0.8:1.2in", "run.speed=normal(120,5)rpm"], lhs=n, seed=7)
    lap = d.values[:, 0]
    assert sorted(np.floor((lap - 0.8) / 0.4 * n).astype(int)) == list(range(n))
    u = ndtr((d.values[:, 1] - 120.0) / 5.0)
    assert sorted(np.floor(u * n).astype(int)) == list(range(n))
    again = make_design(["valve_gear.lap=0.8:1.2in", "run.speed=normal(120,5)rpm"], lhs=n, seed=7)
    assert np.array_equal(d.values, again.values), "a seed gives the same runs"
    other = make_design(["valve_gear.lap=0.8:1.2in", "run.speed=normal(120,5)rpm"], lhs=n, seed=8)
    assert not np.array_equal(d.values, other.values)


def test_monte_carlo_draws_follow_their_distributions():
    """4000 draws: the normal's mean within 4 standard errors (5/sqrt(4000) rpm) and its
    standard deviation within 5 %; the triangular's mean (a + c + b) / 3 within 4
    standard errors (its sd is sqrt((a2+b2+c2-ab-ac-bc)/18))."""
    d = make_design(["run.speed=normal(120,5)rpm", "valve_gear.lap=triangular(0.8,1.1,1.2)in"],
                    monte_carlo=4000, seed=1)
    v, w = d.values[:, 0], d.values[:, 1]
    assert abs(v.mean() - 120.0) < 4 * 5.0 / math.sqrt(4000)
    assert v.std() == pytest.approx(5.0, rel=0.05)
    a, c, b = 0.8, 1.1, 1.2
    sd = math.sqrt((a * a + b * b + c * c - a * b - a * c - b * c) / 18.0)
    assert abs(w.mean() - (a + b + c) / 3.0) < 4 * sd / math.sqrt(4000)
    assert w.min() >= a and w.max() <= b


def test_a_grid_is_the_full_factorial_first_key_slowest():
    d = make_design(["valve_gear.lap=0.8:1.2in", "engine.clearance=0.05,0.1"], grid=True,
                    levels=3)
    assert d.values.tolist() == [[0.8, 0.05], [0.8, 0.1], [1.0, 0.05], [1.0, 0.1],
                                 [1.2, 0.05], [1.2, 0.1]]
    assert d.columns == ["valve_gear.lap_in", "engine.clearance_frac"]


@pytest.mark.parametrize("spec, key", [
    ("run.speed=normal(120,0)rpm", "--vary run.speed"),          # sd not above 0
    ("run.speed=normal(120rpm,5in)", "--vary run.speed"),        # two units
    ("run.speed=lognormal(1,2)rpm", "--vary run.speed"),         # unknown distribution
    ("run.speed=triangular(100,150,140)rpm", "--vary run.speed"),  # mode beyond high
])
def test_a_bad_distribution_names_its_key(spec, key):
    with pytest.raises(InputError) as err:
        parse_distribution(spec)
    assert err.value.key == key


# --- the same table wherever it runs --------------------------------------------------------

VARY = ["valve_gear.lap=0.8:1.2in", "engine.clearance=0.05:0.12", "run.speed=90:150rpm"]


def _small(**kw):
    return corliss.study(_base(), VARY, lhs=5, seed=11, fidelity="fast",
                         responses=["indicated_power_W", "steam_rate_kg_per_h",
                                    "events.head.cutoff_frac", "cycles_to_converge"], **kw)


def test_a_study_on_a_local_dask_cluster_equals_the_serial_study_row_for_row():
    """Five runs, one a task, on two Dask worker processes against the same five in this
    process: equal to the last bit (the same compiled kernels on the same inputs give
    the same numbers; nothing in a run depends on the process it runs in)."""
    distributed = pytest.importorskip("distributed")
    serial = _small(jobs=1)
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster:
        on_dask = _small(scheduler=cluster.scheduler_address, chunk_size=1)
    assert on_dask.scheduler == cluster.scheduler_address and on_dask.workers == 2
    assert (serial.points["status"] == "ok").all()
    pd.testing.assert_frame_equal(on_dask.points, serial.points, check_exact=True)
    pooled = _small(jobs=2, chunk_size=2)
    pd.testing.assert_frame_equal(pooled.points, serial.points, check_exact=True)


def test_every_row_rebuilds_the_scene_it_ran_from_the_csv_and_the_parquet(tmp_path):
    """The scene rebuilt from a row read back from either file is the scene that was
    run: rerun, it gives the row's power exactly."""
    r = _small(jobs=1)
    files = r.write(tmp_path, plots=True)
    assert {"points", "parquet", "base", "study", "summary"} <= set(files)
    meta = json.loads(files["points"].with_name("scene.study.meta.json").read_text())
    assert tomllib.loads(files["base"].read_text()) == r.base_data == _base()
    assert [v["column"] for v in meta["varied"]] == ["valve_gear.lap_in",
                                                     "engine.clearance_frac", "run.speed_rpm"]
    for kind in ("points", "parquet"):
        frame, _ = study_output.read_study(files[kind])
        assert frame["run_id"].tolist() == list(range(5))
        for col in ("valve_gear.lap_in", "engine.clearance_frac", "run.speed_rpm"):
            assert np.array_equal(frame[col].to_numpy(), r.points[col].to_numpy())
    for run_id in (0, 3):
        sc = study_output.study_scene(files["parquet"], run_id)
        assert sc == study_output.study_scene(files["points"], run_id) == r.scene_of(run_id)
        got = run_steady(steady_scene(sc)).summary["indicated_power_W"]
        assert got == r.points.loc[run_id, "indicated_power_W"]


def test_a_run_that_stops_is_a_row_with_its_error(monkeypatch):
    """A run whose solver gives up leaves a failed row (NaN responses, the reason) and
    the other runs stand."""
    real = study_runner.run_steady

    def flaky(scene):
        if scene.run.speed_rpm > 140.0:
            raise RunError("the cycle did not become periodic (test)")
        return real(scene)

    monkeypatch.setattr(study_runner, "run_steady", flaky)
    r = corliss.study(_base(), ["run.speed=100,120,150rpm"], grid=True, fidelity="fast", jobs=1)
    p = r.points
    assert p["status"].tolist() == ["ok", "ok", "failed"]
    assert "did not become periodic" in p.loc[2, "error"]
    assert np.isnan(p.loc[2, "indicated_power_W"]) and p.loc[1, "indicated_power_W"] > 0
    assert r.summary["failed"] == 1


# --- refused before any run ---------------------------------------------------------------

def _no_run(monkeypatch):
    def boom(*a, **k):
        raise AssertionError("a run started")
    monkeypatch.setattr(study_runner, "run_chunk", boom)


def test_an_unknown_response_is_refused_naming_the_valid_ones(monkeypatch, tmp_path, capsys):
    from corliss.cli.commands import main
    _no_run(monkeypatch)
    out = tmp_path / "out"
    rc = main(["study", "default", "--vary", "valve_gear.lap=0.8:1.2in", "--grid",
               "--response", "indicated_power_kW", "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and not out.exists()
    assert "--response = 'indicated_power_kW'" in err and "indicated_power_hp" in err


def test_a_value_the_loader_refuses_is_named_with_its_run(monkeypatch, tmp_path, capsys):
    """Clearance below the loader's least (0.005) at the low end of the range: refused
    before any run, naming the key, the value and the run; nothing written."""
    from corliss.cli.commands import main
    _no_run(monkeypatch)
    out = tmp_path / "out"
    rc = main(["study", "default", "--vary", "engine.clearance=0.001:0.1", "--lhs", "4",
               "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 2 and not out.exists()
    assert "engine.clearance" in err and "(run " in err


def test_a_misspelt_key_is_refused(monkeypatch):
    _no_run(monkeypatch)
    with pytest.raises(InputError) as err:
        corliss.study(_base(), ["valve_gear.lapp=0.8:1.2in"], grid=True)
    assert err.value.key == "valve_gear.lapp"


def test_without_distributed_the_scheduler_says_how_to_get_it(monkeypatch):
    _no_run(monkeypatch)
    monkeypatch.setitem(sys.modules, "distributed", None)
    with pytest.raises(InputError) as err:
        corliss.study(_base(), ["valve_gear.lap=0.8:1.2in"], grid=True,
                      scheduler="tcp://127.0.0.1:8786")
    assert err.value.key == "--scheduler" and "corliss[dask]" in str(err.value)


def test_jobs_and_a_scheduler_together_are_refused(monkeypatch):
    _no_run(monkeypatch)
    with pytest.raises(InputError) as err:
        corliss.study(_base(), ["valve_gear.lap=0.8:1.2in"], grid=True, jobs=2,
                      scheduler="tcp://127.0.0.1:8786")
    assert err.value.key == "--jobs"


def test_without_pyarrow_the_csv_is_written_alone(monkeypatch, tmp_path):
    r = corliss.study(_base(model="ideal"), ["engine.clearance=0.05,0.1"], grid=True, jobs=1)
    monkeypatch.setattr(study_output, "have_parquet", lambda: False)
    with pytest.raises(InputError) as err:
        r.write(tmp_path / "a", parquet=True)
    assert "corliss[parquet]" in str(err.value) and not (tmp_path / "a").exists()
    files = r.write(tmp_path / "b", plots=False)
    assert "parquet" not in files and files["points"].exists()


# --- the responses a study may ask for ---------------------------------------------------

@pytest.mark.parametrize("changes", [
    {},
    {"run.effects": ["port_flow", "rod_angularity", "wall_heat"]},
    {"run.effects": ["port_flow", "rod_angularity", "friction", "steam_chest"],
     "engine.friction_torque": "200 lbf ft", "supply.chest_volume": "1 ft3",
     "supply.pipe_diameter": "4 in"},
])
def test_the_responses_offered_are_the_numbers_the_summary_gives(changes):
    """The list a study checks ``--response`` against is exactly the summary's numbers,
    for the plain engine, with the skin wall, and with friction and a steam chest."""
    sc = scene_from_dict(with_keys(_base(), changes)).with_fidelity("fast")
    got = set(flatten(run_steady(steady_scene(sc)).summary))
    assert set(response_keys(sc)) == got


@pytest.mark.parametrize("name", ["marks-compound-9-14x14", "twin-90-degrees"])
def test_the_responses_offered_for_a_compound_and_a_twin(name):
    """The same for a compound (its LP cylinder's ends and events) and for two
    cylinders on one shaft."""
    sc = steady_scene(corliss.load_scene(find_scene(name)).with_fidelity("fast"))
    got = set(flatten(run_steady(sc).summary))
    assert set(response_keys(sc)) == got


def test_the_command_writes_the_table_and_prints_the_summary_as_json(tmp_path, capsys):
    """``corliss study --json``: the summary on stdout, the files in --out."""
    from corliss.cli.commands import main
    rc = main(["study", "default", "--vary", "engine.clearance=0.05,0.1", "--vary",
               "run.speed=100:140rpm", "--grid", "--levels", "2", "--fidelity", "fast",
               "--jobs", "1", "--response", "indicated_power_hp", "--json",
               "--out", str(tmp_path)])
    s = json.loads(capsys.readouterr().out)
    assert rc == 0 and s["runs"] == 4 and s["design"] == "grid" and s["failed"] == 0
    assert s["responses"] == ["indicated_power_hp"]
    frame = pd.read_csv(tmp_path / "default.study.csv")
    assert list(frame.columns) == ["run_id", "engine.clearance_frac", "run.speed_rpm",
                                   "indicated_power_hp", "status", "error"]
    assert frame["run.speed_rpm"].tolist() == [100.0, 140.0, 100.0, 140.0]
    assert (tmp_path / "default.study.parquet").exists()
    assert (tmp_path / "default.study.png").exists()


def test_the_table_in_us_units_converts_the_responses_and_keeps_the_keys(tmp_path):
    """``to_pandas("points", "US")``: watts to horse-power (745.7 W each), Pa to psia; the
    varied keys as given; ``to_csv`` writes the same with its meta file."""
    r = corliss.study(_base(model="ideal"), ["engine.clearance=0.05,0.1"], grid=True, jobs=1,
                      responses=["indicated_power_W", "mep_mean_Pa",
                                 "fluctuation_coefficient_c"])
    us = r.to_pandas("points", "US")
    assert list(us.columns) == ["run_id", "engine.clearance_frac", "indicated_power_hp",
                                "mep_mean_psia", "fluctuation_coefficient_c", "status",
                                "error"]
    assert us["indicated_power_hp"].to_numpy() == pytest.approx(
        r.points["indicated_power_W"].to_numpy() / 745.69987158227022, rel=1e-12)
    assert us["mep_mean_psia"].to_numpy() == pytest.approx(
        r.points["mep_mean_Pa"].to_numpy() / PSI_Pa, rel=1e-12)
    path = r.to_csv(tmp_path / "s.csv", units_system="US")
    meta = json.loads((tmp_path / "s.meta.json").read_text())
    assert meta["columns"]["indicated_power_hp"] == "hp"
    assert list(pd.read_csv(path).columns) == list(us.columns)
