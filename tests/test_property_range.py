"""The range of the steam properties: down to the triple point for condensers, up to
the superheat a scene can give, and no state a run visits clamped silently."""

from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest

import corliss
from corliss.engine.kernels import properties
from corliss.errors import InputError, RunError
from corliss.scene.loader import bundled_scenes, scene_from_dict
from corliss.thermo import steam_table
from corliss.thermo.steam_table import load_table, lookup_flagged

TRIPLE_POINT_Pa = 611.657


def _scene(**changes):
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["default"].read_text()))
    for section, values in changes.items():
        data.setdefault(section, {}).update(values)
    return scene_from_dict(data, name="range")


@pytest.fixture(scope="module")
def tab():
    return load_table().arrays()


def test_table_against_heos_from_the_triple_point_to_1273_K(tab):
    """States a condenser and a superheater reach, from the table and from HEOS
    (IAPWS-95): dry, wet and slightly superheated steam from 700 Pa to 2 kPa, and steam
    at 1273.15 K (the top of a scene's supply temperature) from 0.1 to 10 MPa.  Each is
    answered without a clamp and its pressure within 1e-4 of HEOS's (the table's
    measured error is 2e-6; bilinear interpolation on its grid allows 1e-5); the dry
    and superheated ones are inside the range a supply may have."""
    import CoolProp
    import CoolProp.CoolProp as CP
    a = CoolProp.AbstractState("HEOS", "Water")
    states = []
    wet = []
    for p in (700.0, 1000.0, 1426.0, 2000.0):
        for q in (0.8, 1.0):
            a.update(CP.PQ_INPUTS, p, q)
            (wet if q < 1.0 else states).append((a.rhomass(), a.umass(), a.p()))
        a.update(CP.PQ_INPUTS, p, 1.0)
        a.update(CP.PT_INPUTS, p, a.T() + 20.0)
        states.append((a.rhomass(), a.umass(), a.p()))
    for p in (1e5, 1e6, 1e7):
        a.update(CP.PT_INPUTS, p, 1273.15)
        states.append((a.rhomass(), a.umass(), a.p()))
    for rho, u, p in states + wet:
        assert steam_table.covers(rho, u) or (rho, u, p) in wet
        pt, _, _, _, code = lookup_flagged(tab, rho, u)
        assert code == 0
        assert pt == pytest.approx(p, rel=1e-4)


def test_states_off_the_table_are_flagged(tab):
    """Below the least density, above the greatest energy, and wet steam colder than the
    triple point each carry their own code; the kernel's clamp says so too."""
    assert lookup_flagged(tab, 1e-4, 2.6e6)[4] & steam_table.CLAMP_LOW_DENSITY
    assert lookup_flagged(tab, 1.0, 5.0e6)[4] & steam_table.CLAMP_HIGH_ENERGY
    # dryness 0.5 by volume at the triple point, with the energy of dryness 0.1: no
    # saturation temperature above 273.16 K has both
    assert lookup_flagged(tab, 0.0097, 2.4e5)[4] & steam_table.CLAMP_TRIPLE_POINT
    assert properties.admissible_flagged(-0.1, 2.6e6)[2] & steam_table.CLAMP_LOW_DENSITY
    assert properties.admissible_flagged(1.0, 2.6e6)[2] == 0


def test_a_29_5_inch_condenser_keeps_every_mass_positive():
    """The default engine exhausting to 29.5 inHg of vacuum (1.43 kPa, dry steam of
    0.0108 kg/m3; below the old table's 0.01 kg/m3 with the room to expand): the run
    converges with no clamp at any state it visits (it would stop), the least mass in
    either end over the last cycle is positive, and the cylinder reaches back pressure
    during exhaust (within 5 %: the clamp at 0.02 kg/m3 held it at about 2.7 kPa)."""
    r = corliss.simulate(_scene(exhaust={"pressure": "29.5 inHg vacuum"}))
    s = r.summary
    assert s["cycles_to_converge"] is not None
    assert r.exhaust.p == pytest.approx(101325.0 - 29.5 * 3386.389, rel=1e-3)
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    for end in ("head", "crank"):
        m = last[f"m_{end}_kg"].to_numpy()
        assert np.all(np.isfinite(m))
        assert m.min() > 0.0
        assert (m / last[f"V_{end}_m3"].to_numpy()).min() > properties.RHO_MIN
        assert last[f"p_{end}_Pa"].min() < 1.05 * r.exhaust.p
    assert isinstance(s["clamped_trial_evaluations_count"], int)


def test_a_vacuum_below_the_triple_point_is_refused_before_any_work():
    """29.9 inHg of vacuum under a 14.696 psia barometer is 72 Pa absolute: below the
    triple point (611.657 Pa) there is no steam to condense into; the scene is refused
    naming the key."""
    with pytest.raises(InputError) as err:
        _scene(exhaust={"pressure": "29.9 inHg vacuum"})
    assert err.value.key == "exhaust.pressure"


def test_a_visited_state_off_the_properties_stops_the_run():
    """A cycle started from a head end holding a thousandth of the least density the
    properties cover: the first state the run visits needs a clamp, and the run stops
    with a RunError naming the scene quantity, not with a card."""
    from corliss.engine.crank_resolved import CrankResolved
    from corliss.engine.model import assemble
    scene = _scene()
    model = assemble(scene, tabulated=True)
    net = model.network(model.portmap)
    fid = scene.run.fidelity
    crank = CrankResolved(net, model.steam, fid.method, fid.rtol)
    y = crank.initial_state()
    i = net.node("head")
    V = float(net.volume(i, np.array(0.0)))
    m = 1e-3 * properties.RHO_MIN * V
    y[2 * i + 1] *= m / y[2 * i]
    y[2 * i] = m
    with pytest.raises(RunError, match="exhaust.pressure"):
        crank.cycle(y, 0.0, np.linspace(0.0, 2.0 * math.pi, 361))


def test_steam_heated_beyond_the_table_is_counted_and_warned(caplog):
    """Marks's law gives the walls' heat back from cut-off to compression whatever
    steam is left: in the exhaust stroke it heats the thin remainder beyond 4.2 MJ/kg
    (over 1300 K; 6 to 8 MJ/kg once periodic, measured), where the properties end.
    That clamp does not stop the run, but it is not silent: a warning names
    engine.wall_heat_model and the summary counts the evaluations.  The adiabatic
    default card needs none."""
    import logging
    from conftest import make_scene
    scene = make_scene(engine={"wall_heat_model": "marks"},
                       run={"effects": ["port_flow", "rod_angularity", "wall_heat"]})
    with caplog.at_level(logging.WARNING, logger="corliss.engine.crank_resolved"):
        s = corliss.simulate(scene).summary
    assert s["clamped_hot_state_evaluations_count"] > 0
    assert any("engine.wall_heat_model" in rec.getMessage() for rec in caplog.records)
    assert corliss.simulate(_scene()).summary["clamped_hot_state_evaluations_count"] == 0
