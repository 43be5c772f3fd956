"""Where a governed engine runs steadily under a load: its operating point.

A governed engine is in equilibrium when two balances hold at once:

* the governor's: at shaft speed omega it rests at the coordinate z where the
  centrifugal force balances gravity and springs, G(z) (r omega)^2 = R(z), i.e.
  omega = omega_eq(z), its static characteristic (Marks Art. 70; Spangler Art. 155);
* the shaft's: over a turn the indicated work equals the work of the load and of
  friction, so the mean surplus torque S = T_ind - T_friction - T_load is zero.

Along the static characteristic both speed and setting are functions of z, so the
operating point is the root of one function of one variable, S(omega_eq(z), z), on the
governor's working travel [z_lo, 1] (z_lo the top of the safety range, or 0).  S falls
as z rises (the governor shuts off steam as it lifts): at the bottom of the travel the
engine has its most steam and should have a surplus; at the top a deficit.  When it
does not, there is no operating point in the governor's range, and the result says
which way the engine will go (the load is too heavy for the engine with the governor
down, or too light to pull the speed into the governor's range).

The surplus comes from the caller (the crank-resolved loop run turns with speed and
governor held; the mean-value model reads its maps), so this module knows neither.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

#: The operating point is found when the surplus torque is below this fraction of the
#: load torque (0.01 %: a speed error of well under 0.01 % on a governor of a few per
#: cent droop), or the bracket on z is narrower than ``Z_TOL``.
SURPLUS_TOL = 1e-4
Z_TOL = 1e-7
MAX_EVALUATIONS = 40

BALANCED, LOAD_TOO_HEAVY, LOAD_TOO_LIGHT = "balanced", "load_too_heavy", "load_too_light"


@dataclass(frozen=True)
class OperatingPoint:
    """The state a governed run starts from.

    Parameters
    ----------
    speed_rad_s : float
        Shaft speed [rad/s].
    governor_z : float
        Governor coordinate [-].
    surplus_N_m : float
        The mean surplus torque left at that point [N m] (the solve's residual).
    status : str
        ``"balanced"``; or ``"load_too_heavy"`` (even with the governor down the engine
        cannot carry the load: it will slow below the governor's range) or
        ``"load_too_light"`` (with the governor at its top stop the engine still gains
        speed), in which case the point is the end of the travel nearest the balance.
    evaluations : int
        Surplus evaluations the solve took.
    """

    speed_rad_s: float
    governor_z: float
    surplus_N_m: float
    status: str
    evaluations: int


def characteristic_speed(mech, z: float) -> float:
    """The governor's static characteristic: the shaft speed at which it balances at ``z``.

    Without friction, ``G(z) (ratio omega)^2 = R(z)``, so ``omega = sqrt(R / G) /
    ratio`` (Marks Art. 70), interpolated linearly on the governor's z grid.

    Parameters
    ----------
    mech : GovernorMechanism
        The governor, tabulated: ``z``, ``G``, ``R`` on its grid and the ``ratio`` of
        governor to shaft speed.
    z : float
        Governor coordinate [-], 0 at the bottom stop, 1 at the top.

    Returns
    -------
    float
        The shaft speed [rad/s].
    """
    w = np.sqrt(np.asarray(mech.R) / np.asarray(mech.G)) / mech.ratio
    return float(np.interp(z, mech.z, w))


def working_travel(mech) -> tuple[float, float]:
    """The governor's travel in which it governs.

    Above its safety range, if it has one (there the cams hold the steam valves shut),
    up to the top stop.

    Parameters
    ----------
    mech : GovernorMechanism
        The governor, tabulated (``safety_z`` and ``actuator_safety``).

    Returns
    -------
    z_lo : float
        The bottom of the working travel [-]: the top of the safety range, or 0.
    z_hi : float
        The top stop, 1 [-].
    """
    lo = mech.safety_z if mech.safety_z > 0.0 and math.isfinite(mech.actuator_safety) else 0.0
    return float(lo), 1.0


def find_operating_point(surplus: Callable[[float, float], float], mech,
                         load_torque_N_m: float) -> OperatingPoint:
    """Solve for the governed operating point on the static characteristic.

    Parameters
    ----------
    surplus : callable
        ``surplus(omega [rad/s], z [-])`` -> mean surplus torque [N m] of the engine run
        steadily at that speed with the governor held at z.
    mech : GovernorMechanism
        The governor, tabulated.
    load_torque_N_m : float
        The load torque at the start [N m] (the scale of the tolerance).

    Returns
    -------
    OperatingPoint
        Found by the Illinois variant of regula falsi on z (bracketing, so it cannot
        leave the travel, and superlinear on a smooth surplus).
    """
    tol = SURPLUS_TOL * max(abs(load_torque_N_m), 1e-9)
    z_lo, z_hi = working_travel(mech)
    # just above the safety range the actuator is the governor's own, not the cams'
    z_lo = min(z_lo + 1e-9 if z_lo > 0.0 else z_lo, z_hi)
    n = 0

    def f(z):
        nonlocal n
        n += 1
        return surplus(characteristic_speed(mech, z), z)

    f_lo = f(z_lo)
    if f_lo <= 0.0:
        return OperatingPoint(characteristic_speed(mech, z_lo), float(z_lo), float(f_lo), LOAD_TOO_HEAVY, n)
    f_hi = f(z_hi)
    if f_hi >= 0.0:
        return OperatingPoint(characteristic_speed(mech, z_hi), float(z_hi), float(f_hi), LOAD_TOO_LIGHT, n)
    a, fa, b, fb = z_lo, f_lo, z_hi, f_hi
    side = 0
    z, fz = a, fa
    while n < MAX_EVALUATIONS:
        z = (a * fb - b * fa) / (fb - fa)
        fz = f(z)
        if abs(fz) <= tol or b - a <= Z_TOL:
            break
        if fz > 0.0:
            a, fa = z, fz
            if side == 1:
                fb *= 0.5
            side = 1
        else:
            b, fb = z, fz
            if side == -1:
                fa *= 0.5
            side = -1
    return OperatingPoint(characteristic_speed(mech, z), float(z), float(fz), BALANCED, n)
