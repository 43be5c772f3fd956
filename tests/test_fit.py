"""``corliss fit``: scene keys recovered from synthetic indicator cards.

The cards are made by the simulator itself from known scenes (the default 12 x 24 in
engine: clearance 0.08, lap 1 in), on the ``standard`` tier, with Gaussian noise of a
stated size added to every pressure; the fits start away from the truth and search on
the ``fast`` tier, so the tiers' own difference is part of what the reported errors
must cover.
"""

from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest

import corliss
from corliss.cli import commands as cli
from corliss.keys import units
from corliss.errors import InputError
from corliss.fitting.card import EndCard, MeasuredCard, parse_card, read_card
from corliss.fitting.solver import fit_card, loop_area
from corliss.keys.toml_text import dumps
from corliss.keys.edits import parse_range
from corliss.studies import pool as study_pool
from conftest import BASE

PSI = units.PSI_Pa
#: The truth of the synthetic cards.
TRUTH = {"engine.clearance": 0.08, "valve_gear.lap": 1.0}
#: Where the fits start: 0.3 of the clearance range and a quarter of the lap's away.
START = {"clearance": 0.11, "lap": "0.85 in"}
RANGES = ["engine.clearance=0.04:0.14", "valve_gear.lap=0.7:1.3in"]


def scene_with(**changes):
    data = copy.deepcopy(BASE)
    for sec, kv in changes.items():
        data[sec].update(kv)
    return corliss.scene_from_dict(data, name="fit-test")


@pytest.fixture(scope="module")
def truth_run():
    """The default engine at the truth, standard tier."""
    return corliss.simulate(scene_with())


def noisy_card(result, sigma_psi: float, seed: int, ends=("head", "crank"), every: int = 2):
    """The result's card, every ``every``-th point, with N(0, sigma) on each pressure."""
    rng = np.random.default_rng(seed)
    out = {}
    for end in ends:
        c = result.cards[end].iloc[:-1:every]
        p = c["p_Pa"].to_numpy() + rng.normal(0.0, sigma_psi * PSI, len(c))
        out[end] = EndCard("piston_frac", c["piston_frac"].to_numpy(), p)
    return MeasuredCard(out, f"synthetic, sigma {sigma_psi} psi, seed {seed}")


@pytest.fixture(scope="module")
def fit_half_psi(truth_run, tmp_path_factory):
    """Clearance and lap fitted to the card with 0.5 psi of noise, written to a folder."""
    out = tmp_path_factory.mktemp("fit")
    card = noisy_card(truth_run, 0.5, seed=7)
    start = scene_with(engine={"clearance": START["clearance"]},
                       valve_gear={"lap": START["lap"]})
    return corliss.fit(start, card, RANGES, out=out), out


def test_known_clearance_and_lap_are_recovered_within_three_standard_errors(fit_half_psi):
    f, _ = fit_half_psi
    assert not f.unidentifiable
    for key, truth in TRUTH.items():
        se = f.standard_errors[key]
        r = next(r for r in f.ranges if r.key == key)
        # sensible errors: well inside the range, and not below what 0.5 psi of noise
        # on 360 points can give (the errors are 0.0014 and 0.0024 in)
        assert 1e-3 * (r.high - r.low) < se < 0.05 * (r.high - r.low), (key, se)
        assert abs(f.values[key] - truth) < 3.0 * se, (key, f.values[key], se)
        # and the search moved: the start was many errors away
        assert abs(f.start[key] - truth) > 5.0 * se
    # the noise estimate is the noise put in, less what the nearest-point distance takes
    # off on the card's steep lines (0.44 psi for 0.5)
    assert 0.35 * PSI < f.s_Pa < 0.55 * PSI
    assert abs(f.correlation[0, 1]) < 0.99


def test_standard_errors_grow_with_the_noise_of_the_card(truth_run, fit_half_psi):
    """Four times the noise on the same card: the noise estimate grows four times, the
    lap's error (fixed by the long flat lines' ends) about four times (3.9), the
    clearance's (fixed by the few points where compression and admission turn, which
    a larger scatter moves onto other lines) less (1.8); the truth stays within three
    errors.  The errors come from the card's scatter, not from the solver."""
    f1, _ = fit_half_psi
    start = scene_with(engine={"clearance": START["clearance"]},
                       valve_gear={"lap": START["lap"]})
    f4 = fit_card(start, noisy_card(truth_run, 2.0, seed=7), [parse_range(r) for r in RANGES])
    ratio = {k: f4.standard_errors[k] / f1.standard_errors[k] for k in TRUTH}
    assert 3.0 < ratio["valve_gear.lap"] < 5.0, ratio
    assert 1.4 < ratio["engine.clearance"] < 5.0, ratio
    for key, truth in TRUTH.items():
        assert abs(f4.values[key] - truth) < 3.0 * f4.standard_errors[key]
    assert 3.0 < f4.s_Pa / f1.s_Pa < 5.0


def test_the_fitted_card_conserves_the_indicated_work(fit_half_psi):
    """The fitted card's area (the loop integral of p dV of its points) is the work the
    integrator's quadrature gives, end by end, and the fitted card's m.e.p. is the
    measured card's."""
    f, _ = fit_half_psi
    for end, w in f.end_work.items():
        assert w["fitted_card_work_J"] == pytest.approx(w["integrated_work_J"], rel=2e-3)
        assert w["fitted_mep_Pa"] == pytest.approx(w["measured_mep_Pa"], rel=5e-3)
    total = sum(w["integrated_work_J"] for w in f.end_work.values())
    assert total == pytest.approx(f.result.summary["indicated_work_J_per_cycle"], rel=1e-9)
    # the measured m.e.p. itself is right: the truth's work over the swept volumes
    geo = f.result.geometry
    assert f.end_work["head"]["measured_mep_Pa"] == pytest.approx(
        f.result.summary["mep_head_Pa"], rel=0.01)
    assert geo.swept_m3[0] > geo.swept_m3[1]


def test_the_fit_writes_its_files_and_the_fitted_scene_runs(fit_half_psi):
    f, out = fit_half_psi
    stem = f"{f.scene.name}.fit"
    assert sorted(p.name for p in out.iterdir()) == [f"{stem}.card.png", f"{stem}.json",
                                                      f"{stem}.toml"]
    meta = json.loads((out / f"{stem}.json").read_text())
    par = {p["key"]: p for p in meta["parameters"]}
    assert par["valve_gear.lap"]["unit"] == "in"
    assert par["valve_gear.lap"]["value"] == pytest.approx(f.values["valve_gear.lap"])
    assert meta["residual_rms"]["unit"] == "psi"
    assert meta["residual_rms"]["value"] == pytest.approx(f.residual_rms_Pa / PSI)
    fitted = corliss.load_scene(out / f"{stem}.toml")
    assert fitted.engine.clearance[0] == pytest.approx(f.values["engine.clearance"], rel=1e-5)
    assert fitted.gear.lap_m[0] == pytest.approx(f.values["valve_gear.lap"] * units.INCH_m,
                                                 rel=1e-5)
    assert fitted.run.fidelity.name == "standard"       # the scene's own, not the search's


def test_keys_the_card_does_not_show_are_reported_unidentifiable(truth_run):
    """The reciprocating mass changes the crank effort, not the card (its column of the
    Jacobian is exactly zero); the piston rod's diameter changes only the crank end, so
    on a card of the head end alone it changes nothing above the solver's noise.  Both
    are reported as not determined, with no number, while the clearance beside them
    keeps its error."""
    card = noisy_card(truth_run, 0.5, seed=11, ends=("head",))
    start = scene_with(engine={"clearance": START["clearance"], "piston_rod_diameter": "2 in",
                               "reciprocating_mass": "300 lb"})
    f = fit_card(start, card, [parse_range("engine.clearance=0.04:0.14"),
                               parse_range("engine.piston_rod_diameter=1:4in"),
                               parse_range("engine.reciprocating_mass=100:900lb")])
    assert set(f.unidentifiable) == {"engine.piston_rod_diameter", "engine.reciprocating_mass"}
    assert "does not change with it" in f.unidentifiable["engine.reciprocating_mass"]
    why = f.unidentifiable["engine.piston_rod_diameter"]
    assert "noise" in why or "larger than its range" in why
    assert f.standard_errors["engine.piston_rod_diameter"] is None
    assert f.standard_errors["engine.reciprocating_mass"] is None
    se = f.standard_errors["engine.clearance"]
    assert se is not None and abs(f.values["engine.clearance"] - 0.08) < 3.0 * se
    assert [p["identifiable"] for p in f.summary["parameters"]] == [True, False, False]


def test_two_keys_that_act_only_together_are_reported_unidentifiable(truth_run):
    """A port's length and its discharge coefficient act on the flow only through their
    product: the card cannot tell them apart, and both are reported so."""
    card = noisy_card(truth_run, 0.5, seed=5)
    start = scene_with(valve_gear={"port_length": "8 in", "discharge_coefficient": 0.8})
    f = fit_card(start, card, [parse_range("valve_gear.port_length=6:12in"),
                               parse_range("valve_gear.discharge_coefficient=0.5:0.95")])
    assert set(f.unidentifiable) == {"valve_gear.port_length",
                                     "valve_gear.discharge_coefficient"}
    assert all(v is None for v in f.standard_errors.values())
    # each is named with the key it cannot be told from
    assert "valve_gear.discharge_coefficient" in f.unidentifiable["valve_gear.port_length"]
    assert "valve_gear.port_length" in f.unidentifiable["valve_gear.discharge_coefficient"]
    # their columns of the Jacobian are parallel; the fitted product is near the truth's
    assert abs(f.sensitivity_cosine[0, 1]) > 0.999
    product = f.values["valve_gear.port_length"] * f.values["valve_gear.discharge_coefficient"]
    assert product == pytest.approx(9.6 * 0.7, rel=0.05)


def test_card_files_as_corliss_writes_them_in_us_and_si_read_alike(truth_run, tmp_path):
    us = truth_run.to_csv(tmp_path / "us.csv", table="cards", units_system="US")
    si = truth_run.to_csv(tmp_path / "si.csv", table="cards", units_system="SI")
    a, b = read_card(us), read_card(si)
    for end in ("head", "crank"):
        ref = truth_run.cards[end]
        assert a.ends[end].abscissa == "piston_frac"
        np.testing.assert_allclose(a.ends[end].p_Pa, ref["p_Pa"], rtol=1e-7)
        np.testing.assert_allclose(b.ends[end].p_Pa, ref["p_Pa"], rtol=1e-7)
        np.testing.assert_allclose(a.ends[end].x, ref["piston_frac"], rtol=1e-7, atol=1e-12)


def test_a_digitised_card_in_gauge_pressure_is_read_against_the_barometer():
    """``end,piston_position [in],pressure [psig]``: position to metres, gauge to
    absolute with the barometer given (a museum at altitude: 12.2 psia)."""
    rows = ["end,piston_position [in],pressure [psig]"]
    xs = np.linspace(0.0, 24.0, 13)
    rows += [f"head,{x:g},{100.0 - 4 * x:g}" for x in xs]
    card = parse_card("\n".join(rows), barometer_Pa=12.2 * PSI)
    e = card.ends["head"]
    assert e.abscissa == "piston_m"
    np.testing.assert_allclose(e.x, xs * 0.0254)
    np.testing.assert_allclose(e.p_Pa, (100.0 - 4 * xs + 12.2) * PSI)
    # wide layout, SI, the end in the names
    wide = ["piston_position_head [mm],head pressure [bara],x_crank (mm),p_crank [bara]"]
    wide += [f"{i * 50},{1 + i * 0.1},{i * 50},{2 + i * 0.1}" for i in range(12)]
    c2 = parse_card("\n".join(wide))
    assert set(c2.ends) == {"head", "crank"}
    np.testing.assert_allclose(c2.ends["crank"].p_Pa, (2 + np.arange(12) * 0.1) * 1e5)
    assert loop_area(np.array([0.0, 1.0, 1.0, 0.0]), np.array([1.0, 1.0, 0.0, 0.0])) == 1.0


@pytest.mark.parametrize("text, words", [
    ("end,piston_position,pressure [psig]\n", "names its unit"),
    ("end,piston_position [in],pressure [psi]\n", "a pressure in psia, psig"),
    ("end,piston_position [in],pressure [bar]\n", "a pressure in psia, psig"),
    ("end,piston_position [furlong],pressure [psig]\n", "length unit"),
    ("end,piston_position [in],pressure [psig]\n" + "head,1,2\n" * 5, "at least 12 points"),
    ("end,piston_position [in],pressure [psig]\n" + "middle,1,2\n" * 15, "an end of"),
    ("piston_position [in],pressure [psig]\n" + "1,2\n" * 15, "the end in"),
])
def test_bad_card_files_are_refused_by_name(text, words):
    with pytest.raises(InputError, match=words):
        parse_card(text)


def test_bad_input_through_the_command_leaves_the_output_folder_as_it_was(
        truth_run, tmp_path, capsys):
    scene = tmp_path / "engine.toml"
    scene.write_text(dumps(BASE))
    card = truth_run.to_csv(tmp_path / "card.csv", table="cards")
    out = tmp_path / "out"
    out.mkdir()
    (out / "earlier.txt").write_text("earlier")
    cases = [
        (["--vary", "engine.bogus=1:2in"], "bogus"),
        (["--vary", "valve_gear.lap=1.3:0.7in"], "LOW below HIGH"),
        (["--vary", "engine.clearance=0.04:0.9"], "clearance"),
        (["--vary", "valve_gear.lap=0.7:1.3in", "--vary", "valve_gear.lap=0.8:1in"], "once"),
    ]
    bad_card = tmp_path / "bad.csv"
    bad_card.write_text("end,position,pressure [psig]\nhead,1,2\n")
    for extra, words in cases:
        assert cli.main(["fit", str(scene), str(card), "--out", str(out), *extra]) == 2
        err = capsys.readouterr().err
        assert words in err and "Traceback" not in err, err
    assert cli.main(["fit", str(scene), str(bad_card), "--out", str(out),
                     "--vary", "valve_gear.lap=0.7:1.3in"]) == 2
    assert "position" in capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == ["earlier.txt"]
    assert (out / "earlier.txt").read_text() == "earlier"


def test_the_command_fits_a_card_corliss_wrote_and_prints_json(truth_run, tmp_path, capsys):
    """The card CSV ``corliss run`` writes (US units) is fitted as it stands; without
    noise the lap comes back to a thousandth of an inch."""
    scene = tmp_path / "engine.toml"
    data = copy.deepcopy(BASE)
    data["valve_gear"]["lap"] = "0.9 in"
    scene.write_text(dumps(data))
    card = truth_run.to_csv(tmp_path / "card.csv", table="cards")
    assert cli.main(["fit", str(scene), str(card), "--vary", "valve_gear.lap=0.7:1.3in",
                     "--json", "--no-plots", "--out", str(tmp_path / "o")]) == 0
    s = json.loads(capsys.readouterr().out)
    lap = s["parameters"][0]
    assert lap["value"] == pytest.approx(1.0, abs=1e-3)
    assert lap["identifiable"] and lap["standard_error"] < 1e-3
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == ["engine.fit.json",
                                                                   "engine.fit.toml"]
    written = tomllib.loads((tmp_path / "o" / "engine.fit.toml").read_text())["valve_gear"]["lap"]
    assert units.parse(written, "length") == pytest.approx(lap["value"] * units.INCH_m, rel=1e-5)
    assert math.isfinite(s["residual_rms_Pa"])


def test_a_card_of_volumes_fits_as_a_card_of_positions(truth_run, tmp_path):
    """The card ``corliss run`` writes, with its volume column alone (no position): the
    lap comes back as from positions, the volume read in ft3 with the clearance in it."""
    df = truth_run.to_pandas("cards", "US")[["end", "V_ft3", "p_psia"]].iloc[::3]
    path = tmp_path / "volumes.csv"
    df.to_csv(path, index=False)
    card = read_card(path)
    assert card.ends["crank"].abscissa == "V_m3"
    start = scene_with(valve_gear={"lap": "1.2 in"})
    f = corliss.fit(start, card, "valve_gear.lap=0.7:1.3in")
    assert f.values["valve_gear.lap"] == pytest.approx(1.0, abs=2e-3)
    assert f.standard_errors["valve_gear.lap"] < 2e-3


def test_the_python_function_refuses_bad_input_before_any_simulation(truth_run, monkeypatch):
    """An end the scene does not have, a transient scene, a key outside the scene:
    each an InputError naming it, raised before the first simulation."""
    from corliss.engine import simulate as sim_module
    from corliss.fitting import solver

    def no_run(*a, **k):
        raise AssertionError("a simulation ran before the input was checked")

    monkeypatch.setattr(solver, "simulate", no_run)
    assert sim_module.simulate is not no_run
    good = noisy_card(truth_run, 0.5, seed=1)
    lp = MeasuredCard({"lp_head": good.ends["head"]}, "lp card")
    with pytest.raises(InputError, match="ends of the scene"):
        corliss.fit(scene_with(), lp, RANGES)
    transient = copy.deepcopy(BASE)
    transient["run"].update(mode="transient", duration="2 s")
    transient["flywheel"] = {"moment_of_inertia": "500 kg m2"}
    transient["load"] = {"torque": "1000 N m"}
    with pytest.raises(InputError, match="steady"):
        corliss.fit(corliss.scene_from_dict(transient), good, RANGES)
    with pytest.raises(InputError, match="bogus"):
        corliss.fit(scene_with(), good, "valve_gear.bogus=1:2in")
    with pytest.raises(InputError, match="run and output keys"):
        corliss.fit(scene_with(), good, "run.speed=100:140rpm")


def test_the_bootstrap_agrees_with_the_jacobian_and_repeats_with_its_seed(truth_run):
    """Residuals resampled onto the fitted card and refitted: the spread of the lap over
    the refits is of the size of the Jacobian's error, its 95 % interval holds the
    fit, and the same seed gives the same refits, on two processes too (the
    uncertainty's runs and the refits on the kept pool of workers: each run depends
    only on its inputs, so the values, the errors and the refits are equal exactly)."""
    card = noisy_card(truth_run, 0.5, seed=21)
    start = scene_with(valve_gear={"lap": "0.9 in"})
    ranges = [parse_range("valve_gear.lap=0.7:1.3in")]
    a = fit_card(start, card, ranges, bootstrap=8, seed=4)
    b = fit_card(start, card, ranges, bootstrap=8, seed=4, jobs=2)
    key = "valve_gear.lap"
    se, bse = a.standard_errors[key], a.bootstrap["standard_errors"][key]
    assert 0.3 < bse / se < 3.0, (bse, se)
    assert a.bootstrap["low"][key] < a.values[key] < a.bootstrap["high"][key]
    assert b.bootstrap == a.bootstrap
    assert b.values == a.values and b.standard_errors == a.standard_errors
    assert len(study_pool.worker_pids()) == 2
    assert abs(a.values[key] - 1.0) < 3.0 * se


def test_the_clearance_error_is_the_noise_s_not_the_card_s_accident(truth_run):
    """Eight cards of the same engine with the same 0.5 psi of noise: the clearance's
    standard error is about the same on each (the sandwich estimate: 0.0013-0.0017;
    the classic s^2 (J^T J)^-1 ranges over a factor of 4.6 on these cards, as a few
    points at the card's corners happen to fall), and every fit lies within three of
    them of the truth."""
    start = scene_with(engine={"clearance": START["clearance"]},
                       valve_gear={"lap": START["lap"]})
    ranges = [parse_range(r) for r in RANGES]
    se, z = [], []
    for seed in range(100, 108):
        f = fit_card(start, noisy_card(truth_run, 0.5, seed=seed), ranges)
        se.append(f.standard_errors["engine.clearance"])
        z.append((f.values["engine.clearance"] - 0.08) / se[-1])
    assert max(se) / min(se) < 2.0, se
    assert max(abs(v) for v in z) < 3.0, z
