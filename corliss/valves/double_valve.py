"""Double valves: a main valve and a cut-off valve on their own eccentrics (Spangler,
*Valve-Gears*, Chs. XV-XVIII, Arts. 115-148).

The main valve is a lapped D valve (or, in the Buckeye, a valve taking steam inside):
it alone admits to and exhausts from each end, and its displacement ``x`` is taken in
the sense that opens the head-end steam port.  Steam reaches its steam edge only
through the cut-off valve, which is of one of two classes (Art. 115):

* **on its own seat** (class 1, the gridiron or Gonzenbach valve, Arts. 116-126): it
  controls the admission to the main valve's chest, common to both ends.  Its ports
  (width ``e`` in the seat, ``f`` in the valve, centred over each other in its middle
  position) are open by ``s - |x1|`` with ``s = (e + f)/2``, wide open (``e``) while
  ``|x1| <= (f - e)/2`` (Art. 121), ``x1`` being the cut-off valve's own displacement;
* **riding on the back of the main valve** (class 2: Polonceau, Buckeye, Meyer,
  Guinotte, Arts. 117, 127-148): a block covers the passage through the main valve to
  each end when the relative displacement of the two valves reaches the block's lap
  ``s`` on that end (Art. 130).  With the relative displacement ``x_r`` taken in the
  sense that closes the head-end passage, the top of the passage (width ``e``) is
  open by ``s_h - x_r`` at the head end and ``s_c + x_r`` at the crank end; a block
  of finite length ``d`` uncovers the passage again from its other side once
  ``x_r > s + d - e`` (Art. 134: "the length of d > r_x - (s - e)", Art. 144).

The steam port of each end is open only as far as both valves leave it open: the
passages are in series, so the open area is the smaller of the two (the cut-off
valve's opening converted to the main port's length), each bounded by its own width
(notes on the book: "evaluate the effective area as the series combination of the
main-valve and cut-off-valve openings at every angle").  The exhaust is under the
main valve alone (Art. 115).  The steam held between the valves after the cut-off
valve closes (the gridiron's chest, Art. 116; the passages of a riding valve) is not
modelled: its small expansion with the cylinder's is neglected.

**Double admission** (Arts. 118, 130, 133, 139, 142): if the cut-off valve opens its
passage again while the main valve's port is still open, steam enters twice in one
stroke.  :meth:`DoubleValve.double_admissions` finds every such second admission from
the openings themselves.  The cut-off valve must also be open when the main valve opens
(Art. 118: it "must open between D and A"); :meth:`DoubleValve.late_admissions` finds
the strokes where it is not (steam entering late, or not at all).  A scene whose
setting gives either logs a warning.

Both motions: the Zeuner form (each eccentric a harmonic, so the relative motion is
itself one, the "relative valve circle" of Art. 128) and ``motion = "exact"`` with
finite eccentric rods (and, for the Buckeye, its levers) solved per crank angle.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np

from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Derived, Key, group
from corliss.keys.toml_table import Table
from corliss.valves.gear import ValveGear
from corliss.valves.slide_valve import LAP_KEYS, PORT_KEYS, parse_ports

log = logging.getLogger(__name__)
TWO_PI = 2.0 * math.pi
_SAMPLES = 7200


@dataclass(frozen=True)
class MainValveSpec:
    """The main valve's laps and steam ports (all SI).

    Parameters
    ----------
    lap_m : tuple of float
        Steam lap of the (head, crank) end [m].
    exhaust_lap_m : tuple of float
        Exhaust lap of the (head, crank) end [m]; negative = exhaust clearance.
    port_width_m : float
        Width of each cylinder port in the direction of travel [m].
    port_length_m : float
        Length of each cylinder port across the valve face [m].
    discharge_coefficient : float, optional
        Of the steam and exhaust openings [-].
    ports_per_end : int, optional
        Number of openings each edge uncovers (2 for a double-ported valve).
    """

    lap_m: tuple[float, float]
    exhaust_lap_m: tuple[float, float]
    port_width_m: float
    port_length_m: float
    discharge_coefficient: float = 0.7
    ports_per_end: int = 1


@dataclass(frozen=True)
class CutoffSpec:
    """The cut-off valve's passages (all SI).

    Parameters
    ----------
    kind : str
        ``"seat"`` (class 1, gridiron) or ``"riding"`` (class 2, on the main valve).
    lap_m : tuple of float
        ``s`` of the (head, crank) end [m]: how far the cut-off valve moves (relative
        to the main valve, for a riding valve) from its middle position to close.
    passage_width_m : float
        ``e``: width of the port it covers [m] (Arts. 121, 134, 144).
    passage_length_m : float
        Length of that port times the number of openings [m].
    block_length_m : float or None, optional
        ``d``: length of a riding block [m]; None for a block long enough never to
        uncover the passage from its far side.
    """

    kind: str
    lap_m: tuple[float, float]
    passage_width_m: float
    passage_length_m: float
    block_length_m: float | None = None


def eccentric_travel(theta, r: float, delta: float, rod: float | None = None,
                     sign: int = 1) -> np.ndarray:
    """Displacement [m] of a valve driven by an eccentric of throw ``r`` and advance
    ``delta``: ``r sin(theta + delta)`` (Spangler Art. 13, eq. 4), plus, with a rod of
    finite length ``g``, the rod end's shortfall ``g - sqrt(g^2 - r^2 cos^2(theta +
    delta))`` taken with ``sign`` (+1 directly connected, -1 through a reverse lever),
    measured from the valve's mean dead-point position (set for equal lead, as the
    plain slide valve is; Marks Art. 96).

    Parameters
    ----------
    theta : float or ndarray
        Crank angles [rad] from head-end dead centre, any shape.
    r : float
        Eccentric's throw [m].
    delta : float
        Eccentric's angular advance [rad].
    rod : float or None, optional
        Eccentric rod length g [m]; None for Zeuner's motion (an infinite rod).
    sign : int, optional
        +1 directly connected, -1 through a reverse lever [-].

    Returns
    -------
    ndarray
        Valve displacement [m], of the shape of ``theta``.
    """
    phase = np.asarray(theta, dtype=float) + delta
    x = r * np.sin(phase)
    if rod is not None:
        x = x + sign * (math.sqrt(rod * rod - (r * math.cos(delta)) ** 2)
                        - np.sqrt(rod * rod - (r * np.cos(phase)) ** 2))
    return x


class DoubleValve(ValveGear):
    """A main valve and a cut-off valve (see the module doc).

    Subclasses set ``spec`` (with ``main``: :class:`MainValveSpec` and ``cutoff``:
    :class:`CutoffSpec`) and give :meth:`main_travel` and either
    :meth:`cutoff_travel` (a valve on its own seat) or :meth:`closing_travel` (a
    riding valve), with their Zeuner forms for the drawing.
    """

    #: What the book calls the relative motion, for the drawing's legend.
    relative_label = "relative (main - cut-off)"

    # -- motions ---------------------------------------------------------------
    def main_travel(self, theta) -> np.ndarray:  # pragma: no cover - interface
        """Main valve displacement, + opening the head steam port.

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Displacement [m], shape ``(n,)``.
        """
        raise NotImplementedError

    def cutoff_travel(self, theta) -> np.ndarray:  # pragma: no cover - interface
        """Cut-off valve displacement, in the main valve's sense (+ toward opening the
        head steam port).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Displacement [m], shape ``(n,)``.
        """
        raise NotImplementedError

    def closing_travel(self, theta) -> np.ndarray:
        """Relative displacement of a riding cut-off valve, + closing the head-end
        passage: main minus cut-off (the distance ``ef`` of Art. 127).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Relative displacement x_r [m], shape ``(n,)``.
        """
        return self.main_travel(theta) - self.cutoff_travel(theta)

    def zeuner_closing_coefficients(self) -> tuple[float, float] | None:
        """The Zeuner relative motion ``C cos(theta) + S sin(theta)``, for the drawing.

        Returns
        -------
        tuple of float or None
            ``(C, S)`` [m] of a riding valve's relative valve circle (Art. 128); None
            where the gear has none (the base class's answer).
        """
        return None

    # -- openings --------------------------------------------------------------
    def main_signed(self, theta) -> np.ndarray:
        """Signed openings of the main valve alone, the cut-off valve ignored.

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Signed openings [m], shape ``(4, n)``, in the order of
            :data:`corliss.valves.gear.PORTS`.
        """
        x = self.main_travel(theta)
        m = self.spec.main
        (lh, lc), (eh, ec) = m.lap_m, m.exhaust_lap_m
        return np.vstack([x - lh, -x - eh, -x - lc, x - ec])

    def cutoff_signed(self, theta) -> np.ndarray:
        """Signed opening of the cut-off valve's passage to each end (see the module
        doc).

        Parameters
        ----------
        theta : ndarray
            Crank angles [rad] from head-end dead centre, shape ``(n,)``.

        Returns
        -------
        ndarray
            Signed openings [m] of the (head, crank) passages, shape ``(2, n)``, in
            the cut-off valve's own widths (not yet converted to the main port's
            length).
        """
        c = self.spec.cutoff
        sh, sc = c.lap_m
        if c.kind == "seat":
            x1 = np.abs(self.cutoff_travel(theta))
            return np.vstack([sh - x1, sc - x1])
        xr = self.closing_travel(theta)
        head, crank = sh - xr, sc + xr
        if c.block_length_m is not None:
            d, e = c.block_length_m, c.passage_width_m
            head = np.maximum(head, xr - (sh + d - e))
            crank = np.maximum(crank, -xr - (sc + d - e))
        return np.vstack([head, crank])

    def _passage_scale(self) -> float:
        m = self.spec.main
        return self.spec.cutoff.passage_length_m / (m.port_length_m * m.ports_per_end)

    def signed_openings(self, theta):
        s = self.main_signed(theta)
        cut = self.cutoff_signed(theta) * self._passage_scale()
        s[0] = np.minimum(s[0], cut[0])
        s[2] = np.minimum(s[2], cut[1])
        return s

    def port_widths(self):
        m = self.spec.main
        w = np.full(4, m.port_width_m)
        w[[0, 2]] = min(m.port_width_m, self.spec.cutoff.passage_width_m * self._passage_scale())
        return w

    def port_lengths(self):
        m = self.spec.main
        return np.full(4, m.port_length_m * m.ports_per_end)

    def openings_per_edge(self):
        return np.full(4, float(self.spec.main.ports_per_end))

    def discharge_coefficients(self):
        return np.full(4, self.spec.main.discharge_coefficient)

    # -- double admission ------------------------------------------------------
    def admission_runs(self) -> dict[str, list[tuple[float, float, list[tuple[float, float]]]]]:
        """Each interval in which the main valve's steam port is open, with the
        intervals inside it in which both valves are open.

        Returns
        -------
        dict
            ``{"head": runs, "crank": runs}``, each run
            ``(open_rad, close_rad, [(start_rad, end_rad), ...])``.  Angles [rad]
            unwrapped (an end may pass 2 pi); the main valve's edges to a sample
            (1/20 deg), the combined opening's bisected to better than 1e-10 rad
            (40 halvings of a sample).
        """
        dt = TWO_PI / _SAMPLES
        th = np.arange(_SAMPLES) * dt
        main = self.main_signed(th)
        comb = self.signed_openings(th)
        out = {}
        for end, p in (("head", 0), ("crank", 2)):
            runs = []
            co = comb[p] > 0.0
            for a0, a1 in _circular_runs(main[p] > 0.0):
                sub = co[np.arange(a0, a1) % _SAMPLES]
                d = np.diff(np.concatenate([[0], sub.astype(int), [0]]))
                inner = []
                for s, e in zip(np.nonzero(d == 1)[0], np.nonzero(d == -1)[0]):
                    inner.append((self._edge(p, (a0 + s - 1) * dt, (a0 + s) * dt),
                                  self._edge(p, (a0 + e - 1) * dt, (a0 + e) * dt)))
                runs.append((a0 * dt, a1 * dt, inner))
            out[end] = runs
        return out

    def double_admissions(self) -> dict[str, list[tuple[float, float]]]:
        """Crank-angle intervals [deg] of any second admission, per end.

        Within each interval in which the main valve's steam port is open, the combined
        opening may open more than once: every opening after the first is steam
        admitted again after the cut-off valve had closed (Art. 118: the cut-off valve
        "must not open again until the crank passes B, otherwise steam would be
        admitted twice during one stroke"; Arts. 130, 139, 142).

        Returns
        -------
        dict
            ``{"head": [(start_deg, end_deg), ...], "crank": [...]}``, angles in [0, 360).
        """
        return {end: [(math.degrees(a) % 360.0, math.degrees(b) % 360.0)
                      for _, _, inner in runs for a, b in inner[1:]]
                for end, runs in self.admission_runs().items()}

    def late_admissions(self) -> dict[str, list[tuple[float, float | None]]]:
        """The openings of the main valve that find the cut-off valve closed.

        Art. 118: "the cut-off valve must open between D and A in order that the steam
        may be admitted as soon as the main valve opens".

        Returns
        -------
        dict
            ``{"head": [...], "crank": [...]}``, each item ``(opens_deg,
            admitted_deg)``: the crank angle [deg] in [0, 360) where the main valve
            opens, and where steam is first admitted, or None for no steam at all
            that stroke.
        """
        tol = 2.0 * TWO_PI / _SAMPLES
        out = {}
        for end, runs in self.admission_runs().items():
            out[end] = [(math.degrees(a0) % 360.0,
                         None if not inner else math.degrees(inner[0][0]) % 360.0)
                        for a0, _, inner in runs if not inner or inner[0][0] > a0 + tol]
        return out

    def _edge(self, port: int, a: float, b: float) -> float:
        fa = self.signed_openings(np.array([a]))[port, 0] > 0.0
        for _ in range(40):
            m = 0.5 * (a + b)
            if (self.signed_openings(np.array([m]))[port, 0] > 0.0) == fa:
                a = m
            else:
                b = m
        return 0.5 * (a + b)

    def warn_double_admission(self) -> None:
        """Log a warning naming the second (and the late) admissions of this setting."""
        for end, spans in self.double_admissions().items():
            if spans:
                txt = ", ".join(f"{a:.1f}-{b:.1f} deg" for a, b in spans)
                log.warning("%s gear: steam is admitted twice in the %s-end stroke (second "
                            "admission at crank angles %s): the cut-off valve re-opens "
                            "before the main valve cuts off (Spangler Arts. 118, 130)",
                            self.name, end, txt)
        for end, late in self.late_admissions().items():
            for a, b in late:
                what = ("no steam is admitted at all" if b is None
                        else f"steam enters only at {b:.1f} deg")
                log.warning("%s gear: the main valve opens the %s-end port at %.1f deg with "
                            "the cut-off valve closed, and %s (Spangler Art. 118: the cut-off "
                            "valve must open before the main valve does)", self.name, end, a,
                            what)


def _circular_runs(mask: np.ndarray) -> list[tuple[int, int]]:
    """Runs of True in a periodic boolean array, as (start, end) indices, end exclusive,
    unwrapped (an end may exceed the length)."""
    n = mask.size
    if mask.all():
        return [(0, n)]
    if not mask.any():
        return []
    k = int(np.argmin(mask))
    m = np.roll(mask, -k).astype(int)
    d = np.diff(np.concatenate([[0], m, [0]]))
    return [(int(a) + k, int(b) + k) for a, b in zip(np.nonzero(d == 1)[0], np.nonzero(d == -1)[0])]


# -- reading scenes -------------------------------------------------------------

#: The main valve's keys: its laps and ports.
MAIN_KEYS = group("main_valve", "The main valve of a double-valve gear.", LAP_KEYS, PORT_KEYS)
#: A riding cut-off valve's keys.
RIDING_KEYS = group(
    "riding", "A riding cut-off valve on the back of the main valve.",
    Key("cutoff_lap", "length", "Lap of the cut-off valve over the main valve's passage.",
        ends=True, unit="in"),
    Key("passage_width", "length", "Width of the passage through the main valve.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("passage_length", "length", "Length of the passage across the valve face.",
        default=Derived("the port length times ports_per_end"), within=POSITIVE_LENGTH,
        unit="in"),
    Key("block_length", "length", "Length of the cut-off block, at least the passage width; "
        "absent: long enough never to uncover the far side.", default=None,
        within=POSITIVE_LENGTH, unit="in"),
)
#: The cut-off valve's own eccentric.
CUTOFF_ECCENTRIC_KEYS = group(
    "cutoff_eccentric", "The cut-off valve's eccentric.",
    Key("cutoff_eccentricity", "length", "Throw of the cut-off eccentric.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("cutoff_angular_advance", "angle", "Angular advance of the cut-off eccentric.",
        unit="deg"),
)
#: The motion the double-valve gears solve, and their rods for the exact one.
MOTION_KEYS = group(
    "motion", "Zeuner's (infinite rods) or the exact motion.",
    Key("motion", "choice", "Zeuner's motion (infinite rods) or the exact linkage.",
        default="zeuner", choices=("zeuner", "exact")),
    Key("eccentric_rod", "length", "Main eccentric rod, longer than its throw.",
        within=POSITIVE_LENGTH, unit="in", when="with motion = \"exact\" (required there)"),
    Key("cutoff_eccentric_rod", "length", "Cut-off eccentric rod, longer than its throw.",
        within=POSITIVE_LENGTH, unit="in", when="with motion = \"exact\" (required there)"),
)


def setting_key(lo: float, hi: float, what: str) -> Key:
    """The ``setting`` key of a double-valve gear: a plain number from ``lo`` (its
    default) to ``hi``.

    Parameters
    ----------
    lo, hi : float
        The setting's range [-].
    what : str
        What the setting is (``"governor position"``).

    Returns
    -------
    Key
        The declaration.
    """
    return Key("setting", "number", f"The gear's setting: {what}.", default=lo,
               within=(lo, hi))


def parse_main(t: Table) -> MainValveSpec:
    """The main valve's keys (:data:`MAIN_KEYS`): ``lap``, ``exhaust_lap`` and the port
    keys.

    Parameters
    ----------
    t : Table
        The gear's table.

    Returns
    -------
    MainValveSpec
        The main valve.
    """
    return MainValveSpec(t.get("lap"), t.get("exhaust_lap"), **parse_ports(t))


def parse_riding(t: Table, main: MainValveSpec, lap: tuple[float, float] | None = None) -> CutoffSpec:
    """A riding cut-off valve's keys (:data:`RIDING_KEYS`): ``cutoff_lap`` (s, once or
    [head, crank]; unless the gear finds it), ``passage_width`` (e), optional
    ``passage_length`` and ``block_length`` (d).

    Parameters
    ----------
    t : Table
        The gear's table.
    main : MainValveSpec
        The main valve (its ports give the default passage length).
    lap : (float, float), optional
        The cut-off lap [m] when the gear finds it; None: read ``cutoff_lap``.

    Returns
    -------
    CutoffSpec
        The cut-off valve.
    """
    if lap is None:
        lap = t.get("cutoff_lap")
    e = t.get("passage_width")
    length = (t.get("passage_length") if t.has("passage_length")
              else main.port_length_m * main.ports_per_end)
    d = t.get("block_length")
    if d is not None and d < e:
        raise InputError(t.key("block_length"), t.raw("block_length"),
                         "a block at least as long as the passage is wide (it must cover it)")
    return CutoffSpec("riding", lap, e, length, d)


def rod(t: Table, key: str, throw: float, motion: str) -> float | None:
    """An eccentric rod's length for the exact motion (None for Zeuner's).

    Parameters
    ----------
    t : Table
        The gear's table.
    key : str
        The rod's key.
    throw : float
        Its eccentric's throw [m].
    motion : str
        ``"exact"`` reads the rod; any other motion has none.

    Returns
    -------
    float or None
        The rod's length [m].
    """
    if motion != "exact":
        return None
    g = t.get(key)
    if g <= throw:
        raise InputError(t.key(key), t.raw(key), "a rod longer than its eccentric's throw")
    return g


def check_setting(t: Table, key: str, lo: float, hi: float, what: str) -> float:
    """The gear's setting (:func:`setting_key`, which holds its range), from ``lo`` to
    ``hi``.

    Parameters
    ----------
    t : Table
        The gear's table.
    key : str
        The setting's key.
    lo, hi : float
        Its range [-].
    what : str
        What it is, for the message.

    Returns
    -------
    float
        The setting [-].
    """
    v = t.get(key)
    if not lo <= v <= hi:
        raise InputError(t.key(key), v, f"a setting from {lo} to {hi} ({what})")
    return v


def built(gear: DoubleValve) -> DoubleValve:
    """A gear as a scene builds it: warn if its setting admits steam twice.

    Parameters
    ----------
    gear : DoubleValve
        The gear just built from its spec.

    Returns
    -------
    DoubleValve
        The same gear, after :meth:`DoubleValve.warn_double_admission` has logged any
        second or late admission.
    """
    gear.warn_double_admission()
    return gear
