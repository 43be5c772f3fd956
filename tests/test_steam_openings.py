"""The Porter-Allen's steam valves with several openings (``valve_gear.steam_openings``).

Spangler, *Valve-Gears*, Art. 30 (p. 31): the Porter-Allen's steam valves "consist of
flat plates having rectangular openings through them"; as a plate moves it uncovers its
own end and the near edge of each opening through it, every edge moving with the plate
(as the double-ported valve of Art. 26, "the problem is exactly the same as for a single
valve", and Allen's valve of Art. 27, "double the area for the same movement").  So with
n openings each of width w along the travel and length L across, and s(theta) the one
signed opening of the plate's edges (the first edge's), the open area is, in closed form::

    A_n(theta) = n L clip(s(theta), 0, w)

the same n-fold multiple of one opening's area at every angle, each opening full once
s reaches w (the plate's bars are taken wider than its travel, so an opening never
passes over the next port's edge, Art. 26's condition): the full area is n w L.  The
events are the crossings of s, the same for every n.

The dimensions are the bundled scene's (``scenes/porter-allen-engine.toml``: Spangler's
Problem 46 Fink motion, Marks's 14 1/2 x 24 in engine of Fig. 39).
"""

import dataclasses
import json
import math
import re
import tomllib

import numpy as np
import pytest

from corliss.cli import commands as cli
from corliss.engine.model import build_gear
from corliss.engine.simulate import simulate
from corliss.errors import InputError
from corliss.scene.loader import bundled_scenes, load_scene, scene_from_dict
from corliss.valves.events import events
from corliss.valves.gear import openings_note
from corliss.valves.portmap import tabulate, tabulate_settings

SCENE = bundled_scenes()["porter-allen-engine"]
TH = np.linspace(0.0, 2 * math.pi, 1441)
HARMONIC = lambda t: (1 - math.cos(t)) / 2  # noqa: E731


def _scene(n: int, setting: float | None = None):
    sc = load_scene(SCENE)
    g = dataclasses.replace(sc.gear, steam_openings=n,
                            setting=sc.gear.setting if setting is None else setting)
    return dataclasses.replace(sc, gear=g)


def _gear(n: int, setting: float | None = None):
    return build_gear(_scene(n, setting))


def test_the_bundled_scene_takes_two_openings_each_half_the_port():
    """The least number the text allows (the plate's end and one opening through it),
    each half the 1 in port so that together they give Art. 35's 22 sq in."""
    g = _scene(2).gear
    assert load_scene(SCENE).gear.steam_openings == 2
    assert g.steam_port_width_m == pytest.approx(0.5 * 0.0254, rel=1e-12)
    full = g.steam_openings * g.steam_port_width_m * g.steam_port_length_m
    assert full == pytest.approx(22 * 0.0254 ** 2, rel=1e-12)


@pytest.mark.parametrize("n", [2, 3, 4])
@pytest.mark.parametrize("setting", [0.0, 0.75])
def test_area_is_n_times_one_openings_up_to_the_full_port(n, setting):
    """A_n = n L clip(s, 0, w) at every angle (module doc), against the one-opening gear:
    n times its steam areas, its exhaust areas unchanged.  At the governor's rest the
    plate travels past w (its largest signed opening about 1 in against w = 1/2 in), so
    the clip, each opening full, is exercised; at 0.75 it never fills.  The tolerance is
    rounding: the same floating products, n exact."""
    one, many = _gear(1, setting), _gear(n, setting)
    s = many.signed_openings(TH)
    assert np.array_equal(s, one.signed_openings(TH))         # the same edges' motion
    sp = many.spec
    closed = n * sp.steam_port_length_m * np.clip(s[[0, 2]], 0.0, sp.steam_port_width_m)
    a1, an = one.areas(TH), many.areas(TH)
    np.testing.assert_allclose(an[[0, 2]], closed, rtol=1e-14, atol=0.0)
    np.testing.assert_allclose(an[[0, 2]], n * a1[[0, 2]], rtol=1e-14, atol=0.0)
    assert np.array_equal(an[[1, 3]], a1[[1, 3]])
    full = n * sp.steam_port_width_m * sp.steam_port_length_m
    assert an[[0, 2]].max() <= full * (1 + 1e-14)
    if setting == 0.0:
        assert s[0].max() > sp.steam_port_width_m                # past full opening
        assert an[0].max() == pytest.approx(full, rel=1e-14)
    else:
        assert s[0].max() < sp.steam_port_width_m
    # the port map the runs read, and a governed run's table over the settings, agree
    pm1, pmn = tabulate(one, 720), tabulate(many, 720)
    assert np.array_equal(pm1.theta_rad, pmn.theta_rad)
    np.testing.assert_allclose(pmn.area_m2[[0, 2]], n * pm1.area_m2[[0, 2]], rtol=1e-14)
    assert np.array_equal(pmn.area_m2[[1, 3]], pm1.area_m2[[1, 3]])
    spm1 = tabulate_settings(one, 0.5, 1.0, 3, 360)
    spmn = tabulate_settings(many, 0.5, 1.0, 3, 360)
    np.testing.assert_allclose(spmn.area_m2[:, [0, 2]], n * spm1.area_m2[:, [0, 2]],
                               rtol=1e-14)
    assert list(many.openings_per_edge()) == [n, 1, n, 1]
    assert openings_note(one) == ""
    assert f"steam ports: {n} openings an edge" in openings_note(many)


@pytest.mark.parametrize("setting", [0.0, 0.5, 0.75, 1.0])
def test_the_events_are_the_first_edges_and_do_not_change_with_n(setting):
    """Every edge moves with the plate, so the events are the crossings of the one
    signed opening: equal to the last bit for n = 1 and 3, the port map's kinks too
    (the largest opening, the port's whole, is the next test's)."""
    one, three = _gear(1, setting), _gear(3, setting)
    e1, e3 = events(one, HARMONIC), events(three, HARMONIC)
    for end in ("head", "crank"):
        e1[end].pop("max_port_opening_m")
        e3[end].pop("max_port_opening_m")
    assert e1 == e3
    assert np.array_equal(tabulate(one, 720).breakpoints_rad,
                          tabulate(three, 720).breakpoints_rad)


@pytest.mark.parametrize("n", [1, 2, 3])
@pytest.mark.parametrize("setting", [0.0, 0.75])
def test_the_largest_opening_reported_is_the_ports_whole_of_n_edges(n, setting):
    """The events' ``max_port_opening_m`` is the steam port's whole opening: n edges each
    open by min(s_max, w), s_max the plate's largest signed opening, so n min(s_max, w)
    (module doc: A_n = n L clip(s, 0, w)).  s_max in closed form from the rock shaft
    (fink_motion's module doc): the valve's edge opens by R_v sin(phi - beta) with
    phi = asin(x_s / R_d), greatest at the radius rod's greatest throw towards the
    port, x_s max for the head valve and -x_s max for the crank valve (its arm worked
    the other way), x_s over 1/4 deg samples of the Fink motion's block travel.  At the
    governor's rest the plate overtravels the 1/2 in opening (s_max about 1 in), so
    the width bounds it; at 0.75 it does not.  Tolerance 1e-6 in (2.5e-8 m): the events
    take the largest over their own samples of the turn, the closed form over 1/40 deg
    samples; the edge's opening is flat at its top (its derivative zero there), so each
    falls short of the true top by the curvature times its half-step squared (with 1/4
    deg samples the two differed by 1.5e-8 m an edge)."""
    g = _gear(n, setting)
    sp = g.spec
    xs = sp.link.block_travel(sp.block_m, np.linspace(0.0, 2 * math.pi, 14401))
    bh, bc = sp.arm_angles_rad
    w = sp.steam_port_width_m
    top = {"head": sp.valve_arm_m * math.sin(math.asin(xs.max() / sp.drive_arm_m) - bh),
           "crank": sp.valve_arm_m * math.sin(math.asin(-xs.min() / sp.drive_arm_m) - bc)}
    ev = events(g, HARMONIC)
    for end in ("head", "crank"):
        want = n * min(top[end], w)
        assert ev[end]["max_port_opening_m"] == pytest.approx(want, abs=1e-6 * 0.0254), end
        # n times one edge's, as the one-opening gear reports it
        one = events(_gear(1, setting), HARMONIC)[end]["max_port_opening_m"]
        assert ev[end]["max_port_opening_m"] == pytest.approx(n * one, rel=1e-15)
    if setting == 0.0:
        assert top["head"] > w          # the width bounds it at rest
    else:
        assert top["head"] < w


def _mid_admission_drop(result) -> dict:
    """Chest less cylinder pressure [Pa] of each end at the crank angle midway from
    admission to cut-off, on the last cycle."""
    ts = result.timeseries
    last = ts[ts.cycle == ts.cycle.max()]
    ang = last.crank_angle_deg.to_numpy() - last.crank_angle_deg.min()
    out = {}
    for end in ("head", "crank"):
        a, c = result.events[end]["admission_deg"], result.events[end]["cutoff_deg"]
        mid = (a + 0.5 * ((c - a) % 360.0)) % 360.0
        out[end] = result.chest.p - float(np.interp(mid, ang, last[f"p_{end}_Pa"]))
    return out


def test_two_openings_wire_draw_less_and_the_card_comes_nearer_the_ideal():
    """At the scene's setting (0.75: cut-off 0.22 and 0.18) the plate opens 0.17 in at
    most, so two openings double the area all through admission.  Through an orifice
    at a given flow the drop goes as (m_dot / (Cd A))^2: a quarter for twice the area.
    The fuller card draws more steam, so the drop falls by less than that; it must fall
    below half the one-opening drop (measured 0.29 at both ends), a bound that a
    doubled area meets and an unchanged one (ratio 1) does not.  The mean effective
    pressure comes nearer the ideal card's (the hyperbolic card at the same events, no
    wire-drawing): 218 kPa, against 96 kPa with one opening and 133 with two."""
    r1, r2 = simulate(_scene(1)), simulate(_scene(2))
    d1, d2 = _mid_admission_drop(r1), _mid_admission_drop(r2)
    for end in ("head", "crank"):
        assert d1[end] > 10e3, d1                  # one opening wire-draws: tens of kPa
        assert 0.0 < d2[end] < 0.5 * d1[end], (d1, d2)
    ideal = simulate(_scene(2).replace_run(model="ideal")).summary["mep_mean_Pa"]
    m1, m2 = r1.summary["mep_mean_Pa"], r2.summary["mep_mean_Pa"]
    assert m1 < m2 < ideal
    assert abs(ideal - m2) < abs(ideal - m1)
    e1, e2 = r1.events, r2.events
    for end in ("head", "crank"):     # the same events; the port's whole opening twice
        assert e2[end]["max_port_opening_m"] == pytest.approx(
            2.0 * e1[end]["max_port_opening_m"], rel=1e-15)
    assert ({e: {k: v for k, v in e1[e].items() if k != "max_port_opening_m"} for e in e1}
            == {e: {k: v for k, v in e2[e].items() if k != "max_port_opening_m"} for e in e2})


@pytest.mark.parametrize("value, why", [
    ("0", "from 1 to 4"), ("5", "from 1 to 4"), ("2.5", "whole number"),
    ('"2"', "whole number"),
])
def test_a_bad_number_of_openings_is_refused(value, why, tmp_path, capsys):
    text = SCENE.read_text()
    path = tmp_path / "bad.toml"
    path.write_text(re.sub(r"(?m)^steam_openings = .*$", f"steam_openings = {value}", text))
    out = tmp_path / "out"
    code = cli.main(["run", str(path), "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "valve_gear.steam_openings" in err and why in err, err
    assert "Traceback" not in err
    assert not out.exists() or not any(out.iterdir())


def test_a_gear_without_separate_steam_plates_refuses_the_key(capsys, tmp_path):
    """A slide valve's edges work steam and exhaust alike: its openings are
    ``ports_per_end``; ``steam_openings`` is refused there, naming who takes it."""
    data = tomllib.loads(bundled_scenes()["default"].read_text())
    data["valve_gear"]["steam_openings"] = 2
    with pytest.raises(InputError, match=r"valve_gear\.steam_openings.*porter_allen"):
        scene_from_dict(data, name="slide")


def test_the_commands_on_a_scene_with_two_openings(tmp_path, capsys):
    """``corliss events`` gives the same events for 1 and 2 openings, the largest
    opening the port's whole (twice one edge's with two); ``corliss run``
    reports the larger mean effective pressure of two; ``corliss gear`` draws the
    port openings marked with the openings."""
    text = SCENE.read_text()
    one = tmp_path / "one.toml"
    one.write_text(re.sub(r"(?m)^steam_openings = .*$", "steam_openings = 1", text))
    two = tmp_path / "two.toml"
    two.write_text(text)
    ev = {}
    for name, path in (("one", one), ("two", two)):
        assert cli.main(["events", str(path), "--json"]) == 0
        ev[name] = json.loads(capsys.readouterr().out)
    for end in ("head", "crank"):     # the same events; the port's whole opening twice
        assert ev["two"][end].pop("max_port_opening_m") == pytest.approx(
            2.0 * ev["one"][end].pop("max_port_opening_m"), rel=1e-15)
    assert ev["one"] == ev["two"]
    mep = {}
    for name, path in (("one", one), ("two", two)):
        out = tmp_path / f"out-{name}"
        assert cli.main(["run", str(path), "--out", str(out), "--fidelity", "fast"]) == 0
        capsys.readouterr()
        mep[name] = json.loads((out / f"{name}.summary.json").read_text())["mep_mean_Pa"]
    assert mep["two"] > 1.2 * mep["one"]          # measured 1.38: the area doubled
    out = tmp_path / "gear"
    assert cli.main(["gear", str(two), "--out", str(out)]) == 0
    assert any(p.suffix == ".png" for p in out.iterdir())
