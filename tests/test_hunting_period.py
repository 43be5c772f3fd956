"""The hunting period and swing read from the crank-resolved governor position.

A slow engine's governor can hunt in less than two turns (the Corliss scene's hunt is
about one and a half); the turn-mean position samples that motion once a turn and
aliases it (Shannon's sampling theorem).  The detector reads the crank-resolved
position instead, less its ripple once a turn (the speed's fluctuation within the
turn, Marks Art. 62).
"""

import copy
import math
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import corliss
from corliss.engine.speed_metrics import hunting
from corliss.governors import governor_type

SCENE = Path(__file__).resolve().parents[1] / "scenes" / "corliss-governor.toml"
FIDELITY = "fast"       # the standard tier gives the same period (1.129 s) and swing

SPEED_RPM = 80.0
TURN_S = 60.0 / SPEED_RPM


def _synthetic(period_s, swing, ripple, turns=40, per_turn=360):
    """A governor hunting sinusoidally (period ``period_s``, peak-to-peak ``swing``)
    about 0.5, plus a ripple of amplitude ``ripple`` at once and twice a turn, sampled
    each degree at a steady 80 rpm; with its per-turn table (turn means)."""
    theta = np.arange(turns * per_turn) * (2 * math.pi / per_turn)
    t = theta / (2 * math.pi) * TURN_S
    z = (0.5 + 0.5 * swing * np.sin(2 * math.pi * t / period_s + 0.3)
         + ripple * np.sin(theta + 1.0) + 0.5 * ripple * np.cos(2 * theta))
    ts = pd.DataFrame({"time_s": t, "crank_angle_deg": np.degrees(theta),
                       "governor_z_frac": z})
    k = np.arange(turns)
    cycles = pd.DataFrame({"t_start_s": k * TURN_S, "t_end_s": (k + 1) * TURN_S,
                           "governor_z_frac": z.reshape(turns, per_turn).mean(axis=1)})
    return cycles, ts


def test_a_hunt_shorter_than_two_turns_is_read_at_its_own_period_and_swing():
    """A hunt of 1.1 s and 0.65 of the travel at 80 rpm (0.75 s a turn) with a ripple of
    0.02 once a turn.  Read from the crank angle: the period within 1 % (the crossings
    are interpolated between degree samples, and the window holds only about seven
    periods, so their spacing varies by a fraction of a sample), the swing within the
    0.005 (the ripple and the hunt are fitted together, so neither leaks into the
    other: what is left is the degree sampling of the peaks, 1e-4).  Read from the turn means it
    aliases: sampled at f_s = 1/0.75 s, a motion at f = 1/1.1 s shows at
    |f - f_s| = 0.424 Hz, a period of 2.36 s (the issue's 2.42 s), and each turn's
    mean shrinks the swing by sin(pi f T)/(pi f T) = 0.39 (T the turn)."""
    cycles, ts = _synthetic(1.1, 0.65, 0.02)
    h = hunting(cycles, 0.0, ts)
    assert h["hunting"] and h["hunting_read_from"] == "crank_angle"
    assert h["hunting_period_s"] == pytest.approx(1.1, rel=0.01)
    assert h["governor_swing_frac"] == pytest.approx(0.65, abs=0.005)
    means = hunting(cycles, 0.0)
    assert means["hunting_read_from"] == "turn_means"
    f, fs = 1 / 1.1, 1 / TURN_S
    assert means["hunting_period_s"] == pytest.approx(1 / abs(f - fs), rel=0.05)
    x = math.pi * f * TURN_S
    assert means["governor_swing_frac"] == pytest.approx(0.65 * math.sin(x) / x, rel=0.1)


def test_the_ripple_alone_is_no_hunt():
    """A governor steady but for a ripple of 0.05 once and twice a turn (more than the
    1 % of travel that counts as a swing) does not hunt: the ripple is periodic in the
    crank angle and the fit takes it off (what is left is rounding)."""
    cycles, ts = _synthetic(1.1, 0.0, 0.05)
    h = hunting(cycles, 0.0, ts)
    assert not h["hunting"] and h["hunting_period_s"] is None
    assert h["governor_swing_frac"] < 1e-6


def test_a_decaying_swing_is_no_hunt():
    """The same motion dying away with a time constant of 3 s (the window's second half
    swings at about a third of its first half's, below the 70 % that counts as
    sustained) is not hunting."""
    cycles, ts = _synthetic(1.1, 0.65, 0.02)
    ts["governor_z_frac"] = 0.5 + (ts["governor_z_frac"] - 0.5) * np.exp(-ts["time_s"] / 3.0)
    assert not hunting(cycles, 0.0, ts)["hunting"]


def _scene_dict():
    return tomllib.loads(SCENE.read_text())


def _steady_torque(d0, setting, rpm):
    """Mean indicated torque [N m] of the scene's engine at a gear setting and speed."""
    d = copy.deepcopy(d0)
    for k in ("governor", "flywheel", "load"):
        d.pop(k)
    d["valve_gear"]["setting"] = setting
    d["run"] = {"mode": "steady", "speed": f"{rpm} rpm", "effects": d0["run"]["effects"],
                "fidelity": FIDELITY}
    s = corliss.simulate(corliss.scene_from_dict(d, "s")).summary
    return s["indicated_power_W"] / (rpm * math.pi / 30.0)


@pytest.fixture(scope="module")
def corliss_loop():
    """The Corliss scene's speed loop linearised about its state after the step (60 %
    of the load), as tests/test_governed_loop.py does for a shaft governor.

    Flywheel:  I dw/dt = K_z dz - D dw, with K_z = dT/dz through the gear setting
    (a0 + (a1 - a0) z) and D = dT_f/dw - dT/dw.  The trip gear makes D negative: the
    dash-pot closes the valve in a time of its own, so a faster engine cuts off later
    and makes more torque.
    Governor:  M z'' + c z' + k_g dz = b dw, k_g = R' - G' w_g^2, b = 2 G w_g ratio.
    Characteristic polynomial (q = -b K_z):

        I M s^3 + (I c + D M) s^2 + (I k_g + D c) s + (D k_g + q) = 0

    Routh-Hurwitz: stable iff (I c + D M)(I k_g + D c) > I M (D k_g + q), a quadratic
    in c whose positive root is the critical dash-pot c*.  Below it a pair of roots
    s = sigma +- i w has sigma > 0: the hunt, at the period 2 pi / w.  The
    equilibrium: the setting whose torque carries 60 % of the load and the friction,
    at the speed the governor's characteristic gives for it (79.76 rpm).  K_z and D
    from steady runs of the same engine; M, G, R from the governor's mechanism.
    Measured: c* = 1.43 lbf s/ft at the sleeve; at 0.8 c*, sigma = 0.10 /s and
    2 pi / w = 1.087 s (the issue's 1.107 s from its own linearisation).
    """
    d0 = _scene_dict()
    sc = corliss.scene_from_dict(copy.deepcopy(d0), "c")
    gov = governor_type(sc.governor_type).build(sc.governor)
    m = gov.mechanism(401)
    a0, a1 = m.actuator_at_rest, m.actuator_at_top
    t_need = float(sc.load.fraction(1e3)) * sc.load.torque_N_m + sc.engine.friction_torque_N_m
    zs = np.linspace(0.2, 0.9, 8)
    rpm = sc.run.speed_rpm
    for _ in range(2):      # the equilibrium's speed from its setting, and again
        torque = np.array([_steady_torque(d0, a0 + (a1 - a0) * z, rpm) for z in zs])
        z0 = float(np.interp(-t_need, -torque, zs))
        rpm = float(gov.equilibrium_speed_rad_s(z0)) * 30.0 / math.pi
    w0 = rpm * math.pi / 30.0
    p = np.polyfit(zs, torque, 2)
    k_z = float(2 * p[0] * z0 + p[1])
    s0 = a0 + (a1 - a0) * z0
    dT_dw = (_steady_torque(d0, s0, rpm * 1.03) - _steady_torque(d0, s0, rpm * 0.97)) / (0.06 * w0)
    D = sc.engine.friction_N_m_s - dT_dw
    wg = m.ratio * w0
    M = float(np.interp(z0, m.z, m.M))
    G = float(np.interp(z0, m.z, m.G))
    k_g = float(np.interp(z0, m.z, np.gradient(m.R, m.z) - np.gradient(m.G, m.z) * wg ** 2))
    q = -2.0 * G * wg * m.ratio * k_z
    I = sc.flywheel.inertia_kg_m2
    A, B, C = I * D, I * I * k_g + D * D * M, D * M * I * k_g - I * M * (D * k_g + q)
    c_star = (-B + math.sqrt(B * B - 4 * A * C)) / (2 * A)
    d1 = copy.deepcopy(d0)
    d1["governor"]["dashpot"] = "1 lbf s/ft"
    s1 = corliss.scene_from_dict(d1, "c1")
    unit = governor_type(s1.governor_type).build(s1.governor).mechanism(11).c  # c per lbf s/ft
    roots = np.roots([I * M, I * 0.8 * c_star + D * M, I * k_g + D * 0.8 * c_star, D * k_g + q])
    pair = max(roots, key=lambda r: r.imag)
    return {"c_star_lbf_s_ft": c_star / unit, "sigma": pair.real,
            "period_s": 2.0 * math.pi / pair.imag, "scene": d0}


def _run(d0, dashpot_lbf_s_ft, friction):
    d = copy.deepcopy(d0)
    d["governor"].update(dashpot=f"{dashpot_lbf_s_ft} lbf s/ft", friction=friction)
    d["run"]["fidelity"] = FIDELITY
    return corliss.simulate(corliss.scene_from_dict(d, "hunt"))


def test_the_corliss_hunt_at_0_8_of_the_critical_dashpot_is_read_at_its_period(corliss_loop):
    """At 0.8 c* the linear loop is unstable (sigma > 0) with a period of 1.087 s; the
    run, without the sleeve's friction (which the linear analysis leaves out), hunts,
    and the detector reads a period within 5 % of it and of the issue's 1.1 s (the
    hunt is of finite size, 0.27 of the travel, where the gear's torque slope and the
    governor's stiffness are not those at the equilibrium, and the engine changes its
    torque only at each cut-off: measured 1.129 s, 3.9 % above the analysis).  Its
    swing is the position's own: the raw crank-resolved position's peak-to-peak over
    the window, within the ripple taken off it (0.02 of travel peak to peak, measured
    on the settled run below, which can add to a peak or take from it) and 0.01 more
    (measured: 0.275 against 0.272 raw); the turn means, sampled once in 0.75 s, alias the same motion
    to about twice its period and under half its swing."""
    lin = corliss_loop
    assert lin["c_star_lbf_s_ft"] == pytest.approx(1.43, rel=0.05)
    assert lin["sigma"] > 0.0
    assert lin["period_s"] == pytest.approx(1.1, rel=0.05)
    r = _run(lin["scene"], 0.8 * lin["c_star_lbf_s_ft"], "0 lbf")
    s = r.summary
    assert s["hunting"] and s["hunting_read_from"] == "crank_angle"
    assert s["hunting_period_s"] == pytest.approx(lin["period_s"], rel=0.05)
    assert s["hunting_period_s"] == pytest.approx(1.1, rel=0.05)
    ts = r.timeseries
    start = r.cycles["t_start_s"].to_numpy()
    late = ts["time_s"].to_numpy() >= start[start <= 0.5 * (8.0 + start[-1])][-1]
    raw = float(np.ptp(ts["governor_z_frac"].to_numpy()[late]))
    assert s["governor_swing_frac"] == pytest.approx(raw, abs=0.03)
    means = hunting(r.cycles, 8.0)
    assert means["hunting_period_s"] > 1.8 * s["hunting_period_s"]
    assert means["governor_swing_frac"] < 0.5 * s["governor_swing_frac"]


def test_with_the_scenes_sleeve_friction_the_same_dashpot_settles_and_its_ripple_is_no_hunt(
        corliss_loop):
    """With the scene's 0.1 lbf at the sleeve the same 0.8 c* settles: Coulomb friction
    holds the sleeve once the swing is small (a linearly unstable loop held by
    friction, which the linear analysis leaves out).  The governor still follows the
    speed's fluctuation within each turn, about 0.02 of its travel; the detector takes
    that ripple off and reads no swing (under 0.005) and no hunt."""
    r = _run(corliss_loop["scene"], 0.8 * corliss_loop["c_star_lbf_s_ft"], "0.1 lbf")
    s = r.summary
    ts = r.timeseries
    late = ts["time_s"].to_numpy() >= 20.0
    assert float(np.ptp(ts["governor_z_frac"].to_numpy()[late])) > 0.01   # the ripple
    assert not s["hunting"] and s["governor_swing_frac"] < 0.005
