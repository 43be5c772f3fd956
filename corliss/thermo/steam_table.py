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
  energy, ``(u - u_f)(v_g - v_f) = (v - v_f)(u_g - u_f)``, found by bracketed
  regula falsi (Illinois).

Which part applies is decided by the saturated-vapour energy ``u_g`` at the state's
density.  Every index is clamped, so no input can read outside the arrays: a state
off the table is evaluated at the nearest edge, never crashes (a crash near
saturation at 0.18 bar is what ruled out CoolProp's TTSE backend).
"""

from __future__ import annotations

import hashlib
import json
import logging
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numba import njit

from corliss.logs import NOTICE

log = logging.getLogger(__name__)

#: Build parameters; their hash names the cache file.
PARAMS = {
    "version": 1,
    "rho_min": 0.01, "rho_max": 80.0, "n_rho": 481,        # kg/m3, geometric
    "u_min": 2.0e6, "u_max": 3.9e6, "n_u": 951,            # J/kg, uniform
    "T_row_step": 0.5, "T_row_max": 1250.0,                # K, fine rows for inversion
    "T_sat_min": 273.16, "T_sat_max": 646.0, "n_sat": 7500,
}


def covers(rho: float, u: float) -> bool:
    """True when the table spans density ``rho`` [kg/m3] and internal energy ``u``
    [J/kg] (its build parameters, :data:`PARAMS`)."""
    return (PARAMS["rho_min"] <= rho <= PARAMS["rho_max"]
            and PARAMS["u_min"] <= u <= PARAMS["u_max"])


@dataclass(frozen=True)
class SteamTable:
    """Arrays of the table (all SI).  Build with :func:`load_table`."""

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
    error: dict          # measured error against HEOS

    def arrays(self):
        """The tuple the compiled lookup takes."""
        return (self.lnrho0, self.dlnrho, self.u0, self.du, self.q, self.T, self.ug_row,
                self.Tg_row, self.sT0, self.sdT, self.s_lnp, self.s_vf, self.s_lnvg, self.s_uf,
                self.s_ug)


# --- compiled lookup ------------------------------------------------------------------

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
def lookup(tab, rho, u):
    """(p [Pa], T [K], dryness [-], superheated) at density ``rho`` and energy ``u``.

    ``tab`` is :meth:`SteamTable.arrays`.  Inputs off the table are clamped to it.
    """
    (lnrho0, dlnrho, u0, du, q, TT, ug_row, Tg_row, sT0, sdT, s_lnp, s_vf, s_lnvg,
     s_uf, s_ug) = tab
    nr, nu = q.shape
    if not rho > 0.0:
        rho = math.exp(lnrho0)
    fr = (math.log(rho) - lnrho0) / dlnrho
    if fr < 0.0:
        fr = 0.0
    if fr > nr - 1.0:
        fr = nr - 1.0
    i = int(fr)
    if i > nr - 2:
        i = nr - 2
    wr = fr - i
    rho_c = math.exp(lnrho0 + fr * dlnrho)
    ug0 = ug_row[i]
    ug1 = ug_row[i + 1]
    if ug0 == ug0 and ug1 == ug1:      # both rows below the critical density
        u_sat = ug0 * (1.0 - wr) + ug1 * wr
    else:
        u_sat = -1.0
    if not (u == u):
        u = u0
    if u >= u_sat:
        fu = (u - u0) / du
        if fu < 0.0:
            fu = 0.0
        if fu > nu - 1.0:
            fu = nu - 1.0
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
        return qq * rho_c, T, 1.0, True
    # wet steam: lever rule on the saturation table
    v = 1.0 / rho_c
    lo = sT0
    hi = Tg_row[i] * (1.0 - wr) + Tg_row[i + 1] * wr

    def f(T):
        vf = _sat_at(T, sT0, sdT, s_vf)
        vg = math.exp(_sat_at(T, sT0, sdT, s_lnvg))
        uf = _sat_at(T, sT0, sdT, s_uf)
        ugs = _sat_at(T, sT0, sdT, s_ug)
        return (u - uf) * (vg - vf) - (v - vf) * (ugs - uf)

    flo = f(lo)
    fhi = f(hi)
    T = lo
    if flo <= 0.0:
        T = lo
    elif fhi >= 0.0:
        T = hi
    else:
        side = 0
        for _ in range(100):
            T = (lo * fhi - hi * flo) / (fhi - flo)
            ft = f(T)
            if ft == 0.0 or hi - lo < 1e-9:
                break
            if ft > 0.0:
                lo, flo = T, ft
                if side == 1:
                    fhi *= 0.5
                side = 1
            else:
                hi, fhi = T, ft
                if side == -1:
                    flo *= 0.5
                side = -1
            if abs(ft) < 1e-12 * abs(u) * abs(v):
                break
    vf = _sat_at(T, sT0, sdT, s_vf)
    vg = math.exp(_sat_at(T, sT0, sdT, s_lnvg))
    x = (v - vf) / (vg - vf)
    if x < 0.0:
        x = 0.0
    if x > 1.0:
        x = 1.0
    return math.exp(_sat_at(T, sT0, sdT, s_lnp)), T, x, False


@njit(cache=True)
def lookup_many(tab, rho, u):
    """Vectorised :func:`lookup`: arrays of p, T, dryness."""
    n = rho.shape[0]
    p = np.empty(n)
    T = np.empty(n)
    x = np.empty(n)
    for k in range(n):
        p[k], T[k], x[k], _ = lookup(tab, rho[k], u[k])
    return p, T, x


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
        us, ps, ts = [], [], []
        for T in T_row:
            try:
                gas.update(CP.DmassT_INPUTS, rho, T)
                p, uu = gas.p(), gas.umass()
            except ValueError:
                continue
            if not (p > 0 and math.isfinite(uu)) or (us and uu <= us[-1]):
                continue
            us.append(uu)
            ps.append(p / rho)
            ts.append(T)
        us, ps, ts = np.array(us), np.array(ps), np.array(ts)
        # below the lowest valid metastable point, extend with the lowest slope
        q[i] = np.interp(u_grid, us, ps)
        TT[i] = np.interp(u_grid, us, ts)
        lo = u_grid < us[0]
        if lo.any():
            sq = (ps[1] - ps[0]) / (us[1] - us[0])
            st = (ts[1] - ts[0]) / (us[1] - us[0])
            q[i, lo] = ps[0] + sq * (u_grid[lo] - us[0])
            TT[i, lo] = ts[0] + st * (u_grid[lo] - us[0])
    return {"lnrho0": float(lnrho[0]), "dlnrho": float(lnrho[1] - lnrho[0]),
            "u0": float(u_grid[0]), "du": float(u_grid[1] - u_grid[0]), "q": q, "T": TT,
            "ug_row": ug_row, "Tg_row": Tg_row, "sT0": float(sT[0]), "sdT": float(sT[1] - sT[0]),
            "s_lnp": sat[0], "s_vf": sat[1], "s_lnvg": sat[2], "s_uf": sat[3], "s_ug": sat[4]}


def measure_error(table: SteamTable, n: int = 4000, seed: int = 0) -> dict:
    """Largest relative errors of p and T, and absolute error of dryness, against HEOS.

    States: dryness 0.5 to 1 and superheat 0 to 300 K, 0.05 to 25 bar, plus a band
    within 2 K of saturation on both sides, where the two parts of the table meet.
    """
    import CoolProp
    import CoolProp.CoolProp as CP
    rng = np.random.default_rng(seed)
    heos = CoolProp.AbstractState("HEOS", "Water")
    rho, u, ref = [], [], []
    for k in range(n):
        p = math.exp(rng.uniform(math.log(5e3), math.log(2.5e6)))
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
    ref = np.array(ref)
    p, T, x = lookup_many(table.arrays(), np.array(rho), np.array(u))
    return {"states": n,
            "max_rel_error_p": float(np.max(np.abs(p / ref[:, 0] - 1))),
            "max_rel_error_T": float(np.max(np.abs(T / ref[:, 1] - 1))),
            "max_abs_error_dryness": float(np.max(np.abs(x - ref[:, 2]))),
            "range": "0.05-25 bar, dryness 0.5-1, superheat 0-300 K"}


def cache_dir() -> Path:
    """Where the table is cached: ``$CORLISS_CACHE`` or the user's cache directory."""
    base = os.environ.get("CORLISS_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "corliss")
    return Path(base)


_LOADED: dict[str, SteamTable] = {}


def _coolprop_version() -> str:
    """CoolProp's version from its distribution's metadata (without importing it, which
    takes over a second)."""
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("CoolProp")
    except PackageNotFoundError:      # pragma: no cover - an unusual install
        import CoolProp
        return CoolProp.__version__


def load_table() -> SteamTable:
    """The steam table: from memory, from the disk cache, or built from HEOS (and cached)."""
    key = hashlib.sha1((json.dumps(PARAMS, sort_keys=True) + _coolprop_version())
                       .encode()).hexdigest()[:12]
    if key in _LOADED:
        return _LOADED[key]
    path = cache_dir() / f"steam-table-{key}.npz"
    data = None
    if path.is_file():
        try:
            with np.load(path, allow_pickle=False) as z:
                data = {k: z[k] for k in z.files}
        except (OSError, ValueError):
            data = None
    if data is None:
        log.log(NOTICE, "building the steam table once for this machine (about a minute); "
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
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_suffix(f".{os.getpid()}.tmp.npz")
            np.savez_compressed(tmp, **data)
            os.replace(tmp, path)
        except OSError as exc:   # a read-only home: keep it in memory only
            log.warning("could not cache the steam table at %s: %s", path, exc)
    meta = json.loads(str(data.pop("meta")))
    scal = ("lnrho0", "dlnrho", "u0", "du", "sT0", "sdT")
    kw = {k: (float(v) if k in scal else np.ascontiguousarray(v, dtype=np.float64))
          for k, v in data.items()}
    tab = SteamTable(error=meta, **kw)
    _LOADED[key] = tab
    return tab


@njit(cache=True)
def t_sat(tab, p):
    """Saturation temperature [K] at pressure ``p`` [Pa]: bisection on the table's
    ln p_sat over its uniform temperature grid, linear within the cell."""
    sT0, sdT, s_lnp = tab[8], tab[9], tab[10]
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
