"""Valve gears: kinematics -> valve travel -> port areas (PortMap) and events."""

from corliss.valves import baker, buckeye, corliss_gear, fink_motion, gridiron, link_motion, meyer, oscillating, polonceau, radial_gear, shaft_governor, slide_valve, slip_eccentric  # noqa: F401  (register)
from corliss.valves.events import events
from corliss.valves.gear import GEARS, PORTS, ValveGear, gear_type
from corliss.valves.portmap import PortMap, tabulate

__all__ = ["GEARS", "PORTS", "PortMap", "ValveGear", "events", "gear_type", "tabulate"]
