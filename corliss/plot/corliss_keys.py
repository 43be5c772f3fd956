"""The Corliss gear's keys sketched from a gear's own geometry (Spangler Arts. 155-157).

Three panels, each lettered as the book letters Fig. 107 and each dimension named by its
scene key: the eccentric and the wrist plate at the plate's mid position (the hook rod
drawn shortened, its length written on it), and the steam and exhaust valve chains of the
head end (a four-bar chain: plate centre o, stud j, valve rod, spindle arm, spindle q;
the crank end's chains are their mirror images).  Every length and angle is the gear's,
drawn to scale; the angles' arcs carry an arrow in their positive sense.
"""

from __future__ import annotations

import math

import numpy as np

from corliss.keys import units


def _arc(ax, centre, radius, a0, a1, label, color="0.25", text_r=1.25, **text):
    """An angle's arc from ``a0`` to ``a1`` [rad] about ``centre``, arrow at ``a1`` (the
    positive sense of the key when ``a1`` is the key's end), and its label."""
    t = np.linspace(a0, a1, 40)
    x, y = centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t)
    ax.plot(x[:-1], y[:-1], color=color, lw=0.8)
    ax.annotate("", (x[-1], y[-1]), (x[-3], y[-3]),
                arrowprops=dict(arrowstyle="-|>", color=color, lw=0.8, mutation_scale=8))
    mid = 0.5 * (a0 + a1)
    return ax.text(centre[0] + text_r * radius * math.cos(mid),
                   centre[1] + text_r * radius * math.sin(mid), label, fontsize=7,
                   color=color, ha="center", va="center", **text)


def _chain(ax, chain, u: str, kind: str, lap_text: str) -> dict:
    """One valve chain at the plate's mid position, in its own frame (o at the origin,
    q on the x axis), its keys named on it."""
    U = lambda v: float(units.to_unit(v, u))  # noqa: E731
    rho, a0 = U(chain.stud_radius_m), chain.stud_angle_rad
    arm, g0 = U(chain.arm_m), chain.arm_angle_rad
    D, Rv = U(chain.spindle_distance_m), U(chain.valve_radius_m)
    j = (rho * math.cos(a0), rho * math.sin(a0))
    q = (D, 0.0)
    l_ = (D - arm * math.cos(g0), arm * math.sin(g0))
    lines = {}
    lines["line of centres"] = ax.plot([0, D], [0, 0], color="0.6", lw=0.7, ls="-.")[0]
    lines["stud"] = ax.plot([0, j[0]], [0, j[1]], color="k", lw=2.0)[0]
    lines["rod"] = ax.plot([j[0], l_[0]], [j[1], l_[1]], color="k", lw=1.2)[0]
    lines["arm"] = ax.plot([q[0], l_[0]], [q[1], l_[1]], color="k", lw=2.0)[0]
    t = np.linspace(0, 2 * math.pi, 181)
    lines["valve face"] = ax.plot(D + Rv * np.cos(t), Rv * np.sin(t), color="0.35", lw=1.0)[0]
    ax.plot([0, D, j[0], l_[0]], [0, 0, j[1], l_[1]], "o", color="k", ms=3.5, mfc="white")
    letter = dict(fontsize=9, fontstyle="italic", family="serif")
    ax.text(0.0, -0.03 * D, "o", ha="center", va="top", **letter)
    ax.text(D + 0.03 * D, -0.03 * D, "q", ha="left", va="top", **letter)
    ax.text(j[0] + 0.02 * D, j[1], "j", ha="left", va="bottom", **letter)
    ax.text(l_[0] - 0.02 * D, l_[1], "l", ha="right", va="center", **letter)
    k = f"{kind}_"
    h = 0.025 * D                      # a text's clearance from its line [units]
    ax.text(0.5 * j[0] - h, 0.5 * j[1] + h, f"{k}stud_radius = {rho:.3g} {u}",
            fontsize=7, ha="right", va="bottom")
    _arc(ax, (0.0, 0.0), 0.6 * rho, 0.0, a0, "", text_r=1.0)
    ax.text(0.65 * rho, 0.3 * rho * math.sin(a0), f"  {k}stud_angle = "
            f"{math.degrees(a0):.3g}\N{DEGREE SIGN} (+ towards j)", fontsize=7, ha="left",
            va="center")
    # the arm's angle counts from q -> o (angle pi in this frame), the same side as j
    _arc(ax, q, 0.6 * arm, math.pi, math.pi - g0, "", text_r=1.0)
    side = 1.0 if g0 >= 0 else -1.0
    # the arm's angle and length named under (or over) the arm, led to it
    ax.annotate(f"{k}arm_angle = {math.degrees(g0):.3g}\N{DEGREE SIGN} "
                f"(from q\N{RIGHTWARDS ARROW}o, + on j's side)",
                (q[0] + 0.6 * arm * math.cos(math.pi - 0.5 * g0),
                 0.6 * arm * math.sin(math.pi - 0.5 * g0)),
                (q[0] - 0.5 * arm, side * 2.6 * arm), fontsize=7, ha="left",
                va="bottom" if side > 0 else "top",
                arrowprops=dict(arrowstyle="-", color="0.5", lw=0.5))
    ax.annotate(f"{k}arm = {arm:.3g} {u}", (0.5 * (q[0] + l_[0]), 0.5 * (q[1] + l_[1])),
                (q[0] + Rv + 2 * h, side * 1.6 * arm), fontsize=7, ha="left",
                va="bottom" if side > 0 else "top",
                arrowprops=dict(arrowstyle="-", color="0.5", lw=0.5))
    ax.text(0.75 * j[0] + 0.25 * l_[0], 0.75 * j[1] + 0.25 * l_[1] + h,
            "valve rod (its length set at mid position)", fontsize=6.5, color="0.3",
            ha="left", va="bottom")
    y = -max(Rv, 2.6 * arm, 0.2 * D) - 4 * h
    ax.plot([0, D], [y, y], color="0.3", lw=0.7, marker="|", ms=8)
    ax.text(0.5 * D, y - h, f"{k}spindle_distance = {D:.3g} {u}", fontsize=7,
            ha="center", va="top")
    ax.plot([D, D + Rv * math.cos(0.6)], [0, Rv * math.sin(0.6)], color="0.35", lw=0.7)
    ax.text(D + Rv + h, 0.0, f"{k}valve_radius = {Rv:.3g} {u}\n{lap_text}",
            fontsize=7, ha="left", va="center")
    ax.set_aspect("equal")
    ax.axis("off")
    return lines


def plot_corliss_keys(gear, fig=None, units_system: str = "US") -> dict:
    """The Corliss gear's scene keys, sketched from its geometry at mid position.

    Above, the eccentric (throw ``eccentricity`` at ``angular_advance`` beyond the
    perpendicular to the crank, the crank on head-end dead centre), the hook rod
    (``hook_rod``, drawn shortened) and the wrist plate (``wrist_plate_radius`` to the
    hook pin f about its centre o); below it, the head end's steam and exhaust
    chains (``*_stud_radius``, ``*_stud_angle``, ``*_arm``, ``*_arm_angle``,
    ``*_spindle_distance``, ``*_valve_radius``).  Angles are drawn from their zero
    line with an arrow in their positive sense: a stud's from o -> q the way the plate
    turns to open that valve, an arm's from q -> o on the same side.

    Parameters
    ----------
    gear : CorlissGear
        The gear (its ``spec``; the sketch is to its scale).
    fig : matplotlib.figure.Figure, optional
        Drawn on (three panels, one above another); a new 11 x 13 in figure when None.
    units_system : str, optional
        ``"US"`` (inches) or ``"SI"`` (mm).

    Returns
    -------
    dict
        ``{"figure": fig, "axes": [plate, steam, exhaust], "lines": {...}}``: the drawn
        stud, arm and rod of each chain (``lines["steam"]["stud"]``, ...), and the
        eccentric, hook rod and plate arm (``lines["plate"]``), each in [in] or [mm].
    """
    if fig is None:
        import matplotlib.pyplot as plt
        fig = plt.figure(figsize=(11, 13))
    s = gear.spec
    u = "in" if units_system == "US" else "mm"
    U = lambda v: float(units.to_unit(v, u))  # noqa: E731
    ax0, ax1, ax2 = (fig.add_subplot(3, 1, k) for k in (1, 2, 3))
    r, R, g, delta = U(s.eccentricity_m), U(s.wrist_plate_radius_m), U(s.hook_rod_m), \
        s.angular_advance_rad
    # the hook rod shortened to a few plate radii, its true length written on it
    shown = 2.6 * (r + R)
    ecc = (r * math.sin(delta), r * math.cos(delta))
    o = (ecc[0] + shown, R)
    f = (o[0], 0.0)
    plate = {}
    t = np.linspace(0, 2 * math.pi, 181)
    ax0.plot(r * np.cos(t), r * np.sin(t), color="0.6", lw=0.7, ls=":")
    plate["eccentric"] = ax0.plot([0, ecc[0]], [0, ecc[1]], color="k", lw=2.0)[0]
    ax0.plot([0, 0], [0, 1.15 * r], color="0.6", lw=0.7, ls="-.")
    ax0.plot([-1.2 * r, o[0] + 1.3 * R], [0, 0], color="0.75", lw=0.6, ls="-.")
    plate["hook rod"] = ax0.plot([ecc[0], f[0]], [ecc[1], f[1]], color="k", lw=1.2)[0]
    mid = (0.5 * (ecc[0] + f[0]), 0.5 * (ecc[1] + f[1]))
    ax0.plot([mid[0] - 0.05 * R, mid[0] + 0.05 * R], [mid[1] - 0.12 * R, mid[1] + 0.12 * R],
             color="k", lw=0.8)
    ax0.text(mid[0], mid[1] + 0.15 * R, f"hook_rod = {g:.4g} {u}\n(drawn shortened)",
             fontsize=7, ha="center", va="bottom")
    ax0.plot(o[0] + R * np.cos(t), o[1] + R * np.sin(t), color="0.35", lw=1.0)
    plate["plate arm"] = ax0.plot([o[0], f[0]], [o[1], f[1]], color="k", lw=2.0)[0]
    ax0.plot([0, ecc[0], o[0], f[0]], [0, ecc[1], o[1], f[1]], "o", color="k", ms=3.5,
             mfc="white")
    ax0.text(0.0, -0.15 * r, "shaft", fontsize=7, ha="center", va="top")
    letter = dict(fontsize=9, fontstyle="italic", family="serif")
    ax0.text(o[0] - 0.06 * R, o[1] + 0.06 * R, "o", ha="right", **letter)
    ax0.text(f[0] + 0.06 * R, f[1] - 0.06 * R, "f", va="top", **letter)
    ax0.text(o[0] + 0.1 * R, 0.5 * R, f"wrist_plate_radius\n= {R:.3g} {u}", fontsize=7,
             ha="left", va="center")
    ax0.annotate(f"eccentricity = {r:.3g} {u}", (0.5 * ecc[0], 0.5 * ecc[1]),
                 (-1.3 * r, 0.9 * r), fontsize=7, ha="right", va="center",
                 arrowprops=dict(arrowstyle="-", color="0.5", lw=0.5))
    _arc(ax0, (0.0, 0.0), 0.75 * r, 0.5 * math.pi, 0.5 * math.pi - delta, "")
    mid_a = 0.5 * math.pi - 0.5 * delta
    ax0.annotate(f"angular_advance = {math.degrees(delta):.3g}\N{DEGREE SIGN}\n"
                 "(+ ahead, the way the crank turns)",
                 (0.75 * r * math.cos(mid_a), 0.75 * r * math.sin(mid_a)), (-1.3 * r, 1.9 * r),
                 fontsize=7, ha="right", va="center",
                 arrowprops=dict(arrowstyle="-", color="0.5", lw=0.5))
    ax0.text(-1.2 * r, -0.6 * r, "the crank on head-end dead centre, turning "
             "counter-clockwise;\nthe eccentric 90 deg + angular_advance ahead of it",
             fontsize=6.5, color="0.3", ha="left", va="top")
    ax0.set_aspect("equal")
    ax0.axis("off")
    ax0.set_title("Eccentric, hook rod and wrist plate at mid position", fontsize=9)
    lap = lambda v: U(v)  # noqa: E731
    steam = _chain(ax1, s.steam, u, "steam",
                   f"steam_lap = {lap(s.steam_lap_m[0]):.3g} {u}\n"
                   f"steam_port_width = {lap(s.steam_port_width_m):.3g} {u} (arcs on the face)")
    ax1.set_title("Head-end steam valve's chain (the plate turns + to open it)", fontsize=9)
    exhaust = _chain(ax2, s.exhaust, u, "exhaust",
                     f"exhaust_lap = {lap(s.exhaust_lap_m[0]):.3g} {u}\n"
                     f"exhaust_port_width = {lap(s.exhaust_port_width_m):.3g} {u} "
                     "(arcs on the face)")
    ax2.set_title("Head-end exhaust valve's chain (the crank end's mirror these)", fontsize=9)
    return {"figure": fig, "axes": [ax0, ax1, ax2],
            "lines": {"plate": plate, "steam": steam, "exhaust": exhaust}}
