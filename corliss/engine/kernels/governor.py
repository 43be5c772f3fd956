"""The governor's equation of motion, written once: the compiled speed loop
(:func:`corliss.engine.kernels.loop.transient_rhs`) and the mean-value model
(:func:`corliss.engine.mean_value.run_mean_value`, its Python form
``governor_motion.py_func``) both call :func:`governor_motion`.

The common form of :mod:`corliss.governors` (spindle speed ``w_g = ratio omega``)::

    M(z) z'' + 1/2 M'(z) z'^2 = G(z) w_g^2 - R(z) - c z' - F_f sat(z'/v_e) - J(z) dw_g/dt

Coulomb friction is regularised over a creep speed v_e
(:data:`corliss.governors.mechanism.CREEP_PER_S`); the stops at z = 0 and z = 1 are
inelastic: no acceleration, and no velocity, into a stop.  How M, M', G, R and J are
read from their tables at z is each caller's own (the loop's uniform grid, the
mean-value model's ``numpy.interp``).
"""

from __future__ import annotations

from corliss.engine.kernels.compiled import njit


@njit(cache=True, inline="always")
def governor_motion(z, zd, M, dM, G, R, J, ratio, damping, friction, creep, omega, wdot):
    """The governor's velocity and acceleration, its stops applied.

    Parameters
    ----------
    z : float
        The governor's coordinate [-], 0 to 1 (may stand past a stop within a step).
    zd : float
        dz/dt [1/s].
    M, dM, G, R, J : float
        The common form's coefficients at ``z`` clipped to [0, 1]: mass M [kg], dM/dz
        [kg], G [kg/rad2], R [N], J [kg/rad] (their units with z a length of 1).
    ratio : float
        Spindle speed per shaft speed [-].
    damping : float
        The dashpot's coefficient c [N s].
    friction : float
        Coulomb friction F_f [N].
    creep : float
        The creep speed v_e over which friction is regularised [1/s].
    omega : float
        Shaft speed [rad/s].
    wdot : float
        d omega/dt [rad/s2].

    Returns
    -------
    zd : float
        dz/dt [1/s], 0 against a stop.
    zdd : float
        d2z/dt2 [1/s2], 0 against a stop.
    """
    wg = ratio * omega
    v = zd / creep
    if v > 1.0:
        v = 1.0
    if v < -1.0:
        v = -1.0
    force = (G * wg * wg - R - damping * zd - friction * v
             - J * ratio * wdot - 0.5 * dM * zd * zd)
    zdd = force / M
    if (z <= 0.0 and zdd < 0.0 and zd <= 0.0) or (z >= 1.0 and zdd > 0.0 and zd >= 0.0):
        zdd = 0.0
        zd = 0.0
    return zd, zdd
