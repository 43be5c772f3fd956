"""The Meyer valve: two cut-off blocks on the back of a Polonceau-type main valve,
their distance apart set by a right-and-left screw (Spangler Arts. 141-145).

Both valves have their own eccentrics, directly connected (Art. 141).  The main
valve moves ``x = r sin(theta + delta)`` and the blocks ``x1 = r1 sin(theta + delta1)``
(Art. 13, eq. 4), so the relative displacement, + closing the head-end passage, is
the relative valve circle of Art. 128::

    x_r = x - x1 = (r sin d - r1 sin d1) cos(theta) + (r cos d - r1 cos d1) sin(theta)

With ``L`` the distance from outside to outside of the ports in the top of the main
valve, ``d`` the length of a block and ``2y`` the distance between the blocks, each
block laps its passage by (Art. 142)::

    2 s = L - 2 d - 2 y,        i.e.   s = L/2 - d - y

so the hand wheel, drawing the blocks apart (``y`` up), shortens ``s`` and the
cut-off: cut-off where x_r = s, re-opening where the circle of radius s cuts the
relative circle again, which must not come before the main valve cuts off (Art.
142).  ``s`` may go to zero and negative, so "almost any point of cut-off desired can
be obtained".

The setting is ``y / y_max`` from 0 (blocks together, latest cut-off) to 1 (blocks
at the screw's widest, earliest cut-off).  The right-and-left screw moves both blocks
equally; ``block_offset`` (once, or [head, crank]) adds a fixed offset to a block's y,
as a block set on its rod (Q. 178: one block farther from the centre than the other
gives unequal cut-offs, which may correct the connecting rod's angularity at one
setting only).

``motion = "exact"``: both eccentric rods of finite length (the rod shortfall, as for
the plain slide valve), each valve set for equal lead.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, ZERO_OR_MORE, Derived, Key, group
from corliss.keys.toml_table import Table
from corliss.valves import double_valve as dv
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import ANGULAR_ADVANCE, ECCENTRICITY


@dataclass(frozen=True)
class MeyerSpec:
    """A Meyer valve (all SI; Spangler Arts. 141-145).

    Parameters
    ----------
    main : MainValveSpec
        The main valve's laps and ports.
    cutoff : CutoffSpec
        The blocks' passages (``kind = "riding"``); its ``lap_m`` is s of each end at
        the current setting (:meth:`block_lap`).
    eccentricity_m : float
        Main eccentric's throw r [m].
    angular_advance_rad : float
        Main eccentric's angular advance delta [rad].
    cutoff_eccentricity_m : float
        Cut-off eccentric's throw r1 [m].
    cutoff_angular_advance_rad : float
        Cut-off eccentric's angular advance delta1 [rad].
    port_span_m : float
        L, outside to outside of the ports in the main valve's top [m].
    block_length_m : float
        d, the length of a block [m].
    max_half_spacing_m : float
        y at setting 1, the screw's widest [m].
    block_offset_m : tuple of float, optional
        Fixed addition to y of the (head, crank) block [m] (Q. 178).
    setting : float, optional
        y / y_max [-], from 0 (blocks together, latest cut-off) to 1.
    motion : str, optional
        ``"zeuner"`` or ``"exact"`` (finite eccentric rods).
    eccentric_rod_m, cutoff_eccentric_rod_m : float or None, optional
        Rod lengths for ``motion = "exact"`` [m]; None for Zeuner's motion.
    """

    main: dv.MainValveSpec
    cutoff: dv.CutoffSpec
    eccentricity_m: float
    angular_advance_rad: float
    cutoff_eccentricity_m: float
    cutoff_angular_advance_rad: float
    port_span_m: float
    block_length_m: float
    max_half_spacing_m: float
    block_offset_m: tuple[float, float] = (0.0, 0.0)
    setting: float = 0.0
    motion: str = "zeuner"
    eccentric_rod_m: float | None = None
    cutoff_eccentric_rod_m: float | None = None

    def half_spacing(self, setting: float | None = None) -> tuple[float, float]:
        """Distance y of each block from the valve's centre.

        Parameters
        ----------
        setting : float or None, optional
            y / y_max [-]; None for the spec's own setting.

        Returns
        -------
        tuple of float
            y of the (head, crank) block [m], the block offsets included.
        """
        y = (self.setting if setting is None else setting) * self.max_half_spacing_m
        return (y + self.block_offset_m[0], y + self.block_offset_m[1])

    @property
    def blocks_together_lap_m(self) -> float:
        """``L/2 - d`` [m]: the block lap s with the blocks together (y = 0), and the
        radius of the Meyer diagram's circle about the origin, on which any cut-off
        line cuts off ``be = L/2 - d = y + s`` (Art. 142).

        Returns
        -------
        float
            The lap [m].
        """
        return self.port_span_m / 2 - self.block_length_m

    def block_lap(self, setting: float | None = None) -> tuple[float, float]:
        """Lap of each block over its passage, ``s = L/2 - d - y`` (Art. 142).

        Parameters
        ----------
        setting : float or None, optional
            y / y_max [-]; None for the spec's own setting.

        Returns
        -------
        tuple of float
            s of the (head, crank) end [m]; it may be zero or negative at wide
            spacings, for the earliest cut-offs (Art. 142).
        """
        head, crank = (self.blocks_together_lap_m - y for y in self.half_spacing(setting))
        return head, crank

    def relative_coefficients(self) -> tuple[float, float]:
        """The relative valve circle, ``x_r = C cos(theta) + S sin(theta)`` (Art. 128).

        Returns
        -------
        C, S : float
            Coefficients [m] of the main valve's displacement less the blocks', in
            Zeuner's form (+ closing the head-end passage).
        """
        r, d = self.eccentricity_m, self.angular_advance_rad
        r1, d1 = self.cutoff_eccentricity_m, self.cutoff_angular_advance_rad
        return r * math.sin(d) - r1 * math.sin(d1), r * math.cos(d) - r1 * math.cos(d1)


class MeyerValve(dv.DoubleValve):
    """Meyer valve: adjustable cut-off blocks on a right-and-left screw.

    Its setting is the blocks' half spacing ``y / y_max``.

    Parameters
    ----------
    spec : MeyerSpec
        The valves, their eccentrics and the blocks' geometry.
    """

    name = "meyer"
    summary = ("Meyer valve: cut-off blocks on a right-and-left screw riding on the main "
               "valve, own eccentrics (Spangler Arts. 141-145); setting = block spacing y/y_max")
    setting_name = "block half-spacing y / y_max (0 blocks together, latest cut-off; 1 widest)"
    setting_range = (0.0, 1.0)

    def __init__(self, spec: MeyerSpec):
        self.spec = spec

    def _at_setting(self, value: float) -> "MeyerValve":
        s = self.spec
        cut = dataclasses.replace(s.cutoff, lap_m=s.block_lap(value))
        return MeyerValve(dataclasses.replace(s, setting=value, cutoff=cut))

    def main_travel(self, theta):
        s = self.spec
        return dv.eccentric_travel(theta, s.eccentricity_m, s.angular_advance_rad,
                                   s.eccentric_rod_m)

    def cutoff_travel(self, theta):
        s = self.spec
        return dv.eccentric_travel(theta, s.cutoff_eccentricity_m, s.cutoff_angular_advance_rad,
                                   s.cutoff_eccentric_rod_m)

    def zeuner_closing_coefficients(self):
        return self.spec.relative_coefficients()


MEYER_KEYS = group(
    "meyer", "Meyer's adjustable cut-off: two blocks on a right-and-left screw riding the "
    "main valve.",
    ECCENTRICITY, ANGULAR_ADVANCE, dv.CUTOFF_ECCENTRIC_KEYS, dv.MAIN_KEYS,
    Key("port_span", "length", "Span L between the outer edges of the main valve's "
        "passages, with L/2 above the block length (Art. 142).", within=POSITIVE_LENGTH,
        unit="in"),
    Key("block_length", "length", "Length d of each cut-off block.", within=POSITIVE_LENGTH,
        unit="in"),
    Key("max_half_spacing", "length", "The screw's greatest half spacing y_max of the blocks "
        "(zero or more).", unit="in", within=ZERO_OR_MORE),
    Key("block_offset", "length", "Offset of each block on the screw, leaving the blocks "
        "apart at y = 0.", default="0 in", ends=True, unit="in"),
    Key("passage_width", "length", "Width of the passage through the main valve.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("passage_length", "length", "Length of the passage across the valve face.",
        default=Derived("the port length times ports_per_end"), within=POSITIVE_LENGTH,
        unit="in"),
    dv.setting_key(0.0, 1.0, "y / y_max"), dv.MOTION_KEYS,
)


def parse_meyer(t: Table) -> MeyerSpec:
    """Read a ``[valve_gear] type = "meyer"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`MEYER_KEYS`.

    Returns
    -------
    MeyerSpec
        The gear's spec.
    """
    t = t.bound(MEYER_KEYS)
    main = dv.parse_main(t)
    r = t.get("eccentricity")
    r1 = t.get("cutoff_eccentricity")
    span = t.get("port_span")
    d = t.get("block_length")
    ymax = t.get("max_half_spacing")
    if ymax < 0.0:
        raise InputError(t.key("max_half_spacing"), t.raw("max_half_spacing"),
                         "a length >= 0 (the screw's greatest half spacing of the blocks)")
    setting = dv.check_setting(t, "setting", 0.0, 1.0, "y / y_max")
    motion = t.get("motion")
    e = t.get("passage_width")
    length = (t.get("passage_length") if t.has("passage_length")
              else main.port_length_m * main.ports_per_end)
    offset = t.get("block_offset")
    spec = MeyerSpec(main, dv.CutoffSpec("riding", (0.0, 0.0), e, length, d), r,
                     t.get("angular_advance"), r1, t.get("cutoff_angular_advance"), span, d,
                     ymax, offset, setting, motion, dv.rod(t, "eccentric_rod", r, motion),
                     dv.rod(t, "cutoff_eccentric_rod", r1, motion))
    spec = dataclasses.replace(spec, cutoff=dataclasses.replace(spec.cutoff,
                                                                lap_m=spec.block_lap()))
    if min(spec.half_spacing(0.0)) < 0.0:
        raise InputError(t.key("block_offset"), t.raw("block_offset"),
                         "offsets that leave the blocks apart when the screw brings them "
                         "together (y >= 0)")
    if span / 2 - d <= 0.0:
        raise InputError(t.key("port_span"), t.raw("port_span"),
                         "a span L with L/2 greater than the block length d (Art. 142)")
    return spec


register(GearType("meyer", MeyerValve.summary, parse_meyer,
                  lambda spec: dv.built(MeyerValve(spec)), MEYER_KEYS))
