"""A cylinder wall with a temperature: the ``skin`` model of initial condensation.

Why a wall with a temperature
-----------------------------
Marks (Relative Proportions, 3rd ed. 1887, Art. 74, p. 187) explains initial
condensation as heat stored in the iron: the exhaust cools the surface, the entering
steam condenses on it until the surface is warmed, and the water re-evaporates as the
pressure falls during expansion and exhaust (Art. 74, 3-4).  A model that obeys the
second law must therefore carry the surface's temperature: heat flows only from the
hotter of steam and surface to the colder, and dry steam is heated at most to the
surface's temperature.

The wall's laws themselves (Adair's convection, the film's and the wet steam's
coefficients, the film's limits) are written once, in
:mod:`corliss.engine.kernels.walls`, which this module's reference path and the
compiled balances both call.

The surface as one lumped node (the choice, argued)
---------------------------------------------------
The temperature wave the cycle drives into the iron dies within the skin depth
``delta = sqrt(2 alpha / omega)``: for grey cast iron (k = 46 W/(m K), c = 490 J/(kg K),
rho = 7500 kg/m3; alpha = 1.25e-5 m2/s) 2.0 mm at 60 rpm and 0.89 mm at 300 rpm,
against walls of 20 mm or more, so the wall is thermally semi-infinite.  A
semi-infinite solid answers a surface temperature oscillating at omega,
``theta_s e^{i omega t}``, with the heat flux into it (Carslaw & Jaeger, Conduction of
Heat in Solids, 2nd ed. 1959, sec. 2.6)::

    q = sqrt(k rho c omega) e^{i pi/4} theta_s = (k / delta) (1 + i) theta_s.

A lumped surface node of areal capacity ``C`` joined by a conductance ``G`` to a deep
node at the cycle's mean answers ``q = (G + i omega C) theta_s``.  With

    G = k / delta,        C = rho c delta / 2

the two are identical at the engine's frequency, the one that carries most of the
swing; the higher harmonics (sharp admission) are given a little too much capacity
(``n omega C`` against ``sqrt(n)`` growth), which errs on the side of a smaller swing.
A 1-D conduction grid through several skin depths would capture the harmonics at the
cost of ten states per end and a stiff diffusion operator in every right-hand side;
the lumped node keeps one state per end and the exact fundamental, and gives the
``1/sqrt(N)`` speed law of the heat a conducting wall absorbs per cycle (Cotterill's
liquefaction factor has ``sqrt(N)`` in its denominator; Lineham, Text-Book of
Mechanical Engineering, App. II, p. 884) rather than Marks's ``1/N``.

Short events (the film flashing off at release, the first milliseconds of
admission) a semi-infinite wall answers through a layer thinner than the skin depth;
:class:`ConductionGrid` resolves them (a 14-node grid to three skin depths, tested
against Carslaw & Jaeger secs. 2.5 and 2.6) and can stand under the ideal-port
wall's surface.  On the bundled Meyer engine it changes the missing water by under
0.01 of the steam and leaves its trends against the exhaust's temperature and the
initial pressure as they were: what the next admission meets is the surface the iron
has warmed through the dry part of the exhaust, which the grid recovers faster, not
its lowest point (docs/validation/condensation.md).  The lumped node is kept.

The deep node's temperature is found cycle by cycle (:meth:`update_wall` of the
runners): without a jacket, so that the wall neither gains nor loses heat over a
cycle; with a jacket, so that what the steam leaves in the wall over a cycle is what
the jacket gives through the wall's thickness, ``k / L (T_jacket - T_deep)`` where the
deep wall is below the jacket's saturation, nothing where it is above
(:func:`jacket_heat_J`: the jacket's steam condenses, or does nothing).

Exchange between steam, film and surface
----------------------------------------
Per unit of the wall the steam touches [W/m2], two flows, each down its own
temperature difference:

* the film, ``q_f = h_c (T_w - T_sat)`` where the surface is below the saturation
  temperature of the cylinder's pressure and the steam at it is at saturation
  (below), or above it and wetted (its water boils off; the wetted share rises
  from 0 to 1 as the film grows to ``FILM_WET_KG_M2``, 10 microns of water); where the
  film is gone, wet steam still wets the surface with its own water (the share
  falling from 1 to 0 as the mixture's wetness falls through ``WET_BAND``), which
  boils off into the steam at the same coefficient: wet exhaust steam cools the wall;
* convection, ``q_v = h_v (T_w - T)`` with ``T`` the steam's temperature (the
  saturation temperature when wet): dry steam is heated at most to ``T_w``.

Superheated steam condenses only once the steam at the wall is at saturation: while
it is superheated the wall takes its superheat by convection alone (``h_v``, a few
hundred W/(m2 K)), and the condensing coefficient is multiplied by a share that
falls from 1 at saturation to 0 at ``SUPERHEAT_BAND_K`` of superheat
(:func:`corliss.engine.kernels.walls.condensing_share`).  The steam at the wall is
the bulk's, but while steam enters the jet sweeping the wall is, its superheat judged
from its enthalpy at the end's pressure
(:func:`~corliss.engine.kernels.walls.steam_at_wall_superheat`); and it is taken no
more superheated than the steam supplied: with saturated steam supplied the
superheat the filling and the compression give the bulk is the mixed steam's, not
that of the steam touching a wall its own film keeps wet (Kirsch, through DPJ 282,
1891, p. 202: the surface is nowhere appreciably colder than the steam touching it),
and a saturated engine condenses as it did.  Steam superheated at the supply
condenses only once the expansion and the wall have taken its superheat: Hirn
(Theorie mecanique de la chaleur, 1876, through DPJ 278 pp. 538-539): heat enters
the gas very slowly, and a dry wall takes little from it; Marks Art. 78 (eq. 220b):
the superheat must meet the wall's demand; Lineham (A Text-Book of Mechanical
Engineering, p. 885): "a 5 % extra heat supply will often eliminate a 20 % loss".
On the bundled 20 x 42 in Corliss engine (80 rpm, 100 psig, about 0.2 cut-off) 80 K
of superheat takes the water missing at cut-off from 0.157 of the steam (saturated)
to 0.006; without the rule it was 0.180.  Callendar and Nicolson's finding that the
compression's superheat prevents condensation in the clearance (DPJ 312, 1899, pp.
164-165) is kept for superheated supplies only: judging a saturated engine's cushion
by its bulk left the bundled Meyer engine's wall at its shortest cut-off and at 40
psia without a periodic state in the fast preset's cycles (the cushion dry in one
cycle, wet in the next).

``h_c``, condensation and evaporation on the surface.  Nusselt's laminar film on a
vertical surface (Z. VDI 60, 1916, pp. 541-546, 569-575)::

    h = 0.943 [rho_l (rho_l - rho_v) g h_fg k_l^3 / (mu_l L dT)]^(1/4)

gives about 8 kW/(m2 K) for a 12 in cover and a 20 K drop (``nusselt_film_W_m2K``):
a lower bound, for a film gravity drains, not a wall the piston wipes.  The one
measurement of a cylinder's surface is Callendar and Nicolson's (Min. Proc. ICE 131,
1897-98; in Freytag's report, Dinglers Polytechnisches Journal 312, 1899, pp.
161-165): thermo-junctions in the cast iron of a single-acting 10.5 x 12 in engine,
read to 1/20 degC, gave a coefficient of condensation and re-evaporation of 4 kcal
per second, m2 and degC on clean dry surfaces (p. 164), the resistance in a film of
water or oil under 1/40 mm, the surface staying about 15 degC below the steam in
admission (p. 163).  The default, ``CONDENSING_W_M2K``, is theirs, 16.7 kW/(m2 K)
(:data:`corliss.thermo.wall_cycle.CALLENDAR_NICOLSON_W_M2K`).  It replaced 3e5
W/(m2 K), dropwise condensation's order (J. W. Rose, Proc. IMechE A 216, 2002, pp.
115-128), for which no cylinder measurement speaks: with it the surface swung 50 K
at 150 rpm on the small engine and 40 K at 44 rpm under a card like theirs, where
they computed 6 to 11.5 K (``tests/test_period_wall_and_leak.py``), and the water
missing at cut-off on the Meyer engine at 0.42 cut-off was 0.345 of the steam
where Marks's eq. 221 gives 0.19 (docs/validation/condensation.md has the
measurements beside the model with each coefficient).  Marks's constant (Art. 82, p. 209,
18.13 Btu per ft2, degF and minute) is a period calibration of the whole cycle, not a
surface coefficient; ``condensing_coefficient = "marks"`` sets ``h_c`` so that the
missing water at cut-off is what his eq. 221 gives for the same card
(:func:`corliss.engine.calibration.marks_coefficient`).

``h_v``, forced convection of the steam itself: Adair, Qvale and Pearson's
correlation for reciprocating machines (Purdue Compressor Conference, 1972),
``h = 0.053 (k/D_e) Re^0.8 Pr^0.6``, ``D_e = 6 V / A``, gas speed ``omega D_e / 2``:
a few hundred W/(m2 K), rising with density; it is all a dry surface exchanges with
superheated steam.

The water film
--------------
The water condensed on the wall stays there, a film of mass ``m_f`` per end (a
state), until the surface, warmer than the falling saturation temperature, boils it
off: during expansion (re-evaporation, which feeds the expanding steam and lifts the
expansion line towards the hyperbola) and through the exhaust (the period's loss:
the heat the wall took at admission carried to the condenser).  A homogeneous
mixture would lose its water with the first rush of the exhaust and leave the wall
dry and hot through the exhaust stroke, which is not what the engineers measured
(Marks Art. 74).  Water beyond the film gravity holds on a surface the height of the
bore, Nusselt's film thickness (about 0.1 mm, ``FILM_MAX_KG_M2``), runs off into the
steam; and while the steam flows out of the cylinder it sweeps the film beyond the
thin layer that clings as drops (``FILM_WET_KG_M2``) with it, in the proportion of
the steam leaving.

The film is thin (under 0.1 mm) and lies on the surface: its water is saturated
water at the surface's temperature, ``h_L(T_w)``, condensate forms there and vapour
leaves from there (:func:`corliss.engine.kernels.walls.film_water`).  Condensing, the
steam gives up its own enthalpy ``h`` (superheat and all) and the wall takes
``h - h_L(T_w)`` per kilogram; evaporating, the film gives vapour of
``h_L(T_w) + L(T_w)``.  The film's energy ``m_f h_L(T_w)`` moves with the surface:
its warming, ``m_f c_f dT_w``, is the surface's heat, so the surface and its film
have the capacity ``C A_w + m_f c_f``, and the first law closes exactly over the
steam, the film and the wall.  The heat into the steam (``Q_<end>_J``) counts the
film's water from a reference enthalpy, saturated water at the mean of supply and
exhaust temperatures: over a periodic cycle the reference drops out.

So booked, every exchange makes entropy (``tests/test_wall_skin.py`` sums it interval
by interval over a cycle): condensing, water at ``T_w`` is the state of least
``h - T_w s`` at the cylinder's pressure, so the steam's availability at ``T_w`` can
only fall; evaporating, water warmed from ``T_sat`` to ``T_w`` and vapour mixed into
the steam both make entropy.  Until 2026-11 the film's water was booked at one fixed
enthalpy, saturated water at the mean of supply and exhaust temperatures (408 K on
the default engine, above any saturation temperature of its exhaust stroke): with it
the entropy made went negative on some intervals at 10 rpm, and moving that
temperature between the exhaust's and the supply's saturation moved the water rate
by -0.9 to +1.0 %; now by under 1e-4.

Both flows carry heat down their own difference (the film's between surface and
saturation, the convection's between surface and steam), so the wall never gives
heat to what is hotter than it nor takes it from what is colder.

How far the exhaust cools the wall
----------------------------------
The water the admission condenses is what cools the wall afterwards: at 0.42
cut-off on the bundled Meyer engine 70 % of it is still on the wall at release and
71 % of the heat comes back during the exhaust (as Spangler's Buckeye in Marks Art.
86: 0.39 of the steam missing at 0.3 of the stroke, 0.30 at 0.9).  The film boils
off before the surface reaches the exhaust's temperature (10 K above it at 16.7
psia, 44 K at 4 psia), so the water, not the exhaust's temperature, sets the
surface's lowest temperature, and the missing water is nearly flat against the
exhaust's temperature where Marks's eq. 221 rises (docs/validation/condensation.md
lists the changes to the film that were measured and not kept).

With ideal ports
----------------
Without ``port_flow`` the same wall steps beside the ideal-port model
(:class:`IdealPortWall`, :mod:`corliss.engine.equilibrium`).

Jackets
-------
A jacket holds the outer face of the jacketed parts at its steam's saturation
temperature (by default the supply's; a compound's LP at its receiver's; or the
scene's ``jacket_pressure``, ``lp_jacket_pressure``); its heat reaches the deep node
through the wall's thickness, ``k / L`` per unit of jacketed area
(:func:`jacketed_area_m2`).  Each end's wall is one lumped area, cover, piston face
and the barrel the steam touches, ``2 A_p + pi D V / A_p`` (:func:`mean_exposed_area_m2`);
a barrel jacket covers the barrel's mean share ``pi D mean(V) / A_p``, a cover jacket
the cover's face ``A_p``.  The piston's face is never jacketed: it moves, and no steam
can be led to it (Marks Art. 79: the heads, that is the covers, are usually not
jacketed, but may be).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from corliss.engine.condensation import exposed_wall_m2
from corliss.engine.kernels.data import WALL_SKIN
from corliss.engine.kernels.walls import (FILM_MAX_KG_M2, FILM_WET_KG_M2,
                                          INFLOW_SWEEP_PER_RAD, adair_h, condensing_share,
                                          film_water, skin_coefficients,
                                          steam_at_wall_superheat)
from corliss.thermo.wall_cycle import CALLENDAR_NICOLSON_W_M2K

#: Grey cast iron (makeitfrom.com, "Grey Cast Iron"): conductivity [W/(m K)], specific
#: heat [J/(kg K)], density [kg/m3].
CAST_IRON_K, CAST_IRON_C, CAST_IRON_RHO = 46.0, 490.0, 7500.0
#: Coefficient of condensation and evaporation on the surface [W/(m2 K)]: Callendar and
#: Nicolson's, 4 kcal/(s m2 degC) (DPJ 312, 1899, p. 164; see the module docstring).
CONDENSING_W_M2K = CALLENDAR_NICOLSON_W_M2K
#: The parts each ``engine.jacket`` covers: (barrel, covers).
JACKET_PARTS = {"none": (False, False), "barrel": (True, False), "covers": (False, True),
                "barrel_and_covers": (True, True)}
#: Skin-model columns of a node's wall-heat row (after code, h_c, k, mu, Pr).
COL_CAPACITY, COL_CONDUCTANCE, COL_AREA, COL_STATE, COL_JACKET_GA, COL_JACKET_T = 5, 6, 7, 8, 9, 10


def skin_depth_m(omega_rad_s: float, k: float = CAST_IRON_K, c: float = CAST_IRON_C,
                 rho: float = CAST_IRON_RHO) -> float:
    """Depth [m] at which the cycle's temperature wave falls to 1/e,
    sqrt(2 alpha / omega) (Carslaw & Jaeger sec. 2.6).

    Parameters
    ----------
    omega_rad_s : float
        The wave's angular frequency [rad/s].
    k, c, rho : float
        The wall's conductivity [W/(m K)], specific heat [J/(kg K)] and density
        [kg/m3] (grey cast iron by default).

    Returns
    -------
    float
        The skin depth [m].
    """
    return math.sqrt(2.0 * k / (rho * c) / omega_rad_s)


def surface_node(omega_rad_s: float) -> tuple[float, float]:
    """The lumped surface node that has a semi-infinite cast-iron wall's impedance at
    ``omega_rad_s``.

    Parameters
    ----------
    omega_rad_s : float
        The engine's angular speed [rad/s].

    Returns
    -------
    tuple of float
        Areal capacity [J/(m2 K)] and conductance to the deep wall [W/(m2 K)].
    """
    d = skin_depth_m(omega_rad_s)
    return CAST_IRON_RHO * CAST_IRON_C * d / 2.0, CAST_IRON_K / d


def nusselt_film_W_m2K(rho_l: float, rho_v: float, h_fg: float, k_l: float, mu_l: float,
                       height_m: float, dT_K: float, g: float = 9.80665) -> float:
    """Nusselt's mean coefficient of laminar film condensation on a vertical surface
    (Z. VDI 60, 1916).

    Parameters
    ----------
    rho_l, rho_v : float
        Densities of the water and the vapour [kg/m3].
    h_fg : float
        Latent heat [J/kg].
    k_l, mu_l : float
        The water's conductivity [W/(m K)] and viscosity [Pa s].
    height_m : float
        The surface's height [m].
    dT_K : float
        Saturation less surface temperature [K].
    g : float
        Gravity [m/s2].

    Returns
    -------
    float
        The mean coefficient [W/(m2 K)].
    """
    return 0.943 * (rho_l * (rho_l - rho_v) * g * h_fg * k_l ** 3
                    / (mu_l * height_m * dT_K)) ** 0.25


def mean_exposed_area_m2(geometry, end: int, n: int = 361) -> float:
    """The wall one end's steam touches, averaged over the cycle (the area of
    :func:`corliss.engine.condensation.exposed_wall_m2`).

    Parameters
    ----------
    geometry : CylinderGeometry
        The cylinder's geometry.
    end : int
        0 head, 1 crank.
    n : int
        Points over the cycle.

    Returns
    -------
    float
        The mean area [m2].
    """
    th = np.linspace(0.0, 2.0 * math.pi, n)
    return float(np.mean(exposed_wall_m2(geometry, end, th)))


def jacketed_area_m2(geometry, end: int, jacket: str) -> float:
    """The area of one end's wall that a jacket covers [m2].

    The end's wall is one lumped area, ``2 A_p + pi D V / A_p`` (cover, piston face and
    the barrel the steam touches, the clearance as its equivalent length); the barrel's
    share over a cycle is ``pi D mean(V) / A_p`` and the cover's ``A_p`` (the crank
    end's cover an annulus round the rod, as its piston face).  The piston's face is
    never jacketed.  So ``"barrel"`` gives ``pi D mean(V) / A_p``, ``"covers"`` ``A_p``,
    ``"barrel_and_covers"`` their sum and ``"none"`` zero.

    Parameters
    ----------
    geometry : CylinderGeometry
        The cylinder's geometry.
    end : int
        0 head, 1 crank.
    jacket : str
        ``"none"``, ``"barrel"``, ``"covers"`` or ``"barrel_and_covers"``.

    Returns
    -------
    float
        The jacketed area [m2].
    """
    if jacket not in JACKET_PARTS:
        raise ValueError(f"jacket {jacket!r}: one of {', '.join(JACKET_PARTS)}")
    ap = geometry.area_head_m2 if end == 0 else geometry.area_crank_m2
    barrel, covers = JACKET_PARTS[jacket]
    area = ap if covers else 0.0
    if barrel:
        th = np.linspace(0.0, 2.0 * math.pi, 361)
        area += math.pi * geometry.spec.bore_m * float(np.mean(geometry.volumes_m3(th)[end])) / ap
    return area


def skin_row(geometry, end: int, omega_rad_s: float, h_c: float, steam_props,
             state_index: int, jacket_T_K: float | None = None,
             wall_thickness_m: float = 0.025, jacket: str = "barrel") -> tuple:
    """A node's wall-heat row for the skin model (columns as
    :data:`corliss.engine.network.HEAT_COLUMNS`, less the film's two).

    Parameters
    ----------
    geometry : CylinderGeometry
        The cylinder's geometry.
    end : int
        0 head, 1 crank.
    omega_rad_s : float
        Shaft speed [rad/s].
    h_c : float
        Coefficient of condensation and evaporation [W/(m2 K)].
    steam_props : tuple of float
        The vapour's conductivity [W/(m K)], viscosity [Pa s] and Prandtl number [-].
    state_index : int
        Index of the surface's state in the kernel's state vector.
    jacket_T_K : float, optional
        The jacket's temperature [K], or None.
    wall_thickness_m : float
        The wall between bore (or cover's face) and jacket [m].
    jacket : str
        The parts jacketed (:func:`jacketed_area_m2`), with ``jacket_T_K``.

    Returns
    -------
    tuple
        The row's first eleven columns.
    """
    k, mu, pr = steam_props
    cap, cond = surface_node(omega_rad_s)
    area = mean_exposed_area_m2(geometry, end)
    ga, tj = 0.0, 0.0
    if jacket_T_K is not None:
        ga = CAST_IRON_K / wall_thickness_m * jacketed_area_m2(geometry, end, jacket)
        tj = jacket_T_K
    return (WALL_SKIN, h_c, k, mu, pr, cap, cond, area, float(state_index), ga, tj)


def jacket_pressures_Pa(supply_Pa: float, exhaust_Pa: float, compound: bool,
                        hp_Pa: float | None = None, lp_Pa: float | None = None) -> tuple:
    """The pressure of each cylinder's jacket steam: the scene's, or by default these.

    The high-pressure (or only) cylinder's jacket takes the supply's steam; a
    compound's low-pressure cylinder's takes its own receiver's, at the receiver's
    starting pressure, the geometric mean of supply and exhaust (the network's
    :func:`corliss.engine.network.compound`).  A jacket at the supply's saturation on
    the LP cylinder, far hotter than its own steam, removed nearly all its condensation
    (0.30 of its supply to 0.007 on the bundled compound), which is not the period's
    practice (Marks Art. 79: the jacket's steam from the boiler on the first cylinder;
    Lineham: 10 to 20 % saved).

    Parameters
    ----------
    supply_Pa : float
        The supply's pressure [Pa].
    exhaust_Pa : float
        The exhaust's pressure [Pa].
    compound : bool
        Whether the engine is a compound (two cylinders, HP then LP).
    hp_Pa, lp_Pa : float, optional
        The scene's ``jacket_pressure`` and ``lp_jacket_pressure`` [Pa]; None: the
        defaults above.

    Returns
    -------
    tuple of float
        One pressure per cylinder [Pa].
    """
    hp = supply_Pa if hp_Pa is None else hp_Pa
    if compound:
        return (hp, math.sqrt(supply_Pa * exhaust_Pa) if lp_Pa is None else lp_Pa)
    return (hp,)


#: Nodes of the conduction grid under the surface (:class:`ConductionGrid`) [-].
GRID_NODES = 14
#: Depth of the grid's held node, in skin depths at the engine's frequency [-].
GRID_DEPTH_SKINS = 3.0
#: The surface cell's thickness, in skin depths [-]: 2.5 % of delta (31 microns at 150
#: rpm), which a step change at the surface crosses in about 0.1 ms.
GRID_FIRST_SKINS = 0.025


class ConductionGrid:
    """One-dimensional conduction through the wall under the surface: the surface's
    answer to short events as well as to the cycle's fundamental.

    Why a grid: the lumped node (:func:`surface_node`) has the semi-infinite wall's
    impedance at the cycle's frequency only.  The exhaust's evaporation and the
    admission's condensation are short events; a semi-infinite wall answers a step
    ``dT`` of its surface with the heat ``2 dT sqrt(k rho c t / pi)`` per unit area
    after a time ``t`` (Carslaw & Jaeger, Conduction of Heat in Solids, 2nd ed. 1959,
    sec. 2.5), through a layer of depth ``sqrt(alpha t)`` much thinner than the skin
    depth, whereas the lumped node must move its whole capacity ``rho c delta / 2`` at
    once.

    The discretisation: nodes at depths ``x_0 = 0 < x_1 < ... < x_n``, spaced
    geometrically, ``x_{i+1} - x_i = d_1 r^i`` with ``d_1`` :data:`GRID_FIRST_SKINS` skin depths and
    ``r`` such that ``x_n`` is :data:`GRID_DEPTH_SKINS` skin depths; the deepest node is
    held at the deep wall's temperature (the cycle's wave is ``e^{-3}``, 5 %, there).
    Node ``i`` owns the iron half-way to its neighbours (the surface node half its first
    cell), areal capacity ``C_i = rho c (d_i + d_{i+1}) / 2``, and the cells conduct
    ``g_i = k / d_{i+1}`` between nodes ``i`` and ``i+1``.  Backward Euler over a step
    ``dt``, for the interior nodes::

        C_i (T_i' - T_i) / dt = g_{i-1} (T_{i-1}' - T_i') + g_i (T_{i+1}' - T_i'),

    and for the surface ``C_0 (T_0' - T_0) / dt = -q + g_0 (T_1' - T_0')`` with ``q``
    the heat into the steam per unit area.  Eliminating from the held node upwards
    (Thomas's algorithm), ``T_i' = a_i + b_i T_{i-1}'`` with::

        D_i = C_i / dt + g_{i-1} + g_i (1 - b_{i+1}),
        a_i = (C_i T_i / dt + g_i a_{i+1}) / D_i,     b_i = g_{i-1} / D_i,

    starting from ``a_n = T_deep``, ``b_n = 0``; the surface is then a lumped node of
    capacity ``C_0`` joined by ``g_0 (1 - b_1)`` to the temperature
    ``a_1 / (1 - b_1)`` (:meth:`surface_terms`), and once its new temperature is found
    the rest follows (:meth:`advance`).  Backward Euler is stable at any step and its
    error is first order in ``dt``; the test
    ``test_the_conduction_grid_has_the_semi_infinite_walls_periodic_response`` compares
    the grid's flux with Carslaw & Jaeger's sec. 2.6,
    ``q = sqrt(k rho c omega) e^{i pi/4} theta_s``.

    Parameters
    ----------
    omega_rad_s : float
        The engine's angular speed [rad/s] (sets the skin depth).
    nodes : int
        Nodes including the surface and the held node [-].
    k, c, rho : float
        The wall's conductivity [W/(m K)], specific heat [J/(kg K)] and density
        [kg/m3].
    """

    def __init__(self, omega_rad_s: float, nodes: int = GRID_NODES, k: float = CAST_IRON_K,
                 c: float = CAST_IRON_C, rho: float = CAST_IRON_RHO):
        delta = skin_depth_m(omega_rad_s, k, c, rho)
        n = nodes - 1
        d1, depth = GRID_FIRST_SKINS * delta, GRID_DEPTH_SKINS * delta
        lo, hi = 1.0 + 1e-9, 4.0          # r with d1 (r^n - 1) / (r - 1) = depth
        for _ in range(200):
            r = 0.5 * (lo + hi)
            if d1 * (r ** n - 1.0) / (r - 1.0) > depth:
                hi = r
            else:
                lo = r
        widths = [d1 * r ** i for i in range(n)]
        #: the nodes' depths [m]
        self.x_m = [0.0]
        for w in widths:
            self.x_m.append(self.x_m[-1] + w)
        #: areal capacities of nodes 0 .. n-1 [J/(m2 K)]
        self.C = [rho * c * 0.5 * widths[0]] + [
            rho * c * 0.5 * (widths[i - 1] + widths[i]) for i in range(1, n)]
        #: conductances between node i and i+1 [W/(m2 K)]
        self.g = [k / w for w in widths]
        #: the nodes' temperatures less the held node's [K] (0 .. n-1)
        self.theta = [0.0] * n
        #: the elimination's (a, b) of each node, set by :meth:`surface_terms`
        self._ab: list[tuple[float, float]] = []

    def surface_terms(self, dt: float) -> tuple[float, float, float]:
        """The surface's lumped equivalent over a step, from the grid below it.

        Parameters
        ----------
        dt : float
            The step [s].

        Returns
        -------
        tuple of float
            The surface's areal capacity over the step, ``C_0 / dt`` [W/(m2 K)], its
            conductance to the grid ``g_0 (1 - b_1)`` [W/(m2 K)], and the temperature
            it is joined to, less the held node's [K].
        """
        n = len(self.theta)
        a, b = 0.0, 0.0
        ab = [(0.0, 0.0)] * n           # node 0's pair is never read
        for i in range(n - 1, 0, -1):
            cd = self.C[i] / dt
            D = cd + self.g[i - 1] + self.g[i] * (1.0 - b)
            a = (cd * self.theta[i] + self.g[i] * a) / D
            b = self.g[i - 1] / D
            ab[i] = (a, b)
        self._ab = ab
        g_eff = self.g[0] * (1.0 - b)
        return self.C[0] / dt, g_eff, (self.g[0] * a / g_eff if g_eff > 0.0 else 0.0)

    def advance(self, theta0: float) -> None:
        """Set the surface's new temperature and carry the step through the grid
        (after :meth:`surface_terms` for the same step).

        Parameters
        ----------
        theta0 : float
            The surface's new temperature less the held node's [K].
        """
        self.theta[0] = theta0
        for i in range(1, len(self.theta)):
            a, b = self._ab[i]
            self.theta[i] = a + b * self.theta[i - 1]


class IdealPortWall:
    """The skin wall of one cylinder end for the ideal-port model (no ``port_flow``).

    With ideal ports (:mod:`corliss.engine.equilibrium`) an end open to the chest is at
    chest pressure whatever the wall takes: the steam the wall condenses during
    admission is made up from the chest, as the textbook's cylinder takes it (Marks
    Art. 74: the steam condensed at admission is supplied steam that never shows on the
    card).  The stepping splits each step of the grid in two: first the wall exchanges
    heat and water with the steam over the step's time ``dt = d(theta) / omega`` (the
    same flows as the compiled kernel's, :func:`corliss.engine.kernels.balances.balances`), then
    the ports act (isentropic while closed; at the reservoir's pressure while open).

    The exchange over a step, per end (``A`` the wall the steam touches now, ``A_w``
    its mean, ``C`` and ``G`` the surface node's areal capacity and conductance to the
    deep wall at ``T_d``):

    * the surface, backward Euler with the coefficients of the step's start (the
      surface's own time constant, ``C / h_c``, is a few milliseconds against steps
      of a tenth of one; with a :class:`ConductionGrid`, ``C`` is its surface cell's,
      and ``G`` and ``T_d`` the grid's equivalent over the step,
      :meth:`ConductionGrid.surface_terms`)::

          C A_w (T_w' - T_w) / dt = -(h_f + h_m)(T_w' - T_sat) A - h_v (T_w' - T) A
                                    + G A_w (T_d - T_w');

    * the film: ``m_f' = m_f - q_f dt / lat`` with ``q_f = h_f (T_w' - T_sat) A``, and
      never below nothing (the evaporation is then what the film held, and the surface
      is solved again with that heat); likewise the mixture's water ``q_m`` boils at
      most what the steam holds, and while closed at most half the steam condenses in
      a step (at 10 rpm a step is 4 ms, against the surface's few milliseconds);
    * the steam: its mass changes by the film's loss, ``dm = q_f dt / lat``, and its
      energy by ``dm h_L + (q_f + q_m + q_v) dt``, ``h_L`` and ``L`` the film's water
      at the surface's temperature at the step's start (condensing, the steam gives
      up its own enthalpy, ``lat = h - h_L``; evaporating, the vapour has
      ``h_L + L``); the film's own warming is the surface's (``C A_w`` above is
      ``C A_w + m_f c_f``), so that steam, film and wall close as in the kernel.
      Closed, the steam's new state is found from its density and internal energy.
      Open, the end stays at the reservoir's pressure and the port's step takes the
      wall's mass and enthalpy with its own flow: ``d(m h) = dm h_L + Q + h_res
      dm_port`` at constant pressure, the end
      filled or emptied to its volume, so that the chest makes up at once whatever
      the wall condenses, even more than the end held.

    Water beyond the film the wall holds (``FILM_MAX_KG_M2``) runs into the steam, and
    while the steam flows out the film beyond ``FILM_WET_KG_M2`` goes with it in the
    proportion of the steam leaving (:meth:`sweep`), as in the kernel, taken with the
    exchange of the step after an open step's outflow; a blow-down sweeps as it goes,
    so that part of the water swept leaves with the rest of the steam, as through
    ports (:func:`corliss.engine.equilibrium.step_end`).

    Parameters
    ----------
    row : tuple
        The end's skin row (:func:`skin_row`, the film's ``(h_L, L)`` and the
        supply's superheat [K]).
    geometry : CylinderGeometry
        The cylinder's geometry (the exposed wall from the volume).
    end : int
        0 head, 1 crank.
    omega_rad_s : float
        Shaft speed [rad/s].
    T_deep_K : float
        The deep wall's starting temperature [K].
    grid_nodes : int, optional
        Nodes of a :class:`ConductionGrid` under the surface in place of the lumped
        node's conductance to the deep wall (the surface keeps the grid's first cell's
        capacity), or None for the lumped node, the compiled kernel's wall.  On the
        bundled Meyer engine the two give the same missing water to 0.01 of the steam
        (docs/validation/condensation.md).
    """

    def __init__(self, row, geometry, end: int, omega_rad_s: float, T_deep_K: float,
                 grid_nodes: int | None = None):
        (_, self.h_c, self.k, self.mu, self.pr, self.cap, self.cond, self.area_mean,
         _, self.ga, self.T_jacket, self.h_L, self.L, self.supply_superheat) = row
        self.a_p = geometry.area_head_m2 if end == 0 else geometry.area_crank_m2
        self.bore = geometry.spec.bore_m
        self.omega = omega_rad_s
        self.T_deep = T_deep_K
        self.dT = 0.0          # the surface less the deep wall [K]
        self.film = 0.0        # the film's water [kg]
        #: the share of the steam the last open step let out [-] (its sweep is taken at
        #: the next step's start, :meth:`exchange`)
        self.outflow = 0.0
        #: heat [J] of water swept (its enthalpy above ``h_L``) not yet in the steam
        self.swept_heat = 0.0
        #: the deep wall's search (:class:`DeepWallSearch`)
        self.search = DeepWallSearch()
        #: the conduction grid under the surface, or None for the lumped node
        self.grid = ConductionGrid(omega_rad_s, grid_nodes) if grid_nodes else None
        self.begin_cycle()

    def begin_cycle(self) -> None:
        """Restart the cycle's quadratures and records."""
        self.Q = self.Q_to_wall = self.Q_sat = self.Q_conv = self.hA = 0.0
        self.records: list[tuple[float, ...]] = []

    def record(self) -> None:
        """Keep the surface temperature [K], the film [kg] and the heats so far [J]."""
        self.records.append((self.T_deep + self.dT, self.film, self.Q, self.Q_sat,
                             self.Q_conv))

    def exchange(self, steam, st, m: float, V: float, dt: float, open_: bool,
                 entering=None):
        """Exchange heat and water with the steam over ``dt`` [s].

        Parameters
        ----------
        steam : Steam
            The property tier.
        st : State
            The steam's state at the step's start.
        m : float
            The steam's mass [kg].
        V : float
            The end's volume [m3].
        dt : float
            The step's time [s].
        open_ : bool
            Open to a reservoir: the pressure is held, and what the steam gains is
            returned for the port's step to take with its own flow
            (:func:`corliss.engine.equilibrium.step_end`); closed, the volume is held
            and the steam's new state found from density and internal energy.
        entering : State, optional
            The steam entering through the open port (the chest's), which sweeps the
            wall and is the steam at it
            (:func:`~corliss.engine.kernels.walls.steam_at_wall_superheat`); None
            when none enters.

        Returns
        -------
        tuple
            The steam's state and mass [kg] (closed: after the exchange; open: as
            given), and the mass [kg] and enthalpy [J] the steam takes from the wall
            and film that the port's step is still to add (zero when closed).
        """
        dm_sw = 0.0
        if self.outflow > 0.0:
            # the film swept by the last step's outflow, into the steam as water of
            # the film's enthalpy
            dm_sw = self.sweep(self.outflow)
            self.outflow = 0.0
        A = 2.0 * self.a_p + math.pi * self.bore * V / self.a_p
        Aw = self.area_mean
        Tw = self.T_deep + self.dT
        # the film's water at the surface's temperature, at the step's start (the
        # kernel's film_water); the film's own heat moves with the surface
        h_fw, c_fw, L = film_water(Tw)
        T = st.T
        x = 1.0 if st.superheated else st.x
        Tsat = steam.t_sat(st.p) if st.superheated else T
        # the wall's laws, the compiled balances' own (corliss.engine.kernels.walls)
        hv = adair_h(float(st.rho), self.omega, V, A, self.mu, self.k, self.pr)
        sweep = INFLOW_SWEEP_PER_RAD * m if entering is not None else 0.0
        sup = steam_at_wall_superheat(T, Tsat, float(x), self.L, st.h,
                                      entering.h if entering is not None else 0.0, sweep, m)
        share = condensing_share(min(float(sup), self.supply_superheat))
        hf, hm = skin_coefficients(Tw, Tsat, self.h_c, float(self.film), Aw, float(x), share)
        lat_c = max(st.h - h_fw, 0.5 * L)     # condensing, per kg [J/kg]
        # the surface, backward Euler; a flow that would take more than there is
        # within the step (the film's water boiling off, the mixture's water, or,
        # while closed, half the steam condensing) is held at that and the surface
        # solved again with it fixed
        if self.grid is not None:
            c0, g0, th1 = self.grid.surface_terms(dt)
            cA, gA, T_under = c0 * Aw, g0 * Aw, self.T_deep + th1
        else:
            cA, gA, T_under = self.cap * Aw / dt, self.cond * Aw, self.T_deep
        cA += self.film * c_fw / dt
        limits = {"f": (hf, Tsat, self.film * L / dt if Tw > Tsat
                        else (-0.5 * m * lat_c / dt if not open_ else -math.inf)),
                  "m": (hm, Tsat, (1.0 - x) * m * L / dt),
                  "c": (hv, T, None)}
        fixed: dict[str, float] = {}
        for _ in range(3):
            num, den = cA * Tw + gA * T_under, cA + gA
            for key, (h, t, _cap) in limits.items():
                if key in fixed:
                    num -= fixed[key]
                else:
                    num += h * A * t
                    den += h * A
            Tw1 = num / den
            flows = {key: fixed.get(key, h * (Tw1 - t) * A)
                     for key, (h, t, _cap) in limits.items()}
            over = [key for key, (h, t, cap) in limits.items() if key not in fixed
                    and cap is not None and (flows[key] > cap if cap >= 0.0 else flows[key] < cap)]
            if not over:
                break
            for key in over:
                fixed[key] = limits[key][2]
        qf, qm, qc = flows["f"], flows["m"], flows["c"]
        dm = qf * dt / (L if qf >= 0.0 else lat_c)
        self.film -= dm
        run = max(self.film - FILM_MAX_KG_M2 * Aw, 0.0)
        self.film -= run
        dm += run
        # the heat into the steam counts its water from the row's reference h_L, as
        # the kernel's (the sweep's counted in :meth:`sweep`)
        q = (qf + qm + qc) * dt + dm * (h_fw - self.h_L)
        dm += dm_sw
        self.dT = Tw1 - self.T_deep
        if self.grid is not None:
            self.grid.advance(self.dT)
        self.Q += q
        self.Q_to_wall += -q if q < 0.0 else 0.0
        self.Q_sat += (qf + qm) * dt
        self.Q_conv += qc * dt
        self.hA += ((hf + hm + hv) * A + self.ga) * dt
        dH = dm * self.h_L + q + self.take_swept_heat()
        if open_:
            return st, m, dm, dH
        m1 = m + dm
        return steam.du(m1 / V, (m * st.u + dH) / m1), m1, 0.0, 0.0

    def sweep(self, share: float) -> float:
        """Sweep the film beyond the drops that cling while the share ``share`` [-] of
        the end's steam leaves.

        Parameters
        ----------
        share : float
            The share of the end's steam that left [-].

        Returns
        -------
        float
            The water swept off the wall into the steam [kg].
        """
        extra = self.film - FILM_WET_KG_M2 * self.area_mean
        if not (extra > 0.0 and share > 0.0):
            return 0.0
        sw = extra * min(share, 1.0)
        self.film -= sw
        # water at the surface's temperature: its enthalpy above the reference h_L
        # is heat into the steam (kept for the next exchange's, or the blow-down's,
        # energy: :attr:`swept_heat`)
        dq = sw * (self.h_film - self.h_L)
        self.Q += dq
        if dq < 0.0:
            self.Q_to_wall -= dq
        self.swept_heat += dq
        return sw

    def take_swept_heat(self) -> float:
        """The swept water's heat [J] not yet given to the steam (:meth:`sweep`), now
        given.

        Returns
        -------
        float
            The heat: the swept water's enthalpy above ``h_L`` [J].
        """
        q, self.swept_heat = self.swept_heat, 0.0
        return q

    @property
    def h_film(self) -> float:
        """The film's water now: saturated water at the surface's temperature [J/kg]."""
        h_f, _, _ = film_water(self.T_deep + self.dT)
        return h_f

    def deep_step(self, apply: bool, heat_scale: float = 0.0, dT_scale: float = 0.0,
                  trusted: bool = True) -> tuple[float, float]:
        """The deep wall's step on its balance over the cycle just run,
        ``r = -Q + G_j A_j P max(T_j - T_d, 0)`` (:class:`DeepWallSearch`, as the
        crank-resolved runner's,
        :meth:`corliss.engine.crank_resolved.CrankResolved.update_wall`).

        Parameters
        ----------
        apply : bool
            Take the step (else only measure it).
        heat_scale : float
            The imbalance's scale [J]; 0 for the wall's own, the heat the steam gave
            it over the cycle.
        dT_scale : float
            The temperature scale [K] against which the bracket's width counts as an
            imbalance (:meth:`DeepWallSearch.imbalance`); 0 for none.
        trusted : bool
            Whether the rest of the cycle was periodic to the tolerance
            (:meth:`DeepWallSearch.step`).

        Returns
        -------
        tuple of float
            The step [K] and the imbalance [-].
        """
        gap = self.ga * 2.0 * math.pi / self.omega
        step, r = self.search.step(self.T_deep, self.Q, self.hA - gap, gap, self.T_jacket,
                                   apply, trusted)
        imbalance = self.search.imbalance(r, heat_scale or self.Q_to_wall, dT_scale)
        if apply:
            # the surface moves with the deep wall (its state is the difference, as
            # the kernel's)
            self.T_deep += step
        return step, imbalance


def jacket_heat_J(gap_J_K: float, T_jacket_K: float, T_deep_K: float) -> float:
    """The heat a jacket gives the deep wall over a cycle [J].

    ``G_j A_j P (T_j - T_d)`` where the deep wall is below the jacket's saturation
    temperature, else nothing: the jacket gives heat by condensing its steam on the
    iron (Marks Art. 79), and an outer face hotter than the steam's saturation
    condenses none.  The heat the iron would then give the jacket's steam, by
    convection to a vapour that is not renewed (the jacket is fed only as its steam
    condenses), is left out, so a jacket at or below the wall's own temperature, one at
    the exhaust's pressure, does nothing.

    Parameters
    ----------
    gap_J_K : float
        The jacket's conductance over the cycle, ``G_j A_j P`` [J/K] (0 without one).
    T_jacket_K : float
        The jacket steam's saturation temperature [K].
    T_deep_K : float
        The deep wall's temperature over the cycle [K].

    Returns
    -------
    float
        The heat into the wall [J], zero or more.
    """
    return gap_J_K * max(T_jacket_K - T_deep_K, 0.0)


@dataclass(frozen=True)
class WallJump:
    """A deep wall's balance over a cycle that changes sign across a band without a
    root: the warmest wall measured to gain heat over a cycle and the coolest measured
    to lose it, each balance larger than the tolerance and their difference larger
    than any continuous balance could change across the band
    (:meth:`DeepWallSearch.jump`).  On a superheated supply with the skin wall, a wet
    state of the film below the band and a dry one above it
    (docs/validation/condensation.md, "Superheated walls that do not settle").

    Parameters
    ----------
    T_low_K : float
        The band's cool edge, the warmest wall measured to gain heat [K].
    T_high_K : float
        The band's warm edge, the coolest wall measured to lose heat [K].
    balance_low_J : float
        The heat the wall kept over the cycle at ``T_low_K``, ``r > 0`` [J].
    balance_high_J : float
        The heat the wall kept over the cycle at ``T_high_K``, ``r < 0`` [J].
    """

    T_low_K: float
    T_high_K: float
    balance_low_J: float
    balance_high_J: float


#: How many tolerances of the wall's heat each edge of a jump must exceed
#: (:meth:`DeepWallSearch.jump`): the runner trusts a cycle whose other states are
#: within one tolerance of periodic, and the wall's balance on such cycles still
#: differs by some of them at one temperature (the Meyer engine with the skin wall
#: through 4 times its ports, fast preset: +20 J and -20 J within 1e-13 K, 1.6
#: tolerances of its 12.6 kJ), noise the bracket's width was made to absorb.
JUMP_TOLERANCES = 10.0

#: The summary's ``wall_periodic_state`` where a deep wall's balance jumps
#: (:class:`WallJump`).
NO_PERIODIC_STATE_JUMP = "none: the balance jumps"


def wall_jump_text(jumps: dict[str, WallJump]) -> str:
    """The words a run whose deep walls' balances jump says in its warning.

    Parameters
    ----------
    jumps : dict
        End name to its :class:`WallJump`.

    Returns
    -------
    str
        One sentence, each end's jump in it: the balances [J] and the band [K].
    """
    each = "; ".join(f"{end} end: its balance over a cycle jumps from "
                     f"{j.balance_low_J:+,.0f} J to {j.balance_high_J:+,.0f} J between "
                     f"{j.T_low_K:.2f} and {j.T_high_K:.2f} K"
                     for end, j in jumps.items())
    return (f"no periodic state of the wall: {each} (a wet and a dry state of the film); "
            "more cycles will not settle it")


class DeepWallSearch:
    """The deep wall's temperature, found cycle by cycle: the root of its balance over
    a cycle, ``r(T) = -Q(T) + G_j A_j P max(T_j - T, 0)`` (the heat the steam leaves in
    the wall, and the jacket's through its thickness, :func:`jacket_heat_J`), by a
    secant held inside a bracket.

    The first step uses the slope the kernel integrates (every coefficient's ``h A``),
    which overstates it, since water condensed on a cooler wall evaporates from it later
    in the same cycle; then the slope of the last two steps taken, kept between a
    hundredth and all of that one, steps of 20 K at most.  The balance has a kink where
    the surface's cycle starts or stops crossing the saturation temperature (a
    superheated supply: condensing at ``h_c`` below it, convection's few hundred W/(m2
    K) above), and there a secant alone wanders.  So each measured sign narrows a
    bracket, ``lo`` the warmest wall found to gain heat over a cycle, ``hi`` the
    coolest found to lose it, and a step that would leave the bracket goes halfway to
    its edge instead (bisection).  A cycle measured before it was quite periodic may
    give the wrong sign near the root: a measurement that contradicts an edge (a gain
    at or above ``hi``, a loss at or below ``lo``) drops that edge, so that the bracket
    never closes on noise.

    Each edge keeps the balance measured there and the largest slope a continuous
    balance could have there (the kernel's ``h A``, and the jacket's): where the two
    edges' balances differ by more than that slope carries across the bracket, the
    bracket holds a jump, not a root, and its width no longer counts as the wall's
    imbalance (:meth:`imbalance`, :meth:`jump`).  The steps are the same either way.
    """

    def __init__(self) -> None:
        #: the last step's (temperature [K], heat into the steam [J]), or None
        self.prev: tuple[float, float] | None = None
        #: the bracket [K]
        self.lo, self.hi = -math.inf, math.inf
        #: the balance [J] and the largest slope [J/K] measured at each edge (nan at
        #: an open one)
        self.edges = ((math.nan, math.nan), (math.nan, math.nan))
        self.measured = (self.lo, self.hi)
        #: the edges with the last measurement, kept or not
        self.measured_edges = self.edges
        #: the heat scale of the last imbalance asked [J]
        self.heat_scale = 0.0

    def _bracket(self, T: float, r: float, slope: float):
        lo, hi = self.lo, self.hi
        e_lo, e_hi = self.edges
        none = (math.nan, math.nan)
        if r > 0.0:
            if T >= hi:
                hi, e_hi = math.inf, none
            if T >= lo:
                lo, e_lo = T, (r, slope)
        elif r < 0.0:
            if T <= lo:
                lo, e_lo = -math.inf, none
            if T <= hi:
                hi, e_hi = T, (r, slope)
        return lo, hi, (e_lo, e_hi)

    def _jumps(self) -> bool:
        """Whether the measured bracket's edges differ by more than a continuous balance
        could change across it (a jump, not a root)."""
        lo, hi = self.measured
        (r_lo, d_lo), (r_hi, d_hi) = self.measured_edges
        if not (math.isfinite(lo) and math.isfinite(hi)):
            return False
        return r_lo - r_hi > max(d_lo, d_hi) * (hi - lo)

    def step(self, T: float, Q: float, d_full: float, gap: float, T_jacket: float,
             apply: bool, trusted: bool = True) -> tuple[float, float]:
        """The step from the cycle just run at ``T``.

        Parameters
        ----------
        T : float
            The deep wall's temperature over the cycle [K].
        Q : float
            The heat into the steam over the cycle [J].
        d_full : float
            The cycle's integrated ``h A`` of the steam's coefficients [J/K].
        gap : float
            The jacket's ``G_j A_j P`` over the cycle [J/K] (0 without one).
        T_jacket : float
            The jacket's temperature [K].
        apply : bool
            Keep the measurement (the step is taken); else only measure.
        trusted : bool
            Whether the rest of the cycle was periodic to the tolerance, so that the
            balance's sign may narrow the bracket (the runners step the wall once the
            rest is within ten tolerances; a cycle just after a step, the surface
            still moving by up to a hundredth of the temperature scale a cycle, gave
            the crank end of the Meyer engine with ideal ports the wrong sign 1.5 K
            from the root).

        Returns
        -------
        tuple of float
            The step [K] and the balance ``r`` [J].
        """
        # the jacket gives heat only by condensing its steam: an outer face hotter than
        # the jacket's saturation condenses none, and the jacket then takes no heat
        # (jacket_heat_J)
        r = -Q + jacket_heat_J(gap, T_jacket, T)
        slope = d_full
        if self.prev is not None and abs(T - self.prev[0]) > 1e-9:
            slope = min(max((Q - self.prev[1]) / (T - self.prev[0]), 0.01 * d_full), d_full)
        step = min(max(r / (slope + (gap if T < T_jacket else 0.0)), -20.0), 20.0)
        lo, hi, edges = (self._bracket(T, r, d_full + (gap if T < T_jacket else 0.0))
                         if trusted else (self.lo, self.hi, self.edges))
        target = T + step
        if target >= hi:
            target = 0.5 * (T + hi)
        elif target <= lo:
            target = 0.5 * (T + lo)
        #: the bracket with this cycle's measurement (:meth:`imbalance`) [K]
        self.measured = (lo, hi)
        self.measured_edges = edges
        if apply:
            self.prev = (T, Q)
            self.lo, self.hi = lo, hi
            self.edges = edges
        return target - T, r

    def imbalance(self, r: float, heat_scale: float, dT_scale: float = 0.0) -> float:
        """The wall's imbalance as a fraction: ``|r|`` over ``heat_scale``, or the
        bracket's width over ``dT_scale`` where that is smaller (the root is then
        located to the tolerance in temperature, however the balance's kink or the
        cycles' noise leaves ``r``); where the bracket holds a jump (:meth:`jump`),
        the larger of its width's and its smaller edge's balance over
        :data:`JUMP_TOLERANCES` times ``heat_scale`` (a bracket closed across a jump
        locates no root); the bracket with the last measurement (:meth:`step`), kept
        or not.

        Parameters
        ----------
        r : float
            The balance over the cycle [J].
        heat_scale : float
            Its scale [J].
        dT_scale : float
            The temperature scale [K]; 0 for none.

        Returns
        -------
        float
            The imbalance [-].
        """
        self.heat_scale = heat_scale
        out = abs(r) / max(heat_scale, 1e-300)
        lo, hi = self.measured
        if dT_scale > 0.0 and math.isfinite(hi - lo):
            closed = (hi - lo) / dT_scale
            if self._jumps():
                # across a jump the bracket counts only while an edge's balance is
                # within the noise (JUMP_TOLERANCES): a jump larger locates no root
                (r_lo, _), (r_hi, _) = self.measured_edges
                closed = max(closed, min(r_lo, -r_hi)
                             / (JUMP_TOLERANCES * max(heat_scale, 1e-300)))
            out = min(out, closed)
        return out

    def jump(self, tolerance: float) -> WallJump | None:
        """The jump the bracket with the last measurement holds, if any: both edges
        measured, each edge's balance larger than :data:`JUMP_TOLERANCES` times
        ``tolerance`` of the heat scale (:meth:`imbalance`'s last, the noise of a
        trusted cycle's balance), and the two differing by more than the larger
        edge's slope (the kernel's ``h A``, an upper bound on a continuous balance's:
        the heat a cooler wall takes in condensing it partly gives back the same cycle)
        times the bracket's width.  Then no temperature in the bracket balances the
        wall, and more cycles will not find one; a bracket that has not closed decides
        it as well as a closed one, from its measured edges.

        Parameters
        ----------
        tolerance : float
            The run's periodicity tolerance [-].

        Returns
        -------
        WallJump or None
            The band and its edges' balances; None where the bracket is open, an edge
            balances to the tolerance, or a continuous balance could join the edges.
        """
        if not self._jumps():
            return None
        lo, hi = self.measured
        (r_lo, _), (r_hi, _) = self.measured_edges
        heat_tol = JUMP_TOLERANCES * tolerance * self.heat_scale
        if min(r_lo, -r_hi) <= heat_tol:
            return None
        return WallJump(lo, hi, r_lo, r_hi)
