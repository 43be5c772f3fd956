"""Steam properties behind one interface.

A control volume carries density and specific internal energy; everything else
(pressure, temperature, enthalpy, entropy, dryness) comes from a :class:`Steam`
backend.  The reference backend is CoolProp's Helmholtz equation of state for water
(IAPWS-95) through the low-level ``AbstractState`` interface: one ``update`` per
state, never ``PropsSI`` in a loop.

Faster tiers (tables, perfect steam) implement the same methods.
"""

from __future__ import annotations

from typing import NamedTuple

import math

import numpy as np

from corliss.errors import InputError
from corliss.thermo import table_states


class State(NamedTuple):
    """A thermodynamic state of steam (all SI, absolute pressure).

    Parameters
    ----------
    p : float
        Pressure [Pa].
    T : float
        Temperature [K].
    rho : float
        Density [kg/m3].
    u : float
        Specific internal energy [J/kg].
    h : float
        Specific enthalpy [J/kg].
    s : float
        Specific entropy [J/(kg K)].
    x : float
        Dryness fraction [-]: in [0, 1] for wet steam, 1 for superheated vapour,
        0 for compressed liquid.
    superheated : bool
        True for single-phase vapour.
    """

    p: float
    T: float
    rho: float
    u: float
    h: float
    s: float
    x: float
    superheated: bool


class Steam:
    """Interface of a steam-property backend.

    Every method returns a :class:`State`.  Subclasses set ``name`` (the tier name
    that goes into result metadata) and ``description``.
    """

    name = "abstract"
    description = ""
    #: True when every method is answered by this tier itself (entropy included).
    complete = True
    #: Code of the tier in the compiled kernel, or None if it has none.
    kernel_tier: int | None = None

    def du(self, rho: float, u: float) -> State:  # pragma: no cover - interface
        """State from density and specific internal energy (the control volume's own
        variables).

        Parameters
        ----------
        rho : float
            Density [kg/m3].
        u : float
            Specific internal energy [J/kg].

        Returns
        -------
        State
            The state, all SI.
        """
        raise NotImplementedError

    def ph(self, p: float, h: float) -> State:  # pragma: no cover - interface
        """State from pressure and specific enthalpy.

        Parameters
        ----------
        p : float
            Absolute pressure [Pa].
        h : float
            Specific enthalpy [J/kg].

        Returns
        -------
        State
            The state, all SI.
        """
        raise NotImplementedError

    def ps(self, p: float, s: float) -> State:  # pragma: no cover - interface
        """State from pressure and specific entropy.

        Parameters
        ----------
        p : float
            Absolute pressure [Pa].
        s : float
            Specific entropy [J/(kg K)].

        Returns
        -------
        State
            The state, all SI.
        """
        raise NotImplementedError

    def ds(self, rho: float, s: float) -> State:  # pragma: no cover - interface
        """State from density and specific entropy.

        Parameters
        ----------
        rho : float
            Density [kg/m3].
        s : float
            Specific entropy [J/(kg K)].

        Returns
        -------
        State
            The state, all SI.
        """
        raise NotImplementedError

    def pt(self, p: float, T: float) -> State:  # pragma: no cover - interface
        """State from pressure and temperature (single phase only: on the saturation
        line the two do not fix the state).

        Parameters
        ----------
        p : float
            Absolute pressure [Pa].
        T : float
            Temperature [K].

        Returns
        -------
        State
            The state, all SI.
        """
        raise NotImplementedError

    def px(self, p: float, x: float) -> State:  # pragma: no cover - interface
        """Saturated state from pressure and dryness.

        Parameters
        ----------
        p : float
            Absolute pressure [Pa].
        x : float
            Dryness fraction [-]: 0 saturated liquid, 1 dry saturated vapour.

        Returns
        -------
        State
            The state, all SI.
        """
        raise NotImplementedError

    def states(self, rho: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Pressure, temperature and dryness of many states at once (for output; a
        compiled tier answers in one call, this default calls :meth:`du` per state).

        Parameters
        ----------
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
        st = [self.du(r, e) for r, e in zip(np.asarray(rho, float), np.asarray(u, float))]
        return (np.array([x.p for x in st]), np.array([x.T for x in st]),
                np.array([x.x for x in st]))

    def t_sat(self, p: float) -> float:  # pragma: no cover - interface
        """Saturation temperature at a pressure.

        Parameters
        ----------
        p : float
            Absolute pressure [Pa].

        Returns
        -------
        float
            Saturation temperature [K].
        """
        raise NotImplementedError


class HEOSSteam(Steam):
    """IAPWS-95 water through CoolProp's HEOS backend (the reference tier).

    Notes
    -----
    Measured on the development machine: an ``update`` with density and internal
    energy costs 20-60 us, which is why faster tiers exist.
    """

    name = "heos"
    description = "CoolProp HEOS (IAPWS-95), AbstractState"

    def __init__(self) -> None:
        # CoolProp is imported here, not with the module: it takes over a second, and
        # commands that need no properties (list, events, gear) should not pay it
        import CoolProp
        import CoolProp.CoolProp as CP
        self._CP = CP
        self._as = CoolProp.AbstractState("HEOS", "Water")
        self._twophase = CoolProp.iphase_twophase
        self._liquid = (CoolProp.iphase_liquid,)

    def _state(self) -> State:
        a = self._as
        phase = a.phase()
        if phase == self._twophase:
            x = a.Q()
            sup = False
        elif phase in self._liquid:
            x = 0.0
            sup = False
        else:
            x = 1.0
            sup = True
        return State(a.p(), a.T(), a.rhomass(), a.umass(), a.hmass(), a.smass(), x, sup)

    def _update(self, pair: int, a: float, b: float, what: str) -> State:
        try:
            self._as.update(pair, a, b)
        except ValueError as exc:
            raise ValueError(f"steam state not found from {what} = ({a:.6g}, {b:.6g}): "
                             f"{exc}") from None
        return self._state()

    def du(self, rho, u):
        return self._update(self._CP.DmassUmass_INPUTS, rho, u, "density, internal energy")

    def ph(self, p, h):
        return self._update(self._CP.HmassP_INPUTS, h, p, "enthalpy, pressure")

    def ps(self, p, s):
        return self._update(self._CP.PSmass_INPUTS, p, s, "pressure, entropy")

    def ds(self, rho, s):
        return self._update(self._CP.DmassSmass_INPUTS, rho, s, "density, entropy")

    def pt(self, p, T):
        return self._update(self._CP.PT_INPUTS, p, T, "pressure, temperature")

    def px(self, p, x):
        return self._update(self._CP.PQ_INPUTS, p, x, "pressure, dryness")

    def t_sat(self, p):
        return self._update(self._CP.PQ_INPUTS, p, 1.0, "pressure, dryness").T


class TableSteam(Steam):
    """The project's own (density, internal energy) table (:mod:`corliss.thermo.steam_table`).

    ``du`` comes from the table (entropy is not tabulated: ``s`` is NaN).  The states a
    run sets up its reservoirs with, ``px``, ``pt`` and ``t_sat``, come from the table's
    arrays too (:mod:`corliss.thermo.table_states`, entropy included), so a run on this
    tier never imports CoolProp; ``ph``, ``ps`` and ``ds`` (the ideal-port models), and
    a state off the arrays, are HEOS's, CoolProp imported on the first such call.  The
    table's measured error against HEOS is in ``self.error``.
    """

    name = "table"
    description = "corliss (density, internal energy) table built from HEOS"
    complete = False
    kernel_tier = 0

    def __init__(self) -> None:
        from corliss.thermo.steam_table import load_table
        self.table = load_table()
        self.error = self.table.error
        self._arrays = self.table.arrays()
        self._heos_tier: HEOSSteam | None = None

    @property
    def _heos(self) -> HEOSSteam:
        if self._heos_tier is None:
            self._heos_tier = HEOSSteam()
        return self._heos_tier

    def du(self, rho, u):
        from corliss.thermo.steam_table import lookup
        p, T, x, sup = lookup(self._arrays, rho, u)
        return State(p, T, rho, u, u + p / rho, float("nan"), x, bool(sup))

    def states(self, rho, u):
        from corliss.thermo.steam_table import lookup_many
        return lookup_many(self._arrays, np.asarray(rho, float), np.asarray(u, float))

    def px(self, p, x):
        st = table_states.px(self.table, p, x)
        return State(*st) if st is not None else self._heos.px(p, x)

    def pt(self, p, T):
        st = table_states.pt(self.table, p, T)
        return State(*st) if st is not None else self._heos.pt(p, T)

    def t_sat(self, p):
        T = table_states.t_sat(self.table, p)
        return T if T is not None else self._heos.t_sat(p)

    def ph(self, p, h):
        return self._heos.ph(p, h)

    def ps(self, p, s):
        return self._heos.ps(p, s)

    def ds(self, rho, s):
        return self._heos.ds(rho, s)


class PerfectSteam(Steam):
    """Perfect steam: an ideal gas with R = 461.52 J/(kg K) and kappa = 1.3, never wet.

    A fast sanity model: with it, a card has no condensation and no real-gas
    departure (about 5 % in density at 7 bar).  Energy is referred so that u matches
    dry saturated steam at 100 degC; only differences of energy matter.  ``px`` and
    ``t_sat`` take the saturation temperature from HEOS, so reservoirs sit where the
    real ones do.
    """

    name = "perfect"
    description = "perfect steam, ideal gas R = 461.52 J/(kg K), kappa = 1.3"
    kernel_tier = 1
    R = 461.52
    KAPPA = 1.3
    CV = R / (KAPPA - 1.0)
    CP_ = CV + R
    T0, P0 = 373.15, 101_325.0
    U_REF = 2.5066e6 - CV * 373.15

    def __init__(self) -> None:
        self._heos = HEOSSteam()

    def _state(self, p, T):
        rho = p / (self.R * T)
        u = self.U_REF + self.CV * T
        s = self.CP_ * math.log(T / self.T0) - self.R * math.log(p / self.P0)
        return State(p, T, rho, u, u + self.R * T, s, 1.0, True)

    def du(self, rho, u):
        T = (u - self.U_REF) / self.CV
        return self._state(rho * self.R * T, T)

    def ph(self, p, h):
        return self._state(p, (h - self.U_REF) / self.CP_)

    def ps(self, p, s):
        return self._state(p, self.T0 * math.exp((s + self.R * math.log(p / self.P0)) / self.CP_))

    def ds(self, rho, s):
        # s = cv ln(T/T0) - R ln(rho R T0 / P0)
        T = self.T0 * math.exp((s + self.R * math.log(rho * self.R * self.T0 / self.P0)) / self.CV)
        return self._state(rho * self.R * T, T)

    def pt(self, p, T):
        return self._state(p, T)

    def px(self, p, x):
        return self._state(p, self._heos.t_sat(p))

    def t_sat(self, p):
        return self._heos.t_sat(p)

    def perfect_params(self):
        """The perfect gas's constants, for the compiled kernel.

        Returns
        -------
        tuple of float
            ``(R, cv, u_ref)``: gas constant [J/(kg K)], specific heat at constant
            volume [J/(kg K)] and the internal energy extrapolated to 0 K [J/kg]
            (``u = u_ref + cv T``, matching dry saturated steam at 100 degC).
        """
        return (self.R, self.CV, self.U_REF)


#: Registry of property tiers by name.
BACKENDS: dict[str, type[Steam]] = {"heos": HEOSSteam, "table": TableSteam,
                                    "perfect": PerfectSteam}


def make_steam(name: str = "heos") -> Steam:
    """Build a property backend by tier name.

    Parameters
    ----------
    name : str, optional
        One of :data:`~corliss.thermo.steam.BACKENDS`: ``"heos"`` (CoolProp
        IAPWS-95, the reference), ``"table"`` or ``"perfect"``.

    Returns
    -------
    Steam
        A new backend of that tier.

    Raises
    ------
    InputError
        Naming ``run.properties``, for an unknown tier.
    """
    try:
        return BACKENDS[name]()
    except KeyError:
        raise InputError("run.properties", name,
                         "one of " + ", ".join(sorted(BACKENDS))) from None


def latent_heat(T_K: float) -> float:
    """Latent heat of evaporation ``h_g - h_f`` (IAPWS-95 through CoolProp).

    Parameters
    ----------
    T_K : float
        Saturation temperature [K], below the critical point.

    Returns
    -------
    float
        Latent heat [J/kg].
    """
    import CoolProp.CoolProp as CP
    return (CP.PropsSI("H", "T", T_K, "Q", 1.0, "Water")
            - CP.PropsSI("H", "T", T_K, "Q", 0.0, "Water"))


def saturated_vapour_density(T_K: float) -> float:
    """Density of dry saturated steam (IAPWS-95 through CoolProp).

    Parameters
    ----------
    T_K : float
        Saturation temperature [K], below the critical point.

    Returns
    -------
    float
        Density of the saturated vapour [kg/m3].
    """
    import CoolProp.CoolProp as CP
    return CP.PropsSI("D", "T", T_K, "Q", 1.0, "Water")


def coolprop_version() -> str:
    """CoolProp version and git revision, for result metadata.

    Returns
    -------
    str
        ``"<version> (<first 10 characters of the git revision>)"``.
    """
    import CoolProp
    import CoolProp.CoolProp as CP
    return f"{CoolProp.__version__} ({CP.get_global_param_string('gitrevision')[:10]})"
