"""The fast property tier: the project's own table over (density, internal energy).

A control volume carries density and internal energy; CoolProp's tabular backends
take pressure and enthalpy, and HEOS costs 20-60 us to flash (density, internal
energy).  This tier answers the cylinder's question, p, T, dryness from (rho, u), in
well under a microsecond from a compiled function, built once from HEOS and cached
on disk with its build parameters and its measured error.

Two parts, so that the saturation line is never smeared by interpolation:

* **vapour** (superheated, and metastable vapour just inside the dome, which HEOS
  evaluates with the gas phase imposed): ``p / rho`` and ``T`` on a grid uniform in
  ``ln rho`` and ``u``, bilinear.  ``p / rho = Z R T`` is smooth and nearly linear in
  both, so bilinear interpolation is accurate on a modest grid.
* **wet steam**: exact lever rule on a fine saturation table in T: the state is the
  saturation temperature at which the dryness from volume equals the dryness from
  energy, ``(u - u_f)(v_g - v_f) = (v - v_f)(u_g - u_f)``, found by Newton's method
  from the saturated-vapour end, kept inside a bracket (about 4 steps).

Which part applies is decided by the saturated-vapour energy ``u_g`` at the state's
density.  Every index is clamped, so no input can read outside the arrays: a state
off the table is evaluated at the nearest edge, never crashes (a crash near
saturation at 0.18 bar is what ruled out CoolProp's TTSE backend); but
:func:`lookup_flagged` says so, with a code of :data:`CLAMP_CODES`, and the kernel
counts every such evaluation.

Range: density from 0.002 kg/m3 (below dry saturated steam at the triple point,
0.00485 kg/m3, so that a condenser at any pressure the scene grammar allows has room
to expand below it) to 80 kg/m3 (dry saturated steam near 12.5 MPa); energy to
4.2 MJ/kg (steam at 1273 K, the top of IAPWS-95's range and of a scene's supply
temperature, is 4.06 MJ/kg).

A third part is the **isentropic exponent of the port flow** (:func:`kappa_at`): for
each upstream state on a coarse (ln rho, u) grid, HEOS's isentropic nozzle (for the
stagnation state (p0, s0), the throat flux ``G(p) = rho(p, s0) sqrt(2 (h0 - h(p, s0)))``
maximised over p; equilibrium expansion, IAPWS-95 via CoolProp) gives the choked flux
``G*``, and the exponent is the kappa whose Saint-Venant--Wantzel choked flux
``sqrt(kappa (2/(kappa+1))^((kappa+1)/(kappa-1)) p0 rho0)`` equals it.  The choked
flux is continuous in the upstream state (an expansion that starts just superheated
and one that starts just wet end alike), so this exponent is continuous across the
saturation line, where Zeuner's 1.135 and the superheated 1.3 jump by 5 % in flux.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import inspect
import json
import logging
import math
import os
import re
import time
import zipfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
from numba import njit

from corliss.logs import NOTICE
from corliss.versions import installed_version

log = logging.getLogger(__name__)

#: Build parameters; their hash names the cache file.
PARAMS = {
    "version": 2,
    "rho_min": 0.002, "rho_max": 80.0, "n_rho": 567,       # kg/m3, geometric
    "u_min": 2.0e6, "u_max": 4.2e6, "n_u": 1101,           # J/kg, uniform
    "T_row_step": 0.5, "T_row_max": 1400.0,                # K, fine rows for inversion
    "T_sat_min": 273.16, "T_sat_max": 646.0, "n_sat": 7500,
    # the port-flow exponent: geometric in density over the same span, uniform in u
    "kappa_n_rho": 89, "kappa_u_min": 0.0, "kappa_n_u": 261,
}

#: What :func:`lookup_flagged` reports (bits of its code): a density below or above
#: the table, an energy below or above it, a state below the triple point (colder
#: than 273.16 K: no steam there).  The kernel adds its own clamps with the same bits.
CLAMP_LOW_DENSITY, CLAMP_HIGH_DENSITY, CLAMP_LOW_ENERGY, CLAMP_HIGH_ENERGY = 1, 2, 4, 8
CLAMP_TRIPLE_POINT, CLAMP_NO_STATE = 16, 32
#: What each clamp bit means, by bit.
CLAMP_CODES = {CLAMP_LOW_DENSITY: "density below the properties' range",
               CLAMP_HIGH_DENSITY: "density above the properties' range",
               CLAMP_LOW_ENERGY: "internal energy below the properties' range (very wet)",
               CLAMP_HIGH_ENERGY: "internal energy above the properties' range (superheat)",
               CLAMP_TRIPLE_POINT: "a state colder than the triple point",
               CLAMP_NO_STATE: "no steam state at that density and energy"}


def covers(rho: float, u: float) -> bool:
    """Whether the table spans a state as a supply.

    The span is the table's build parameters, :data:`PARAMS`: the vapour grid's
    densities and energies.  Wetter states, down to water at the triple point, are
    answered by the lever rule without a clamp (:func:`lookup_flagged`), for the
    cylinder's steam.

    Parameters
    ----------
    rho : float
        Density [kg/m3].
    u : float
        Specific internal energy [J/kg].

    Returns
    -------
    bool
        True when ``rho`` and ``u`` lie within the vapour grid's ranges.
    """
    return (PARAMS["rho_min"] <= rho <= PARAMS["rho_max"]
            and PARAMS["u_min"] <= u <= PARAMS["u_max"])


class TableArrays(NamedTuple):
    """The steam table as the compiled lookup reads it, by name (:meth:`SteamTable.arrays`).

    Numba compiles a module-level :class:`typing.NamedTuple` as a tuple and caches the
    functions taking it; attribute access compiles to the same code as an index.  The
    fields are :class:`SteamTable`'s, with the same units; their parameters below are
    read from its docstring (written once, there).
    """

    lnrho0: float
    dlnrho: float
    u0: float
    du: float
    q: np.ndarray
    T: np.ndarray
    ug_row: np.ndarray
    Tg_row: np.ndarray
    sT0: float
    sdT: float
    s_lnp: np.ndarray
    s_vf: np.ndarray
    s_lnvg: np.ndarray
    s_uf: np.ndarray
    s_ug: np.ndarray
    k_lnrho0: float
    k_dlnrho: float
    k_u0: float
    k_du: float
    kappa: np.ndarray



@dataclass(frozen=True)
class SteamTable:
    """Arrays of the table (all SI).  Build with :func:`load_table`.

    The vapour grid's rows are uniform in ln rho, its columns uniform in u; the
    saturation table is uniform in T; the port-flow exponent's grid is uniform in
    ln rho and u.

    Parameters
    ----------
    lnrho0 : float
        ln of the vapour grid's first row density [ln(kg/m3)].
    dlnrho : float
        Step of the rows in ln density [-].
    u0 : float
        The vapour grid's first column energy [J/kg].
    du : float
        Step of the columns in energy [J/kg].
    q : ndarray
        ``p / rho`` on the vapour grid [J/kg], shape ``(n_rho, n_u)``.
    T : ndarray
        Temperature on the vapour grid [K], shape ``(n_rho, n_u)``.
    ug_row : ndarray
        Saturated-vapour energy at each row's density [J/kg], shape ``(n_rho,)``;
        NaN above the critical density, -1 below the triple point's vapour density
        (all vapour there).
    Tg_row : ndarray
        Saturation temperature at each row's density [K], shape ``(n_rho,)``; NaN
        above the critical density.
    sT0 : float
        The saturation table's first temperature [K].
    sdT : float
        Its step in temperature [K].
    s_lnp : ndarray
        ln of the saturation pressure [ln Pa], shape ``(n_sat,)``.
    s_vf : ndarray
        Specific volume of saturated liquid [m3/kg], shape ``(n_sat,)``.
    s_lnvg : ndarray
        ln of the specific volume of saturated vapour [ln(m3/kg)], shape
        ``(n_sat,)``.
    s_uf : ndarray
        Internal energy of saturated liquid [J/kg], shape ``(n_sat,)``.
    s_ug : ndarray
        Internal energy of saturated vapour [J/kg], shape ``(n_sat,)``.
    k_lnrho0 : float
        ln of the port-flow exponent's first row density [ln(kg/m3)].
    k_dlnrho : float
        Its step in ln density [-].
    k_u0 : float
        Its first column energy [J/kg].
    k_du : float
        Its step in energy [J/kg].
    kappa : ndarray
        Isentropic exponent of the choked flux [-], shape ``(kappa_n_rho,
        kappa_n_u)`` (see the module doc).
    error : dict
        The table's measured error against HEOS (:func:`measure_error`), with its
        build time, parameters and CoolProp version.
    """

    lnrho0: float
    dlnrho: float
    u0: float
    du: float
    q: np.ndarray        # p / rho [J/kg], shape (n_rho, n_u)
    T: np.ndarray        # [K], shape (n_rho, n_u)
    ug_row: np.ndarray   # saturated-vapour u at each row's density [J/kg]; nan above rho_c
    Tg_row: np.ndarray   # saturation temperature at each row's density [K]
    sT0: float
    sdT: float
    s_lnp: np.ndarray    # saturation table over T: ln p_sat [ln Pa]
    s_vf: np.ndarray     # [m3/kg]
    s_lnvg: np.ndarray   # ln v_g
    s_uf: np.ndarray     # [J/kg]
    s_ug: np.ndarray     # [J/kg]
    k_lnrho0: float      # the port-flow exponent's grid: ln rho of its first row
    k_dlnrho: float
    k_u0: float          # [J/kg]
    k_du: float
    kappa: np.ndarray    # isentropic exponent of the choked flux [-], (k_n_rho, k_n_u)
    error: dict          # measured error against HEOS

    def arrays(self):
        """The arrays the compiled lookup takes, by name.

        Returns
        -------
        TableArrays
            The fields above, ``error`` left out (20 fields).
        """
        return TableArrays(self.lnrho0, self.dlnrho, self.u0, self.du, self.q, self.T,
                           self.ug_row, self.Tg_row, self.sT0, self.sdT, self.s_lnp, self.s_vf,
                           self.s_lnvg, self.s_uf, self.s_ug, self.k_lnrho0, self.k_dlnrho,
                           self.k_u0, self.k_du, self.kappa)


# --- compiled lookup ------------------------------------------------------------------

def _fields_of(doc: str, fields: tuple) -> str:
    """The entries of ``fields`` from a numpydoc Parameters section, as a section."""
    text = inspect.cleandoc(doc).split("Parameters\n----------\n", 1)[1]
    entries = re.split(r"\n(?=\S)", text.split("\n\n")[0])
    kept = [e for f in fields for e in entries if e.split(" : ")[0] == f]
    return "\n    Parameters\n    ----------\n" + "\n".join(
        "    " + line for e in kept for line in e.split("\n")) + "\n"


TableArrays.__doc__ = ((TableArrays.__doc__ or "").rstrip() + "\n"
                       + _fields_of(SteamTable.__doc__ or "", TableArrays._fields) + "    ")


@njit(cache=True)
def _sat_at(T, sT0, sdT, arr):
    f = (T - sT0) / sdT
    n = arr.shape[0]
    if f < 0.0:
        f = 0.0
    i = int(f)
    if i > n - 2:
        i = n - 2
    w = f - i
    if w > 1.0:
        w = 1.0
    return arr[i] * (1.0 - w) + arr[i + 1] * w


@njit(cache=True)
def _lever(T, u, v, sT0, sdT, s_vf, s_lnvg, s_uf, s_ug):
    """The lever rule's residual at saturation temperature ``T`` [K] for specific
    volume ``v`` [m3/kg] and energy ``u`` [J/kg],
    ``(u - u_f)(v_g - v_f) - (v - v_f)(u_g - u_f)`` (falling with T through the wet
    state's temperature), and its derivative in T within the saturation table's cell."""
    f = (T - sT0) / sdT
    n = s_vf.shape[0]
    if f < 0.0:
        f = 0.0
    k = int(f)
    if k > n - 2:
        k = n - 2
    w = f - k
    if w > 1.0:
        w = 1.0
    vf = s_vf[k] * (1.0 - w) + s_vf[k + 1] * w
    dvf = (s_vf[k + 1] - s_vf[k]) / sdT
    vg = math.exp(s_lnvg[k] * (1.0 - w) + s_lnvg[k + 1] * w)
    dvg = vg * (s_lnvg[k + 1] - s_lnvg[k]) / sdT
    uf = s_uf[k] * (1.0 - w) + s_uf[k + 1] * w
    duf = (s_uf[k + 1] - s_uf[k]) / sdT
    ug = s_ug[k] * (1.0 - w) + s_ug[k + 1] * w
    dug = (s_ug[k + 1] - s_ug[k]) / sdT
    res = (u - uf) * (vg - vf) - (v - vf) * (ug - uf)
    der = -duf * (vg - vf) + (u - uf) * (dvg - dvf) + dvf * (ug - uf) - (v - vf) * (dug - duf)
    return res, der


@njit(cache=True)
def lookup(tab, rho, u):
    """Pressure, temperature and dryness from density and internal energy (compiled).

    Inputs off the table are clamped to it (:func:`lookup_flagged` says when).

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    rho : float
        Density [kg/m3].
    u : float
        Specific internal energy [J/kg].

    Returns
    -------
    p : float
        Absolute pressure [Pa].
    T : float
        Temperature [K].
    x : float
        Dryness [-], 1 for vapour.
    superheated : bool
        True where the vapour grid answered (``u`` at or above the saturated
        vapour's at that density).
    """
    p, T, x, sup, _ = lookup_flagged(tab, rho, u)
    return p, T, x, sup


@njit(cache=True, inline="always")
def lookup_flagged(tab, rho, u):
    """:func:`lookup` and a code saying whether, and how, the state was clamped.

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    rho : float
        Density [kg/m3].
    u : float
        Specific internal energy [J/kg].

    Returns
    -------
    p, T, x, superheated : float, float, float, bool
        As :func:`lookup`: pressure [Pa], temperature [K], dryness [-], vapour.
    code : int
        0 when the state is inside the table, else the bits of :data:`CLAMP_CODES`.
    """
    return lookup_near(tab, rho, u, math.nan)


@njit(cache=True, inline="always")
def lookup_near(tab, rho, u, T_near):
    """:func:`lookup_flagged`, the wet state's Newton iteration started from a
    temperature near the answer.

    The same answer (within 1e-12 K where Newton's steps converge, 2e-9 K where the
    safeguard bisects; tests/test_property_tiers.py starts it from everywhere), for
    fewer evaluations of the lever rule when ``T_near`` is close: a
    node's temperature at its previous evaluation (the integrators evaluate nearby
    states in turn), or that of the same state (a Jacobian after the right-hand side)
    takes one or two against about five from the saturated-vapour end.

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    rho : float
        Density [kg/m3].
    u : float
        Specific internal energy [J/kg].
    T_near : float
        The first temperature of the iteration [K]; ignored (the iteration starts
        from the saturated vapour at ``rho``) unless strictly inside the bracket, the
        triple point to the saturation temperature at ``rho`` (NaN: never).

    Returns
    -------
    p, T, x, superheated : float, float, float, bool
        As :func:`lookup`: pressure [Pa], temperature [K], dryness [-], vapour.
    code : int
        0 when the state is inside the table, else the bits of :data:`CLAMP_CODES`.
    """
    lnrho0, dlnrho, u0, du, q, TT, ug_row, Tg_row = (tab.lnrho0, tab.dlnrho, tab.u0, tab.du, tab.q,
                                                     tab.T, tab.ug_row, tab.Tg_row)
    sT0, sdT, s_lnp, s_vf, s_lnvg, s_uf, s_ug = (tab.sT0, tab.sdT, tab.s_lnp, tab.s_vf, tab.s_lnvg,
                                                 tab.s_uf, tab.s_ug)
    nr, nu = q.shape
    code = 0
    if not rho > 0.0:
        rho = math.exp(lnrho0)
        code |= 1
    fr = (math.log(rho) - lnrho0) / dlnrho
    if fr < 0.0:
        fr = 0.0
        code |= 1
    if fr > nr - 1.0:
        fr = nr - 1.0
        code |= 2
    i = int(fr)
    if i > nr - 2:
        i = nr - 2
    wr = fr - i
    # the density evaluated: the table's edge when clamped
    rho_c = math.exp(lnrho0 + fr * dlnrho) if code & 3 else rho
    ug0 = ug_row[i]
    ug1 = ug_row[i + 1]
    if ug0 == ug0 and ug1 == ug1:      # both rows below the critical density
        u_sat = ug0 * (1.0 - wr) + ug1 * wr
    else:
        u_sat = -1.0
    if not (u == u):
        u = u0
        code |= 32
    if u >= u_sat:
        fu = (u - u0) / du
        if fu < 0.0:
            fu = 0.0
            code |= 16       # below the triple point's vapour: only rows there reach it
        if fu > nu - 1.0:
            fu = nu - 1.0
            code |= 8
        j = int(fu)
        if j > nu - 2:
            j = nu - 2
        wu = fu - j
        a = (1.0 - wr) * (1.0 - wu)
        b = (1.0 - wr) * wu
        c = wr * (1.0 - wu)
        d = wr * wu
        qq = a * q[i, j] + b * q[i, j + 1] + c * q[i + 1, j] + d * q[i + 1, j + 1]
        T = a * TT[i, j] + b * TT[i, j + 1] + c * TT[i + 1, j] + d * TT[i + 1, j + 1]
        return qq * rho_c, T, 1.0, True, code
    # wet steam: lever rule on the saturation table
    v = 1.0 / rho_c
    lo = sT0
    hi = Tg_row[i] * (1.0 - wr) + Tg_row[i + 1] * wr
    # f(hi) < 0 known: the root lies below the saturated vapour's temperature
    hi_known = False
    T = T_near if (T_near > lo and T_near < hi) else hi
    ft, dt = _lever(T, u, v, sT0, sdT, s_vf, s_lnvg, s_uf, s_ug)
    if T == hi:
        hi_known = ft < 0.0
    if T < hi or hi_known:
        # Newton from T_near, or from the saturated-vapour end (cylinder steam is nearly
        # dry), kept inside the bracket [lo, hi] (f falls through its root), bisecting
        # when a step would leave it; each end of the bracket is evaluated only when a
        # step reaches it
        lo_known = False
        for _ in range(100):
            if ft > 0.0:
                lo = T
                lo_known = True
            else:
                hi = T
                hi_known = True
            Tn = T - ft / dt if dt < 0.0 else lo
            if dt < 0.0 and abs(Tn - T) < 1e-7:
                # converged: the next step would be below 1e-12 K (quadratic).  Tested
                # before the bracket, which the last step may graze by a rounding
                # error (a bisection there sent it away again: 16 iterations on
                # average, against 4)
                T = min(max(Tn, lo), hi)
                break
            if not Tn > lo:
                if not lo_known:
                    flo, dlo = _lever(lo, u, v, sT0, sdT, s_vf, s_lnvg, s_uf, s_ug)
                    if flo <= 0.0:
                        T = lo
                        if flo < 0.0:
                            code |= 16       # wet steam colder than the triple point
                        break
                    lo_known = True
                Tn = 0.5 * (lo + hi)
            elif not Tn < hi:
                if not hi_known:
                    # from T_near, a step beyond the saturated vapour: is the root
                    # below it at all?
                    fh, dh = _lever(hi, u, v, sT0, sdT, s_vf, s_lnvg, s_uf, s_ug)
                    if not fh < 0.0:
                        T = hi
                        break
                    hi_known = True
                Tn = 0.5 * (lo + hi)
            if abs(Tn - T) < 1e-9 or hi - lo < 1e-9:
                T = Tn
                break
            T = Tn
            ft, dt = _lever(T, u, v, sT0, sdT, s_vf, s_lnvg, s_uf, s_ug)
            if ft == 0.0:
                break
    vf = _sat_at(T, sT0, sdT, s_vf)
    vg = math.exp(_sat_at(T, sT0, sdT, s_lnvg))
    x = (v - vf) / (vg - vf)
    if x < 0.0:
        x = 0.0
    if x > 1.0:
        x = 1.0
    return math.exp(_sat_at(T, sT0, sdT, s_lnp)), T, x, False, code


@njit(cache=True, inline="always")
def kappa_at(tab, rho, u):
    """Isentropic exponent of the port flow from an upstream state (compiled).

    Bilinear on the table's grid of exponents fitted to HEOS's choked nozzle (module
    docstring), clamped to the grid (whose edges are the property range's: a state off
    it is flagged by the lookup).

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    rho : float
        Upstream density [kg/m3].
    u : float
        Upstream specific internal energy [J/kg].

    Returns
    -------
    float
        kappa [-], for :func:`corliss.thermo.orifice.mass_flux`.
    """
    k_lnrho0, k_dlnrho, k_u0, k_du, kap = tab.k_lnrho0, tab.k_dlnrho, tab.k_u0, tab.k_du, tab.kappa
    nr, nu = kap.shape
    fr = (math.log(rho) - k_lnrho0) / k_dlnrho if rho > 0.0 else 0.0
    if not fr > 0.0:
        fr = 0.0
    if fr > nr - 1.0:
        fr = nr - 1.0
    i = int(fr)
    if i > nr - 2:
        i = nr - 2
    wr = fr - i
    fu = (u - k_u0) / k_du
    if not fu > 0.0:
        fu = 0.0
    if fu > nu - 1.0:
        fu = nu - 1.0
    j = int(fu)
    if j > nu - 2:
        j = nu - 2
    wu = fu - j
    return ((1.0 - wr) * ((1.0 - wu) * kap[i, j] + wu * kap[i, j + 1])
            + wr * ((1.0 - wu) * kap[i + 1, j] + wu * kap[i + 1, j + 1]))


@njit(cache=True, inline="always")
def pressure_partials(tab, rho, u, p, T, superheated, code):
    """The pressure's partial derivatives at a state the lookup has answered, from
    the same interpolation.

    Vapour: ``p = q rho`` with ``q`` bilinear in (ln rho, u), differentiated on its
    cell.  Wet steam: the temperature solves the lever rule's residual
    ``R(T; u, v) = 0`` (:func:`_lever`), so ``dT/du = -(v_g - v_f) / R_T`` and
    ``dT/dv = (u_g - u_f) / R_T``, and ``p = exp(ln p(T))`` piecewise linear in T.
    A coordinate clamped to the table's edge has no derivative.  The answer is the
    caller's (:func:`lookup_near`'s, or for the analytic Jacobian that of the
    right-hand side just evaluated at the same state).

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    rho : float
        Density [kg/m3].
    u : float
        Specific internal energy [J/kg].
    p : float
        The pressure :func:`lookup_near` gave for (``rho``, ``u``) [Pa].
    T : float
        The temperature it gave [K].
    superheated : bool
        Whether it answered from the vapour grid.
    code : int
        Its clamp code (:data:`CLAMP_CODES`).

    Returns
    -------
    p_rho : float
        dp/drho at constant u [Pa m3/kg] (0 in a clamped density).
    p_u : float
        dp/du at constant rho [Pa kg/J] (0 in a clamped energy).
    """
    if superheated:
        lnrho0, dlnrho, u0, du, q = tab.lnrho0, tab.dlnrho, tab.u0, tab.du, tab.q
        nr, nu = q.shape
        fr = (math.log(rho) - lnrho0) / dlnrho if rho > 0.0 else 0.0
        fr = min(max(fr, 0.0), nr - 1.0)
        i = min(int(fr), nr - 2)
        wr = fr - i
        fu = min(max((u - u0) / du, 0.0), nu - 1.0)
        j = min(int(fu), nu - 2)
        wu = fu - j
        q_fr = (1.0 - wu) * (q[i + 1, j] - q[i, j]) + wu * (q[i + 1, j + 1] - q[i, j + 1])
        q_fu = (1.0 - wr) * (q[i, j + 1] - q[i, j]) + wr * (q[i + 1, j + 1] - q[i + 1, j])
        rho_c = p / ((1.0 - wr) * ((1.0 - wu) * q[i, j] + wu * q[i, j + 1])
                     + wr * ((1.0 - wu) * q[i + 1, j] + wu * q[i + 1, j + 1]))
        p_rho = 0.0 if code & 3 else p / rho_c + q_fr / dlnrho
        p_u = 0.0 if code & 24 else rho_c * q_fu / du
        return p_rho, p_u
    if code != 0:
        return 0.0, 0.0
    sT0, sdT, s_lnp, s_vf, s_lnvg, s_uf, s_ug = (tab.sT0, tab.sdT, tab.s_lnp, tab.s_vf, tab.s_lnvg,
                                                 tab.s_uf, tab.s_ug)
    f = max((T - sT0) / sdT, 0.0)
    k = min(int(f), s_lnp.shape[0] - 2)
    w = min(f - k, 1.0)
    v = 1.0 / rho
    _, der = _lever(T, u, v, sT0, sdT, s_vf, s_lnvg, s_uf, s_ug)
    vf = s_vf[k] * (1.0 - w) + s_vf[k + 1] * w
    vg = math.exp(s_lnvg[k] * (1.0 - w) + s_lnvg[k + 1] * w)
    uf = s_uf[k] * (1.0 - w) + s_uf[k + 1] * w
    ug = s_ug[k] * (1.0 - w) + s_ug[k + 1] * w
    if not der < 0.0:
        return 0.0, 0.0
    p_T = p * (s_lnp[k + 1] - s_lnp[k]) / sdT
    return p_T * (ug - uf) / der * (-v * v), p_T * (-(vg - vf) / der)


@njit(cache=True, inline="always")
def kappa_partials(tab, rho, u):
    """:func:`kappa_at` and its partial derivatives on the same bilinear cell (none
    in a coordinate clamped to the grid).

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    rho : float
        Upstream density [kg/m3].
    u : float
        Upstream specific internal energy [J/kg].

    Returns
    -------
    kappa : float
        As :func:`kappa_at` [-].
    k_rho : float
        dkappa/drho at constant u [m3/kg].
    k_u : float
        dkappa/du at constant rho [kg/J].
    """
    k_lnrho0, k_dlnrho, k_u0, k_du, kap = tab.k_lnrho0, tab.k_dlnrho, tab.k_u0, tab.k_du, tab.kappa
    nr, nu = kap.shape
    fr = (math.log(rho) - k_lnrho0) / k_dlnrho if rho > 0.0 else 0.0
    in_r = fr > 0.0 and fr < nr - 1.0
    fr = min(max(fr, 0.0), nr - 1.0)
    i = min(int(fr), nr - 2)
    wr = fr - i
    fu = (u - k_u0) / k_du
    in_u = fu > 0.0 and fu < nu - 1.0
    fu = min(max(fu, 0.0), nu - 1.0)
    j = min(int(fu), nu - 2)
    wu = fu - j
    k = ((1.0 - wr) * ((1.0 - wu) * kap[i, j] + wu * kap[i, j + 1])
         + wr * ((1.0 - wu) * kap[i + 1, j] + wu * kap[i + 1, j + 1]))
    k_fr = (1.0 - wu) * (kap[i + 1, j] - kap[i, j]) + wu * (kap[i + 1, j + 1] - kap[i, j + 1])
    k_fu = (1.0 - wr) * (kap[i, j + 1] - kap[i, j]) + wr * (kap[i + 1, j + 1] - kap[i + 1, j])
    k_rho = k_fr / (k_dlnrho * rho) if in_r else 0.0
    k_u = k_fu / k_du if in_u else 0.0
    return k, k_rho, k_u


def lookup_many(tab, rho, u):
    """Vectorised :func:`lookup`: the arrays allocated here, filled by the compiled
    :func:`lookup_into`.

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    rho : ndarray
        Densities [kg/m3], shape ``(n,)``.
    u : ndarray
        Specific internal energies [J/kg], shape ``(n,)``.

    Returns
    -------
    p, T, x : ndarray
        Absolute pressure [Pa], temperature [K] and dryness [-], each shape
        ``(n,)``.
    """
    rho = np.asarray(rho, dtype=float)
    u = np.asarray(u, dtype=float)
    p, T, x = np.empty(rho.shape[0]), np.empty(rho.shape[0]), np.empty(rho.shape[0])
    lookup_into(tab, rho, u, p, T, x)
    return p, T, x


@njit(cache=True, _nrt=False)
def lookup_into(tab, rho, u, p, T, x):
    """:func:`lookup` of each state into arrays the caller allocated (compiled).

    Each state is :func:`lookup_flagged`'s, inlined, in a function that allocates
    nothing and so counts no references (``_nrt=False``, as the kernel's loops): a
    compiled loop that allocated its outputs and called :func:`lookup` took 0.17 us a
    state on the default card's samples, this one 0.10; the same arithmetic, so the
    same values.

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    rho : ndarray
        Densities [kg/m3], shape ``(n,)``.
    u : ndarray
        Specific internal energies [J/kg], shape ``(n,)``.
    p, T, x : ndarray
        Written: absolute pressure [Pa], temperature [K] and dryness [-], each shape
        ``(n,)``.
    """
    for k in range(rho.shape[0]):
        p[k], T[k], x[k], _, _ = lookup_flagged(tab, rho[k], u[k])


# --- build and cache ------------------------------------------------------------------

def _build(params: dict) -> dict:
    import CoolProp
    import CoolProp.CoolProp as CP
    heos = CoolProp.AbstractState("HEOS", "Water")
    gas = CoolProp.AbstractState("HEOS", "Water")
    gas.specify_phase(CoolProp.iphase_gas)
    # saturation table over T
    sT = np.linspace(params["T_sat_min"], params["T_sat_max"], params["n_sat"])
    sat = np.empty((5, sT.size))
    for k, T in enumerate(sT):
        heos.update(CP.QT_INPUTS, 0.0, T)
        vf, uf = 1 / heos.rhomass(), heos.umass()
        heos.update(CP.QT_INPUTS, 1.0, T)
        sat[:, k] = (math.log(heos.p()), vf, math.log(1 / heos.rhomass()), uf, heos.umass())
    lnrho = np.linspace(math.log(params["rho_min"]), math.log(params["rho_max"]), params["n_rho"])
    u_grid = np.linspace(params["u_min"], params["u_max"], params["n_u"])
    # saturated vapour at each row density: ln rho_g rises with T
    lnrhog = -sat[2]
    ug_row = np.interp(lnrho, lnrhog, sat[4], left=np.nan, right=np.nan)
    Tg_row = np.interp(lnrho, lnrhog, sT, left=np.nan, right=np.nan)
    ug_row[lnrho < lnrhog[0]] = -1.0     # below the triple-point vapour density: all vapour
    Tg_row[lnrho < lnrhog[0]] = sT[0]
    # vapour rows: fine in T (metastable below saturation), inverted to uniform u
    T_row = np.arange(params["T_sat_min"] - 40.0, params["T_row_max"], params["T_row_step"])
    q = np.empty((lnrho.size, u_grid.size))
    TT = np.empty_like(q)
    for i, lr in enumerate(lnrho):
        rho = math.exp(lr)
        u_list: list[float] = []
        p_list: list[float] = []
        t_list: list[float] = []
        for T in T_row:
            try:
                gas.update(CP.DmassT_INPUTS, rho, T)
                p, uu = gas.p(), gas.umass()
            except ValueError:
                continue
            if not (p > 0 and math.isfinite(uu)) or (u_list and uu <= u_list[-1]):
                continue
            u_list.append(uu)
            p_list.append(p / rho)
            t_list.append(T)
        us, ps, ts = np.array(u_list), np.array(p_list), np.array(t_list)
        # below the lowest valid metastable point, extend with the lowest slope
        q[i] = np.interp(u_grid, us, ps)
        TT[i] = np.interp(u_grid, us, ts)
        lo = u_grid < us[0]
        if lo.any():
            sq = (ps[1] - ps[0]) / (us[1] - us[0])
            st = (ts[1] - ts[0]) / (us[1] - us[0])
            q[i, lo] = ps[0] + sq * (u_grid[lo] - us[0])
            TT[i, lo] = ts[0] + st * (u_grid[lo] - us[0])
    k_lnrho, k_u = kappa_axes(params)
    kappa = shipped_kappa(params)
    if kappa is None:
        kappa = _kappa_grid(k_lnrho, k_u)
    return {"lnrho0": float(lnrho[0]), "dlnrho": float(lnrho[1] - lnrho[0]),
            "u0": float(u_grid[0]), "du": float(u_grid[1] - u_grid[0]), "q": q, "T": TT,
            "ug_row": ug_row, "Tg_row": Tg_row, "sT0": float(sT[0]), "sdT": float(sT[1] - sT[0]),
            "s_lnp": sat[0], "s_vf": sat[1], "s_lnvg": sat[2], "s_uf": sat[3], "s_ug": sat[4],
            "k_lnrho0": float(k_lnrho[0]), "k_dlnrho": float(k_lnrho[1] - k_lnrho[0]),
            "k_u0": float(k_u[0]), "k_du": float(k_u[1] - k_u[0]), "kappa": kappa}


#: The port-flow exponent's grid, shipped with the package (its build is three
#: quarters of the table's: a nozzle maximisation per cell), with the parameters it
#: was built for; :func:`write_kappa_grid` remakes it.
KAPPA_FILE = Path(__file__).with_name("kappa_grid.npz")
#: The build parameters the shipped exponent grid must have been built for.
KAPPA_KEYS = ("rho_min", "rho_max", "kappa_n_rho", "kappa_u_min", "u_max", "kappa_n_u")


def kappa_axes(params: dict) -> tuple[np.ndarray, np.ndarray]:
    """The port-flow exponent's grid axes.

    Parameters
    ----------
    params : dict
        Build parameters, as :data:`PARAMS`.

    Returns
    -------
    k_lnrho : ndarray
        ln density [ln(kg/m3)], shape ``(kappa_n_rho,)``, uniform.
    k_u : ndarray
        Internal energy [J/kg], shape ``(kappa_n_u,)``, uniform.
    """
    k_lnrho = np.linspace(math.log(params["rho_min"]), math.log(params["rho_max"]),
                          params["kappa_n_rho"])
    k_u = np.linspace(params["kappa_u_min"], params["u_max"], params["kappa_n_u"])
    return k_lnrho, k_u


def shipped_kappa(params: dict, path: Path = KAPPA_FILE) -> np.ndarray | None:
    """The shipped grid of the port-flow exponent, when it was built for ``params``.

    Parameters
    ----------
    params : dict
        Build parameters, as :data:`PARAMS`; the keys of :data:`KAPPA_KEYS` must
        match the grid's.
    path : Path, optional
        The grid's file.

    Returns
    -------
    ndarray or None
        kappa [-], shape ``(kappa_n_rho, kappa_n_u)``; None when the file is missing,
        unreadable or built for other parameters (then it is computed).
    """
    try:
        with np.load(path, allow_pickle=False) as z:
            built_for = json.loads(str(z["params"]))
            kappa = np.array(z["kappa"], dtype=np.float64)
    except (OSError, KeyError, ValueError):
        return None
    if built_for != {k: params[k] for k in KAPPA_KEYS}:
        return None
    if kappa.shape != (params["kappa_n_rho"], params["kappa_n_u"]):
        return None
    return kappa


def write_kappa_grid(path: Path = KAPPA_FILE, params: dict | None = None) -> Path:
    """Compute the port-flow exponent's grid from HEOS (about 15 s) and write it.

    The file holds the grid, the parameters and the CoolProp version it was built
    with.  To remake the shipped grid::

        python -c "from corliss.thermo.steam_table import write_kappa_grid; write_kappa_grid()"

    Parameters
    ----------
    path : Path, optional
        File to write (``.npz``).
    params : dict or None, optional
        Build parameters; None for :data:`PARAMS`.

    Returns
    -------
    Path
        The file written.
    """
    params = params or PARAMS
    kappa = _kappa_grid(*kappa_axes(params))
    np.savez_compressed(path, kappa=kappa,
                        params=np.array(json.dumps({k: params[k] for k in KAPPA_KEYS})),
                        coolprop=np.array(_coolprop_version()))
    return Path(path)


TRIPLE_POINT_PA = 611.657


def choked_flux_coefficient(flash, rho0: float, u0: float) -> tuple[float, float]:
    """HEOS's isentropic nozzle from the stagnation state (``rho0``, ``u0``).

    Parameters
    ----------
    flash : CoolProp.AbstractState
        A HEOS water state to work with.
    rho0, u0 : float
        Stagnation density [kg/m3] and internal energy [J/kg].

    Returns
    -------
    tuple of float
        (``G* / sqrt(p0 rho0)`` [-], the critical pressure ratio [-]): the throat flux
        ``rho(p, s0) sqrt(2 (h0 - h(p, s0)))`` maximised over the throat pressure p
        (Brent, to 1e-6 in ratio); NaN when the stagnation state has no steam or the
        maximum would need a throat below the triple-point pressure.
    """
    import CoolProp.CoolProp as CP
    from scipy.optimize import minimize_scalar
    try:
        flash.update(CP.DmassUmass_INPUTS, rho0, u0)
        p0, h0, s0, T0 = flash.p(), flash.hmass(), flash.smass(), flash.T()
    except ValueError:
        return math.nan, math.nan
    if not (T0 >= 273.16 and p0 > 0.0):
        return math.nan, math.nan
    r_lo = max(0.3, 1.001 * TRIPLE_POINT_PA / p0)
    if r_lo > 0.9:
        return math.nan, math.nan

    def neg_flux(r):
        try:
            flash.update(CP.PSmass_INPUTS, r * p0, s0)
        except ValueError:
            return 0.0
        dh = h0 - flash.hmass()
        return -flash.rhomass() * math.sqrt(2.0 * dh) if dh > 0.0 else 0.0

    res = minimize_scalar(neg_flux, bounds=(r_lo, 0.95), method="bounded",
                          options={"xatol": 1e-6})
    if res.x < r_lo + 1e-3 or res.x > 0.95 - 1e-3 or not res.fun < 0.0:
        return math.nan, math.nan      # no interior maximum: not a choked nozzle
    return -res.fun / math.sqrt(p0 * rho0), float(res.x)


def kappa_of_flux_coefficient(c: float) -> float:
    """The exponent kappa whose Saint-Venant--Wantzel choked flux coefficient
    ``sqrt(kappa (2/(kappa+1))^((kappa+1)/(kappa-1)))`` is ``c`` (monotonic in kappa).

    The coefficient cannot fall below ``exp(-1/2) = 0.607`` (kappa -> 1); very wet steam
    (dryness under about 0.3, far wetter than a cylinder holds) chokes at less, and
    takes kappa = 1.001, the floor, whose flux is then too high.

    Parameters
    ----------
    c : float
        Choked flux coefficient ``G* / sqrt(p0 rho0)`` [-].

    Returns
    -------
    float
        kappa [-] in [:data:`~corliss.thermo.steam_table.KAPPA_FLOOR`, 2], by
        Brent's method to 1e-12.
    """
    from scipy.optimize import brentq

    def psi(k):
        return math.sqrt(k * (2.0 / (k + 1.0)) ** ((k + 1.0) / (k - 1.0))) - c
    if psi(KAPPA_FLOOR) >= 0.0:
        return KAPPA_FLOOR
    return brentq(psi, KAPPA_FLOOR, 2.0, xtol=1e-12)


#: The least port-flow exponent [-] (see :func:`kappa_of_flux_coefficient`).
KAPPA_FLOOR = 1.001


def _kappa_grid(k_lnrho: np.ndarray, k_u: np.ndarray) -> np.ndarray:
    """The port-flow exponent on the grid; a cell with no computable nozzle (below the
    triple point, or a stagnation pressure under about 2 kPa, where the throat would
    fall below the triple-point pressure) takes the value at the nearest density of
    the same energy that has one (off the range a run may visit: the kernel flags the
    state)."""
    import CoolProp
    flash = CoolProp.AbstractState("HEOS", "Water")
    kap = np.full((k_lnrho.size, k_u.size), np.nan)
    for i, lr in enumerate(k_lnrho):
        for j, u in enumerate(k_u):
            c, _ = choked_flux_coefficient(flash, math.exp(lr), u)
            if math.isfinite(c):
                kap[i, j] = kappa_of_flux_coefficient(c)
    for j in range(k_u.size):
        col = kap[:, j]
        ok = np.nonzero(np.isfinite(col))[0]
        if ok.size == 0:
            continue
        for bad in np.nonzero(~np.isfinite(col))[0]:
            col[bad] = col[ok[np.argmin(np.abs(ok - bad))]]
    for i in range(k_lnrho.size):     # a column with none at all: the nearest energy
        row = kap[i]
        ok = np.nonzero(np.isfinite(row))[0]
        for bad in np.nonzero(~np.isfinite(row))[0]:
            row[bad] = row[ok[np.argmin(np.abs(ok - bad))]]
    return kap


def measure_error(table: SteamTable, n: int = 4000, seed: int = 0) -> dict:
    """Largest relative errors of p and T, and absolute error of dryness, against HEOS.

    States: dryness 0.5 to 1 and superheat 0 to 300 K, 0.007 to 25 bar (from just
    above the triple-point pressure: the deepest condenser), plus a band
    within 2 K of saturation on both sides, where the two parts of the table meet.

    Parameters
    ----------
    table : SteamTable
        The table to measure.
    n : int, optional
        Number of random states, a quarter of each kind.
    seed : int, optional
        Seed of the random generator (the same states each time).

    Returns
    -------
    dict
        ``states``; ``max_rel_error_p`` [-], ``max_rel_error_T`` [-],
        ``max_abs_error_dryness`` [-]; ``range``: the states' description.
    """
    import CoolProp
    import CoolProp.CoolProp as CP
    rng = np.random.default_rng(seed)
    heos = CoolProp.AbstractState("HEOS", "Water")
    rho, u, ref = [], [], []
    for k in range(n):
        p = math.exp(rng.uniform(math.log(700.0), math.log(2.5e6)))
        heos.update(CP.PQ_INPUTS, p, 1.0)
        Tsat = heos.T()
        kind = k % 4
        if kind == 0:
            heos.update(CP.PQ_INPUTS, p, rng.uniform(0.5, 1.0))
        elif kind == 1:
            heos.update(CP.PT_INPUTS, p, Tsat + rng.uniform(0.05, 300.0))
        elif kind == 2:
            heos.update(CP.PT_INPUTS, p, Tsat + rng.uniform(0.01, 2.0))
        else:
            heos.update(CP.PQ_INPUTS, p, rng.uniform(0.98, 1.0))
        x = heos.Q() if heos.phase() == CoolProp.iphase_twophase else 1.0
        rho.append(heos.rhomass())
        u.append(heos.umass())
        ref.append((heos.p(), heos.T(), x))
    want = np.array(ref)
    p, T, x = lookup_many(table.arrays(), np.array(rho), np.array(u))
    return {"states": n,
            "max_rel_error_p": float(np.max(np.abs(p / want[:, 0] - 1))),
            "max_rel_error_T": float(np.max(np.abs(T / want[:, 1] - 1))),
            "max_abs_error_dryness": float(np.max(np.abs(x - want[:, 2]))),
            "range": "0.007-25 bar, dryness 0.5-1, superheat 0-300 K"}


def cache_dir() -> Path:
    """Where the table is cached.

    Returns
    -------
    Path
        ``$CORLISS_CACHE``, else ``$XDG_CACHE_HOME/corliss``, else
        ``~/.cache/corliss``.
    """
    base = os.environ.get("CORLISS_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "corliss")
    return Path(base)


_LOADED: dict[str, SteamTable] = {}
#: A table :func:`load_table` returns in place of the real one (:func:`stand_in`).
_STAND_IN: list[SteamTable] = []

#: A miniature table, built in a fraction of a second: the same arrays (and so the same
#: compiled signatures) on a coarse grid, for compiling the kernels while the real table
#: is built (``corliss.engine.first_run``).  Its values are coarse; no result is read
#: from it.
MINI_PARAMS = {**PARAMS, "n_rho": 24, "n_u": 40, "n_sat": 200, "T_row_step": 10.0}


@functools.lru_cache(maxsize=1)
def _coolprop_version() -> str:
    """CoolProp's version from its distribution's metadata (without importing it, which
    takes over a second); read once per process (reading the metadata takes 1.4 ms,
    and every run asks for the table several times)."""
    from importlib.metadata import PackageNotFoundError
    try:
        return installed_version("CoolProp")
    except PackageNotFoundError:      # pragma: no cover - an unusual install
        import CoolProp
        return CoolProp.__version__


def table_path() -> Path:
    """The disk cache's file of the steam table for :data:`PARAMS` and this CoolProp.

    Returns
    -------
    Path
        ``steam-table-<hash>.npz`` in :func:`cache_dir`, the hash of the parameters
        and the CoolProp version.
    """
    env = os.environ
    return _table_path(env.get("CORLISS_CACHE"), env.get("XDG_CACHE_HOME"), env.get("HOME"))


@functools.lru_cache(maxsize=8)
def _table_path(corliss_cache, xdg_cache_home, home) -> Path:
    """:func:`table_path` for the environment's cache variables (the arguments, which
    key the cache: a changed variable names another file)."""
    return cache_dir() / f"steam-table-{_table_key()}.npz"


@functools.lru_cache(maxsize=1)
def _table_key() -> str:
    """The hash of :data:`PARAMS` and the CoolProp version naming the table's file,
    made once per process (its JSON and hash took 40 us, and a study's every run asks
    for the table several times)."""
    return hashlib.sha1((json.dumps(PARAMS, sort_keys=True) + _coolprop_version())
                        .encode()).hexdigest()[:12]


#: The miniature table, shipped with the package (its port-flow exponent is the shipped
#: grid's, not repeated): a first run reads it without importing CoolProp.
MINI_FILE = Path(__file__).with_name("mini_table.npz")
_SCALARS = ("lnrho0", "dlnrho", "u0", "du", "sT0", "sdT", "k_lnrho0", "k_dlnrho", "k_u0",
            "k_du")


def _table_of(arrays: dict, error: dict) -> SteamTable:
    """A :class:`SteamTable` of the arrays read from a file (its scalars as floats, its
    arrays contiguous float64, as the compiled lookup takes them)."""
    fields: dict[str, Any] = {
        k: (float(v) if k in _SCALARS else np.ascontiguousarray(v, dtype=np.float64))
        for k, v in arrays.items()}
    return SteamTable(error=error, **fields)


def write_mini_table(path: Path = MINI_FILE) -> Path:
    """Build the miniature table from HEOS and write it (its port-flow exponent left
    out: the shipped grid's is read with it).

    To remake the shipped miniature table::

        python -c "from corliss.thermo.steam_table import write_mini_table; write_mini_table()"

    Parameters
    ----------
    path : Path, optional
        File to write (``.npz``).

    Returns
    -------
    Path
        The file written.
    """
    built = _build(MINI_PARAMS)
    built.pop("kappa")
    saved: dict[str, Any] = {k: np.asarray(v) for k, v in built.items()}
    np.savez_compressed(path, params=np.array(json.dumps(MINI_PARAMS)), **saved)
    return Path(path)


def mini_table() -> SteamTable:
    """A coarse table of :data:`MINI_PARAMS` (not cached, not measured).

    Returns
    -------
    SteamTable
        The shipped one, or built from HEOS when it is missing or was made for other
        parameters; its ``error`` holds only its parameters.
    """
    kappa = shipped_kappa(MINI_PARAMS)
    try:
        with np.load(MINI_FILE, allow_pickle=False) as z:
            if kappa is not None and json.loads(str(z["params"])) == MINI_PARAMS:
                arrays = {k: z[k] for k in z.files if k != "params"}
                return _table_of({**arrays, "kappa": kappa}, {"params": MINI_PARAMS})
    except (OSError, KeyError, ValueError):
        pass
    return SteamTable(error={"params": MINI_PARAMS}, **_build(MINI_PARAMS))


@contextlib.contextmanager
def stand_in(table: SteamTable):
    """Within the block, :func:`load_table` returns ``table``.

    Parameters
    ----------
    table : SteamTable
        The table to stand in for the real one.

    Yields
    ------
    SteamTable
        ``table``.
    """
    _STAND_IN.append(table)
    try:
        yield table
    finally:
        _STAND_IN.remove(table)


def _save(path: Path, data: dict) -> None:
    """Write the table's arrays to the cache file ``path`` whole (a temporary file moved
    into place), uncompressed: a warm run reads its 10 MB in a few milliseconds, where
    inflating a compressed file (5 MB less disk) took about 0.1 s of every run.

    The temporary file, in the cache's own folder and named by the process, is removed
    on any exit from the save (an error, Ctrl-C); one a killed process left is removed
    by the next save (:func:`_remove_stale_temporaries`)."""
    tmp = None
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        _remove_stale_temporaries(path)
        tmp = path.with_suffix(f".{os.getpid()}.tmp.npz")
        np.savez(tmp, **data)
        os.replace(tmp, path)
        tmp = None
    except OSError as exc:   # a read-only home: keep it in memory only
        log.warning("could not cache the steam table at %s: %s", path, exc)
    finally:
        if tmp is not None:
            with contextlib.suppress(OSError):
                tmp.unlink(missing_ok=True)


def _remove_stale_temporaries(path: Path) -> None:
    """Remove the temporary files of ``path`` whose process is gone (killed while saving:
    10 MB each, never removed before).  POSIX only: elsewhere ``os.kill`` does not ask
    whether a process lives."""
    if os.name != "posix":
        return
    for f in path.parent.glob(path.stem + ".*.tmp.npz"):
        try:
            pid = int(f.name.split(".")[-3])
        except (ValueError, IndexError):
            continue
        if pid == os.getpid():
            continue
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            with contextlib.suppress(OSError):
                f.unlink()
                log.debug("removed %s, left by a process killed while saving", f)
        except OSError:      # alive, another user's (PermissionError), or unknowable
            pass


def load_table() -> SteamTable:
    """The steam table: from memory, from the disk cache, or built from HEOS (and cached).

    Building takes a few seconds, once a machine; a read-only cache directory keeps
    the table in memory only, with a warning.

    Returns
    -------
    SteamTable
        The table of :data:`PARAMS`, with its measured error; the stand-in within
        :func:`stand_in`.
    """
    if _STAND_IN:
        return _STAND_IN[-1]
    path = table_path()
    key = path.stem
    if key in _LOADED:
        return _LOADED[key]
    data = None
    if path.is_file():
        try:
            with np.load(path, allow_pickle=False) as z:
                data = {k: z[k] for k in z.files}
                deflated = any(i.compress_type != zipfile.ZIP_STORED for i in z.zip.infolist())
        except (OSError, ValueError, zipfile.BadZipFile):
            data = None
        else:
            if deflated:     # a cache written compressed (before 0.2.1): store it plain once
                _save(path, data)
    if data is None:
        log.log(NOTICE, "building the steam table once for this machine (a few seconds); "
                "it is cached in %s", path.parent)
        t0 = time.perf_counter()
        built = _build(PARAMS)
        tab = SteamTable(error={}, **built)
        err = measure_error(tab)
        err["build_seconds"] = time.perf_counter() - t0
        err["params"] = PARAMS
        err["coolprop"] = _coolprop_version()
        log.info("built steam table in %.1f s: %s", err["build_seconds"], err)
        data = {k: np.asarray(v) for k, v in built.items()}
        data["meta"] = np.array(json.dumps(err))
        _save(path, data)
    meta = json.loads(str(data.pop("meta")))
    tab = _table_of(data, meta)
    _LOADED[key] = tab
    return tab


@njit(cache=True, inline="always")
def t_sat(tab, p):
    """Saturation temperature at a pressure (compiled): bisection on the table's
    ln p_sat over its uniform temperature grid, linear within the cell.

    Parameters
    ----------
    tab : tuple
        The table's arrays, :meth:`SteamTable.arrays`.
    p : float
        Absolute pressure [Pa].

    Returns
    -------
    float
        Saturation temperature [K], clamped to the saturation table's range.
    """
    sT0, sdT, s_lnp = tab.sT0, tab.sdT, tab.s_lnp
    lp = math.log(p)
    n = s_lnp.shape[0]
    if lp <= s_lnp[0]:
        return sT0
    if lp >= s_lnp[n - 1]:
        return sT0 + sdT * (n - 1)
    lo, hi = 0, n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if s_lnp[mid] <= lp:
            lo = mid
        else:
            hi = mid
    w = (lp - s_lnp[lo]) / (s_lnp[hi] - s_lnp[lo])
    return sT0 + sdT * (lo + w)
