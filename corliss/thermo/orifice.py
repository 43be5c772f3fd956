"""Compressible flow of steam through a port.

The port is an orifice of area ``A`` with a discharge coefficient ``Cd``.  Flow is
isentropic from the upstream stagnation state to the throat, with the exponent of
the isentropic ``p v^kappa = const`` taken from the upstream state.  The engine's
port flow takes it from the real fluid: the exponent whose choked flux equals that of
HEOS's equilibrium isentropic nozzle from the same upstream state
(:func:`corliss.thermo.steam_table.kappa_at`), continuous across the saturation line.
The classical rule, :func:`kappa_of`, is kept for reference and closed-form checks:

* wet steam, Zeuner's rule ``kappa = 1.035 + 0.1 x`` (G. Zeuner, *Technische
  Thermodynamik*, 1890; the 1.135 of dry saturated steam used throughout the steam
  nozzle literature);
* superheated steam, ``kappa = 1.3``;

its choked flux jumps by 5 % across the saturation line.

Mass flux per unit throat area (Saint-Venant and Wantzel)::

    G = sqrt( 2 kappa/(kappa-1) * p0 rho0 * (r^(2/kappa) - r^((kappa+1)/kappa)) )

with ``r = max(p_down/p0, r_crit)`` and ``r_crit = (2/(kappa+1))^(kappa/(kappa-1))``
(choked flow below it).  The flux has an infinite slope as ``r -> 1``; in a band
``1 - band < r <= 1`` it is replaced by the straight line through the band edge and
zero, which keeps the right-hand side Lipschitz.  The functions are compiled: the
Python model and the compiled kernel call the same code.  Reverse flow swaps the roles
of the two sides and carries the other side's enthalpy.

The engine's band is :data:`PORT_BAND`, in the C1 form (``c1=True``: in the band, the
quadratic through zero at ``r = 1`` that matches the flux and its slope at the band's
edge).  Its bias of the indicated work, against the same run with a band of 1e-6
(where bands of 1e-6 to 1e-4 agree to 1e-8; all dopri5 at rtol 1e-9), measured:

==================  ==========  ==========  ==========  ==========
band, form          default     high-speed  compound    evaluations
                                condensing              (default)
==================  ==========  ==========  ==========  ==========
1 %, straight       0.178 %     0.103 %     0.054 %     3,400
1 %, C1             0.072 %     0.049 %     0.025 %     3,600
0.35 %, C1          0.0049 %    0.0046 %    0.0030 %    4,000
0.1 %, straight     0.0005 %    0.0001 %    0.0004 %    4,600
==================  ==========  ==========  ==========  ==========

(evaluations: per cycle at the standard preset).  Narrower bands cost the explicit
integrator little, but make the fast preset's Rosenbrock method erratic on stiff
ports (ports 1000 times too large: 3,200 evaluations a cycle at 0.35 %, 48,000 at
0.25 %, 820,000 at 0.1 %), so the band is the widest that keeps the bias at half the
0.01 % a test holds it to (``tests/test_port_flow.py``).  The functions' own default
(1 %, straight) is kept for their closed-form tests.
"""

from __future__ import annotations

import math

from numba import njit

KAPPA_SUPERHEATED = 1.3
#: The regularisation band of the engine's port flow [-], in the C1 form (see the
#: module docstring).
PORT_BAND = 3.5e-3


@njit(cache=True)
def kappa_of(x: float, superheated: bool) -> float:
    """Isentropic exponent of steam by the classical rule (Zeuner's rule when wet).

    Parameters
    ----------
    x : float
        Dryness fraction [-] (ignored when superheated).
    superheated : bool
        True for superheated steam.

    Returns
    -------
    float
        kappa [-]: 1.3 superheated, ``1.035 + 0.1 x`` wet (1.135 dry saturated).
    """
    if superheated:
        return KAPPA_SUPERHEATED
    return 1.035 + 0.1 * x


@njit(cache=True)
def _flux_unregularised(r: float, p0: float, rho0: float, kappa: float) -> float:
    # in logarithms: ln r_crit = kappa/(kappa-1) ln(2/(kappa+1)), and with
    # a = r^(1/kappa) the bracket r^(2/kappa) - r^((kappa+1)/kappa) is a (a - r): two
    # logarithms and an exponential instead of three powers
    ln_crit = kappa / (kappa - 1.0) * math.log(2.0 / (kappa + 1.0))
    ln_r = math.log(r) if r > 0.0 else -math.inf
    if ln_r < ln_crit:
        ln_r = ln_crit
        r = math.exp(ln_crit)
    a = math.exp(ln_r / kappa)
    term = a * (a - r)
    if term <= 0.0:
        return 0.0
    return math.sqrt(2.0 * kappa / (kappa - 1.0) * p0 * rho0 * term)


@njit(cache=True)
def _flux_in_band_c1(r: float, r_edge: float, band: float, p0: float, rho0: float,
                     kappa: float) -> float:
    """The C1 form of the band: the quadratic in ``t = (1 - r)/band`` that is zero at
    ``r = 1`` and matches the flux and its slope at the band's edge."""
    g_e = _flux_unregularised(r_edge, p0, rho0, kappa)
    if g_e <= 0.0:
        return 0.0
    # s = (dG/dt) / G at t = 1, from G^2 = c term(r): dG/dt = -band c term'(r) / (2 G),
    # term'(r) = (2/kappa) r^(2/kappa - 1) - ((kappa+1)/kappa) r^(1/kappa)
    a = math.exp(math.log(r_edge) / kappa)
    term_d = (2.0 / kappa) * a * a / r_edge - ((kappa + 1.0) / kappa) * a
    c = 2.0 * kappa / (kappa - 1.0) * p0 * rho0
    s = -band * c * term_d / (2.0 * g_e * g_e)
    s = min(max(s, 0.0), 2.0)        # keeps the quadratic monotonic on the band
    t = (1.0 - r) / band
    return g_e * t * ((2.0 - s) + (s - 1.0) * t)


@njit(cache=True)
def mass_flux(p0: float, rho0: float, p_down: float, kappa: float,
              band: float = 0.01, c1: bool = False) -> float:
    """Mass flux through a port from upstream to downstream [kg/(s m2)], >= 0.

    Parameters
    ----------
    p0, rho0 : float
        Upstream (stagnation) pressure [Pa] and density [kg/m3].
    p_down : float
        Downstream pressure [Pa]; must not exceed ``p0``.
    kappa : float
        Isentropic exponent [-] of the upstream steam.
    band : float, optional
        Width of the regularised band of pressure ratio near 1 [-].
    c1 : bool, optional
        In the band, the quadratic that matches the flux and its slope at the band's
        edge (continuous slope, the engine's form) instead of the straight line.

    Returns
    -------
    float
        Mass flux per unit throat area [kg/(s m2)], >= 0; 0 when ``p_down >= p0``.
    """
    r = p_down / p0
    if r >= 1.0:
        return 0.0
    r_edge = 1.0 - band
    if r > r_edge:
        if c1:
            return _flux_in_band_c1(r, r_edge, band, p0, rho0, kappa)
        return _flux_unregularised(r_edge, p0, rho0, kappa) * (1.0 - r) / band
    return _flux_unregularised(r, p0, rho0, kappa)


@njit(cache=True)
def port_flow(area: float, cd: float, p1: float, rho1: float, kappa1: float,
              p2: float, rho2: float, kappa2: float, band: float = 0.01,
              c1: bool = False) -> float:
    """Signed mass flow [kg/s] through a port, positive from side 1 to side 2.

    Parameters
    ----------
    area : float
        Open area of the port [m2].
    cd : float
        Discharge coefficient [-].
    p1, rho1, kappa1 : float
        Pressure [Pa], density [kg/m3] and isentropic exponent [-] of side 1.
    p2, rho2, kappa2 : float
        The same for side 2.
    band : float, optional
        Regularisation band of pressure ratio [-], see :func:`mass_flux`.
    c1 : bool, optional
        The band's form, see :func:`mass_flux`.

    Returns
    -------
    float
        Mass flow [kg/s], ``cd * area * G`` with G the flux from the side of higher
        pressure; positive from side 1 to side 2, 0 when the port is shut.
    """
    if area <= 0.0:
        return 0.0
    if p1 >= p2:
        return cd * area * mass_flux(p1, rho1, p2, kappa1, band, c1)
    return -cd * area * mass_flux(p2, rho2, p1, kappa2, band, c1)


@njit(cache=True)
def _flux_and_slope(r: float, p0: float, rho0: float, kappa: float, band: float,
                    c1: bool) -> tuple:
    """:func:`mass_flux` ``G`` at pressure ratio ``r < 1`` and its slope ``dG/dr`` at
    fixed upstream state and exponent, from the same branches: zero while choked (the
    critical ratio is where the flux peaks), ``c p0 rho0 term'(r) / (2 G)`` on the
    unregularised curve, the derivative of the band's straight line or quadratic in
    it."""
    r_edge = 1.0 - band
    if r > r_edge:
        g_e = _flux_unregularised(r_edge, p0, rho0, kappa)
        if not c1:
            return g_e * (1.0 - r) / band, -g_e / band
        if g_e <= 0.0:
            return 0.0, 0.0
        a = math.exp(math.log(r_edge) / kappa)
        term_d = (2.0 / kappa) * a * a / r_edge - ((kappa + 1.0) / kappa) * a
        c = 2.0 * kappa / (kappa - 1.0) * p0 * rho0
        s = -band * c * term_d / (2.0 * g_e * g_e)
        s = min(max(s, 0.0), 2.0)
        t = (1.0 - r) / band
        return (g_e * t * ((2.0 - s) + (s - 1.0) * t),
                -g_e / band * ((2.0 - s) + 2.0 * (s - 1.0) * t))
    g = _flux_unregularised(r, p0, rho0, kappa)
    if g <= 0.0:
        return 0.0, 0.0
    ln_crit = kappa / (kappa - 1.0) * math.log(2.0 / (kappa + 1.0))
    if not math.log(r) > ln_crit:
        return g, 0.0
    a = math.exp(math.log(r) / kappa)
    term_d = (2.0 / kappa) * a * a / r - ((kappa + 1.0) / kappa) * a
    c = 2.0 * kappa / (kappa - 1.0) * p0 * rho0
    return g, c * term_d / (2.0 * g)


@njit(cache=True)
def port_flow_partials(area: float, cd: float, p1: float, rho1: float, kappa1: float,
                       p2: float, rho2: float, kappa2: float, band: float = 0.01,
                       c1: bool = False) -> tuple:
    """:func:`port_flow` and its partial derivatives in the two sides' states.

    The flux from the side of higher pressure is ``G = sqrt(p0 rho0) psi(r, kappa)``
    with ``r = p_down / p0`` (on every branch of :func:`mass_flux`: the band's edge
    flux scales as ``sqrt(p0 rho0)`` and its slope factor not at all), so
    ``dG/drho0 = G / (2 rho0)``, ``dG/dp_down = G_r / p0`` and
    ``dG/dp0 = G / (2 p0) - r G_r / p0``, ``G_r`` the slope in ``r`` from the same
    branch; the exponent's derivative is a forward difference of step ``1e-7``
    (relative error near 1e-7, the exponent's share of a flow's change being small).

    Parameters
    ----------
    area : float
        Open area of the port [m2].
    cd : float
        Discharge coefficient [-].
    p1, rho1, kappa1 : float
        Pressure [Pa], density [kg/m3] and isentropic exponent [-] of side 1.
    p2, rho2, kappa2 : float
        The same for side 2.
    band : float, optional
        Regularisation band of pressure ratio [-], see :func:`mass_flux`.
    c1 : bool, optional
        The band's form, see :func:`mass_flux`.

    Returns
    -------
    tuple
        The mass flow [kg/s] as :func:`port_flow` gives it, then its derivatives in
        ``p1`` [kg/(s Pa)], ``rho1`` [kg/s per kg/m3], ``kappa1`` [kg/s], ``p2``,
        ``rho2``, ``kappa2``: seven floats, all 0 for a shut port; at equal pressures
        those of side 1 upstream, as :func:`port_flow` takes it.
    """
    if area <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    ca = cd * area
    up_is_1 = p1 >= p2
    if up_is_1:
        p0, rho0, kap, pd = p1, rho1, kappa1, p2
    else:
        p0, rho0, kap, pd = p2, rho2, kappa2, p1
        ca = -ca
    r = pd / p0
    g, g_r = _flux_and_slope(r, p0, rho0, kap, band, c1)
    dk = 1e-7 * kap
    g2, _ = _flux_and_slope(r, p0, rho0, kap + dk, band, c1)
    d_p0 = ca * (0.5 * g - r * g_r) / p0
    d_rho0 = ca * 0.5 * g / rho0
    d_k = ca * (g2 - g) / dk
    d_pd = ca * g_r / p0
    if up_is_1:
        return ca * g, d_p0, d_rho0, d_k, d_pd, 0.0, 0.0
    return ca * g, d_pd, 0.0, 0.0, d_p0, d_rho0, d_k
