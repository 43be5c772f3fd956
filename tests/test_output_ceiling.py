"""A ceiling on what a run writes, and memory that does not grow with what it does not.

``--cycles 1000000000`` was taken and the run's memory grew about 11 MB/s without end:
every cycle's samples were kept.  A run's time series is now counted before any work
(:func:`corliss.engine.output_size.output_samples`) and refused over
:data:`corliss.keys.limits.MAX_OUTPUT_SAMPLES` rows, and a steady run recording once a
cycle (``[run] record = "cycle"``) lets each cycle's samples go once the next has run.

The count is a closed form, checked here against the rows runs write: a steady
crank-resolved cycle sampled every ``d`` degrees from 0 to 360 inclusive has
``360 / d + 1`` rows (the fast preset's 2 deg: 181), ``n`` cycles ``n`` times that; once
a cycle, ``n - 1`` rows and the last cycle's 181.
"""

from __future__ import annotations

import dataclasses
import gc
import tracemalloc
from pathlib import Path

import pytest

from corliss.cli import commands as cli
from corliss.engine.output_size import check_output_samples, output_samples, samples_per_cycle
from corliss.engine.simulate import simulate
from corliss.errors import InputError
from corliss.keys import limits
from corliss.scene.loader import bundled_scenes, load_scene, scene_from_dict

SCENES = bundled_scenes()
DEFAULT = SCENES["default"]


def _data(path: Path) -> dict:
    import tomllib
    return tomllib.loads(path.read_text(encoding="utf-8"))


def _scene(path: Path = DEFAULT, **run) -> object:
    data = _data(path)
    data["run"].update(run)
    return scene_from_dict(data, name="ceiling")


@pytest.mark.parametrize("record, rows", [("degree", 3 * 181), ("cycle", 2 + 181)])
def test_the_count_is_the_rows_a_steady_run_writes(record, rows):
    """361 - 180 = 181 rows a cycle at the fast preset's 2 deg, 0 and 360 both written;
    the count before the run and the rows after it must agree exactly."""
    scene = _scene(fidelity="fast", cycles=3, record=record)
    assert samples_per_cycle(scene.run) == 360 // 2 + 1
    assert output_samples(scene.run)[0] == rows
    ts = simulate(scene).frame("timeseries")
    assert len(ts["cycle"]) == rows
    # once a cycle: each earlier cycle's row is its start, the last cycle whole
    if record == "cycle":
        assert list(ts["crank_angle_deg"][:2]) == [0.0, 360.0]
        assert list(ts["cycle"][:3]) == [1, 2, 3]


def test_a_cycle_recorded_once_gives_the_same_last_cycle_and_balances():
    """Recording once a cycle changes what is kept, not what is computed: the last
    cycle's samples and every cycle's balances are the same numbers."""
    full = simulate(_scene(fidelity="fast", cycles=3))
    once = simulate(_scene(fidelity="fast", cycles=3, record="cycle"))
    a, b = full.frame("timeseries"), once.frame("timeseries")
    for col in ("p_head_Pa", "m_crank_kg", "time_s"):
        assert list(a[col][-181:]) == list(b[col][-181:])
        assert list(a[col][0::181][:2]) == list(b[col][:2])
    assert full.summary["indicated_power_W"] == once.summary["indicated_power_W"]


def test_the_ideal_port_grid_is_counted_at_its_own_step():
    """Without port_flow the time series holds the 0.25 deg equilibrium grid and the
    ports' kinks, whatever the output step: the count is its 1,441 points and an
    allowance for the kinks, never fewer than written."""
    scene = _scene(fidelity="fast", cycles=2, effects=["rod_angularity"])
    n = len(simulate(scene).frame("timeseries")["cycle"])
    assert 2 * 1441 <= n <= output_samples(scene.run)[0]
    # once a cycle: the first cycle's start, then the last cycle's grid
    once = _scene(fidelity="fast", cycles=2, effects=["rod_angularity"], record="cycle")
    ts = simulate(once).frame("timeseries")
    assert len(ts["cycle"]) == 1 + n // 2 and list(ts["cycle"][:2]) == [1, 2]


def test_the_command_line_refuses_cycles_over_the_ceiling_before_any_work(tmp_path, capsys):
    """10,000 cycles at the reference's 0.25 deg are 1,441 x 10,000 = 14.41 million rows,
    over the 5 million: refused (exit 2), naming --cycles, its value, the count and the
    ceiling, nothing written; at the standard 1 deg they are 3.61 million, taken."""
    out = tmp_path / "out"
    code = cli.main(["run", "--fidelity", "reference", "--cycles", "10000", "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "Traceback" not in err
    assert "--cycles = 10000" in err and "14,410,000" in err
    assert f"{limits.MAX_OUTPUT_SAMPLES:,}" in err and 'record = "cycle"' in err
    assert not out.exists()
    standard = dataclasses.replace(load_scene(DEFAULT).run, cycles=limits.MAX_CYCLES)
    assert output_samples(standard)[0] == 361 * 10_000 <= limits.MAX_OUTPUT_SAMPLES
    check_output_samples(standard)


def test_a_transient_recording_every_degree_for_an_hour_is_refused(tmp_path, capsys):
    """An hour at 300 rpm is 18,000 turns; at 360 rows a turn, 6.48 million rows:
    refused naming --duration.  The same hour once a turn is 18,000 rows."""
    path = tmp_path / "degree.toml"
    text = SCENES["armington-sims-governor"].read_text(encoding="utf-8")
    path.write_text(text.replace("[run]\n", "[run]\nrecord = \"degree\"\n", 1),
                    encoding="utf-8")
    code = cli.main(["run", str(path), "--duration", "3600 s", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 2 and "--duration = '3600 s'" in err and "Traceback" not in err
    assert not (tmp_path / "o").exists()
    run = dataclasses.replace(load_scene(str(path)).run, duration_s=3600.0, record="cycle")
    assert output_samples(run)[0] == round(3600.0 * run.speed_rpm / 60.0)


def test_a_scene_over_the_ceiling_is_refused_when_loaded():
    """A scene's own run is counted as it is loaded: 1,441 x 5,000 = 7.2 million rows."""
    with pytest.raises(InputError) as e:
        _scene(fidelity="reference", cycles=5000)
    assert e.value.key == "run.cycles" and e.value.value == 5000
    assert "7,205,000" in e.value.expected


def test_a_run_until_periodic_is_counted_at_its_most_cycles():
    """Until periodic, a run may take max_cycles (at most 1,000), three times that with
    wall_heat: 1,441 x 3,000 = 4,323,000 rows at the reference's step, the most a scene
    can ask for this way, under the ceiling; a max_cycles beyond the scene's range (a
    fidelity built in Python) is refused naming run.max_cycles."""
    scene = _scene(fidelity="reference", max_cycles=1000, effects=["port_flow", "wall_heat"])
    assert output_samples(scene.run)[0] == 1441 * 3000 <= limits.MAX_OUTPUT_SAMPLES
    fid = dataclasses.replace(scene.run.fidelity, max_cycles=2000)
    with pytest.raises(InputError) as e:
        check_output_samples(dataclasses.replace(scene.run, fidelity=fid))
    assert e.value.key == "run.max_cycles" and e.value.value == 2000


def test_simulate_counts_a_run_changed_after_loading():
    """The Python path: a run changed with replace_run is refused by simulate before
    any work, as the command line refuses it."""
    scene = _scene(fidelity="reference").replace_run(cycles=limits.MAX_CYCLES)
    with pytest.raises(InputError) as e:
        simulate(scene)
    assert e.value.key == "run.cycles" and e.value.value == limits.MAX_CYCLES


def test_a_steady_run_does_not_record_integrator_steps():
    with pytest.raises(InputError) as e:
        _scene(record="step")
    assert e.value.key == "run.record" and "steady" in e.value.expected


def _peak_bytes(scene) -> int:
    """Peak memory traced while the run runs, above what was held before it [bytes]."""
    gc.collect()
    tracemalloc.start()
    try:
        before = tracemalloc.get_traced_memory()[0]
        tracemalloc.reset_peak()
        result = simulate(scene)
        peak = tracemalloc.get_traced_memory()[1] - before
    finally:
        tracemalloc.stop()
    assert result.summary["cycles_simulated"] == scene.run.cycles
    return peak


def test_memory_does_not_grow_with_cycles_that_are_not_recorded():
    """A steady run recording once a cycle at the reference's 0.25 deg output step
    (1,441 samples a cycle; the table tier and dopri5 for speed): 20 and 80 cycles.

    What the run records for the 60 cycles more grows: a row of the cycles table
    (some 40 values, a dict of floats) and a row of the time series, a few kB a cycle;
    measured, the peaks (0.87 and 0.97 MB above the start) differ by 0.1 MB.  Kept
    whole, each cycle's samples (the volumes' states at 1,441 angles) and the time
    series made of them took 0.26 MB a cycle: 15 MB more for the 60 (measured with
    the letting-go switched off: 5.6 against 21 MB).  So the peaks must agree within
    1 MB: ten times the growth of what is recorded, a fifteenth of what keeping the
    cycles adds."""
    knobs = {"fidelity": "reference", "properties": "table", "method": "dopri5",
             "rtol": 1e-6, "record": "cycle"}
    n = 20
    simulate(_scene(cycles=2, **knobs))             # compiled and loaded before measuring
    small = _peak_bytes(_scene(cycles=n, **knobs))
    large = _peak_bytes(_scene(cycles=4 * n, **knobs))
    print(f"peak above the start: {n} cycles {small / 1e6:.2f} MB, {4 * n} cycles "
          f"{large / 1e6:.2f} MB")
    assert large - small < 1_000_000, (small, large)
