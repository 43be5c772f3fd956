"""Events on the polar valve diagrams: where a valve circle meets the lap circles
(Spangler Arts. 12-17), and the crank lines through them, numbered as Spangler numbers
them and named in the legend, for the Zeuner and Bilgram diagrams and the Porter-Allen
gear's diagram of its steam motion."""

from __future__ import annotations

import numpy as np

from corliss.plot.labels import merge_rays, ray_labels

#: (end, event, signed level x = L of the valve's displacement as a function of the
#: steam and exhaust laps (head, crank), whether x rises through it there): the opening
#: of each port is zero where x = L (Spangler Art. 15).
POLAR_EVENTS = (
    ("head", "admission", lambda l, e: l[0], True),
    ("head", "cutoff", lambda l, e: l[0], False),
    ("head", "release", lambda l, e: -e[0], False),
    ("head", "compression", lambda l, e: -e[0], True),
    ("crank", "admission", lambda l, e: -l[1], False),
    ("crank", "cutoff", lambda l, e: -l[1], True),
    ("crank", "release", lambda l, e: e[1], True),
    ("crank", "compression", lambda l, e: e[1], False),
)


#: The events' names in the diagrams' labels.
EVENT_WORDS = {"admission": "admission", "cutoff": "cut-off", "release": "release",
               "compression": "compression"}


def polar_events(travel, laps, exhaust_laps=None, idle: str | None = None) -> dict:
    """The events where a valve circle (the polar of a displacement) meets lap circles.

    Parameters
    ----------
    travel : callable
        Crank angle [rad] (array) -> the displacement x [m] in the sense that opens the
        head steam port.
    laps : (float, float)
        Steam laps (head, crank) [m], as the displacement sees them.
    exhaust_laps : (float, float) or None, optional
        Exhaust laps (head, crank) [m]; None for a diagram of the steam motion alone
        (release and compression are then None).
    idle : str or None, optional
        An end with no events (a single-acting cylinder's idle end).

    Returns
    -------
    dict
        As :func:`zeuner_events`.
    """
    from scipy.optimize import brentq

    th = np.linspace(0.0, 2.0 * np.pi, 7201)
    x = np.asarray(travel(th), dtype=float)
    elaps = exhaust_laps if exhaust_laps is not None else (0.0, 0.0)
    out: dict = {"head": {}, "crank": {}}
    for end, name, level, rising in POLAR_EVENTS:
        out[end][f"{name}_deg"] = None
    two_pi = 2.0 * np.pi

    def meetings(level, up):
        """Angles [rad] where x passes ``level`` upwards (``up``) or downwards."""
        above = x - level > 0.0
        idx = np.nonzero(above[1:] != above[:-1])[0]
        found = []
        for i in idx:
            if bool(above[i + 1]) != up:
                continue
            found.append(brentq(lambda t: float(np.asarray(travel(np.array([t])))[0]) - level,
                                th[i], th[i + 1], xtol=1e-12) % two_pi)
        return found

    def near(angles, anchor):
        return min(angles, key=lambda t: min((t - anchor) % two_pi, (anchor - t) % two_pi))

    for end, dead in (("head", 0.0), ("crank", np.pi)):
        if end == idle:
            continue
        rows = [r for r in POLAR_EVENTS if r[0] == end]
        pairs = [(rows[0], rows[1], dead)]
        if exhaust_laps is not None:
            pairs.append((rows[2], rows[3], dead + np.pi))
        for opening, closing, anchor in pairs:
            # the port opens where its opening rises: for the steam port the
            # admission's crossing, for the exhaust the release's
            opens = meetings(opening[2](laps, elaps), opening[3])
            shuts = meetings(closing[2](laps, elaps), closing[3])
            if not opens or not shuts:
                continue
            t0 = near(opens, anchor % two_pi)
            t1 = min(shuts, key=lambda t: (t - t0) % two_pi)
            out[end][f"{opening[1]}_deg"] = float(np.degrees(t0) % 360.0)
            out[end][f"{closing[1]}_deg"] = float(np.degrees(t1) % 360.0)
    return out


def event_rays(ev, ends=("head", "crank")) -> list:
    """The events an events dict holds, as crank lines.

    Parameters
    ----------
    ev : dict
        ``{"head": {...}, "crank": {...}}`` with ``admission_deg`` etc. (None where
        absent).
    ends : tuple of str, optional
        The ends to take.

    Returns
    -------
    list of (float, str, str)
        ``(angle [deg], end, event)`` of each event present.
    """
    return [(ev[end][f"{name}_deg"], end, name) for end in ends for name in EVENT_WORDS
            if ev[end].get(f"{name}_deg") is not None]


#: The events' numbers on the crank lines, as Spangler numbers them (Art. 17, Figs.
#: 12-13: 1 admission, 2 cut-off, 3 release, 4 compression at one end), the crank
#: end's following on.
EVENT_NUMBERS = {("head", name): str(i + 1) for i, name in enumerate(EVENT_WORDS)} | \
    {("crank", name): str(i + 5) for i, name in enumerate(EVENT_WORDS)}


def crank_lines(ax, ev, radius: float, lines: dict) -> list:
    """The crank line of every event, numbered beyond its end and named in the legend.

    Each line runs from o to ``radius``, the head end's solid and the crank end's
    dashed; its number (:data:`EVENT_NUMBERS`) stands beyond its end, lines within 4
    deg sharing one label (:func:`corliss.plot.labels.merge_rays`); the legend gives
    each number's end, event and angle.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The diagram.
    ev : dict
        The events, ``{"head": {"admission_deg": ...}, "crank": {...}}`` [deg].
    radius : float
        The lines' length [data units].
    lines : dict
        Where the lines are recorded, as ``lines["crank_lines"][end][event]``.

    Returns
    -------
    list of matplotlib.text.Text
        The numbers' labels.
    """
    rays = []
    drawn: dict = {"head": {}, "crank": {}}
    for a, end, name in event_rays(ev):
        p = np.radians(a)
        c, s = np.cos(p), np.sin(p)
        n = EVENT_NUMBERS[(end, name)]
        (drawn[end][name],) = ax.plot(
            [0.0, radius * c], [0.0, radius * s], color="0.2", lw=0.8,
            ls="-" if end == "head" else "--",
            label=f"{n}  {end} {EVENT_WORDS[name]}, {a:.1f}\N{DEGREE SIGN}")
        rays.append((a, n))
    lines["crank_lines"] = drawn
    return ray_labels(ax, merge_rays([(a, n) for a, n in rays], within_deg=4.0), radius,
                      fontsize=7.5)


def dead_centre_lines(ax, radius: float) -> None:
    """The dead-centre line and the line square to it through o (Art. 15: "draw the two
    lines ab and cd at right angles to each other").

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The diagram.
    radius : float
        Their half length [data units], as the crank lines'.

    Returns
    -------
    None
    """
    ax.plot([-radius, radius], [0.0, 0.0], color="0.6", lw=0.6)
    ax.plot([0.0, 0.0], [-radius, radius], color="0.6", lw=0.6)


def period_frame(ax, u: str, title: str) -> None:
    """A polar diagram's frame: equal aspect, no box, the legend under the diagram
    (where no curve runs).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The diagram.
    u : str
        The unit of its lengths (``"in"`` or ``"mm"``).
    title : str
        Its title.

    Returns
    -------
    None
    """
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(f"[{u}]  crank turning counter-clockwise from head dead centre (right)",
                  fontsize=7)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=7, frameon=False, loc="upper center", bbox_to_anchor=(0.5, -0.16),
              ncol=2)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)


