"""A slide valve's travel over an array of crank angles in one compiled loop.

:meth:`corliss.valves.slide_valve.SlideValve.travel` on a turn's samples (7201 a
tabulation) took eleven numpy passes, each making or rewriting an array; this loop takes
one, with the same operations in the same order on each angle: IEEE additions,
subtractions, multiplications and square roots (each correctly rounded; numba contracts
no multiply-add without ``fastmath``) and the C library's ``sin`` and ``cos``, the
functions numpy's ``np.sin`` and ``np.cos`` call for float64 (the same bits: a test
compares them), so that every displacement is numpy's to the bit.  Compiled once and
kept in numba's disk cache (``cache=True``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True, error_model="numpy")
def eccentric_travel(theta: np.ndarray, advance: float, throw: float, rod: float,
                     rod_sq: float, shift: float, sigma: float,
                     has_rod: bool) -> np.ndarray:
    """The displacement of a valve on one eccentric, finite rod included [m].

    ``x = r sin(theta + delta) + sigma (g - sqrt(g**2 - (r cos(theta + delta))**2) -
    shift)`` (Spangler Art. 13), each term taken as
    :meth:`~corliss.valves.slide_valve.SlideValve.travel` takes it on arrays; without a
    rod, ``r sin(theta + delta)``.

    Parameters
    ----------
    theta : ndarray
        Crank angles [rad], shape ``(n,)``.
    advance : float
        Angular advance delta [rad].
    throw : float
        Eccentricity r [m].
    rod, rod_sq : float
        Eccentric rod g [m] and its square as Python finds ``g * g`` [m2].
    shift : float
        Subtracted from the rod's shortfall (the equal-lead setting's shortfall at
        dead centre; 0 subtracts nothing) [m].
    sigma : float
        Sign of the shortfall; 1 multiplies by nothing [-].
    has_rod : bool
        Whether the rod is finite.

    Returns
    -------
    ndarray
        Displacement [m], shape ``(n,)``.
    """
    out = np.empty(theta.size)
    for k in range(theta.size):
        phase = theta[k] + advance
        x = math.sin(phase) * throw
        if has_rod:
            short = math.cos(phase) * throw
            short = short * short
            short = rod_sq - short
            short = math.sqrt(short)
            short = rod - short
            if shift != 0.0:
                short = short - shift
            if sigma != 1.0:
                short = short * sigma
            x = x + short
        out[k] = x
    return out


@njit(cache=True, error_model="numpy")
def eccentric_signed(theta: np.ndarray, advance: float, throw: float, rod: float,
                     rod_sq: float, shift: float, sigma: float, has_rod: bool,
                     laps: np.ndarray) -> np.ndarray:
    """The four ports' signed openings of a lapped valve on one eccentric [m]:
    ``x - lap_head``, ``-x - exhaust_lap_head``, ``-x - lap_crank``, ``x -
    exhaust_lap_crank``, ``x`` as :func:`eccentric_travel` finds it.

    Parameters
    ----------
    theta, advance, throw, rod, rod_sq, shift, sigma, has_rod
        As :func:`eccentric_travel`.
    laps : ndarray
        Head steam lap, head exhaust lap, crank steam lap, crank exhaust lap [m],
        shape ``(4,)``.

    Returns
    -------
    ndarray
        Signed openings [m], shape ``(4, n)``, in the order of
        :data:`corliss.valves.gear.PORTS`.
    """
    x = eccentric_travel(theta, advance, throw, rod, rod_sq, shift, sigma, has_rod)
    out = np.empty((4, theta.size))
    for k in range(theta.size):
        out[0, k] = x[k] - laps[0]
        out[1, k] = -x[k] - laps[1]
        out[2, k] = -x[k] - laps[2]
        out[3, k] = x[k] - laps[3]
    return out
