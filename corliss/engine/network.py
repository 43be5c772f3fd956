"""The crank-resolved model as a network: control volumes joined by ports.

Nodes are control volumes with a state (mass m, internal energy U): the two ends of
each cylinder (volume set by the crank) and, when the scene asks, vessels of fixed
volume (the steam chest).  Reservoirs hold a fixed state (the boiler, the exhaust).
Edges are orifices between two of them: a port of a cylinder, whose area comes from
that cylinder's PortMap at its own crank angle, or an opening of fixed area (the
steam pipe and throttle).  The equations for every node (first law for an open
system, constant crank speed omega, crank angle theta)::

    dm/dtheta = sum of mdot in / omega
    dU/dtheta = sum of mdot h in / omega - p dV/dtheta

with each edge's flow from :func:`corliss.thermo.orifice.port_flow`, carrying the
enthalpy of the side it leaves.  Quadratures ride along: mass and enthalpy through
every edge, and the work p dV of every node.

:class:`Network` holds the arrays the compiled kernel reads (:meth:`Network.arrays`)
and the bookkeeping that names them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from corliss.engine.kernels.data import (HEAT_COLUMNS, H_MODEL, WALL_ADAIR, WALL_CONDUCTANCE,
                                         WALL_MARKS, WALL_SKIN, NetworkArrays)
from corliss.engine.kernels.loop import turn_stops

PISTON, FIXED = 0, 1
#: Edge kinds: a cylinder's port (area from the PortMap), an orifice of fixed area, and
#: the period's linear leak (its ``area`` column the rate of leak [kg/(s Pa)],
#: :mod:`corliss.thermo.leak_law`).
PORTMAP_EDGE, FIXED_EDGE, LINEAR_EDGE = 0, 1, 2


def reservoir(r: int) -> int:
    """Edge end code of reservoir ``r``.

    An edge's ends are node indices (0 and up) or reservoir codes (negative).

    Parameters
    ----------
    r : int
        Index of the reservoir in :attr:`Network.reservoirs` (0 the supply, 1 the
        exhaust).

    Returns
    -------
    int
        ``-1 - r``.
    """
    return -1 - r


@dataclass
class Network:
    """Nodes, reservoirs and edges of one engine (all SI).

    Built empty of nodes and edges by the constructors below (:func:`single_cylinder`,
    :func:`compound`) and filled by :meth:`add_node`, :meth:`add_edge` and the effects
    (:func:`with_steam_chest`, :func:`with_leakage`, :func:`with_wall_heat`).  The
    per-node and per-edge lists are parallel, indexed by node or edge.

    Parameters
    ----------
    omega : float
        Shaft speed [rad/s].
    band : float
        The port flow's regularisation band [-] (:func:`corliss.thermo.orifice.port_flow`).
    geometries : list of CylinderGeometry
        Each cylinder's geometry.
    phases : list of float
        Each cylinder's crank angle less the shaft's [rad]: a cylinder's own angle is
        ``theta + phases[c]``.
    portmaps : list of PortMap
        Each cylinder's port areas against its own crank angle.
    reservoirs : list of State
        Fixed states: 0 the supply (boiler), 1 the exhaust.
    node_names : list of str
        Each node's name (``head``, ``crank``, ``lp_head``, ``chest``, ``receiver`` ...).
    node_kind : list of int
        :data:`PISTON` (a cylinder end) or :data:`FIXED` (a vessel).
    node_cyl, node_end : list of int
        A cylinder end's cylinder and end (0 head, 1 crank); -1 for a vessel.
    node_V : list of float
        A vessel's volume [m3] (0 for a cylinder end).
    node_init : list of State
        The state each node starts from.
    edge_names : list of str
        Each edge's name (``head_steam``, ``crank_exhaust``, ``steam_pipe`` ...).
    e_a, e_b : list of int
        Each edge's two ends: a node index, or a reservoir's code (:func:`reservoir`);
        flow from ``a`` to ``b`` is positive.
    e_kind : list of int
        :data:`PORTMAP_EDGE` (a cylinder's port), :data:`FIXED_EDGE` (an orifice) or
        :data:`LINEAR_EDGE` (a leak by the period's law, its area the rate of leak).
    e_cyl, e_port : list of int
        A port edge's cylinder and port (0 head steam, 1 head exhaust, 2 crank steam,
        3 crank exhaust); -1 for a fixed orifice.
    e_area : list of float
        A fixed orifice's area [m2].
    e_cd : list of float
        Each edge's discharge coefficient [-].
    node_heat : list of tuple
        Each node's wall-heat row, :data:`HEAT_COLUMNS` floats (see the field's
        comment and :func:`with_wall_heat`).
    wall_T : ndarray or None
        Each node's wall temperature [K], shape (nodes,) (for the skin model, the deep
        wall's under the skin); set to the mean of supply and exhaust temperatures by
        :meth:`arrays` when None or of another length.
    schedule_stops : list of float
        Shaft angles [rad] where a wall-heat schedule switches (Marks's or English's
        law, :class:`corliss.engine.condensation.ScheduledWallHeat`), stops of the
        integrators as the ports' kinks are (:meth:`stops`).
    edge_leaks : list of tuple
        The period law's leaks past a closed valve edge
        (:func:`with_period_leakage`): ``(edge, cylinder, port, rate)``, the rate of
        the reference valve [kg/(s Pa)] that the edge's scale multiplies
        (:func:`corliss.engine.leak_paths.edge_leak_scales`), so that a governed run can
        set the scale for the gear's setting turn by turn.
    """

    omega: float
    band: float
    geometries: list                      # CylinderGeometry per cylinder
    phases: list[float]                   # crank lead of each cylinder [rad]
    portmaps: list                        # PortMap per cylinder
    reservoirs: list                      # State per reservoir
    node_names: list[str] = field(default_factory=list)
    node_kind: list[int] = field(default_factory=list)
    node_cyl: list[int] = field(default_factory=list)
    node_end: list[int] = field(default_factory=list)
    node_V: list[float] = field(default_factory=list)
    node_init: list = field(default_factory=list)    # State each node starts from
    edge_names: list[str] = field(default_factory=list)
    e_a: list[int] = field(default_factory=list)
    e_b: list[int] = field(default_factory=list)
    e_kind: list[int] = field(default_factory=list)
    e_cyl: list[int] = field(default_factory=list)
    e_port: list[int] = field(default_factory=list)
    e_area: list[float] = field(default_factory=list)
    e_cd: list[float] = field(default_factory=list)
    #: Wall heat of each node: (model 0 none, 1 constant h, 2 Adair, 3 Marks's law, 4 skin;
    #: h [W/(m2 K)]; conductivity [W/(m K)]; viscosity [Pa s]; Prandtl [-]; then the
    #: model's own columns, see HEAT_COLUMNS), and the wall temperature [K] (for the skin
    #: model, the temperature of the deep wall under the skin).
    node_heat: list = field(default_factory=list)
    wall_T: np.ndarray | None = None
    #: so that no switch of a schedule falls inside a step
    schedule_stops: list[float] = field(default_factory=list)
    #: (edge, cylinder, port, reference rate [kg/(s Pa)]) of each valve edge's leak
    edge_leaks: list[tuple] = field(default_factory=list)

    # --- building -----------------------------------------------------------------
    def add_node(self, name, kind, init, cyl=-1, end=-1, volume=0.0) -> int:
        """Add a control volume, without wall heat.

        Parameters
        ----------
        name : str
            The node's name (unique; columns of the results are named after it).
        kind : int
            :data:`PISTON` or :data:`FIXED`.
        init : State
            The state it starts from.
        cyl, end : int
            A cylinder end's cylinder and end (0 head, 1 crank); -1 for a vessel.
        volume : float
            A vessel's volume [m3].

        Returns
        -------
        int
            The new node's index.
        """
        self.node_names.append(name)
        self.node_kind.append(kind)
        self.node_cyl.append(cyl)
        self.node_end.append(end)
        self.node_V.append(volume)
        self.node_init.append(init)
        self.node_heat.append((0.0,) * HEAT_COLUMNS)
        return len(self.node_names) - 1

    def add_edge(self, name, a, b, cd, kind=FIXED_EDGE, cyl=-1, port=-1, area=0.0) -> int:
        """Add an orifice between two nodes or a node and a reservoir.

        Parameters
        ----------
        name : str
            The edge's name (unique).
        a, b : int
            Its ends: node indices or reservoir codes (:func:`reservoir`); flow from
            ``a`` to ``b`` is positive.
        cd : float
            Discharge coefficient [-].
        kind : int
            :data:`FIXED_EDGE` (area ``area``), :data:`PORTMAP_EDGE` (port ``port``
            of cylinder ``cyl``) or :data:`LINEAR_EDGE` (``area`` the rate of leak
            [kg/(s Pa)]).
        cyl, port : int
            A port edge's cylinder and port (0 head steam, 1 head exhaust, 2 crank
            steam, 3 crank exhaust).
        area : float
            A fixed orifice's area [m2].

        Returns
        -------
        int
            The new edge's index.
        """
        self.edge_names.append(name)
        self.e_a.append(a)
        self.e_b.append(b)
        self.e_kind.append(kind)
        self.e_cyl.append(cyl)
        self.e_port.append(port)
        self.e_area.append(area)
        self.e_cd.append(cd)
        return len(self.edge_names) - 1

    # --- layout of the state vector -------------------------------------------------
    @property
    def n_nodes(self) -> int:
        """Number of nodes (control volumes)."""
        return len(self.node_names)

    @property
    def n_edges(self) -> int:
        """Number of edges (orifices)."""
        return len(self.edge_names)

    @property
    def n_dyn(self) -> int:
        """Number of dynamic states.

        Mass [kg] and internal energy [J] of each node, interleaved (``y[2 i]``,
        ``y[2 i + 1]``).
        """
        return 2 * self.n_nodes

    #: Quadratures of each node: work p dV, net heat into the steam, heat from the steam
    #: to the wall, and the integrals of h A and h A T (for the wall's mean temperature).
    NODE_QUADS = ("work", "heat", "heat_to_wall", "hA", "hAT")

    @property
    def n_quad_end(self) -> int:
        """One past the last quadrature: the wall states (skin model) follow."""
        return 2 * self.n_nodes + 2 * self.n_edges + len(self.NODE_QUADS) * self.n_nodes

    @property
    def wall_nodes(self) -> list[int]:
        """Nodes whose wall surface temperature is a state (the skin model), in order."""
        return [i for i, row in enumerate(self.node_heat) if row[H_MODEL] == WALL_SKIN]

    #: States of a skin-model wall: the surface temperature less the deep wall's [K],
    #: the water film [kg], and two quadratures restarted each cycle: the heat from the
    #: wall that goes down T_w - T_sat (condensing on it, boiling off it) and down
    #: T_w - T (convection) [J].
    WALL_STATES = ("surface", "film", "heat_sat", "heat_conv")

    @property
    def n_state(self) -> int:
        """Length of the state vector.

        The dynamic states, then mass [kg] and enthalpy [J] through each edge, then
        :data:`NODE_QUADS` of each node, then :data:`WALL_STATES` of each skin-model
        wall.
        """
        return self.n_quad_end + len(self.WALL_STATES) * len(self.wall_nodes)

    def i_wall(self, node: int, what: str = "surface") -> int:
        """Index in the state vector of one of a skin-model wall's states.

        Parameters
        ----------
        node : int
            A node in :attr:`wall_nodes`.
        what : str
            One of :data:`WALL_STATES`.

        Returns
        -------
        int
            The index.
        """
        return (self.n_quad_end + len(self.WALL_STATES) * self.wall_nodes.index(node)
                + self.WALL_STATES.index(what))

    def i_film(self, node: int) -> int:
        """Index in the state vector of the mass of the water film on a node's wall.

        Parameters
        ----------
        node : int
            A node in :attr:`wall_nodes`.

        Returns
        -------
        int
            The index of the film's mass [kg].
        """
        return self.i_wall(node, "film")

    def i_edge_mass(self, e: int) -> int:
        """Index in the state vector of the mass through an edge.

        Parameters
        ----------
        e : int
            The edge.

        Returns
        -------
        int
            The index of the mass that has flowed from its end ``a`` to ``b`` [kg].
        """
        return self.n_dyn + 2 * e

    def i_edge_enthalpy(self, e: int) -> int:
        """Index in the state vector of the enthalpy through an edge.

        Parameters
        ----------
        e : int
            The edge.

        Returns
        -------
        int
            The index of the enthalpy carried from its end ``a`` to ``b`` [J].
        """
        return self.n_dyn + 2 * e + 1

    def i_node_quad(self, node: int, what: str) -> int:
        """Index in the state vector of one of a node's quadratures.

        Parameters
        ----------
        node : int
            The node.
        what : str
            One of :data:`NODE_QUADS`: ``work`` (``p dV`` [J]), ``heat`` (into the steam
            [J]), ``heat_to_wall`` [J], ``hA`` [J/K] and ``hAT`` [J] (integrals over
            time of ``h A`` and ``h A T``).

        Returns
        -------
        int
            The index.
        """
        return (self.n_dyn + 2 * self.n_edges + len(self.NODE_QUADS) * node
                + self.NODE_QUADS.index(what))

    def i_work(self, node: int) -> int:
        """Index in the state vector of a node's work ``p dV`` [J].

        Parameters
        ----------
        node : int
            The node.

        Returns
        -------
        int
            The index.
        """
        return self.i_node_quad(node, "work")

    def node(self, name: str) -> int:
        """Index of a node by name.

        Parameters
        ----------
        name : str
            One of :attr:`node_names`.

        Returns
        -------
        int
            The node's index.

        Raises
        ------
        ValueError
            No node of that name.
        """
        return self.node_names.index(name)

    def edge(self, name: str) -> int:
        """Index of an edge by name.

        Parameters
        ----------
        name : str
            One of :attr:`edge_names`.

        Returns
        -------
        int
            The edge's index.

        Raises
        ------
        ValueError
            No edge of that name.
        """
        return self.edge_names.index(name)

    def boundary_terms(self) -> list[tuple[str, float, int]]:
        """The terms :meth:`boundary_totals` adds, for a runner to look up once a run.

        Returns
        -------
        list of (str, float, int)
            For each edge end at a reservoir, in edge order, its mass then its
            enthalpy: the total it adds to (``m_supply_kg``, ``H_supply_J``,
            ``m_exhaust_kg``, ``H_exhaust_J``), the sign [-] (+1 from the edge's end
            ``a``, -1 from its end ``b``) and the index in the state vector.
        """
        terms = []
        for e, (a, b) in enumerate(zip(self.e_a, self.e_b)):
            for end, sign in ((a, 1.0), (b, -1.0)):
                if end < 0:
                    what = "supply" if end == reservoir(0) else "exhaust"
                    terms.append((f"m_{what}_kg", sign, self.i_edge_mass(e)))
                    terms.append((f"H_{what}_J", sign, self.i_edge_enthalpy(e)))
        return terms

    def boundary_totals(self, y, terms: list[tuple[str, float, int]] | None = None) -> dict:
        """Mass and enthalpy into the engine over a cycle across its boundary.

        Parameters
        ----------
        y : ndarray or list of float
            The state at the end of a cycle whose quadratures started from zero; shape
            (:attr:`n_state`,).
        terms : list, optional
            :meth:`boundary_terms`, when the caller holds them (a steady run sums them
            every cycle); looked up here when not given.

        Returns
        -------
        dict of str to float
            ``m_supply_kg`` [kg] and ``H_supply_J`` [J] in from the supply (reservoir
            0); ``m_exhaust_kg`` [kg] and ``H_exhaust_J`` [J] in from the exhaust
            (reservoir 1; negative when, as usual, it goes out).
        """
        out = {"m_supply_kg": 0.0, "H_supply_J": 0.0, "m_exhaust_kg": 0.0, "H_exhaust_J": 0.0}
        for name, sign, k in (self.boundary_terms() if terms is None else terms):
            out[name] += sign * y[k]
        return out

    def leak_edges(self) -> list[tuple[str, int]]:
        """The leakage paths (edges whose name holds ``leak``).

        Returns
        -------
        list of (str, int)
            The name and index of each.
        """
        return [(n, e) for e, n in enumerate(self.edge_names) if "leak" in n]

    # --- volumes --------------------------------------------------------------------
    def volume(self, node: int, theta: np.ndarray) -> np.ndarray:
        """Volume of a node at shaft crank angles.

        Parameters
        ----------
        node : int
            The node.
        theta : ndarray
            Shaft crank angles [rad] (a cylinder's own angle leads by its phase).

        Returns
        -------
        ndarray
            The volume [m3], of ``theta``'s shape.
        """
        if self.node_kind[node] == FIXED:
            return np.full(np.shape(theta), self.node_V[node])
        c = self.node_cyl[node]
        return self.geometries[c].volumes_m3(np.asarray(theta) + self.phases[c])[self.node_end[node]]

    def initial_state(self) -> np.ndarray:
        """The state vector at crank angle 0: each node holding its initial state.

        Returns
        -------
        ndarray
            Shape (:attr:`n_state`,): mass [kg] and internal energy [J] of each node
            at its volume at 0 rad; quadratures and wall states zero.
        """
        y = np.zeros(self.n_state)
        for i, st in enumerate(self.node_init):
            V = float(self.volume(i, np.array(0.0)))
            y[2 * i] = V * st.rho
            y[2 * i + 1] = V * st.rho * st.u
        return y

    def stops(self, theta0: float) -> list[float]:
        """Crank angles over one turn where any port area has a kink.

        The integrators restart at each, so that no port opens inside a step.

        Parameters
        ----------
        theta0 : float
            The shaft angle the turn starts from [rad].

        Returns
        -------
        list of float
            Increasing shaft angles [rad] from ``theta0`` to ``theta0 + 2 pi``, both
            included, with every breakpoint of every cylinder's PortMap and every
            switch of a wall-heat schedule (:attr:`schedule_stops`) between, each
            switch :data:`~corliss.engine.kernels.balances.SWITCH_MARGIN_RAD` short of
            it (:func:`~corliss.engine.kernels.loop.turn_stops`).
        """
        two_pi = 2.0 * math.pi
        pts = []
        for pm, ph in zip(self.portmaps, self.phases):
            pts += [(b - ph) % two_pi for b in pm.breakpoints_rad]
        stops = sorted({theta0 + ((p - theta0) % two_pi) for p in pts})
        stops = [s for s in stops if 1e-9 < s - theta0 < two_pi - 1e-9]
        if self.schedule_stops:
            # each switch SWITCH_MARGIN_RAD short of it, as a turn's; the segment from
            # it reads its first derivative past the switch (kernels.balances.past_switch),
            # so a kink within 1e-8 of it (an admission where the port opens) is passed by
            # it rather than cutting a sliver
            switches = [float(w) for w in turn_stops(theta0, self.schedule_stops)[1:-1]]
            stops = sorted([s for s in stops if all(abs(s - w) > 1e-8 for w in switches)]
                           + switches)
        return [theta0] + stops + [theta0 + two_pi]

    def scales(self) -> np.ndarray:
        """Magnitude of every state component, for absolute tolerances.

        Masses scale with the largest reservoir density filling every node at its
        largest volume, energies and enthalpies with that mass's, work and heat with
        ``p V``; the ``hA`` and ``hAT`` quadratures get huge scales (kept out of the step
        control) and a skin wall's temperature the supply's less the exhaust's.

        Returns
        -------
        ndarray
            One scale per state component, in its unit; shape (:attr:`n_state`,).
        """
        ref = max(self.reservoirs, key=lambda s: s.p)
        # each cylinder's volumes found once for both its ends (the same values as
        # :meth:`volume` node by node)
        per_cyl: dict = {}
        vmax = 0.0
        for i in range(self.n_nodes):
            if self.node_kind[i] == FIXED:
                v = np.full(_SCALE_THETA.shape, self.node_V[i])
            else:
                c = self.node_cyl[i]
                if c not in per_cyl:
                    per_cyl[c] = self.geometries[c].volumes_m3(_SCALE_THETA + self.phases[c])
                v = per_cyl[c][self.node_end[i]]
            vmax += float(np.max(v))
        m = vmax * ref.rho
        nd, q0 = self.n_dyn, self.n_dyn + 2 * self.n_edges
        sc = np.empty(self.n_state)
        sc[0:nd:2] = m
        sc[1:nd:2] = m * ref.u
        sc[nd:q0:2] = m
        sc[nd + 1:q0:2] = m * ref.h
        sc[q0:] = ref.p * vmax
        # diagnostics for the wall temperature, kept out of the step-size control: each
        # node's hA and hAT (:meth:`i_node_quad`, every node's at once)
        nq, q_end = len(self.NODE_QUADS), q0 + len(self.NODE_QUADS) * self.n_nodes
        sc[q0 + self.NODE_QUADS.index("hA"):q_end:nq] = 1e12
        sc[q0 + self.NODE_QUADS.index("hAT"):q_end:nq] = 1e15
        for i in self.wall_nodes:
            # the surface temperature's swing is a fraction of supply less exhaust
            sc[self.i_wall(i)] = max(ref.T - min(s.T for s in self.reservoirs), 10.0)
            sc[self.i_film(i)] = m
            sc[self.i_wall(i, "heat_sat")] = sc[self.i_wall(i, "heat_conv")] = ref.p * vmax
        return sc

    def column_colors(self) -> tuple[np.ndarray, np.ndarray]:
        """Groups of state columns a finite-difference Jacobian may perturb together.

        Perturbing node i moves the derivatives of i, of its neighbours through an
        edge, and of the quadratures of those edges; nodes whose such rows do not
        overlap share a colour.

        Returns
        -------
        color : ndarray of int64
            The colour of each dynamic column; shape (:attr:`n_dyn`,).
        owner : ndarray of int64
            ``owner[c, row]``: the column of colour ``c`` that moves ``row``, or -1;
            shape (colours, :attr:`n_state`).
        """
        key = (type(self), self.n_nodes, tuple(self.e_a), tuple(self.e_b),
               tuple(self.wall_nodes))
        got = _COLORS.get(key)
        if got is None:
            got = self._column_colors()
            if len(_COLORS) >= COLORS_KEPT:
                _COLORS.clear()
            _COLORS[key] = got
        return got[0].copy(), got[1].copy()

    def _column_colors(self) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`column_colors`, found."""
        nv = self.n_nodes
        nbr: list[set[int]] = [set() for _ in range(nv)]
        for a, b in zip(self.e_a, self.e_b):
            if a >= 0 and b >= 0:
                nbr[a].add(b)
                nbr[b].add(a)
        reach = [nbr[i] | {i} for i in range(nv)]
        node_color = [-1] * nv
        for i in range(nv):
            used = {node_color[j] for j in range(nv) if node_color[j] >= 0 and reach[i] & reach[j]}
            c = 0
            while c in used:
                c += 1
            node_color[i] = c
        ncol = 2 * (max(node_color) + 1)
        color = np.array([2 * node_color[i] + v for i in range(nv) for v in (0, 1)], dtype=np.int64)
        owner = np.full((ncol, self.n_state), -1, dtype=np.int64)
        for i in range(nv):
            for v in (0, 1):
                col = 2 * i + v
                c = color[col]
                for j in reach[i]:
                    owner[c, 2 * j] = col
                    owner[c, 2 * j + 1] = col
                for e, (a, b) in enumerate(zip(self.e_a, self.e_b)):
                    if a == i or b == i:
                        owner[c, self.i_edge_mass(e)] = col
                        owner[c, self.i_edge_enthalpy(e)] = col
                for what in self.NODE_QUADS:
                    owner[c, self.i_node_quad(i, what)] = col
                if i in self.wall_nodes:
                    for what in self.WALL_STATES:
                        owner[c, self.i_wall(i, what)] = col
        return color, owner

    # --- arrays for the kernel ------------------------------------------------------
    def arrays(self) -> NetworkArrays:
        """The plain arrays the compiled right-hand side reads, by name.

        Sets :attr:`wall_T` to the mean of supply and exhaust temperatures when it is
        unset (or of another length than the nodes).

        Returns
        -------
        NetworkArrays
            21 fields (:class:`corliss.engine.kernels.data.NetworkArrays`): ``omega``
            ``[omega]`` [rad/s]; ``band`` [-]; ``geometry`` (cylinders, 8): crank
            radius, rod, stroke [m], head and crank piston areas [m2], head and crank
            clearances [m3], rod angularity (1 or 0); ``phase`` [rad]; ``node_kind``,
            ``node_cyl``, ``node_end``, ``node_V`` [m3]; ``reservoirs`` (reservoirs, 4):
            p [Pa], rho [kg/m3], h [J/kg], the port-flow exponent [-]; ``edge_a``,
            ``edge_b``, ``edge_kind``, ``edge_cyl``, ``edge_port``, ``edge_area`` [m2],
            ``edge_cd`` [-]; ``port_grid`` the PortMaps' angle grids (cylinders, points)
            [rad], ``port_npts`` their lengths, ``port_area`` their areas (cylinders, 4,
            points) [m2]; ``heat`` the wall-heat rows (nodes, :data:`HEAT_COLUMNS`);
            ``wall_T`` :attr:`wall_T` [K].
        """
        ncyl = len(self.geometries)
        geo = np.array([[g.crank_m, g.spec.connecting_rod_m, g.spec.stroke_m, g.area_head_m2,
                         g.area_crank_m2, *g.clearance_m3, 1.0 if g.rod_angularity else 0.0]
                        for g in self.geometries])
        nmax = max(pm.theta_rad.size for pm in self.portmaps)
        grid = np.zeros((ncyl, nmax))
        area = np.zeros((ncyl, 4, nmax))
        npts = np.zeros(ncyl, dtype=np.int64)
        for c, pm in enumerate(self.portmaps):
            n = pm.theta_rad.size
            grid[c, :n] = pm.theta_rad
            grid[c, n:] = pm.theta_rad[-1]
            area[c, :, :n] = pm.area_m2
            npts[c] = n
        # the reservoirs' port-flow exponent is the real fluid's (the kernel puts the
        # perfect tier's own in its place)
        res = _reservoir_rows(self.reservoirs)
        i64 = lambda v: np.asarray(v, dtype=np.int64)  # noqa: E731
        f64 = lambda v: np.asarray(v, dtype=np.float64)  # noqa: E731
        if self.wall_T is None or self.wall_T.size != self.n_nodes:
            t0 = 0.5 * (self.reservoirs[0].T + self.reservoirs[-1].T)
            self.wall_T = np.full(self.n_nodes, t0)
        return NetworkArrays(
            omega=np.array([float(self.omega)]), band=float(self.band), geometry=geo,
            phase=f64(self.phases), node_kind=i64(self.node_kind), node_cyl=i64(self.node_cyl),
            node_end=i64(self.node_end), node_V=f64(self.node_V), reservoirs=res,
            edge_a=i64(self.e_a), edge_b=i64(self.e_b), edge_kind=i64(self.e_kind),
            edge_cyl=i64(self.e_cyl), edge_port=i64(self.e_port), edge_area=f64(self.e_area),
            edge_cd=f64(self.e_cd), port_grid=grid, port_npts=npts, port_area=area,
            heat=f64(self.node_heat), wall_T=self.wall_T)


#: The reservoirs' kernel rows (:func:`_reservoir_rows`) by their states, with the table
#: their exponents came from; and how many are kept.
_RESERVOIR_ROWS: dict = {}
RESERVOIR_ROWS_KEPT = 64


def _reservoir_rows(reservoirs) -> np.ndarray:
    """Each reservoir's row of ``NetworkArrays.reservoirs``: p [Pa], rho [kg/m3],
    h [J/kg] and the real fluid's port-flow exponent at its state [-], kept by the
    states and the table (a study's runs share their reservoirs: the compiled
    exponent's call, which hands the whole table over, made once)."""
    from corliss.thermo.steam_table import kappa_at, load_table
    table = load_table()
    key = (id(table), tuple(reservoirs))
    kept = _RESERVOIR_ROWS.get(key)
    if kept is not None and kept[0] is table:
        return kept[1].copy()
    tab = table.arrays()
    rows = np.array([[s.p, s.rho, s.h, kappa_at(tab, s.rho, s.u)] for s in reservoirs])
    if len(_RESERVOIR_ROWS) >= RESERVOIR_ROWS_KEPT:
        _RESERVOIR_ROWS.clear()
    _RESERVOIR_ROWS[key] = (table, rows)
    return rows.copy()


#: The crank angles a network's volumes are sampled at for its states' scales [rad].
_SCALE_THETA = np.linspace(0, 2 * math.pi, 73)
#: The column colours of the networks of each layout (:meth:`Network.column_colors`):
#: a study's runs share their network's layout, found once.
_COLORS: dict = {}
#: How many layouts it keeps.
COLORS_KEPT = 64


def _band(band: float | None) -> float:
    """The regularisation band asked for, or the port flow's own (read at each call)."""
    from corliss.thermo import orifice
    return orifice.PORT_BAND if band is None else float(band)


def cylinder_prefix(c: int) -> str:
    """Column prefix of an identical cylinder's ends and columns.

    Parameters
    ----------
    c : int
        The cylinder's index, 0 first.

    Returns
    -------
    str
        ``""`` for the first, ``"c2_"``, ``"c3_"`` ... after it.
    """
    return "" if c == 0 else f"c{c + 1}_"


def single_cylinder(geometry, portmap, chest, exhaust, omega: float, band: float | None = None,
                    crank_angles: tuple[float, ...] = (0.0,)) -> Network:
    """Identical double-acting cylinders fed straight from the chest at supply state.

    One cylinder by default; with ``crank_angles``, one cylinder per entry, its crank
    following the first by that angle (Marks Arts. 54-59).  Each end is a node
    (``head``, ``crank``, prefixed by :func:`cylinder_prefix`) with a steam edge from
    reservoir 0 and an exhaust edge from reservoir 1; the head end starts at the chest's
    state, the crank end at the exhaust's.

    Parameters
    ----------
    geometry : CylinderGeometry
        Every cylinder's geometry.
    portmap : PortMap
        Every cylinder's port areas and discharge coefficients.
    chest : State
        The supply steam at the chest (reservoir 0).
    exhaust : State
        The steam at back pressure (reservoir 1).
    omega : float
        Shaft speed [rad/s].
    band : float, optional
        The port flow's regularisation band [-]
        (:data:`corliss.thermo.orifice.PORT_BAND` unless given).
    crank_angles : tuple of float
        The angle each cylinder's crank follows the first's [rad], the first's (0)
        included.

    Returns
    -------
    Network
        The network, without effects.
    """
    band = _band(band)
    n = len(crank_angles)
    net = Network(omega, band, [geometry] * n, [-a for a in crank_angles], [portmap] * n,
                  [chest, exhaust])
    cd = portmap.cd
    for c in range(n):
        pre = cylinder_prefix(c)
        for e, end in enumerate(("head", "crank")):
            node = net.add_node(pre + end, PISTON, chest if e == 0 else exhaust, cyl=c, end=e)
            net.add_edge(f"{pre}{end}_steam", reservoir(0), node, float(cd[2 * e]),
                         PORTMAP_EDGE, c, 2 * e)
            net.add_edge(f"{pre}{end}_exhaust", reservoir(1), node, float(cd[2 * e + 1]),
                         PORTMAP_EDGE, c, 2 * e + 1)
    return net


def throttle_area_m2(supply) -> float:
    """Effective area [m2] of the steam pipe and its throttle, in series.

    The pipe (bore d) and the throttle valve are two orifices in series; for the same
    flow their areas combine as 1/A^2 = 1/A_pipe^2 + 1/A_throttle^2 (the pressure
    drops add, each ~ (mdot/A)^2).  A_throttle = A_pipe x opening (``linear``) or
    A_pipe (1 - cos(90 deg x opening)) (``butterfly``); wide open, the valve's own
    loss remains (A = A_pipe / sqrt 2).

    Parameters
    ----------
    supply : SupplySpec
        The scene's supply: ``pipe_diameter_m`` [m], ``throttle`` (the opening [-], 0
        to 1) and ``throttle_law`` (``linear`` or ``butterfly``).

    Returns
    -------
    float
        The effective area [m2].
    """
    a_pipe = math.pi / 4.0 * supply.pipe_diameter_m ** 2
    x = supply.throttle
    frac = x if supply.throttle_law == "linear" else 1.0 - math.cos(0.5 * math.pi * x)
    a_thr = a_pipe * frac
    return 1.0 / math.sqrt(1.0 / a_pipe ** 2 + 1.0 / a_thr ** 2)


def with_steam_chest(net: Network, supply) -> Network:
    """Put a chest of finite volume between the boiler (reservoir 0) and the ports.

    The chest is a fixed node ``chest`` starting at the boiler's state; every edge that
    took steam from reservoir 0 takes it from the chest, and a ``steam_pipe`` edge of
    :func:`throttle_area_m2` joins the boiler to the chest.

    Parameters
    ----------
    net : Network
        The network, changed in place.
    supply : SupplySpec
        The scene's supply: ``chest_volume_m3`` [m3], ``pipe_discharge_coefficient``
        [-] and what :func:`throttle_area_m2` reads.

    Returns
    -------
    Network
        ``net``.
    """
    boiler = net.reservoirs[0]
    chest = net.add_node("chest", FIXED, boiler, volume=supply.chest_volume_m3)
    for e, a in enumerate(net.e_a):
        if a == reservoir(0):
            net.e_a[e] = chest
    net.add_edge("steam_pipe", reservoir(0), chest, supply.pipe_discharge_coefficient,
                 FIXED_EDGE, area=throttle_area_m2(supply))
    return net


def with_leakage(net: Network, valve_area_m2: float, piston_area_m2: float,
                 cd: float = 0.7) -> Network:
    """Leakage as orifices of equivalent area.

    Past the valve, from the steam side (chest, or the supply) into each end (edges
    ``valve_leak_<end>``); past the piston, between the two ends (``piston_leak``); for
    every cylinder fed from the chest (a compound's LP, fed from the receiver, is left
    tight: its leak areas are not given).  A zero area adds no edge.

    Parameters
    ----------
    net : Network
        The network, changed in place.
    valve_area_m2 : float
        Equivalent area of the leak past the valve into each end [m2].
    piston_area_m2 : float
        Equivalent area of the leak past the piston [m2].
    cd : float
        Discharge coefficient of every leak [-].

    Returns
    -------
    Network
        ``net``.
    """
    src = net.node("chest") if "chest" in net.node_names else reservoir(0)
    for c in range(len(net.geometries)):
        pre = cylinder_prefix(c)
        if f"{pre}head" not in net.node_names:
            continue
        head, crank = net.node(f"{pre}head"), net.node(f"{pre}crank")
        if valve_area_m2 > 0.0:
            for name, node in (("head", head), ("crank", crank)):
                net.add_edge(f"valve_leak_{pre}{name}", src, node, cd, FIXED_EDGE,
                             area=valve_area_m2)
        if piston_area_m2 > 0.0:
            net.add_edge(f"{pre}piston_leak", head, crank, cd, FIXED_EDGE, area=piston_area_m2)
    return net


def with_period_leakage(net: Network, valve_rate_kg_s_Pa: float,
                        piston_rate_kg_s_Pa: float, steam_edge_rate_kg_s_Pa: float = 0.0,
                        exhaust_edge_rate_kg_s_Pa: float = 0.0,
                        edge_scales: list | None = None,
                        idle_ends: tuple[int, ...] = ()) -> Network:
    """Leakage by the period's law (:mod:`corliss.thermo.leak_law`): a flow equal to a
    rate of leak times the pressure difference, independent of speed.

    Past the valve, from the steam side (chest, or the supply) straight to the exhaust
    (edge ``valve_leak_exhaust``, one for the engine; a compound's HP valve into the
    receiver, ``valve_leak_receiver``, and its LP valve from there to the exhaust):
    the path Callendar and Nicolson measured their "rate of leak of the valve" on,
    the steam ports blocked (DPJ 312, 1899, p. 163; their quadruple engine's HP and
    LP valves leaked alike, 17.3 and 18.6 kg/h); past the piston, between the two ends
    of every cylinder (``piston_leak``); and across each edge of every cylinder's
    valve: from its steam side into each end past the steam edge
    (``valve_leak_<end>``, the chest's or a compound LP's receiver) and from each end to
    its exhaust side past the exhaust edge (``valve_leak_<end>_exhaust``), each at its
    rate times the edge's scale (:func:`corliss.engine.leak_paths.edge_leak_scales`:
    the port's length over the reference's, the reference's face width over the
    edge's).  A zero rate adds no edge.

    The edges' leaks flow all the turn, the port open or shut.  Across an open port
    the two sides differ by the port's own drop (wire-drawing), so the leak there is
    a small part of its closed value and a far smaller part of the port's flow;
    stopping it when the port opens would put a step in the right-hand side at every
    event for a flow the measurements cannot tell apart (Callendar and Nicolson
    measured the valve's whole leak, not by the edge's state).

    The leak carries the enthalpy of the side it leaves.  Callendar and Nicolson found
    it mostly water: steam condensing on the valve's faces, which the water's
    re-evaporation on the far side cools again (p. 164).  Over a cycle the faces
    neither gain nor lose heat, so what passes delivers the enthalpy it took, as an
    adiabatic throttling does; where it arrives as water or steam changes only where
    it re-evaporates, which for the chest-to-exhaust path is outside the cylinder.

    Parameters
    ----------
    net : Network
        The network, changed in place.
    valve_rate_kg_s_Pa : float
        Rate of leak of the valve, chest to exhaust [kg/(s Pa)].
    piston_rate_kg_s_Pa : float
        Rate of leak past the piston [kg/(s Pa)].
    steam_edge_rate_kg_s_Pa, exhaust_edge_rate_kg_s_Pa : float
        Rates of leak of the reference valve past a closed steam edge (steam side into
        the end) and a closed exhaust edge (the end to the exhaust side) [kg/(s Pa)].
    edge_scales : list of ndarray, optional
        Each cylinder's factor on those rates for each of its ports, shape ``(4,)``
        in port order (:func:`corliss.engine.leak_paths.edge_leak_scales`); 1 when
        not given.
    idle_ends : tuple of int
        Ends (0 head, 1 crank) of every cylinder that take no steam (single-acting):
        their ports stand open or shut, not past a valve's edge, and leak nothing.

    Returns
    -------
    Network
        ``net``.
    """
    for e in range(net.n_edges):
        if net.e_kind[e] != PORTMAP_EDGE:
            continue
        c, port, node = net.e_cyl[e], net.e_port[e], net.e_b[e]
        steam = port % 2 == 0
        reference = steam_edge_rate_kg_s_Pa if steam else exhaust_edge_rate_kg_s_Pa
        rate = reference * (1.0 if edge_scales is None else float(edge_scales[c][port]))
        if rate <= 0.0 or net.node_end[node] in idle_ends:
            continue
        name = net.node_names[node]
        if steam:
            k = net.add_edge(f"valve_leak_{name}", net.e_a[e], node, 1.0, LINEAR_EDGE,
                             area=rate)
        else:
            k = net.add_edge(f"valve_leak_{name}_exhaust", node, net.e_a[e], 1.0,
                             LINEAR_EDGE, area=rate)
        net.edge_leaks.append((k, c, port, reference))
    src = net.node("chest") if "chest" in net.node_names else reservoir(0)
    if valve_rate_kg_s_Pa > 0.0:
        if "receiver" in net.node_names:
            # a compound: the HP valve leaks into the receiver, the LP's to the exhaust
            rec = net.node("receiver")
            net.add_edge("valve_leak_receiver", src, rec, 1.0, LINEAR_EDGE,
                         area=valve_rate_kg_s_Pa)
            src = rec
        net.add_edge("valve_leak_exhaust", src, reservoir(1), 1.0, LINEAR_EDGE,
                     area=valve_rate_kg_s_Pa)
    if piston_rate_kg_s_Pa > 0.0:
        prefixes = [cylinder_prefix(c) for c in range(len(net.geometries))] + ["lp_"]
        for pre in dict.fromkeys(prefixes):
            if f"{pre}head" in net.node_names:
                net.add_edge(f"{pre}piston_leak", net.node(f"{pre}head"),
                             net.node(f"{pre}crank"), 1.0, LINEAR_EDGE,
                             area=piston_rate_kg_s_Pa)
    return net


#: Columns of a node's wall-heat row (:data:`HEAT_COLUMNS`, named ``H_*`` in
#: :mod:`corliss.engine.kernels.data`): the model code, then the model's own columns.
#: The wall models by name, and their codes (``WALL_*`` there).
WALL_MODELS = {"conductance": WALL_CONDUCTANCE, "adair": WALL_ADAIR, "marks": WALL_MARKS,
               "english": WALL_MARKS, "skin": WALL_SKIN}


def with_wall_heat(net: Network, model: str, h_marks: float, steam_props, *,
                   condensing_W_m2K: float | None = None,
                   jacket_T_K: float | tuple | None = None, wall_thickness_m: float = 0.025, idle_ends: tuple = (),
                   supply_superheat_K: float = 0.0, jacket: str = "barrel") -> Network:
    """Heat exchange between the steam of each cylinder end and its walls.

    ``model``:

    * ``"marks"``: Marks's law of condensation (Arts. 74-75, eq. 221): the heat of
      condensing the steam eq. 221 gives leaves the steam during admission and is
      given back from cut-off to compression, each spread over the crank angle in
      proportion to the wall exposed; the heat of each cycle and the windows are set
      by :class:`corliss.engine.condensation.MarksLaw` from the cycle before;
    * ``"english"``: English's law (DPJ 267, 1888, p. 302) on Marks's schedule (the same
      model code): the heat the steam-swept surfaces hold at cut-off leaves the steam
      during admission and is given back from cut-off to compression, set by
      :class:`corliss.engine.condensation.EnglishLaw` from the cycle before;
    * ``"conductance"``: Marks's constant of condensation (Art. 82: C = 18.13 Btu per
      ft2, degF and minute, about 6180 W/(m2 K)) as a surface conductance to a wall at
      one temperature per end, its periodic mean, found cycle by cycle so that the
      wall neither gains nor loses heat over a cycle; a wall hotter than the steam
      boils its film at the saturation temperature of the cylinder's pressure;
    * ``"adair"``: the correlation for reciprocating machines of Adair, Qvale and
      Pearson (Purdue Compressor Conference, 1972), h = 0.053 (k/D_e) Re^0.8 Pr^0.6
      with D_e = 6 V / A and the gas velocity taken as omega D_e / 2, with transport
      properties of the supply steam (``steam_props``: conductivity, viscosity,
      Prandtl), to a wall at its periodic mean temperature;
    * ``"skin"``: a wall with a temperature (:mod:`corliss.engine.wall`): each end's
      surface temperature is a state, exchanging heat with the steam by condensation and
      evaporation (``condensing_W_m2K``) and Adair's convection, over a deep wall found
      cycle by cycle; with ``jacket_T_K``, the outer face of the jacketed parts
      (``jacket``: barrel, covers or both; ``wall_thickness_m`` of iron away) is held
      at that temperature.  Every cylinder has its own wall.  A
      surface below saturation condenses only where the steam at it is at saturation,
      its superheat taken as the bulk's but no more than the supply's
      (``supply_superheat_K``; :func:`corliss.engine.kernels.walls.condensing_share`).

    Every cylinder end gets the model's row in :attr:`Network.node_heat` but a
    single-acting cylinder's idle end (``idle_ends``), whose side of the piston stands
    open to the exhaust and is no part of the engine's steam; vessels (chest,
    receiver) exchange no heat.

    Parameters
    ----------
    net : Network
        The network, changed in place.
    model : str
        One of :data:`WALL_MODELS`: ``marks``, ``english``, ``conductance``, ``adair``
        or ``skin``.
    h_marks : float
        Marks's constant as a surface conductance [W/(m2 K)] (the ``conductance``
        model's coefficient).
    steam_props : tuple of float
        Transport properties of the supply steam: conductivity [W/(m K)], viscosity
        [Pa s] and Prandtl number [-].
    condensing_W_m2K : float, optional
        The skin model's coefficient of condensation and evaporation [W/(m2 K)]
        (default :data:`corliss.engine.wall.CONDENSING_W_M2K`).
    jacket_T_K : float or tuple of float, optional
        A jacket's temperature [K], or one per cylinder (the last for any beyond)
        (skin model; None: no jacket).
    wall_thickness_m : float
        The barrel's iron between bore and jacket [m] (skin model, with a jacket).
    idle_ends : tuple of int
        Ends (0 head, 1 crank) of every cylinder that take no steam: no wall heat.
    supply_superheat_K : float
        The superheat of the steam supplied [K] (0 when saturated or wet; skin model).
    jacket : str
        The parts jacketed with ``jacket_T_K``: ``"barrel"``, ``"covers"`` or
        ``"barrel_and_covers"`` (:func:`corliss.engine.wall.jacketed_area_m2`).

    Returns
    -------
    Network
        ``net``.
    """
    from corliss.engine import wall
    from corliss.thermo.wall_properties import film_enthalpies
    k, mu, pr = steam_props
    code = WALL_MODELS[model]
    for i, kind in enumerate(net.node_kind):
        if kind == PISTON and net.node_end[i] not in idle_ends:
            net.node_heat[i] = (code, h_marks, k, mu, pr) + (0.0,) * (HEAT_COLUMNS - 5)
    if model == "skin":
        h_c = wall.CONDENSING_W_M2K if condensing_W_m2K is None else condensing_W_m2K
        # the reference the heat into the steam counts the film's water from (the film
        # itself is water at the surface's temperature: kernels.walls.film_water)
        t0 = 0.5 * (net.reservoirs[0].T + net.reservoirs[-1].T)
        film = film_enthalpies(t0)

        def jacket_of(c):
            if jacket_T_K is None or isinstance(jacket_T_K, float):
                return jacket_T_K
            return jacket_T_K[min(c, len(jacket_T_K) - 1)]
        for i in net.wall_nodes:
            net.node_heat[i] = wall.skin_row(net.geometries[net.node_cyl[i]], net.node_end[i],
                                             net.omega, h_c, steam_props, net.i_wall(i),
                                             jacket_of(net.node_cyl[i]), wall_thickness_m,
                                             jacket) + film + (
                                                 max(supply_superheat_K, 0.0),)
    return net


def compound(hp_geometry, hp_portmap, lp_geometry, lp_portmap, lp_phase: float, receiver_m3: float,
             chest, exhaust, receiver_init, omega: float, band: float | None = None) -> Network:
    """A compound engine (Marks Arts. 87-92).

    The high-pressure cylinder exhausts into a receiver of fixed volume, from which the
    low-pressure cylinder takes its steam.

    Nodes: ``head``, ``crank`` (HP), ``receiver``, ``lp_head``, ``lp_crank``; edges
    named ``<end>_steam`` and ``<end>_exhaust`` as for one cylinder.

    Parameters
    ----------
    hp_geometry, lp_geometry : CylinderGeometry
        The high- and low-pressure cylinders.
    hp_portmap, lp_portmap : PortMap
        Their port areas and discharge coefficients.
    lp_phase : float
        The LP crank's angle less the HP's [rad].
    receiver_m3 : float
        The receiver's volume [m3].
    chest : State
        The supply steam at the chest (reservoir 0).
    exhaust : State
        The steam at back pressure (reservoir 1).
    receiver_init : State
        The state the receiver, the HP crank end and the LP head end start from.
    omega : float
        Shaft speed [rad/s].
    band : float, optional
        The port flow's regularisation band [-]
        (:data:`corliss.thermo.orifice.PORT_BAND` unless given).

    Returns
    -------
    Network
        The network, without effects.
    """
    band = _band(band)
    net = Network(omega, band, [hp_geometry, lp_geometry], [0.0, lp_phase],
                  [hp_portmap, lp_portmap], [chest, exhaust])
    hp = [net.add_node(end, PISTON, chest if e == 0 else receiver_init, cyl=0, end=e)
          for e, end in enumerate(("head", "crank"))]
    rec = net.add_node("receiver", FIXED, receiver_init, volume=receiver_m3)
    lp = [net.add_node(f"lp_{end}", PISTON, receiver_init if e == 0 else exhaust, cyl=1, end=e)
          for e, end in enumerate(("head", "crank"))]
    for cyl, (nodes, src, dst, pm, prefix) in enumerate(
            ((hp, reservoir(0), rec, hp_portmap, ""), (lp, rec, reservoir(1), lp_portmap, "lp_"))):
        for e, (node, end) in enumerate(zip(nodes, ("head", "crank"))):
            net.add_edge(f"{prefix}{end}_steam", src, node, float(pm.cd[2 * e]), PORTMAP_EDGE,
                         cyl, 2 * e)
            net.add_edge(f"{prefix}{end}_exhaust", dst, node, float(pm.cd[2 * e + 1]),
                         PORTMAP_EDGE, cyl, 2 * e + 1)
    return net


def piston_ends(net: Network) -> list[str]:
    """Names of the nodes that are cylinder ends.

    Parameters
    ----------
    net : Network
        The network.

    Returns
    -------
    list of str
        The names, in node order.
    """
    return [n for n, k in zip(net.node_names, net.node_kind) if k == PISTON]
