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
* the film's limits (:data:`FILM_MAX_KG_M2`).

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
def skin_coefficients(Tw, Tsat, h_c, film, Aw, x):
    """The skin model's coefficients of the film's flow and the mixture's water's.

    Below the saturation temperature the surface condenses steam into its film at
    ``h_c``.  Above it a wetted surface boils its water off: the film's, wetted from 0
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

    Returns
    -------
    tuple of float
        ``(h_f, h_m)``: the film's coefficient and the mixture's water's
        [W/(m2 K)], each down ``T_w - T_sat``.
    """
    hf = h_c
    hm = 0.0
    if Tw > Tsat:
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
