"""The skin wall with ideal ports (no ``port_flow``): corliss.engine.wall.IdealPortWall
in the stepping of corliss.engine.equilibrium, the textbook cylinder whose ends are at
chest pressure while open to the chest, so that the steam the wall condenses during
admission is made up from the chest.

One run of the 10 x 16 in Meyer cut-off engine of the bundled scenes (150 rpm, 100 psig,
exhaust 2 psig, blocks at 0.4 of the screw) at the ``fast`` fidelity serves the tests;
the port-flow runs beside it are the same engine through its gear's ports made 4, 16
and 64 times larger (``run_steady(portmap_scale=...)``), which tend to ideal ports.
"""

from __future__ import annotations

import copy
import dataclasses
import tomllib

import numpy as np
import pytest

from corliss.engine.steady import run_steady
from corliss.scene.loader import bundled_scenes, scene_from_dict
from corliss.thermo.steam import HEOSSteam
from corliss.thermo.wall_properties import film_enthalpies


def _scene(port_flow: bool):
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["meyer-cutoff"].read_text()))
    effects = [e for e in data["run"]["effects"] if e != "port_flow"] + ["wall_heat"]
    data["run"]["effects"] = effects + (["port_flow"] if port_flow else [])
    data["run"]["fidelity"] = "fast"
    return scene_from_dict(data, name="ideal-ports-wall")


@pytest.fixture(scope="module")
def ideal():
    r = run_steady(_scene(False))
    assert r.summary["cycles_to_converge"] is not None
    return r


#: The ideal-port stepping's grid [deg], at which the port-flow runs below are also
#: written out: the missing water is read at cut-off by interpolating the time series,
#: and across the kink of the end's mass there the fast preset's 2 deg output errs by
#: up to 0.005 of the steam (head end at 64 times the ports: 0.1007 from 2 deg, 0.0953
#: from 0.25 deg), as large as the gap to the ideal ports the tests measure.
OUTPUT_STEP_DEG = 0.25


@pytest.fixture(scope="module")
def ported():
    """The port-flow runs through the gear's ports made 4, 16 and 64 times larger,
    by scale (summaries)."""
    out = {}
    for scale in (4.0, 16.0, 64.0):
        sc = _scene(True)
        sc = sc.replace_run(fidelity=dataclasses.replace(sc.run.fidelity,
                                                         output_step_deg=OUTPUT_STEP_DEG))
        s = run_steady(sc, portmap_scale=scale).summary
        assert s["cycles_to_converge"] is not None
        out[scale] = s
    return out


def _last(r):
    ts = r.timeseries
    return ts[ts["cycle"] == ts["cycle"].max()]


def test_ideal_ports_with_the_wall_close_mass_and_energy_over_a_cycle(ideal):
    """Over the last cycle, steam and film in both ends change by what the chest gave
    and the exhaust took (the wall's steps move water between film and steam, never
    make or lose it): to 1e-9 of the steam supplied, the property solvers' tolerance.
    Their energy changes by the enthalpy through the ports, the wall's heat and the
    work, ``dU + h_L dm_f = H_supply + H_exhaust + Q - W`` (the film is water of
    enthalpy h_L), to 1e-6 of the enthalpy supplied: the work is the trapezoid of the
    pressure over steps of 0.25 deg, the ideal-port model's own error (1e-7 and 2e-7
    of each end's enthalpy in the same engine without the wall)."""
    r = ideal
    row = r.last_cycle
    last = _last(r)
    heos = HEOSSteam()
    dm = dU = dfilm = 0.0
    for end in ("head", "crank"):
        m = last[f"m_{end}_kg"].to_numpy()
        f = last[f"m_film_{end}_kg"].to_numpy()
        p = last[f"p_{end}_Pa"].to_numpy()
        x = last[f"x_{end}_frac"].to_numpy()
        T = last[f"T_{end}_K"].to_numpy()

        def u(k):
            return (heos.px(p[k], x[k]) if x[k] < 1.0 - 1e-9 else heos.pt(p[k], T[k])).u

        dm += m[-1] - m[0]
        dfilm += f[-1] - f[0]
        dU += m[-1] * u(-1) - m[0] * u(0)
    m_in = float(row["m_supply_kg"])
    assert abs(dm + dfilm - (m_in + float(row["m_exhaust_kg"]))) < 1e-9 * m_in
    h_L = film_enthalpies(0.5 * (r.chest.T + r.exhaust.T))[0]
    Q = float(row["Q_head_J"] + row["Q_crank_J"])
    H_in = float(row["H_supply_J"])
    rhs = H_in + float(row["H_exhaust_J"]) + Q - float(row["work_head_J"] + row["work_crank_J"])
    assert abs(dU + h_L * dfilm - rhs) < 1e-6 * H_in
    # and the summary's periodic balances hold to the fast preset's tolerance
    assert r.summary["energy_balance_error"] < 1e-3
    assert r.summary["mass_balance_error"] < 1e-3


def test_with_ideal_ports_the_wall_gives_heat_only_down_the_temperature_difference(ideal):
    """Second law at the wall: over every step of the converged cycle, the heat down
    T_w - T_sat (condensing on the wall, boiling off it) has the sign of T_w - T_sat,
    and the convected heat the sign of T_w - T, wherever the difference keeps its
    sign over the step (the surface is solved at the step's end, the steam's
    temperatures taken at its start, so where it changes sign the heat may go either
    way; 0.05 K, the temperature the table resolves)."""
    last = _last(ideal)
    heos = HEOSSteam()
    for end in ("head", "crank"):
        p = last[f"p_{end}_Pa"].to_numpy()
        T = last[f"T_{end}_K"].to_numpy()
        Tw = last[f"T_wall_{end}_K"].to_numpy()
        Tsat = np.array([heos.t_sat(v) for v in p])
        for col, diff in ((f"Q_sat_{end}_J", Tw - Tsat), (f"Q_conv_{end}_J", Tw - T)):
            dQ = np.diff(last[col].to_numpy())
            same = ((np.sign(diff[1:]) == np.sign(diff[:-1])) & (np.abs(diff[1:]) > 0.05)
                    & (np.abs(diff[:-1]) > 0.05))
            bad = same & (dQ * np.sign(diff[1:]) < 0.0)
            assert not bad.any(), (col, np.nonzero(bad)[0][:5])
            assert same.sum() > 0.5 * same.size      # the check saw most of the cycle
        assert last[f"m_film_{end}_kg"].min() >= 0.0


def test_ideal_ports_are_the_limit_of_ever_larger_ports(ideal, ported):
    """The ideal-port model is what the port-flow model tends to as the ports grow
    without bound (corliss.engine.equilibrium): through the gear's ports made 4, 16
    and 64 times larger, the missing water at cut-off of each end comes nearer the
    ideal ports', the largest gap of the two ends at 64 times under half its value at
    4 times and within 0.01 (head end 0.1059, 0.0981, 0.0954 against 0.0927; crank
    end 0.1383, 0.1311, 0.1287 against 0.1269: with larger ports the admission's
    wire-drawing, which lowers the pressure at cut-off and so the steam the card
    shows, shrinks slowly, as the square root of the area or slower)."""
    s_ideal = ideal.summary
    gaps = []
    for scale in (4.0, 16.0, 64.0):
        s = ported[scale]
        gaps.append([s[f"missing_water_fraction_{end}"] - s_ideal[f"missing_water_fraction_{end}"]
                     for end in ("head", "crank")])
    gaps = np.abs(np.array(gaps))
    assert gaps[-1].max() < 0.5 * gaps[0].max()
    assert gaps[-1].max() < 0.01


def test_the_walls_surface_and_heat_tend_to_the_ideal_ports(ideal, ported):
    """The wall's mean surface temperature and heat come nearer the ideal-port
    wall's as the ports grow (4 and 64 times), and at 64 times lie within 4 K and a
    fifth: head end 129.3, 131.5 degC against 132.1, its heat 13.37, 13.31 kJ against
    13.13; crank end 123.5, 124.7 against 125.0 degC, 12.80, 13.00 kJ against 13.09.
    The bands are those the test was written with (the old coefficient, 3e5 W/(m2 K),
    came within 1.5 K and 5 %); at 64 times the ports still wire-draw (the missing
    water's gap, above).  The two walls parted before (the head end's
    surface 1.3 K off at 4 times, 3.5 K at 64) because the ideal ports' blow-down at
    release swept the film once, after it, into the steam left behind, where the
    port-flow model sweeps it as the steam leaves and part of the water swept leaves
    with it (corliss.engine.equilibrium._blow_down_sweeping); and because the
    compiled balances swept on any fall of the end's mass, condensation on a closed
    end included, where the ideal-port wall sweeps on the port's outflow alone
    (corliss.engine.kernels.balances.sweep_films)."""
    s_ideal = ideal.summary
    runs = [ported[4.0], ported[64.0]]
    for end in ("head", "crank"):
        for key, within in ((f"wall_surface_mean_{end}_K", 4.0),
                            (f"heat_to_walls_{end}_J_per_cycle",
                             0.2 * s_ideal[f"heat_to_walls_{end}_J_per_cycle"])):
            far, near = (abs(r[key] - s_ideal[key]) for r in runs)
            assert near < far, (key, far, near)
            assert near < within, (key, near)


@pytest.mark.parametrize("supply,speed", [("saturated", "10 rpm"), ("wet", "600 rpm"),
                                          ("superheated", "120 rpm")])
def test_ideal_ports_carry_the_wall_at_every_speed_and_supply(supply, speed):
    """The bundled default engine with ideal ports and the skin wall, saturated at 10
    rpm (a step is 4 ms: the wall condenses more than the clearance holds within one,
    and the film runs off into the steam, so the chest's filling must take very wet
    contents), 5 % wet at 600 rpm and 250 degF superheated at 120 rpm: each settles,
    closes its balances to the fast preset's tolerance, keeps its film at nothing or
    more, and gives heat only down the temperature difference (as above)."""
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["default"].read_text()))
    data["run"]["effects"] = [e for e in data["run"]["effects"]
                              if e not in ("port_flow", "leakage", "steam_chest")] + ["wall_heat"]
    data["run"]["fidelity"] = "fast"
    data["run"]["speed"] = speed
    data["supply"].update({"saturated": {"temperature": "saturated"},
                           "wet": {"temperature": "saturated", "dryness": 0.95},
                           "superheated": {"temperature": "588 degF"}}[supply])
    r = run_steady(scene_from_dict(data, name="ideal-ports-wall"))
    s = r.summary
    assert s["cycles_to_converge"] is not None
    assert s["energy_balance_error"] < 1e-3 and s["mass_balance_error"] < 1e-3
    last = _last(r)
    heos = HEOSSteam()
    for end in ("head", "crank"):
        assert last[f"m_film_{end}_kg"].min() >= 0.0
        p = last[f"p_{end}_Pa"].to_numpy()
        Tw = last[f"T_wall_{end}_K"].to_numpy()
        Tsat = np.array([heos.t_sat(v) for v in p])
        for col, diff in ((f"Q_sat_{end}_J", Tw - Tsat),
                          (f"Q_conv_{end}_J", Tw - last[f"T_{end}_K"].to_numpy())):
            dQ = np.diff(last[col].to_numpy())
            same = ((np.sign(diff[1:]) == np.sign(diff[:-1])) & (np.abs(diff[1:]) > 0.05)
                    & (np.abs(diff[:-1]) > 0.05))
            assert not (same & (dQ * np.sign(diff[1:]) < 0.0)).any(), col


def test_a_conduction_grid_under_the_surface_changes_the_missing_water_little(ideal, monkeypatch):
    """The lumped surface node has the semi-infinite wall's impedance at the cycle's
    frequency only (corliss.engine.wall, Carslaw & Jaeger sec. 2.6); the 14-node
    conduction grid (wall.ConductionGrid) has it at every harmonic and answers the
    short events (the film boiling off at release, the first milliseconds of
    admission) through a thin layer.  The cycle's fundamental carries most of the
    swing, so the two give nearly the same missing water at cut-off: within 0.015 of
    the steam at each end (0.0074 and 0.0081 measured, the grid's lower; the rest of
    the band is the convergence tolerance of the fast preset, 1e-3 on the cycle, and
    margin), and the grid's run closes mass as the lumped one does."""
    from functools import partial

    from corliss.engine import steady, wall
    monkeypatch.setattr(steady, "IdealPortWall", partial(wall.IdealPortWall, grid_nodes=14))
    r = run_steady(_scene(False))
    assert r.summary["cycles_to_converge"] is not None
    for end in ("head", "crank"):
        key = f"missing_water_fraction_{end}"
        assert r.summary[key] == pytest.approx(ideal.summary[key], abs=0.015)
    row = r.last_cycle
    last = _last(r)
    dm = sum(last[f"m_{e}_kg"].to_numpy()[-1] - last[f"m_{e}_kg"].to_numpy()[0]
             + last[f"m_film_{e}_kg"].to_numpy()[-1] - last[f"m_film_{e}_kg"].to_numpy()[0]
             for e in ("head", "crank"))
    m_in = float(row["m_supply_kg"])
    assert abs(dm - (m_in + float(row["m_exhaust_kg"]))) < 1e-9 * m_in
