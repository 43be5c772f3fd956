"""A transient run's summary carries the steady contract's keys for its final state:
one name per quantity whichever mode a script reads."""

import tomllib
from pathlib import Path

import pytest

import corliss
from corliss.keys import units

SCENE = Path(__file__).resolve().parents[1] / "scenes" / "corliss-governor.toml"
CONTRACT = ("indicated_power_W", "indicated_power_hp", "steam_rate_kg_per_h",
            "water_rate_kg_per_kWh", "water_rate_lb_per_ihp_h", "mep_head_Pa",
            "mep_crank_Pa", "mep_mean_Pa")


@pytest.fixture(scope="module")
def run():
    d = tomllib.loads(SCENE.read_text())
    d["run"].update(duration="4 s", fidelity="fast", record="degree")
    d["load"] = {"power": "150 hp"}
    return corliss.simulate(corliss.scene_from_dict(d, "contract"))


def test_the_final_state_has_the_steady_contracts_keys_and_its_cards_close_the_work(run):
    """The keys are those of a steady summary.  Each end's m.e.p. is its card's area over
    its swept volume; the two cards' areas together must give the work the run
    integrated over the same last turn (p dV summed by the kernel as it stepped),
    within 1 %: the cards are sampled each degree and their loop is closed across the
    turn's ends, where a transient's state has moved a little.  The m.e.p. over both
    ends is the last five turns' work over both swept volumes (Marks Art. 90), and the
    water rate the steam per horse-power hour, 745.7 W to the horse-power (the
    mechanical horse-power, 550 ft lbf/s)."""
    s = run.summary
    steady_keys = set(corliss.simulate(run.scene.replace_run(mode="steady")).summary)
    assert set(CONTRACT) <= steady_keys and set(CONTRACT) <= set(s)
    sw_h, sw_c = run.geometry.swept_m3
    last = run.cycles.iloc[-1]
    assert s["mep_head_Pa"] * sw_h + s["mep_crank_Pa"] * sw_c == pytest.approx(
        last["work_J"], rel=0.01)
    assert s["mep_mean_Pa"] == pytest.approx(
        run.cycles["work_J"].iloc[-5:].mean() / (sw_h + sw_c), rel=1e-12)
    assert s["indicated_power_hp"] * 745.6999 == pytest.approx(s["indicated_power_W"], rel=1e-6)
    assert s["indicated_power_W"] == s["final_indicated_power_W"]
    assert s["water_rate_lb_per_ihp_h"] == pytest.approx(
        s["steam_rate_kg_per_h"] / units.POUND_kg / s["indicated_power_hp"], rel=1e-12)
