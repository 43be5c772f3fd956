"""The compiled hot loop: right-hand side and integrators of the crank-resolved model.

The equations are those of :mod:`corliss.engine.network`: control volumes (cylinder
ends, chest) joined by ports, each with a mass and energy balance.  The network is a
tuple of plain arrays (:meth:`corliss.engine.network.Network.arrays`); one call
integrates a whole cycle.  :func:`derivatives` takes the properties of every node as
given, so the reference path (HEOS, called from Python) and the compiled tiers share
one implementation of the physics.  The integrators:

* ``"dopri5"``: Dormand-Prince 5(4), adaptive, with the usual error norm
  ``max |err_i| / (atol_i + rtol |y_i|)``, step-size control with safety 0.9 and
  limits 0.2-5, FSAL; restarted at every kink of the port areas, so a port opening
  never lies inside a step (no storm of rejected steps);
* ``"rk4"``: classical fourth-order Runge-Kutta at a fixed crank-angle step, each
  segment between kinks divided into equal steps no longer than the step asked for;
* ``"rosenbrock"``: the L-stable Rosenbrock 2(3) pair of Shampine and Reichelt
  (MATLAB's ode23s; SIAM J. Sci. Comput. 18, 1997), with the Jacobian over the
  dynamic states (the quadratures do not feed back) and the derivative in crank
  angle computed analytically (:func:`_jacobian_exact`: the steam table's and the
  port flow's own derivatives, no evaluation of the right-hand side) where the
  network has no state-dependent wall heat, else by finite differences, columns
  grouped by the network's structure (:meth:`Network.column_colors`).  Pressure
  equalisation through an open port is stiff (an eigenvalue near -300 per radian on
  the default engine), which holds the explicit methods to steps of about 0.6 deg
  whatever their tolerance; the Rosenbrock method steps over it;
* ``"ros4"``, ``"rodas3"``, ``"rodas4"``: Rosenbrock methods of higher order from
  their tableaus (:data:`ROS_TABLEAUS`), on the same Jacobian and in the same
  compiled step loop as ode23s (:func:`cycle_ros`, one integrator for every
  Rosenbrock method, so that a run of one compiles them all): Shampine's A-stable
  4(3) pair, and the L-stable, stiffly accurate RODAS3 (order 3) and RODAS4 (order
  4).  On the accuracy study's three
  scenes they reach either preset's accuracy for a half to two thirds of its
  evaluations (the README's "Accuracy and time").  On a very stiff network (ports
  1000 times too large) they ran out of the run-time budget with the
  finite-difference Jacobian; with the analytic one they settle in 3 cycles of
  3,000 (RODAS4) and 6,700 (``ros4``) evaluations.  They are offered, not presets.

Output samples between steps come from cubic Hermite interpolation on the states and
derivatives at the step ends (third-order, well inside the step error).

Compiled code is cached on disk by numba (``cache=True``): a run pays compilation
once per machine (measured in the accuracy study).  What it compiles is kept small:
the right-hand side is one compiled function (:func:`rhs`, its parts and the property
lookups inlined into it once), called by one function per integrator
(:data:`CYCLE_KERNELS`), so that a run compiles the right-hand side once and only the
integrator it uses; inlining :func:`rhs` itself at every stage of every method, as
before, made numba compile it ten times (2 min against 10 s on a loaded 2-core
machine).  The functions that take the network or the table tuple stay inlined inside
:func:`rhs`: a call that passes those tuples costs more than the work of a small one.

:func:`rhs` is compiled without numba's reference counting (``_nrt=False``, the flag
numba's own string functions use): every array it reads from the network and table
tuples would otherwise be counted up and down with an atomic instruction (over 200 in
its compiled code, many inside the loops over nodes and edges), which cost 0.76 of its
1.2 us on the default scene.  It allocates nothing and keeps no reference past its
return (its arrays are its caller's), so no count is needed; numba refuses to compile
an allocation there (a typing error, not a silent leak).  So are the integrators'
step loops (:func:`_dopri5_steps`, :func:`_ros_steps`, on scratch their Python callers
:func:`cycle_dopri5` and :func:`cycle_ros` allocate) and their helpers (clamp tallies,
copies, Hermite output, the Jacobians, W's inverse and solves, the first step): numba
counts a reference on every array argument on entry and exit of a compiled function,
and on every view of a scratch array, about 0.4 us of a ros4 step's 3.4 before.  The
private helpers only compiled code calls (:func:`_jacobian`, :func:`_w_inverse`,
:func:`_w_solve`) have no CPython wrapper (``no_cpython_wrapper``: less to compile; a
call from Python would crash the interpreter).  The public ones keep theirs: without,
a first ``ros4`` call compiled 0.4-0.6 s less (16.2 and 15.9 against 16.5 and 16.5 s).

Numba keys that cache on the
content of this file alone, not on the compiled functions it inlines from
:mod:`corliss.thermo.orifice` and :mod:`corliss.thermo.steam_table`: a change there
must come with a new :data:`DEPENDENCY_REVISION` here (and in
:mod:`corliss.engine.transient_kernel`), or the cached kernel keeps the old code.
"""

from __future__ import annotations

import logging
import math
import os

import numpy as np
from numba import njit

from corliss.logs import NOTICE
from corliss.thermo.orifice import port_flow, port_flow_partials
from corliss.thermo.steam_table import (CLAMP_HIGH_ENERGY, PARAMS, kappa_at, kappa_partials,
                                        lookup_near, pressure_partials,
                                        t_sat)

log = logging.getLogger(__name__)
#: Revision of the inlined property and port-flow code (see the module's docstring).
DEPENDENCY_REVISION = 24
TIER_TABLE, TIER_PERFECT = 0, 1
TWO_PI = 2.0 * math.pi
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
#: Rows of the node-property scratch ``pr`` (see :func:`node_states`).
PR_ROWS = 14
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
#: What the cycle integrator reports of clamps (the array it returns last): clamped
#: evaluations at visited states, at trial states, the codes of each (OR of the
#: bits), and the shaft angle [rad] and node of the first visited one.
CL_ACCEPTED, CL_REJECTED, CL_ACCEPTED_CODE, CL_REJECTED_CODE, CL_THETA, CL_NODE = range(6)
#: The run-time budget: right-hand-side evaluations allowed in one cycle (or one turn of
#: the transient loop).  The default card needs 3,400 at the standard preset and a
#: 10 rpm engine 36,000; a cycle that needs 2,000,000 (about half a minute) is stepping
#: through something no engine does (a speed, stroke or friction far outside the
#: physical), and the run stops with a message instead of hanging.
MAX_RHS_PER_CYCLE = 2_000_000


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
        R, cv, u_ref = perf[0], perf[1], perf[2]
        T = (u - u_ref) / cv
        if T < 1.0:
            T = 1.0
            code |= 16
        return rho * R * T, T, 1.0, True, code
    p, T, x, sup, c2 = lookup_near(tab, rho, u, T_near)
    return p, T, x, sup, code | c2


@njit(cache=True, inline="always")
def piston_position(th, net, c):
    """Piston travel from head dead centre and its derivative with crank angle.

    The slider crank of :mod:`corliss.engine.geometry`, at the cylinder's own angle
    ``th + phase``.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    c : int
        The cylinder.

    Returns
    -------
    s : float
        Travel [m].
    ds : float
        ds/dtheta [m/rad].
    """
    geo, phase = net[2], net[3]
    R, L, ang = geo[c, 0], geo[c, 1], geo[c, 7]
    a = th + phase[c]
    sn = math.sin(a)
    cs = math.cos(a)
    s = R * (1.0 - cs)
    ds = R * sn
    if ang > 0.0:
        root = math.sqrt(L * L - R * R * sn * sn)
        s += L - root
        ds += R * R * sn * cs / root
    return s, ds


@njit(cache=True, inline="always")
def piston_kinematics(th, net, c):
    """Piston velocity and acceleration per crank angle of one cylinder.

    The slider crank of :mod:`corliss.engine.geometry` at the cylinder's own angle
    (an infinite rod without rod angularity).

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    c : int
        The cylinder.

    Returns
    -------
    ds : float
        ``ds/dtheta`` [m/rad].
    d2s : float
        ``d2s/dtheta2`` [m/rad2].
    """
    geo, phase = net[2], net[3]
    R, L, ang = geo[c, 0], geo[c, 1], geo[c, 7]
    a = th + phase[c]
    sn = math.sin(a)
    cs = math.cos(a)
    ds = R * sn
    d2s = R * cs
    if ang > 0.0:
        root = math.sqrt(L * L - R * R * sn * sn)
        ds += R * R * sn * cs / root
        d2s += R * R * (cs * cs - sn * sn) / root + (R * R * sn * cs) ** 2 / root ** 3
    return ds, d2s


@njit(cache=True, inline="always")
def end_volume(net, c, end, s, ds):
    """Volume of one end of a cylinder and its derivative, from the piston's travel.

    Parameters
    ----------
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    c : int
        The cylinder.
    end : int
        0 the head end, 1 the crank end.
    s : float
        Piston travel from head dead centre [m] (:func:`piston_position`).
    ds : float
        ds/dtheta [m/rad].

    Returns
    -------
    V : float
        Volume [m3].
    dV : float
        dV/dtheta [m3/rad].
    """
    geo = net[2]
    if end == 0:
        return geo[c, 5] + geo[c, 3] * s, geo[c, 3] * ds
    return geo[c, 6] + geo[c, 4] * (geo[c, 2] - s), -geo[c, 4] * ds


@njit(cache=True, inline="always")
def node_volume(th, net, i):
    """Volume of a node and its derivative with crank angle.

    The slider crank of :mod:`corliss.engine.geometry`, at the cylinder's own angle
    ``th + phase`` (:func:`piston_position`, :func:`end_volume`); a vessel's volume is
    fixed.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    i : int
        The node.

    Returns
    -------
    V : float
        Volume [m3].
    dV : float
        dV/dtheta [m3/rad].
    """
    kind, cyl, end, fixedV = net[4], net[5], net[6], net[7]
    if kind[i] == 1:
        return fixedV[i], 0.0
    s, ds = piston_position(th, net, cyl[i])
    return end_volume(net, cyl[i], end[i], s, ds)


@njit(cache=True, inline="always")
def port_areas(th, net, pa):
    """Open area of every port of every cylinder, from the PortMap tables.

    Linear interpolation at the cylinder's own angle, one search per cylinder.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    pa : ndarray
        Written: the areas [m2], shape (cylinders, 4), ports in PortMap order (head
        steam, head exhaust, crank steam, crank exhaust).
    """
    phase, grid, npts, area = net[3], net[16], net[17], net[18]
    for c in range(npts.shape[0]):
        n = npts[c]
        t = (th + phase[c]) % TWO_PI
        k = np.searchsorted(grid[c, :n], t) - 1
        if k < 0:
            k = 0
        if k > n - 2:
            k = n - 2
        g0 = grid[c, k]
        w = (t - g0) / (grid[c, k + 1] - g0)
        for p in range(4):
            pa[c, p] = area[c, p, k] * (1.0 - w) + area[c, p, k + 1] * w


@njit(cache=True, inline="always")
def edge_area(net, e, pa):
    """Open area of an edge: a fixed orifice's, or its port's.

    Parameters
    ----------
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    e : int
        The edge.
    pa : ndarray
        The port areas [m2], shape (cylinders, 4) (:func:`port_areas`).

    Returns
    -------
    float
        The area [m2].
    """
    ekind, ecyl, eport, earea = net[11], net[12], net[13], net[14]
    if ekind[e] == 1:
        return earea[e]
    return pa[ecyl[e], eport[e]]


@njit(cache=True, inline="always")
def _port_area_slopes(th, net, out):
    """d(area)/dtheta [m2/rad] of every port, shape (cylinders, 4), on the cell of the
    PortMap table that lies ahead of ``th`` (the side a forward step takes at a kink)."""
    phase, grid, npts, area = net[3], net[16], net[17], net[18]
    for c in range(npts.shape[0]):
        n = npts[c]
        t = (th + phase[c]) % TWO_PI
        k = np.searchsorted(grid[c, :n], t, side="right") - 1
        if k < 0:
            k = 0
        if k > n - 2:
            k = n - 2
        dg = grid[c, k + 1] - grid[c, k]
        for p in range(4):
            out[c, p] = (area[c, p, k + 1] - area[c, p, k]) / dg


@njit(cache=True, inline="always")
def _volume_curvature(th, net, i):
    """d2V/dtheta2 of a node [m3/rad2]: the slider crank of :func:`node_volume`
    differentiated once more (:func:`piston_kinematics`; 0 for a vessel)."""
    geo, kind, cyl, end = net[2], net[4], net[5], net[6]
    if kind[i] == 1:
        return 0.0
    c = cyl[i]
    d2s = piston_kinematics(th, net, c)[1]
    if end[i] == 0:
        return geo[c, 3] * d2s
    return -geo[c, 4] * d2s


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
        return pr[0, x], pr[1, x], pr[2, x], pr[3, x]
    r = -1 - x
    return res[r, 0], res[r, 1], res[r, 2], res[r, 3]


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
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    pa : ndarray
        Scratch for the port areas [m2], shape (cylinders, 4).
    """
    port_areas(th, net, pa)
    balances(th, y, pr, dy, net, pa)


#: The skin model's film (corliss.engine.wall): wetted from FILM_WET, running off into
#: the steam beyond FILM_MAX [kg/m2]; wet steam wets the wall while it holds more than
#: WET_BAND of water.
FILM_WET = 1.0e-2
FILM_MAX = 0.1
WET_BAND = 0.02


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
    w = min(max((1.0 - x) / WET_BAND, 0.0), 1.0)
    return w * w * (3.0 - 2.0 * w)


@njit(cache=True, inline="always")
def balances(th, y, pr, dy, net, areas):
    """Mass and energy balances of every node per radian of crank angle.

    The first law for each node (``- p dV``, the wall heat of its model, the flows
    through its edges from :func:`corliss.thermo.orifice.port_flow` carrying the
    enthalpy of the side they leave), the quadratures of every edge and node, the skin
    model's wall states, and the film swept out (:func:`sweep_films`).  The shaft
    speed is read from ``net[0][0]`` [rad/s].

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
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    areas : ndarray
        The port areas [m2], shape (cylinders, 4).
    """
    omega, band, res = net[0][0], net[1], net[8]
    P, RHO, H = pr[0], pr[1], pr[2]
    geo, ncyl_, end_, heat, wallT = net[2], net[5], net[6], net[19], net[20]
    ea, eb, ecd = net[9], net[10], net[15]
    nv = P.shape[0]
    ne = ea.shape[0]
    ndyn = 2 * nv
    for i in range(dy.shape[0]):
        dy[i] = 0.0
    for i in range(nv):
        dV = pr[4, i]
        q0 = ndyn + 2 * ne + 5 * i
        dy[2 * i + 1] -= P[i] * dV
        dy[q0] = P[i] * dV
        model = heat[i, 0]
        if model > 0.0:
            # wall area: piston face and cover, and the barrel uncovered (with the
            # clearance as its equivalent length): 2 A_p + pi D V / A_p
            c = ncyl_[i]
            ap = geo[c, 3] if end_[i] == 0 else geo[c, 4]
            bore = math.sqrt(4.0 * geo[c, 3] / math.pi)
            V = pr[5, i]
            A = 2.0 * ap + math.pi * bore * V / ap
            Ts = pr[6, i]
            if model == 4.0:
                # the skin model (corliss.engine.wall): states y[k] = T_w - T_deep and
                # y[k + 1] = the film's water; the film's flow goes down T_w - T_sat,
                # the convection's down T_w - T
                k = int(heat[i, 8])
                Tw = wallT[i] + y[k]
                mf = y[k + 1]
                Aw = heat[i, 7]
                Tsat = pr[7, i]
                de = 6.0 * V / A
                re_ = RHO[i] * (0.5 * omega * de) * de / heat[i, 3]
                hv = 0.053 * heat[i, 2] / de * re_ ** 0.8 * heat[i, 4] ** 0.6
                hf = heat[i, 1]
                hm = 0.0
                if Tw > Tsat:
                    # a wetted surface boils its water off: the film's, and where the
                    # film is gone, the water wet steam brings to it
                    wf = min(max(mf / (FILM_WET * Aw), 0.0), 1.0)
                    wf = wf * wf * (3.0 - 2.0 * wf)      # smooth at dry and fully wet
                    hm = hf * (1.0 - wf) * wetted_share(pr[PR_X, i])
                    hf *= wf
                qf = hf * (Tw - Tsat) * A            # [W] from the wall into the film
                qm = hm * (Tw - Tsat) * A            # [W] into the mixture's water
                qc = hv * (Tw - Ts) * A              # [W] into the steam by convection
                qv = qm + qc
                hL, L = heat[i, 11], heat[i, 12]
                # evaporated (+, as vapour of h_L + L) or condensed (-, the steam
                # giving up its own enthalpy, superheat and all, down to the film's
                # h_L) [kg/s]; water beyond the film the wall holds runs off into
                # the steam (its excess per radian)
                if qf < 0.0:
                    lat = max(H[i] - hL, 0.5 * L)
                else:
                    lat = L
                mdot = qf / lat
                run = (mf - FILM_MAX * Aw) * omega if mf > FILM_MAX * Aw else 0.0
                dy[2 * i] += (mdot + run) / omega
                dy[2 * i + 1] += ((mdot + run) * hL + qf + qv) / omega
                dy[k + 1] = -(mdot + run) / omega
                q = (qf + qv) / omega
                dy[q0 + 1] = q
                dy[q0 + 2] = -q if q < 0.0 else 0.0
                # for the deep wall's update (T_deep <- hAT / hA, a Newton step on the
                # wall's, or with a jacket the wall and jacket's, balance over a cycle)
                d = (hv + hf + hm) * A / omega
                ga = heat[i, 9] / omega
                dy[q0 + 3] = d + ga
                dy[q0 + 4] = d * wallT[i] - q + ga * heat[i, 10]
                dy[k] = (-(qf + qv) + heat[i, 6] * Aw * (wallT[i] - Tw)) / (
                    heat[i, 5] * Aw * omega)
                dy[k + 2] = (qf + qm) / omega
                dy[k + 3] = qc / omega
                continue
            if model == 3.0:
                # Marks's law (Art. 75): the heat of eq. 221 leaves the steam during
                # admission and comes back from cut-off to compression, each spread
                # over the crank angle in proportion to the wall exposed
                t = (th + net[3][c]) % TWO_PI
                q = 0.0
                if (t - heat[i, 6]) % TWO_PI < (heat[i, 7] - heat[i, 6]) % TWO_PI:
                    q = -heat[i, 5] * A / heat[i, 9]
                elif (t - heat[i, 7]) % TWO_PI < (heat[i, 8] - heat[i, 7]) % TWO_PI:
                    q = heat[i, 5] * A / heat[i, 10]
                dy[2 * i + 1] += q
                dy[q0 + 1] = q
                dy[q0 + 2] = -q if q < 0.0 else 0.0
                continue
            if model == 1.0:
                h = heat[i, 1]
                # a wall hotter than the steam gives its heat to the water film that
                # the admission condensed on it, which boils at the saturation
                # temperature of the cylinder's pressure (pr[7]), however superheated
                # the thin exhaust steam around it (Marks Art. 74, 3-4)
                if wallT[i] > Ts:
                    Ts = pr[7, i]
            else:
                de = 6.0 * V / A
                re_ = RHO[i] * (0.5 * omega * de) * de / heat[i, 3]
                h = 0.053 * heat[i, 2] / de * re_ ** 0.8 * heat[i, 4] ** 0.6
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
        dy[ndyn + 2 * e] = md
        dy[ndyn + 2 * e + 1] = hd
    sweep_films(y, pr, dy, net)


@njit(cache=True, inline="always")
def sweep_films(y, pr, dy, net):
    """The skin model's film swept out with the steam (:mod:`corliss.engine.wall`).

    While an end's steam flows out, the film beyond :data:`FILM_WET` goes with it in
    the proportion of the steam leaving, into the steam as water of the film's
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
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    """
    heat = net[19]
    for i in range(heat.shape[0]):
        if heat[i, 0] != 4.0 or not dy[2 * i] < 0.0:
            continue
        k = int(heat[i, 8])
        extra = y[k + 1] - FILM_WET * heat[i, 7]
        m = y[2 * i]
        if extra > 0.0 and m > 0.0:
            sw = extra * (-dy[2 * i]) / m
            dy[2 * i] += sw
            dy[2 * i + 1] += sw * heat[i, 11]
            dy[k + 1] -= sw


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
    net : tuple
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
    nv = net[4].shape[0]
    if tier == TIER_PERFECT:
        res = net[8]
        for r in range(res.shape[0]):
            res[r, 3] = 1.0 + perf[0] / perf[1]
    kind, cyl, end, fixedV = net[4], net[5], net[6], net[7]
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
        pr[4, i] = dV
        pr[5, i] = V
        m = y[2 * i]
        u = y[2 * i + 1] / m if m > 0.0 else 2.6e6
        # the node's temperature at the evaluation before (the scratch's; anything
        # outside the wet bracket, garbage or NaN included, is ignored) starts the
        # table's wet iteration near its answer
        p, T, x, sup, code = props(tier, tab, perf, m / V, u, pr[6, i])
        rho, u = admissible(m / V, u)
        pr[0, i] = p
        pr[1, i] = rho
        pr[2, i] = u + p / rho
        pr[3, i] = 1.0 + perf[0] / perf[1] if tier == TIER_PERFECT else kappa_at(tab, rho, u)
        pr[6, i] = T
        pr[PR_CLAMP, i] = code
        pr[PR_X, i] = 1.0 if sup else x
        pr[PR_SUP, i] = 1.0 if sup else 0.0
        pr[PR_AT, i] = th
        pr[PR_AT + 1, i] = m
        pr[PR_AT + 2, i] = y[2 * i + 1]
        # the temperature of a wetted wall at this pressure, for the wall-heat effect only
        if net[19][i, 0] > 0.0:
            pr[7, i] = t_sat(tab, p) if (sup and tier != TIER_PERFECT) else T


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
    net : tuple
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


@njit(cache=True, _nrt=False)
def tally_clamps(pr, t, att):
    """Add the latest evaluation's clamps to a step attempt's tally.

    Parameters
    ----------
    pr : ndarray
        The node properties of the latest evaluation; row :data:`PR_CLAMP` is read.
    t : float
        The shaft angle of that evaluation [rad].
    att : ndarray
        Updated: a step attempt's clamp tally, shape (4,): clamped evaluations,
        the OR of their codes, shaft angle [rad] and node of the first.
    """
    c = 0
    first = -1
    for i in range(pr.shape[1]):
        ci = int(pr[PR_CLAMP, i])
        if ci != 0 and first < 0:
            first = i
        c |= ci
    if c != 0:
        if att[0] == 0.0:
            att[2] = t
            att[3] = first
        att[0] += 1.0
        att[1] = float(int(att[1]) | c)


@njit(cache=True, _nrt=False)
def settle_visited(att, clamps):
    """Move a step attempt's tally into the cycle's as evaluations at visited states.

    Parameters
    ----------
    att : ndarray
        A step attempt's clamp tally, shape (4,), cleared: clamped evaluations,
        the OR of their codes, shaft angle [rad] and node of the first.
    clamps : ndarray
        The cycle's clamp counts, shape (6,), updated, indexed by ``CL_*``.
    """
    if att[0] > 0.0:
        if clamps[CL_ACCEPTED] == 0.0:
            clamps[CL_THETA] = att[2]
            clamps[CL_NODE] = att[3]
        clamps[CL_ACCEPTED] += att[0]
        clamps[CL_ACCEPTED_CODE] = float(int(clamps[CL_ACCEPTED_CODE]) | int(att[1]))
    for k in range(4):
        att[k] = 0.0


@njit(cache=True, _nrt=False)
def settle_trial(att, clamps):
    """Move a step attempt's tally into the cycle's as evaluations at trial states.

    Parameters
    ----------
    att : ndarray
        A step attempt's clamp tally, shape (4,), cleared: clamped evaluations,
        the OR of their codes, shaft angle [rad] and node of the first.
    clamps : ndarray
        The cycle's clamp counts, shape (6,), updated, indexed by ``CL_*``.
    """
    if att[0] > 0.0:
        clamps[CL_REJECTED] += att[0]
        clamps[CL_REJECTED_CODE] = float(int(clamps[CL_REJECTED_CODE]) | int(att[1]))
    for k in range(4):
        att[k] = 0.0


@njit(cache=True, _nrt=False)
def settle_clamps(att, accepted, clamps):
    """Move a step attempt's tally into the cycle's, as visited or trial states.

    For a run-time flag; callers that know which use :func:`settle_visited` or
    :func:`settle_trial` (one compiled version each).

    Parameters
    ----------
    att : ndarray
        A step attempt's clamp tally, shape (4,), cleared: clamped evaluations,
        the OR of their codes, shaft angle [rad] and node of the first.
    accepted : bool
        Whether the step was accepted (its end a visited state).
    clamps : ndarray
        The cycle's clamp counts, shape (6,), updated, indexed by ``CL_*``.
    """
    if accepted:
        settle_visited(att, clamps)
    else:
        settle_trial(att, clamps)


@njit(cache=True, _nrt=False)
def copy_into(dst, src):
    """``dst[:] = src`` for 1-d arrays of one length.

    Without the shape check's error path, which numba would compile into every
    caller.

    Parameters
    ----------
    dst : ndarray
        Written; shape (n,).
    src : ndarray
        Shape (n,).
    """
    for i in range(dst.shape[0]):
        dst[i] = src[i]


@njit(cache=True, _nrt=False)
def put_column(samples, k, y):
    """``samples[:, k] = y``, as :func:`copy_into`.

    Parameters
    ----------
    samples : ndarray
        Written at column ``k``; shape (n, outputs).
    k : int
        The column.
    y : ndarray
        Shape (n,).
    """
    for i in range(y.shape[0]):
        samples[i, k] = y[i]


# Dormand-Prince 5(4) tableau
DOPRI_NODES = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = np.array([
    [0, 0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0],
    [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
])
_B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0])
_E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


@njit(cache=True, _nrt=False)
def hermite(t0, y0, f0, t1, y1, f1, t, out):
    """Cubic Hermite interpolation on a step from its end states and derivatives.

    Parameters
    ----------
    t0, t1 : float
        The step's ends [rad].
    y0, y1 : ndarray
        The states there; shape (n,).
    f0, f1 : ndarray
        Their derivatives (per radian); shape (n,).
    t : float
        Where to interpolate [rad], between ``t0`` and ``t1``.
    out : ndarray
        Written: the interpolated state; shape (n,).
    """
    h = t1 - t0
    s = (t - t0) / h
    h00 = 2 * s ** 3 - 3 * s ** 2 + 1
    h10 = s ** 3 - 2 * s ** 2 + s
    h01 = -2 * s ** 3 + 3 * s ** 2
    h11 = s ** 3 - s ** 2
    for i in range(y0.shape[0]):
        out[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]


@njit(cache=True, _nrt=False)
def dopri_stage(y, K, s_, h, ytmp):
    """The state at a Dormand-Prince stage: ``y + h sum_j a_sj K_j``.

    Parameters
    ----------
    y : ndarray
        The state at the step's start; shape (n,).
    K : ndarray
        The stages' derivatives so far; shape (7, n).
    s_ : int
        The stage, 1 to 6.
    h : float
        The step [rad].
    ytmp : ndarray
        Written: the stage's state; shape (n,).
    """
    for i in range(y.shape[0]):
        acc = 0.0
        for j in range(s_):
            acc += _A[s_, j] * K[j, i]
        ytmp[i] = y[i] + h * acc


@njit(cache=True, _nrt=False)
def dopri_error(y, ynew, K, h, atol, rtol):
    """The 5(4) pair's scaled error.

    ``max_i |err_i| / (atol_i + rtol max(|y_i|, |ynew_i|))``, the error ``err`` being
    the difference of the fifth- and fourth-order results.

    Parameters
    ----------
    y : ndarray
        The state at the step's start; shape (n,).
    ynew : ndarray
        The fifth-order state at its end; shape (n,).
    K : ndarray
        The seven stages' derivatives; shape (7, n).
    h : float
        The step [rad].
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n,).
    rtol : float
        Relative tolerance [-].

    Returns
    -------
    float
        The error [-]: the step is accurate enough at 1 or less.
    """
    err = 0.0
    for i in range(y.shape[0]):
        e = 0.0
        for j in range(7):
            e += _E[j] * K[j, i]
        e = abs(h * e) / (atol[i] + rtol * max(abs(y[i]), abs(ynew[i])))
        if e > err:
            err = e
    return err


@njit(cache=True, inline="always")
def _exact_jacobian_holds(net):
    """Whether :func:`_jacobian_exact` covers the network's right-hand side: no wall
    heat that depends on the state (none, or Marks's schedule); the film and wall
    temperature models are differentiated by finite differences."""
    heat = net[19]
    for i in range(heat.shape[0]):
        if heat[i, 0] != 0.0 and heat[i, 0] != 3.0:
            return False
    return True


def exact_jacobian_covers(net) -> bool:
    """Whether the Rosenbrock methods' Jacobian of this network is exact.

    The Python face of the compiled test the integrators make: no wall heat that
    depends on the state (none, or Marks's schedule).

    Parameters
    ----------
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).

    Returns
    -------
    bool
        True when :func:`_jacobian_exact` covers the network.
    """
    return bool(_exact_jacobian_holds.py_func(net))


@njit(cache=True, _nrt=False)
def _jacobian_exact(t, y, J, T, net, tier, tab, perf, pr, cell, jd, slope):
    """The Jacobian of :func:`rhs` over the dynamic columns, and its time derivative,
    from the derivatives of its parts, for a network :func:`_exact_jacobian_holds`
    covers.

    Each node's pressure, density, enthalpy and port-flow exponent depend on its own
    mass m and energy E alone, through rho = m/V and u = E/m: their partials in
    (rho, u) come from the table's own interpolation
    (:func:`corliss.thermo.steam_table.pressure_partials`,
    :func:`~corliss.thermo.steam_table.kappa_partials`) or the perfect gas's closed
    form, and go to (m, E) by the chain rule (none in a coordinate the state's clamp
    holds), and to the crank angle through the volume (drho/dtheta = -rho V'/V).  Each
    node's work term ``-p dV/dtheta`` then moves its energy row and work quadrature
    (in time also through V''); each edge's flow
    (:func:`corliss.thermo.orifice.port_flow_partials`, and in time its area's slope
    on the PortMap table) and the enthalpy it carries (of the side it leaves) move the
    rows of its two ends and its quadratures.  ``pr`` is written with the properties
    at ``y``, ``jd`` (shape (12, nodes)) with their partials, ``slope`` (shape
    (cylinders, 4)) with the ports' area slopes.

    A node whose properties on ``pr`` are those of its state at (``t``, ``y``) (the
    angle, mass and energy of rows :data:`PR_AT` on: an integrator's step starts
    where its last evaluation was) and were not clamped keeps that evaluation's volume,
    pressure and temperature, and only the partials are computed
    (:func:`corliss.thermo.steam_table.pressure_partials`: the same numbers, without
    the lookup's iteration, about a third of this function's time).
    """
    nv = net[4].shape[0]
    n = y.shape[0]
    ndyn = 2 * nv
    for i in range(n):
        T[i] = 0.0
        for j in range(ndyn):
            J[i, j] = 0.0
    for i in range(nv):
        known = (pr[PR_CLAMP, i] == 0.0 and pr[PR_AT, i] == t
                 and pr[PR_AT + 1, i] == y[2 * i] and pr[PR_AT + 2, i] == y[2 * i + 1])
        if known:
            V, dV = pr[5, i], pr[4, i]
        else:
            V, dV = node_volume(t, net, i)
            pr[4, i] = dV
            pr[5, i] = V
        m = y[2 * i]
        if m > 0.0:
            u = y[2 * i + 1] / m
            u_m = -u / m
            u_e = 1.0 / m
        else:
            u = 2.6e6
            u_m = 0.0
            u_e = 0.0
        r_m = 1.0 / V
        r_t = -m / V * dV / V
        rho, u, code = admissible_flagged(m / V, u)
        if code & 3:
            r_m = 0.0
            r_t = 0.0
        if code & 12:
            u_m = 0.0
            u_e = 0.0
        if tier == TIER_PERFECT:
            R, cv, u_ref = perf[0], perf[1], perf[2]
            Tk = (u - u_ref) / cv
            if Tk < 1.0:
                Tk = 1.0
                p_r, p_u = R * Tk, 0.0
            else:
                p_r, p_u = R * Tk, rho * R / cv
            p = rho * R * Tk
            k, k_r, k_u = 1.0 + R / cv, 0.0, 0.0
        else:
            if known:
                p, Tk, sup, c2 = pr[0, i], pr[6, i], pr[PR_SUP, i] != 0.0, 0
            else:
                p, Tk, x, sup, c2 = lookup_near(tab, rho, u, pr[6, i])
            # (the lookup skipped for a known node: one copy of the partials' code,
            # which numba inlines)
            p_r, p_u = pressure_partials(tab, rho, u, p, Tk, sup, c2)
            k, k_r, k_u = kappa_partials(tab, rho, u)
        h_r = p_r / rho - p / (rho * rho)
        h_u = 1.0 + p_u / rho
        pr[0, i] = p
        pr[1, i] = rho
        pr[2, i] = u + p / rho
        pr[3, i] = k
        # rows: d(p, rho, h, kappa) / d(m, E), then / dtheta
        jd[0, i] = p_r * r_m + p_u * u_m
        jd[1, i] = p_u * u_e
        jd[2, i] = r_m
        jd[3, i] = 0.0
        jd[4, i] = h_r * r_m + h_u * u_m
        jd[5, i] = h_u * u_e
        jd[6, i] = k_r * r_m + k_u * u_m
        jd[7, i] = k_u * u_e
        jd[8, i] = p_r * r_t
        jd[9, i] = r_t
        jd[10, i] = h_r * r_t
        jd[11, i] = k_r * r_t
        q0 = ndyn + 2 * net[9].shape[0] + 5 * i
        for v in range(2):
            J[2 * i + 1, 2 * i + v] = -jd[v, i] * dV
            J[q0, 2 * i + v] = jd[v, i] * dV
        w_t = jd[8, i] * dV + p * _volume_curvature(t, net, i)
        T[2 * i + 1] = -w_t
        T[q0] = w_t
    omega, band, res = net[0][0], net[1], net[8]
    ea, eb, ecd, ekind, ecyl, eport = net[9], net[10], net[15], net[11], net[12], net[13]
    port_areas(t, net, cell)
    _port_area_slopes(t, net, slope)
    for e in range(ea.shape[0]):
        area = edge_area(net, e, cell)
        if area <= 0.0:
            # a shut port: no flow and no partials (port_flow_partials's own test), nor
            # in time (the area's slope enters only where the area is open), as in
            # :func:`balances`
            continue
        a = ea[e]
        b = eb[e]
        pa, ra, ha, ka = edge_side(a, pr, res)
        pb, rb, hb, kb = edge_side(b, pr, res)
        md, d1p, d1r, d1k, d2p, d2r, d2k = port_flow_partials(
            area, ecd[e], pa, ra, ka, pb, rb, kb, band, True)
        # the side upstream as the flow's partials take it (side a at equal pressures):
        # not by the sign of md, which is 0 there, where the right-hand side carries no
        # enthalpy and its two one-sided derivatives carry side a's (pressure of b
        # falling) or b's (rising); mixing a's flux slope with b's enthalpy matched
        # neither (a steam chest that has equalised with the supply to the last bit)
        up_a = pa >= pb
        h_up = ha if up_a else hb
        # in time: the area's slope (the flow is proportional to the area) and the
        # two sides' states
        md_t = md / area * slope[ecyl[e], eport[e]] if ekind[e] != 1 and area > 0.0 else 0.0
        hd_t = 0.0
        for side in range(2):
            nd = a if side == 0 else b
            if nd < 0:
                continue
            dp, dr, dk = (d1p, d1r, d1k) if side == 0 else (d2p, d2r, d2k)
            carries = up_a == (side == 0)
            md_t += dp * jd[8, nd] + dr * jd[9, nd] + dk * jd[11, nd]
            if carries:
                hd_t += md * jd[10, nd]
            for v in range(2):
                col = 2 * nd + v
                dmd = dp * jd[v, nd] + dr * jd[2 + v, nd] + dk * jd[6 + v, nd]
                dhd = dmd * h_up
                if carries:
                    dhd += md * jd[4 + v, nd]
                dmd /= omega
                dhd /= omega
                if a >= 0:
                    J[2 * a, col] -= dmd
                    J[2 * a + 1, col] -= dhd
                if b >= 0:
                    J[2 * b, col] += dmd
                    J[2 * b + 1, col] += dhd
                J[ndyn + 2 * e, col] += dmd
                J[ndyn + 2 * e + 1, col] += dhd
        hd_t += md_t * h_up
        md_t /= omega
        hd_t /= omega
        if a >= 0:
            T[2 * a] -= md_t
            T[2 * a + 1] -= hd_t
        if b >= 0:
            T[2 * b] += md_t
            T[2 * b + 1] += hd_t
        T[ndyn + 2 * e] += md_t
        T[ndyn + 2 * e + 1] += hd_t


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _jacobian(t, y, f0, J, T, yscale, color, owner, net, tier, tab, perf, pr, cell, att,
              yp, fp, dl, jd, slope):
    """Jacobian of the dynamic columns, and the time derivative, for both Rosenbrock
    integrators.

    Analytic (:func:`_jacobian_exact`, no evaluation of :func:`rhs`) where it covers
    the network, else by finite differences: columns of one colour are perturbed
    together (their rows do not overlap), so a single cylinder costs two evaluations,
    and the time derivative a forward difference, one more.  Clamped evaluations go
    into the step's tally ``att``; ``yp``, ``fp`` (length of the state), ``dl`` (of
    the dynamic states), ``jd`` (shape (12, nodes)) and ``slope`` (shape (cylinders,
    4)) are scratch.  Returns the evaluations of :func:`rhs` spent.
    """
    if _exact_jacobian_holds(net):
        _jacobian_exact(t, y, J, T, net, tier, tab, perf, pr, cell, jd, slope)
        return 0
    n = y.shape[0]
    ndyn = J.shape[1]
    ncol = owner.shape[0]
    for j in range(ndyn):
        dl[j] = 1e-7 * max(abs(y[j]), yscale[j])
    for c in range(ncol):
        copy_into(yp, y)
        for j in range(ndyn):
            if color[j] == c:
                yp[j] += dl[j]
        rhs(t, yp, fp, net, tier, tab, perf, pr, cell)
        tally_clamps(pr, t, att)
        for j in range(ndyn):
            if color[j] == c:
                for i in range(n):
                    J[i, j] = 0.0
        for i in range(n):
            j = owner[c, i]
            if j >= 0:
                J[i, j] = (fp[i] - f0[i]) / dl[j]
    dt = 1e-7 * max(abs(t), 1.0)
    rhs(t + dt, y, fp, net, tier, tab, perf, pr, cell)
    tally_clamps(pr, t + dt, att)
    for i in range(n):
        T[i] = (fp[i] - f0[i]) / dt
    return ncol + 1


@njit(cache=True, _nrt=False)
def gauss_jordan(A, Winv):
    """Invert ``A`` into ``Winv`` (which holds the identity), by Gauss-Jordan elimination
    with partial pivoting, ``A`` overwritten: a few rows, no LAPACK call, and none to
    compile.  Shared by the steady and transient Rosenbrock integrators.

    Parameters
    ----------
    A : ndarray
        The matrix, shape (m, m); overwritten.
    Winv : ndarray
        The identity on entry, the inverse of ``A`` on return; shape (m, m).
    """
    ndyn = A.shape[0]
    for c in range(ndyn):
        piv = c
        for r in range(c + 1, ndyn):
            if abs(A[r, c]) > abs(A[piv, c]):
                piv = r
        if piv != c:
            for j in range(ndyn):
                A[c, j], A[piv, j] = A[piv, j], A[c, j]
                Winv[c, j], Winv[piv, j] = Winv[piv, j], Winv[c, j]
        d = 1.0 / A[c, c]
        for j in range(ndyn):
            A[c, j] *= d
            Winv[c, j] *= d
        for r in range(ndyn):
            if r != c:
                f = A[r, c]
                if f != 0.0:
                    for j in range(ndyn):
                        A[r, j] -= f * A[c, j]
                        Winv[r, j] -= f * Winv[c, j]


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _w_inverse(J, hd, Winv, A):
    """Inverse of the dynamic block of W = I - hd J into ``Winv``
    (:func:`gauss_jordan`); ``A`` is scratch of its shape."""
    ndyn = J.shape[1]
    for i in range(ndyn):
        for j in range(ndyn):
            A[i, j] = (1.0 if i == j else 0.0) - hd * J[i, j]
            Winv[i, j] = 1.0 if i == j else 0.0
    gauss_jordan(A, Winv)


@njit(cache=True, _nrt=False, no_cpython_wrapper=True)
def _w_solve(J, Winv, hd, x, out):
    """Solve W out = x: the dynamic block by its inverse, the quadratures (which do
    not feed back) by substitution, out_q = x_q + hd J_q,dyn out_dyn."""
    ndyn = J.shape[1]
    for i in range(ndyn):
        acc = 0.0
        for j in range(ndyn):
            acc += Winv[i, j] * x[j]
        out[i] = acc
    for q in range(ndyn, x.shape[0]):
        acc = x[q]
        for j in range(ndyn):
            acc += hd * J[q, j] * out[j]
        out[q] = acc


@njit(cache=True, inline="always")
def tableau_argument(y, U, tA, st, ytmp):
    """A Rosenbrock tableau's stage argument, ``ytmp = y + sum_j a_st,j u_j``
    (the steady and the transient loops' shared arithmetic).

    Parameters
    ----------
    y : ndarray
        The state at the step's start, shape (n,).
    U : ndarray
        The stages so far, shape (stages, n).
    tA : ndarray
        The tableau's a_ij, shape (stages, stages) [-].
    st : int
        The stage.
    ytmp : ndarray
        Written: the argument, shape (n,).
    """
    for i in range(y.shape[0]):
        acc = y[i]
        for j in range(st):
            acc += tA[st, j] * U[j, i]
        ytmp[i] = acc


@njit(cache=True, inline="always")
def tableau_stage_rhs(fp, T, U, tC, td, st, h, x):
    """The right-hand side of a tableau's stage equation,
    ``x = f + h d_st df/dt + sum_j c_st,j u_j / h``.

    Parameters
    ----------
    fp : ndarray
        The derivatives at the stage's argument, shape (n,).
    T : ndarray
        The derivatives' rate in crank angle, shape (n,).
    U : ndarray
        The stages so far, shape (stages, n).
    tC : ndarray
        The tableau's c_ij, shape (stages, stages) [-].
    td : ndarray
        The tableau's d_i, shape (stages,) [-].
    st : int
        The stage.
    h : float
        The step [rad].
    x : ndarray
        Written: the right-hand side, shape (n,).
    """
    for i in range(fp.shape[0]):
        acc = 0.0
        for j in range(st):
            acc += tC[st, j] * U[j, i]
        x[i] = fp[i] + h * td[st] * T[i] + acc / h


@njit(cache=True, inline="always")
def tableau_solution(y, U, tb, te, atol, rtol, ytmp):
    """A tableau step's solution ``ytmp = y + sum_i b_i u_i`` and its error against
    the tolerances, ``max_i |sum_j e_j u_j,i| / (atol_i + rtol max(|y_i|, |ytmp_i|))``.

    Parameters
    ----------
    y : ndarray
        The state at the step's start, shape (n,).
    U : ndarray
        The stages, shape (stages, n).
    tb, te : ndarray
        The tableau's weights b_i and error weights e_i, shape (stages,) [-].
    atol : ndarray
        Absolute tolerances, shape (n,).
    rtol : float
        Relative tolerance [-].
    ytmp : ndarray
        Written: the step's solution, shape (n,).

    Returns
    -------
    float
        The error norm [-] (at most 1 passes).
    """
    ns = tb.shape[0]
    err = 0.0
    for i in range(y.shape[0]):
        acc = y[i]
        e = 0.0
        for j in range(ns):
            acc += tb[j] * U[j, i]
            e += te[j] * U[j, i]
        ytmp[i] = acc
        e = abs(e) / (atol[i] + rtol * max(abs(y[i]), abs(acc)))
        if e > err:
            err = e
    return err


_D = 1.0 / (2.0 + math.sqrt(2.0))
_E32 = 6.0 + math.sqrt(2.0)
#: :func:`cycle_ros`'s ``kind``: the ode23s pair's own stages, or a tableau's.
KIND_ODE23S = 0
KIND_TABLEAU = 1


@njit(cache=True, _nrt=False)
def emit_samples(io, out_theta, t0, y0, f0, t1, y1, f1, samples, tmp):
    """Write the states at the output angles a step passed (cubic Hermite on the step).

    Parameters
    ----------
    io : int
        The next output angle not yet written.
    out_theta : ndarray
        The output angles [rad], increasing; shape (outputs,).
    t0, t1 : float
        The step's ends [rad].
    y0, y1 : ndarray
        The states there; shape (n,).
    f0, f1 : ndarray
        Their derivatives (per radian); shape (n,).
    samples : ndarray
        Written at the columns of ``out_theta[io:]`` up to ``t1``; shape (n, outputs).
    tmp : ndarray
        Scratch; shape (n,).

    Returns
    -------
    int
        The index of the next output angle not written.
    """
    while io < out_theta.shape[0] and out_theta[io] <= t1:
        hermite(t0, y0, f0, t1, y1, f1, out_theta[io], tmp)
        put_column(samples, io, tmp)
        io += 1
    return io


@njit(cache=True, _nrt=False)
def initial_step(f0, y, atol, rtol, span):
    """A first step from the derivative's scale.

    ``0.01 rtol^(1/5) / max_i (|f_i| / (atol_i + rtol |y_i|))``.

    Parameters
    ----------
    f0 : ndarray
        The derivative at the start (per radian); shape (n,).
    y : ndarray
        The state at the start; shape (n,).
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n,).
    rtol : float
        Relative tolerance [-].
    span : float
        The segment's length [rad].

    Returns
    -------
    float
        The step [rad], within [1e-9, ``span``] (``span`` when nothing changes).
    """
    scale = 0.0
    for i in range(y.shape[0]):
        v = abs(f0[i]) / (atol[i] + rtol * abs(y[i]))
        if v > scale:
            scale = v
    h = 0.01 * (rtol ** 0.2) / scale if scale > 0.0 else span
    return min(max(h, 1e-9), span)


@njit(cache=True, _nrt=False)
def starting_step(t, y, f0, atol, rtol, span, expo, net, tier, tab, perf, pr, cell, att,
                  yp, fp, prs):
    """A first step from the derivative and its change over a trial Euler step.

    Hairer, Norsett and Wanner's starting step (*Solving Ordinary Differential
    Equations I*, Sec. II.4), in the error's max norm: with ``d0``, ``d1`` the scaled
    state and derivative, a trial step ``h0 = 0.01 d0 / d1``; ``d2`` the scaled change
    of the derivative over it, per radian; the step ``(0.01 / max(d1, d2))^(-expo)``,
    at most ``100 h0``.  One evaluation of :func:`rhs` (its clamps go into ``att``, a
    trial's); ``pr`` is left as it came (the properties at ``t``, ``y``, where the
    step's Jacobian may take them).

    Parameters
    ----------
    t : float
        The start [rad].
    y : ndarray
        The state there; shape (n_state,).
    f0 : ndarray
        The derivative there (per radian); shape (n_state,).
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n_state,).
    rtol : float
        Relative tolerance [-].
    span : float
        The segment's length [rad].
    expo : float
        The exponent, ``-1 / (order + 1)`` of the method's error estimate [-].
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    pr : ndarray
        The node properties at ``t``, ``y``, shape (:data:`PR_ROWS`, nodes); used as
        scratch and restored.
    cell : ndarray
        Scratch for the port areas [m2], shape (cylinders, 4).
    att : ndarray
        A step attempt's clamp tally, shape (4,), added to.
    yp, fp : ndarray
        Scratch, shape (n_state,).
    prs : ndarray
        Scratch of at least ``pr``'s rows, shape (rows, nodes).

    Returns
    -------
    float
        The step [rad], within [1e-9, ``span``].
    """
    n = y.shape[0]
    d0 = 0.0
    d1 = 0.0
    for i in range(n):
        sc = atol[i] + rtol * abs(y[i])
        d0 = max(d0, abs(y[i]) / sc)
        d1 = max(d1, abs(f0[i]) / sc)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, span)
    for i in range(n):
        yp[i] = y[i] + h0 * f0[i]
    for r in range(pr.shape[0]):
        for i in range(pr.shape[1]):
            prs[r, i] = pr[r, i]
    rhs(t + h0, yp, fp, net, tier, tab, perf, pr, cell)
    tally_clamps(pr, t + h0, att)
    for r in range(pr.shape[0]):
        for i in range(pr.shape[1]):
            pr[r, i] = prs[r, i]
    d2 = 0.0
    for i in range(n):
        d2 = max(d2, abs(fp[i] - f0[i]) / (atol[i] + rtol * abs(y[i])))
    d2 /= h0
    m = max(d1, d2)
    h1 = max(1e-6, h0 * 1e-3) if m <= 1e-15 else (0.01 / m) ** (-expo)
    return min(max(min(100.0 * h0, h1), 1e-9), span)


@njit(cache=True, _nrt=False)
def step_factor(err, safety, expo):
    """The ratio of the next step to this one after an accepted step.

    Parameters
    ----------
    err : float
        The step's scaled error [-].
    safety : float
        The safety factor [-] (0.9 for dopri5 and the Rosenbrock methods).
    expo : float
        The exponent, ``-1 / (order + 1)`` of the error estimate [-].

    Returns
    -------
    float
        ``safety err^expo`` kept within [0.2, 5] (5 for an error of zero).
    """
    if err == 0.0:
        return 5.0
    return min(5.0, max(0.2, safety * err ** expo))


@njit(cache=True, _nrt=False)
def predictive_factor(err, h, err_acc, h_acc, safety, expo):
    """The ratio of the next step to this one after an accepted step, by Gustafsson's
    predictive controller.

    The smaller of :func:`step_factor` and the ratio that the error's trend over the
    last two accepted steps predicts, ``safety (h / h_acc) err^(2 expo) err_acc^(-expo)``
    (Hairer and Wanner, *Solving Ordinary Differential Equations II*, Sec. IV.8,
    eq. 8.21, as their codes RODAS and RADAU5 apply it, ``err_acc`` kept at least 0.01).

    Parameters
    ----------
    err : float
        The step's scaled error [-].
    h : float
        The step [rad].
    err_acc : float
        The scaled error of the accepted step before it, at least 0.01 [-]; 0 when
        there was none (the factor is then :func:`step_factor`'s).
    h_acc : float
        That step [rad].
    safety : float
        The safety factor [-].
    expo : float
        The exponent, ``-1 / (order + 1)`` of the error estimate [-].

    Returns
    -------
    float
        The ratio [-], within [0.2, 5].
    """
    fac = step_factor(err, safety, expo)
    if err_acc > 0.0 and err > 0.0:
        gus = safety * (h / h_acc) * err ** (2.0 * expo) * err_acc ** (-expo)
        fac = min(fac, min(5.0, max(0.2, gus)))
    return fac


@njit(cache=True, _nrt=False)
def visited_clamp_off(att_end):
    """The clamp bits of a step's end that make it no step of the physical path.

    Every clamp but steam overheated by the walls (code 8), which is not the step's
    doing.

    Parameters
    ----------
    att_end : ndarray
        The clamp tally of the evaluation at the step's end; shape (4,).

    Returns
    -------
    int
        The bits (0: the end is a physical state).
    """
    if att_end[0] > 0.0:
        return int(att_end[1]) & ~CLAMP_HIGH_ENERGY
    return 0


@njit(cache=True, _nrt=False)
def segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att):
    """The derivative at the start of a segment between kinks, a visited state.

    Its clamps are settled as a visited state's.

    Parameters
    ----------
    t : float
        The segment's start [rad].
    y : ndarray
        The state, shape (n_state,), laid out as
        :class:`~corliss.engine.network.Network` says (masses [kg] and internal
        energies [J] of the nodes first).
    f0 : ndarray
        Written: the derivative there (per radian); shape (n_state,).
    net : tuple
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
    clamps : ndarray
        The cycle's clamp counts, shape (6,), updated, indexed by ``CL_*``.
    att : ndarray
        A step attempt's clamp tally, shape (4,), used and cleared: clamped
        evaluations, the OR of their codes, shaft angle [rad] and node of the first.
    """
    rhs(t, y, f0, net, tier, tab, perf, pr, cell)
    tally_clamps(pr, t, att)
    settle_visited(att, clamps)


def cycle_dopri5(y0, stops, out_theta, rtol, atol, net, tier, tab, perf, max_rhs):
    """:func:`integrate_cycle` with Dormand-Prince 5(4) (see the module docstring).

    Allocates the scratch (in Python: no compiled function to compile for it) and hands
    over to the compiled step loop :func:`_dopri5_steps`.

    Parameters
    ----------
    y0 : ndarray
        The state at ``stops[0]``; shape (n_state,).
    stops : ndarray
        Shaft angles [rad], increasing: the segments between them are integrated
        with a restart at each (:meth:`corliss.engine.network.Network.stops`).
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    rtol : float
        Relative tolerance [-].
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n_state,).
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.

    Returns
    -------
    y_end : ndarray
        The state at ``stops[-1]``; shape (n_state,).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n_state, outputs).
    nfev : int
        Right-hand-side evaluations spent.
    ok : bool
        False when the step size collapsed, the state went non-finite or more than
        ``max_rhs`` evaluations were spent.
    clamps : ndarray
        Evaluations that clamped a state, shape (6,), indexed by ``CL_*``: at visited
        states (the ends of accepted steps) and at trial states (stages, probes,
        rejected steps) apart.
    """
    n = y0.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    vec = np.empty((3, n))
    K = np.empty((7, n))
    pr = np.empty((PR_ROWS, net[4].shape[0]))
    cell = np.empty((net[17].shape[0], 4))
    clamps = np.zeros(6)
    clamps[CL_NODE] = -1.0
    tally = np.zeros((2, 4))
    nfev, ok = _dopri5_steps(y, samples, stops, out_theta, rtol, atol, net, tier, tab, perf,
                             max_rhs, vec, K, pr, cell, clamps, tally)
    return y, samples, nfev, ok, clamps


@njit(cache=True, _nrt=False)
def _dopri5_steps(y, samples, stops, out_theta, rtol, atol, net, tier, tab, perf, max_rhs,
                  vec, K, pr, cell, clamps, tally):
    """:func:`cycle_dopri5`'s steps, on scratch it allocated (no reference counts).
    ``y`` is advanced to the cycle's end, ``samples`` and ``clamps`` written; returns
    the evaluations spent and whether the cycle ended well."""
    f0, ytmp, tmp = vec[0], vec[1], vec[2]
    att, att_end = tally[0], tally[1]
    nfev = 0
    io = 0
    while io < out_theta.shape[0] and out_theta[io] <= stops[0]:
        put_column(samples, io, y)
        io += 1
    h_prev = 0.0
    for seg in range(stops.shape[0] - 1):
        a = stops[seg]
        b = stops[seg + 1]
        if b - a <= 0.0:
            continue
        t = a
        segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att)
        nfev += 1
        h = min(h_prev, b - a) if h_prev > 0.0 else initial_step(f0, y, atol, rtol, b - a)
        while t < b:
            if t + h > b or b - (t + h) < 1e-12:
                h = b - t
            copy_into(K[0], f0)
            for s_ in range(1, 7):
                dopri_stage(y, K, s_, h, ytmp)
                rhs(t + DOPRI_NODES[s_] * h, ytmp, K[s_], net, tier, tab, perf, pr, cell)
                tally_clamps(pr, t + DOPRI_NODES[s_] * h, att_end if s_ == 6 else att)
            nfev += 6
            err = dopri_error(y, ytmp, K, h, atol, rtol)
            # ytmp: the new state; K[6]: the derivative there (FSAL).  A step whose end
            # needed the properties clamped (a volume emptied below their least density,
            # say) is no step of the physical path: it is retried shorter, as an
            # inaccurate one is (positivity by step control).
            accepted = (err <= 1.0 and visited_clamp_off(att_end) == 0) or h < 1e-12
            settle_trial(att, clamps)
            settle_clamps(att_end, accepted, clamps)
            if accepted:
                t1 = t + h
                io = emit_samples(io, out_theta, t, y, f0, t1, ytmp, K[6], samples, tmp)
                t = t1
                copy_into(y, ytmp)
                copy_into(f0, K[6])
                h_prev = h * step_factor(err, 0.9, -0.2)
                h = h_prev
            elif err <= 1.0:
                h = 0.5 * h      # accurate, but through a state the properties do not hold
            else:
                h = h * max(0.2, 0.9 * err ** -0.2)
            if not (h > 0.0) or not math.isfinite(y[0]) or nfev > max_rhs:
                return nfev, False
    while io < out_theta.shape[0]:
        put_column(samples, io, y)
        io += 1
    return nfev, True


@njit(cache=True)
def cycle_rk4(y0, stops, out_theta, step, net, tier, tab, perf, max_rhs):
    """:func:`integrate_cycle` with the classical Runge-Kutta method at a fixed step.

    Each segment between stops is divided into equal steps no longer than ``step``.

    Parameters
    ----------
    y0 : ndarray
        The state at ``stops[0]``; shape (n_state,).
    stops : ndarray
        Shaft angles [rad], increasing: the segments between them are integrated
        with a restart at each (:meth:`corliss.engine.network.Network.stops`).
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    step : float
        The largest fixed step [rad].
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.

    Returns
    -------
    y_end : ndarray
        The state at ``stops[-1]``; shape (n_state,).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n_state, outputs).
    nfev : int
        Right-hand-side evaluations spent.
    ok : bool
        False when the step size collapsed, the state went non-finite or more than
        ``max_rhs`` evaluations were spent.
    clamps : ndarray
        Evaluations that clamped a state, shape (6,), indexed by ``CL_*``: at visited
        states (the ends of accepted steps) and at trial states (stages, probes,
        rejected steps) apart.
    """
    n = y0.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    f0 = np.empty(n)
    f1 = np.empty(n)
    K = np.empty((4, n))
    ynew = np.empty(n)
    ytmp = np.empty(n)
    tmp = np.empty(n)
    pr = np.empty((PR_ROWS, net[4].shape[0]))
    cell = np.empty((net[17].shape[0], 4))
    nfev = 0
    clamps = np.zeros(6)
    clamps[CL_NODE] = -1.0
    att = np.zeros(4)
    att_end = np.zeros(4)
    io = 0
    while io < out_theta.shape[0] and out_theta[io] <= stops[0]:
        put_column(samples, io, y)
        io += 1
    for seg in range(stops.shape[0] - 1):
        a = stops[seg]
        b = stops[seg + 1]
        if b - a <= 0.0:
            continue
        t = a
        segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att)
        nfev += 1
        nstep = int(math.ceil((b - a) / step - 1e-9))
        if nstep < 1:
            nstep = 1
        h = (b - a) / nstep
        for k_ in range(nstep):
            for i in range(n):
                ytmp[i] = y[i] + 0.5 * h * f0[i]
            rhs(t + 0.5 * h, ytmp, K[1], net, tier, tab, perf, pr, cell)
            tally_clamps(pr, t + 0.5 * h, att)
            for i in range(n):
                ytmp[i] = y[i] + 0.5 * h * K[1, i]
            rhs(t + 0.5 * h, ytmp, K[2], net, tier, tab, perf, pr, cell)
            tally_clamps(pr, t + 0.5 * h, att)
            for i in range(n):
                ytmp[i] = y[i] + h * K[2, i]
            rhs(t + h, ytmp, K[3], net, tier, tab, perf, pr, cell)
            tally_clamps(pr, t + h, att)
            for i in range(n):
                ynew[i] = y[i] + h / 6.0 * (f0[i] + 2 * K[1, i] + 2 * K[2, i] + K[3, i])
            t1 = b if k_ == nstep - 1 else t + h
            rhs(t1, ynew, f1, net, tier, tab, perf, pr, cell)
            tally_clamps(pr, t1, att_end)
            settle_trial(att, clamps)
            settle_visited(att_end, clamps)
            nfev += 4
            io = emit_samples(io, out_theta, t, y, f0, t1, ynew, f1, samples, tmp)
            t = t1
            copy_into(y, ynew)
            copy_into(f0, f1)
        if not math.isfinite(y[0]) or nfev > max_rhs:
            return y, samples, nfev, False, clamps
    while io < out_theta.shape[0]:
        put_column(samples, io, y)
        io += 1
    return y, samples, nfev, True, clamps


def _tableau(gamma, A, C, c, d, b, e, expo):
    """A Rosenbrock tableau as the arrays :func:`cycle_ros` takes, in the form
    ``(I/(gamma h) - J) u_i = f(t + c_i h, y + sum_j a_ij u_j) + sum_j c_ij u_j / h
    + d_i h df/dt``, ``y1 = y + sum_i b_i u_i``, error ``sum_i e_i u_i`` (Hairer and
    Wanner, *Solving Ordinary Differential Equations II*, Sec. IV.7, eq. 7.25), with the
    step's exponent of the error ``expo``.  ``same[i]`` says when stage i's argument is one already
    evaluated: 1 the step's start (no evaluation), 2 the stage before."""
    s_ = len(b)
    At = np.zeros((s_, s_))
    Ct = np.zeros((s_, s_))
    for i in range(1, s_):
        At[i, :i] = A[i - 1]
        Ct[i, :i] = C[i - 1]
    ct = np.array(c, dtype=float)
    same = np.zeros(s_, dtype=np.int64)
    for i in range(1, s_):
        if ct[i] == 0.0 and not At[i].any():
            same[i] = 1
        elif ct[i] == ct[i - 1] and np.array_equal(At[i, :i - 1], At[i - 1, :i - 1]) \
                and At[i, i - 1] == 0.0:
            same[i] = 2
    return (float(gamma), At, Ct, ct, np.array(d, dtype=float), np.array(b, dtype=float),
            np.array(e, dtype=float), same, float(expo))


#: Rosenbrock tableaus of :func:`cycle_ros` by method name.
#: ``ros4``: Shampine's 4(3) pair (ACM Trans. Math. Softw. 8, 1982; Press et al.,
#: *Numerical Recipes*, 2nd ed., Sec. 16.6): four stages, three evaluations, A-stable,
#: its stability function 1/3 at infinity.
#: ``rodas3``: Sandu et al.'s RODAS3 (Atmos. Environ. 31, 1997): four stages, two
#: evaluations (the second stage's argument is the step's start), order 3, L-stable
#: and stiffly accurate, its error the last stage.
#: ``rodas4``: Hairer and Wanner's RODAS4 (*Solving Ordinary Differential Equations II*,
#: Sec. VI.4): six stages, five evaluations, order 4, L-stable and stiffly accurate.
ROS_TABLEAUS = {
    "ros4": _tableau(0.5, [[2.0], [48.0 / 25.0, 6.0 / 25.0], [48.0 / 25.0, 6.0 / 25.0, 0.0]],
                     [[-8.0], [372.0 / 25.0, 12.0 / 5.0],
                      [-112.0 / 125.0, -54.0 / 125.0, -2.0 / 5.0]],
                     [0.0, 1.0, 0.6, 0.6], [0.5, -1.5, 121.0 / 50.0, 29.0 / 250.0],
                     [19.0 / 9.0, 0.5, 25.0 / 108.0, 125.0 / 108.0],
                     [17.0 / 54.0, 7.0 / 36.0, 0.0, 125.0 / 108.0], -0.25),
    "rodas3": _tableau(0.5, [[0.0], [2.0, 0.0], [2.0, 0.0, 1.0]],
                       [[4.0], [1.0, -1.0], [1.0, -1.0, -8.0 / 3.0]],
                       [0.0, 0.0, 1.0, 1.0], [0.5, 1.5, 0.0, 0.0], [2.0, 0.0, 1.0, 1.0],
                       [0.0, 0.0, 0.0, 1.0], -1.0 / 3.0),
    "rodas4": _tableau(
        0.25,
        [[1.544],
         [0.9466785280815826, 0.2557011698983284],
         [3.314825187068521, 2.896124015972201, 0.9986419139977817],
         [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895],
         [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895, 1.0]],
        [[-5.6688],
         [-2.430093356833875, -0.2063599157091915],
         [-0.1073529058151375, -9.594562251023355, -20.47028614809616],
         [7.496443313967647, -10.24680431464352, -33.99990352819905, 11.7089089320616],
         [8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136,
          -6.058818238834054]],
        [0.0, 0.386, 0.21, 0.63, 1.0, 1.0], [0.25, -0.1043, 0.1035, -0.0362, 0.0, 0.0],
        [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895,
         1.0, 1.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 1.0], -0.25),
}


def cycle_ros(y0, stops, out_theta, rtol, atol, net, tier, tab, perf, color, owner,
              max_rhs, jac_age, gam, tA, tC, tc, td, tb, te, same, expo, kind):
    """:func:`integrate_cycle` with a Rosenbrock method: the ode23s pair, or a tableau's.

    One compiled step loop for every Rosenbrock method (segments, Jacobian, W, step
    control, clamps, output), with the stages of the method: Shampine and Reichelt's
    2(3) pair of ode23s (``kind`` :data:`KIND_ODE23S`, its formulas as the paper
    writes them; the tableau's arrays are then unused) or those of a tableau
    (:data:`KIND_TABLEAU`, :data:`ROS_TABLEAUS`).  The ode23s pair evaluates the
    derivative at the step's end as its last stage, for every step; a tableau's method
    evaluates it (for the next step and the output) only for a step whose error passes.
    The ode23s pair's steps follow Gustafsson's predictive controller
    (:func:`predictive_factor`) from Hairer, Norsett and Wanner's starting step
    (:func:`starting_step`); a tableau's, the error alone (:func:`step_factor`) from
    :func:`initial_step`.  On the default card the error-alone control drove the pair's
    steps at the crank end's admission through a cycle of acceptance at an error of
    0.2, growth and rejection, onto a spurious solution of the pair (the cylinder
    0.5-1 % below the chest, at 0.3-0.4 deg steps: its midpoint stage overshoots the
    port's equilibrium into the steeper square-root flux and comes back reversed);
    the predictive controller keeps to the filling at 1.7 deg steps, with 353
    evaluations a cycle against 454.
    Allocates the scratch (in Python: no compiled function to compile for it) and hands
    over to the compiled step loop :func:`_ros_steps`.

    Parameters
    ----------
    y0 : ndarray
        The state at ``stops[0]``; shape (n_state,).
    stops : ndarray
        Shaft angles [rad], increasing: the segments between them are integrated
        with a restart at each (:meth:`corliss.engine.network.Network.stops`).
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    rtol : float
        Relative tolerance [-].
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n_state,).
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    color : ndarray of int64
        The colour of each dynamic column
        (:meth:`corliss.engine.network.Network.column_colors`).
    owner : ndarray of int64
        Which column of each colour moves each row; shape (colours, n_state).
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.
    jac_age : int
        Accepted steps a Jacobian serves (:data:`JACOBIAN_AGE`); it is computed
        afresh at every segment's start and after a step rejected on a Jacobian
        older than the step.
    gam : float
        The method's diagonal gamma [-] (ode23s: 1 / (2 + sqrt 2)).
    tA, tC : ndarray
        The tableau's stage coefficients a_ij and c_ij, shape (stages, stages), below
        the diagonal [-].
    tc, td, tb, te : ndarray
        Its stage angles c_i (fractions of the step), the coefficients d_i of the time
        derivative, the weights b_i of the solution and e_i of the error [-]; shape
        (stages,) (ode23s: 4 stages' scratch).
    same : ndarray of int64
        Per stage: 0 evaluate, 1 its argument is the step's start, 2 the stage
        before's; shape (stages,).
    expo : float
        The exponent of the step's ratio to its error, ``-1/(order + 1)`` of the
        error estimate [-].
    kind : int
        :data:`KIND_ODE23S` or :data:`KIND_TABLEAU`.  The step loop takes it as
        ``pair``, True or None: numba prunes the branches of the other kind from a
        version compiled for None (``pair is None`` is known when it types the
        function), so a run compiles only its own kind's stages; likewise whether the
        network's Jacobian is analytic or by finite differences (``finite``, None or
        True).  With both, a first cycle of the ``standard`` preset compiled in 11.7 s
        instead of 16.7 s.

    Returns
    -------
    y_end : ndarray
        The state at ``stops[-1]``; shape (n_state,).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n_state, outputs).
    nfev : int
        Right-hand-side evaluations spent.
    ok : bool
        False when the step size collapsed, the state went non-finite or more than
        ``max_rhs`` evaluations were spent.
    clamps : ndarray
        Evaluations that clamped a state, shape (6,), indexed by ``CL_*``: at visited
        states (the ends of accepted steps) and at trial states (stages, probes,
        rejected steps) apart.
    """
    n = y0.shape[0]
    ndyn = color.shape[0]
    y = y0.copy()
    samples = np.full((n, out_theta.shape[0]), np.nan)
    vec = np.empty((9, n))
    U = np.empty((tb.shape[0], n))
    J = np.zeros((n, ndyn))
    mats = np.empty((2, ndyn, ndyn))
    dl = np.empty(ndyn)
    pr = np.empty((PR_ROWS, net[4].shape[0]))
    jd = np.empty((max(12, PR_ROWS), net[4].shape[0]))   # also holds pr's rows (starting_step)
    cyl = np.empty((2, net[17].shape[0], 4))
    clamps = np.zeros(6)
    clamps[CL_NODE] = -1.0
    tally = np.zeros((2, 4))
    nfev, ok = _ros_steps(y, samples, stops, out_theta, rtol, atol, net, tier, tab, perf,
                          color, owner, max_rhs, jac_age, gam, tA, tC, tc, td, tb, te, same,
                          expo, True if kind == KIND_ODE23S else None,
                          None if _exact_jacobian_holds.py_func(net) else True, vec, U, J,
                          mats, dl, pr, jd, cyl, clamps, tally)
    return y, samples, nfev, ok, clamps


@njit(cache=True, _nrt=False)
def _ros_steps(y, samples, stops, out_theta, rtol, atol, net, tier, tab, perf, color, owner,
               max_rhs, jac_age, gam, tA, tC, tc, td, tb, te, same, expo, pair, finite, vec,
               U, J, mats, dl, pr, jd, cyl, clamps, tally):
    """:func:`cycle_ros`'s steps, on scratch it allocated (no reference counts:
    the views of the scratch taken here cost nothing).  ``y`` is advanced to the
    cycle's end, ``samples`` and ``clamps`` written; returns the evaluations spent
    and whether the cycle ended well.  ``pair``: True for the ode23s pair, None for a
    tableau's method; ``finite``: True for a network whose Jacobian is taken by finite
    differences (:func:`_exact_jacobian_holds` false), None for the analytic one.  Each
    is a separate compiled version without the other's code."""
    n = y.shape[0]
    ns = tb.shape[0]
    safety = 0.9
    # the ode23s pair's steps by Gustafsson's predictive controller, no growth on the
    # step after a rejection (:func:`predictive_factor`); a tableau's by the error alone
    predictive = pair is not None
    f0, f1, ytmp, tmp, T, x, yscale, yp, fp = (vec[0], vec[1], vec[2], vec[3], vec[4],
                                               vec[5], vec[6], vec[7], vec[8])
    for i in range(n):
        yscale[i] = atol[i] / rtol
    Winv, A = mats[0], mats[1]
    slope, cell = cyl[0], cyl[1]
    att, att_end = tally[0], tally[1]
    nfev = 0
    io = 0
    while io < out_theta.shape[0] and out_theta[io] <= stops[0]:
        put_column(samples, io, y)
        io += 1
    h_prev = 0.0
    h_acc = 0.0            # the last accepted step, and its error (at least 0.01)
    err_acc = 0.0
    rejected = False       # the last step tried was rejected
    t_end = -1.0           # the angle of the last accepted step's end, f0 evaluated there
    for seg in range(stops.shape[0] - 1):
        a = stops[seg]
        b = stops[seg + 1]
        if b - a <= 0.0:
            continue
        t = a
        if not (predictive and t_end == a):
            # (the ode23s pair's last step ended on this stop: f0 is the derivative at
            # this angle and state, evaluated and its clamps settled as a visited
            # state's; the area's kink changes the derivative's slope, not its value)
            segment_start(t, y, f0, net, tier, tab, perf, pr, cell, clamps, att)
            nfev += 1
        if h_prev > 0.0:
            h = min(h_prev, b - a)
        elif predictive:
            h = starting_step(t, y, f0, atol, rtol, b - a, expo, net, tier, tab, perf, pr,
                              cell, att, yp, fp, jd)
            nfev += 1
        else:
            h = initial_step(f0, y, atol, rtol, b - a)
        age = jac_age          # accepted steps since J and T were computed
        h_w = -1.0             # the step W was inverted for
        while t < b:
            if t + h > b or b - (t + h) < 1e-12:
                h = b - t
            if age >= jac_age:
                if finite is None:
                    # called from here, not through :func:`_jacobian`: through it, a call
                    # cost 2.2 us against 0.7 us (the default scene; numba's handling of a
                    # function that passes the network and table tuples on, it seems)
                    _jacobian_exact(t, y, J, T, net, tier, tab, perf, pr, cell, jd, slope)
                else:
                    nfev += _jacobian(t, y, f0, J, T, yscale, color, owner, net, tier, tab,
                                      perf, pr, cell, att, yp, fp, dl, jd, slope)
                age = 0
                h_w = -1.0
            hd = h * gam
            if h != h_w:
                _w_inverse(J, hd, Winv, A)
                h_w = h
            if pair is not None:
                # Shampine and Reichelt's formulas, k_i in U[i]; the end's derivative
                # is the third stage's argument
                for i in range(n):
                    x[i] = f0[i] + hd * T[i]
                _w_solve(J, Winv, hd, x, U[0])
                for i in range(n):
                    ytmp[i] = y[i] + 0.5 * h * U[0, i]
                rhs(t + 0.5 * h, ytmp, U[1], net, tier, tab, perf, pr, cell)
                tally_clamps(pr, t + 0.5 * h, att)
                for i in range(n):
                    x[i] = U[1, i] - U[0, i]
                _w_solve(J, Winv, hd, x, U[2])
                for i in range(n):
                    U[2, i] += U[0, i]
                    ytmp[i] = y[i] + h * U[2, i]
                rhs(t + h, ytmp, f1, net, tier, tab, perf, pr, cell)
                tally_clamps(pr, t + h, att_end)
                nfev += 2
                for i in range(n):
                    x[i] = (f1[i] - _E32 * (U[2, i] - U[1, i]) - 2.0 * (U[0, i] - f0[i])
                            + hd * T[i])
                _w_solve(J, Winv, hd, x, U[3])
                err = 0.0
                for i in range(n):
                    e = abs(h / 6.0 * (U[0, i] - 2.0 * U[2, i] + U[3, i]))
                    e /= atol[i] + rtol * max(abs(y[i]), abs(ytmp[i]))
                    if e > err:
                        err = e
                accepted = (err <= 1.0 and visited_clamp_off(att_end) == 0) or h < 1e-12
            else:
                # u_i = hd W^-1 (...), W = I - hd J: the stages of I/(gamma h) - J
                for st in range(ns):
                    if st == 0 or same[st] == 1:
                        copy_into(fp, f0)
                    elif same[st] == 0:
                        tableau_argument(y, U, tA, st, ytmp)
                        rhs(t + tc[st] * h, ytmp, fp, net, tier, tab, perf, pr, cell)
                        tally_clamps(pr, t + tc[st] * h, att)
                        nfev += 1
                    tableau_stage_rhs(fp, T, U, tC, td, st, h, x)
                    _w_solve(J, Winv, hd, x, U[st])
                    for i in range(n):
                        U[st, i] *= hd
                err = tableau_solution(y, U, tb, te, atol, rtol, ytmp)
                accepted = err <= 1.0 or h < 1e-12
                if accepted:
                    rhs(t + h, ytmp, f1, net, tier, tab, perf, pr, cell)
                    tally_clamps(pr, t + h, att_end)
                    nfev += 1
                    # a step whose end needed the properties clamped is retried shorter
                    accepted = visited_clamp_off(att_end) == 0 or h < 1e-12
            settle_trial(att, clamps)
            settle_clamps(att_end, accepted, clamps)
            if accepted:
                t1 = t + h
                io = emit_samples(io, out_theta, t, y, f0, t1, ytmp, f1, samples, tmp)
                t = t1
                t_end = t1
                copy_into(y, ytmp)
                copy_into(f0, f1)
                age += 1
                if predictive:
                    fac = predictive_factor(err, h, err_acc, h_acc, safety, expo)
                    if rejected:
                        fac = min(fac, 1.0)
                    h_acc = h
                    err_acc = max(err, 1e-2)
                else:
                    fac = step_factor(err, safety, expo)
                rejected = False
                h_prev = h * fac
                h = h_prev
            else:
                rejected = True
                if age > 0:
                    age = jac_age    # rejected on an old Jacobian: a fresh one
                if err <= 1.0:
                    h = 0.5 * h  # accurate, but through a state the properties do not hold
                else:
                    h = h * max(0.2, safety * err ** expo)
            if not (h > 0.0) or not math.isfinite(y[0]) or nfev > max_rhs:
                return nfev, False
    while io < out_theta.shape[0]:
        put_column(samples, io, y)
        io += 1
    return nfev, True


#: Accepted steps of the Rosenbrock methods one Jacobian serves (1: a fresh one every
#: step; the retry of a rejected step reuses the one of its start, which is the same).
#: Serving 2 or 4 steps cost more evaluations than it saved on the default card (more
#: and shorter steps), at ``fast``'s tolerance and at ``standard``'s.
JACOBIAN_AGE = 1

#: The tableau methods of :func:`cycle_ros`, by code from 3.
ROS_METHODS = ("ros4", "rodas3", "rodas4")
#: Every method :func:`cycle_ros` integrates (on :func:`_jacobian`).
ROSENBROCK_METHODS = ("rosenbrock",) + ROS_METHODS
#: :func:`cycle_ros`'s tableau arguments for the ode23s pair: its gamma and four
#: stages' scratch (its stages are its own formulas), its safety and exponent.
_ODE23S_ARGS = (_D, np.zeros((4, 4)), np.zeros((4, 4)), np.zeros(4), np.zeros(4),
                np.zeros(4), np.zeros(4), np.zeros(4, dtype=np.int64), -1.0 / 3.0)
#: The compiled integrators by code (0 dopri5, 1 rk4, 2 Rosenbrock ode23s, 3 and on
#: the tableaus of :data:`ROS_METHODS`): separate functions, so that a run compiles
#: only the one it uses; one, :func:`_ros_steps` (called by :func:`cycle_ros`), for
#: every Rosenbrock method.
CYCLE_KERNELS = (_dopri5_steps, cycle_rk4, _ros_steps, _ros_steps, _ros_steps, _ros_steps)
#: The position of :func:`_ros_steps`'s ``pair`` among its arguments, and the type it
#: takes by code (True: boolean for the ode23s pair; None for the tableaus): numba
#: compiles and caches one version for each (:func:`cycle_kernel_uncached`).
ROS_PAIR_ARG = 23
#: The position of its ``finite`` (True: the Jacobian by finite differences; None: the
#: analytic one), also a version each.
ROS_FINITE_ARG = 24


def integrate_cycle(y0, stops, out_theta, method, rtol, atol, step, net, tier, tab, perf,
                    color, owner, max_rhs):
    """Integrate from ``stops[0]`` to ``stops[-1]``, restarting at every stop.

    Hands over to the compiled integrator of ``method`` (:data:`CYCLE_KERNELS`).

    Parameters
    ----------
    y0 : ndarray
        The state at ``stops[0]``; shape (n_state,).
    stops : ndarray
        Shaft angles [rad], increasing: the segments between them are integrated
        with a restart at each (:meth:`corliss.engine.network.Network.stops`).
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    method : int
        0 dopri5, 1 rk4, 2 Rosenbrock ode23s, 3 and on the Rosenbrock tableaus of
        :data:`ROS_METHODS` (``ros4``, ``rodas3``, ``rodas4``).
    rtol : float
        Relative tolerance [-] (the adaptive methods).
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n_state,).
    step : float
        The largest step of rk4 [rad].
    net : tuple
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    color : ndarray of int64
        The colour of each dynamic column (Rosenbrock;
        :meth:`corliss.engine.network.Network.column_colors`).
    owner : ndarray of int64
        Which column of each colour moves each row; shape (colours, n_state).
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.

    Returns
    -------
    y_end : ndarray
        The state at ``stops[-1]``; shape (n_state,).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n_state, outputs).
    nfev : int
        Right-hand-side evaluations spent.
    ok : bool
        False when the step size collapsed, the state went non-finite or more than
        ``max_rhs`` evaluations were spent.
    clamps : ndarray
        Evaluations that clamped a state, shape (6,), indexed by ``CL_*``: at visited
        states (the ends of accepted steps) and at trial states (stages, probes,
        rejected steps) apart.
    """
    if method == 0:
        return cycle_dopri5(y0, stops, out_theta, rtol, atol, net, tier, tab, perf, max_rhs)
    if method == 1:
        return cycle_rk4(y0, stops, out_theta, step, net, tier, tab, perf, max_rhs)
    if method >= 3:
        tableau, kind = ROS_TABLEAUS[ROS_METHODS[method - 3]], KIND_TABLEAU
    else:
        tableau, kind = _ODE23S_ARGS, KIND_ODE23S
    return cycle_ros(y0, stops, out_theta, rtol, atol, net, tier, tab, perf, color, owner,
                     max_rhs, JACOBIAN_AGE, *tableau, kind)


def uncached(dispatcher, nones: dict[int, bool] | None = None) -> bool | None:
    """Whether a compiled function's first call will compile it.

    Parameters
    ----------
    dispatcher : numba Dispatcher
        The compiled function (``@njit(cache=True)``).
    nones : dict of int to bool, optional
        For a function compiled in versions by whether arguments are None: each such
        argument's position, and whether the version wanted takes None there; only
        that version counts.

    Returns
    -------
    bool or None
        True when it is neither compiled in this process nor in numba's disk cache;
        None when this numba does not show its cache (internals this reads are gone).
    """
    def counts(sig) -> bool:
        return all((str(sig[k]) == "none") == v for k, v in (nones or {}).items())
    try:
        if any(counts(sig) for sig in dispatcher.signatures):
            return False
        cache_file = dispatcher._cache._cache_file
        if not os.path.exists(cache_file._index_path):
            return True
        if not nones:
            return False
        return not any(counts(key[0]) for key in cache_file._load_index())
    except (AttributeError, IndexError, TypeError):
        return None


def cycle_kernel_uncached(code: int, exact: bool = True) -> bool | None:
    """:func:`uncached` of the compiled cycle integrator of a method code, in the
    version that method runs on the network (:data:`ROS_PAIR_ARG`,
    :data:`ROS_FINITE_ARG`).

    Parameters
    ----------
    code : int
        The method's code (:data:`CYCLE_KERNELS`).
    exact : bool
        Whether the network's Jacobian is analytic (:func:`exact_jacobian_covers`).

    Returns
    -------
    bool or None
        As :func:`uncached`.
    """
    dispatcher = CYCLE_KERNELS[code]
    if dispatcher is _ros_steps:
        return uncached(dispatcher, {ROS_PAIR_ARG: code != 2, ROS_FINITE_ARG: exact})
    return uncached(dispatcher)


def announce_compile(*dispatchers, cycle: int | None = None, exact: bool = True) -> None:
    """Say so before compiled functions not yet in numba's disk cache are first called.

    The first run on a machine spends some seconds compiling them; a NOTICE names the
    functions to be compiled (nothing when all are cached, or this numba does not show
    its cache).

    Parameters
    ----------
    *dispatchers : numba Dispatcher
        The compiled functions about to be called.
    cycle : int, optional
        A method's code (:data:`CYCLE_KERNELS`) whose cycle integrator is about to be
        called, in that method's version (:func:`cycle_kernel_uncached`).
    exact : bool
        With ``cycle``: whether the network's Jacobian is analytic.
    """
    state = [uncached(d) for d in dispatchers]
    if cycle is not None:
        dispatchers = dispatchers + (CYCLE_KERNELS[cycle],)
        state.append(cycle_kernel_uncached(cycle, exact))
    if None in state:          # a numba without these internals: say nothing
        return
    missing = [d.__name__ for d, m in zip(dispatchers, state) if m]
    if missing:
        log.log(NOTICE, "compiling the kernels once for this machine (%s; 10 to 15 s); "
                "later runs load them from the cache", ", ".join(missing))
