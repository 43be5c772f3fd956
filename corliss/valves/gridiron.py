"""The gridiron (Gonzenbach) valve: a cut-off valve on its own seat controls the
admission to the main valve's chest (Spangler Chap. XV, Arts. 115-126).

The main valve is a plain D slide on its eccentric (r, delta); the cut-off valve on
another (r1, delta1), "generally" of negative advance (Art. 118)::

    x = r sin(theta + delta),        x1 = r1 sin(theta + delta1)          (Art. 13, eq. 4)

With ``e`` the width of the port in the cut-off valve's seat and ``f`` that in the
valve, centred over each other in its middle position, the cut-off valve closes when
displaced ``s = (e + f)/2`` either way, begins to close at ``(f - e)/2`` and is wide
open again at ``x1 = (f - e)/2`` (Arts. 118, 121): it is open by ``s - |x1|`` to the
chest, which feeds both ends.  On the book's combined diagram (Arts. 118-119) the
cut-off valve must close (E) between the main valve's admission A and cut-off B, and
open again (F) between B and the other end's admission C, "otherwise steam would be
admitted twice during one stroke".

Varying the cut-off (Arts. 123-124): with the advance fixed, a greater throw r1 cuts
off earlier, down to the throw at which the cut-off valve's circle passes through the
other end's admission; a smaller throw cuts off later, until the re-opening comes
before the main valve's cut-off.  The arrangement of Art. 124 drives the cut-off valve
through a reverse lever hij whose end h is moved along an arc, changing the travel "in
the proportion of ih to ij".  That ratio is the setting here: ``lever_ratio = [lo,
hi]`` is ih/ij at the two ends of h's arc and the setting 0..1 runs between them; the
cut-off valve's throw is r1 times the ratio, its advance (as drawn in the diagram, the
reverse lever already accounted for) ``cutoff_angular_advance``.

``motion = "exact"``: both eccentric rods of finite length (the cut-off valve's taken
through the reverse lever, so its rod shortfall enters reversed and scaled by the
lever's ratio), each valve set for equal lead.
"""

from __future__ import annotations

from dataclasses import dataclass

from corliss.errors import InputError
from corliss.keys.declared import POSITIVE_LENGTH, Derived, Key, group
from corliss.keys.toml_table import Table
from corliss.valves import double_valve as dv
from corliss.valves.gear import GearType, register
from corliss.valves.slide_valve import ANGULAR_ADVANCE, ECCENTRICITY


@dataclass(frozen=True)
class GridironSpec:
    """A gridiron valve (all SI; Spangler Arts. 115-126).

    Parameters
    ----------
    main : MainValveSpec
        The main valve's laps and ports.
    cutoff : CutoffSpec
        The cut-off valve's seat ports (``kind = "seat"``): ``lap_m`` is
        ``s = (e + f)/2`` for both ends, ``passage_width_m`` is e.
    eccentricity_m : float
        Main eccentric's throw r [m].
    angular_advance_rad : float
        Main eccentric's angular advance delta [rad].
    cutoff_eccentricity_m : float
        The cut-off eccentric's throw r1 [m], before the reverse lever.
    cutoff_angular_advance_rad : float
        The cut-off valve's advance delta1 [rad] as drawn in the diagram (the
        reverse lever already accounted for).
    valve_port_width_m : float
        f, the width of the ports in the cut-off valve [m].
    lever_ratio : tuple of float, optional
        ih/ij at setting 0 and at setting 1 [-] (Art. 124).
    setting : float, optional
        Position of h along its arc, 0..1 [-].
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
    valve_port_width_m: float
    lever_ratio: tuple[float, float] = (1.0, 1.0)
    setting: float = 0.0
    motion: str = "zeuner"
    eccentric_rod_m: float | None = None
    cutoff_eccentric_rod_m: float | None = None

    @property
    def ratio(self) -> float:
        """The reverse lever's ratio ih/ij at this setting, linear between the two
        ends of ``lever_ratio`` (Art. 124).

        Returns
        -------
        float
            ih/ij [-].
        """
        lo, hi = self.lever_ratio
        return lo + self.setting * (hi - lo)

    @property
    def cutoff_throw_m(self) -> float:
        """The cut-off valve's half travel at this setting, ``r1 ih/ij`` (Art. 124).

        Returns
        -------
        float
            Half travel [m].
        """
        return self.cutoff_eccentricity_m * self.ratio


class GridironValve(dv.DoubleValve):
    """Gridiron (Gonzenbach) valve: cut-off valve on its own seat over the main chest.

    Its setting is the position of h on the reverse lever's arc, 0..1.

    Parameters
    ----------
    spec : GridironSpec
        The valves, their eccentrics and the reverse lever.
    """

    name = "gridiron"
    summary = ("gridiron (Gonzenbach) valve: cut-off valve on its own seat over the main "
               "valve's chest, travel varied through a reverse lever (Spangler Arts. 115-126); "
               "setting = lever position 0..1")
    setting_name = "position of h on the reverse lever (0: ratio lo, 1: ratio hi; Art. 124)"
    setting_range = (0.0, 1.0)

    def __init__(self, spec: GridironSpec):
        self.spec = spec

    def main_travel(self, theta):
        s = self.spec
        return dv.eccentric_travel(theta, s.eccentricity_m, s.angular_advance_rad,
                                   s.eccentric_rod_m)

    def cutoff_travel(self, theta):
        s = self.spec
        x = dv.eccentric_travel(theta, s.cutoff_eccentricity_m, s.cutoff_angular_advance_rad,
                                s.cutoff_eccentric_rod_m, sign=-1)
        return s.ratio * x


#: The reverse lever's ratio ih/ij: a lever's proportion, a few times either way (the
#: bundled gridiron scene's runs from 0.6 to 1), never orders of magnitude.
LEVER_RATIO = (0.05, 20.0)


GRIDIRON_KEYS = group(
    "gridiron", "A gridiron cut-off valve on a seat on the back of the main valve.",
    ECCENTRICITY, ANGULAR_ADVANCE, dv.CUTOFF_ECCENTRIC_KEYS, dv.MAIN_KEYS,
    Key("seat_port_width", "length", "Width e of each port of the cut-off valve's seat.",
        within=POSITIVE_LENGTH, unit="in"),
    Key("valve_port_width", "length", "Width f of each port of the cut-off valve, at least "
        "e (Spangler Art. 121).", within=POSITIVE_LENGTH, unit="in"),
    Key("passage_length", "length", "Length of the seat's ports across the face.",
        default=Derived("the port length times ports_per_end"), within=POSITIVE_LENGTH,
        unit="in"),
    Key("lever_ratio", "number_pair", "[lo, hi]: the reverse lever's ratio ih/ij at the two "
        f"ends of h's arc, {LEVER_RATIO[0]:g} to {LEVER_RATIO[1]:g}.", default=[1.0, 1.0]),
    dv.setting_key(0.0, 1.0, "lever position"), dv.MOTION_KEYS,
)


def parse_gridiron(t: Table) -> GridironSpec:
    """Read a ``[valve_gear] type = "gridiron"`` table.

    Parameters
    ----------
    t : Table
        The table, bound to :data:`GRIDIRON_KEYS`.

    Returns
    -------
    GridironSpec
        The gear's spec.
    """
    t = t.bound(GRIDIRON_KEYS)
    main = dv.parse_main(t)
    r = t.get("eccentricity")
    r1 = t.get("cutoff_eccentricity")
    e = t.get("seat_port_width")
    f = t.get("valve_port_width")
    if f < e:
        raise InputError(t.key("valve_port_width"), t.raw("valve_port_width"),
                         "a valve port at least as wide as the seat port e (Art. 121: "
                         "the opening in the cut-off valve is usually greater)")
    length = (t.get("passage_length") if t.has("passage_length")
              else main.port_length_m * main.ports_per_end)
    raw = t.get("lever_ratio")
    if (not isinstance(raw, list) or len(raw) != 2
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                       and LEVER_RATIO[0] <= v <= LEVER_RATIO[1] for v in raw)):
        raise InputError(t.key("lever_ratio"), raw, "[lo, hi]: the reverse lever's ratio ih/ij "
                         f"at the two ends of h's arc, numbers from {LEVER_RATIO[0]:g} to "
                         f"{LEVER_RATIO[1]:g}")
    motion = t.get("motion")
    s = 0.5 * (e + f)
    return GridironSpec(main, dv.CutoffSpec("seat", (s, s), e, length), r,
                        t.get("angular_advance"), r1, t.get("cutoff_angular_advance"), f,
                        (float(raw[0]), float(raw[1])),
                        dv.check_setting(t, "setting", 0.0, 1.0, "lever position"), motion,
                        dv.rod(t, "eccentric_rod", r, motion),
                        dv.rod(t, "cutoff_eccentric_rod", r1, motion))


register(GearType("gridiron", GridironValve.summary, parse_gridiron,
                  lambda spec: dv.built(GridironValve(spec)), GRIDIRON_KEYS))
