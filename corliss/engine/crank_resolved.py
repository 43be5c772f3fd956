"""The crank-resolved filling-and-emptying model: a network integrated cycle by cycle.

The equations are those of :mod:`corliss.engine.network`, evaluated by
:func:`corliss.engine.kernels.balances.derivatives` whatever the property tier:

* a compiled tier (``table``, ``perfect``) with a compiled integrator (``dopri5``,
  ``rk4``, ``rosenbrock``): one compiled call integrates a whole cycle;
* otherwise scipy's ``solve_ivp`` (``LSODA`` and the rest) on a Python right-hand
  side; with ``heos`` that right-hand side asks CoolProp for each node's properties
  and hands them to the same compiled derivatives.

Integration stops at every kink of the port areas.

No state a run visits is clamped silently: the compiled integrators count the
evaluations that clamped a state to the range of the steam properties, apart for the
states the run visits (the ends of accepted steps) and for trial states (stages inside
a step, a Jacobian's probes, rejected steps); a visited state that needed a clamp
stops the run (:class:`~corliss.errors.RunError`, naming the scene quantity to look
at), and the trials are counted for the summary.  One exception, loud rather than
fatal: steam heated beyond the properties' energy (4.2 MJ/kg, about 1300 K), which
Marks's law of condensation does to the thin steam of the exhaust stroke (it returns
its heat whatever the steam left to take it); the run goes on at the edge of the
table, warns naming the quantity, and the summary counts those evaluations.  On the Python path (scipy's
integrators, which do not say which evaluations were trials) every clamped evaluation
is counted as a trial, and the run stops when a state of the accepted solution (the
samples) lies outside the range.
"""

from __future__ import annotations

import logging
import math

import numpy as np

from corliss.engine.kernels import (balances, cache, cycle, jacobians, mechanism, properties,
                                    stepping)
from corliss.engine.kernels.clamps import (CL_ACCEPTED, CL_ACCEPTED_CODE, CL_NODE,
                                           CL_REJECTED, CL_THETA)
from corliss.engine.kernels.data import (H_MODEL, H_SKIN_JACKET_G, H_SKIN_JACKET_T, WALL_NONE,
                                         WALL_SKIN)
from corliss.engine.network import Network
from corliss.engine.options import COMPILED_METHODS
from corliss.engine.wall import DeepWallSearch, WallJump
from corliss.errors import RunError
from corliss.thermo.steam import Steam
from corliss.thermo.steam_table import CLAMP_CODES, CLAMP_HIGH_ENERGY, kappa_at

log = logging.getLogger(__name__)

COMPILED_CODES = {"dopri5": 0, "rk4": 1, "rosenbrock": 2, "ros4": 3, "rodas3": 4, "rodas4": 5}


class CrankResolved:
    """Integrates a :class:`Network` on a property tier with one integrator.

    Parameters
    ----------
    network : Network
        The engine's control volumes and ports (its wall temperatures are updated by
        :meth:`update_wall`).
    steam : Steam
        The property tier.
    method : str
        A scipy method or a compiled one (which needs a compiled tier).
    rtol : float
        Relative tolerance [-]; absolute tolerances follow from the network's scales.
    step_deg : float
        Step of the fixed-step ``rk4`` [deg].
    arrays : NetworkArrays, optional
        ``network.arrays()`` when the caller has them already (the network unchanged
        since).

    Raises
    ------
    ValueError
        A compiled method on a tier without a compiled form (``heos``).
    """

    def __init__(self, network: Network, steam: Steam, method: str = "LSODA",
                 rtol: float = 1e-6, step_deg: float = 1.0, arrays=None):
        self.network = network
        self.steam = steam
        self.method = method
        self.rtol = rtol
        self.step = math.radians(step_deg)
        self.net = network.arrays() if arrays is None else arrays
        self.color, self.owner = network.column_colors()
        self.atol = rtol * network.scales()
        self.nfev = 0
        #: evaluations that clamped a trial state, over the run [-]
        self.clamped_trials = 0
        #: evaluations that clamped a visited state to the greatest energy, over the run [-]
        self.clamped_hot = 0
        #: the run-time budget of a cycle [right-hand-side evaluations]
        self.max_rhs = stepping.MAX_RHS_PER_CYCLE
        self.compiled = method in COMPILED_METHODS
        if self.compiled and steam.kernel_tier is None:
            raise ValueError(f"property tier {steam.name!r} has no compiled form")
        self._tier = steam.kernel_tier if steam.kernel_tier is not None else -1
        if self.compiled:
            cache.announce_compile(cycle=COMPILED_CODES[method],
                                    exact=jacobians.exact_jacobian_covers(self.net))
        else:
            cache.announce_compile(balances.rhs)
        from corliss.thermo.steam_table import load_table
        self._tab = steam.table.arrays() if hasattr(steam, "table") else load_table().arrays()
        self._perf = (np.array(steam.perfect_params()) if hasattr(steam, "perfect_params")
                      else np.zeros(3))
        self._pr = np.full((properties.PR_ROWS, network.n_nodes), np.nan)
        self._stops: dict[float, np.ndarray] = {}
        # the states each cycle restarts from zero: the quadratures, and the skin
        # walls' heat quadratures (their other states carry on)
        self._quads = slice(network.n_dyn, network.n_quad_end)
        self._wall_quads = [network.i_wall(i, w) for i in network.wall_nodes
                            for w in ("heat_sat", "heat_conv")]
        self._cell = np.empty((len(network.geometries), 4))

    def rhs(self, th: float, y: np.ndarray) -> np.ndarray:
        """Derivatives with respect to crank angle (the Python entry, for scipy).

        On a compiled tier the compiled :func:`~corliss.engine.kernels.balances.rhs`; otherwise
        each node's properties from the tier in Python (a clamped evaluation counted as
        a trial) handed to the compiled :func:`~corliss.engine.kernels.balances.derivatives`.

        Parameters
        ----------
        th : float
            Shaft crank angle [rad].
        y : ndarray
            The state, shape (n_state,) (layout of :class:`Network`).

        Returns
        -------
        ndarray
            The derivatives per radian, of ``y``'s shape.
        """
        self.nfev += 1
        dy = np.empty_like(y)
        if self._tier >= 0:
            balances.rhs(th, y, dy, self.net, self._tier, self._tab, self._perf, self._pr,
                       self._cell)
            return dy
        clamped = False
        for i in range(self.network.n_nodes):
            V, dV = mechanism.node_volume(th, self.net, i)
            m = y[2 * i]
            rho, u, code = properties.admissible_flagged(m / V, y[2 * i + 1] / m if m > 0.0 else 2.6e6)
            try:
                st = self.steam.du(rho, u)
            except ValueError:   # a trial state with no steam state: take the exhaust's
                st = self.network.reservoirs[-1]
                code |= 32
            clamped = clamped or code != 0
            t_wet = st.T
            if st.superheated and self.network.node_heat[i][H_MODEL] > WALL_NONE:
                t_wet = self.steam.t_sat(st.p)
            self._pr[:, i] = (st.p, rho, u + st.p / rho, kappa_at(self._tab, rho, u), dV, V,
                              st.T, t_wet, code, 1.0 if st.superheated else st.x,
                              1.0 if st.superheated else 0.0, th, m, y[2 * i + 1])
        # scipy does not say which evaluations are trials: each clamped one is counted as
        # one, and the accepted solution is checked after the cycle (:meth:`cycle`)
        self.clamped_trials += int(clamped)
        balances.derivatives(th, y, self._pr, dy, self.net, self._cell)
        return dy

    def update_wall(self, y_end: np.ndarray, apply: bool = True, heat_scale: float = 0.0,
                    dT_scale: float = 0.0, trusted: bool = True) -> tuple[float, float]:
        """Set each wall to the mean steam temperature of the cycle just run.

        The mean weighted by ``h A``: the temperature at which the wall neither gains
        nor loses heat over a cycle.

        The skin model's deep wall (:mod:`corliss.engine.wall`) takes a step on its
        balance over the cycle, ``r(T) = -Q + G_j A_j P (T_j - T) = 0`` (heat the
        steam leaves in the wall, and the jacket's): a secant held inside a bracket of
        the balance's signs (:class:`corliss.engine.wall.DeepWallSearch`, the
        ideal-port wall's too).  The balance is weak (the heat a wall takes at
        admission it mostly gives back the same cycle), so the runner takes a step
        only once the cycle at the present deep temperature is periodic, ``apply``;
        otherwise the step is only measured.

        Walls of the other models are set to their mean at once, whatever ``apply``.

        Parameters
        ----------
        y_end : ndarray
            The state at the end of the cycle just run (its quadratures the cycle's
            totals); shape (n_state,).
        apply : bool
            Whether a skin model's deep wall takes its step (else it is only
            measured).
        heat_scale : float
            The scale of the imbalance [J]; 0 for each wall's own, the heat the steam
            gave it over the cycle.
        dT_scale : float
            The temperature scale [K] against which a wall's bracket counts as an
            imbalance (:meth:`corliss.engine.wall.DeepWallSearch.imbalance`); 0 for
            none.
        trusted : bool
            Whether the rest of the cycle was periodic to the tolerance, so that the
            balance's sign may narrow the bracket
            (:meth:`corliss.engine.wall.DeepWallSearch.step`).

        Returns
        -------
        step : float
            The largest step of a skin model's deep wall [K] (0 without one).
        imbalance : float
            The largest imbalance of a skin model's wall over the cycle [-] (0 without
            one).
        """
        net = self.network
        searches = self.__dict__.setdefault("_wall_searches", {})
        largest = imbalance = 0.0
        for i in range(net.n_nodes):
            ha = y_end[net.i_node_quad(i, "hA")]
            if not ha > 0.0:
                continue
            wall_T = net.wall_T
            assert wall_T is not None      # set by initial_state for every walled node
            if net.node_heat[i][H_MODEL] != WALL_SKIN:
                wall_T[i] = y_end[net.i_node_quad(i, "hAT")] / ha
                continue
            gap = net.node_heat[i][H_SKIN_JACKET_G] * 2.0 * math.pi / net.omega
            T = float(wall_T[i])
            search = searches.setdefault(i, DeepWallSearch())
            step, r = search.step(T, float(y_end[net.i_node_quad(i, "heat")]), ha - gap, gap,
                                  float(net.node_heat[i][H_SKIN_JACKET_T]), apply, trusted)
            largest = max(largest, abs(step))
            scale = heat_scale or float(y_end[net.i_node_quad(i, "heat_to_wall")])
            imbalance = max(imbalance, search.imbalance(r, scale, dT_scale))
            if apply:
                wall_T[i] = T + step
        return largest, imbalance

    def wall_jumps(self, tolerance: float) -> dict[str, WallJump]:
        """The skin walls whose deep wall's balance over a cycle jumps across its
        bracket without a root (:meth:`corliss.engine.wall.DeepWallSearch.jump`), from
        the measurements :meth:`update_wall` has made: no periodic state of that wall
        lies in the bracket, and more cycles will not find one.

        Parameters
        ----------
        tolerance : float
            The run's periodicity tolerance [-].

        Returns
        -------
        dict
            End name to its :class:`~corliss.engine.wall.WallJump`; empty where none
            jumps (or no skin wall was stepped).
        """
        searches = self.__dict__.get("_wall_searches", {})
        out = {}
        for i, search in sorted(searches.items()):
            jump = search.jump(tolerance)
            if jump is not None:
                out[self.network.node_names[i]] = jump
        return out

    def initial_state(self) -> np.ndarray:
        """The cold start: :meth:`Network.initial_state`.

        Returns
        -------
        ndarray
            The state at crank angle 0, shape (n_state,).
        """
        return self.network.initial_state()

    def cycle(self, y0: np.ndarray, theta0: float, out_theta: np.ndarray):
        """Integrate one cycle from ``theta0``, restarting at every kink of the ports.

        The quadratures restart from zero (the skin model's wall states carry on from
        ``y0``, their heat quadratures restart).

        Parameters
        ----------
        y0 : ndarray
            The state at ``theta0``; shape (n_state,).
        theta0 : float
            The shaft angle the cycle starts from [rad].
        out_theta : ndarray
            Shaft angles [rad] at which to sample the state, within the cycle,
            increasing.

        Returns
        -------
        y_end : ndarray
            The state at the cycle's end, its quadratures the cycle's totals; shape
            (n_state,).
        samples : ndarray
            The states at ``out_theta``; shape (n_state, len(out_theta)).

        Raises
        ------
        RunError
            A visited state needed clamping to the range of the steam properties
            (:func:`clamp_message`), or the cycle ran out of its budget
            (:func:`budget_message`).
        RuntimeError
            The integrator failed (its step size collapsed).
        """
        y = np.array(y0, dtype=float)
        y[self._quads] = 0.0              # the wall states carry on
        if self._wall_quads:              # but their quadratures restart
            y[self._wall_quads] = 0.0
        if theta0 not in self._stops:      # the ports' kinks: the same every cycle
            self._stops[theta0] = np.asarray(self.network.stops(theta0), dtype=float)
        stops = self._stops[theta0]
        out_theta = np.asarray(out_theta, dtype=float)
        if self.compiled:
            y_end, samples, nfev, ok, clamps = cycle.integrate_cycle(
                y, stops, out_theta, COMPILED_CODES[self.method], self.rtol, self.atol,
                self.step, self.net, self._tier, self._tab, self._perf, self.color, self.owner,
                self.max_rhs)
            self.nfev += nfev
            self.clamped_trials += int(clamps[CL_REJECTED])
            code = int(clamps[CL_ACCEPTED_CODE])
            if clamps[CL_ACCEPTED] > 0:
                fatal = bool(code & ~CLAMP_HIGH_ENERGY)
                message = clamp_message(self.network, code, int(clamps[CL_NODE]),
                                        float(clamps[CL_THETA] + theta0),
                                        int(clamps[CL_ACCEPTED]), goes_on=not fatal)
                if fatal:
                    raise RunError(message)
                if self.clamped_hot == 0:
                    log.warning("%s", message)
                self.clamped_hot += int(clamps[CL_ACCEPTED])
            if not ok and nfev > self.max_rhs:
                raise RunError(budget_message(self.network, self.max_rhs))
            if not ok:
                raise RuntimeError("the compiled integrator failed (step size collapsed); "
                                   "try another method or a smaller rtol")
            return y_end, samples
        # scipy only on this path (a method the compiled integrator does not have): a
        # compiled run should not pay the import (a third of a second)
        from scipy.integrate import solve_ivp
        samples = np.full((y.size, out_theta.size), np.nan)
        for a, b in zip(stops[:-1], stops[1:]):
            sel = np.nonzero((out_theta >= a) & (out_theta <= b))[0]
            t_eval = np.unique(np.append(out_theta[sel], b))
            # a segment from just short of a schedule's switch reads past it, as the
            # compiled loops' (kernels.balances.past_switch)
            ta = float(balances.past_switch(a, self.net))
            fun = self.rhs if ta == a else (lambda th, yy, ta=ta: self.rhs(max(th, ta), yy))
            sol = solve_ivp(fun, (a, b), y, method=self.method, rtol=self.rtol,
                            atol=self.atol, t_eval=t_eval)
            if not sol.success:
                raise RuntimeError(f"integration failed between {math.degrees(a):.2f} and "
                                   f"{math.degrees(b):.2f} deg: {sol.message}")
            if sel.size:
                samples[:, sel] = sol.y[:, np.searchsorted(sol.t, out_theta[sel])]
            y = sol.y[:, -1].copy()
        self._check_accepted(samples, out_theta)
        return y, samples

    def _check_accepted(self, samples: np.ndarray, out_theta: np.ndarray) -> None:
        """Stop the run when a sampled state of the accepted solution lies outside the
        range of the steam properties (the Python path's test for clamped states)."""
        for i in range(self.network.n_nodes):
            V = self.network.volume(i, out_theta)
            m = samples[2 * i]
            ok = np.isfinite(m)
            if not ok.any():
                continue
            m, V, U = m[ok], V[ok], samples[2 * i + 1][ok]
            rho = m / V
            u = np.where(m > 0.0, U / np.where(m > 0.0, m, 1.0), np.nan)
            code = np.zeros(m.size, dtype=np.int64)
            code[~(rho > properties.RHO_MIN)] |= 1
            code[rho > properties.RHO_MAX] |= 2
            code[~(u > properties.U_MIN)] |= 4
            code[u > properties.U_MAX] |= 8
            bad = np.nonzero(code)[0]
            if bad.size:
                k = bad[0]
                allc = int(np.bitwise_or.reduce(code))
                fatal = bool(allc & ~CLAMP_HIGH_ENERGY)
                message = clamp_message(self.network, allc, i, float(out_theta[ok][k]),
                                        int(bad.size), goes_on=not fatal)
                if fatal:
                    raise RunError(message)
                if self.clamped_hot == 0:
                    log.warning("%s", message)
                self.clamped_hot += int(bad.size)


#: The scene quantity to look at for each kind of clamp (bits of
#: :data:`corliss.thermo.steam_table.CLAMP_CODES`), and why.
CLAMP_CAUSES = {
    1: ("exhaust.pressure", "the steam expanded below the least density the properties "
        "cover: a condenser vacuum (or an expansion below back pressure) deeper than they reach"),
    16: ("exhaust.pressure", "the steam cooled below the triple point: a condenser vacuum "
         "deeper than steam exists"),
    2: ("supply.pressure", "the steam was compressed above the greatest density the "
        "properties cover"),
    8: ("supply.temperature", "the steam was heated beyond the properties' range"),
    4: ("supply.dryness", "the steam became wetter than the properties' range (very wet "
        "supply, or condensation on the walls)"),
    32: ("exhaust.pressure", "the steam reached a density and energy with no steam state"),
}


def clamp_message(network, code: int, node: int, theta: float, count: int,
                  goes_on: bool = False) -> str:
    """Why a run stopped: a state it visited needed clamping to the steam properties.

    Names the scene quantity that most likely caused it (:data:`CLAMP_CAUSES`; the
    wall-heat model for steam overheated by the walls).

    Parameters
    ----------
    network : Network
        The network run (node names and wall-heat rows).
    code : int
        The clamp code: bits of :data:`corliss.thermo.steam_table.CLAMP_CODES`.
    node : int
        The node whose state was clamped first (-1 or out of range: unknown).
    theta : float
        The shaft angle of the first clamped state [rad].
    count : int
        Clamped evaluations at visited states.
    goes_on : bool, optional
        The run goes on (steam heated beyond the properties' greatest energy): the
        message says so, where by default it says the run was stopped.

    Returns
    -------
    str
        The message, ending with the scene key to check.
    """
    what = "; ".join(text for bit, text in CLAMP_CODES.items() if code & bit)
    bit = next((b for b in CLAMP_CAUSES if code & b), 32)
    key, why = CLAMP_CAUSES[bit]
    if bit == CLAMP_HIGH_ENERGY and any(h[0] > 0.0 for h in network.node_heat):
        key, why = ("engine.wall_heat_model", "the heat given back by the walls (Marks's law "
                    "returns it to whatever steam is left in the exhaust stroke) heated the "
                    "steam beyond the properties' range")
    name = network.node_names[node] if 0 <= node < network.n_nodes else "a volume"
    return (f"the steam in the {name} left the range of the steam properties ({what}) at "
            f"{math.degrees(theta) % 360.0:.1f} deg of crank angle, in {count} evaluation(s) "
            f"at states the run visited: {why}.  "
            + ("The run goes on with the properties at their greatest energy (the summary "
               "counts those evaluations)" if goes_on else
               "The run was stopped rather than continue on clamped properties")
            + f"; check {key}")


def budget_message(network, max_rhs: int) -> str:
    """Why a cycle ran out of its budget, with the scene quantities that usually cause it.

    Parameters
    ----------
    network : Network
        The network run (its first cylinder's stroke and bore are quoted).
    max_rhs : int
        The budget: right-hand-side evaluations allowed in one cycle.

    Returns
    -------
    str
        The message.
    """
    spec = network.geometries[0].spec
    return (f"one cycle needed more than {int(max_rhs):,} evaluations of the model and was "
            f"stopped: the run is stepping through something no engine "
            f"does.  Check run.speed (a very slow engine makes the ports' filling stiff; the "
            f"\"fast\" fidelity's L-stable integrator copes better), engine.stroke and "
            f"engine.bore ({spec.stroke_m:.4g} m, {spec.bore_m:.4g} m) against the port "
            f"areas, and any friction or governor force far beyond the engine's")
