"""Reservoir states from the steam table's cached arrays, without CoolProp.

A run on the ``table`` tier asks for a handful of states besides the cylinder's
(density, internal energy) lookups: the supply at the chest (saturated, wet or
superheated), dry saturated steam at back pressure, a receiver, a saturation
temperature.  They are answered here from the arrays :mod:`corliss.thermo.steam_table`
caches, so that a run whose table is built never imports CoolProp (over a second):

* **saturation** (:func:`t_sat`, :func:`px`): the table's saturation line, ln p_sat,
  v_f, ln v_g, u_f, u_g on a uniform grid in T, interpolated linearly in T exactly as
  the compiled lookup does; T_sat(p) inverts ln p_sat the same way.
* **superheated vapour** (:func:`pt`): the (ln rho, u) vapour grid's bilinear
  interpolant inverted for the (density, energy) at which it gives the pressure and
  temperature asked for, so the state is the one the compiled lookup returns.
* **entropy**, which the table does not hold: of saturated liquid by integrating
  ``T ds = dh - v dp`` along the saturation line from the triple point (IAPWS-95's
  reference state: u = s = 0 for the saturated liquid there), of saturated vapour as
  ``s_f + (h_g - h_f) / T``, and of superheated vapour by integrating ``ds = du / T``
  along the grid's rows, which are isochores, from each row's saturated vapour.

States are tuples in the order of :class:`corliss.thermo.steam.State`, (p, T, rho, u,
h, s, dryness, superheated), all SI.  Each function returns None for a state outside the arrays (beyond the saturation
table's 646 K, a density off the vapour grid, an energy above it): the caller then
asks IAPWS-95 itself.  Agreement with CoolProp is tested in tests/test_thermo.py.
"""

from __future__ import annotations

import math

import numpy as np

#: Derived arrays of a table, by ``id`` of its saturation array (kept, so the id stays
#: its): (that array, T grid [K], s_f, s_g [J/(kg K)]).
_DERIVED: dict[int, tuple] = {}


def _saturation_entropy(tab) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(T grid [K], s_f [J/(kg K)], s_g [J/(kg K)]) on the table's saturation grid."""
    key = id(tab.s_lnp)
    if key not in _DERIVED or _DERIVED[key][0] is not tab.s_lnp:
        n = tab.s_lnp.size
        T = tab.sT0 + tab.sdT * np.arange(n)
        p = np.exp(tab.s_lnp)
        vf, vg = tab.s_vf, np.exp(tab.s_lnvg)
        hf = tab.s_uf + p * vf
        hg = tab.s_ug + p * vg
        # T ds_f = dh_f - v_f dp along the saturation line, midpoint in each cell
        ds = (np.diff(hf) - 0.5 * (vf[1:] + vf[:-1]) * np.diff(p)) / (0.5 * (T[1:] + T[:-1]))
        sf = np.concatenate([[0.0], np.cumsum(ds)])
        sg = sf + (hg - hf) / T
        _DERIVED[key] = (tab.s_lnp, T, sf, sg)
    return _DERIVED[key][1:]


def t_sat(tab, p: float) -> float | None:
    """Saturation temperature at a pressure, inverting the table's ln p_sat linearly
    in T.

    Parameters
    ----------
    tab : SteamTable
        The table (:func:`corliss.thermo.steam_table.load_table`).
    p : float
        Absolute pressure [Pa].

    Returns
    -------
    float or None
        Saturation temperature [K]; None off the saturation table (below the
        triple point's pressure or above its 646 K).
    """
    lp = math.log(p) if p > 0.0 else -math.inf
    if not tab.s_lnp[0] <= lp <= tab.s_lnp[-1]:
        return None
    i = min(int(np.searchsorted(tab.s_lnp, lp, side="right")) - 1, tab.s_lnp.size - 2)
    w = (lp - tab.s_lnp[i]) / (tab.s_lnp[i + 1] - tab.s_lnp[i])
    return float(tab.sT0 + tab.sdT * (i + w))


def _at(tab, T: float, arr: np.ndarray) -> float:
    """``arr`` of the saturation table at temperature ``T`` [K], linear in T."""
    f = (T - tab.sT0) / tab.sdT
    i = min(max(int(f), 0), arr.size - 2)
    w = f - i
    return float(arr[i] * (1.0 - w) + arr[i + 1] * w)


def px(tab, p: float, x: float) -> tuple | None:
    """Saturated steam of a dryness at a pressure, entropy included.

    Parameters
    ----------
    tab : SteamTable
        The table (:func:`corliss.thermo.steam_table.load_table`).
    p : float
        Absolute pressure [Pa].
    x : float
        Dryness fraction [-], in [0, 1].

    Returns
    -------
    tuple or None
        ``(p [Pa], T [K], rho [kg/m3], u [J/kg], h [J/kg], s [J/(kg K)], x [-],
        superheated)``, the fields of :class:`corliss.thermo.steam.State`; None off
        the saturation table or for a dryness outside [0, 1] (the caller then asks
        IAPWS-95).
    """
    T = t_sat(tab, p)
    if T is None or not 0.0 <= x <= 1.0:      # IAPWS-95 says what is wrong with it
        return None
    _, sf, sg = _saturation_entropy(tab)
    vf, vg = _at(tab, T, tab.s_vf), math.exp(_at(tab, T, tab.s_lnvg))
    uf, ug = _at(tab, T, tab.s_uf), _at(tab, T, tab.s_ug)
    sf_T, sg_T = _at(tab, T, sf), _at(tab, T, sg)
    v = vf + x * (vg - vf)
    u = uf + x * (ug - uf)
    return (p, T, 1.0 / v, u, u + p * v, sf_T + x * (sg_T - sf_T), x, False)


def _row(tab, i: int, wr: float) -> tuple[np.ndarray, np.ndarray]:
    """The vapour grid's T and p/rho at fractional row ``i + wr``, over its u grid."""
    return ((1.0 - wr) * tab.T[i] + wr * tab.T[i + 1],
            (1.0 - wr) * tab.q[i] + wr * tab.q[i + 1])


def _u_grid(tab) -> np.ndarray:
    return tab.u0 + tab.du * np.arange(tab.q.shape[1])


def _row_entropy(tab, i: int, u: float) -> float:
    """Entropy [J/(kg K)] on grid row ``i`` (an isochore) at energy ``u`` [J/kg]:
    the row's saturated vapour's plus the integral of du / T from its energy."""
    ug, Tg = float(tab.ug_row[i]), float(tab.Tg_row[i])
    _, _, sg = _saturation_entropy(tab)
    ugrid = _u_grid(tab)
    # du / T by the trapezium rule on the grid, between ug and u (both inside it)
    inv = 1.0 / tab.T[i]
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (inv[1:] + inv[:-1]) * tab.du)])
    return _at(tab, Tg, sg) + float(np.interp(u, ugrid, cum) - np.interp(ug, ugrid, cum))


def pt(tab, p: float, T: float) -> tuple | None:
    """Superheated steam at a pressure and temperature: the (density, energy) at which
    the vapour grid gives (p, T), found by bisection on the grid's rows.

    Parameters
    ----------
    tab : SteamTable
        The table (:func:`corliss.thermo.steam_table.load_table`).
    p : float
        Absolute pressure [Pa].
    T : float
        Temperature [K], at or above the saturation temperature.

    Returns
    -------
    tuple or None
        ``(p [Pa], T [K], rho [kg/m3], u [J/kg], h [J/kg], s [J/(kg K)], x [-],
        superheated)``, the fields of :class:`corliss.thermo.steam.State`; None
        below saturation, off the vapour grid, or where the lookup would take the
        state as wet (the caller then asks IAPWS-95).
    """
    ts = t_sat(tab, p)
    if ts is None or T < ts:
        return None
    nr, nu = tab.q.shape
    ugrid = _u_grid(tab)

    def state_at(fr):
        i = min(int(fr), nr - 2)
        wr = fr - i
        Trow, qrow = _row(tab, i, wr)
        if T > Trow[-1]:
            return None           # hotter than the grid's highest energy
        if T < Trow[0]:
            return math.inf, math.nan, math.nan, i, wr     # denser than the isotherm's vapour
        u = float(np.interp(T, Trow, ugrid))
        rho = math.exp(tab.lnrho0 + fr * tab.dlnrho)
        return rho * float(np.interp(u, ugrid, qrow)), u, rho, i, wr

    # p rises with density along the isotherm: bisection on the fractional row
    lo, hi = 0.0, nr - 1.0
    a, b = state_at(lo), state_at(hi)
    if a is None or b is None or not a[0] <= p <= b[0]:
        return None
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        m = state_at(mid)
        if m is None:
            return None
        if m[0] < p:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-12:
            break
    _, u, rho, i, wr = state_at(0.5 * (lo + hi))
    ug0, ug1 = tab.ug_row[i], tab.ug_row[i + 1]
    # rows below the triple point's vapour density have no saturated vapour (-1), and
    # a state the lookup would take as wet is not vapour here: IAPWS-95 answers both
    if not (ug0 > 0.0 and ug1 > 0.0 and u >= (1.0 - wr) * ug0 + wr * ug1):
        return None
    s = (1.0 - wr) * _row_entropy(tab, i, u) + wr * _row_entropy(tab, i + 1, u)
    return (p, T, rho, u, u + p / rho, s, 1.0, True)
