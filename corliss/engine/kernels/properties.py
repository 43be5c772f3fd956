"""Steam properties of the network's nodes in compiled code: the clamps on trial states,
the lookup of each node's pressure, temperature and enthalpy from its mass and energy
through the property tier (the steam table of :mod:`corliss.thermo.steam_table`, or
the perfect gas), and the rows of the node-property scratch ``pr`` (``PR_*``).
"""

from __future__ import annotations

import numpy as np

from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.data import H_MODEL, WALL_NONE
from corliss.engine.kernels.mechanism import end_volume, piston_position
from corliss.thermo.steam_table import PARAMS, kappa_at, lookup_near, t_sat


TIER_TABLE, TIER_PERFECT = 0, 1


#: Clamps on trial states: integrators probe states with no steam (a negative mass in
#: a stiff blow-down); clamping keeps the right-hand side defined and its flows push
#: the state back.  The bounds are the steam table's (and its port-flow exponent's):
#: a state inside them is evaluated, not clamped.  Every clamped evaluation is
#: flagged (row ``PR_CLAMP`` of the node properties, the bits of
#: :data:`corliss.thermo.steam_table.CLAMP_CODES`) and counted by the integrators: a
#: state the run visits (where an accepted step starts or ends) that needed one stops
#: the run; a trial state (a stage inside a step, a Jacobian's probe, or any state of
#: a rejected step) is counted.  Inside a stiff step an L-stable method's stages may
#: leave the physical range while the step's result stays accurate.
RHO_MIN = PARAMS["rho_min"]     # [kg/m3], below dry saturated steam at the triple point


RHO_MAX = PARAMS["rho_max"]     # [kg/m3], dry saturated steam near 12.5 MPa


U_MIN = PARAMS["kappa_u_min"]   # [J/kg], saturated water at the triple point


U_MAX = PARAMS["u_max"]         # [J/kg], superheated steam beyond 1273 K


def visited_states(steam, rho, u):
    """Pressure, temperature and dryness of states a run visited, as its right-hand
    side read them.

    The one clamp a run goes on with (:mod:`corliss.engine.crank_resolved`) is steam
    heated beyond the properties' greatest energy (Marks's law heating the thin
    exhaust steam): the right-hand side read such a state at that energy, the table
    tier's lookup answers it there too, and on a tier that asks CoolProp (HEOS, which
    finds no state beyond 3000 K) it is read there as well, not left to fail.

    Parameters
    ----------
    steam : corliss.thermo.steam.Steam
        The run's steam properties.
    rho : numpy.ndarray
        Densities [kg/m3].
    u : numpy.ndarray
        Specific internal energies [J/kg].

    Returns
    -------
    tuple of numpy.ndarray
        Pressure [Pa], temperature [K] and dryness [-] of each state.
    """
    if steam.kernel_tier is None:
        u = np.minimum(u, U_MAX)
    return steam.states(rho, u)


#: Rows of the node-property scratch ``pr`` (see :func:`node_states`).
PR_ROWS = 14


#: rows of the node properties: pressure [Pa], density [kg/m3], specific enthalpy
#: [J/kg], the port flow's exponent [-], the volume's rate dV/dtheta [m3/rad], the
#: volume [m3], the temperature [K] and the saturation temperature at the pressure [K]
PR_P, PR_RHO, PR_H, PR_KAPPA, PR_DV, PR_V, PR_T, PR_TSAT = 0, 1, 2, 3, 4, 5, 6, 7


#: entries of the perfect tier's parameters ``perf``: gas constant [J/(kg K)], cv
#: [J/(kg K)] and the energy at 0 K [J/kg]
PERF_R, PERF_CV, PERF_U_REF = 0, 1, 2


#: row of the node properties holding each node's clamp code of the latest evaluation
PR_CLAMP = 8


#: row of the node properties holding the mixture's dryness [-] (1 when superheated)
PR_X = 9


#: row of the node properties saying whether the table answered from its vapour grid
#: (1.0) or the lever rule (0.0), for :func:`_jacobian_exact` after :func:`rhs`
PR_SUP = 10


#: rows of the node properties holding the evaluation's shaft angle [rad] and the
#: node's mass [kg] and energy [J] there: the state the properties are of, by which
#: :func:`_jacobian_exact` knows it may take them
PR_AT = 11


@njit(cache=True, inline="always")
def admissible(rho, u):
    """Density and internal energy clamped to where steam properties exist.

    Parameters
    ----------
    rho : float
        Density [kg/m3].
    u : float
        Specific internal energy [J/kg].

    Returns
    -------
    rho : float
        Within [:data:`RHO_MIN`, :data:`RHO_MAX`] [kg/m3].
    u : float
        Within [:data:`U_MIN`, :data:`U_MAX`] [J/kg].
    """
    rho, u, _ = admissible_flagged(rho, u)
    return rho, u


@njit(cache=True, inline="always")
def admissible_flagged(rho, u):
    """:func:`admissible` and its clamp code.

    Parameters
    ----------
    rho : float
        Density [kg/m3] (NaN counts as below the range).
    u : float
        Specific internal energy [J/kg] (NaN counts as below the range).

    Returns
    -------
    rho : float
        The clamped density [kg/m3].
    u : float
        The clamped internal energy [J/kg].
    code : int
        0 when nothing was clamped; else the bits of
        :data:`corliss.thermo.steam_table.CLAMP_CODES` (1 density low, 2 high, 4
        energy low, 8 high).
    """
    code = 0
    if not rho > RHO_MIN:
        rho = RHO_MIN
        code |= 1
    if rho > RHO_MAX:
        rho = RHO_MAX
        code |= 2
    if not u > U_MIN:
        u = U_MIN
        code |= 4
    if u > U_MAX:
        u = U_MAX
        code |= 8
    return rho, u, code


@njit(cache=True, inline="always")
def props(tier, tab, perf, rho, u, T_near):
    """Properties of a state on a compiled tier, its inputs clamped first.

    Parameters
    ----------
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    rho : float
        Density [kg/m3].
    u : float
        Specific internal energy [J/kg].
    T_near : float
        A temperature near the answer [K], where the table's wet-state iteration
        starts (:func:`corliss.thermo.steam_table.lookup_near`; NaN: from the
        saturated vapour).

    Returns
    -------
    p : float
        Pressure [Pa].
    T : float
        Temperature [K] (at least 1 K on the perfect tier).
    x : float
        Dryness [-] (1 on the perfect tier).
    superheated : bool
        Whether the state is superheated (always on the perfect tier).
    code : int
        The clamp code (:func:`admissible_flagged`; 16 for a perfect-gas state below
        1 K), ORed with the table's own.
    """
    rho, u, code = admissible_flagged(rho, u)
    if tier == TIER_PERFECT:
        R, cv, u_ref = perf[PERF_R], perf[PERF_CV], perf[PERF_U_REF]
        T = (u - u_ref) / cv
        if T < 1.0:
            T = 1.0
            code |= 16
        return rho * R * T, T, 1.0, True, code
    p, T, x, sup, c2 = lookup_near(tab, rho, u, T_near)
    return p, T, x, sup, code | c2


@njit(cache=True, inline="always")
def node_states(th, y, net, tier, tab, perf, pr):
    """Each node's properties into the rows of ``pr``, on a compiled property tier.

    Pressure, density, enthalpy, isentropic exponent of its port flow, dV/dtheta,
    volume, temperature, (with wall heat) wetted-wall temperature, clamp code and
    dryness.  The exponent is the real fluid's
    (:func:`corliss.thermo.steam_table.kappa_at`), or the perfect tier's own
    ``1 + R/cv`` (then also written into the reservoirs' row of ``net``).

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    y : ndarray
        The state, shape (n_state,), laid out as
        :class:`~corliss.engine.network.Network` says (masses [kg] and internal
        energies [J] of the nodes first).
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    pr : ndarray
        Written: node properties, shape (:data:`PR_ROWS`, nodes): rows
        pressure [Pa], density [kg/m3], enthalpy [J/kg], port-flow exponent [-],
        dV/dtheta [m3/rad], volume [m3], temperature [K], wetted-wall temperature
        [K], clamp code (:data:`PR_CLAMP`), dryness [-]
        (:data:`PR_X`), whether superheated (:data:`PR_SUP`) and the state
        they are of (:data:`PR_AT`).
    """
    nv = net.node_kind.shape[0]
    if tier == TIER_PERFECT:
        res = net.reservoirs
        for r in range(res.shape[0]):
            res[r, 3] = 1.0 + perf[PERF_R] / perf[PERF_CV]
    kind, cyl, end, fixedV = net.node_kind, net.node_cyl, net.node_end, net.node_V
    # the piston's travel once per cylinder, not once per end: the nodes of a
    # cylinder's two ends are adjacent (it is computed again for one that is not)
    last = -1
    s = 0.0
    ds = 0.0
    for i in range(nv):
        if kind[i] == 1:
            V, dV = fixedV[i], 0.0
        else:
            c = cyl[i]
            if c != last:
                s, ds = piston_position(th, net, c)
                last = c
            V, dV = end_volume(net, c, end[i], s, ds)
        pr[PR_DV, i] = dV
        pr[PR_V, i] = V
        m = y[2 * i]
        u = y[2 * i + 1] / m if m > 0.0 else 2.6e6
        # the node's temperature at the evaluation before (the scratch's; anything
        # outside the wet bracket, garbage or NaN included, is ignored) starts the
        # table's wet iteration near its answer
        p, T, x, sup, code = props(tier, tab, perf, m / V, u, pr[PR_T, i])
        rho, u = admissible(m / V, u)
        pr[PR_P, i] = p
        pr[PR_RHO, i] = rho
        pr[PR_H, i] = u + p / rho
        pr[PR_KAPPA, i] = (1.0 + perf[PERF_R] / perf[PERF_CV] if tier == TIER_PERFECT
                           else kappa_at(tab, rho, u))
        pr[PR_T, i] = T
        pr[PR_CLAMP, i] = code
        pr[PR_X, i] = 1.0 if sup else x
        pr[PR_SUP, i] = 1.0 if sup else 0.0
        pr[PR_AT, i] = th
        pr[PR_AT + 1, i] = m
        pr[PR_AT + 2, i] = y[2 * i + 1]
        # the temperature of a wetted wall at this pressure, for the wall-heat effect only
        if net.heat[i, H_MODEL] > WALL_NONE:
            pr[PR_TSAT, i] = t_sat(tab, p) if (sup and tier != TIER_PERFECT) else T
