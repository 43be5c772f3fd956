"""The kernels' data, by name: the network's arrays and the governed loop's tables.

Numba compiles a :class:`typing.NamedTuple` as a heterogeneous tuple whose fields it
reads by name at no cost (attribute access compiles to the same code as an index), and
caches functions taking one like any tuple.  The classes live here, at module level,
so a second process finds the same types in numba's cache.  Outside this module a
kernel tuple is read by name only (``tests/test_kernel_data.py`` holds it).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


#: Columns of :attr:`NetworkArrays.geometry`, per cylinder: crank radius, connecting
#: rod and stroke [m], head and crank piston areas [m2], head and crank clearances
#: [m3], rod angularity (1.0 or 0.0).
GEO_CRANK, GEO_ROD, GEO_STROKE, GEO_AREA_HEAD, GEO_AREA_CRANK = 0, 1, 2, 3, 4
GEO_CLEAR_HEAD, GEO_CLEAR_CRANK, GEO_ANGULARITY = 5, 6, 7

#: The wall-heat models' codes, column :data:`H_MODEL` of a node's wall-heat row
#: (:attr:`NetworkArrays.heat`; floats, as the row is): no wall heat, Marks's constant
#: as a conductance, Adair's correlation, Marks's law of condensation, the skin model
#: (:func:`corliss.engine.network.with_wall_heat`).
WALL_NONE, WALL_CONDUCTANCE, WALL_ADAIR, WALL_MARKS, WALL_SKIN = 0.0, 1.0, 2.0, 3.0, 4.0

#: Columns of a node's wall-heat row; their meaning after the model code's depends on
#: the model.  Every model: the code.
H_MODEL = 0
#: Conductance and Adair (and the skin's convection): Marks's constant as a conductance
#: [W/(m2 K)] (the skin model: its coefficient of condensation and evaporation), the
#: supply steam's conductivity [W/(m K)], viscosity [Pa s] and Prandtl number [-].
H_CONDUCTANCE, H_K, H_MU, H_PRANDTL = 1, 2, 3, 4
#: Marks's law, as :func:`corliss.engine.condensation.marks_law_rows` writes them: the
#: heat of a cycle, the admission, cut-off and compression angles [rad], the wall
#: exposed over admission and over cut-off to compression, integrated in crank angle.
H_MARKS_Q, H_MARKS_ADMIT, H_MARKS_CUTOFF, H_MARKS_COMPRESS = 5, 6, 7, 8
H_MARKS_WALL_ADMIT, H_MARKS_WALL_EXPAND = 9, 10
#: The skin model (:mod:`corliss.engine.wall`): the surface node's capacity
#: [J/(m2 K)] and conductance to the deep wall [W/(m2 K)], its mean area [m2], the
#: index of its first state, the jacket's conductance [W/K] and temperature [K], and
#: the reference the heat into the steam counts the film's water from, saturated water
#: at the mean of supply and exhaust temperatures, with the latent heat there [J/kg]
#: (the film itself is water at the surface's temperature,
#: :func:`corliss.engine.kernels.walls.film_water`); and the superheat of the steam
#: supplied [K] (0 when saturated or wet).
H_SKIN_CAPACITY, H_SKIN_DEEP, H_SKIN_AREA, H_SKIN_STATE = 5, 6, 7, 8
H_SKIN_JACKET_G, H_SKIN_JACKET_T, H_SKIN_FILM_H, H_SKIN_LATENT = 9, 10, 11, 12
H_SKIN_SUPPLY_SUPERHEAT = 13
#: Columns of the row.
HEAT_COLUMNS = 14

#: Rows of :attr:`LoopArrays.trip` (a trip gear's tables, over the settings): the
#: setting grid [-]; the head end's release angle per setting [rad] (nan: none), the
#: crank end's the row after; the head end's latched opening area at release [m2], the
#: crank end's after; the dash-pot's closing fraction over a uniform grid of time from 0
#: to the closing time [-]; the scalars (columns ``TS_*``).
TRIP_GRID, TRIP_RELEASE, TRIP_AREA, TRIP_CLOSING, TRIP_SCALARS = 0, 1, 3, 5, 6
#: Columns of the trip's scalars row: the closing time [s]; the head end's latched
#: closing angle [rad], the crank end's after; the head end's latched opening angle
#: [rad], the crank end's after; the number of settings; the closing table's points.
TS_CLOSE_TIME, TS_CLOSE_ANGLE, TS_OPEN_ANGLE, TS_N_SETTINGS, TS_N_CLOSING = 0, 1, 3, 5, 6


class NetworkArrays(NamedTuple):
    """The network as plain arrays (:meth:`corliss.engine.network.Network.arrays`).

    Fields are arrays of float64 unless said; per cylinder ``c``, node ``i``, edge
    ``e``, reservoir ``r``.

    Parameters
    ----------
    omega : ndarray
        The speed [rad/s], shape (1,), written by the loop.
    band : float
        The port flow's regularisation band [-].
    geometry : ndarray
        (cylinders, 8): GEO_* columns (kernels.mechanism).
    phase : ndarray
        (cylinders,) crank phase [rad].
    node_kind : ndarray
        (nodes,) int64: node kind (cylinder end, vessel).
    node_cyl : ndarray
        (nodes,) int64: its cylinder.
    node_end : ndarray
        (nodes,) int64: its end (0 head, 1 crank).
    node_V : ndarray
        (nodes,) a vessel's volume [m3].
    reservoirs : ndarray
        (reservoirs, 4): p [Pa], rho [kg/m3], h [J/kg], kappa [-].
    edge_a : ndarray
        (edges,) int64: end a (node, or -1 - reservoir).
    edge_b : ndarray
        (edges,) int64: end b.
    edge_kind : ndarray
        (edges,) int64: edge kind.
    edge_cyl : ndarray
        (edges,) int64: its cylinder (port edges).
    edge_port : ndarray
        (edges,) int64: its port (port edges).
    edge_area : ndarray
        (edges,) fixed area [m2] (the throttle's, written by the loop).
    edge_cd : ndarray
        (edges,) discharge coefficient [-].
    port_grid : ndarray
        (cylinders, points): the PortMaps' angle grids [rad].
    port_npts : ndarray
        (cylinders,) int64: their lengths.
    port_area : ndarray
        (cylinders, 4, points): their areas [m2].
    heat : ndarray
        (nodes, HEAT_COLUMNS): the wall-heat rows.
    wall_T : ndarray
        (nodes,) wall temperature [K].
    """

    omega: np.ndarray
    band: float
    geometry: np.ndarray
    phase: np.ndarray
    node_kind: np.ndarray
    node_cyl: np.ndarray
    node_end: np.ndarray
    node_V: np.ndarray
    reservoirs: np.ndarray
    edge_a: np.ndarray
    edge_b: np.ndarray
    edge_kind: np.ndarray
    edge_cyl: np.ndarray
    edge_port: np.ndarray
    edge_area: np.ndarray
    edge_cd: np.ndarray
    port_grid: np.ndarray
    port_npts: np.ndarray
    port_area: np.ndarray
    heat: np.ndarray
    wall_T: np.ndarray


class LoopArrays(NamedTuple):
    """The governed loop's tables (:attr:`corliss.engine.transient.LoopTables.tr`).

    Parameters
    ----------
    sc : ndarray
        The scalars, indices S_* (kernels.loop).
    load_t : ndarray
        The load's times [s].
    load_f : ndarray
        The load's fractions [-].
    setting_grid : ndarray
        The settings tabulated [-].
    area_s : ndarray
        Port areas over (cylinder, port, setting, crank angle) [m2].
    governed : ndarray
        (cylinders,) int64: 1 where the governor moves the gear.
    gov : ndarray
        The governor's M, M', G, R, J on a uniform z grid.
    trip : ndarray
        The trip gear's tables, rows TRIP_* (kernels.loop).
    throttle : ndarray
        The throttle's area over a uniform grid of opening [m2].
    """

    sc: np.ndarray
    load_t: np.ndarray
    load_f: np.ndarray
    setting_grid: np.ndarray
    area_s: np.ndarray
    governed: np.ndarray
    gov: np.ndarray
    trip: np.ndarray
    throttle: np.ndarray


class Physics(NamedTuple):
    """What the right-hand side needs besides the state: the network and the steam's
    compiled properties (the quadruple ``net, tier, tab, perf`` of the kernels).

    Parameters
    ----------
    net : NetworkArrays
        
    tier : int
        The property tier: TIER_TABLE or TIER_PERFECT (kernels.properties).
    tab : TableArrays
        The steam table's arrays (corliss.thermo.steam_table.TableArrays).
    perf : ndarray
        The perfect tier's R, cv [J/(kg K)], u_ref [J/kg]; PERF_* (kernels.properties).
    """

    net: NetworkArrays
    tier: int
    tab: tuple
    perf: np.ndarray


class StepControl(NamedTuple):
    """A steady cycle's step control.

    Parameters
    ----------
    rtol : float
        Relative tolerance [-].
    atol : ndarray
        Absolute tolerances, in each component's unit.
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.
    jac_age : int
        Accepted steps a Jacobian serves (Rosenbrock methods; 0 else).
    """

    rtol: float
    atol: np.ndarray
    max_rhs: int
    jac_age: int


class Tableau(NamedTuple):
    """A Rosenbrock method's tableau (:data:`corliss.engine.kernels.tableaus.ROS_TABLEAUS`).

    Parameters
    ----------
    gamma : float
        The diagonal gamma [-].
    A : ndarray
        Stage coefficients a_ij, (stages, stages) [-].
    C : ndarray
        Stage coefficients c_ij, (stages, stages) [-].
    c : ndarray
        Stage angles, fractions of the step [-].
    d : ndarray
        Coefficients of the time derivative [-].
    b : ndarray
        Weights of the solution [-].
    e : ndarray
        Weights of the error [-].
    same : ndarray
        Int64 per stage: 0 evaluate, 1 the step's start, 2 the stage before's.
    expo : float
        Exponent of the step's ratio to its error [-].
    """

    gamma: float
    A: np.ndarray
    C: np.ndarray
    c: np.ndarray
    d: np.ndarray
    b: np.ndarray
    e: np.ndarray
    same: np.ndarray
    expo: float


class StepScratch(NamedTuple):
    """Scratch of the Rosenbrock step loop's starting step and Jacobian.

    Parameters
    ----------
    pr : ndarray
        Node properties (PR_ROWS, nodes).
    cell : ndarray
        Port areas (cylinders, 4) [m2].
    att : ndarray
        A trial's clamp tally (4,).
    yp : ndarray
        A probe state (n,).
    fp : ndarray
        Its derivative (n,).
    dl : ndarray
        The dynamic columns' increments (ndyn,).
    jd : ndarray
        The analytic Jacobian's rows, also a copy of pr's.
    slope : ndarray
        Port areas' slopes in crank angle (cylinders, 4) [m2/rad].
    """

    pr: np.ndarray
    cell: np.ndarray
    att: np.ndarray
    yp: np.ndarray
    fp: np.ndarray
    dl: np.ndarray
    jd: np.ndarray
    slope: np.ndarray


class RosScratch(NamedTuple):
    """Scratch of the Rosenbrock step loop, allocated by its caller.

    Parameters
    ----------
    vec : ndarray
        Ten state vectors (10, n): derivatives at a step's start and end, a stage's
        argument, the output's scratch, the time derivative, a solve's right-hand
        side, the tolerances' scale, a probe state and its derivative, a solve's
        columns (the loop's W).
    U : ndarray
        The stages (stages, n).
    J : ndarray
        The Jacobian (n, m): the ndyn dynamic columns, and the loop's three in a turn.
    mats : ndarray
        W's inverse and its factor (2, m, m).
    dl : ndarray
        (ndyn,).
    pr : ndarray
        Node properties (PR_ROWS, nodes).
    jd : ndarray
        (max(12, PR_ROWS), nodes).
    cyl : ndarray
        Port-area slopes and areas (2, cylinders, 4).
    clamps : ndarray
        The clamp counts (6,), CL_* (kernels.clamps).
    tally : ndarray
        A trial's and a step end's clamp tally (2, 4).
    """

    vec: np.ndarray
    U: np.ndarray
    J: np.ndarray
    mats: np.ndarray
    dl: np.ndarray
    pr: np.ndarray
    jd: np.ndarray
    cyl: np.ndarray
    clamps: np.ndarray
    tally: np.ndarray


class DopriScratch(NamedTuple):
    """Scratch of the Dormand-Prince step loop, allocated by its caller.

    Parameters
    ----------
    vec : ndarray
        Three state vectors (3, n): the derivative at the step's start, a stage's
        argument, the output's scratch.
    K : ndarray
        The stages' derivatives (7, n).
    pr : ndarray
        Node properties (PR_ROWS, nodes).
    cell : ndarray
        Port areas (cylinders, 4) [m2].
    clamps : ndarray
        The clamp counts (6,), CL_* (kernels.clamps).
    tally : ndarray
        A trial's and a step end's clamp tally (2, 4).
    """

    vec: np.ndarray
    K: np.ndarray
    pr: np.ndarray
    cell: np.ndarray
    clamps: np.ndarray
    tally: np.ndarray


class LoopTurn(NamedTuple):
    """What a turn of the governed loop adds to a step loop: its tables, its record and
    its scratch.  Passed to the step loops of a steady cycle as None.

    Parameters
    ----------
    tr : LoopArrays
        The loop's tables; the clamp counts and the Rosenbrock loop's next step
        written into ``tr.sc``.
    out : ndarray
        (2, 4): the loop's outputs (indicated and load torques [N m], actuator [-],
        domega/dt [rad/s2]) of the evaluation at a step's end (row 0, the one recorded)
        and of a stage's (row 1).
    rec : ndarray
        (N_REC, columns): per accepted step, rows as kernels.loop._record writes them.
    record : bool
        Whether to record every accepted step.
    t_end : float
        The run's end time [s].
    tq : ndarray
        (3, nodes): each node's share of the indicated torque [N m] at a step's start,
        at its end, and their change in a column of the Jacobian.
    """

    tr: LoopArrays
    out: np.ndarray
    rec: np.ndarray
    record: bool
    t_end: float
    tq: np.ndarray


class Columns(NamedTuple):
    """The Jacobian's dynamic columns in groups whose rows do not overlap, perturbed
    together by the finite differences (:meth:`corliss.engine.network.Network.column_colors`).

    Parameters
    ----------
    color : ndarray
        Int64 (ndyn,): the colour of each dynamic column.
    owner : ndarray
        Int64 (colours, rows): which column of each colour moves each row (-1: none).
    """

    color: np.ndarray
    owner: np.ndarray
