"""The temperature cycle of a cylinder's wall under a condensing film: Callendar and
Nicolson's law, and the wall it calibrates.

The measurement
---------------
H. L. Callendar and J. T. Nicolson ("On the law of condensation of steam deduced from
measurements of temperature-cycles of the walls and steam in the cylinder of a steam
engine", Min. Proc. ICE 131, 1897-98; read in Fr. Freytag's report, Dinglers
Polytechnisches Journal 312, 1899, pp. 161-165) put thermo-junctions into the cast
iron of a single-acting 10.5 x 12 in engine (dry saturated steam, non-condensing, no
jacket, 43 to 102 rpm), at 0.25 to 16 mm under the surface, and read them to about
1/20 degC at any crank angle.  At 1 mm under the surface the iron swung 2.2 degC (73
rpm, 0.2 cut-off, steam 164.5 to 100 degC), 2.5 degC (77 rpm) and 3 to 6.5 degC (44
rpm, cover and barrel); from the swings at several depths they computed the
surface's: 6 degC at 77 rpm and 11.5 degC at 44 rpm (p. 162), the surface staying
about 15 degC below the steam late in admission (149 against 164 degC, p. 163).  Their
law (pp. 163-165): condensation is proportional to the temperature difference between
steam and wall, "re-evaporation apparently follows the same law", and on clean dry
surfaces the heat is 4 kcal per second, m2 and degC, 16.7 kW/(m2 K)
(:data:`CALLENDAR_NICOLSON_W_M2K`); the largest condensation seen, 23.74 kg of steam
per m2, hour and degC (p. 165), is 13.9 kW/(m2 K) with the latent heat at 150 degC.
They found cast iron's conductivity "about 30 % below the value assumed until then"
(p. 162).

The model (:func:`periodic_wall_cycle`)
---------------------------------------
A semi-infinite wall (one-dimensional conduction, :func:`periodic_wall_cycle` grids
it to several skin depths ``sqrt(2 alpha / omega)``, Carslaw and Jaeger, Conduction
of Heat in Solids, 2nd ed. 1959, sec. 2.6) under steam whose saturation temperature
``T_sat(t)`` is given over a cycle.  At the surface, per unit area:

* where the surface is below ``T_sat`` the steam condenses on it:
  ``q = h (T_sat - T_s)`` into the wall, the water ``q / L`` joining a film;
* where the surface is above ``T_sat`` and wet, the film boils off at the same
  coefficient ("re-evaporation follows the same law");
* where it is above and dry, only the steam's convection, ``h_dry (T - T_s)``, a few
  hundred W/(m2 K) (Hirn, through DPJ 278 pp. 538-539: once the water has gone, only
  an insignificant heat follows), with ``T`` the steam's temperature, taken as
  ``T_sat`` (the steam at the wall in the exhaust "takes nearly the walls'
  temperature", C&N p. 163, which this errs on the side of over-cooling).

The swing this gives at the surface and at any depth is set against Callendar and
Nicolson's in ``tests/test_wall_cycle.py``.
"""

from __future__ import annotations

import math

import numpy as np

#: Callendar and Nicolson's coefficient of condensation on clean dry cast iron, 4 kcal
#: per second, m2 and degC (DPJ 312, 1899, p. 164), in W/(m2 K): 4 x 4186.8.
CALLENDAR_NICOLSON_W_M2K = 4.0 * 4186.8
#: The largest condensation they saw: 23.74 kg of steam per m2, hour and degC (DPJ 312
#: p. 165) [kg/(m2 s K)]; times the latent heat, a coefficient (13.9 kW/(m2 K) at 150
#: degC, 2.114 MJ/kg).
CALLENDAR_NICOLSON_MAX_KG_M2SK = 23.74 / 3600.0
#: Grey cast iron: conductivity [W/(m K)], specific heat [J/(kg K)], density [kg/m3]
#: (makeitfrom.com, "Grey Cast Iron"; the engine's wall, :mod:`corliss.engine.wall`,
#: takes the same).
CAST_IRON_K, CAST_IRON_C, CAST_IRON_RHO = 46.0, 490.0, 7500.0
#: A dry surface's exchange with the steam [W/(m2 K)]: forced convection in a cylinder
#: (Adair, Qvale and Pearson's correlation gives a few hundred at these engines' gas
#: speeds and densities).
DRY_W_M2K = 300.0


def skin_depth_m(omega_rad_s: float, k: float = CAST_IRON_K, c: float = CAST_IRON_C,
                 rho: float = CAST_IRON_RHO) -> float:
    """Depth [m] at which a wave of angular frequency ``omega_rad_s`` falls to 1/e,
    ``sqrt(2 alpha / omega)`` (Carslaw & Jaeger sec. 2.6).

    Parameters
    ----------
    omega_rad_s : float
        The wave's angular frequency [rad/s].
    k, c, rho : float
        The wall's conductivity [W/(m K)], specific heat [J/(kg K)], density [kg/m3].

    Returns
    -------
    float
        The skin depth [m].
    """
    return math.sqrt(2.0 * k / (rho * c) / omega_rad_s)


def depth_attenuation(depth_m: float, omega_rad_s: float, k: float = CAST_IRON_K,
                      c: float = CAST_IRON_C, rho: float = CAST_IRON_RHO) -> float:
    """Ratio of a harmonic temperature wave's amplitude at ``depth_m`` to the
    surface's in a semi-infinite solid, ``exp(-depth / delta)`` (Carslaw & Jaeger sec.
    2.6): the ratio Callendar and Nicolson used to compute the surface's swing from
    their readings at depth.

    Parameters
    ----------
    depth_m : float
        Depth under the surface [m].
    omega_rad_s : float
        The wave's angular frequency [rad/s].
    k, c, rho : float
        The wall's conductivity [W/(m K)], specific heat [J/(kg K)], density [kg/m3].

    Returns
    -------
    float
        The amplitude ratio [-], 0 to 1.
    """
    return math.exp(-depth_m / skin_depth_m(omega_rad_s, k, c, rho))


def periodic_wall_cycle(t_sat_K: np.ndarray, speed_rpm: float, h_W_m2K: float,
                        depths_m=(0.0, 1e-3), *, latent_J_kg: float = 2.1e6,
                        h_dry_W_m2K: float = DRY_W_M2K, k: float = CAST_IRON_K,
                        c: float = CAST_IRON_C, rho: float = CAST_IRON_RHO,
                        T_deep_K: float | None = None, cycles: int = 60,
                        tol_K: float = 1e-3) -> dict:
    """The wall's periodic temperature cycle under steam of a given saturation
    temperature, with the film law of the module docstring.

    Backward Euler in time on a grid from the surface to five skin depths (at the
    cycle's fundamental; the wave is under 1 % of the surface's there), held behind at
    ``T_deep_K`` or, without it, insulated behind; the surface's
    exchange is linear within a step, with the law chosen from the state at the step's
    start.  Run cycle after cycle until the wall's temperatures repeat to ``tol_K``.

    Parameters
    ----------
    t_sat_K : ndarray
        The steam's saturation temperature over one cycle, at equal steps of crank
        angle (the first sample at the start of the cycle, the last one step before
        its end) [K].
    speed_rpm : float
        The engine's speed [rpm] (one cycle a revolution).
    h_W_m2K : float
        The coefficient of condensation and re-evaporation [W/(m2 K)].
    depths_m : sequence of float
        Depths under the surface at which to report the temperature [m].
    latent_J_kg : float
        Latent heat of the film's water [J/kg].
    h_dry_W_m2K : float
        The dry surface's exchange with the steam [W/(m2 K)].
    k, c, rho : float
        The wall's conductivity [W/(m K)], specific heat [J/(kg K)], density [kg/m3].
    T_deep_K : float, optional
        The wall's temperature where the wave has died [K]: its mean, measured (held
        there), or None (insulated behind; the film law is nearly neutral to the
        wall's mean, which then drifts slowly, so a measured mean is the better
        input).
    cycles : int
        Most cycles to run.
    tol_K : float
        Largest change of any grid temperature from one cycle's start to the next's
        that counts as periodic [K].

    Returns
    -------
    dict
        ``T_K`` (shape (len(depths_m), samples): the temperature at each depth over the
        last cycle [K]), ``swing_K`` (max less min at each depth [K]), ``film_kg_m2``
        (the film over the last cycle), ``heat_in_J_m2`` (the most heat the wall
        takes over the cycle, its temperature's rise integrated: the largest
        cumulative flux from its least [J/m2]), ``cycles`` run.

    Raises
    ------
    ValueError
        For a speed, coefficient or sample count that is not positive.
    """
    t_sat = np.asarray(t_sat_K, dtype=float)
    if speed_rpm <= 0.0 or h_W_m2K <= 0.0 or t_sat.size < 8:
        raise ValueError(f"periodic_wall_cycle: speed_rpm={speed_rpm!r} and "
                         f"h_W_m2K={h_W_m2K!r} must be positive and t_sat_K have 8 or "
                         f"more samples (has {t_sat.size})")
    n_t = t_sat.size
    period = 60.0 / speed_rpm
    dt = period / n_t
    omega = 2.0 * math.pi / period
    alpha = k / (rho * c)
    delta = skin_depth_m(omega, k, c, rho)
    depth = max(5.0 * delta, 2.0 * max(depths_m))
    n_x = 161
    dx = depth / (n_x - 1)
    x = np.linspace(0.0, depth, n_x)
    r = alpha * dt / dx ** 2
    # the matrix of (I - dt * Laplacian): ghost-node Neumann at both ends (or the deep
    # node held), the surface's flux added per step as h_eff (T_gas - T_0); inverted
    # once for each of the two coefficients the surface takes (wet, dry)
    m = np.zeros((n_x, n_x))
    i = np.arange(n_x)
    m[i, i] = 1.0 + 2.0 * r
    m[i[1:], i[:-1]] = -r
    m[i[:-1], i[1:]] = -r
    m[0, 1] = -2.0 * r
    m[-1, -2] = -2.0 * r
    if T_deep_K is not None:                    # held behind: the last row is T = T_deep
        m[-1, :] = 0.0
        m[-1, -1] = 1.0
    flux_gain = 2.0 * dt / (rho * c * dx)       # surface node: half cell
    inverse = {}
    for h in (h_W_m2K, h_dry_W_m2K):
        a = m.copy()
        a[0, 0] += flux_gain * h
        inverse[h] = np.linalg.inv(a)
    T = np.full(n_x, float(np.mean(t_sat)) if T_deep_K is None else float(T_deep_K))
    film = 0.0
    out = np.empty((len(depths_m), n_t))
    film_trace = np.empty(n_t)
    flux_trace = np.empty(n_t)
    ran = 0
    for ran in range(1, cycles + 1):
        start = T.copy()
        for j in range(n_t):
            ts = t_sat[j]
            if T[0] < ts or film > 0.0:
                h = h_W_m2K
            else:
                h = h_dry_W_m2K
            rhs = T.copy()
            rhs[0] += flux_gain * h * ts
            T = inverse[h] @ rhs
            q = h * (ts - T[0])                      # [W/m2] into the wall
            if h == h_W_m2K:
                film = max(film + q * dt / latent_J_kg, 0.0)
            film_trace[j] = film
            flux_trace[j] = q
            for d, z in enumerate(depths_m):
                out[d, j] = np.interp(z, x, T)
        if np.max(np.abs(T - start)) < tol_K:
            break
    cum = np.cumsum(flux_trace) * dt
    return {"T_K": out, "swing_K": out.max(axis=1) - out.min(axis=1),
            "film_kg_m2": film_trace, "heat_in_J_m2": float(cum.max() - cum.min()),
            "cycles": ran}
