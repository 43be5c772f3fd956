"""The slip eccentric: a plain slide valve on a loose eccentric with two stops.

The reversing gear of most small marine, launch and model engines.  The eccentric's
sheave is free on the shaft; a driving pin (or a collar's tooth) fixed to the shaft
bears on one of two stops on the sheave and carries it round.  Running ahead, the pin
drives on the forward stop and the eccentric stands ``90 deg + delta_f`` ahead of the
crank; to reverse, the engine is turned backward by hand (or by steam, a little way)
and the sheave, held by the friction of its strap and rod, stays where it is while the
shaft slips round inside it until the pin meets the backward stop, which sets the
eccentric ``90 deg + delta_b`` ahead of the crank in the new direction of rotation.

Reckoned as everywhere in corliss, from head-end dead centre in the direction of
rotation, the valve then moves as a plain slide valve's (Spangler, *Valve-Gears*,
Art. 13)::

    ahead:   x(theta) = r sin(theta + delta_f)
    astern:  x(theta) = r sin(theta + delta_b)

with the finite eccentric rod's correction of :mod:`corliss.valves.slide_valve`.
*Derived here* (the stops' geometry; not from a book): measured in a fixed frame,
counter-clockwise ahead, the eccentric's centre is at the crank's angle plus
``90 deg + delta_f`` ahead and at the crank's angle less ``90 deg + delta_b`` astern,
so the shaft turns backward through::

    slip = 180 deg - delta_f - delta_b

inside the sheave between the two drives: the angle between the stops, as the pin
sees it (:attr:`SlipEccentricSpec.slip_rad`).  With equal advances the two directions
give the same valve events, the card is the same either way, and the engine is
symmetrical; a launch engine set for more advance ahead gives its early cut-off ahead
only.  The gear has no notch: the cut-off is the valve's, in either direction.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from corliss.keys import units
from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Key, group
from corliss.keys.toml_table import Table
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import (ADVANCE_RANGE_rad, ALLEN_KEYS, ECCENTRICITY,
                                        LAP_KEYS, PORT_KEYS, SlideValve, SlideValveSpec,
                                        parse_allen_passage, parse_ports)

#: The directions of rotation, by the ``direction`` key's values.
DIRECTIONS = ("ahead", "astern")


@dataclass(frozen=True)
class SlipEccentricSpec(SlideValveSpec):
    """A slide valve on a slip eccentric (all SI).

    The fields of :class:`~corliss.valves.slide_valve.SlideValveSpec`, with
    ``angular_advance_rad`` the advance the eccentric has in the direction it is
    running (``forward_advance_rad`` ahead, ``backward_advance_rad`` astern: the
    parser and :meth:`running` keep them so).

    Parameters
    ----------
    eccentricity_m : float
        Eccentric throw r [m].
    lap_m, exhaust_lap_m : tuple of float
        Steam and exhaust laps of the (head, crank) end [m].
    angular_advance_rad : float
        The advance of the stop that drives [rad].
    port_width_m, port_length_m : float
        The steam ports' width along the travel and length [m].
    discharge_coefficient : float, optional
        Of the port opening [-].
    eccentric_rod_m : float or None, optional
        Eccentric rod plus valve stem [m]; None for Zeuner's motion.
    connection, steam, setting : str, optional
        As the slide valve's (a slip eccentric drives its valve directly, steam
        outside, set for equal lead).
    ports_per_end : int, optional
        Openings each edge uncovers.
    allen_passage_m : float or None, optional
        An Allen valve's passage [m]; None for a plain valve.
    forward_advance_rad : float
        Angular advance delta_f with the pin on the forward stop [rad].
    backward_advance_rad : float
        Angular advance delta_b with the pin on the backward stop [rad].
    direction : str
        ``"ahead"`` or ``"astern"``: which stop drives.
    """

    forward_advance_rad: float = 0.0
    backward_advance_rad: float = 0.0
    direction: str = "ahead"

    @property
    def slip_rad(self) -> float:
        """The angle the shaft turns backward inside the sheave between the two drives,
        ``pi - delta_f - delta_b`` (module doc) [rad]."""
        return math.pi - self.forward_advance_rad - self.backward_advance_rad

    def running(self, direction: str) -> "SlipEccentricSpec":
        """The same gear running ``direction``: the other stop driving after the slip.

        Parameters
        ----------
        direction : str
            ``"ahead"`` or ``"astern"``.

        Returns
        -------
        SlipEccentricSpec
            The spec with ``direction`` and the advance of that stop.

        Raises
        ------
        ValueError
            For a direction not in :data:`DIRECTIONS`.
        """
        if direction not in DIRECTIONS:
            raise ValueError(f"direction {direction!r}: one of {DIRECTIONS}")
        adv = self.forward_advance_rad if direction == "ahead" else self.backward_advance_rad
        return dataclasses.replace(self, direction=direction, angular_advance_rad=adv)


class SlipEccentric(SlideValve):
    """A plain slide valve on a slip eccentric, running in the spec's direction.

    In its direction of rotation the valve moves as a plain slide valve with that
    stop's advance (module doc), so the travel, the events, the Zeuner and Bilgram
    diagrams, the card and the drawn eccentric are the slide valve's;
    :meth:`reversed` is the gear after the slip.

    Parameters
    ----------
    spec : SlipEccentricSpec
        The valve, its eccentric, its two stops and the direction it runs.
    """

    name = "slip_eccentric"
    spec: SlipEccentricSpec
    summary = ("plain slide valve on a slip eccentric with forward and backward stops; "
               "reversed by running backward until the eccentric slips")

    def reversed(self) -> "SlipEccentric":
        """The gear after the engine is run backward through the slip.

        Returns
        -------
        SlipEccentric
            The gear running the other way, driven by the other stop.
        """
        other = "astern" if self.spec.direction == "ahead" else "ahead"
        return SlipEccentric(self.spec.running(other))


SLIP_ECCENTRIC_KEYS = group(
    "slip_eccentric", "A plain slide valve on a slip eccentric (two stops, no link).",
    ECCENTRICITY, LAP_KEYS,
    Key("forward_advance", "angle", "Angular advance with the pin on the forward stop, "
        "between -90 and 90 deg.", within=ADVANCE_RANGE_rad, unit="deg"),
    Key("backward_advance", "angle", "Angular advance with the pin on the backward stop, "
        "between -90 and 90 deg; absent: the forward advance (a symmetrical engine).",
        default=None, within=ADVANCE_RANGE_rad, unit="deg"),
    Key("direction", "choice", "Which way the engine runs, and so which stop drives "
        "(astern: after running backward through the slip).", default="ahead",
        choices=DIRECTIONS),
    Key("eccentric_rod", "length", "Eccentric rod plus valve stem, longer than the "
        "eccentricity; absent: the Zeuner (infinite rod) motion.", default=None,
        within=POSITIVE_LENGTH, unit="in"),
    ALLEN_KEYS, PORT_KEYS,
)


def parse_slip_eccentric(t: Table) -> SlipEccentricSpec:
    """Read a ``[valve_gear] type = "slip_eccentric"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`SLIP_ECCENTRIC_KEYS`.

    Returns
    -------
    SlipEccentricSpec
        The gear's spec, running in its ``direction``.
    """
    t = t.bound(SLIP_ECCENTRIC_KEYS)
    r = t.get("eccentricity")
    lap = t.get("lap")
    for end, l in zip(("head", "crank"), lap):
        if l >= r:
            raise InputError(t.key("lap"), t.raw("lap"),
                             f"a lap smaller than the eccentricity ({r / units.INCH_m:.4g} in): "
                             f"with lap >= eccentricity the {end}-end steam port never opens")
    exhaust_lap = t.get("exhaust_lap")
    for end, e in zip(("head", "crank"), exhaust_lap):
        if e >= r:
            raise InputError(t.key("exhaust_lap"), t.raw("exhaust_lap"),
                             "an exhaust lap smaller than the eccentricity: the "
                             f"{end}-end exhaust would never open")
    fwd = t.get("forward_advance")
    back = t.get("backward_advance") if t.has("backward_advance") else fwd
    for key, v in (("forward_advance", fwd), ("backward_advance", back)):
        if not -math.pi / 2 < v < math.pi / 2:
            raise InputError(t.key(key), t.raw(key), "an angle between -90 deg and 90 deg")
    g = t.get("eccentric_rod")
    if g is not None and g <= r:
        raise InputError(t.key("eccentric_rod"), t.raw("eccentric_rod"),
                         "an eccentric rod longer than the eccentricity")
    spec = SlipEccentricSpec(
        eccentricity_m=r, lap_m=lap, exhaust_lap_m=exhaust_lap, angular_advance_rad=fwd,
        eccentric_rod_m=g, allen_passage_m=parse_allen_passage(t),
        forward_advance_rad=fwd, backward_advance_rad=back, **parse_ports(t))
    return spec.running(t.get("direction"))


register(GearType("slip_eccentric", SlipEccentric.summary, parse_slip_eccentric,
                  SlipEccentric, SLIP_ECCENTRIC_KEYS))
