"""Steady runs: the speed held, cycles integrated until the run is periodic.

Only the effects the scene names are assembled (:mod:`corliss.engine.model`): without
``port_flow`` the ends take chest and back pressure through ideal ports
(:mod:`corliss.engine.equilibrium`); ``model = "ideal"`` is the algebraic card
(:mod:`corliss.engine.ideal_card`), hyperbolic or isentropic.
"""

from __future__ import annotations

import dataclasses
import functools
import logging
import math
import time
from typing import Callable

import numpy as np

from corliss.engine import equilibrium as eq
from corliss.engine.kernels import jacobians
from corliss.engine.kernels.properties import visited_states
from corliss.engine.calibration import marks_coefficient
from corliss.engine.condensation import wall_schedule
from corliss.engine.crank_resolved import CrankResolved
from corliss.engine.ideal_card import card_area, hyperbolic_card, indicated_steam_kg
from corliss.engine.model import assemble
from corliss.engine.network import cylinder_prefix, piston_ends
from corliss.engine.options import record_of
from corliss.engine.output_size import EQUILIBRIUM_STEP_DEG, WALL_CYCLES_FACTOR
from corliss.engine.result import Deferred, SteadyResult
from corliss.engine.wall import IdealPortWall, wall_jump_text
from corliss.frames.frame import Frame
from corliss.thermo.steam import HEOSSteam

log = logging.getLogger(__name__)
TWO_PI = 2.0 * math.pi


@dataclasses.dataclass(frozen=True)
class SteadyStart:
    """Where a crank-resolved steady run ended, to start a neighbouring run from.

    A run of the same engine at a nearby setting, throttle, speed or tier settles in a
    few cycles from here instead of from the cold start (states at the reservoirs'
    conditions, walls midway between them): a study that walks a knob, or refines on a
    finer tier, pays for the walls' slow settling once.

    Parameters
    ----------
    y : ndarray
        The kernel's state at the end of the last cycle (masses [kg], energies [J],
        film and wall states; the quadratures restart each cycle).
    wall_T_K : ndarray or None
        Each node's wall temperature [K] (the skin model's deep wall), or None.
    """

    y: np.ndarray
    wall_T_K: np.ndarray | None


def run_steady(scene, *, portmap_scale: float = 1.0,
               progress: Callable[[int, float], None] | None = None,
               start: SteadyStart | None = None) -> SteadyResult:
    """Run a steady scene until its cycle is periodic (or for ``run.cycles`` cycles).

    Parameters
    ----------
    scene : Scene
        ``run.mode = "steady"``.
    portmap_scale : float
        Multiply every port area by this factor [-] (for studies of the port-flow limit).
    progress : callable, optional
        Called after each cycle with (cycle number, relative change of work [-]).
    start : SteadyStart, optional
        Start the cycles from where a run of the same engine ended
        (:attr:`SteadyResult.final_state`) instead of the cold start; taken only by the
        crank-resolved model, and only when the two runs' states have the same layout.
        The run still goes on until it is periodic to the fidelity's tolerance.

    Returns
    -------
    SteadyResult
        The run: every cycle's time series (with ``run.record = "cycle"`` each cycle's
        first sample and the last cycle's all) and balances, the last cycle's cards,
        valve events and summary.
    """
    t0 = time.perf_counter()
    eng = scene.engine
    if (scene.run.has("wall_heat") and eng.wall_heat_model == "skin"
            and eng.condensing_W_m2K is None):
        h = marks_coefficient(dataclasses.replace(
            scene, engine=dataclasses.replace(eng, condensing_W_m2K=0.0)), run_steady)
        scene = dataclasses.replace(scene, engine=dataclasses.replace(eng, condensing_W_m2K=h))
    model = assemble(scene, tabulated=scene.run.model == "crank_resolved")
    steam, chest, exhaust = model.steam, model.chest, model.exhaust
    geo, pm, ev = model.geometry, model.portmap, model.events

    # the ideal-port models need entropy: a tier without it lends them HEOS
    def steam_eq():
        return steam if steam.complete else HEOSSteam()

    if scene.run.model == "ideal":
        if scene.run.expansion == "hyperbolic":
            data = _ideal_hyperbolic(scene, geo, ev, chest, exhaust)
        else:
            data = _equilibrium(scene, geo, steam_eq(), chest, exhaust, _ideal_schedule(ev, geo))
    elif scene.run.has("port_flow"):
        assert pm is not None          # a port-flow model has its port map
        if portmap_scale != 1.0:
            pm = pm.scaled(portmap_scale)
        data = _crank_resolved(scene, model, pm, progress, start)
    else:
        data = _equilibrium(scene, geo, steam_eq(), chest, exhaust, _portmap_schedule(pm), pm,
                            progress, _ideal_port_walls(scene, model))
    return SteadyResult(scene=scene, property_tier=steam.name,
                        rhs_evaluations=data.pop("nfev"),
                        wall_time_s=time.perf_counter() - t0, events=ev, geometry=geo,
                        chest=chest, exhaust=exhaust, lp_events=model.lp_events, **data)


def _with_totals(row: dict) -> dict:
    """Add the boundary totals (supply, exhaust) to a row of the ideal-port models."""
    for what, key in (("supply", "chest"), ("exhaust", "exhaust")):
        row[f"m_{what}_kg"] = row[f"m_{key}_head_kg"] + row[f"m_{key}_crank_kg"]
        if f"H_{key}_head_J" in row:
            row[f"H_{what}_J"] = row[f"H_{key}_head_J"] + row[f"H_{key}_crank_J"]
    return row


def _cycle_frame(k: int, theta: np.ndarray, omega: float, ends: dict) -> Frame:
    """Time-series rows of cycle ``k`` (from 0): ``ends[end] = (p, T, x, V, m)`` arrays."""
    cols = {"cycle": np.full(theta.size, k + 1),
            "crank_angle_deg": np.degrees(theta + TWO_PI * k),
            "time_s": (theta + TWO_PI * k) / omega}
    for end, (p, T, x, V, m) in ends.items():
        cols[f"p_{end}_Pa"], cols[f"T_{end}_K"], cols[f"x_{end}_frac"] = p, T, x
        cols[f"V_{end}_m3"], cols[f"m_{end}_kg"] = V, m
    return Frame(cols)


# --- crank-resolved with port flow -------------------------------------------------

def _crank_resolved(scene, model, pm, progress, start=None):
    fid = scene.run.fidelity
    omega = scene.run.speed_rad_s
    steam, geo = model.steam, model.geometry
    net = model.network(pm)
    heat = scene.run.has("wall_heat")
    wall_nodes = net.wall_nodes
    # Marks's or English's law imposed as a schedule (corliss.engine.condensation)
    marks = wall_schedule(scene, net, geo, model.events, omega, model.chest.T, model.exhaust.T,
                          lp_events=model.lp_events)
    arrays = net.arrays()
    method, rtol = fid.steady_integrator(steam.kernel_tier is not None
                                         and jacobians.exact_jacobian_covers(arrays))
    crank = CrankResolved(net, steam, method, rtol, step_deg=fid.step_deg, arrays=arrays)
    ends_all = piston_ends(net)
    out_theta = _output_angles(fid.output_step_deg)
    y = crank.initial_state()
    if start is not None and start.y.shape == y.shape:
        y = start.y.copy()
        if start.wall_T_K is not None and net.wall_T is not None \
                and start.wall_T_K.shape == net.wall_T.shape:
            net.wall_T[:] = start.wall_T_K
    rows, samples_all, walls_used = [], [], []
    # recorded once a cycle (record = "cycle"), a cycle keeps its first sample once the
    # next has run: the run holds what it writes, not every cycle it ran
    once = record_of(scene.run) == "cycle"
    # the sampled rows the time series reads: the volumes' states, first, and with skin
    # walls their states and quadratures too; a run kept every cycle's whole samples
    # before, and paid for the fresh memory (page faults) 10 to 20 us a cycle
    kept = net.n_state if net.wall_nodes else net.n_dyn
    w_prev = None
    converged = None
    residuals = {}
    n_max = scene.run.cycles or fid.max_cycles
    if net.wall_nodes and not scene.run.cycles:
        # the skin model's deep wall settles over a few periodic cycles of its own
        n_max *= WALL_CYCLES_FACTOR
    dT_scale = max(model.chest.T - model.exhaust.T, 1.0)
    lay = _layout(net, ends_all, heat, marks)
    for k in range(1, n_max + 1):
        if marks is not None:
            marks.apply(crank.net.heat)
        y_start = y.copy()
        wall_start = None if net.wall_T is None else np.array(net.wall_T, dtype=float)
        y, samples = crank.cycle(y, 0.0, out_theta)
        walls_used.append(wall_start)
        if marks is not None:
            marks.update(steam, samples, out_theta)
        elif heat and not wall_nodes:
            crank.update_wall(y)
        row = _cycle_row(k, lay, net, y, wall_start)
        rows.append(row)
        if once and samples_all:
            samples_all[-1] = samples_all[-1][:, :1].copy()
        samples_all.append(samples[:kept].copy() if kept < samples.shape[0] else samples)
        w = row["work_J"]
        residuals = _periodicity(lay, net.wall_T, y_start, y, samples, wall_start, dT_scale,
                                 row, w_prev)
        if heat and wall_nodes:
            # the skin model's deep wall steps once the cycle at its temperature is
            # periodic (CrankResolved.update_wall)
            # (or, while the wall's own step is large, once the cycle's other residuals
            # are a tenth of it)
            # the wall is periodic when its heat over the cycle balances (what it took
            # less what it gave, and the jacket's) to the tolerance of the heat it took,
            # its own scale, or when its bracket has closed to the tolerance of the
            # supply's less the exhaust's temperature (where the balance has a kink, a
            # superheated wall's, or the cycles' noise exceeds the tolerance of a small
            # heat): against the enthalpy supplied (some 30 times the wall's heat) the
            # fast preset's 1e-3 left the wall up to 0.8 K from periodic, for the wall's
            # heat moves only about 1.4 kJ a cycle per kelvin
            inner = max(v for n, v in residuals.items() if n != "wall_temperature")
            trusted = inner <= fid.convergence_tolerance
            step, imbalance = crank.update_wall(y, apply=False, dT_scale=dT_scale,
                                                trusted=trusted)
            settled = inner <= max(10.0 * fid.convergence_tolerance, 0.1 * step / dT_scale)
            if settled:
                crank.update_wall(y, apply=True, dT_scale=dT_scale, trusted=trusted)
            residuals["wall_temperature"] = max(residuals.get("wall_temperature", 0.0),
                                                imbalance)
        change = max(residuals.values())
        if progress:
            progress(k, change)
        if log.isEnabledFor(logging.DEBUG):     # the text costs a few us a cycle
            log.debug("cycle %d: work %.6g J, residuals %s", k, w,
                      ", ".join(f"{n} {v:.2g}" for n, v in residuals.items()))
        if scene.run.cycles is None and change <= fid.convergence_tolerance:
            converged = k
            break
        w_prev = w
    # a deep wall whose balance jumps across its bracket has no periodic state there
    # (DeepWallSearch.jump): the run says so instead of asking for more cycles
    jumps = (crank.wall_jumps(fid.convergence_tolerance)
             if converged is None and scene.run.cycles is None and heat and wall_nodes else {})
    if jumps:
        log.warning("not periodic after %d cycles: %s", n_max, wall_jump_text(jumps))
    elif converged is None and scene.run.cycles is None:
        log.warning("not periodic after %d cycles: the largest residual is %.2g (%s) against "
                    "a tolerance of %.2g; the card is the last cycle's (a tighter fidelity, or "
                    "more max_cycles, may settle it)", n_max, change,
                    max(residuals, key=residuals.get), fid.convergence_tolerance)
    # the time series is built when first read (the summary's cards, a file, a plot): a
    # study's run that records the summary's balances and rates never needs it
    timeseries = Deferred(lambda: _crank_timeseries(net, steam, ends_all, out_theta, omega,
                                                    samples_all, walls_used))
    final = SteadyStart(y.copy(), None if net.wall_T is None else np.array(net.wall_T, dtype=float))
    return {"timeseries": timeseries, "cycles": Frame.from_rows(rows), "final_state": final,
            "cycles_to_converge": converged, "periodicity": residuals, "portmap": pm, "nfev": crank.nfev,
            "clamped_trials": crank.clamped_trials, "clamped_hot": crank.clamped_hot,
            "wall_jumps": jumps,
            "cylinders": [(("lp_" if scene.compound and c else cylinder_prefix(c)), g, ph)
                          for c, (g, ph) in enumerate(zip(net.geometries, net.phases))]}


def _output_angles(step_deg: float) -> np.ndarray:
    """The crank angles a cycle's states are sampled at, every ``step_deg`` from 0 to
    2 pi [rad]: a copy of the run's own (the compiled cycle takes a writable array)."""
    return _angles_every(step_deg).copy()


@functools.lru_cache(maxsize=8)
def _angles_every(step_deg: float) -> np.ndarray:
    """:func:`_output_angles`, found once a step."""
    step = math.radians(step_deg)
    return np.linspace(0.0, TWO_PI, int(round(TWO_PI / step)) + 1)


@dataclasses.dataclass(frozen=True)
class _Layout:
    """Where a crank-resolved steady run reads each cycle's row and residuals, looked
    up once a run (the network's index methods cost more than the reads, every cycle).

    ``names[n]`` is read from ``index[n]`` of the state at the cycle's end followed by
    the wall temperatures at its start; ``terms`` are
    :meth:`~corliss.engine.network.Network.boundary_terms`; ``work`` the names of the
    ends' work; ``walls`` each skin wall's node, surface state and film state.
    """

    names: tuple[str, ...]
    index: tuple[int, ...]
    terms: tuple[tuple[str, float, int], ...]
    work: tuple[str, ...]
    n_dyn: int
    walls: tuple[tuple[int, int, int], ...]


def _layout(net, ends_all, heat: bool, marks) -> _Layout:
    """The indices of a run's cycle rows (:func:`_cycle_row`) and residuals."""
    names, index = [], []
    for end in ends_all:
        for what, edge in (("chest", f"{end}_steam"), ("exhaust", f"{end}_exhaust")):
            e = net.edge(edge)
            names += [f"m_{what}_{end}_kg", f"H_{what}_{end}_J"]
            index += [net.i_edge_mass(e), net.i_edge_enthalpy(e)]
        i = net.node(end)
        names.append(f"work_{end}_J")
        index.append(net.i_work(i))
        if heat:           # every end's heat, so a compound's balance closes
            names += [f"Q_{end}_J", f"Q_to_wall_{end}_J"]
            index += [net.i_node_quad(i, "heat"), net.i_node_quad(i, "heat_to_wall")]
            if marks is None:      # a period law imposes the heat: the wall has no T
                names.append(f"T_wall_{end}_K")
                index.append(net.n_state + i)      # the wall at the cycle's start
    if "steam_pipe" in net.edge_names:
        names.append("m_pipe_kg")
        index.append(net.i_edge_mass(net.edge("steam_pipe")))
    for name, e in net.leak_edges():
        names.append(f"m_{name}_kg")
        index.append(net.i_edge_mass(e))
    return _Layout(tuple(names), tuple(index), tuple(net.boundary_terms()),
                   tuple(f"work_{end}_J" for end in ends_all), net.n_dyn,
                   tuple((i, net.i_wall(i), net.i_film(i)) for i in net.wall_nodes))


def _cycle_row(k: int, lay: _Layout, net, y: np.ndarray, wall_start) -> dict:
    """Cycle ``k``'s row of balances: each edge's and end's totals, the boundary's, the
    work, from the state ``y`` at its end and the walls ``wall_start`` at its start
    (read as Python floats: the same values, cheaper to index)."""
    src = y.tolist()
    if wall_start is not None:
        src += wall_start.tolist()
    row = {"cycle": k}
    row.update(zip(lay.names, [src[j] for j in lay.index]))
    row.update(net.boundary_totals(src, lay.terms))
    row["work_J"] = sum(row[w] for w in lay.work)
    return row


def _crank_timeseries(net, steam, ends_all, out_theta, omega: float, samples_all,
                      walls_used) -> Frame:
    """Every cycle's time series, from the states sampled at ``out_theta`` each cycle
    (``samples_all``: each cycle's rows of the state, all or the volumes' only).

    The cycles' samples are stacked and each volume's states turned into pressure,
    temperature and dryness in one call of the tier (for the table, one compiled call
    per volume), not one per cycle; the values are those of a conversion cycle by
    cycle, element by element the same arithmetic.  A cycle recorded once holds the
    first of the output angles only.
    """
    n_cyc = len(samples_all)
    counts = np.array([b.shape[1] for b in samples_all])
    s = np.concatenate(samples_all, axis=1)
    k = np.arange(n_cyc)
    angle = np.concatenate([out_theta[:c] for c in counts]) + np.repeat(TWO_PI * k, counts)
    cols = {"cycle": np.repeat(k + 1, counts), "crank_angle_deg": np.degrees(angle),
            "time_s": angle / omega}

    def each_cycle(values):
        """Values at the output angles, the same every cycle, for every row."""
        return np.concatenate([values[:c] for c in counts])
    for end in ends_all:
        i = net.node(end)
        V = each_cycle(net.volume(i, out_theta))
        m, U = s[2 * i], s[2 * i + 1]
        cols[f"p_{end}_Pa"], cols[f"T_{end}_K"], cols[f"x_{end}_frac"] = visited_states(
            steam, m / V, U / m)
        cols[f"V_{end}_m3"], cols[f"m_{end}_kg"] = V, m
    for i in net.wall_nodes:
        # the skin model's surface temperature and the heat into the steam so far
        end = net.node_names[i]
        deep = np.repeat([w[i] for w in walls_used], counts)
        cols[f"T_wall_{end}_K"] = deep + s[net.i_wall(i)]
        cols[f"Q_{end}_J"] = s[net.i_node_quad(i, "heat")]
        cols[f"m_film_{end}_kg"] = s[net.i_film(i)]
        cols[f"Q_sat_{end}_J"] = s[net.i_wall(i, "heat_sat")]
        cols[f"Q_conv_{end}_J"] = s[net.i_wall(i, "heat_conv")]
    for vessel in ("chest", "receiver"):
        if vessel in net.node_names:
            i = net.node(vessel)
            V = each_cycle(net.volume(i, out_theta))
            cols[f"p_{vessel}_Pa"] = visited_states(steam, s[2 * i] / V,
                                                     s[2 * i + 1] / s[2 * i])[0]
    return Frame(cols)


def _periodicity(lay: _Layout, wall_T, y0, y1, samples, wall0, dT_scale: float, row: dict,
                 w_prev: float | None) -> dict[str, float]:
    """How far one cycle is from periodic, each state against its own scale [-].

    ``work``: change of the indicated work from the cycle before; ``mass``, ``energy``:
    the largest change over the cycle of a volume's mass or internal energy (every end,
    chest, receiver), against that state's largest value over the cycle; ``mass_balance``:
    steam in less steam out over the cycle, against the greater of the steam through the
    engine and the steam it holds (a periodic cycle's contents may drift by the tolerance
    of what they hold, and the flows' quadratures resolve the net flow to about a
    hundred integrator tolerances of it; a valve that barely opens, passing micrograms,
    is judged by its contents; the skin model's film counts with its end's mass);
    ``wall_temperature``: the largest change of a wall's temperature (the skin model's
    surface), against the supply's less the exhaust's temperature, and for the skin
    model the wall's heat imbalance over the cycle against the heat it took, or its
    bracket against the temperature scale where that is smaller (set by the runner,
    :class:`corliss.engine.wall.DeepWallSearch`).  A cycle is periodic when every one
    is below the convergence tolerance.
    """
    w = row["work_J"]
    out = {"work": abs(w - w_prev) / max(abs(w), 1e-300) if w_prev is not None else math.inf}
    # each dynamic state's largest magnitude over the cycle (fmax skips a sample the
    # integrator did not reach, as nanmax would, in one ufunc call: nanmax's copies cost
    # a quarter of a fast cycle)
    # (the arrays' own methods: numpy's functions wrap them at a microsecond a call)
    nd = lay.n_dyn
    peak = np.fmax.reduce(np.abs(samples[:nd]), axis=1)
    rel = np.abs(y1[:nd] - y0[:nd]) / np.maximum(peak, 1e-300)
    out["mass"], out["energy"] = float(rel[0::2].max()), float(rel[1::2].max())
    m_in, m_out = row["m_supply_kg"], row["m_exhaust_kg"]
    held = float(peak[0::2].sum())
    out["mass_balance"] = abs(m_in + m_out) / max(abs(m_in), abs(m_out), held, 1e-300)
    if wall0 is not None and wall_T is not None and (wall_T != wall0).any():
        out["wall_temperature"] = float(np.max(np.abs(wall_T - wall0))) / dT_scale
    for i, k, f in lay.walls:
        # the skin model's surface: its change over the cycle, and its deep wall's
        out["wall_temperature"] = max(out.get("wall_temperature", 0.0),
                                      abs(y1[k] - y0[k]) / dT_scale)
        # the film's water against the steam the end holds at most
        m_end = max(float(peak[2 * i]), 1e-300)
        out["mass"] = max(out["mass"], abs(y1[f] - y0[f]) / m_end)
    return out


# --- ideal ports (no port_flow) and the isentropic ideal card -----------------------

def _portmap_schedule(pm):
    def schedule(theta):
        mid = 0.5 * (theta[1:] + theta[:-1])
        mask = pm.open_mask(mid)
        return (eq.connection_from_areas(mask[0], mask[1]),
                eq.connection_from_areas(mask[2], mask[3]))
    return schedule, pm.breakpoints_rad


def _ideal_schedule(ev, geo):
    """Admission from dead centre to cut-off; exhaust from release to compression."""
    def window(theta, a_deg, b_deg):
        if a_deg is None or b_deg is None:
            return np.zeros(theta.size, dtype=bool)
        a, b = math.radians(a_deg), math.radians(b_deg)
        t = theta % TWO_PI
        return ((t - a) % TWO_PI) < ((b - a) % TWO_PI)

    h, c = ev["head"], ev["crank"]
    bps = [math.radians(v) for v in (0.0, 180.0, h["cutoff_deg"], h["release_deg"],
                                     h["compression_deg"], c["cutoff_deg"], c["release_deg"],
                                     c["compression_deg"]) if v is not None]

    def schedule(theta):
        mid = 0.5 * (theta[1:] + theta[:-1])
        hs = window(mid, 0.0, h["cutoff_deg"])
        he = window(mid, h["release_deg"], h["compression_deg"])
        cs = window(mid, 180.0, c["cutoff_deg"])
        ce = window(mid, c["release_deg"], c["compression_deg"])
        return eq.connection_from_areas(hs, he), eq.connection_from_areas(cs, ce)
    return schedule, np.asarray(bps)


def _ideal_port_walls(scene, model):
    """The skin walls of the two ends for the ideal-port model, or None."""
    if not scene.run.has("wall_heat"):
        return None
    net = model.network()
    return [IdealPortWall(net.node_heat[i], model.geometry, net.node_end[i],
                          scene.run.speed_rad_s, 0.5 * (model.chest.T + model.exhaust.T))
            for i in (net.node("head"), net.node("crank"))]


def _equilibrium(scene, geo, steam, chest, exhaust, sched, pm=None, progress=None, walls=None):
    schedule, bps = sched
    theta = eq.stepping_grid(bps, math.radians(EQUILIBRIUM_STEP_DEG))
    conns = schedule(theta)
    vols = geo.volumes_m3(theta)
    fid = scene.run.fidelity
    omega = scene.run.speed_rad_s
    traces, converged = eq.run_cycles(steam, theta, vols, conns, chest, exhaust,
                                      fid.convergence_tolerance, fid.max_cycles, scene.run.cycles,
                                      walls, omega, record_of(scene.run) != "cycle")
    rows, ts = [], []
    for k, (th_, tc_) in enumerate(traces):
        row = {"cycle": k + 1}
        for end, tr in (("head", th_), ("crank", tc_)):
            row[f"m_chest_{end}_kg"] = tr.m_chest_kg
            row[f"H_chest_{end}_J"] = tr.H_chest_J
            row[f"m_exhaust_{end}_kg"] = tr.m_exhaust_kg
            row[f"H_exhaust_{end}_J"] = tr.H_exhaust_J
            row[f"work_{end}_J"] = tr.work_J
            if tr.wall is not None:
                row[f"Q_{end}_J"] = tr.wall["Q_J"]
                row[f"Q_to_wall_{end}_J"] = tr.wall["Q_to_wall_J"]
                row[f"T_wall_{end}_K"] = tr.wall["T_deep_K"]
        rows.append(_with_totals(row))
        # (a cycle recorded once has its first point only)
        frame = _cycle_frame(k, theta[:th_.p_Pa.size], omega, {
            end: (tr.p_Pa, tr.T_K, tr.x, tr.V_m3, tr.m_kg)
            for end, tr in (("head", th_), ("crank", tc_))})
        for end, tr in (("head", th_), ("crank", tc_)):
            if tr.wall_records is not None:
                for n, col in enumerate(("T_wall_{}_K", "m_film_{}_kg", "Q_{}_J", "Q_sat_{}_J",
                                         "Q_conv_{}_J")):
                    frame[col.format(end)] = tr.wall_records[:, n]
        ts.append(frame)
    if progress:      # the ideal-port cycles are algebraic: one report at the end
        progress(len(rows), 0.0)
    return {"timeseries": Frame.concat(ts), "cycles": Frame.from_rows(rows),
            "cycles_to_converge": converged, "portmap": pm, "nfev": 0}


# --- hyperbolic ideal card ------------------------------------------------------------

def _ideal_hyperbolic(scene, geo, ev, chest, exhaust):
    p_s, p_b = chest.p, exhaust.p
    row = {"cycle": 1}
    cols = {}
    # the head end's stroke 0..pi inverted by interpolation (s is monotonic there)
    head_theta = np.linspace(0.0, math.pi, 20001)
    head_frac = geo.fraction(head_theta)
    for e, end in enumerate(("head", "crank")):
        x = ev[end]
        f_c = x["cutoff_frac"] if x["cutoff_frac"] is not None else 0.0
        f_r = x["release_frac"] if x["release_frac"] is not None else 1.0
        f_k = x["compression_frac"] if x["compression_frac"] is not None else 0.0
        Vc, Vs = geo.clearance_m3[e], geo.swept_m3[e]
        frac, V, p = hyperbolic_card(Vc, Vs, f_c, f_r, f_k, p_s, p_b)
        row[f"work_{end}_J"] = card_area(V, p)
        m = indicated_steam_kg(Vc, Vs, f_c, f_k, chest, exhaust)
        row[f"m_chest_{end}_kg"] = m
        row[f"H_chest_{end}_J"] = m * chest.h
        row[f"m_exhaust_{end}_kg"] = -m
        # the hyperbolic card is no thermodynamic process: no exhaust enthalpy
        # crank angles of the card points: forward stroke then return stroke
        half = np.interp(np.clip(frac if end == "head" else 1.0 - frac, 0.0, 1.0),
                         head_frac, head_theta)
        n = frac.size
        fwd = np.zeros(n, dtype=bool)
        fwd[: 3 * (n // 5)] = True     # admission, expansion, release to end of stroke
        if end == "head":
            th = np.where(fwd, half, TWO_PI - half)
        else:
            th = np.where(fwd, TWO_PI - half, half)
        cols[end] = (th, V, p)
    grid = np.radians(np.arange(0.0, 360.0 + 1e-9, scene.run.fidelity.output_step_deg))
    data = {"cycle": np.ones(grid.size, dtype=int), "crank_angle_deg": np.degrees(grid),
            "time_s": grid / scene.run.speed_rad_s}
    for end, (th, V, p) in cols.items():
        order = np.argsort(th, kind="stable")
        data[f"p_{end}_Pa"] = np.interp(grid, th[order], p[order])
        data[f"V_{end}_m3"] = np.interp(grid, th[order], V[order])
    cards = {end: Frame({"frac": (V - geo.clearance_m3[e]) / geo.swept_m3[e],
                         "V_m3": V, "p_Pa": p})
             for e, (end, (th, V, p)) in enumerate(cols.items())}
    return {"timeseries": Frame(data), "cycles": Frame.from_rows([_with_totals(row)]),
            "cycles_to_converge": 1, "portmap": None, "nfev": 0, "ideal_cards": cards}
