"""The skin model of the cylinder wall (corliss.engine.wall): a wall with a
temperature, a water film, and heat only down the temperature difference.

The behaviour tests run the 10 x 16 in Meyer cut-off engine of the bundled scenes
(150 rpm, 100 psig, exhaust 2 psig) at the ``fast`` fidelity; each compares the model
with itself under one change, in the direction the period measured.
"""

from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest

import corliss
from conftest import make_scene
from corliss.engine.kernels import properties, walls
from corliss.scene.loader import bundled_scenes, scene_from_dict
from corliss.thermo.steam import HEOSSteam
from corliss.thermo.steam_table import covers
from corliss.thermo.wall_properties import film_enthalpies


def _scene(name="meyer-cutoff", fidelity="fast", **changes):
    data = copy.deepcopy(tomllib.loads(bundled_scenes()[name].read_text()))
    data["engine"]["wall_heat_model"] = "skin"
    data["run"]["effects"] = list(data["run"]["effects"]) + ["wall_heat"]
    data["run"]["fidelity"] = fidelity
    for section, values in changes.items():
        data.setdefault(section, {}).update(values)
    return scene_from_dict(data, name=f"skin-{name}")


_RUNS: dict = {}


def _run(key, **changes):
    """A run of the Meyer engine with the skin wall, each asked for once."""
    if key not in _RUNS:
        _RUNS[key] = corliss.simulate(_scene(**changes))
    return _RUNS[key]


def _missing(r):
    s = r.summary
    assert s["cycles_to_converge"] is not None
    return 0.5 * (s["missing_water_fraction_head"] + s["missing_water_fraction_crank"])


# --- the second law -----------------------------------------------------------------

SUPPLIES = {"saturated": {"temperature": "saturated"},
            "wet": {"temperature": "saturated", "dryness": 0.95},
            # 250 degF above the saturation temperature of 114.7 psia (337.9 degF)
            "superheated": {"temperature": "588 degF"}}


@pytest.mark.parametrize("supply", sorted(SUPPLIES))
@pytest.mark.parametrize("speed", ["10 rpm", "120 rpm", "600 rpm"])
def test_the_wall_never_gives_heat_against_the_temperature_difference(supply, speed):
    """Second law at the wall: over every interval between samples of a converged
    cycle, the heat that goes down T_w - T_sat (condensation on the wall, evaporation
    off it) has the sign of T_w - T_sat, and the convected heat the sign of T_w - T,
    wherever the difference keeps its sign over the interval (where it changes sign
    the heat may go either way; 0.05 K is the table's temperature resolution).  Every
    sampled state lies inside the steam table's range and away from the kernel's
    clamps (the old Marks schedule pushed exhaust steam to 1195 K)."""
    r = corliss.simulate(_scene("default", "standard", run={"speed": speed},
                                supply=SUPPLIES[supply]))
    s = r.summary
    assert s["cycles_to_converge"] is not None
    assert s["energy_balance_error"] < 1e-4       # the standard preset's tolerance
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    heos = HEOSSteam()
    for end in ("head", "crank"):
        p = last[f"p_{end}_Pa"].to_numpy()
        T = last[f"T_{end}_K"].to_numpy()
        Tw = last[f"T_wall_{end}_K"].to_numpy()
        Tsat = np.array([heos.t_sat(v) for v in p])
        for col, diff in ((f"Q_sat_{end}_J", Tw - Tsat), (f"Q_conv_{end}_J", Tw - T)):
            dQ = np.diff(last[col].to_numpy())
            scale = np.max(np.abs(dQ))
            same = (np.sign(diff[1:]) == np.sign(diff[:-1])) & (np.abs(diff[1:]) > 0.05) & (
                np.abs(diff[:-1]) > 0.05)
            # samples are cubic Hermite interpolants inside the integrator's steps: a
            # flow that starts within a step (the film wetting, the steam turning
            # wet) dips by up to about 1 % of the largest interval's heat before it
            # rises (the old schedule sent a third of its heat the wrong way)
            bad = same & (dQ * np.sign(diff[1:]) < -1e-2 * scale)
            assert not bad.any(), (col, np.nonzero(bad)[0][:5])
            # and over each stretch where the difference keeps its sign, the heat's
            # total goes its way (to the preset's 1e-4 of the largest interval's)
            edges = np.flatnonzero(~same)
            for a, b in zip(np.r_[-1, edges], np.r_[edges, same.size]):
                if b - a > 2:
                    total = np.sum(dQ[a + 1:b])
                    assert total * np.sign(diff[a + 2]) >= -1e-4 * scale, (col, a, b)
        # dry steam is heated at most to the wall: superheat only where the wall,
        # the supply or compression put it (the supply's temperature bounds them)
        rho = last[f"m_{end}_kg"].to_numpy() / last[f"V_{end}_m3"].to_numpy()
        assert rho.min() > properties.RHO_MIN
        assert T.max() < max(r.chest.T, Tw.max()) + 150.0
        x = last[f"x_{end}_frac"].to_numpy()
        for k in range(0, p.size, 8):     # every eighth sample: HEOS is slow
            st = (heos.px(p[k], x[k]) if x[k] < 1.0 - 1e-9
                  else heos.pt(p[k], max(T[k], Tsat[k] + 1e-3)))
            assert covers(rho[k], st.u), (end, k, rho[k], st.u)
        # the film dries to nothing, not below (within 1e-4 of the steam the end
        # holds, ten times the standard preset's absolute tolerance on the film)
        assert last[f"m_film_{end}_kg"].min() > -1e-4 * last[f"m_{end}_kg"].max()


def _default_skin(speed: str):
    """The default engine (12 x 24 in, 100 psig, exhausting to atmosphere) with the skin
    wall at the standard preset."""
    return make_scene(engine={"wall_heat_model": "skin"},
                      run={"speed": speed, "effects": ["port_flow", "rod_angularity",
                                                       "wall_heat"]})


@pytest.mark.parametrize("speed", ["10 rpm", "120 rpm"])
def test_steam_film_and_surface_make_entropy_at_every_sample(speed):
    """The second law for the exchange of steam, film and surface, interval by interval.

    Take the steam of an end (enthalpy h, entropy s, temperature T: the saturation
    temperature when wet), its film (saturated water at the surface's temperature
    T_w: h_L(T_w), s_L(T_w), IAPWS-95) and the surface at T_w.  Over an interval the
    film gives the steam the water dm = -d m_f at h_L, and the surface gives film and
    steam the heat dQ' = d(Q_sat + Q_conv) (condensation and evaporation down
    T_w - T_sat, convection down T_w - T).  The steam, an open system at fixed volume
    as far as this exchange goes, gains T dS = dE - h dm with dE = h_L dm + dQ', so
    dS_steam = s dm + (h_L dm + dQ' - h dm) / T; the film changes by -s_L dm (and by
    m_f c dT_w / T_w as it warms with the surface, whose heat m_f c dT_w that is: the
    two cancel), and the surface by -dQ' / T_w.  The entropy made is their sum::

        dS_gen = dm [s - s_L + (h_L - h) / T] + dQ' (1/T - 1/T_w).

    Condensing (dm < 0, T_w < T_sat): at one pressure b = h - T_w s is least for water
    at T_w, so the sum is >= 0; evaporating (dm > 0, T_w > T_sat), the water's own
    term is c [x - 1 - ln x] >= 0 with x = T_w/T_sat, and the vapour's mixing into the
    steam is >= 0 as s is concave in h at one pressure.  The model's heat into the
    steam, Q_<end>_J, counts the water from the row's reference h_ref (the steam's
    energy gains dQ + h_ref dm): it must be dQ' + dm (h_L(T_w) - h_ref), the water
    at the surface's temperature; written with it, dS_gen = dm [s - s_L + (h_ref -
    h)/T + (h_L - h_ref)/T_w] + dQ (1/T - 1/T_w).  Before, the film's water was
    booked at h_ref, saturated water at 408 K (the mean of supply and exhaust: above
    the exhaust stroke's saturation temperature): the heat check failed, and with that
    booking (s_L at 408 K) the sum was negative at 10 rpm on 6 and 5 intervals of the
    cycle, -1.8e-3 and -1.6e-3 J/K in all, by up to 8e-5 J/K beyond the tolerance.

    The states are the samples 1 deg apart, each interval's sum taken at its midpoint;
    the tolerance is that quadrature's error, the variation over the interval of
    each factor times its flow, |dm| |d f| + |dQ| |d g| (at admission the pressure
    doubles within a degree, and the midpoint errs by up to 6e-4 J/K there, inside
    the bound); the heat check to 1e-3 of the largest interval's, the same midpoint's
    error."""
    import CoolProp.CoolProp as CP
    r = corliss.simulate(_default_skin(speed))
    assert r.summary["cycles_to_converge"] is not None
    # the reference the heat into the steam counts the film's water from
    h_ref = film_enthalpies(0.5 * (r.chest.T + r.exhaust.T))[0]
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    heos = HEOSSteam()

    def water(T_K):
        return (CP.PropsSI("H", "T", T_K, "Q", 0, "Water"),
                CP.PropsSI("S", "T", T_K, "Q", 0, "Water"))
    for end in ("head", "crank"):
        p = last[f"p_{end}_Pa"].to_numpy()
        T = last[f"T_{end}_K"].to_numpy()
        x = last[f"x_{end}_frac"].to_numpy()
        Tw = last[f"T_wall_{end}_K"].to_numpy()
        film = last[f"m_film_{end}_kg"].to_numpy()
        Qw = (last[f"Q_sat_{end}_J"] + last[f"Q_conv_{end}_J"]).to_numpy()
        Q = last[f"Q_{end}_J"].to_numpy()
        st = [heos.px(p[k], x[k]) if x[k] < 1.0 - 1e-9 else heos.pt(p[k], T[k])
              for k in range(p.size)]
        h, s = np.array([v.h for v in st]), np.array([v.s for v in st])
        hL, sL = np.array([water(t) for t in Tw]).T
        f = s - sL + (h_ref - h) / T + (hL - h_ref) / Tw
        g = 1.0 / T - 1.0 / Tw
        dm, dQ = -np.diff(film), np.diff(Q)
        mid = lambda v: 0.5 * (v[1:] + v[:-1])   # noqa: E731
        gen = dm * mid(f) + dQ * mid(g)
        tol = np.abs(dm) * np.abs(np.diff(f)) + np.abs(dQ) * np.abs(np.diff(g))
        # the heat the surface gave (Q_sat + Q_conv) is what the steam's heat counts
        # beyond the water's enthalpy at the surface's temperature
        assert np.allclose(np.diff(Qw) + dm * mid(hL - h_ref), dQ, rtol=0.0,
                           atol=1e-3 * np.abs(dQ).max())
        k = int(np.argmin(gen + tol))
        assert (gen + tol).min() >= 0.0, (end, k, gen[k], tol[k])
        assert gen.sum() > 0.0


def test_the_films_reference_enthalpy_leaves_the_water_rate():
    """The film's water is at the surface's temperature: the temperature the row's
    reference enthalpy h_L is taken at (the mean of supply and exhaust, 408 K on the
    default engine) only sets where the film's energy is counted from, and moving it
    to the exhaust's saturation (373 K) or the supply's (444.6 K) leaves the water
    rate at 120 rpm within 1e-4 (the convergence tolerance: the reference enters the
    deep wall's search through films not yet periodic; 8e-6 and 3.1e-5 measured).
    With the film's water at that fixed enthalpy the water rate moved by -0.9 to
    +1.0 % (the issue's figures)."""
    from corliss.thermo import wall_properties
    film_enthalpies = wall_properties.film_enthalpies
    rates = {}
    for name, T_ref in (("mean", None), ("exhaust", 373.124), ("supply", 444.6)):
        with pytest.MonkeyPatch.context() as mp:
            if T_ref is not None:
                mp.setattr(wall_properties, "film_enthalpies",
                           lambda T, T_ref=T_ref: film_enthalpies(T_ref))
            r = corliss.simulate(_default_skin("120 rpm"))
        assert r.summary["cycles_to_converge"] is not None
        rates[name] = r.summary["water_rate_kg_per_kWh"]
    for name in ("exhaust", "supply"):
        assert rates[name] == pytest.approx(rates["mean"], rel=1e-4), name


# --- behaviour against the period ---------------------------------------------------

def test_missing_water_rises_as_cut_off_shortens():
    """Marks Art. 93 ("early cut-offs in small cylinders very much increase the
    condensation") and the superheater makers' table for saturated locomotives (0.42
    of the steam at 0.1 cut-off falling to 0.11 at 0.55; Elesco engineering data as
    quoted in Open Rails' SteamTable.cs): three cut-offs of the Meyer engine (blocks
    at 1, 0.4 and 0 of the screw: about 0.16, 0.42 and 0.79 of the stroke), the
    missing water at cut-off rises as cut-off shortens, by more than a third from the
    longest to the shortest (the table's ratio over 0.1-0.55 is nearly four)."""
    m = [_missing(_run(f"cut{v}", valve_gear={"setting": v})) for v in (0.0, 0.4, 1.0)]
    assert m[0] < m[1] < m[2]
    assert m[2] > 1.33 * m[0]


def test_missing_water_changes_only_a_little_with_the_exhaust_temperature():
    """Callendar and Nicolson (Min. Proc. ICE 131, 1897-98; DPJ 312, 1899, p. 165): the
    condensation "changes only a little with the temperatures of the entering and
    exhausting steam".  The period disagrees with itself here: Hill's Harris-Corliss
    engine condensed 66 % of its indicated steam running condensing and 56 %
    non-condensing (Marks Art. 78, p. 198: 0.40 and 0.36 of the steam, a ratio of
    1.11), and Marks's eq. 221, a formula fitted to engines, makes it proportional to
    the fall to the exhaust's temperature (0.19, 0.22 and 0.26 on this card at 16.7,
    10 and 4 psia, a ratio of 1.37).  The model takes the measurements' side: the same
    engine and supply exhausting at 2 psig, 10 psia and 4 psia (a condenser), the
    missing water at cut-off changes by under a fifth from the least to the most
    (0.144, 0.134 and 0.13 here, the water left on the wall boiling off in the exhaust
    before the surface reaches the exhaust's temperature)."""
    m = [_missing(_run(key, valve_gear={"setting": 0.4}, exhaust=ex))
         for key, ex in (("cut0.4", {}), ("ex10", {"pressure": "10 psia"}),
                         ("ex4", {"pressure": "4 psia"}))]
    assert max(m) < 1.2 * min(m)


def _leak_run(key, **changes):
    """The Meyer engine with Callendar and Nicolson's rate of leak (3 lb/h per psi, chest
    to exhaust: DPJ 312, 1899, p. 163) by the period's law."""
    changes.setdefault("engine", {}).update(
        {"leakage_model": "period", "valve_leak_rate": "3 lb/h psi"})
    changes.setdefault("run", {})["effects"] = ["port_flow", "rod_angularity", "wall_heat",
                                                "leakage"]
    return _run(key, **changes)


PRESSURES = (("p40", {"pressure": "40 psia"}), ("p90", {"pressure": "90 psia"}),
             ("cut0.4", {}))


def test_condensation_alone_falls_as_the_initial_temperature_rises():
    """The IMechE Steam-Engine Research Committee (Capper, 1905, in Lineham, A Text-Book
    of Mechanical Engineering, App. VI) measured condensation and leakage apart: "the
    initial condensation, taken separately from leakage, diminishes with increase of
    initial temperature", with a leak of over 20 % of the steam supplied.  The Meyer
    engine at one cut-off on 40, 90 and 114.7 psia: the water missing at cut-off
    without leakage falls (0.24, 0.17, 0.14 of the steam here); with Callendar and
    Nicolson's rate of leak the leak is a rising share of the steam, from 0.1 to 0.25
    of it, about the fifth the committee found."""
    m = [_missing(_run(key, valve_gear={"setting": 0.4}, supply=sup))
         for key, sup in PRESSURES]
    assert m[0] > m[1] > m[2]
    leak = [_leak_run(f"leak-{key}", valve_gear={"setting": 0.4}, supply=sup).summary[
        "valve_leakage_fraction_of_steam"] for key, sup in PRESSURES]
    assert leak[0] < leak[1] < leak[2]
    assert 0.1 < leak[0] and leak[2] < 0.25


def _edge_leak_run(key, **changes):
    """The Meyer engine with leakage by the period's law across each edge of its valve:
    Callendar and Nicolson's 3 lb/h per psi (DPJ 312, 1899, p. 163) past each closed
    steam edge and each closed exhaust edge of the reference valve, scaled to the
    Meyer valve's 7 in ports and its faces (:mod:`corliss.engine.leak_paths`; with the
    ports blocked, each end's two edges in series and the two ends side by side leak
    the valve's whole 3 lb/h per psi, the path they measured)."""
    changes.setdefault("engine", {}).update(
        {"leakage_model": "period", "steam_edge_leak_rate": "3 lb/h psi",
         "exhaust_edge_leak_rate": "3 lb/h psi"})
    changes.setdefault("run", {})["effects"] = ["port_flow", "rod_angularity", "wall_heat",
                                                "leakage"]
    return _run(key, **changes)


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="issue 31: condensation alone falls with the initial "
                   "temperature as Capper found, but the total with a fifth of the steam "
                   "leaking falls too, where his rose (docs/validation/condensation.md)")
def test_condensation_alone_falls_while_condensation_plus_leakage_rises_as_capper_found():
    """Capper's pair (the IMechE Steam-Engine Research Committee's first report, March
    1905, in Lineham, A Text-Book of Mechanical Engineering, App. VI, note to pp. 614 and
    884): on one horizontal engine, non-condensing and condensing, with a slide valve's
    leak "over 20 % of the steam supply", (2) "the initial condensation, taken separately
    from leakage, diminishes with increase of initial temperature" and (3) "the total
    missing quantity increases with temperature increase".  How the temperature was
    raised is not in what was read; the steam is taken saturated, its temperature raised
    with its pressure (the period's "initial temperature" of saturated steam), an
    inference.  His engine's size, speed and cut-off were not read: the Meyer engine
    (horizontal, double-acting, slide valves, non-condensing) at one setting (0.4 of the
    screw) on 40, 90 and 114.7 psia, the leak across each valve edge at Callendar and
    Nicolson's rate (``_edge_leak_run``), 0.23 to 0.29 of the steam: over the fifth he
    found.  Condensation alone (no leak) must fall and the missing water of the feed with
    the leak must rise, each from one pressure to the next (the sign only: his figures
    were not read).

    The model: condensation alone 0.234, 0.166, 0.143 (falls, as he found); the feed's
    missing water with the leak 0.476, 0.473, 0.467 (falls by 0.009: his total rose).
    Raising the temperature by superheat instead, at 114.7 psia (0, 10, 20, 40, 80 K):
    condensation alone 0.143, 0.069, 0.001, 0.001, 0.014 (falls; the last not settled); the total 0.467,
    0.440, 0.425, 0.437, 0.458 (falls, then rises, never above the saturated run's).
    Neither reading reproduces his total's rise; strict: this fails once the model does."""
    alone = [_missing(_run(key, valve_gear={"setting": 0.4}, supply=sup))
             for key, sup in PRESSURES]
    assert alone[0] > alone[1] > alone[2], alone
    total = [_edge_leak_run(f"edge-leak-{key}", valve_gear={"setting": 0.4}, supply=sup)
             .summary["missing_water_fraction_of_feed"] for key, sup in PRESSURES]
    assert total[0] < total[1] < total[2], (alone, total)


#: Willans's trials (1888; abstract in Sci. Am. Suppl. 647, 26 May 1888): the missing
#: quantity of feed water at cut-off of his simple engine against the initial pressure
#: [psia] (``docs/validation/condensation_measurements.csv``, S1).
WILLANS_1888 = {40: 0.117, 90: 0.248, 110: 0.30}

#: One pound-force per square inch [Pa].
PSI = 6894.757293168

#: The pressure of the dry saturated steam his throttle worked from [psia]: not stated
#: in what was read, so the least that gives his highest initial pressure, 110 psia,
#: through a throttle (an assumption; from 165 psia, above the 160 lb of his compound
#: trials, the model's total rises less, docs/validation/condensation.md).
WILLANS_BOILER_PSIA = 115.0


def _throttled(p_psia, boiler_psia=WILLANS_BOILER_PSIA):
    """The temperature [K] of dry saturated steam at ``boiler_psia`` throttled to
    ``p_psia``: a throttle does no work and, short and lagged, takes no heat, so the
    enthalpy after it is the enthalpy before (steady-flow energy equation)."""
    heos = HEOSSteam()
    return heos.ph(p_psia * PSI, heos.px(boiler_psia * PSI, 1.0).h).T


def _willans_run(p_psia, leak=True):
    """The Meyer engine run as Willans ran his simple engine: single-acting (steam on
    the head end only; Lineham, App. II, note to p. 633: "work is only done on the down
    stroke"), 400 rpm, exhausting to the atmosphere, no jacket (Sci. Am. Suppl. 647), at
    one expansion (the 0.4 setting: cut-off 0.42) with the initial pressure set by
    throttling (Lineham, note to p. 627: the power "varied by throttling the steam at
    constant expansion"), the steam throttled from :data:`WILLANS_BOILER_PSIA`.  With
    ``leak`` the leak across each valve edge at Callendar and Nicolson's 3 lb/h per psi
    (``_edge_leak_run``; the central valve's own path chest to exhaust is not known, so
    none).  The wall with the steam superheated settles slowly: up to 150 cycles are
    allowed (the 40 psia point settles in 79)."""
    changes = dict(valve_gear={"setting": 0.4}, engine={"steam_ends": "head"},
                   run={"speed": "400 rpm", "max_cycles": 150},
                   exhaust={"pressure": "0 psig"},
                   supply={"pressure": f"{p_psia} psia",
                           "temperature": f"{_throttled(p_psia):.3f} K"})
    if leak:
        return _edge_leak_run(f"willans-leak-p{p_psia}", **changes)
    return _run(f"willans-p{p_psia}", **changes)


def test_throttled_steam_lifts_the_missing_water_with_the_initial_pressure_as_willans_found():
    """Willans's missing water of the feed rose with the initial pressure (``WILLANS_1888``)
    on an engine whose pressure was set by throttling at constant expansion
    (``_willans_run``).  Throttled from 115 psia, his steam is superheated by 21.6 K at 40
    psia, 4.2 K at 90 and 0.7 K at 110 (``_throttled``, HEOS): at 40 psia the superheat
    keeps the steam off the wall (of superheating, Lineham p. 885: "a 5 % extra heat
    supply will often eliminate a 20 % loss"), so on his conditions the water missing
    at cut-off without leakage rises with the pressure (0.003, 0.074, 0.078 of the
    steam here) and the missing water of the feed with the leak rises too (0.225,
    0.271, 0.272), the direction he found (the sign only: his level and expansion were
    not found).  Both runs must be periodic and each of the higher pressures
    must lose more than the 40 psia point; the same runs on dry saturated steam fall
    (0.147, 0.090, 0.079 alone; 0.312, 0.280, 0.272 with the leak).  The size is held
    by the strict xfail below."""
    alone = {p: _willans_run(p, leak=False).summary for p in WILLANS_1888}
    total = {p: _willans_run(p).summary for p in WILLANS_1888}
    for s in (*alone.values(), *total.values()):
        assert s["cycles_to_converge"] is not None
    alone = {p: s["missing_water_fraction_head"] for p, s in alone.items()}
    total = {p: s["missing_water_fraction_of_feed"] for p, s in total.items()}
    for p in (90, 110):
        assert alone[p] > alone[40] and total[p] > total[40], (alone, total)


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="issue 31: on Willans's conditions as found (single-acting, "
                   "400 rpm, throttled at constant expansion) the model's missing water "
                   "of the feed rises by 0.05 where his rose by 0.13 and 0.18 "
                   "(docs/validation/condensation.md)")
def test_condensation_plus_leakage_rises_with_the_initial_pressure_as_willans_found():
    """Willans's trials (``WILLANS_1888``): the missing water of the feed at cut-off,
    leakage included, rose from 0.117 at 40 psia to 0.248 at 90 and nearly 0.30 at 110.
    On his conditions as far as they were found (``_willans_run``: single-acting, 400
    rpm, non-condensing, no jacket, throttled at constant expansion) the model's must
    rise from 40 to 90 and to 110 psia by his 0.131 and 0.183, each to half of it (his
    bore, stroke, cut-off and boiler pressure were not found, so the rise compares, not
    the level).

    The model, the leak past each edge at 3 lb/h per psi (0.15 to 0.16 of the steam):
    0.225, 0.271, 0.272, a rise of 0.046 and 0.047.  Across the period's range of rates
    on one valve: past each edge at 0.4, 0.039, 0.106, 0.109 (rises 0.067, 0.070); at
    3.6 past each edge and 3.6 chest to exhaust (0.30 to 0.32 of the steam), 0.374,
    0.415, 0.418 (0.041, 0.044).  Throttled from 165 psia (28 K superheat at 40 psia,
    where the wall does not settle in 450 cycles): rises of 0.006 to 0.016 and 0.025 to
    0.046.  Other settings of the 10 x 16 engine at 400 rpm (head cut-off 0.55 to 0.23, the
    same rates, throttled from 115 psia): rises of -0.04 to 0.07 (at 0.31 and 0.23 the
    40 psia point does not settle in 450 cycles).  On dry saturated steam, as the
    test stood before, the total falls (0.312, 0.280, 0.272).  The rise comes from the
    superheat at 40 psia taking the condensation there to nothing; the leak's share of
    the steam rises only from 0.148 to 0.159.  Strict: this fails once the model does
    what his trials show."""
    m = {p: _willans_run(p).summary["missing_water_fraction_of_feed"] for p in WILLANS_1888}
    for p in (90, 110):
        rise, theirs = m[p] - m[40], WILLANS_1888[p] - WILLANS_1888[40]
        assert abs(rise - theirs) < 0.5 * abs(theirs), (p, m)


def test_the_condensing_share_falls_from_saturation_to_the_band():
    """A surface below saturation condenses at the full coefficient while the steam at
    it is saturated or wet, and not at all once it is superheated by
    :data:`walls.SUPERHEAT_BAND_K` (Hirn, through DPJ 278 pp. 538-539: heat enters the
    gas very slowly; Marks Art. 78, eq. 220b: the superheat meets the wall's demand
    first), the cubic step's middle half-way."""
    assert walls.condensing_share(-5.0) == 1.0
    assert walls.condensing_share(0.0) == 1.0
    assert walls.condensing_share(0.5 * walls.SUPERHEAT_BAND_K) == pytest.approx(0.5)
    assert walls.condensing_share(walls.SUPERHEAT_BAND_K) == 0.0
    assert walls.condensing_share(80.0) == 0.0


#: Superheated supplies whose skin wall has no periodic state (issue 31): the bundled
#: 20 x 42 in Corliss engine at 80 K of superheat (482 degF against 338 degF at 114.7
#: psia); the Meyer engine at 0.4 of the screw with 150 degF of superheat (488 degF);
#: the Meyer engine on 40 psia of steam throttled from 140 psia dry saturated
#: (isenthalpic, IAPWS-95: 312.7 degF, 25 K of superheat).
SUPERHEATED_UNSETTLED = {
    "corliss-80K": ("corliss-trip-gear", {"supply": {"temperature": "482 degF"}}),
    "meyer-150degF": ("meyer-cutoff", {"valve_gear": {"setting": 0.4},
                                       "supply": {"temperature": "488 degF"}}),
    "meyer-40psia-throttled": ("meyer-cutoff", {"supply": {"pressure": "40 psia",
                                                           "temperature": "312.7 degF"}}),
}


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="issue 31: at a fixed deep wall the superheated skin wall has a "
                   "dry and a wet periodic state, and the deep wall's balance changes sign "
                   "between them without a root (docs/validation/condensation.md, "
                   "\"Superheated walls that do not settle\")")
@pytest.mark.parametrize("case", sorted(SUPERHEATED_UNSETTLED))
def test_a_superheated_supply_settles_with_the_skin_wall(case):
    """A superheated supply with the skin wall reaches a periodic state in the fast
    preset's cycles (60 with the wall), and its water missing at cut-off is not
    negative at either end (the steam read at cut-off cannot exceed the steam
    supplied and the cushion's).  The period's engines ran steadily on superheated
    steam, with less condensation than on saturated (Lineham p. 885; Marks Art. 78).
    Strict: this fails once the model settles them."""
    name, changes = SUPERHEATED_UNSETTLED[case]
    r = corliss.simulate(_scene(name=name, **changes))
    s = r.summary
    assert s["cycles_to_converge"] is not None, s["periodicity_residuals"]
    assert s["missing_water_fraction_head"] >= 0.0
    assert s["missing_water_fraction_crank"] >= 0.0


def _large_slow(**changes):
    """Marks's 32 x 48 in stationary engine (the bundled scene, after his Art. 3: 20
    rpm, 60 psig, 1 psig exhaust) with the skin wall, fast preset."""
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["marks-32x48-stationary"].read_text()))
    data["engine"]["wall_heat_model"] = "skin"
    data["run"]["effects"] = list(data["run"]["effects"]) + ["wall_heat"]
    data["run"].update({"fidelity": "fast", "max_cycles": 300})
    for section, values in changes.items():
        data.setdefault(section, {}).update(values)
    return corliss.simulate(scene_from_dict(data, name="skin-large-slow"))


def test_superheat_of_80_K_removes_most_initial_condensation_on_a_large_slow_engine():
    """Lineham (A Text-Book of Mechanical Engineering, p. 885): "a 5 % extra heat
    supply will often eliminate a 20 % loss"; Marks Art. 78 (superheat "the most
    efficient expedient"; Hirn's unjacketed cylinder, 14.75 kg of steam per horse-power
    hour saturated, 10 superheated to 250 degC).  On a large slow engine (the bundled
    32 x 48 in stationary engine at 20 rpm) 80 K of superheat at the supply (451 degF
    against the 307 degF saturation of 74.7 psia, some 7 % more heat per kilogram)
    leaves under a fifth of the saturated supply's water missing at cut-off (both
    ends' mean): the loss "eliminated".  The saturated supply still has more than a
    tenth of its steam missing (the period's saturated engines lost more: Hill's
    Harris-Corliss 0.36 to 0.40, Marks Art. 78), so the fall is the superheat's, not
    the rule's.  (The bundled 20 x 42 in Corliss engine at 80 rpm shows the same,
    0.157 saturated and 0.006 superheated before the film's enthalpy followed the surface, but its superheated wall does not settle to
    the presets' tolerances: docs/validation/condensation.md.)"""
    runs = {k: _large_slow(supply={"temperature": t})
            for k, t in (("saturated", "saturated"), ("superheated", "451 degF"))}
    m = {}
    for k, r in runs.items():
        assert r.summary["cycles_to_converge"] is not None, k
        m[k] = _missing(r)
    assert m["saturated"] > 0.1
    assert m["superheated"] < 0.2 * m["saturated"]


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="issue 31: with Callendar and Nicolson's coefficient the wall "
                   "condenses on through the expansion (docs/validation/condensation.md)")
def test_the_water_missing_at_cut_off_is_mostly_still_missing_at_release():
    """Marks Art. 86, pp. 213-215: on tight engines the steam present as vapour is
    least at cut-off and rises steadily to release (re-evaporation); Spangler's 10 x 20
    in Buckeye at 200 rpm (J. Franklin Inst., Feb. 1886, in Marks) showed 0.39 of its
    steam missing at 0.3 of the stroke and still 0.30 at 0.9, three quarters of it:
    the rest of the wall's heat goes back in the exhaust, the period's "exhaust
    waste".  With the blocks at 0.4 of the screw (cut-off 0.42 head, 0.29 crank) the
    missing water, read from the steam's state less the cushion's, falls at every
    eighth of the crank angle from cut-off to release, and at release is between 0.6
    and 0.9 of its value at cut-off (the band spans Spangler's 0.75 and a cut-off a
    tenth of the stroke either side of his).  With the old coefficient, 3e5 W/(m2 K),
    it did (0.80 and 0.72 of 0.345 and 0.419); with Callendar and Nicolson's the
    surface stays below the steam's saturation temperature through the expansion and
    the missing water rises from 0.13 at cut-off to 0.22 at release (head end).  Their
    own record has the wall warmest "after cut-off, when the condensation period
    ends" (DPJ 312 p. 162), so the two measurements pull apart here.  The surface
    under the steam in admission is 36 to 44 K below it here (theirs about 15 K, p.
    163), held down through the exhaust by the wet exhaust steam boiling on it; without
    that (the exhaust's mist not wetting a surface above saturation, after Kirsch and
    Donkin's revealer, DPJ 282 pp. 150-151 and 202) the surface is 15 to 18 K below in
    admission, as theirs, but the wall then holds 5 % of the steam at cut-off, spent
    against the expansion's own wetness (isentropic from 114.7 to 50 psia, 5.4 %):
    0.052 missing at cut-off, 0.079 at mid-expansion, 0.075 at release.  Not kept
    (docs/validation/condensation.md, "the mechanisms examined").  Strict: this fails
    once the model does what Spangler's card shows."""
    r = _run("cut0.4", valve_gear={"setting": 0.4})
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    ang = np.mod(last["crank_angle_deg"].to_numpy(), 360.0)
    ang, idx = np.unique(ang, return_index=True)

    def at(col, deg):
        return float(np.interp(deg, ang, last[col].to_numpy()[idx], period=360.0))

    for end in ("head", "crank"):
        ev = r.events[end]

        def steam(deg):
            return at(f"m_{end}_kg", deg) * at(f"x_{end}_frac", deg)

        supplied = float(r.last_cycle[f"m_chest_{end}_kg"])
        cushion = steam(ev["compression_deg"])
        c = ev["cutoff_deg"]
        span = (ev["release_deg"] - c) % 360.0
        missing = np.array([(supplied - steam(c + f * span) + cushion) / supplied
                            for f in np.linspace(0.0, 1.0, 9)])
        assert np.all(np.diff(missing) < 0.0), (end, missing)
        assert 0.6 < missing[-1] / missing[0] < 0.9, (end, missing)


def test_the_water_condensed_per_stroke_rises_with_the_initial_temperature():
    """Marks Art. 75, eq. 221: the steam condensed per stroke is proportional to the
    fall from the temperature at cut-off to the exhaust's; Willans's trials (1888, as
    abstracted in Sci. Am. Suppl. 647) found the missing water rising with the initial
    pressure at constant expansion.  The Meyer engine at the same cut-off on 40, 90 and
    114.7 psia (exhausting at 16.7 psia; the fall from admission to exhaust
    temperature 27, 56 and 66 K): the water missing at cut-off per stroke rises with
    it.  (As a fraction of the steam supplied it falls, where Willans's rose: the
    steam per stroke grows with its density faster than the fall of temperature; the
    validation page gives the figures.)"""
    from corliss.thermo.steam import HEOSSteam
    steam = HEOSSteam()
    m = []
    for key, sup in (("p40", {"pressure": "40 psia"}), ("p90", {"pressure": "90 psia"}),
                     ("cut0.4", {})):
        r = _run(key, valve_gear={"setting": 0.4}, supply=sup)
        m.append(r.summary["missing_water_per_stroke_head_kg"])
        # the water missing is the steam the admission's heat condensed: the heat the
        # steam gave the wall from admission to cut-off over the latent heat, within
        # 25 % (the water the cushion and supply already held, the convection's share
        # of the heat, the film's latent heat at its own temperature: 0.97-1.20 here;
        # at 40 psia the cushion gives the wall a fifth as much again in compression)
        p = r.scene.supply.pressure_Pa
        latent = steam.px(p, 1.0).h - steam.px(p, 0.0).h
        condensed = -r.summary["heat_into_steam_admission_head_J"] / latent
        assert m[-1] == pytest.approx(condensed, rel=0.25), key
    assert 0.0 < m[0] < m[1] < m[2]
    # the rise is more than half the temperature fall's (1.7 against 2.4 from 40 psia:
    # the exhaust's temperature reaches the wall only through the water left on it)
    assert m[2] / m[0] > 1.3


def test_missing_water_falls_as_speed_rises():
    """Marks Art. 75 (the condensation per stroke is inversely as the strokes per
    minute) and Lineham, Text-Book of Mechanical Engineering, App. II p. 884 ("quick
    running" first among the remedies; Cotterill's liquefaction factor falls as the
    square root of the speed): at 60, 150 and 300 rpm the missing water falls."""
    m = [_missing(_run(f"speed{n}", valve_gear={"setting": 0.4}, run={"speed": f"{n} rpm"}))
         for n in (60, 150, 300)]
    assert m[0] > m[1] > m[2]


def test_superheat_of_250_degF_leaves_under_two_percent_missing():
    """The superheater makers' table (Elesco data, as above): 250 degF of superheat
    prevents cylinder condensation even at 0.1 cut-off; Marks Art. 78, Hirn's trials:
    superheat "the most efficient expedient".  At 250 degF above saturation the
    missing water at cut-off is under 2 % (and the steam, read from its state, is
    not counted missing for its superheat, as the dry-saturated card would be)."""
    hot = _run("superheat", valve_gear={"setting": 0.4},
               supply={"temperature": "588 degF"})
    assert _missing(hot) < 0.02
    assert _missing(hot) < 0.1 * _missing(_run("cut0.4", valve_gear={"setting": 0.4}))


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="issue 31: with Callendar and Nicolson's coefficient the wall "
                   "condenses on through the expansion (docs/validation/condensation.md)")
def test_a_saturated_card_expands_near_the_hyperbola():
    """Marks Art. 73, p. 177 (the hyperbola "coincides, with great accuracy, with the
    best results derived from indicator-diagrams") and Art. 86, p. 213 (Spangler's
    Buckeye card follows it "very closely"; its steam rises about 4 % by mid-expansion
    against the hyperbola from cut-off): at mid-expansion, halfway in crank angle from
    cut-off to release, pV of the saturated card is within 3 % of its value at
    cut-off (at 0.55 and 0.40 of the stroke, the head and crank ends' cut-offs with
    the blocks at 0.2 of the screw), where the same card without the wall falls 4 and
    6 %.  With Callendar and Nicolson's coefficient the wall condenses on through the
    expansion and the card falls 7 % (0.93 at the head end); with the old 3e5 W/(m2
    K) it was within 2 %; with a wall the exhaust's mist does not wet (above), 0.954
    and 0.948, as without the wall.  Strict: this fails once the model does what the
    cards show."""
    r = _run("cut0.2", valve_gear={"setting": 0.2})
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    ang = np.mod(last["crank_angle_deg"].to_numpy(), 360.0)
    ang, idx = np.unique(ang, return_index=True)
    for end in ("head", "crank"):
        ev = r.events[end]
        c = ev["cutoff_deg"]
        mid = c + 0.5 * ((ev["release_deg"] - c) % 360.0)
        pv = (last[f"p_{end}_Pa"].to_numpy() * last[f"V_{end}_m3"].to_numpy())[idx]
        ratio = np.interp(mid, ang, pv, period=360.0) / np.interp(c, ang, pv, period=360.0)
        assert ratio == pytest.approx(1.0, abs=0.03), end


def test_a_jacket_reduces_the_missing_water():
    """Marks Art. 79, p. 204: the jacket reduces initial condensation and aids
    re-evaporation (savings of 3-5 % "well authenticated"; Lineham App. II reports 10
    to 20 %): with the barrel jacketed at the supply's saturation temperature the
    missing water at cut-off falls."""
    bare = _missing(_run("cut0.4", valve_gear={"setting": 0.4}))
    jacketed = _missing(_run("jacket", valve_gear={"setting": 0.4},
                             engine={"jacket": "barrel"}))
    assert jacketed < bare


def test_the_jacket_is_paid_for_in_steam():
    """Marks Art. 79, p. 204: the jacket's heat comes from steam condensed in it, which
    the period's trials counted with the feed; the savings "well authenticated" are 3
    to 5 % (Lineham, App. II p. 884: 10 to 20 %).  Over the periodic cycle the heat
    the jacket gives, reported as ``jacket_heat_W``, is what the iron conducts from
    the jacket's saturation temperature to the deep wall, k / L times the barrel's
    mean exposed area times the difference (the wall update's balance, to the fast
    preset's 1e-3 of the enthalpy supplied, 2 % of the jacket's heat); its steam,
    drained at the supply's saturation, is that heat over the latent heat there; and
    counting it, the jacketed engine still uses less steam than the bare one, by no
    more than Marks's 5 %.  The period disagrees with itself on the jacket: Marks
    (Art. 79, p. 204) cites 3 to 5 % as "well authenticated" and doubts even those
    ("error is more than probable in the use of indicators"), "very doubtful if any
    very great gain is made in the case of well-covered engines", and concludes "the
    steam-jacket is not so efficient as is ordinarily assumed" (p. 237); Lineham (App.
    II, p. 884) reports 10 to 20 %.  The model's saving, 1.8 % (2.2 % with the covers
    jacketed too: ``tests/test_jackets.py``), takes Marks's side, and this test holds
    it there: above nothing and not above his 5 % (the validation page, "Jackets")."""
    from corliss.engine import wall
    from corliss.thermo.steam import HEOSSteam
    bare = _run("cut0.4", valve_gear={"setting": 0.4})
    r = _run("jacket", valve_gear={"setting": 0.4}, engine={"jacket": "barrel"})
    s = r.summary
    steam = HEOSSteam()
    p = r.scene.supply.pressure_Pa
    t_j = steam.t_sat(p)
    omega = r.scene.run.speed_rad_s
    row = r.last_cycle
    conducted = 0.0
    for e, end in enumerate(("head", "crank")):
        ga = wall.skin_row(r.geometry, e, omega, 1.0, (1.0, 1.0, 1.0), 0, jacket_T_K=t_j,
                           wall_thickness_m=r.scene.engine.wall_thickness_m)[9]
        conducted += ga * (t_j - float(row[f"T_wall_{end}_K"]))
    assert s["jacket_heat_W"] == pytest.approx(conducted, rel=0.02)
    latent = steam.px(p, 1.0).h - steam.px(p, 0.0).h
    # 1e-6: the summary reads the latent heat on the run's steam table (no CoolProp in a
    # table-tier run), whose saturation line is HEOS's to well under that
    assert s["jacket_steam_kg_per_h"] == pytest.approx(s["jacket_heat_W"] / latent * 3600.0,
                                                       rel=1e-6)
    saving = 1.0 - s["water_rate_with_jacket_kg_per_kWh"] / bare.summary["water_rate_kg_per_kWh"]
    assert s["water_rate_with_jacket_kg_per_kWh"] > s["water_rate_kg_per_kWh"]
    assert 0.0 < saving <= 0.05


def test_the_skin_matches_a_semi_infinite_wall_at_the_engine_frequency():
    """Carslaw & Jaeger sec. 2.6: a semi-infinite solid answers a surface temperature
    oscillating at omega with the flux sqrt(k rho c omega) e^{i pi/4} per kelvin; the
    lumped node (capacity C, conductance G to the mean) answers G + i omega C.  Equal
    at 150 rpm to round-off; the skin depth of grey cast iron is 1.26 mm there (the
    condensation study's table: 2.0 mm at 60 rpm, 0.89 mm at 300)."""
    from corliss.engine import wall
    for rpm, depth in ((60, 2.0e-3), (150, 1.26e-3), (300, 0.89e-3)):
        w = rpm * 2 * math.pi / 60
        assert wall.skin_depth_m(w) == pytest.approx(depth, rel=0.01)
    w = 150 * 2 * math.pi / 60
    C, G = wall.surface_node(w)
    e = math.sqrt(wall.CAST_IRON_K * wall.CAST_IRON_RHO * wall.CAST_IRON_C * w)
    assert complex(G, w * C) == pytest.approx(e * complex(math.cos(math.pi / 4),
                                                          math.sin(math.pi / 4)), rel=1e-12)


def _drive_grid(grid, surface, dt, steps):
    """Step ``grid`` with its surface held at ``surface(t)`` [K above the held node];
    the heat flux into the wall at each step's end [W/m2], the surface node's balance
    ``C_0 (T_0' - T_0) / dt + g_0 (1 - b_1) (T_0' - T_1*)``."""
    q = np.empty(steps)
    for j in range(steps):
        th = surface((j + 1) * dt)
        c0, g0, th1 = grid.surface_terms(dt)
        q[j] = c0 * (th - grid.theta[0]) + g0 * (th - th1)
        grid.advance(th)
    return q


def test_the_conduction_grid_has_the_semi_infinite_walls_periodic_response():
    """Carslaw & Jaeger sec. 2.6: a semi-infinite solid whose surface temperature is
    theta_s cos(omega t) takes the flux sqrt(k rho c omega) theta_s cos(omega t + pi/4).
    The grid of corliss.engine.wall.ConductionGrid (14 nodes to three skin depths,
    backward Euler at 0.25 deg of crank, the ideal-port stepping's), driven so at 150 rpm
    for six cycles, gives the fundamental's amplitude within 2 % and its lead within 1
    deg: the held node at three skin depths, where the wave is e^-3, and backward
    Euler's first-order lag are the errors (1.0 % and 0.08 deg measured)."""
    from corliss.engine import wall
    w = 150 * 2 * math.pi / 60
    n = 1440
    dt = 2 * math.pi / w / n
    q = _drive_grid(wall.ConductionGrid(w), lambda t: math.cos(w * t), dt, 6 * n)[-n:]
    t = dt * np.arange(5 * n + 1, 6 * n + 1)
    z = 2.0 / n * np.sum(q * np.exp(-1j * w * t))
    e = math.sqrt(wall.CAST_IRON_K * wall.CAST_IRON_RHO * wall.CAST_IRON_C * w)
    assert abs(z) / e == pytest.approx(1.0, abs=0.02)
    assert math.degrees(np.angle(z)) == pytest.approx(45.0, abs=1.0)


def test_the_conduction_grid_answers_a_short_event_as_a_semi_infinite_wall():
    """Carslaw & Jaeger sec. 2.5: a semi-infinite solid whose surface is raised by dT at
    t = 0 has taken 2 dT sqrt(k rho c t / pi) per unit area after t.  The grid at 150 rpm
    (surface cell 31 microns) and steps of 0.28 ms gives that heat within 3 % from 3
    steps (0.8 ms, a layer of 0.1 mm) to 0.1 s (beyond the admission's length), where
    the lumped node of the same wall must move its whole capacity rho c delta / 2 at
    once, five times the heat the semi-infinite wall takes in its first millisecond
    (backward Euler's lag is the grid's error at the first steps: 7 % at one)."""
    from corliss.engine import wall
    w = 150 * 2 * math.pi / 60
    dt, steps = 2.8e-4, 360
    q = _drive_grid(wall.ConductionGrid(w), lambda t: 1.0, dt, steps)
    heat = np.cumsum(q) * dt
    t = dt * np.arange(1, steps + 1)
    exact = 2.0 * np.sqrt(wall.CAST_IRON_K * wall.CAST_IRON_RHO * wall.CAST_IRON_C * t
                          / math.pi)
    assert np.all(np.abs(heat[2:] / exact[2:] - 1.0) < 0.03)


def test_the_wall_is_wetted_by_the_mixtures_dryness():
    """The wall's wetted share is read from the mixture's dryness, which the property
    step stores in its own row (``PR_X``; the port flow's exponent is the real fluid's
    and says nothing of the dryness): wholly wet below 1 - WET_BAND, dry at x = 1, the
    cubic step's middle half-way between."""
    assert properties.PR_X < properties.PR_ROWS and properties.PR_X != properties.PR_CLAMP
    assert walls.wetted_share(1.0) == 0.0
    assert walls.wetted_share(1.0 - walls.WET_BAND / 2) == pytest.approx(0.5)
    assert walls.wetted_share(0.9) == 1.0


# --- every cylinder its own wall ----------------------------------------------------

def test_a_compounds_lp_jacket_takes_its_receivers_steam():
    """Marks Art. 79 (the jacket reduces initial condensation; savings of 3-5 % "well
    authenticated") and Lineham (App. II: 10 to 20 %): a jacket saves part of the
    condensation, not all of it.  On the bundled 9 & 14 x 14 in compound (skin walls,
    fast preset) with both barrels jacketed, the LP jacket at its own receiver's
    saturation (the receiver's starting pressure, the geometric mean of supply and
    exhaust) leaves each LP end more than 0.05 of its steam missing at cut-off, where a
    jacket at the supply's saturation left 0.007 of 0.30; and the jacket's steam is
    booked at each jacket's own latent heat, so that it is the jackets' heat over
    their latent heats (the LP's at the receiver's pressure, larger than the
    supply's)."""
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["marks-compound-9-14x14"].read_text()))
    data["engine"].update({"wall_heat_model": "skin", "jacket": "barrel"})
    if "wall_heat" not in data["run"]["effects"]:
        data["run"]["effects"] = list(data["run"]["effects"]) + ["wall_heat"]
    data["run"]["fidelity"] = "fast"
    sc = scene_from_dict(data, name="skin-compound-jacketed")
    r = corliss.simulate(sc)
    s = r.summary
    assert s["cycles_to_converge"] is not None
    for end in ("lp_head", "lp_crank"):
        assert s[f"missing_water_fraction_{end}"] > 0.05, end
    heos = HEOSSteam()
    p_hp = sc.supply.pressure_Pa
    p_lp = math.sqrt(p_hp * sc.exhaust.pressure_Pa)
    row = r.last_cycle
    kg = 0.0
    for end, p in (("head", p_hp), ("crank", p_hp), ("lp_head", p_lp), ("lp_crank", p_lp)):
        kg += float(row[f"Q_{end}_J"]) / (heos.px(p, 1.0).h - heos.px(p, 0.0).h)
    rev_per_h = sc.run.speed_rad_s / (2.0 * math.pi) * 3600.0
    # 1e-6: the summary reads the latent heats from its own saturation states, which
    # agree with HEOS's here to a few parts in 1e9
    assert s["jacket_steam_kg_per_h"] == pytest.approx(kg * rev_per_h, rel=1e-6)


def test_a_compound_with_every_effect_and_skin_walls_conserves_mass_and_energy():
    """Marks's 9 & 14 x 14 compound with a chest behind its pipe, leaks, friction,
    reciprocating masses and a skin wall with its film in each end of both cylinders
    (each with its own geometry, area and events): over a converged cycle steam in
    equals steam out and enthalpy in less enthalpy out plus the heat from the walls
    equals the indicated work, to 3e-5 (the film's energy is m_f h_L, the same at
    both ends of a periodic cycle).  Run at rtol 1e-8 and periodic to 1e-5, each
    wall's heat over the cycle balanced to 1e-5 of the enthalpy supplied (the
    conductance wall's test in test_periodicity asks 1e-7 of a wall with no film
    and no deep temperature to find; four walls coupled through the receiver settle
    to 1e-5 within a few hundred cycles, a second of compiled time each hundred)."""
    import dataclasses
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["marks-compound-9-14x14"].read_text()))
    data["engine"].update({"reciprocating_mass": "300 lb", "friction_torque": "100 lbf ft",
                           "valve_leakage_area": "0.01 in2", "piston_leakage_area": "0.01 in2",
                           "wall_heat_model": "skin"})
    data["supply"].update({"chest_volume": "0.2 ft3", "pipe_diameter": "3 in"})
    data["run"]["effects"] = ["port_flow", "rod_angularity", "steam_chest", "leakage",
                              "wall_heat", "friction", "inertia"]
    scene = scene_from_dict(data)
    fid = dataclasses.replace(scene.run.fidelity, rtol=1e-8, convergence_tolerance=1e-5,
                              max_cycles=100)
    r = corliss.simulate(scene.replace_run(fidelity=fid))
    s = r.summary
    assert s["cycles_to_converge"] is not None
    # periodic to 1e-5 on each of four walls' states and the receiver's: the balance
    # closes to a few times that (1.4e-5 measured with the default coefficient)
    assert s["mass_balance_error"] < 3e-5
    assert s["energy_balance_error"] < 3e-5
    row = r.last_cycle
    for end in ("head", "crank", "lp_head", "lp_crank"):
        assert row[f"Q_to_wall_{end}_J"] > 0.0        # every end condenses on its wall
        # and is reported with its own events: water missing at its own cut-off, the
        # heat of its admission leaving the steam
        assert 0.0 < s[f"missing_water_fraction_{end}"] < 1.0
        assert s[f"heat_into_steam_admission_{end}_J"] < 0.0
        assert s[f"wall_surface_swing_{end}_K"] > 0.0


@pytest.mark.parametrize("supply", sorted(SUPPLIES))
@pytest.mark.parametrize("speed", ["10 rpm", "120 rpm", "600 rpm"])
def test_the_reference_tier_runs_the_skin_wall(supply, speed):
    """The reference tier (IAPWS-95 through HEOS at every call, LSODA at 1e-9) runs a
    cycle of each of the second-law cases from the start, the wall and its film
    active, every state inside the properties' range (Marks's schedule failed here at
    10 and 120 rpm, its exhaust steam pushed beyond them); one cycle, for CI time:
    the compiled tiers above take the same right-hand side to periodicity."""
    r = corliss.simulate(_scene("default", "reference", run={"speed": speed, "cycles": 1},
                                supply=SUPPLIES[supply]))
    s = r.summary
    assert s["heat_to_walls_head_J_per_cycle"] > 0.0
    for frame in (r.timeseries, r.cycles):
        assert np.isfinite(frame.select_dtypes("number").to_numpy()).all()


def test_marks_constant_as_a_calibration():
    """``condensing_coefficient = "marks"``: the coefficient is set so that the missing
    water at cut-off is what Marks's eq. 221 gives for the same card (Art. 75, p. 190,
    with his constant of Art. 82), to the search's 1 % (and a run at that coefficient
    is what the search measured).  Marks's formula asks for more condensation than
    Callendar and Nicolson's measured coefficient, the default, gives: 0.19 of the
    steam against 0.14 on this card."""
    sc = _scene(valve_gear={"setting": 0.4}, engine={"condensing_coefficient": "marks"})
    s = corliss.simulate(sc).summary
    assert s["missing_water_fraction_head"] == pytest.approx(
        s["marks_missing_water_fraction_head"], rel=0.015)
    default = _missing(_run("cut0.4", valve_gear={"setting": 0.4}))
    assert s["missing_water_fraction_head"] > default


def test_the_wetness_at_cut_off_counts_the_walls_water():
    """English (Proc. IMechE 1887, in DPJ 267, 1888, p. 302): what counts is the water
    present at the end of admission, whether condensed in the cylinder or carried in.
    On dry saturated steam that water is what condensed, so the wetness at cut-off
    with the wall's film counted is the missing water at cut-off to 0.01 of the steam
    (the cushion's share of each differs: 0.132 against 0.131 at the head end here),
    where the mixture's wetness alone reads under 0.01 (the water is on the wall)."""
    s = _run("cut0.4", valve_gear={"setting": 0.4}).summary
    for end in ("head", "crank"):
        assert s[f"wet_fraction_at_cutoff_{end}"] < 0.01
        assert s[f"wet_fraction_at_cutoff_with_film_{end}"] == pytest.approx(
            s[f"missing_water_fraction_{end}"], abs=0.01)
