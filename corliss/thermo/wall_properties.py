"""Steam properties the wall model takes once a run, from a grid shipped with corliss.

The skin wall (:mod:`corliss.engine.wall`) takes, once a run, the vapour's thermal
conductivity, viscosity and Prandtl number at the chest's state (for its convection)
and saturated water's enthalpy and the latent heat at the wall's starting temperature
(for its film).  They come from CoolProp (IAPWS-95; IAPWS 2008 viscosity and 2011
conductivity), but importing CoolProp costs a second and a half, more than a steady
run of the wall model: a grid of them, computed once from CoolProp and shipped with
the package (:data:`GRID_FILE`, remade by :func:`write_grid`), serves every run
inside it, and a run from the cached steam table imports no CoolProp.

* Transport properties on ln p and the superheat above saturation, along both of
  which they are smooth: bilinear interpolation is within 0.1 % of CoolProp inside
  (``tests/test_wall_properties.py``), well inside the uncertainty of the convection
  correlations they feed (Dittus-Boelter's, some 20 %).
* The film's enthalpies on temperature at 0.5 K spacing: linear interpolation within
  1e-5 of CoolProp.

Outside the grids the properties come from CoolProp.
"""

from __future__ import annotations

import math
from functools import lru_cache
from pathlib import Path

import numpy as np

#: The shipped grid: ``lnp`` [ln Pa], ``T_sat`` [K] at each pressure, ``dT`` [K] the
#: superheat axis, and ``k`` [W/(m K)], ``mu`` [Pa s], ``Pr`` [-] on (lnp, dT);
#: ``T_film`` [K] and saturated water's ``h_f`` and the latent heat ``h_fg`` [J/kg].
GRID_FILE = Path(__file__).with_name("wall_properties.npz")
#: The film's temperatures [K]: the range :func:`film_enthalpies` clamps to, 0.5 K apart.
FILM_T_RANGE_K = (280.0, 640.0)
#: Pressures of the grid [Pa]: from just above the triple point to 5 MPa (725 psia,
#: beyond any engine of the books; nearer the critical point the vapour's properties
#: bend too sharply for the grid, and come from CoolProp).
P_RANGE_Pa = (700.0, 5e6)
#: Points along ln p, and along the superheat.
N_P, N_DT = 90, 48
#: The superheat the properties of saturated steam are taken at [K] (0.5 K: the vapour
#: side of saturation), the grid's least, and its greatest [K].
DT_MIN_K, DT_MAX_K = 0.5, 800.0


def _superheat_axis() -> np.ndarray:
    """Superheats [K], closer near saturation, where the properties bend most."""
    s = np.linspace(0.0, 1.0, N_DT)
    return DT_MIN_K + (DT_MAX_K - DT_MIN_K) * s ** 2


def _coolprop(p_Pa: float, T_K: float) -> tuple[float, float, float, float]:
    """(k, mu, Pr, T_sat) of the vapour at ``p_Pa`` and max(``T_K``, T_sat) + 0.5 K."""
    import CoolProp
    import CoolProp.CoolProp as CP
    a = CoolProp.AbstractState("HEOS", "Water")
    a.update(CP.PQ_INPUTS, p_Pa, 1.0)
    t_sat = a.T()
    a.update(CP.PT_INPUTS, p_Pa, max(T_K, t_sat) + DT_MIN_K)
    return a.conductivity(), a.viscosity(), a.Prandtl(), t_sat


def _film_coolprop(T_K: float) -> tuple[float, float]:
    import CoolProp.CoolProp as CP
    h_f = CP.PropsSI("H", "T", T_K, "Q", 0.0, "Water")
    return h_f, CP.PropsSI("H", "T", T_K, "Q", 1.0, "Water") - h_f


def write_grid(path: Path = GRID_FILE) -> Path:
    """Compute the grids from CoolProp (a few seconds) and write them.

    To remake the shipped grid::

        python -c "from corliss.thermo.wall_properties import write_grid; write_grid()"

    Parameters
    ----------
    path : Path, optional
        File to write (``.npz``; the arrays are those of :data:`GRID_FILE`).

    Returns
    -------
    Path
        The file written.
    """
    import CoolProp
    lnp = np.linspace(math.log(P_RANGE_Pa[0]), math.log(P_RANGE_Pa[1]), N_P)
    dT = _superheat_axis()
    k, mu, pr = (np.empty((N_P, N_DT)) for _ in range(3))
    t_sat = np.empty(N_P)
    for i, lp in enumerate(lnp):
        t_sat[i] = _coolprop(math.exp(lp), 0.0)[3]
        for j, d in enumerate(dT):
            k[i, j], mu[i, j], pr[i, j], _ = _coolprop(math.exp(lp), t_sat[i] + d - DT_MIN_K)
    t_film = np.arange(FILM_T_RANGE_K[0], FILM_T_RANGE_K[1] + 0.25, 0.5)
    film = np.array([_film_coolprop(t) for t in t_film])
    np.savez_compressed(path, lnp=lnp, T_sat=t_sat, dT=dT, k=k, mu=mu, Pr=pr,
                        T_film=t_film, h_f=film[:, 0], h_fg=film[:, 1],
                        coolprop=np.array(CoolProp.__version__))
    return Path(path)


@lru_cache(maxsize=1)
def _grid() -> dict | None:
    try:
        with np.load(GRID_FILE, allow_pickle=False) as z:
            return {n: np.array(z[n], dtype=np.float64)
                    for n in ("lnp", "T_sat", "dT", "k", "mu", "Pr", "T_film", "h_f", "h_fg")}
    except (OSError, KeyError, ValueError):
        return None


def _cell(axis: np.ndarray, x: float) -> tuple[int, float]:
    i = int(np.clip(np.searchsorted(axis, x) - 1, 0, axis.size - 2))
    return i, (x - axis[i]) / (axis[i + 1] - axis[i])


def transport_properties(p_Pa: float, T_K: float) -> tuple[float, float, float]:
    """Transport properties of steam as vapour, 0.5 K above the greater of ``T_K`` and
    the saturation temperature (the vapour side).

    Parameters
    ----------
    p_Pa : float
        Absolute pressure [Pa].
    T_K : float
        Temperature [K].

    Returns
    -------
    tuple of float
        (thermal conductivity [W/(m K)], dynamic viscosity [Pa s], Prandtl number [-]):
        IAPWS formulations, interpolated on the shipped grid inside it, from CoolProp
        outside.
    """
    g = _grid()
    lp = math.log(p_Pa)
    if g is not None and g["lnp"][0] <= lp <= g["lnp"][-1]:
        i, fp = _cell(g["lnp"], lp)
        t_sat = g["T_sat"][i] + fp * (g["T_sat"][i + 1] - g["T_sat"][i])
        d = max(T_K - t_sat, 0.0) + DT_MIN_K
        if d <= g["dT"][-1]:
            j, ft = _cell(g["dT"], d)

            def at(z):
                return ((1 - fp) * ((1 - ft) * z[i, j] + ft * z[i, j + 1])
                        + fp * ((1 - ft) * z[i + 1, j] + ft * z[i + 1, j + 1]))

            return float(at(g["k"])), float(at(g["mu"])), float(at(g["Pr"]))
    return _coolprop(p_Pa, T_K)[:3]


def film_enthalpies(T_K: float) -> tuple[float, float]:
    """Saturated water's enthalpy and the latent heat, the wall film's constants over
    a run (IAPWS-95; linear on the shipped grid, from CoolProp without it).

    Parameters
    ----------
    T_K : float
        Temperature [K], clamped to :data:`FILM_T_RANGE_K` (280-640 K).

    Returns
    -------
    h_L, L : float
        Enthalpy of saturated water and latent heat of evaporation [J/kg].
    """
    T = min(max(T_K, FILM_T_RANGE_K[0]), FILM_T_RANGE_K[1])
    g = _grid()
    if g is None:
        return _film_coolprop(T)
    return (float(np.interp(T, g["T_film"], g["h_f"])),
            float(np.interp(T, g["T_film"], g["h_fg"])))


def film_table() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Saturated water's enthalpy and the latent heat on the film's temperatures, the
    table the compiled wall interpolates linearly at the surface's temperature.

    Returns
    -------
    T, h_f, h_fg : numpy.ndarray
        Temperatures [K] from 280 to 640 K, 0.5 K apart (:data:`FILM_T_RANGE_K`), and
        saturated water's enthalpy and the latent heat there [J/kg] (IAPWS-95: the
        shipped grid, or CoolProp without it).
    """
    g = _grid()
    if g is not None:
        return g["T_film"].copy(), g["h_f"].copy(), g["h_fg"].copy()
    t = np.arange(FILM_T_RANGE_K[0], FILM_T_RANGE_K[1] + 0.25, 0.5)
    film = np.array([_film_coolprop(v) for v in t])
    return t, film[:, 0].copy(), film[:, 1].copy()
