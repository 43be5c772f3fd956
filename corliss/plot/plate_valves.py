"""The Porter-Allen's four flat valves drawn in section over their ports (Spangler Art. 30,
Fig. 22), for :func:`~corliss.plot.animation.animate_gear`.

Each valve is a plate sliding on its seat, the steam valves above (the chest's steam
over them, as in Fig. 22), the exhaust valves below; the head end's on the left, the
crank end's on the right drawn as its mirror image, each valve opening towards the
page's middle (Fig. 22's left-hand steam valve "moves to the right to admit steam on
the left", its right-hand exhaust valve "to the left to exhaust on its right"), so that
the two exhaust valves, on one stem, move together across the page.  Each valve is drawn in its
own frame, x along its travel in the sense that opens its port, the port's first edge
at x = 0:

* the seat has ``n`` ports (a steam plate's ``steam_openings``; one for an exhaust
  valve), each ``w`` wide, their first edges a pitch ``p`` apart;
* the plate's edges stand at ``k p - lap + x`` (k = 0 .. n-1), x the valve's travel from
  mid position (:meth:`~corliss.valves.fink_motion.PorterAllenGear.valve_travels`); the
  plate's end is the first edge, and an opening ``g`` wide through the plate ends at
  each further edge.  Port k is then uncovered over clip(x - lap, 0, w), the gear's
  signed opening clipped, every port alike: the port's area n L clip(s, 0, w), the area
  the gear's port map uses.  That holds exactly when the opening through the plate is
  at least the plate's largest opening (g >= max s, so its far side never passes over
  the port) and the bar between two openings is wide enough to cover the next port at
  the plate's least travel (p >= w + g + lap - min x): the plate's bars wider than its
  travel, as the module doc of :mod:`corliss.valves.fink_motion` takes them.  The
  proportions (g, p and the plate's length past its last port) are so chosen; the
  edges, laps, widths and travels are the gear's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: The four valves in the order of :data:`corliss.valves.gear.PORTS`.
NAMES = ("head steam", "head exhaust", "crank steam", "crank exhaust")
_STEAM, _EXHAUST, _FIXED = "#b03a2e", "#2e5fb0", "0.55"


@dataclass(frozen=True)
class PlateValve:
    """One flat valve and its seat, in its own frame (x along its travel, opening +x).

    Parameters
    ----------
    name : str
        Which port it works (:data:`NAMES`).
    lap_m : float
        Its lap [m] (negative: clearance).
    width_m : float
        Each port's width along the travel [m].
    openings : int
        Ports it uncovers at once [-].
    hole_m : float
        Width of each opening through the plate [m].
    pitch_m : float
        Distance from one port's first edge to the next's [m].
    tail_m : float
        The plate's length past its last edge [m].
    origin_m : float
        Where the frame's x = 0 stands across the page [m].
    mirror : float
        +1 (the frame's x to the right on the page) or -1 (to the left).
    row_m : float
        Height on the page of the seat's face [m].
    seat_m : tuple of float
        The seat drawn, (from, to) in the valve's frame [m].
    """

    name: str
    lap_m: float
    width_m: float
    openings: int
    hole_m: float
    pitch_m: float
    tail_m: float
    origin_m: float
    mirror: float
    row_m: float
    seat_m: tuple[float, float]

    def ports(self) -> list[tuple[float, float]]:
        """The seat's ports, (from, to) in the valve's frame [m].

        Returns
        -------
        list of tuple
            One (from, to) [m] per port.
        """
        return [(k * self.pitch_m, k * self.pitch_m + self.width_m)
                for k in range(self.openings)]

    def solids(self, x_m: float) -> list[tuple[float, float]]:
        """The plate's solid parts, (from, to) in the valve's frame [m], with the valve
        at ``x_m`` from mid position: from each edge to the far side of the next
        opening through the plate, the last to the plate's end.

        Parameters
        ----------
        x_m : float
            The valve's travel from mid position, in the sense that opens its port [m].

        Returns
        -------
        list of tuple
            One (from, to) [m] per solid part.
        """
        edges = [k * self.pitch_m - self.lap_m + x_m for k in range(self.openings)]
        ends = [e + self.pitch_m - self.hole_m for e in edges[:-1]] + [edges[-1] + self.tail_m]
        return list(zip(edges, ends))

    def page_x(self, x_m):
        """Across the page [m] of the frame's ``x_m`` [m].

        Parameters
        ----------
        x_m : float or ndarray
            In the valve's frame [m].

        Returns
        -------
        float or ndarray
            On the page [m].
        """
        return self.origin_m + self.mirror * np.asarray(x_m)


def plate_travels(gear, theta) -> np.ndarray:
    """Each valve's travel from mid position in the sense that opens its port.

    Parameters
    ----------
    gear : PorterAllenGear
        The gear.
    theta : float or ndarray
        Crank angles [rad], shape ``(n,)``.

    Returns
    -------
    ndarray
        Travels [m], shape ``(4, n)``, in the order of :data:`NAMES`: the head and crank
        steam valves' own, the exhaust stem's for the head exhaust and its opposite for
        the crank exhaust (one stem; ``signed_openings`` is each less its lap).
    """
    v = gear.valve_travels(np.atleast_1d(theta))
    return np.vstack([v[0], v[2], v[1], -v[2]])


def plate_layout(gear) -> list[PlateValve]:
    """The four valves of ``gear`` laid out on the page (module doc).

    Parameters
    ----------
    gear : PorterAllenGear
        The gear, at its setting.

    Returns
    -------
    list of PlateValve
        In the order of :data:`NAMES`.
    """
    s = gear.spec
    th = np.linspace(0.0, 2 * math.pi, 721)
    x = plate_travels(gear, th)
    laps = (s.steam_lap_m[0], s.exhaust_lap_m[0], s.steam_lap_m[1], s.exhaust_lap_m[1])
    widths = (s.steam_port_width_m, s.exhaust_port_width_m) * 2
    counts = (s.steam_openings, 1) * 2
    rows: list[dict] = [{} for _ in range(4)]
    for p in range(4):
        w, lap = widths[p], laps[p]
        reach = float(np.max(np.abs(x[p])))
        hole = max(float(np.max(x[p])) - lap, w) + 0.25 * w
        pitch = w + hole + lap - float(np.min(x[p])) + 0.5 * w
        tail = w + abs(lap) + reach + 0.5 * w
        # the seat's far end past the plate's end at its greatest travel
        right = (counts[p] - 1) * pitch + tail + abs(lap) + reach + w
        rows[p] = {"w": w, "lap": lap, "reach": reach, "hole": hole, "pitch": pitch, "tail": tail,
                   "right": right}
    # the head's valve on the left, its frame to the right; the crank's mirrored
    half = max(r["right"] for r in rows) + 0.5 * max(widths)
    height = 3.0 * max(widths)
    out = []
    for p in range(4):
        r = rows[p]
        head = p in (0, 1)
        out.append(PlateValve(NAMES[p], r["lap"], r["w"], counts[p], r["hole"], r["pitch"],
                              r["tail"], -half if head else half, 1.0 if head else -1.0,
                              0.0 if p in (0, 2) else -height,
                              (-(abs(r["lap"]) + r["reach"] + 1.2 * r["w"]), r["right"])))
    return out


class PlateValvesPanel:
    """The four valves in section over their ports in ``ax``, ``update(theta)`` moving
    them to the gear's travels.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Where they are drawn.
    gear : PorterAllenGear
        The gear.
    scale : float
        Drawing units per metre [-].
    unit : str
        The drawing's length unit, for the labels (``"in"``, ``"mm"``).
    moving : list
        The moving artists are appended to it.
    """

    def __init__(self, ax, gear, scale: float, unit: str, moving: list):
        from matplotlib.patches import Rectangle
        self.gear, self.scale, self.unit = gear, scale, unit
        self.valves = plate_layout(gear)
        wmax = max(v.width_m for v in self.valves)
        self.plates: list[list] = []
        self.labels = []
        lo, hi = 0.0, 0.0
        thick = 0.6 * wmax
        for v in self.valves:
            col = _STEAM if "steam" in v.name else _EXHAUST
            ports = v.ports()
            left, right = v.seat_m
            # the seat: solid between the ports, hatched; the ports coloured
            bounds = [left] + [e for pt in ports for e in pt] + [right]
            for a, b in zip(bounds[0::2], bounds[1::2]):
                xa, xb = sorted((float(v.page_x(a)), float(v.page_x(b))))
                ax.add_patch(Rectangle((xa * scale, (v.row_m - thick) * scale),
                                       (xb - xa) * scale, thick * scale, facecolor="0.82",
                                       edgecolor=_FIXED, hatch="///", lw=0.6))
            for a, b in ports:
                xa, xb = sorted((float(v.page_x(a)), float(v.page_x(b))))
                ax.add_patch(Rectangle((xa * scale, (v.row_m - thick) * scale),
                                       (xb - xa) * scale, thick * scale, facecolor=col,
                                       alpha=0.35, edgecolor=col, lw=0.6))
            parts = []
            for _ in v.solids(0.0):
                patch = ax.add_patch(Rectangle((0.0, v.row_m * scale), 0.0, 0.5 * thick * scale,
                                               facecolor="0.6", edgecolor="k", lw=0.9))
                parts.append(patch)
                moving.append(patch)
            self.plates.append(parts)
            text = ax.text(float(v.page_x(0.5 * (left + right))) * scale,
                           (v.row_m + 0.9 * thick) * scale, "", ha="center", va="bottom",
                           fontsize=6, color=col)
            self.labels.append(text)
            moving.append(text)
            for xx in (v.page_x(left), v.page_x(right)):
                lo, hi = min(lo, float(xx)), max(hi, float(xx))
        ax.text(0.5, 0.99, "steam chest over the steam valves; exhaust valves below, on one "
                "stem", transform=ax.transAxes, ha="center", va="top", fontsize=6, color="0.4")
        low = min(v.row_m for v in self.valves) - 2.0 * thick
        pad = 0.03 * (hi - lo)
        ax.set_xlim((lo - pad) * scale, (hi + pad) * scale)
        ax.set_ylim(low * scale, 3.5 * thick * scale)
        ax.set_aspect("equal")
        ax.axis("off")
        n = self.valves[0].openings
        ax.set_title(f"the four valves over their ports (steam plates: {n} opening"
                     f"{'s' if n != 1 else ''} each)", fontsize=8)
        self.travels_m = np.zeros(4)

    def update(self, theta: float) -> np.ndarray:
        """Move the plates to the gear's travels at ``theta``.

        Parameters
        ----------
        theta : float
            Crank angle [rad] from head-end dead centre.

        Returns
        -------
        ndarray
            Each valve's travel [m], shape ``(4,)``, in the order of :data:`NAMES`.
        """
        sc = self.scale
        x = plate_travels(self.gear, np.array([theta]))[:, 0]
        for v, parts, text, xp in zip(self.valves, self.plates, self.labels, x):
            for patch, (a, b) in zip(parts, v.solids(float(xp))):
                xa, xb = sorted((float(v.page_x(a)), float(v.page_x(b))))
                patch.set_x(xa * sc)
                patch.set_width((xb - xa) * sc)
            each = min(max(float(xp) - v.lap_m, 0.0), v.width_m)
            text.set_text(f"{v.name}: open {v.openings} x {each * sc:.3f} {self.unit}")
        self.travels_m = x
        return x
