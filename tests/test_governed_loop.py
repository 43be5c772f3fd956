"""The closed speed loop against a linearised analysis of the same loop, and against
Marks's rules: a governor pumps when the loop is too lightly damped (Art. 97); a load
thrown off is caught with a bounded overspeed (Art. 70: the engine must go fast to go
slow, so it settles at a higher speed)."""

import copy
import math

import numpy as np
import pytest

import corliss
from corliss.engine.options import record_of
from corliss.governors import governor_type

# A 9 x 10 in high-speed engine with a shaft-governed eccentric (straight path, as the
# Erie, Spangler Art. 88), its setting moved by a Porter governor on a belt (Marks
# Art. 97, Fig. 59): a Porter-Allen-like arrangement, chosen because a belted
# fly-ball governor is slow enough against the strokes (several strokes to each of its
# swings) for the continuous linear analysis to hold.
ENGINE = {
    "title": "loop test engine",
    "engine": {"bore": "9 in", "stroke": "10 in", "connecting_rod": "25 in",
               "piston_rod_diameter": "1.5 in", "clearance": 0.1,
               "friction_torque": "15 lbf ft"},
    "supply": {"pressure": "90 psig", "temperature": "saturated", "barometer": "14.696 psia"},
    "exhaust": {"pressure": "1 psig"},
    "valve_gear": {"type": "shaft_governor", "path": "straight", "eccentricity": "1.75 in",
                   "angular_advance": "22 deg", "centre_travel": "1.7 in", "setting": 0.5,
                   "lap": "0.5 in", "exhaust_lap": "-0.0625 in", "port_width": "0.75 in",
                   "port_length": "10 in", "discharge_coefficient": 0.75},
    "output": {"units": "US", "dir": "out"},
}
EFFECTS = ["port_flow", "rod_angularity", "friction"]
GOVERNOR = {"type": "porter_allen", "arm_length": "8 in", "ball_mass": "4 lb", "balls": 2,
            "load_mass": "30 lb", "arm_angle_at_rest": "30 deg", "arm_angle_at_top": "45 deg",
            "ratio": 0.78, "friction": "0 lbf", "setting_at_rest": 0.4, "setting_at_top": 1.0}
SPEED_RPM = 280.0
LOAD_HP = 35.0


def scene(dashpot_lbf_s_ft: float, rim_lb: float, duration: str = "10 s", step=None):
    d = copy.deepcopy(ENGINE)
    d["governor"] = {**GOVERNOR, "dashpot": f"{dashpot_lbf_s_ft} lbf s/ft"}
    d["flywheel"] = {"rim_weight": f"{rim_lb} lb", "mean_radius": "20 in"}
    d["load"] = {"power": f"{LOAD_HP} hp"}
    if step is not None:
        d["load"].update(kind="step", step_time=step[0], step_fraction=step[1])
    d["run"] = {"mode": "transient", "speed": f"{SPEED_RPM} rpm", "duration": duration,
                "effects": EFFECTS, "fidelity": "standard", "record": "cycle"}
    return corliss.scene_from_dict(d, "loop")


def steady_torque(setting: float, rpm: float) -> float:
    """Mean indicated torque [N m] at a gear setting and speed, from a steady run."""
    d = copy.deepcopy(ENGINE)
    d["valve_gear"]["setting"] = setting
    d["run"] = {"mode": "steady", "speed": f"{rpm} rpm", "effects": EFFECTS,
                "fidelity": "standard"}
    s = corliss.simulate(corliss.scene_from_dict(d, "s")).summary
    return s["indicated_power_W"] / (rpm * math.pi / 30.0)


@pytest.fixture(scope="module")
def linear():
    """The loop linearised about its loaded equilibrium.

    Flywheel:  I dw/dt = K_z dz - D dw, with K_z = dT_gas/dz (through the gear setting,
    a0 + (a1 - a0) z) and D = dT_f/dw - dT_gas/dw (friction and the engine's own
    falling torque with speed; the load is a constant torque).
    Governor:  M z'' + c z' + k_g dz = b dw, with k_g = R' - G' w_g^2 the effective
    stiffness and b = 2 G w_g ratio the speed sensitivity, all at the equilibrium.
    Characteristic polynomial (q = -b K_z > 0):

        I M s^3 + (I c + D M) s^2 + (I k_g + D c) s + (D k_g + q) = 0

    Routh-Hurwitz: stable if and only if (I c + D M)(I k_g + D c) > I M (D k_g + q),
    a quadratic in c whose positive root is the critical dash-pot c*.  K_z and D are
    measured from steady runs of the same model; M, G, R from the governor's mechanism.
    """
    sc = scene(0.0, 300.0)
    gov = governor_type(sc.governor_type).build(sc.governor)
    m = gov.mechanism(401)
    w0 = SPEED_RPM * math.pi / 30.0
    a0, a1 = m.actuator_at_rest, m.actuator_at_top
    zs = np.linspace(0.3, 0.9, 7)
    torque = np.array([steady_torque(a0 + (a1 - a0) * z, SPEED_RPM) for z in zs])
    t_need = sc.load.torque_N_m + sc.engine.friction_torque_N_m
    z0 = float(np.interp(-t_need, -torque, zs))
    k_z = float(np.polyfit(zs, torque, 2)[0] * 2 * z0 + np.polyfit(zs, torque, 2)[1])
    s0 = a0 + (a1 - a0) * z0
    dT_dw = (steady_torque(s0, SPEED_RPM * 1.03) - steady_torque(s0, SPEED_RPM * 0.97)) / (0.06 * w0)
    D = sc.engine.friction_N_m_s - dT_dw
    wg = m.ratio * w0
    M = float(np.interp(z0, m.z, m.M))
    G = float(np.interp(z0, m.z, m.G))
    k_g = float(np.interp(z0, m.z, np.gradient(m.R, m.z) - np.gradient(m.G, m.z) * wg ** 2))
    b = 2.0 * G * wg * m.ratio
    q = -b * k_z
    return {"M": M, "k_g": k_g, "q": q, "D": D, "z0": z0, "k_z": k_z}


def critical_c(lin, inertia):
    """Positive root in c of (I c + D M)(I k + D c) - I M (D k + q) = 0."""
    I, M, k, q, D = inertia, lin["M"], lin["k_g"], lin["q"], lin["D"]
    A, B, C = I * D, I * I * k + D * D * M, D * M * I * k - I * M * (D * k + q)
    return (-B + math.sqrt(B * B - 4 * A * C)) / (2 * A)


def generalised_c(dashpot_lbf_s_ft):
    """The scene's sleeve dash-pot as the mechanism's generalised c."""
    sc = scene(dashpot_lbf_s_ft, 300.0)
    return governor_type(sc.governor_type).build(sc.governor).mechanism(11).c


def roots(lin, inertia, c):
    """Roots of the linearised loop's characteristic polynomial."""
    I, M, k, q, D = inertia, lin["M"], lin["k_g"], lin["q"], lin["D"]
    return np.roots([I * M, I * c + D * M, I * k + D * c, D * k + q])


def test_the_loop_hunts_below_the_linear_stability_boundary_and_settles_above(linear):
    """One flywheel (a 1500 lb rim), two dash-pots.  Below the critical dash-pot c* of
    the analysis (0.3 c*) the governor pumps: a sustained swing at the end of the run.
    At 3 c*, where the analysis's slowest pair of roots is damped (damping ratio above
    0.15), the same load step settles with no hunting.  (A factor 3 on each side: the
    engine changes its torque only at each cut-off, a sampling the continuous analysis
    leaves out, which moves the real boundary somewhat.)  The hunting period agrees
    with the analysis's frequency at the boundary, sqrt((I k + D c*)/(I M)), within
    30 %."""
    rim = 1500.0
    I = scene(0.0, rim).flywheel.inertia_kg_m2
    c_star = critical_c(linear, I)
    unit = generalised_c(1.0)                  # generalised c per lbf s/ft at the sleeve
    assert c_star > 0.0
    assert max(r.real for r in roots(linear, I, 0.3 * c_star)) > 0.0
    damped = roots(linear, I, 3.0 * c_star)
    assert min(-r.real / abs(r) for r in damped) > 0.15
    low = corliss.simulate(scene(0.3 * c_star / unit, rim, "16 s", ("5 s", 0.8))).summary
    high = corliss.simulate(scene(3.0 * c_star / unit, rim, "16 s", ("5 s", 0.8))).summary
    assert low["hunting"], low
    assert not high["hunting"], high
    assert high["settling_time_s"] is not None and high["settling_time_s"] < 5.0
    w_b = math.sqrt((I * linear["k_g"] + linear["D"] * c_star) / (I * linear["M"]))
    assert low["hunting_period_s"] == pytest.approx(2 * math.pi / w_b, rel=0.3)


def test_full_load_rejection_keeps_the_overspeed_bounded_and_settles(linear):
    """All the load thrown off at 2 s.  The governor shortens the cut-off toward its top
    stop; the speed rises by no more than the governor's range allows the engine to
    keep accelerating (bounded by the speed at the top stop plus the overshoot), then
    settles above the speed before (Marks Art. 70: it must go fast to go slow), within
    the droop of the static characteristic."""
    rim = 1500.0
    c = 3.0 * critical_c(linear, scene(0.0, rim).flywheel.inertia_kg_m2)
    # 25 s after the step: the speed must have settled (to 0.02 %) before a settling
    # time or a regulation is reported
    sc = scene(c / generalised_c(1.0), rim, "30 s", ("5 s", 0.0))
    r = corliss.simulate(sc)
    s = r.summary
    gov = governor_type(sc.governor_type).build(sc.governor)
    w_top = float(gov.equilibrium_speed_rad_s(1.0)) * 30 / math.pi
    assert not s["stalled"]
    assert s["max_deviation_frac"] > 0
    assert s["speed_before_rpm"] + s["max_deviation_rpm"] < 1.25 * w_top
    assert s["settling_time_s"] is not None and s["settling_time_s"] < 8.0
    assert not s["hunting"]
    assert s["final_speed_rpm"] > s["speed_before_rpm"]
    assert s["regulation_frac"] < gov.droop() + 0.01


def test_a_long_run_records_once_a_turn_unless_the_scene_says_otherwise():
    """By default the time series holds every output degree for a duration of up to 300
    turns and one row a turn beyond (the summary says which); a scene's own ``record``
    is kept whatever the length."""
    long = scene(20.0, 400.0, duration="66 s").replace_run(record=None).with_fidelity("fast")
    assert 66.0 * SPEED_RPM / 60.0 > 300
    r = corliss.simulate(long)
    assert r.summary["record"] == "cycle"
    assert len(r.timeseries) == len(r.cycles) == r.summary["turns"] > 300
    short = scene(20.0, 400.0, duration="1 s").replace_run(record=None)
    r = corliss.simulate(short)
    assert r.summary["record"] == "degree"
    assert len(r.timeseries) == 360 * len(r.cycles)
    d = copy.deepcopy(ENGINE)
    d.update(governor={**GOVERNOR, "dashpot": "20 lbf s/ft"},
             flywheel={"rim_weight": "400 lb", "mean_radius": "20 in"},
             load={"power": f"{LOAD_HP} hp"},
             run={"mode": "transient", "speed": f"{SPEED_RPM} rpm", "duration": "66 s",
                  "effects": EFFECTS, "record": "degree"})
    assert record_of(corliss.scene_from_dict(d, "explicit").run) == "degree"
    del d["run"]["record"]
    assert record_of(corliss.scene_from_dict(d, "default").run) == "cycle"
