"""Leakage past a valve or piston as the period measured it: a flow proportional to
the pressure difference.

The measurements
----------------
H. L. Callendar and J. T. Nicolson (Min. Proc. ICE 131, 1897-98; read in Fr.
Freytag's report, Dinglers Polytechnisches Journal 312, 1899, pp. 163-164) measured
the leak of a flat slide valve apart from the cylinder's condensation: the piston
out, the steam ports blocked, the valve driven by a motor, the steam that passed from
the chest straight to the exhaust condensed and weighed: 51 kg in 25 min at 6.4
kg/cm2 gauge, 144 kg in 66.5 min at 5.6 kg/cm2 gauge (1.35 and 1.63 kg/h per lbf/in2
of difference).  Their law: the loss "is proportional to the difference of the
pressures on the two sides of the valve", a constant for the valve, "the rate of leak
of the valve", times that difference, 1.36 kg per hour (3 lb per hour per lbf/in2:
:data:`CALLENDAR_NICOLSON_RATE_KG_S_PA`); independent of speed; tight with the valve
standing; mostly water: "the quantity of water through a narrow gap ... is
proportional to the difference of the pressures on the two sides of the valve and to
the perimeter of the port's opening, and falls with the width of the valve's working
faces"; the water a pressure difference drives through a gap 20 to 50 times the steam
that would pass.  The Steam-Engine Research Committee of the IMechE (Capper, 1905;
in Lineham, A Text-Book of Mechanical Engineering, App. VI) found the same: leakage
nearly independent of the sliding speed, proportional to the pressure difference and
inversely to the lap, over 20 % of the steam supplied; Lineham (p. 884): "leakage may
be responsible for from 5 to 50 % of the total loss".

The law (:func:`leak_flow_kg_s`)
--------------------------------
``m = R dp (l / l_ref) (w_ref / w)`` [kg/s], with ``R`` the rate of leak [kg/(s Pa)]
measured on a valve of opening perimeter ``l_ref`` and face width (lap) ``w_ref``:
linear in the difference (the measurements' law, not an orifice's square root: a
film of water dragged through a gap by the pressure, a viscous flow), the length
scaling as Callendar and Nicolson's "perimeter of the port's opening", the width
inversely as Capper's "inversely to the lap".
"""

from __future__ import annotations

from typing import NamedTuple

from numba import njit

#: One pound-force per square inch [Pa] and one hour [s].
PSI_PA = 6894.757293168361
HOUR_S = 3600.0
#: Callendar and Nicolson's rate of leak of their flat slide valve, 1.36 kg per hour per
#: lbf/in2 of difference (3 lb/h per psi; DPJ 312, 1899, p. 163) [kg/(s Pa)].
CALLENDAR_NICOLSON_RATE_KG_S_PA = 1.36 / HOUR_S / PSI_PA
#: One technical atmosphere, kg/cm2 [Pa].
AT_PA = 98066.5


class LeakTest(NamedTuple):
    """A leak the period measured apart from condensation.

    Parameters
    ----------
    what : str
        The path and how the test was made.
    mass_kg : float
        Water and steam collected [kg].
    duration_s : float
        Over this time [s].
    dp_Pa : float
        The pressure difference across the path [Pa].
    source : str
        Author, year, and where it was read.
    """

    what: str
    mass_kg: float
    duration_s: float
    dp_Pa: float
    source: str


#: The leak tests of Callendar and Nicolson (DPJ 312, 1899, pp. 163-164).  The chest's
#: pressures are gauge (the report's "Manometerspannung"), the exhaust at atmosphere, so
#: the gauge pressure is the difference.
CALLENDAR_NICOLSON_TESTS = (
    LeakTest("flat slide valve, ports blocked, piston out, valve driven: chest to exhaust",
             51.0, 25.0 * 60.0, 6.4 * AT_PA,
             "Callendar and Nicolson 1897, Min. Proc. ICE 131; DPJ 312 (1899) p. 163"),
    LeakTest("the same valve, later (its oil film worn, the report says)",
             144.0, 66.5 * 60.0, 5.6 * AT_PA,
             "Callendar and Nicolson 1897, Min. Proc. ICE 131; DPJ 312 (1899) p. 163"),
    LeakTest("quadruple-expansion engine, Montreal, HP valve: chest to exhaust, 1 h",
             17.3, HOUR_S, 4.6 * AT_PA,
             "Callendar and Nicolson 1897, Min. Proc. ICE 131; DPJ 312 (1899) p. 163"),
    LeakTest("the same engine, LP valve (tight with the engine standing), 1 h",
             18.6, HOUR_S, 4.6 * AT_PA,
             "Callendar and Nicolson 1897, Min. Proc. ICE 131; DPJ 312 (1899) p. 163"),
)


@njit(cache=True)
def linear_leak(rate_kg_s_Pa: float, p_from_Pa: float, p_to_Pa: float) -> float:
    """The law itself, compiled for the engine's kernels: ``R (p_from - p_to)``.

    Parameters
    ----------
    rate_kg_s_Pa : float
        The path's rate of leak [kg/(s Pa)].
    p_from_Pa, p_to_Pa : float
        Pressures on the two sides [Pa].

    Returns
    -------
    float
        The flow [kg/s] from ``p_from`` to ``p_to`` (negative the other way).
    """
    return rate_kg_s_Pa * (p_from_Pa - p_to_Pa)


def rate_of_leak_kg_s_Pa(mass_kg: float, duration_s: float, dp_Pa: float) -> float:
    """The rate of leak a test gives: the flow per unit of pressure difference.

    Parameters
    ----------
    mass_kg : float
        Water and steam collected [kg].
    duration_s : float
        Over this time [s].
    dp_Pa : float
        The pressure difference across the leak [Pa].

    Returns
    -------
    float
        The rate of leak [kg/(s Pa)].

    Raises
    ------
    ValueError
        Where the duration or the difference is not positive.
    """
    if duration_s <= 0.0 or dp_Pa <= 0.0:
        raise ValueError(f"rate_of_leak_kg_s_Pa: duration_s={duration_s!r} and "
                         f"dp_Pa={dp_Pa!r} must be positive")
    return mass_kg / duration_s / dp_Pa


def leak_flow_kg_s(p_from_Pa: float, p_to_Pa: float, rate_kg_s_Pa: float,
                   opening_m: float = 1.0, opening_ref_m: float = 1.0,
                   face_m: float = 1.0, face_ref_m: float = 1.0) -> float:
    """The leak from one side to the other by Callendar and Nicolson's law (module
    docstring): ``R (p_from - p_to) (l / l_ref) (w_ref / w)``.

    Parameters
    ----------
    p_from_Pa, p_to_Pa : float
        Pressures on the two sides [Pa]; the flow is negative where ``p_to_Pa`` is the
        higher.
    rate_kg_s_Pa : float
        The rate of leak measured on the reference valve [kg/(s Pa)].
    opening_m, opening_ref_m : float
        The perimeter of this port's opening and of the reference's [m].
    face_m, face_ref_m : float
        The width of this valve's faces (its lap) and of the reference's [m].

    Returns
    -------
    float
        The flow [kg/s], from ``p_from`` to ``p_to``.

    Raises
    ------
    ValueError
        For a negative rate or a length or width that is not positive.
    """
    if rate_kg_s_Pa < 0.0 or min(opening_m, opening_ref_m, face_m, face_ref_m) <= 0.0:
        raise ValueError(f"leak_flow_kg_s: rate_kg_s_Pa={rate_kg_s_Pa!r} must be zero or "
                         "more and the lengths and widths positive")
    return linear_leak(rate_kg_s_Pa * (opening_m / opening_ref_m) * (face_ref_m / face_m),
                       p_from_Pa, p_to_Pa)
