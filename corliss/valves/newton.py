"""Newton's method for the two unknowns of a linkage, at every crank angle at once."""

from __future__ import annotations

import numpy as np


def newton2(residual, x, y, hx: float, hy: float, tol_x: float, tol_y: float,
            iterations: int = 40):
    """Solve ``residual(x, y) = (0, 0)`` elementwise over arrays of crank angles.

    The Jacobian is taken by forward differences with steps ``hx`` and ``hy``; the
    iteration stops when every step is below ``tol_x`` and ``tol_y``, or after
    ``iterations`` steps (no error is raised: the caller checks the residual if it
    must).

    Parameters
    ----------
    residual : callable
        ``residual(x, y) -> (r1, r2)``, arrays of the shape of ``x``, zero at the
        solution; evaluated three times a step.
    x, y : ndarray
        Starting values of the two unknowns (in the linkage's own units, an angle
        [rad] or a length [m]), one per crank angle.
    hx, hy : float
        Forward-difference steps of ``x`` and ``y``, in their units.
    tol_x, tol_y : float
        Largest step of ``x`` and ``y`` at which the iteration stops, in their units.
    iterations : int, optional
        Most Newton steps.

    Returns
    -------
    x, y : ndarray
        The solution, of the shape of the starting values.
    """
    for _ in range(iterations):
        r1, r2 = residual(x, y)
        p1, p2 = residual(x + hx, y)
        q1, q2 = residual(x, y + hy)
        j11, j21, j12, j22 = (p1 - r1) / hx, (p2 - r2) / hx, (q1 - r1) / hy, (q2 - r2) / hy
        det = j11 * j22 - j12 * j21
        dx = (-r1 * j22 + r2 * j12) / det
        dy = (-j11 * r2 + j21 * r1) / det
        x, y = x + dx, y + dy
        if np.max(np.abs(dx)) < tol_x and np.max(np.abs(dy)) < tol_y:
            break
    return x, y
