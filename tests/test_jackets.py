"""Steam jackets on the barrel, the covers or both, at their own steam's pressure.

The skin wall's each end is one lumped area, ``2 A_p + pi D V / A_p``: the cover's face
``A_p``, the piston's face ``A_p`` and the barrel the steam touches, the clearance as
its equivalent length (:func:`corliss.engine.condensation.exposed_wall_m2`).  A jacket
holds the outer face of the parts it covers at its steam's saturation temperature,
``wall_thickness`` of cast iron away; the cover's share is ``A_p``, the barrel's over a
cycle ``pi D mean(V) / A_p`` (the lumped wall's mean less ``2 A_p``), the piston's face
never (it moves; no steam can be led to it).  Marks Art. 79 (p. 204): the jacket is
paid for in steam condensed in it; Lineham (App. II, p. 884) 10 to 20 % saved.
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from pathlib import Path

import pytest

import corliss
from corliss.cli import commands as cli
from corliss.engine import wall
from corliss.errors import InputError
from corliss.keys import units
from corliss.scene.loader import bundled_scenes, scene_from_dict
from corliss.thermo.steam import HEOSSteam
from test_wall_english import englishs_heat_from_the_card, meyer

SCENES = Path(__file__).resolve().parent.parent / "scenes"
MEYER = tomllib.loads(bundled_scenes()["meyer-cutoff"].read_text())


def _scene(**changes):
    """The Meyer engine (114.7 psia saturated, 16.7 psia exhaust, 150 rpm) with the
    skin wall, the blocks at 0.4 of the screw (cut-off 0.42 head, 0.29 crank), fast."""
    data = copy.deepcopy(MEYER)
    data["engine"]["wall_heat_model"] = "skin"
    data["run"]["effects"] = list(data["run"]["effects"]) + ["wall_heat"]
    data["run"]["fidelity"] = "fast"
    data["valve_gear"]["setting"] = 0.4
    for section, values in changes.items():
        data.setdefault(section, {}).update(values)
    return scene_from_dict(data, name="meyer-jacket")


_RUNS: dict = {}


def _run(key, **engine):
    """A run of :func:`_scene` with these engine keys, each asked for once."""
    if key not in _RUNS:
        _RUNS[key] = corliss.simulate(_scene(engine=engine))
        assert _RUNS[key].summary["cycles_to_converge"] is not None, key
    return _RUNS[key]


def _exhaust_psia() -> str:
    return f"{_scene().exhaust.pressure_Pa / units.PSI_Pa!r} psia"


def test_the_jacketed_area_is_the_covers_and_barrels_share_of_the_lumped_wall():
    """The closed form of the split (module docstring): on the Meyer engine the cover's
    share is pi D^2 / 4 at the head end and pi (D^2 - d^2) / 4 at the crank end (the
    rod through it), the barrel's the lumped wall's mean less twice that, and both
    jackets their sum; no jacket, nothing.  1e-12: the same sums in another order."""
    geo = _run("bare").geometry
    D, d = geo.spec.bore_m, geo.spec.piston_rod_diameter_m
    for end, cover in ((0, math.pi * D * D / 4.0), (1, math.pi * (D * D - d * d) / 4.0)):
        barrel = wall.mean_exposed_area_m2(geo, end) - 2.0 * cover
        assert wall.jacketed_area_m2(geo, end, "covers") == pytest.approx(cover, rel=1e-12)
        assert wall.jacketed_area_m2(geo, end, "barrel") == pytest.approx(barrel, rel=1e-4)
        assert wall.jacketed_area_m2(geo, end, "barrel_and_covers") == pytest.approx(
            barrel + cover, rel=1e-4)
        assert wall.jacketed_area_m2(geo, end, "none") == 0.0
    # 1e-4 on the barrel: the lumped wall's mean is taken on 721 points, the jacket's
    # on 361 (both of a smooth periodic function: the trapezoid errs far below that)


@pytest.mark.parametrize("jacket", ["covers", "barrel_and_covers"])
def test_jacketed_covers_take_heat_in_proportion_to_their_share(jacket):
    """Over the periodic cycle the heat the jacket gives (``jacket_heat_W``, the heat
    the steam left in the walls) is what the iron conducts from the jacket's saturation
    temperature to each end's deep wall through ``wall_thickness``: k / L times the
    jacketed area (the covers' A_p, with the barrel's share added for both; the
    closed form of the module docstring, computed here apart from the code's) times
    the difference.  2 %: the wall's balance to the fast preset's 1e-3 of the enthalpy
    supplied, as ``test_wall_skin.test_the_jacket_is_paid_for_in_steam``."""
    r = _run(jacket, jacket=jacket)
    geo = r.geometry
    D, d = geo.spec.bore_m, geo.spec.piston_rod_diameter_m
    t_j = HEOSSteam().t_sat(r.scene.supply.pressure_Pa)
    conducted = 0.0
    for e, (end, cover) in enumerate((("head", math.pi * D * D / 4.0),
                                      ("crank", math.pi * (D * D - d * d) / 4.0))):
        area = cover
        if jacket == "barrel_and_covers":
            area += wall.mean_exposed_area_m2(geo, e) - 2.0 * cover
        conducted += (wall.CAST_IRON_K / r.scene.engine.wall_thickness_m * area
                      * (t_j - float(r.last_cycle[f"T_wall_{end}_K"])))
    assert r.summary["jacket_heat_W"] > 0.0
    assert r.summary["jacket_heat_W"] == pytest.approx(conducted, rel=0.02)


def _saving(r) -> float:
    """The steam saved per unit of work, the jacket's counted with the feed (Marks Art.
    79), against the bare engine's water rate [-]."""
    bare = _run("bare").summary["water_rate_kg_per_kWh"]
    return 1.0 - r.summary["water_rate_with_jacket_kg_per_kWh"] / bare


def test_a_lower_jacket_pressure_saves_less_and_one_at_the_exhaust_saves_nothing():
    """The jacket's heat goes down its saturation temperature to the wall: on the
    barrel and covers of the Meyer engine, a jacket at the supply's 114.7 psia saves
    more than one at 60 psia, which saves more than nothing; one at the exhaust's 16.7
    psia is colder than the wall it jackets and condenses none of its steam, so the
    engine runs as the bare one: its saving is zero to 0.002 (the deep wall's balance
    found to the fast preset's 1e-3 of the heat the steam leaves in it, a few
    thousandths of the water rate at most; 0 measured)."""
    full = _saving(_run("both", jacket="barrel_and_covers"))
    half = _saving(_run("both60", jacket="barrel_and_covers", jacket_pressure="60 psia"))
    none = _run("both_exhaust", jacket="barrel_and_covers", jacket_pressure=_exhaust_psia())
    assert full > half > 0.0
    assert none.summary["jacket_heat_W"] == pytest.approx(0.0, abs=1e-3 * abs(
        _run("both", jacket="barrel_and_covers").summary["jacket_heat_W"]))
    assert _saving(none) == pytest.approx(0.0, abs=0.002)


@pytest.mark.parametrize("engine, key", [
    ({"jacket": "barrel", "jacket_pressure": "120 psia"}, "engine.jacket_pressure"),
    ({"jacket": "barrel", "jacket_pressure": "10 psia"}, "engine.jacket_pressure"),
    ({"jacket": "barrel", "jacket_pressure": "-5 psig"}, "engine.jacket_pressure"),
    ({"jacket": "barrel", "lp_jacket_pressure": "30 psia"}, "engine.lp_jacket_pressure"),
    ({"jacket_pressure": "100 psia"}, "engine.jacket_pressure"),
    ({"jacket": "head"}, "engine.jacket"),
])
def test_a_jacket_pressure_outside_the_engines_is_refused(engine, key):
    """A jacket is fed from the boiler's main (or a receiver) and drains against at
    least the exhaust: its pressure above the supply's 114.7 psia, below the exhaust's
    16.7 psia (absolute or gauge), an LP jacket on a simple engine, a jacket pressure
    without a jacket, or an unknown part are refused naming the key and the value."""
    with pytest.raises(InputError) as e:
        _scene(engine=engine)
    assert key in str(e.value)
    value = next(v for k, v in engine.items() if k == key.split(".")[1])
    assert value in str(e.value)


def test_a_compounds_lp_jacket_pressure_is_refused_above_the_supply():
    """The bundled compound with its LP jacket above the supply's pressure."""
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["marks-compound-9-14x14"].read_text()))
    data["engine"].update(jacket="barrel", lp_jacket_pressure="500 psia")
    with pytest.raises(InputError) as e:
        scene_from_dict(data, name="c")
    assert "engine.lp_jacket_pressure" in str(e.value) and "500 psia" in str(e.value)


def test_the_cli_runs_a_scene_jacketed_on_barrel_and_covers(tmp_path, capsys):
    """``corliss run`` on the Meyer engine jacketed on barrel and covers at 80 psig
    writes a summary whose jacket's steam is the jacket's heat over the latent heat at
    80 psig (Marks Art. 79: drained as saturated water at the jacket's pressure), and
    prints it.  1e-6: the summary reads the latent heat on the run's steam table."""
    text = (SCENES / "meyer-cutoff.toml").read_text()
    text = text.replace("effects = [", 'effects = ["wall_heat", ', 1)
    text = text.replace("[engine]\n", '[engine]\njacket = "barrel_and_covers"\n'
                        'jacket_pressure = "80 psig"\n', 1)
    text = text.replace('fidelity = "standard"', 'fidelity = "fast"')
    scene = tmp_path / "both.toml"
    scene.write_text(text)
    out = tmp_path / "out"
    assert cli.main(["run", str(scene), "--out", str(out), "--no-plots", "--units", "SI"]) == 0
    printed = capsys.readouterr().out
    s = json.loads(next(out.glob("*.summary.json")).read_text())
    steam = HEOSSteam()
    p = 80.0 * units.PSI_Pa + units.STANDARD_ATMOSPHERE_Pa
    latent = steam.px(p, 1.0).h - steam.px(p, 0.0).h
    assert s["jacket_heat_W"] > 0.0
    assert s["jacket_steam_kg_per_h"] == pytest.approx(s["jacket_heat_W"] / latent * 3600.0,
                                                       rel=1e-6)
    line = next(x for x in printed.splitlines() if x.strip().startswith("jacket"))
    assert float(line.split()[1]) == pytest.approx(s["jacket_steam_kg_per_h"], abs=0.05)


@pytest.mark.parametrize("jacket", ["covers", "barrel_and_covers"])
def test_englishs_jacketed_constant_applies_with_any_jacket(jacket):
    """English (DPJ 267, 1888, p. 302): 60 in place of 80 for jacketed cylinders, with
    no word of which parts: any jacket takes the 60.  Each end's heat over a cycle is
    his law with the 60 on its own card (2 %, as
    ``test_wall_english.test_each_end_takes_englishs_heat_at_cut_off``; the 80 would be
    a third over)."""
    r = corliss.simulate(meyer(110, jacket=jacket))
    for end in ("head", "crank"):
        want = englishs_heat_from_the_card(r, end, True)
        assert float(r.last_cycle[f"Q_to_wall_{end}_J"]) == pytest.approx(want, rel=0.02)


def test_a_compounds_jackets_each_take_the_pressure_set():
    """The bundled 9 & 14 x 14 in compound (skin walls, fast preset), both barrels
    jacketed: the HP's jacket at the exhaust's 15 psia, colder than the HP's walls,
    gives them nothing (each HP end's heat over a cycle under 2e-3 of the LP ends':
    the fast preset balances each wall to 1e-3 of the enthalpy supplied, several
    times the LP's heat; 6.5e-4 measured), and the LP's at 30 psia (below its
    receiver's starting sqrt(supply x exhaust), 38.7 psia) is booked at the latent
    heat of 30 psia: the jacket's steam is each end's heat over its own jacket's
    latent heat (1e-6, as
    ``test_wall_skin.test_a_compounds_lp_jacket_takes_its_receivers_steam``)."""
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["marks-compound-9-14x14"].read_text()))
    data["engine"].update({"wall_heat_model": "skin", "jacket": "barrel",
                           "lp_jacket_pressure": "30 psia"})
    if "wall_heat" not in data["run"]["effects"]:
        data["run"]["effects"] = list(data["run"]["effects"]) + ["wall_heat"]
    data["run"]["fidelity"] = "fast"
    exhaust = scene_from_dict(data, name="c").exhaust.pressure_Pa
    data["engine"]["jacket_pressure"] = f"{exhaust / units.PSI_Pa!r} psia"
    sc = scene_from_dict(data, name="compound-jackets")
    r = corliss.simulate(sc)
    assert r.summary["cycles_to_converge"] is not None
    row = r.last_cycle
    lp = sum(float(row[f"Q_lp_{e}_J"]) for e in ("head", "crank"))
    assert lp > 0.0
    for e in ("head", "crank"):
        assert abs(float(row[f"Q_{e}_J"])) < 2e-3 * lp, e
    steam = HEOSSteam()
    rev_per_h = sc.run.speed_rad_s / (2.0 * math.pi) * 3600.0
    want = 0.0
    for e, p in (("head", exhaust), ("crank", exhaust), ("lp_head", 30.0 * units.PSI_Pa),
                 ("lp_crank", 30.0 * units.PSI_Pa)):
        want += float(row[f"Q_{e}_J"]) / (steam.px(p, 1.0).h - steam.px(p, 0.0).h)
    assert r.summary["jacket_steam_kg_per_h"] == pytest.approx(want * rev_per_h, rel=1e-6)
