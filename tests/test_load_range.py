"""The load range by governor position: cut-off against throttling, in steady cards."""

from pathlib import Path

import numpy as np
import pytest

import corliss
from corliss.cli import commands as cli
from corliss.studies.load_range import load_range, willans_fit
from corliss.errors import InputError

SCENES = Path(__file__).resolve().parent.parent / "scenes"
CORLISS = SCENES / "corliss-governor.toml"


@pytest.fixture(scope="module")
def sweeps():
    scene = corliss.load_scene(CORLISS)
    cutoff = load_range(scene, "setting", [0.2, 0.4, 0.6, 0.8, 1.0]).points
    # the same engine throttled with its valves latched, near three-quarter cut-off
    import dataclasses
    from corliss.engine.model import build_gear
    latched = dataclasses.replace(
        scene, gear=build_gear(scene).with_setting(1.2).spec,
        supply=dataclasses.replace(scene.supply, chest_volume_m3=0.028, pipe_diameter_m=0.0762),
        run=dataclasses.replace(scene.run, effects=scene.run.effects + ("steam_chest",)))
    throttle = load_range(latched, "throttle", [0.06, 0.1, 0.15, 0.25]).points
    return cutoff, throttle


def test_cut_off_governing_has_an_economical_cut_off(sweeps):
    """Marks Art. 2: with cut-off governing the steam per horse-power-hour is least at
    a middling cut-off; at very short cut-offs the clearance, compression and friction
    of the load eat the card, at long ones the steam is expanded little.  So the water
    rate of the sweep has its minimum inside the range, and the power rises with the
    cut-off throughout."""
    cutoff, _ = sweeps
    wr = cutoff["water_rate_kg_per_kWh"].to_numpy()
    k = int(np.argmin(wr))
    assert 0 < k < len(wr) - 1
    assert np.all(np.diff(cutoff["indicated_power_W"].to_numpy()) > 0)
    assert np.all(np.diff(cutoff["cutoff_head_frac"].to_numpy()) > 0)


def test_throttling_costs_more_steam_at_the_same_power(sweeps):
    """Throttled steam enters at reduced pressure and is expanded little (Marks Art. 97):
    at every power the throttled engine's Willans line lies above the cut-off engine's
    (compared where both sweeps reach, on the throttled sweep's own points), and the
    throttled line is straight (Willans's law, R^2 above 0.99)."""
    cutoff, throttle = sweeps
    p_c = cutoff["indicated_power_W"].to_numpy()
    s_c = cutoff["steam_rate_kg_per_h"].to_numpy()
    inside = throttle[(throttle["indicated_power_W"] > p_c.min())
                      & (throttle["indicated_power_W"] < p_c.max())]
    assert len(inside) >= 2
    for _, row in inside.iterrows():
        assert row["steam_rate_kg_per_h"] > np.interp(row["indicated_power_W"], p_c, s_c)
    assert willans_fit(throttle)[2] > 0.99


def test_cli_sweep_writes_table_meta_and_willans(tmp_path, capsys):
    assert cli.main(["sweep", str(CORLISS), "--settings=0.3,0.7", "--out", str(tmp_path)]) == 0
    for suffix in ("sweep.csv", "sweep.meta.json", "willans.png"):
        assert (tmp_path / f"corliss-governor.{suffix}").is_file()
    assert cli.main(["sweep", str(CORLISS), "--throttle=0.5,1", "--out", str(tmp_path / "x")]) == 2
    assert "steam_chest" in capsys.readouterr().err
    assert not (tmp_path / "x").exists()


def test_sweep_errors_name_the_option():
    scene = corliss.load_scene(SCENES / "default.toml")
    with pytest.raises(InputError) as exc:
        load_range(scene, "setting", [0.5])
    assert exc.value.key == "--settings"
