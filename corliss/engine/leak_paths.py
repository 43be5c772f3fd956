"""How much of a valve's measured rate of leak each of a gear's edges carries.

Callendar and Nicolson (Min. Proc. ICE 131, 1897-98; Freytag's report, Dinglers
Polytechnisches Journal 312, 1899, p. 164) found the water a valve leaks
"proportional to the difference of the pressures on the two sides of the valve and
to the perimeter of the port's opening", falling as the valve's working faces get
wider; the IMechE Steam-Engine Research Committee (Capper, 1905; Lineham, A Text-Book
of Mechanical Engineering, App. VI) "inversely to the lap".  A scene gives each
path's rate of leak as measured on a reference valve, whose port is
:data:`REFERENCE_PORT_LENGTH_M` long and whose faces cover a closed port by
:data:`REFERENCE_FACE_WIDTH_M`; an edge of the scene's gear leaks that rate times
``(l / l_ref) (w_ref / w)`` (:func:`corliss.thermo.leak_law.leak_flow_kg_s`).

``l`` is the gear's effective port length (:meth:`ValveGear.port_lengths`: the port's
length across the valve times its number of openings, the length of the opening's
edge).  ``w`` is how far the valve's face covers the port while the edge is closed,
taken as its mean over the closed part of the turn: the negative of the gear's
signed opening (:meth:`ValveGear.signed_openings`), which is the lap at the valve's
mid travel and the lap plus the travel beyond it elsewhere.  The lap itself would
do for a valve whose lap is its seal (Capper's wording), but gives no width for a
zero or negative lap (an exhaust edge "line and line" or with clearance), which
still seals while it is closed; the mean overlap grows with the lap as Capper's
law asks and stays finite for every edge that closes.

The reference is the valve of the bundled ``callendar-nicolson-single-acting``
scene (8 in ports; its head end's steam edge covered by 2.11 in on the mean while
closed), the engine Callendar and Nicolson measured 3 lb/h per lbf/in2 on (their
valve's own dimensions are not in the report; the scene's are a plain slide valve
set to their cut-off): a scene of that engine leaks the rate it names.

A governor that moves the gear's setting moves both ``l`` (a gear whose opening's
edge changes with it) and ``w`` (the valve's travel): a governed transient run takes
each turn the scales at the setting it starts at (:func:`setting_leak_scales`).
"""

from __future__ import annotations

import numpy as np

from corliss.engine.setting_table import SettingTable

#: Length of the reference valve's port opening, 8 in [m] (module docstring).
REFERENCE_PORT_LENGTH_M = 8.0 * 0.0254
#: Mean width by which the reference valve's face covers its closed steam port,
#: 2.11 in [m] (module docstring; ``tests/test_leak_paths.py`` finds it on the
#: bundled scene's gear).
REFERENCE_FACE_WIDTH_M = 2.11 * 0.0254
#: Crank angles over a turn at which a gear's overlaps are sampled [rad].
_THETA = np.linspace(0.0, 2.0 * np.pi, 1441)[:-1]


def closed_face_widths_m(gear) -> np.ndarray:
    """Mean width by which the valve's face covers each port while it is closed.

    Parameters
    ----------
    gear : ValveGear
        The gear, at its setting.

    Returns
    -------
    ndarray
        For each port in :data:`~corliss.valves.gear.PORTS` order, the mean of the
        negative signed opening over the crank angles where it is negative [m], shape
        ``(4,)``; NaN for a port the gear never closes.
    """
    s = np.asarray(gear.signed_openings(_THETA), dtype=float)
    out = np.full(4, np.nan)
    for p in range(4):
        shut = s[p] < 0.0
        if shut.any():
            out[p] = float(np.mean(-s[p][shut]))
    return out


def edge_leak_scales(gear) -> np.ndarray:
    """The factor by which each of a gear's edges leaks the reference valve's rate.

    Parameters
    ----------
    gear : ValveGear
        The gear, at its setting.

    Returns
    -------
    ndarray
        ``(l / l_ref) (w_ref / w)`` for each port in :data:`~corliss.valves.gear.PORTS`
        order [-], shape ``(4,)`` (module docstring); 0 for a port the gear never
        closes (it has no closed edge to leak past).
    """
    w = closed_face_widths_m(gear)
    length = np.asarray(gear.port_lengths(), dtype=float)
    scale = (length / REFERENCE_PORT_LENGTH_M) * (REFERENCE_FACE_WIDTH_M / w)
    return np.where(np.isfinite(scale), scale, 0.0)


def setting_leak_scales(gear, settings) -> SettingTable:
    """A governed gear's edge scales (:func:`edge_leak_scales`) over its settings:
    found at each of the loop's tabulated settings when first needed (each costs the
    gear's openings over a turn) and read linearly between them, as the loop reads its
    port areas over the same grid (clamped to the grid's ends).

    Parameters
    ----------
    gear : ValveGear
        The governed gear.
    settings : ndarray
        The settings tabulated [-], increasing (the loop's setting grid).

    Returns
    -------
    SettingTable
        ``(l / l_ref) (w_ref / w)`` for each port in :data:`~corliss.valves.gear.PORTS`
        order [-], shape ``(4,)``, at a setting.
    """
    return SettingTable(settings, lambda s: edge_leak_scales(gear.with_setting(s)))
