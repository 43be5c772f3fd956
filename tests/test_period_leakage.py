"""The ``leakage`` effect by the period's law (``[engine] leakage_model = "period"``):
a flow equal to a rate of leak times the pressure difference, independent of speed
(Callendar and Nicolson, Min. Proc. ICE 131, 1897-98, in DPJ 312, 1899, pp. 163-164;
:mod:`corliss.thermo.leak_law`)."""

from __future__ import annotations

import pytest

import corliss
from conftest import make_scene
from corliss.errors import InputError
from corliss.thermo import leak_law

RATE = "3 lb/h psi"          # Callendar and Nicolson's flat slide valve (DPJ 312 p. 163)
#: the same in SI: 3 lb is 1.3608 kg, the report's 1.36 rounded [kg/(s Pa)]
R_SI = 3.0 * 0.45359237 / 3600.0 / leak_law.PSI_PA


def _leaky(speed="120 rpm", **engine):
    return corliss.simulate(make_scene(
        engine={"leakage_model": "period", "valve_leak_rate": RATE, **engine},
        run={"effects": ["port_flow", "rod_angularity", "leakage"], "speed": speed,
             "fidelity": "fast"}))


def test_the_valve_leak_is_the_rate_times_the_difference_at_any_speed():
    """Chest (the supply, 114.7 psia) straight to the exhaust (atmosphere): 3 lb/h per
    psi of a 100 psi difference is 300 lb/h (136.08 kg/h) whatever the speed (the period's
    "independent of speed"): at 60 and 180 rpm the hourly leak is that to 1e-6 (the
    integration's quadrature of a constant flow), though a cycle takes three times as
    long at the one as at the other; the mass and energy balances close with it (the
    fast preset's 1e-4)."""
    for speed in ("60 rpm", "180 rpm"):
        r = _leaky(speed)
        s = r.summary
        dp = r.chest.p - r.exhaust.p       # the reservoirs' pressures as the tier gives them
        want = R_SI * dp * 3600.0
        assert s["valve_leak_exhaust_kg_per_h"] == pytest.approx(want, rel=1e-6)
        assert s["valve_leakage_fraction_of_steam"] == pytest.approx(
            want / s["steam_rate_kg_per_h"], rel=1e-6)
        assert s["mass_balance_error"] < 1e-4
        assert s["energy_balance_error"] < 1e-4


def test_the_piston_leak_runs_from_the_end_at_higher_pressure():
    """Past the piston, head to crank, R (p_head - p_crank) at every instant: over a
    cycle of the (symmetric but for the rod) default engine the net is small against
    the gross, and its sign follows the pressures' integral (the quadrature of the law
    over the last cycle's samples, to the trapezoid's error, 2 %)."""
    import numpy as np
    r = _leaky(piston_leak_rate="1 lb/h psi")
    ts = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    t = ts["time_s"].to_numpy()
    dp = ts["p_head_Pa"].to_numpy() - ts["p_crank_Pa"].to_numpy()
    R = R_SI / 3.0
    want = float(np.trapezoid(R * dp, t))
    got = float(r.last_cycle["m_piston_leak_kg"])
    gross = float(np.trapezoid(R * np.abs(dp), t))
    assert abs(got - want) < 0.02 * gross


def test_the_period_law_needs_a_rate():
    with pytest.raises(InputError, match="engine.valve_leak_rate"):
        make_scene(engine={"leakage_model": "period"},
                   run={"effects": ["port_flow", "rod_angularity", "leakage"]})


# --- across each valve edge (corliss.engine.leak_paths) ---------------------------------

def _gear(**valve):
    from corliss.engine.model import build_gear
    return build_gear(make_scene(valve_gear=valve))


def test_an_edge_leaks_in_proportion_to_its_port_length():
    """Callendar and Nicolson (DPJ 312, 1899, p. 164): the water a valve leaks is
    proportional "to the perimeter of the port's opening".  The default slide valve
    with 9.6 and 19.2 in ports (the overlaps unchanged): every edge's share of the
    reference rate doubles, to rounding (1e-12)."""
    from corliss.engine.leak_paths import edge_leak_scales
    one = edge_leak_scales(_gear(port_length="9.6 in"))
    two = edge_leak_scales(_gear(port_length="19.2 in"))
    assert two == pytest.approx(2.0 * one, rel=1e-12)


def test_an_edge_leaks_less_as_its_face_widens():
    """Capper's committee (1905; Lineham, App. VI): leakage "inversely to the lap".  The
    default slide valve's steam lap from 1 to 1.5 in (the lead held at 0.25 in): its
    steam edges' faces cover the closed ports by more and leak less, in the inverse
    ratio of the mean overlap (``closed_face_widths_m``; 1e-12); the exhaust edges, whose
    lap is unchanged, leak within 15 % of before (the valve's angular advance moves
    with the lap, and with it where the exhaust edge closes)."""
    from corliss.engine.leak_paths import closed_face_widths_m, edge_leak_scales
    small, big = _gear(lap="1 in"), _gear(lap="1.5 in")
    a, b = edge_leak_scales(small), edge_leak_scales(big)
    wa, wb = closed_face_widths_m(small), closed_face_widths_m(big)
    for steam in (0, 2):
        assert b[steam] < a[steam]
        assert b[steam] / a[steam] == pytest.approx(wa[steam] / wb[steam], rel=1e-12)
    for exhaust in (1, 3):
        assert b[exhaust] == pytest.approx(a[exhaust], rel=0.15)


def test_the_face_width_of_a_slide_valve_in_closed_form():
    """A slide valve driven through an eccentric rod long against its throw moves
    harmonically, ``x = r sin(phi)``, and its steam edge's signed opening is ``x - l``:
    shut where ``sin(phi) < l / r``, over ``pi + 2 a`` of the turn (``a = asin(l/r)``),
    and the mean overlap there is ``l + 2 r cos(a) / (pi + 2 a)`` (the integral of
    ``l - r sin(phi)`` over the shut arc, ``l (pi + 2 a) + 2 r cos(a)``, over its length).
    The exhaust edge, lap 0: ``2 r / pi``.  On the default valve (r 3 in, l 1 in) with a
    600 in eccentric rod: within 0.2 % (the rod's angularity at 600 in, r / L = 0.005,
    and the 0.25 deg sampling)."""
    import math
    from corliss.engine.leak_paths import closed_face_widths_m
    r, lap = 3.0, 1.0
    a = math.asin(lap / r)
    want = lap + 2.0 * r * math.cos(a) / (math.pi + 2.0 * a)
    w = closed_face_widths_m(_gear(eccentric_rod="600 in")) / 0.0254
    assert w[0] == pytest.approx(want, rel=2e-3)
    assert w[2] == pytest.approx(want, rel=2e-3)
    assert w[1] == pytest.approx(2.0 * r / math.pi, rel=2e-3)


def test_the_reference_valve_is_the_bundled_single_acting_engines():
    """The reference of the edges' rates (``leak_paths.REFERENCE_*``) is the valve of the
    bundled engine after Callendar and Nicolson's, on which they measured 3 lb/h per
    psi: its head end's steam edge carries the rate the scene names (scale 1, to the
    reference's rounding to 0.01 in of 2.11 in: 0.5 %)."""
    import tomllib
    from corliss.engine.leak_paths import edge_leak_scales
    from corliss.engine.model import build_gear
    from corliss.scene.loader import bundled_scenes, scene_from_dict
    name = "callendar-nicolson-single-acting"
    scene = scene_from_dict(tomllib.loads(bundled_scenes()[name].read_text()), name=name)
    assert edge_leak_scales(build_gear(scene))[0] == pytest.approx(1.0, rel=5e-3)


def test_each_edge_leaks_its_rate_times_the_difference_across_it():
    """The default engine, the supply at 114.7 psia straight to the ports, with 3 lb/h
    per psi past each closed steam edge and each closed exhaust edge (Callendar and
    Nicolson's valve): over the last cycle each end's steam-edge leak is ``R s (p_supply
    - p_end)`` and its exhaust-edge leak ``R s (p_end - p_exhaust)`` integrated in time
    (``s`` the edge's scale), each to 2 % of the gross flow (the trapezoid on the
    recorded samples); into the end past the steam edge is net inward (the chest is the
    highest pressure in the engine), out past the exhaust edge net outward.  The summary
    reports each path per cycle, per hour and of the steam supplied, and the share of the
    steam that leaves the steam side is the steam edges' two together."""
    import numpy as np
    from corliss.engine.leak_paths import edge_leak_scales
    r = corliss.simulate(make_scene(
        engine={"leakage_model": "period", "steam_edge_leak_rate": RATE,
                "exhaust_edge_leak_rate": RATE},
        run={"effects": ["port_flow", "rod_angularity", "leakage"], "fidelity": "fast"}))
    s = r.summary
    scale = edge_leak_scales(_gear())
    ts = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    t = ts["time_s"].to_numpy()
    supplied = float(r.last_cycle["m_supply_kg"])
    fed = 0.0
    for e, end in enumerate(("head", "crank")):
        p = ts[f"p_{end}_Pa"].to_numpy()
        for path, dp, k in ((f"valve_leak_{end}", r.chest.p - p, 2 * e),
                            (f"valve_leak_{end}_exhaust", p - r.exhaust.p, 2 * e + 1)):
            want = float(np.trapezoid(R_SI * scale[k] * dp, t))
            gross = float(np.trapezoid(R_SI * scale[k] * np.abs(dp), t))
            got = s["leak_paths"][path]
            assert want > 0.0
            assert abs(got["kg_per_cycle"] - want) < 0.02 * gross, (path, got, want)
            assert got["fraction_of_steam"] == pytest.approx(got["kg_per_cycle"] / supplied,
                                                             rel=1e-12)
        fed += s["leak_paths"][f"valve_leak_{end}"]["kg_per_cycle"]
    assert s["valve_leakage_fraction_of_steam"] == pytest.approx(fed / supplied, rel=1e-12)
    assert s["mass_balance_error"] < 1e-4


def test_a_negative_edge_rate_is_refused():
    with pytest.raises(InputError, match="engine.exhaust_edge_leak_rate"):
        make_scene(engine={"leakage_model": "period", "exhaust_edge_leak_rate": "-1 lb/h psi"},
                   run={"effects": ["port_flow", "rod_angularity", "leakage"]})


def test_a_governed_runs_edges_leak_at_the_scale_of_each_turns_setting():
    """An edge's leak is the reference rate times its scale, the port's length over the
    reference's and the reference's face width over the edge's mean overlap while
    closed (:mod:`corliss.engine.leak_paths`); a shaft governor that shortens the
    cut-off moves the valve's travel and so the overlap.  The bundled Armington & Sims
    engine with both edges leaking 3 lb/h per psi, its load halved at 1 s: the setting
    goes from 0.56 to 0.80 and the head end's steam-edge scale from 2.81 to 3.48.  Each
    turn, each head-end edge's leak is the rate times the scale of the setting the turn
    starts at (:func:`~corliss.engine.leak_paths.edge_leak_scales` of the gear at that
    setting) times the integral over the turn's time of the difference across it (the
    supply less the head end's pressure, the head end's less the exhaust's).

    Tolerance 1e-3: the integral is the trapezoid's over the one-degree samples of the
    head end's pressure, which swings fastest at the events (5e-4 measured), and the run
    reads the scales linearly between its 21 tabulated settings.  Before, every turn
    leaked at the scene's setting's scales (2.67 and 3.90), 5 to 40 % off."""
    import tomllib

    import numpy as np

    from corliss.engine.leak_paths import edge_leak_scales
    from corliss.engine.model import build_gear
    from corliss.scene import bundled_scenes, scene_from_dict

    data = tomllib.loads(bundled_scenes()["armington-sims-governor"].read_text())
    data["run"]["effects"] = list(data["run"]["effects"]) + ["leakage"]
    data["engine"].update({"leakage_model": "period", "steam_edge_leak_rate": RATE,
                           "exhaust_edge_leak_rate": RATE})
    data["load"]["step_time"] = "1 s"
    data["run"].update({"duration": "3 s", "record": "degree"})
    scene = scene_from_dict(data, name="armington-sims-leaking")
    r = corliss.simulate(scene)
    gear = build_gear(scene)
    ts = r.timeseries
    settings = []
    for k in range(1, int(ts["cycle"].max())):
        turn = ts[ts["cycle"] == k]
        end = ts[ts["cycle"] == k + 1].iloc[:1]        # the turn's end: the next's start
        t = np.r_[turn["time_s"].to_numpy(), end["time_s"].to_numpy()]
        p = np.r_[turn["p_head_Pa"].to_numpy(), end["p_head_Pa"].to_numpy()]
        setting = float(turn["actuator_frac"].iloc[0])
        settings.append(setting)
        scale = edge_leak_scales(gear.with_setting(setting))
        row = r.cycles.iloc[k - 1]
        steam = R_SI * scale[0] * np.trapezoid(r.chest.p - p, t)
        exhaust = R_SI * scale[1] * np.trapezoid(p - r.exhaust.p, t)
        assert row["m_valve_leak_head_kg"] == pytest.approx(steam, rel=1e-3), k
        assert row["m_valve_leak_head_exhaust_kg"] == pytest.approx(exhaust, rel=1e-3), k
    assert min(settings) < 0.57 and max(settings) > 0.79      # the setting moved
