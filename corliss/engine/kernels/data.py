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


class NetworkArrays(NamedTuple):
    """The network as plain arrays (:meth:`corliss.engine.network.Network.arrays`).

    Fields are arrays of float64 unless said; per cylinder ``c``, node ``i``, edge
    ``e``, reservoir ``r``.
    """

    omega: np.ndarray       # [omega] [rad/s], shape (1,): the speed, written by the loop
    band: float             # the port flow's regularisation band [-]
    geometry: np.ndarray    # (cylinders, 8): GEO_* columns (kernels.mechanism)
    phase: np.ndarray       # (cylinders,) crank phase [rad]
    node_kind: np.ndarray   # (nodes,) int64: node kind (cylinder end, vessel)
    node_cyl: np.ndarray    # (nodes,) int64: its cylinder
    node_end: np.ndarray    # (nodes,) int64: its end (0 head, 1 crank)
    node_V: np.ndarray      # (nodes,) a vessel's volume [m3]
    reservoirs: np.ndarray  # (reservoirs, 4): p [Pa], rho [kg/m3], h [J/kg], kappa [-]
    edge_a: np.ndarray      # (edges,) int64: end a (node, or -1 - reservoir)
    edge_b: np.ndarray      # (edges,) int64: end b
    edge_kind: np.ndarray   # (edges,) int64: edge kind
    edge_cyl: np.ndarray    # (edges,) int64: its cylinder (port edges)
    edge_port: np.ndarray   # (edges,) int64: its port (port edges)
    edge_area: np.ndarray   # (edges,) fixed area [m2] (the throttle's, written by the loop)
    edge_cd: np.ndarray     # (edges,) discharge coefficient [-]
    port_grid: np.ndarray   # (cylinders, points): the PortMaps' angle grids [rad]
    port_npts: np.ndarray   # (cylinders,) int64: their lengths
    port_area: np.ndarray   # (cylinders, 4, points): their areas [m2]
    heat: np.ndarray        # (nodes, HEAT_COLUMNS): the wall-heat rows
    wall_T: np.ndarray      # (nodes,) wall temperature [K]


class LoopArrays(NamedTuple):
    """The governed loop's tables (:attr:`corliss.engine.transient.LoopTables.tr`)."""

    sc: np.ndarray          # the scalars, indices S_* (kernels.loop)
    load_t: np.ndarray      # the load's times [s]
    load_f: np.ndarray      # the load's fractions [-]
    setting_grid: np.ndarray  # the settings tabulated [-]
    area_s: np.ndarray      # port areas over (cylinder, port, setting, crank angle) [m2]
    governed: np.ndarray    # (cylinders,) int64: 1 where the governor moves the gear
    gov: np.ndarray         # the governor's M, M', G, R, J on a uniform z grid
    trip: np.ndarray        # the trip gear's tables, rows TRIP_* (kernels.loop)
    throttle: np.ndarray    # the throttle's area over a uniform grid of opening [m2]


class Physics(NamedTuple):
    """What the right-hand side needs besides the state: the network and the steam's
    compiled properties (the quadruple ``net, tier, tab, perf`` of the kernels)."""

    net: NetworkArrays
    tier: int               # the property tier: TIER_TABLE or TIER_PERFECT (kernels.properties)
    tab: tuple              # the steam table's arrays (corliss.thermo.steam_table.TableArrays)
    perf: np.ndarray        # the perfect tier's R, cv [J/(kg K)], u_ref [J/kg]; PERF_* (kernels.properties)


class StepControl(NamedTuple):
    """A steady cycle's step control."""

    rtol: float             # relative tolerance [-]
    atol: np.ndarray        # absolute tolerances, in each component's unit
    max_rhs: int            # the run-time budget: most right-hand-side evaluations
    jac_age: int            # accepted steps a Jacobian serves (Rosenbrock methods; 0 else)


class Tableau(NamedTuple):
    """A Rosenbrock method's tableau (:data:`corliss.engine.kernels.tableaus.ROS_TABLEAUS`)."""

    gamma: float            # the diagonal gamma [-]
    A: np.ndarray           # stage coefficients a_ij, (stages, stages) [-]
    C: np.ndarray           # stage coefficients c_ij, (stages, stages) [-]
    c: np.ndarray           # stage angles, fractions of the step [-]
    d: np.ndarray           # coefficients of the time derivative [-]
    b: np.ndarray           # weights of the solution [-]
    e: np.ndarray           # weights of the error [-]
    same: np.ndarray        # int64 per stage: 0 evaluate, 1 the step's start, 2 the stage before's
    expo: float             # exponent of the step's ratio to its error [-]


class StepScratch(NamedTuple):
    """Scratch of the Rosenbrock cycle's starting step and Jacobian."""

    pr: np.ndarray          # node properties (PR_ROWS, nodes)
    cell: np.ndarray        # port areas (cylinders, 4) [m2]
    att: np.ndarray         # a trial's clamp tally (4,)
    yp: np.ndarray          # a probe state (n,)
    fp: np.ndarray          # its derivative (n,)
    dl: np.ndarray          # the dynamic columns' increments (ndyn,)
    jd: np.ndarray          # the analytic Jacobian's rows, also a copy of pr's
    slope: np.ndarray       # port areas' slopes in crank angle (cylinders, 4) [m2/rad]


class RosScratch(NamedTuple):
    """Scratch of the Rosenbrock cycle's step loop, allocated by its caller."""

    vec: np.ndarray         # nine state vectors (9, n)
    U: np.ndarray           # the stages (stages, n)
    J: np.ndarray           # the Jacobian (n, ndyn)
    mats: np.ndarray        # W's inverse and its factor (2, ndyn, ndyn)
    dl: np.ndarray          # (ndyn,)
    pr: np.ndarray          # node properties (PR_ROWS, nodes)
    jd: np.ndarray          # (max(12, PR_ROWS), nodes)
    cyl: np.ndarray         # port-area slopes and areas (2, cylinders, 4)
    clamps: np.ndarray      # the clamp counts (6,), CL_* (kernels.clamps)
    tally: np.ndarray       # a trial's and a step end's clamp tally (2, 4)


class LoopScratch(NamedTuple):
    """Scratch of the governed loop's Jacobian."""

    pr: np.ndarray          # node properties (PR_ROWS, nodes)
    pa: np.ndarray          # port areas (cylinders, 4) [m2]
    out: np.ndarray         # the loop's outputs (4,)
    att: np.ndarray         # a trial's clamp tally (4,)
    yp: np.ndarray          # a probe state (n,)
    fp: np.ndarray          # its derivative (n,)
    dl: np.ndarray          # the columns' increments
    dtq: np.ndarray         # the nodes' torque change (nodes,)
