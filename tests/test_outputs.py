"""Every bundled scene through the command line, as a user runs it, in both unit
systems: exit 0, every file there, every table parsed by pandas with the units its
names promise, every number finite; and writing is whole or nothing.
"""

from __future__ import annotations

import json
import math
import os
import re
import stat
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import corliss
from corliss.cli import commands as cli
from corliss.frames import columns
from corliss.keys import units
from corliss.scene.loader import bundled_scenes

SCENES = bundled_scenes()
ROOT = Path(__file__).resolve().parent.parent


def _mode(path: Path) -> str:
    return tomllib.loads(path.read_text())["run"].get("mode", "steady")


STEADY = [n for n, p in SCENES.items() if _mode(p) == "steady"]
TRANSIENT = [n for n, p in SCENES.items() if _mode(p) == "transient"]

#: Column suffixes each system may write (the suffix is the unit).
SYSTEM_SUFFIXES = {
    "US": {v[1] for v in columns.SUFFIXES.values()},
    "SI": {v[3] for v in columns.SUFFIXES.values()},
}
#: Suffixes only one system writes: seeing one in the other system is a mix-up.
ONLY = {"US": SYSTEM_SUFFIXES["US"] - SYSTEM_SUFFIXES["SI"],
        "SI": SYSTEM_SUFFIXES["SI"] - SYSTEM_SUFFIXES["US"]}


def _expected(name: str, transient: bool, stem: str | None = None) -> set[str]:
    tables = ("timeseries", "cycles") if transient else ("timeseries", "cycles", "cards")
    figs = ("loadstep",) if transient else ("card", "effort")
    if name in SCENES and "compound" in tomllib.loads(SCENES[name].read_text()):
        figs += ("lp_card",)
    stem = stem or name
    out = {f"{stem}.{t}.csv" for t in tables} | {f"{stem}.{t}.meta.json" for t in tables}
    return out | {f"{stem}.{f}.png" for f in figs} | {f"{stem}.summary.json"}


def _finite_json(obj, where=""):
    if isinstance(obj, dict):
        for k, v in obj.items():
            _finite_json(v, f"{where}.{k}")
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            _finite_json(v, f"{where}[{i}]")
    elif isinstance(obj, float):
        assert math.isfinite(obj), f"{where} = {obj}"


def _check_table(csv: Path, system: str) -> pd.DataFrame:
    df = pd.read_csv(csv)
    assert len(df) > 0, csv.name
    meta = json.loads(csv.with_suffix(".meta.json").read_text())
    assert list(meta["columns"]) == list(df.columns)
    assert meta["units_system"] == system
    for col in df.columns:
        unit = meta["columns"][col]
        if col in columns.INDEX_COLUMNS:
            continue
        sfx = col.rsplit("_", 1)[-1]
        assert any(col.endswith("_" + s) for s in SYSTEM_SUFFIXES[system]), (csv.name, col)
        assert not any(col.endswith("_" + s) and not any(col.endswith("_" + t) for t in
                                                         SYSTEM_SUFFIXES[system])
                       for s in ONLY["US" if system == "SI" else "SI"]), (csv.name, col, sfx)
        # every unit named in a meta file is one corliss.keys.units converts
        base = unit.replace(" absolute", "")
        if base != columns.DIMENSIONLESS:
            units.to_unit(1.0, base)
        values = df[col].to_numpy(dtype=float)
        assert np.isfinite(values).all(), (csv.name, col)
    return df


def _run(args, capsys) -> tuple[int, str, str]:
    code = cli.main(args)
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("system", ["US", "SI"])
@pytest.mark.parametrize("name", sorted(SCENES))
def test_every_scene_runs_in_both_unit_systems(name, system, tmp_path, capsys):
    transient = name in TRANSIENT
    args = ["run", name, "--out", str(tmp_path), "--units", system, "--fidelity", "fast"]
    args += ["--duration", "0.4 s"] if transient else ["--cycles", "2"]
    code, out, err = _run(args, capsys)
    assert code == 0, err
    assert "Traceback" not in err
    # the bundled scenes are in US units: their SI files carry the system in the stem
    stem = name if system == "US" else f"{name}.SI"
    assert {p.name for p in tmp_path.iterdir()} == _expected(name, transient, stem)
    for csv in tmp_path.glob("*.csv"):
        _check_table(csv, system)
    summary = json.loads((tmp_path / f"{stem}.summary.json").read_text())
    _finite_json(summary)
    assert summary["kind"] == ("transient" if transient else "steady")
    if transient:
        assert summary["simulated_s"] >= 0.4 and summary["final_speed_rpm"] > 0
    else:
        assert summary["indicated_power_W"] > 0
        assert summary["cycles_to_converge"] is None     # the cycle count was fixed
    # the printed account speaks the chosen system
    if not transient:
        assert ("ihp" in out) == (system == "US") and ("kW" in out) == (system == "SI")


@pytest.mark.parametrize("name", STEADY)
def test_events_and_gear_of_every_steady_scene(name, tmp_path, capsys):
    code, out, err = _run(["events", name, "--json"], capsys)
    assert code == 0, err
    ev = json.loads(out)
    for end in ("head", "crank"):
        for key, v in ev[end].items():
            assert v is None or math.isfinite(v), (end, key)
    code, out, err = _run(["gear", name, "--out", str(tmp_path)], capsys)
    assert code == 0, err
    assert [p.name for p in tmp_path.iterdir()] == [f"{name}.gear.png"]


def _snapshot(folder: Path) -> dict[str, tuple[bytes, int]]:
    return {str(p.relative_to(folder)): (p.read_bytes() if p.is_file() else b"dir",
                                         p.stat().st_mtime_ns)
            for p in sorted(folder.rglob("*"))}


def test_a_failure_in_a_figure_leaves_the_folder_as_it_was(tmp_path, capsys, monkeypatch):
    """An earlier run's files stay byte for byte when a later run fails while drawing,
    and nothing of the later run appears (no temporary file either)."""
    assert cli.main(["run", "--out", str(tmp_path), "--cycles", "2", "--fidelity", "fast"]) == 0
    (tmp_path / "notes.txt").write_text("the user's own file")
    before = _snapshot(tmp_path)

    def broken(*a, **k):
        raise RuntimeError("injected failure in the crank-effort plot")
    monkeypatch.setattr(corliss.plot, "plot_crank_effort", broken)
    with pytest.raises(RuntimeError, match="injected"):
        cli.main(["run", "--out", str(tmp_path), "--cycles", "3", "--fidelity", "fast"])
    assert _snapshot(tmp_path) == before


def test_a_failure_while_moving_files_into_place_restores_the_earlier_run(
        tmp_path, capsys, monkeypatch):
    """The last file of a run cannot be put in place (the disk fills, say): the files
    already moved are taken back and the earlier run's restored, byte for byte."""
    assert cli.main(["run", "--out", str(tmp_path), "--cycles", "2", "--fidelity", "fast"]) == 0
    before = _snapshot(tmp_path)
    real = os.replace
    failed = []

    def failing(src, dst):
        if str(dst).endswith("default.summary.json") and not failed:
            failed.append(dst)      # once: putting the earlier file back must work
            raise OSError(28, "No space left on device (injected)")
        return real(src, dst)
    monkeypatch.setattr(os, "replace", failing)
    code = cli.main(["run", "--out", str(tmp_path), "--cycles", "3", "--fidelity", "fast"])
    monkeypatch.setattr(os, "replace", real)
    # a full disk is the machine's state, not a traceback: a run that stopped (exit 5)
    assert code == cli.EXIT_RUN_STOPPED
    assert "No space left on device (injected)" in capsys.readouterr().err
    assert failed
    assert _snapshot(tmp_path) == before


def test_a_folder_where_a_file_goes_is_left_alone(tmp_path, capsys):
    """A folder standing where the summary goes stops the run's files before any moves."""
    summary = tmp_path / "default.summary.json"
    summary.mkdir()
    (summary / "keep").write_text("x")
    before = _snapshot(tmp_path)
    with pytest.raises(IsADirectoryError):
        cli.main(["run", "--out", str(tmp_path), "--cycles", "2", "--fidelity", "fast"])
    assert _snapshot(tmp_path) == before


def test_a_failed_run_into_a_new_folder_leaves_no_folder(tmp_path, monkeypatch):
    out = tmp_path / "new" / "deeper"

    def broken(*a, **k):
        raise RuntimeError("injected")
    monkeypatch.setattr(corliss.plot, "plot_card", broken)
    with pytest.raises(RuntimeError):
        cli.main(["run", "--out", str(out), "--cycles", "2", "--fidelity", "fast"])
    assert list(tmp_path.iterdir()) == []


def test_output_files_are_readable_by_group_and_others_under_a_022_umask(tmp_path):
    old = os.umask(0o022)
    try:
        assert cli.main(["run", "--out", str(tmp_path), "--cycles", "2", "--fidelity",
                         "fast"]) == 0
        scene = corliss.load_scene(SCENES["default"])
        r = corliss.simulate(scene.replace_run(cycles=2).with_fidelity("fast"))
        single = r.to_csv(tmp_path / "single" / "card.csv", table="cards")
    finally:
        os.umask(old)
    files = [p for p in tmp_path.rglob("*") if p.is_file()]
    assert len(files) == 11
    assert single in files
    for p in files:
        mode = stat.S_IMODE(p.stat().st_mode)
        assert mode & 0o044 == 0o044, (p.name, oct(mode))


@pytest.mark.parametrize("change", [
    # a plain valve whose lap is within 0.01 in of its eccentricity barely opens: the
    # card does no net work
    {"valve_gear": {"lap": "2.99 in", "lead": "0 in"}},
    # the engine run far past its speed: the ports throttle the steam to a negative card
    {"run": {"speed": "2000 rpm"}},
], ids=["barely-opening-valve", "far-past-its-speed"])
def test_cards_doing_no_work_are_results(change, tmp_path, capsys):
    text = SCENES["default"].read_text()
    for section, values in change.items():
        for k, v in values.items():
            text = re.sub(rf"(?m)^{k} = .*$", f'{k} = "{v}"', text, count=1)
    path = tmp_path / "noworkscene.toml"
    path.write_text(text)
    out = tmp_path / "out"
    code, printed, err = _run(["run", str(path), "--out", str(out), "--fidelity", "fast"], capsys)
    # a completed run that failed physically: exit 4 (docs/exit-codes.md), every file
    assert code == 4 and "negative_work" in err, err
    assert {p.name for p in out.iterdir()} == _expected("noworkscene", False)
    s = json.loads((out / "noworkscene.summary.json").read_text())
    assert s["indicated_power_W"] <= 0.0
    assert s["fluctuation_coefficient_c"] is None
    assert "no net work" in s["fluctuation_coefficient_note"]
    assert "undefined" in printed


def test_from_meta_reruns_a_result_exactly(tmp_path, capsys):
    """The meta file holds the scene's text and hash and the run's knobs as run (here
    overridden on the command line): rerunning from it gives the same numbers."""
    a = tmp_path / "a"
    assert cli.main(["run", "default", "--out", str(a), "--cycles", "2", "--fidelity",
                     "fast"]) == 0
    meta = json.loads((a / "default.cycles.meta.json").read_text())
    import hashlib
    assert meta["scene_sha256"] == hashlib.sha256(meta["scene_toml"].encode()).hexdigest()
    assert meta["scene_toml"] == SCENES["default"].read_text()
    assert meta["run"]["cycles"] == 2 and meta["run"]["fidelity"]["name"] == "fast"
    assert set(meta["versions"]) >= {"python", "numpy", "scipy", "CoolProp", "numba"}
    assert meta["wall_time_s"] > 0
    b = tmp_path / "b"
    capsys.readouterr()
    assert cli.main(["run", "--from-meta", str(a / "default.cycles.meta.json"),
                     "--out", str(b)]) == 0
    first = pd.read_csv(a / "default.cycles.csv")
    again = pd.read_csv(b / "default.cycles.csv")
    pd.testing.assert_frame_equal(first, again)


def test_version_and_bundled_scenes_by_name(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"corliss {corliss.__version__}"
    assert cli.main(["list", "scenes"]) == 0
    listed = capsys.readouterr().out
    for name, path in SCENES.items():
        title = tomllib.loads(path.read_text())["title"]
        assert f"{name}" in listed and title in listed
    assert cli.main(["events", "no-such-scene"]) == 2
    assert "bundled scene" in capsys.readouterr().err


def test_version_is_single_sourced():
    text = (ROOT / "pyproject.toml").read_text()
    assert 'dynamic = ["version"]' in text and "corliss.__version__" in text
    assert re.fullmatch(r"\d+\.\d+\.\d+", corliss.__version__)


def test_verbose_logs_corliss_only(tmp_path, capsys):
    """-v shows corliss's own messages and none of matplotlib's font debugging."""
    assert cli.main(["-v", "run", "--out", str(tmp_path), "--cycles", "2", "--fidelity",
                     "fast"]) == 0
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert lines, "nothing logged with -v"
    assert all(" corliss" in ln.split(":")[0] or ln.startswith("corliss") for ln in lines), lines
    assert "matplotlib" not in err and "findfont" not in err


def test_every_result_kind_exports_the_same_way(tmp_path):
    """Steady, transient and sweep results answer the same methods: to_pandas in SI or a
    system, to_csv of any table, plot returning what it drew."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    steady = corliss.simulate(corliss.load_scene(SCENES["default"]).replace_run(cycles=2)
                              .with_fidelity("fast"))
    gov = corliss.load_scene(SCENES["porter-allen-governor"]).replace_run(duration_s=0.4)
    transient = corliss.simulate(gov.with_fidelity("fast"))
    from corliss.studies.load_range import load_range
    sweep = load_range(corliss.load_scene(SCENES["corliss-governor"]).with_fidelity("fast"),
                       "setting", [0.4, 0.8])
    for r in (steady, transient, sweep):
        assert isinstance(r, corliss.Result)
        for table in r.TABLES:
            si = r.to_pandas(table)
            us = r.to_pandas(table, "US")
            assert len(si) == len(us) > 0
            path = r.to_csv(tmp_path / f"{r.kind}.{table}.csv", table=table)
            assert list(pd.read_csv(path).columns) == list(us.columns)
        drawn = r.plot()
        assert drawn.get("ax") is not None or drawn.get("figure") is not None
        plt.close("all")
    # the same quantity has one name in every kind of table
    assert "m_supply_kg" in steady.cycles and "m_supply_kg" in transient.cycles
    assert "work_J" in steady.cycles and "work_J" in transient.cycles
    assert "rhs_evaluations" in steady.summary and "rhs_evaluations" in transient.summary


def test_csv_writer_writes_what_pandas_writes_and_reads_back(tmp_path):
    """The fast CSV writer gives the text pandas' writer gave (nine significant digits,
    NaN as an empty field, integers as integers), for tables of numbers and, through
    pandas, for tables with text; a re-read gives every number back to 5e-9 relative."""
    from corliss.files.run_output import write_csv
    rng = np.random.default_rng(3)
    n = 500
    numbers = pd.DataFrame({
        "cycle": np.repeat(np.arange(1, 6), n // 5),
        "time_s": np.linspace(0.0, 3.0, n),
        "p_head_psia": 10.0 ** rng.uniform(-4, 7, n) * rng.choice([-1.0, 1.0], n),
        "x_head_frac": np.where(rng.random(n) < 0.1, np.nan, rng.random(n)),
        "odd_values": np.resize([0.0, -0.0, np.inf, -np.inf, 1e-300, 123456789.123], n),
    })
    text = numbers.head(20).assign(winner="cut-off, by far", ok=True)
    for frame in (numbers, text, numbers.head(0)):
        ours, theirs = tmp_path / "ours.csv", tmp_path / "theirs.csv"
        write_csv(frame, ours)
        frame.to_csv(theirs, index=False, float_format="%.9g", lineterminator="\n")
        assert ours.read_bytes() == theirs.read_bytes()
    write_csv(numbers, tmp_path / "n.csv")
    back = pd.read_csv(tmp_path / "n.csv")
    finite = np.isfinite(numbers["p_head_psia"])
    np.testing.assert_allclose(back["p_head_psia"][finite], numbers["p_head_psia"][finite],
                               rtol=5e-9, atol=0.0)
    assert back["x_head_frac"].isna().equals(numbers["x_head_frac"].isna())
    assert back["cycle"].dtype.kind == "i"
