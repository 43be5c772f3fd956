"""The Corliss trip inside the speed loop: the loop releases the steam valves at the
governor's cam and closes them by the dash-pot at its own speed, as the gear itself
does at a fixed speed (Spangler Arts. 155-156), and the cut-off follows the cam up to
the limit of the trip."""

import math
from pathlib import Path

import numpy as np
import pytest

import corliss
from corliss.engine.kernels.data import TRIP_RELEASE, TRIP_SCALARS, TS_N_SETTINGS
from corliss.engine.kernels.loop import governed_areas
from corliss.engine.kernels.mechanism import port_areas
from corliss.engine.model import build_gear, build_network, geometry_of, reservoir_states
from corliss.engine.transient import build_tables
from corliss.thermo.steam import make_steam
from corliss.valves import tabulate

SCENE = Path(__file__).resolve().parent.parent / "scenes" / "corliss-governor.toml"


@pytest.fixture(scope="module")
def loop():
    scene = corliss.load_scene(SCENE)
    steam = make_steam("table")
    chest, exhaust = reservoir_states(scene, steam)
    geo = geometry_of(scene)
    gear = build_gear(scene)
    network = build_network(scene, geo, tabulate(gear, 1440), steam, chest, exhaust)
    tables = build_tables(scene, network, gear, geo)
    return scene, gear, network.arrays(), tables


@pytest.mark.parametrize("setting", [0.1, 0.5, 0.9, 1.0])
@pytest.mark.parametrize("rpm", [70.0, 80.0, 95.0])
def test_the_loop_trips_the_valve_as_the_gear_does(loop, setting, rpm):
    """At a setting and a speed, the loop's compiled port areas equal the gear's own at
    that setting and speed (release at the cam, then the opening at release times the
    dash-pot's closing fraction of the time since release).  Tolerance: 2 % of the
    port's full area, the loop's bilinear reading of the (setting, crank angle) table
    between its 21 settings and across the quarter-degree cells the kinks fall in."""
    scene, gear, net, tables = loop
    omega = rpm * math.pi / 30.0
    g = gear.with_setting(setting).with_speed(omega)
    theta = np.radians(np.arange(0.0, 360.0, 0.5))
    want = g.areas(theta)
    pa = np.empty((1, 4))
    got = np.empty((4, theta.size))
    for k, th in enumerate(theta):
        port_areas(th, net, pa)
        governed_areas(th, setting, omega, net, tables.tr, pa)
        got[:, k] = pa[0]
    full = gear.port_widths() * gear.port_lengths()
    for port in range(4):
        assert np.max(np.abs(got[port] - want[port])) < 0.02 * full[port], port


def test_beyond_the_trip_the_valve_closes_with_the_wrist_plate(loop):
    """Past the end of the hook's travel the cam cannot release the valve: the steam
    valve follows the wrist plate and the cut-off is the latched one, far later (Spangler
    Art. 155); the loop's areas at such a setting are the latched areas."""
    scene, gear, net, tables = loop
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    latched = np.clip(gear.latched_signed_openings(theta), 0.0, gear.port_widths()[:, None]) \
        * gear.port_lengths()[:, None]
    assert gear.release_angle_rad(1.2)[0] is None
    trip = tables.tr.trip
    rel = trip[TRIP_RELEASE, : int(trip[TRIP_SCALARS, TS_N_SETTINGS])]
    assert np.all(np.isfinite(rel))             # the governor's range trips at every setting
    ev_trip = corliss.valves.events(gear.with_setting(1.0).with_speed(scene.run.speed_rad_s),
                                    lambda t: (1 - math.cos(t)) / 2)
    ev_latched = corliss.valves.events(gear.with_setting(1.2).with_speed(scene.run.speed_rad_s),
                                       lambda t: (1 - math.cos(t)) / 2)
    assert ev_latched["head"]["cutoff_frac"] > ev_trip["head"]["cutoff_frac"] + 0.1
    got = np.array(gear.with_setting(1.2).with_speed(scene.run.speed_rad_s).areas(theta))
    np.testing.assert_allclose(got, latched, atol=1e-12)


def test_cut_off_follows_the_governor(loop):
    """In a governed run the per-turn cut-off is the gear's at the governor's mean
    setting, and it shortens when the load falls (the governor rises, the cam moves
    toward earlier release)."""
    scene = corliss.load_scene(SCENE).replace_run(duration_s=14.0, record="cycle")
    r = corliss.simulate(scene)
    c = r.cycles
    before = c[c["t_end_s"] < 8.0].iloc[-1]
    after = c.iloc[-1]
    assert after["cutoff_head_frac"] < before["cutoff_head_frac"] - 0.02
    assert after["gear_setting_frac"] < before["gear_setting_frac"]
    geo = geometry_of(scene)
    gear = build_gear(scene)
    for row in (before, after):
        ev = corliss.valves.events(gear.with_setting(float(row["gear_setting_frac"])),
                                   lambda t: float(geo.fraction(t)))
        # the table's cut-off is read linearly between 21 settings: within 0.01 of stroke
        assert row["cutoff_head_frac"] == pytest.approx(ev["head"]["cutoff_frac"], abs=0.01)


def test_the_safety_cams_shut_off_steam_when_the_governor_falls():
    """Spangler Art. 155: when the governor falls below its working range (a broken belt,
    or an engine dragged down by more load than it can carry), the safety cams trip the
    steam valves before they open.  A load 1.6 times what the engine can give at its
    latest release drags it down; once the governor sits below its safety lift, the
    turns admit no steam: their indicated power is under 2 % of the power before."""
    import dataclasses

    from corliss.engine.load import parse_load
    from corliss.keys.toml_table import Table
    scene = corliss.load_scene(SCENE)
    load = parse_load(Table({"power": "250 hp", "kind": "step", "step_time": "2 s",
                             "step_fraction": 1.6}, "load"), scene.run.speed_rad_s, None)
    scene = dataclasses.replace(scene, load=load).replace_run(duration_s=14.0, record="cycle")
    r = corliss.simulate(scene)
    c = r.cycles
    mech = r.mechanism
    assert mech.safety_z > 0.0
    before = c[c["t_end_s"] < 2.0]["indicated_power_W"].iloc[-1]
    safe = c[(c["governor_z_frac"] < mech.safety_z) & (c["governor_z_end_frac"] < mech.safety_z)]
    assert len(safe) >= 2
    assert (safe["indicated_power_W"] < 0.02 * before).all()
