"""The cylinder wall's laws, written once: the compiled balances
(:func:`corliss.engine.kernels.balances.balances`) and the Python reference path
(:class:`corliss.engine.wall.IdealPortWall`) both call these.

The physics, its sources and its calibration are in :mod:`corliss.engine.wall`'s
docstring ("Exchange between steam, film and surface", "The water film"):

* :func:`adair_h`, forced convection of the steam: Adair, Qvale and Pearson's
  correlation for reciprocating machines (Purdue Compressor Conference, 1972),
  ``h = 0.053 (k/D_e) Re^0.8 Pr^0.6``, ``D_e = 6 V / A``, gas speed ``omega D_e / 2``;
* :func:`skin_coefficients`, the skin model's film: the coefficient of the film's
  flow and of the flow into the mixture's water, by how wet the surface is
  (:data:`FILM_WET_KG_M2`) and how wet the steam is (:data:`WET_BAND`);
* the film's limits (:data:`FILM_MAX_KG_M2`);
* :func:`steam_at_wall_superheat` and :func:`condensing_share`, whether the steam at
  the wall is at saturation: condensation only once it is.

A change of the wall's law (condensation, evaporation, the film) is made here, and
both paths follow.
"""

from __future__ import annotations

from corliss.engine.kernels.compiled import njit
from corliss.thermo.wall_properties import film_table

#: Film of water over which the wall counts as wetted: 10 microns, where a draining
#: film breaks into drops and rivulets [kg/m2].
FILM_WET_KG_M2 = 1.0e-2
#: The thickest film a surface holds before the water runs off into the steam [kg/m2]:
#: Nusselt's film thickness, [4 mu_l k_l L dT / (rho_l^2 g h_fg)]^(1/4), about 0.1 mm
#: for a 12 in cover and a 20 K drop.
FILM_MAX_KG_M2 = 0.1
#: The mixture's wetness from which wet steam wets the whole wall [-].
WET_BAND = 0.02
#: The superheat of the steam at the wall over which condensation fades out, from the
#: full coefficient at saturation to none [K]: a smooth step for the integrators, not
#: a measured width (with 2 K the bundled Corliss engine's runs were not periodic in
#: the fast preset's 60 cycles).
SUPERHEAT_BAND_K = 10.0
#: Specific heat of steam that turns enthalpy over saturated vapour's into kelvin of
#: superheat [J/(kg K)]: 1.95 kJ/(kg K), at or below steam's mean specific heat from
#: saturation to 150 K above it between 0.5 and 12 bar (1.95 to 2.36 kJ/(kg K),
#: IAPWS-95 through CoolProp), so that the entering steam's superheat, read as the
#: bulk's plus ``(h_in - h) / c_p``, is never overstated by the bulk's own.
CP_STEAM_J_KGK = 1950.0
#: The inflow per radian of crank, as a share of the end's steam, over which the
#: steam at the wall goes from the bulk's to the entering steam's [1/rad]: while steam
#: enters the jet sweeps the cover and barrel ("frequently at the rate of a mile a
#: minute", Marks Art. 78); a radian's inflow as large as the end's mass is taken as
#: the wall swept wholly by it.
INFLOW_SWEEP_PER_RAD = 1.0
#: Saturated water's enthalpy and the latent heat [J/kg] on temperatures 0.5 K apart
#: from 280 K [K] (IAPWS-95, :func:`corliss.thermo.wall_properties.film_table`): the
#: film's water at the surface's temperature (:func:`film_water`).
_FILM_T, _FILM_HF, _FILM_HFG = film_table()
FILM_T0_K, FILM_DT_K = float(_FILM_T[0]), float(_FILM_T[1] - _FILM_T[0])


@njit(cache=True, inline="always")
def smoothstep(w):
    """The cubic step: 0 below 0, 1 above 1, ``3 w^2 - 2 w^3`` between.

    Parameters
    ----------
    w : float
        The argument [-].

    Returns
    -------
    float
        The step [-], 0 to 1, smooth at both ends.
    """
    w = min(max(w, 0.0), 1.0)
    return w * w * (3.0 - 2.0 * w)


@njit(cache=True, inline="always")
def wetted_share(x):
    """Share of a wall that wet steam wets.

    1 while the mixture holds more than :data:`WET_BAND` of water, falling smoothly (a
    cubic step) to 0 at dry steam.

    Parameters
    ----------
    x : float
        The mixture's dryness [-] (1 when dry or superheated).

    Returns
    -------
    float
        The wetted share [-], 0 to 1.
    """
    return smoothstep((1.0 - x) / WET_BAND)


@njit(cache=True, inline="always")
def adair_h(rho, omega, V, A, mu, k, pr):
    """Adair, Qvale and Pearson's convection coefficient of the steam in a cylinder.

    Parameters
    ----------
    rho : float
        The steam's density [kg/m3].
    omega : float
        The shaft speed [rad/s].
    V : float
        The end's volume [m3].
    A : float
        The wall the steam touches [m2].
    mu : float
        The steam's viscosity [Pa s].
    k : float
        The steam's conductivity [W/(m K)].
    pr : float
        The steam's Prandtl number [-].

    Returns
    -------
    float
        The coefficient [W/(m2 K)], ``0.053 (k/D_e) Re^0.8 Pr^0.6`` with ``D_e = 6 V/A``
        and ``Re = rho (omega D_e / 2) D_e / mu``.
    """
    de = 6.0 * V / A
    re_ = rho * (0.5 * omega * de) * de / mu
    return 0.053 * k / de * re_ ** 0.8 * pr ** 0.6


@njit(cache=True, inline="always")
def steam_at_wall_superheat(T, Tsat, x, L, h, h_in, inflow, m):
    """The superheat of the steam that touches the wall, as kelvin of the steam's
    enthalpy over saturated vapour's at the end's pressure [K].

    The bulk's, ``T - T_sat`` when superheated and ``-(1 - x) L / c_p`` when wet, but
    while steam enters: then the entering jet sweeps the wall, and the steam there
    is the entering steam at the end's pressure, whose excess over saturated vapour
    is the bulk's plus ``h_in - h``; the share goes from the bulk's to the jet's as
    the inflow per radian grows to :data:`INFLOW_SWEEP_PER_RAD` of the end's steam (a
    cubic step); ``c_p`` is :data:`CP_STEAM_J_KGK`.  The compiled balances and the
    ideal-port wall take no more than the supply's superheat
    (:func:`corliss.engine.network.with_wall_heat`): with saturated steam supplied
    the steam at the wall stays saturated however the filling and the compression
    superheat the bulk.

    Parameters
    ----------
    T : float
        The bulk's temperature [K].
    Tsat : float
        The saturation temperature at the end's pressure [K] (``T`` when wet).
    x : float
        The bulk's dryness [-] (1 when superheated).
    L : float
        The latent heat [J/kg].
    h : float
        The bulk's specific enthalpy [J/kg].
    h_in : float
        The specific enthalpy of the steam entering [J/kg] (any, with no inflow).
    inflow : float
        The steam entering per radian of crank [kg/rad] (0 or above).
    m : float
        The end's steam [kg].

    Returns
    -------
    float
        The superheat [K]; below 0 for wet steam.
    """
    e = CP_STEAM_J_KGK * (T - Tsat) - (1.0 - x) * L
    if inflow > 0.0 and m > 0.0:
        e += smoothstep(inflow / (INFLOW_SWEEP_PER_RAD * m)) * (h_in - h)
    return e / CP_STEAM_J_KGK


@njit(cache=True, inline="always")
def condensing_share(sup):
    """The share of the condensing coefficient the surface has while the steam at it
    has the superheat ``sup``.

    Superheated steam condenses on a wall below its saturation temperature only once
    its superheat is gone: the wall takes the superheat by convection (Adair's
    coefficient, a few hundred W/(m2 K)), and the steam condenses where it touches
    the wall at saturation.  Hirn (Theorie mecanique de la chaleur, 1876, through DPJ
    278, 1890, pp. 538-539): heat enters the gas very slowly; Kirsch (Z. VDI 1891 p.
    962, through DPJ 282, 1891, p. 202): a dry surface may be appreciably warmer than
    the steam touching it; Marks Art. 78 (eq. 220b): the superheat must meet the
    wall's demand before condensation begins; Lineham (A Text-Book of Mechanical
    Engineering, p. 885): "a 5 % extra heat supply will often eliminate a 20 % loss".

    Parameters
    ----------
    sup : float
        The superheat of the steam at the wall [K]
        (:func:`steam_at_wall_superheat`, no more than the supply's).

    Returns
    -------
    float
        The share [-]: 1 at saturation or wet, falling (a cubic step) to 0 at
        :data:`SUPERHEAT_BAND_K` of superheat.
    """
    return 1.0 - smoothstep(sup / SUPERHEAT_BAND_K)


@njit(cache=True, inline="always")
def skin_coefficients(Tw, Tsat, h_c, film, Aw, x, share=1.0):
    """The skin model's coefficients of the film's flow and the mixture's water's.

    Below the saturation temperature the surface condenses steam into its film at
    ``h_c`` times ``share`` (:func:`condensing_share`: none while the steam at the
    wall is superheated).  Above it a wetted surface boils its water off: the film's, wetted from 0
    to 1 as the film grows to :data:`FILM_WET_KG_M2`, and where the film is gone the
    water wet steam brings to it (:func:`wetted_share`), at the same ``h_c``.

    Parameters
    ----------
    Tw : float
        The surface's temperature [K].
    Tsat : float
        The saturation temperature at the cylinder's pressure [K].
    h_c : float
        The coefficient of condensation and evaporation [W/(m2 K)].
    film : float
        The film's water [kg].
    Aw : float
        The wall's mean area [m2] (the film's per area is ``film / Aw``).
    x : float
        The mixture's dryness [-] (1 when dry or superheated).
    share : float
        The share of ``h_c`` a surface below saturation condenses at [-].

    Returns
    -------
    tuple of float
        ``(h_f, h_m)``: the film's coefficient and the mixture's water's
        [W/(m2 K)], each down ``T_w - T_sat``.
    """
    hf = h_c
    hm = 0.0
    if Tw <= Tsat:
        hf *= share
    else:
        wf = smoothstep(film / (FILM_WET_KG_M2 * Aw))   # smooth at dry and fully wet
        hm = hf * (1.0 - wf) * wetted_share(x)
        hf *= wf
    return hf, hm


@njit(cache=True, inline="always")
def film_water(Tw):
    """The film's water at the surface's temperature: saturated water there.

    The film is thin (under 0.1 mm, :data:`FILM_MAX_KG_M2`) and lies on the surface:
    its water is at the surface's temperature, condensate forms there and vapour
    leaves from there.  Booked so, every exchange of steam, film and surface makes
    entropy (:mod:`corliss.engine.wall`, "The water film").  Linear on the IAPWS-95
    table 0.5 K apart (within 1e-5 of it), clamped to 280-640 K; ``c_f`` is the
    interpolant's own slope, so that the film's energy ``m_f h_f(T_w)`` is followed
    exactly by the surface's balance.

    Parameters
    ----------
    Tw : float
        The surface's temperature [K].

    Returns
    -------
    h_f : float
        Saturated water's enthalpy at ``Tw`` [J/kg].
    c_f : float
        Its slope, d h_f / d T_w [J/(kg K)] (0 outside the table).
    L : float
        The latent heat at ``Tw`` [J/kg].
    """
    n = _FILM_T.shape[0]
    z = (Tw - FILM_T0_K) / FILM_DT_K
    if not z > 0.0:
        return _FILM_HF[0], 0.0, _FILM_HFG[0]
    if z >= n - 1:
        return _FILM_HF[n - 1], 0.0, _FILM_HFG[n - 1]
    j = int(z)
    w = z - j
    slope = (_FILM_HF[j + 1] - _FILM_HF[j]) / FILM_DT_K
    return (_FILM_HF[j] + w * (_FILM_HF[j + 1] - _FILM_HF[j]), slope,
            _FILM_HFG[j] + w * (_FILM_HFG[j + 1] - _FILM_HFG[j]))
