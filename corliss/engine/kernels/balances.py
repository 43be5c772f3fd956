"""The crank-resolved model's right-hand side: mass and energy balances of every node,
the wall heat of each node's model, the port flows
(:func:`corliss.thermo.orifice.port_flow`), and :func:`rhs`, the one compiled function
every integrator calls.

:func:`rhs` is compiled without numba's reference counting (``_nrt=False``; see
:mod:`corliss.engine.kernels`); the functions that take the network or the table tuple
are inlined into it (a call passing those tuples costs more than a small one's work).
"""

from __future__ import annotations

import math


from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.mechanism import TWO_PI, edge_area, port_areas
from corliss.engine.kernels.data import (GEO_AREA_CRANK, GEO_AREA_HEAD, H_CONDUCTANCE, H_K,
                                         H_MARKS_ADMIT, H_MARKS_COMPRESS, H_MARKS_CUTOFF,
                                         H_MARKS_Q, H_MARKS_WALL_ADMIT, H_MARKS_WALL_EXPAND,
                                         H_MODEL, H_MU, H_PRANDTL, H_SKIN_AREA,
                                         H_SKIN_CAPACITY, H_SKIN_DEEP, H_SKIN_FILM_H,
                                         H_SKIN_JACKET_G, H_SKIN_JACKET_T, H_SKIN_LATENT,
                                         H_SKIN_STATE, H_SKIN_SUPPLY_SUPERHEAT, WALL_CONDUCTANCE,
                                         WALL_MARKS, WALL_SKIN)
from corliss.engine.kernels.properties import (PR_DV, PR_H, PR_KAPPA, PR_P, PR_RHO, PR_T,
                                               PR_TSAT, PR_V, PR_X, node_states)
from corliss.engine.kernels.walls import (FILM_MAX_KG_M2, FILM_WET_KG_M2, adair_h,
                                          condensing_share, film_water, skin_coefficients,
                                          steam_at_wall_superheat)
from corliss.thermo.leak_law import linear_leak
from corliss.thermo.orifice import port_flow


@njit(cache=True, inline="always")
def edge_side(x, pr, res):
    """The state at one end of an edge: a node's (from the node properties) or a
    reservoir's.

    Parameters
    ----------
    x : int
        The end: a node index (0 and up) or a reservoir's code (``-1 - r``).
    pr : ndarray
        The node properties, shape (:data:`PR_ROWS`, nodes) (rows pressure, density,
        enthalpy, port-flow exponent read).
    res : ndarray
        The reservoirs' states, shape (reservoirs, 4): p [Pa], rho [kg/m3], h [J/kg],
        the port-flow exponent [-].

    Returns
    -------
    p, rho, h, kappa : float
        Pressure [Pa], density [kg/m3], enthalpy [J/kg] and port-flow exponent [-].
    """
    if x >= 0:
        return pr[PR_P, x], pr[PR_RHO, x], pr[PR_H, x], pr[PR_KAPPA, x]
    r = -1 - x
    return res[r, 0], res[r, 1], res[r, 2], res[r, 3]


@njit(cache=True, inline="always")
def marks_window(th, net, i):
    """Where a node stands in Marks's schedule (Art. 75; :mod:`corliss.engine.condensation`).

    The heat of eq. 221 leaves the steam during admission and comes back from cut-off
    to compression, each spread over the crank angle in proportion to the wall
    exposed: the heat into the steam is ``s Q A / W`` per radian, with ``A`` the wall
    exposed [m2] and ``W`` that window's integral of it [m2 rad].  The right-hand side
    and the exact Jacobian's crank-angle derivative both read the window here.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : NetworkArrays
        The network's arrays (its wall-heat rows and each cylinder's phase).
    i : int
        A node whose wall-heat model is Marks's law.

    Returns
    -------
    s : float
        -1 in admission, +1 from cut-off to compression, 0 elsewhere [-].
    W : float
        The window's exposed wall integrated over it [m2 rad] (1 where ``s`` is 0).
    """
    heat = net.heat
    t = (th + net.phase[net.node_cyl[i]]) % TWO_PI
    if ((t - heat[i, H_MARKS_ADMIT]) % TWO_PI
            < (heat[i, H_MARKS_CUTOFF] - heat[i, H_MARKS_ADMIT]) % TWO_PI):
        return -1.0, heat[i, H_MARKS_WALL_ADMIT]
    if ((t - heat[i, H_MARKS_CUTOFF]) % TWO_PI
            < (heat[i, H_MARKS_COMPRESS] - heat[i, H_MARKS_CUTOFF]) % TWO_PI):
        return 1.0, heat[i, H_MARKS_WALL_EXPAND]
    return 0.0, 1.0


#: How far short of a schedule's switch the integrators stop [rad]: the steady cycle's
#: (:meth:`corliss.engine.network.Network.stops`) and a turn's
#: (:func:`corliss.engine.kernels.loop.turn_stops`).  The step that ends at a stop
#: evaluates its last stages there, which must read the window the step integrates,
#: and the window test (:func:`marks_window`) at the switch itself reads either side by
#: a rounding of the shaft angle (an ulp, 1.5e-11 rad at 1e5 rad: an hour at 300 rpm).
#: A stop at the switch gave a step's end stages the next window's heat at random, the
#: ends of a turn netting 1.5e-4 of the heat taken at rtol 1e-6.  The segment after the
#: stop reads its first derivative :data:`SWITCH_MARGIN_RAD` past the switch
#: (:func:`past_switch`), and its sliver short of the switch is integrated on the next
#: window's heat, 1e-9 rad of a window of a radian or more.
SWITCH_MARGIN_RAD = 1e-9


@njit(cache=True, inline="always")
def past_switch(th, net):
    """Where a segment that starts at ``th`` reads its first derivative: past the switch
    of a wall-heat schedule (Marks's or English's law) that lies within
    ``2 SWITCH_MARGIN_RAD`` after ``th`` (a stop put :data:`SWITCH_MARGIN_RAD` short of
    it), so that the segment's first stage sees the window it integrates; ``th`` itself
    where none does (a port's kink, a run without a schedule).

    Parameters
    ----------
    th : float
        The segment's start, a stop [rad].
    net : NetworkArrays
        The network's arrays (its wall-heat rows and each cylinder's phase).

    Returns
    -------
    float
        The shaft angle to read the derivative at [rad].
    """
    te = th + 2.0 * SWITCH_MARGIN_RAD
    for i in range(net.heat.shape[0]):
        if net.heat[i, H_MODEL] == WALL_MARKS:
            s_past, _ = marks_window(te, net, i)
            s_here, _ = marks_window(th, net, i)
            if s_past != s_here:
                return te
    return th


@njit(cache=True, inline="always")
def derivatives(th, y, pr, dy, net, pa):
    """Derivatives with respect to crank angle, given each node's properties.

    The port areas (:func:`port_areas`) and then the balances (:func:`balances`); the
    reference path (HEOS, from Python) fills ``pr`` itself, the compiled tiers through
    :func:`node_states`.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    y : ndarray
        The state, shape (n_state,), laid out as
        :class:`~corliss.engine.network.Network` says (masses [kg] and internal
        energies [J] of the nodes first).
    pr : ndarray
        Node properties, shape (:data:`PR_ROWS`, nodes): rows pressure [Pa], density
        [kg/m3], enthalpy [J/kg], port-flow exponent [-], dV/dtheta [m3/rad], volume
        [m3], temperature [K], wetted-wall temperature [K], clamp code
        (:data:`PR_CLAMP`), dryness [-]
        (:data:`PR_X`), whether superheated (:data:`PR_SUP`) and the state
        they are of (:data:`PR_AT`).
    dy : ndarray
        Written: the derivatives with respect to crank angle (per radian), shape
        (n_state,).
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    pa : ndarray
        Scratch for the port areas [m2], shape (cylinders, 4).
    """
    port_areas(th, net, pa)
    balances(th, y, pr, dy, net, pa)


@njit(cache=True, inline="always")
def balances(th, y, pr, dy, net, areas):
    """Mass and energy balances of every node per radian of crank angle.

    The first law for each node (``- p dV``, the wall heat of its model, the flows
    through its edges from :func:`corliss.thermo.orifice.port_flow` carrying the
    enthalpy of the side they leave), the quadratures of every edge and node, the skin
    model's wall states, and the film swept out (:func:`sweep_films`).  The shaft
    speed is read from ``net.omega[0]`` [rad/s].

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    y : ndarray
        The state, shape (n_state,), laid out as
        :class:`~corliss.engine.network.Network` says (masses [kg] and internal
        energies [J] of the nodes first).
    pr : ndarray
        Node properties, shape (:data:`PR_ROWS`, nodes): rows pressure [Pa], density
        [kg/m3], enthalpy [J/kg], port-flow exponent [-], dV/dtheta [m3/rad], volume
        [m3], temperature [K], wetted-wall temperature [K], clamp code
        (:data:`PR_CLAMP`), dryness [-]
        (:data:`PR_X`), whether superheated (:data:`PR_SUP`) and the state
        they are of (:data:`PR_AT`).
    dy : ndarray
        Written: the derivatives with respect to crank angle (per radian), shape
        (n_state,).
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    areas : ndarray
        The port areas [m2], shape (cylinders, 4).
    """
    omega, band, res = net.omega[0], net.band, net.reservoirs
    P, RHO, H = pr[PR_P], pr[PR_RHO], pr[PR_H]
    geo, ncyl_, end_, heat, wallT = net.geometry, net.node_cyl, net.node_end, net.heat, net.wall_T
    ea, eb, ecd, ekind = net.edge_a, net.edge_b, net.edge_cd, net.edge_kind
    nv = P.shape[0]
    ne = ea.shape[0]
    ndyn = 2 * nv
    for i in range(dy.shape[0]):
        dy[i] = 0.0
    for i in range(nv):
        dV = pr[PR_DV, i]
        q0 = ndyn + 2 * ne + 5 * i
        dy[2 * i + 1] -= P[i] * dV
        dy[q0] = P[i] * dV
        model = heat[i, H_MODEL]
        if model > 0.0:
            # wall area: piston face and cover, and the barrel uncovered (with the
            # clearance as its equivalent length): 2 A_p + pi D V / A_p
            c = ncyl_[i]
            ap = geo[c, GEO_AREA_HEAD] if end_[i] == 0 else geo[c, GEO_AREA_CRANK]
            bore = math.sqrt(4.0 * geo[c, GEO_AREA_HEAD] / math.pi)
            V = pr[PR_V, i]
            A = 2.0 * ap + math.pi * bore * V / ap
            Ts = pr[PR_T, i]
            if model == WALL_SKIN:
                # after the flows (skin_wall): the steam entering decides the steam
                # at the wall
                continue
            if model == WALL_MARKS:
                # Marks's law (Art. 75): the heat of eq. 221 leaves the steam during
                # admission and comes back from cut-off to compression, each spread
                # over the crank angle in proportion to the wall exposed
                sm, W = marks_window(th, net, i)
                q = sm * heat[i, H_MARKS_Q] * A / W if sm != 0.0 else 0.0
                dy[2 * i + 1] += q
                dy[q0 + 1] = q
                dy[q0 + 2] = -q if q < 0.0 else 0.0
                continue
            if model == WALL_CONDUCTANCE:
                h = heat[i, H_CONDUCTANCE]
                # a wall hotter than the steam gives its heat to the water film that
                # the admission condensed on it, which boils at the saturation
                # temperature of the cylinder's pressure (pr[PR_TSAT]), however superheated
                # the thin exhaust steam around it (Marks Art. 74, 3-4)
                if wallT[i] > Ts:
                    Ts = pr[PR_TSAT, i]
            else:
                h = adair_h(RHO[i], omega, V, A, heat[i, H_MU], heat[i, H_K], heat[i, H_PRANDTL])
            q = h * A * (wallT[i] - Ts) / omega
            dy[2 * i + 1] += q
            dy[q0 + 1] = q
            dy[q0 + 2] = -q if q < 0.0 else 0.0
            dy[q0 + 3] = h * A / omega
            dy[q0 + 4] = h * A * Ts / omega
    for e in range(ne):
        ar = edge_area(net, e, areas)
        if ar <= 0.0:
            # a shut port: no flow (its quadratures' zeros are written above); the
            # test is port_flow's own, which would return 0 before reading either side
            continue
        a = ea[e]
        b = eb[e]
        pa, ra, ha, ka = edge_side(a, pr, res)
        pb, rb, hb, kb = edge_side(b, pr, res)
        if ekind[e] == 2:
            # the period's leak (corliss.thermo.leak_law): the rate of leak times the
            # pressure difference, carrying the enthalpy of the side it leaves
            md = linear_leak(ar, pa, pb)
        else:
            md = port_flow(ar, ecd[e], pa, ra, ka, pb, rb, kb, band, True)
        hd = md * (ha if md > 0.0 else hb)
        md /= omega
        hd /= omega
        if a >= 0:
            dy[2 * a] -= md
            dy[2 * a + 1] -= hd
        if b >= 0:
            dy[2 * b] += md
            dy[2 * b + 1] += hd
        # the steam entering a skin wall's end, mass and enthalpy per radian, kept in
        # its node's last two quadratures until skin_wall reads them (and writes
        # those quadratures)
        t = b if md > 0.0 else a
        if t >= 0 and heat[t, H_MODEL] == WALL_SKIN:
            qt = ndyn + 2 * ne + 5 * t
            dy[qt + 3] += abs(md)
            dy[qt + 4] += abs(hd)
        dy[ndyn + 2 * e] = md
        dy[ndyn + 2 * e + 1] = hd
    for i in range(nv):
        if heat[i, H_MODEL] == WALL_SKIN:
            skin_wall(i, y, pr, dy, net, ndyn + 2 * ne + 5 * i)
    sweep_films(y, pr, dy, net)


@njit(cache=True, inline="always")
def skin_wall(i, y, pr, dy, net, q0):
    """The skin model's wall heat of node ``i`` (:mod:`corliss.engine.wall`), after the
    flows through its edges.

    The surface's temperature ``T_w = T_deep + y[k]`` and the film ``y[k + 1]`` are
    states; the film's flow goes down ``T_w - T_sat``, the convection's (Adair's)
    down ``T_w - T``; a surface below saturation condenses only as far as the steam at
    it is at saturation (:func:`~corliss.engine.kernels.walls.condensing_share` of
    :func:`~corliss.engine.kernels.walls.steam_at_wall_superheat`, the entering
    steam's while steam enters, no more than the supply's superheat: the entering
    mass and enthalpy per radian are read from ``dy[q0 + 3]`` and ``dy[q0 + 4]``,
    where the edges' loop of :func:`balances` left them).

    Parameters
    ----------
    i : int
        The node.
    y : ndarray
        The state, shape (n_state,).
    pr : ndarray
        Node properties, shape (:data:`PR_ROWS`, nodes) (:func:`balances`).
    dy : ndarray
        The derivatives with respect to crank angle (per radian), shape (n_state,),
        updated in place.
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    q0 : int
        The index of the node's first quadrature in ``dy``.
    """
    omega = net.omega[0]
    geo, heat, wallT = net.geometry, net.heat, net.wall_T
    H = pr[PR_H]
    c = net.node_cyl[i]
    ap = geo[c, GEO_AREA_HEAD] if net.node_end[i] == 0 else geo[c, GEO_AREA_CRANK]
    bore = math.sqrt(4.0 * geo[c, GEO_AREA_HEAD] / math.pi)
    V = pr[PR_V, i]
    A = 2.0 * ap + math.pi * bore * V / ap
    Ts = pr[PR_T, i]
    RHO = pr[PR_RHO]
    # the skin model (corliss.engine.wall): states y[k] = T_w - T_deep and
    # y[k + 1] = the film's water; the film's flow goes down T_w - T_sat,
    # the convection's down T_w - T
    k = int(heat[i, H_SKIN_STATE])
    Tw = wallT[i] + y[k]
    mf = y[k + 1]
    Aw = heat[i, H_SKIN_AREA]
    Tsat = pr[PR_TSAT, i]
    hv = adair_h(RHO[i], omega, V, A, heat[i, H_MU], heat[i, H_K], heat[i, H_PRANDTL])
    m_in, h_in = dy[q0 + 3], dy[q0 + 4]
    sup = steam_at_wall_superheat(Ts, Tsat, pr[PR_X, i], heat[i, H_SKIN_LATENT], H[i],
                                  h_in / m_in if m_in > 0.0 else 0.0, m_in, y[2 * i])
    # no more superheated than the steam supplied: saturated steam supplied
    # keeps the wall's steam saturated however the filling and the
    # compression superheat the bulk
    hf, hm = skin_coefficients(Tw, Tsat, heat[i, H_CONDUCTANCE], mf, Aw, pr[PR_X, i],
                               condensing_share(min(sup, heat[i, H_SKIN_SUPPLY_SUPERHEAT])))
    qf = hf * (Tw - Tsat) * A            # [W] from the wall into the film
    qm = hm * (Tw - Tsat) * A            # [W] into the mixture's water
    qc = hv * (Tw - Ts) * A              # [W] into the steam by convection
    qv = qm + qc
    # the film's water is saturated water at the surface's temperature
    # (corliss.engine.wall, "The water film"): evaporated (+, as vapour
    # of h_L + L, both at T_w) or condensed (-, the steam giving up its
    # own enthalpy, superheat and all, down to the film's h_L) [kg/s];
    # water beyond the film the wall holds runs off into the steam (its
    # excess per radian)
    hL, cL, L = film_water(Tw)
    if qf < 0.0:
        lat = max(H[i] - hL, 0.5 * L)
    else:
        lat = L
    mdot = qf / lat
    held = FILM_MAX_KG_M2 * Aw
    run = (mf - held) * omega if mf > held else 0.0
    dy[2 * i] += (mdot + run) / omega
    dy[2 * i + 1] += ((mdot + run) * hL + qf + qv) / omega
    dy[k + 1] = -(mdot + run) / omega
    # the heat into the steam counts the film's water from the row's
    # reference enthalpy (the steam gains q + its water's mass times that
    # reference): over a periodic cycle it is what surface and film gave
    q = (qf + qv + (mdot + run) * (hL - heat[i, H_SKIN_FILM_H])) / omega
    dy[q0 + 1] = q
    dy[q0 + 2] = -q if q < 0.0 else 0.0
    # for the deep wall's update (T_deep <- hAT / hA, a Newton step on the
    # wall's, or with a jacket the wall and jacket's, balance over a cycle)
    d = (hv + hf + hm) * A / omega
    ga = heat[i, H_SKIN_JACKET_G] / omega
    dy[q0 + 3] = d + ga
    dy[q0 + 4] = d * wallT[i] - q + ga * heat[i, H_SKIN_JACKET_T]
    # the surface and the film on it, at one temperature: the film's
    # energy m_f h_L(T_w) moves with the surface (its water comes and
    # goes at h_L, above)
    dy[k] = (-(qf + qv) + heat[i, H_SKIN_DEEP] * Aw * (wallT[i] - Tw)) / (
        (heat[i, H_SKIN_CAPACITY] * Aw + mf * cL) * omega)
    dy[k + 2] = (qf + qm) / omega
    dy[k + 3] = qc / omega


@njit(cache=True, inline="always")
def sweep_films(y, pr, dy, net):
    """The skin model's film swept out with the steam (:mod:`corliss.engine.wall`).

    While an end's steam flows out, the film beyond
    :data:`~corliss.engine.kernels.walls.FILM_WET_KG_M2` goes with it in the proportion of the steam leaving, into the steam as water of the film's
    enthalpy.

    Parameters
    ----------
    y : ndarray
        The state, shape (n_state,), laid out as
        :class:`~corliss.engine.network.Network` says (masses [kg] and internal
        energies [J] of the nodes first).
    pr : ndarray
        Node properties, shape (:data:`PR_ROWS`, nodes): rows pressure [Pa], density
        [kg/m3], enthalpy [J/kg], port-flow exponent [-], dV/dtheta [m3/rad], volume
        [m3], temperature [K], wetted-wall temperature [K], clamp code
        (:data:`PR_CLAMP`), dryness [-]
        (:data:`PR_X`), whether superheated (:data:`PR_SUP`) and the state
        they are of (:data:`PR_AT`).
    dy : ndarray
        The derivatives with respect to crank angle (per radian), shape (n_state,),
        updated in place.
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    """
    heat = net.heat
    for i in range(heat.shape[0]):
        if heat[i, H_MODEL] != WALL_SKIN:
            continue
        k = int(heat[i, H_SKIN_STATE])
        # the steam leaving through the ports: the node's mass rate less the wall's
        # own (dy[k + 1] is the film's, the negative of what the wall gave the steam),
        # so that condensation on a closed end sweeps nothing and the water boiling
        # off the wall does not offset the outflow (as the ideal-port wall's sweep,
        # corliss.engine.wall.IdealPortWall.sweep, on the port's flow alone)
        out = -(dy[2 * i] + dy[k + 1])
        if not out > 0.0:
            continue
        extra = y[k + 1] - FILM_WET_KG_M2 * heat[i, H_SKIN_AREA]
        m = y[2 * i]
        if extra > 0.0 and m > 0.0:
            sw = extra * out / m
            # water at the surface's temperature (film_water), its enthalpy above
            # the row's reference counted in the heat into the steam, as in
            # :func:`balances`
            hL, _, _ = film_water(net.wall_T[i] + y[k])
            dq = sw * (hL - heat[i, H_SKIN_FILM_H])
            dy[2 * i] += sw
            dy[2 * i + 1] += sw * hL
            dy[k + 1] -= sw
            q0 = 2 * heat.shape[0] + 2 * net.edge_a.shape[0] + 5 * i
            dy[q0 + 1] += dq
            dy[q0 + 2] = -dy[q0 + 1] if dy[q0 + 1] < 0.0 else 0.0
            dy[q0 + 4] -= dq


@njit(cache=True, _nrt=False)
def rhs(th, y, dy, net, tier, tab, perf, pr, cell):
    """Derivatives with respect to crank angle on a compiled property tier.

    :func:`node_states` then :func:`derivatives`: the one compiled right-hand side
    the integrators call.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    y : ndarray
        The state, shape (n_state,), laid out as
        :class:`~corliss.engine.network.Network` says (masses [kg] and internal
        energies [J] of the nodes first).
    dy : ndarray
        Written: the derivatives with respect to crank angle (per radian), shape
        (n_state,).
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
        Scratch, written: node properties, shape (:data:`PR_ROWS`, nodes): rows
        pressure [Pa], density [kg/m3], enthalpy [J/kg], port-flow exponent [-],
        dV/dtheta [m3/rad], volume [m3], temperature [K], wetted-wall temperature
        [K], clamp code (:data:`PR_CLAMP`), dryness [-]
        (:data:`PR_X`), whether superheated (:data:`PR_SUP`) and the state
        they are of (:data:`PR_AT`).
    cell : ndarray
        Scratch for the port areas [m2], shape (cylinders, 4).
    """
    node_states(th, y, net, tier, tab, perf, pr)
    derivatives(th, y, pr, dy, net, cell)
