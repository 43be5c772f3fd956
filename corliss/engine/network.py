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

PISTON, FIXED = 0, 1
PORTMAP_EDGE, FIXED_EDGE = 0, 1


def reservoir(r: int) -> int:
    """Edge end code of reservoir ``r``."""
    return -1 - r


@dataclass
class Network:
    """Nodes, reservoirs and edges of one engine (all SI)."""

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

    # --- building -----------------------------------------------------------------
    def add_node(self, name, kind, init, cyl=-1, end=-1, volume=0.0) -> int:
        self.node_names.append(name)
        self.node_kind.append(kind)
        self.node_cyl.append(cyl)
        self.node_end.append(end)
        self.node_V.append(volume)
        self.node_init.append(init)
        self.node_heat.append((0.0,) * HEAT_COLUMNS)
        return len(self.node_names) - 1

    def add_edge(self, name, a, b, cd, kind=FIXED_EDGE, cyl=-1, port=-1, area=0.0) -> int:
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
        return len(self.node_names)

    @property
    def n_edges(self) -> int:
        return len(self.edge_names)

    @property
    def n_dyn(self) -> int:
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
        return [i for i, row in enumerate(self.node_heat) if row[0] == WALL_MODELS["skin"]]

    #: States of a skin-model wall: the surface temperature less the deep wall's [K],
    #: the water film [kg], and two quadratures restarted each cycle: the heat from the
    #: wall that goes down T_w - T_sat (condensing on it, boiling off it) and down
    #: T_w - T (convection) [J].
    WALL_STATES = ("surface", "film", "heat_sat", "heat_conv")

    @property
    def n_state(self) -> int:
        return self.n_quad_end + len(self.WALL_STATES) * len(self.wall_nodes)

    def i_wall(self, node: int, what: str = "surface") -> int:
        """Index of one of node's wall states (WALL_STATES)."""
        return (self.n_quad_end + len(self.WALL_STATES) * self.wall_nodes.index(node)
                + self.WALL_STATES.index(what))

    def i_film(self, node: int) -> int:
        """Index of the mass of the water film on node's wall [kg]."""
        return self.i_wall(node, "film")

    def i_edge_mass(self, e: int) -> int:
        return self.n_dyn + 2 * e

    def i_edge_enthalpy(self, e: int) -> int:
        return self.n_dyn + 2 * e + 1

    def i_node_quad(self, node: int, what: str) -> int:
        return (self.n_dyn + 2 * self.n_edges + len(self.NODE_QUADS) * node
                + self.NODE_QUADS.index(what))

    def i_work(self, node: int) -> int:
        return self.i_node_quad(node, "work")

    def node(self, name: str) -> int:
        return self.node_names.index(name)

    def edge(self, name: str) -> int:
        return self.edge_names.index(name)

    def boundary_totals(self, y: np.ndarray) -> dict:
        """Mass and enthalpy into the engine over a cycle from the supply (reservoir 0)
        and from the exhaust (reservoir 1; negative when, as usual, it goes out)."""
        out = {"m_supply_kg": 0.0, "H_supply_J": 0.0, "m_exhaust_kg": 0.0, "H_exhaust_J": 0.0}
        for e, (a, b) in enumerate(zip(self.e_a, self.e_b)):
            for end, sign in ((a, 1.0), (b, -1.0)):
                if end < 0:
                    what = "supply" if end == reservoir(0) else "exhaust"
                    out[f"m_{what}_kg"] += sign * y[self.i_edge_mass(e)]
                    out[f"H_{what}_J"] += sign * y[self.i_edge_enthalpy(e)]
        return out

    def leak_edges(self) -> list[tuple[str, int]]:
        """(name, index) of the leakage paths."""
        return [(n, e) for e, n in enumerate(self.edge_names) if "leak" in n]

    # --- volumes --------------------------------------------------------------------
    def volume(self, node: int, theta: np.ndarray) -> np.ndarray:
        """Volume of a node [m3] at shaft crank angles ``theta`` [rad]."""
        if self.node_kind[node] == FIXED:
            return np.full(np.shape(theta), self.node_V[node])
        c = self.node_cyl[node]
        return self.geometries[c].volumes_m3(np.asarray(theta) + self.phases[c])[self.node_end[node]]

    def initial_state(self) -> np.ndarray:
        y = np.zeros(self.n_state)
        for i, st in enumerate(self.node_init):
            V = float(self.volume(i, np.array(0.0)))
            y[2 * i] = V * st.rho
            y[2 * i + 1] = V * st.rho * st.u
        return y

    def stops(self, theta0: float) -> list[float]:
        """Crank angles over one turn from ``theta0`` where any port area has a kink."""
        two_pi = 2.0 * math.pi
        pts = []
        for pm, ph in zip(self.portmaps, self.phases):
            pts += [(b - ph) % two_pi for b in pm.breakpoints_rad]
        stops = sorted({theta0 + ((p - theta0) % two_pi) for p in pts})
        stops = [s for s in stops if 1e-9 < s - theta0 < two_pi - 1e-9]
        return [theta0] + stops + [theta0 + two_pi]

    def scales(self) -> np.ndarray:
        """Magnitude of every state component, for absolute tolerances."""
        ref = max(self.reservoirs, key=lambda s: s.p)
        vmax = sum(float(np.max(self.volume(i, np.linspace(0, 2 * math.pi, 73))))
                   for i in range(self.n_nodes))
        m = vmax * ref.rho
        sc = np.empty(self.n_state)
        sc[0:self.n_dyn:2] = m
        sc[1:self.n_dyn:2] = m * ref.u
        sc[self.n_dyn:self.n_dyn + 2 * self.n_edges:2] = m
        sc[self.n_dyn + 1:self.n_dyn + 2 * self.n_edges:2] = m * ref.h
        sc[self.n_dyn + 2 * self.n_edges:] = ref.p * vmax
        for i in range(self.n_nodes):
            # diagnostics for the wall temperature: kept out of the step-size control
            sc[self.i_node_quad(i, "hA")] = 1e12
            sc[self.i_node_quad(i, "hAT")] = 1e15
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
        overlap share a colour.  Returns ``(color of each dynamic column, owner)``,
        ``owner[c, row]`` = the column of colour c that moves ``row``, or -1.
        """
        nv = self.n_nodes
        nbr = [set() for _ in range(nv)]
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
    def arrays(self) -> tuple:
        """The tuple the compiled right-hand side reads (see kernel.derivatives)."""
        from corliss.thermo.steam_table import kappa_at, load_table
        tab = load_table().arrays()
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
        res = np.array([[s.p, s.rho, s.h, kappa_at(tab, s.rho, s.u)] for s in self.reservoirs])
        i64 = lambda v: np.asarray(v, dtype=np.int64)  # noqa: E731
        f64 = lambda v: np.asarray(v, dtype=np.float64)  # noqa: E731
        if self.wall_T is None or self.wall_T.size != self.n_nodes:
            t0 = 0.5 * (self.reservoirs[0].T + self.reservoirs[-1].T)
            self.wall_T = np.full(self.n_nodes, t0)
        return (np.array([float(self.omega)]), float(self.band), geo, f64(self.phases), i64(self.node_kind),
                i64(self.node_cyl), i64(self.node_end), f64(self.node_V), res, i64(self.e_a),
                i64(self.e_b), i64(self.e_kind), i64(self.e_cyl), i64(self.e_port),
                f64(self.e_area), f64(self.e_cd), grid, npts, area, f64(self.node_heat),
                self.wall_T)


def _band(band: float | None) -> float:
    """The regularisation band asked for, or the port flow's own (read at each call)."""
    from corliss.thermo import orifice
    return orifice.PORT_BAND if band is None else float(band)


def cylinder_prefix(c: int) -> str:
    """Column prefix of cylinder ``c``: "" for the first, "c2_", "c3_" ... after it."""
    return "" if c == 0 else f"c{c + 1}_"


def single_cylinder(geometry, portmap, chest, exhaust, omega: float, band: float | None = None,
                    crank_angles: tuple[float, ...] = (0.0,)) -> Network:
    """Identical double-acting cylinders fed straight from the chest at supply state.

    One cylinder by default; with ``crank_angles``, one cylinder per entry, its crank
    following the first by that angle [rad] (Marks Arts. 54-59).  ``band``: the port
    flow's regularisation band [-], :data:`corliss.thermo.orifice.PORT_BAND` unless
    given.
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
    """
    a_pipe = math.pi / 4.0 * supply.pipe_diameter_m ** 2
    x = supply.throttle
    frac = x if supply.throttle_law == "linear" else 1.0 - math.cos(0.5 * math.pi * x)
    a_thr = a_pipe * frac
    return 1.0 / math.sqrt(1.0 / a_pipe ** 2 + 1.0 / a_thr ** 2)


def with_steam_chest(net: Network, supply) -> Network:
    """Put a chest of finite volume between the boiler (reservoir 0) and the ports."""
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
    """Leakage as orifices of equivalent area: past the valve, from the steam side
    (chest, or the supply) into each end; past the piston, between the two ends; for
    every cylinder fed from the chest (a compound's LP, fed from the receiver, is left
    tight: its leak areas are not given)."""
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


#: Columns of a node's wall-heat row: model code, conductance, conductivity, viscosity,
#: Prandtl number (codes 1, 2); heat of a cycle, admission, cut-off and compression
#: angles, and the wall exposed over admission and over cut-off to compression,
#: integrated in crank angle (code 3, Marks's law); the surface node's capacity and
#: conductance to the deep wall, its mean area, the index of its state, the jacket's
#: conductance and temperature, the film's enthalpy and latent heat (code 4, the skin
#: model, :mod:`corliss.engine.wall`).
#: The skin model's film: the water's specific enthalpy and the latent heat it takes to
#: evaporate [J/kg] (columns 11, 12).
HEAT_COLUMNS = 13
WALL_MODELS = {"conductance": 1.0, "adair": 2.0, "marks": 3.0, "skin": 4.0}


def with_wall_heat(net: Network, model: str, h_marks: float, steam_props, *,
                   condensing_W_m2K: float | None = None, jacket_T_K: float | None = None,
                   wall_thickness_m: float = 0.025) -> Network:
    """Heat exchange between the steam of each cylinder end and its walls.

    ``model``:

    * ``"marks"``: Marks's law of condensation (Arts. 74-75, eq. 221): the heat of
      condensing the steam eq. 221 gives leaves the steam during admission and is
      given back from cut-off to compression, each spread over the crank angle in
      proportion to the wall exposed; the heat of each cycle and the windows are set
      by :func:`corliss.engine.condensation.marks_law_rows` from the cycle before;
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
      cycle by cycle; with ``jacket_T_K``, the barrel's outer face (``wall_thickness_m``
      of iron away) is held at that temperature.  Every cylinder has its own wall.
    """
    from corliss.engine import wall
    from corliss.thermo.wall_properties import film_enthalpies
    k, mu, pr = steam_props
    code = WALL_MODELS[model]
    for i, kind in enumerate(net.node_kind):
        if kind == PISTON:
            net.node_heat[i] = (code, h_marks, k, mu, pr) + (0.0,) * (HEAT_COLUMNS - 5)
    if model == "skin":
        h_c = wall.CONDENSING_W_M2K if condensing_W_m2K is None else condensing_W_m2K
        # the film's water and its latent heat, at the temperature the wall starts from
        # (constant over a run, so that the film's energy is m_f h_L exactly)
        t0 = 0.5 * (net.reservoirs[0].T + net.reservoirs[-1].T)
        film = film_enthalpies(t0)
        for i in net.wall_nodes:
            net.node_heat[i] = wall.skin_row(net.geometries[net.node_cyl[i]], net.node_end[i],
                                             net.omega, h_c, steam_props, net.i_wall(i),
                                             jacket_T_K, wall_thickness_m) + film
    return net


def compound(hp_geometry, hp_portmap, lp_geometry, lp_portmap, lp_phase: float, receiver_m3: float,
             chest, exhaust, receiver_init, omega: float, band: float | None = None) -> Network:
    """A compound engine (Marks Arts. 87-92): the high-pressure cylinder exhausts into a
    receiver of fixed volume, from which the low-pressure cylinder takes its steam.

    Nodes: ``head``, ``crank`` (HP), ``receiver``, ``lp_head``, ``lp_crank``; edges
    named ``<end>_steam`` and ``<end>_exhaust`` as for one cylinder.
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
    """Names of the nodes that are cylinder ends, in order."""
    return [n for n, k in zip(net.node_names, net.node_kind) if k == PISTON]
