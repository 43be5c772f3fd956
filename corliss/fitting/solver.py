"""Scene keys calibrated to a measured indicator card by least squares.

The historian's problem is the simulator's run backwards: an engine survives as a few
indicator cards and some dimensions, and the valve setting, clearance and losses that
explain the cards are wanted, with how sure that answer is.  :func:`fit_card` varies the
named scene keys (each within its ``LOW:HIGH``) until the simulated card of every end
the measured card holds lies on the measured one, and reports each key's value with a
standard error, or says that the card cannot tell it.

The residuals
-------------
A measured card is a closed loop of points without crank angle (the indicator's drum
turned with the crosshead; nothing on the card says when the pencil was where).  So a
measured point is not compared with the simulated pressure "at the same piston
position": near the dead centres the admission and release lines are nearly vertical,
where a pressure at one position is ill defined, and which branch (forward or return
stroke) a point belongs to would have to be guessed.  Nor are both loops parameterised
by arc length: a point's arc length depends on every point before it, so one bad point
(a pencil's jump) would shift the comparison of the whole loop after it.  Each measured
point is compared with the nearest point of the simulated loop, a closed polyline, in
normalised coordinates (the abscissa over the stroke, or over the end's swept volume;
the pressure over the measured card's range of pressure, so the card is square, as the
eye reads it): the residual is that distance, signed by the side of the simulated loop
the point lies on, in pressure units (times the pressure range).  On the long nearly
flat lines (admission, expansion, exhaust, compression) this is the pressure
difference; on the steep ones, the horizontal distance scaled alike.  The residual of a
point does not depend on any other point, needs no branch and no crank angle.

Shape alone would let a loop slide along itself; the card's area, the indicated work
(its area over its length is the mean effective pressure of Marks Art. 3), is added for
each end as one more residual: the simulated area less the measured, both as the
integral of pressure over the normalised abscissa, divided by the area's own standard
deviation when every point's pressure carries an independent error of one unit (the root
of the sum of the squared trapezoid weights, :func:`area_weights`).  Weighted so, the
area residual has the same noise as one point's residual, so the noise estimate ``s``
holds for every residual alike and the area is counted once, as the one observation it
is (it is made of the same points).  Shape and area then both count, the area as a
strong single observation: on the default engine's card of 180 points an end, an area
wrong by a fraction ``e`` gives a residual of 5.6 ``e`` times the pressure range, which
costs as much as 32 of the 180 points each off by ``e`` of the range.  On a card the
model can match (the tests' synthetic cards) the shape decides, and the fitted and
measured m.e.p. agree to 0.1 % with or without the area.  Where the shape cannot be
matched the area pulls only a little: the default engine's noisy card fitted by the lap
alone, with the clearance and discharge coefficient of the scene wrong (0.11 and 0.55
for 0.08 and 0.7), ends with an m.e.p. 1.2 % short of the card's with the area residual
and 1.3 % short without it (the lap 0.996 in against 1.015 in).  A heavier area weight
would hold the work at the price of the shape, and of ``s`` as an estimate of the noise.

The search
----------
``scipy.optimize.least_squares`` (trust-region reflective) in scaled parameters
``u = (value - LOW) / (HIGH - LOW)``, bounded to ``[0, 1]``.  Every simulation runs the
same whole number of cycles (found once, at the start, by running the starting scene
until its work is periodic to 1e-5), so the card is a smooth function of the keys:
a run stopped when periodic to a tolerance would jump where the cycle count changes.
The Jacobian is by forward differences of ``DIFF_STEP`` of the range.  The runs of a
fit on the ``fast`` tier use its compiled Rosenbrock method at rtol 1e-6, not its own
5e-5: at 5e-5 a few points of the admission line just after dead centre dip by up to
40 kPa and recover, differently as a key moves by a hundredth of its range, which left
the cost rough by 2 % and the search stopped short (:data:`SEARCH_RTOL`, which also
says why not 1e-5).  At 1e-5 the
second difference of a card's pressures over such steps is about 1 Pa (median; 0.5 kPa
at the worst point), so the noise allows a small step; what sets it is the card: the
lap of the default engine is pinned by a 0.5 psi card to a five-hundredth of a
0.6 in range, and a step of 2 % of the range straddled the valley of the cost, where
the forward difference is no derivative (the search stopped 2 to 3 standard errors
short of the minimum).  ``h = 0.005`` of the range on ``fast`` (``0.002`` on
``standard``, rtol 1e-6) resolves it, with a derivative noise of about
``2 x 1 Pa / 0.005`` = 0.4 kPa per unit of the scaled key, against sensitivities of tens
to hundreds of kPa.  ``refine`` repeats the search from the optimum on the ``standard``
tier.

The uncertainty
---------------
At the optimum, the Jacobian is taken again by central differences over ``4 h`` either
side (2 % of the range on the ``fast`` tier): a secant rather than a tangent, because
the residuals of the few points at the card's corners (where admission and release
turn the line) change slope within a fraction of a percent of a key's range.

The covariance of the scaled keys is the sandwich (White's heteroscedasticity-
consistent estimate, with the ``n / (n - p)`` of HC1)
``(J^T J)^-1 J^T diag(r^2) J (J^T J)^-1``, not ``s^2 (J^T J)^-1`` with ``s^2`` = the
residuals' sum of squares over ``n - p``, which is reported beside it
(``standard_error_classic``).  The residuals are distances, and a distance to a steep
line is a fraction of the pressure error that made it: their scatter differs from one
part of the card to another, which the classic form, one variance for all, does not
allow.  The keys the steep lines fix (the clearance, by where compression and
admission turn) are then misjudged: on 20 cards of the default engine with 0.5 psi of
noise (clearance and lap fitted, starting from 0.11 and 0.85 in), the classic
standard error of the clearance ranged from 0.00085 to 0.0039 from card to card,
against a scatter of the fitted clearance of 0.0014; the sandwich's ranged from 0.0013
to 0.0019.  The root mean square of (fitted - truth) / standard error over those cards
was 0.95 for the clearance and 1.16 for the lap (1 is exact; classic: 0.93 and 0.86,
the clearance's right on average only).  The standard errors are the covariance's
diagonal's roots times each range, in the user's units.

A key is reported unidentifiable, by name and with no number, when the card does not
determine it:

- its column of the Jacobian is no larger than the solver's own noise: the central
  difference against the second difference of the same three runs (pure noise gives
  a ratio of about 0.3; a real sensitivity, over a step of 2 % of the range, tens);
- it takes part in a direction of the keys along which the card does not change above
  that noise (two keys that act only through their product, such as a port's length
  and its discharge coefficient): a singular value of the Jacobian below three times
  the noise floor of its columns.  The rows whose second difference is far beyond
  that noise (ten times the columns' robust scale of them: the points at the card's
  corners, where the nearest point of the simulated loop jumps from one line to the
  next, and the area residuals, of large weight) are left out of this test and of the
  columns' cosines: there a central difference is a secant, and two keys whose steps
  move the product by different fractions (2 % of each range: 1.5 % for the port's
  length, 1.1 % for its coefficient) give different secants of the same function.
  On converged cards (rtol 1e-6, or 3e-6) those few rows alone made the port's
  length and coefficient look distinguishable (a least singular value of 39,000
  against a floor of 1,000; 370 without them);
- or its standard error is larger than its range.

The other keys' errors are then given with the unidentifiable ones held at their
fitted values.  ``bootstrap`` adds a wild bootstrap of the residuals: new cards made
of the fitted card's nearest points, each moved along the loop's normal by its own
residual with a random sign (so a point on a steep line keeps its small scatter, as
the sandwich does; drawing residuals from the whole pool put the flat lines' scatter
on the steep ones and doubled the lap's bootstrap error), refitted from the optimum;
the standard deviation and the 2.5 and 97.5 percentiles of the refits are reported
beside the Jacobian's errors.
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import importlib
import logging
import math
import pickle
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from corliss.keys import units
from corliss.engine.options import PRESETS
from corliss.engine.result import Result
from corliss.engine.simulate import simulate
from corliss.errors import InputError, RunError
from corliss.fitting.card import MeasuredCard
from corliss.scene.loader import Scene, scene_from_dict
from corliss.keys.edits import KeyRange, get_key, parse_value, with_keys
from corliss.studies.pool import run_tasks, unpickled_once

log = logging.getLogger(__name__)

#: Integrator tolerance of a tier's runs in a fit.  The ``fast`` tier's own 5e-5 leaves
#: spurious dips of up to 40 kPa in a few points of the admission line just after dead
#: centre, which come and go as a key moves by a hundredth of its range (the default
#: engine: the crank end's pressure at 186-190 deg, clearance 0.076-0.081); at 1e-5 the
#: largest second difference over the same steps is 0.5 kPa (median 1 Pa), for a run
#: 1.6 times as long (86 ms against 55 ms).  But at 1e-5 the card's response to a
#: port's area was still a third short of the converged one (the largest singular
#: value of the port length's and coefficient's Jacobian 368,000 against 559,000 at
#: 3e-6 and at 1e-6), and a key that acts on the crank end alone moved the head end's
#: card by 1 to 15 Pa, smoothly (the two ends share the steps), so that the card of the
#: head end seemed to fix the piston rod's diameter.  At 3e-6 that is 0.4 to 3 Pa, but
#: a fit to a card with 2 psi of noise still stopped where the clearance's error was
#: 0.0020, not the 0.0056 to 0.0057 of the same fit at 1e-6 or with RODAS4 at 3e-6;
#: at 1e-6 it is 0.1 to 0.4 Pa, for 2.2 times the evaluations of 1e-5 (about those of
#: 1e-5 with the finite-difference Jacobian).
SEARCH_RTOL = {"fast": 1e-6}
#: Forward-difference step of the search, as a fraction of each key's range, per
#: fidelity tier (see the module's notes: about twice the root of the tier's noise).
DIFF_STEP = {"fast": 0.005, "standard": 0.002, "reference": 0.001}
#: Central-difference step of the covariance's Jacobian, as a multiple of DIFF_STEP (a
#: secant over +-2 % of the range on the fast tier; see the module's notes).
COV_STEP_FACTOR = 4.0
#: The covariance reported: ``"sandwich"`` or ``"classic"`` (see the module's notes).
COVARIANCE = "sandwich"
#: A column (or direction) of the Jacobian is noise when below this multiple of the
#: noise floor its second differences measure.
NOISE_FACTOR = 3.0
#: A row of the covariance's Jacobian is a secant across a corner of the card, left out
#: of the test of directions and of the columns' cosines, when its second difference in
#: some column exceeds this multiple of that column's robust scale of them (the
#: module's notes).
SECANT_ROW_FACTOR = 10.0
#: Crank-angle step of the simulated cards [deg]: the loop the measured points are
#: held to is a polyline through them, and its corners (admission, release) should be
#: the card's, not the sampling's.
OUTPUT_STEP_DEG = 0.5
#: Work periodic to this fraction sets the cycle count of every run of a fit.
PILOT_TOLERANCE = 1e-5
#: Search tolerances: on the scaled keys (a ten-thousandth of the range) and the cost.
XTOL, FTOL = 1e-4, 1e-8
#: At most this many simulations per key in one search.
MAX_NFEV_PER_KEY = 60


#: The module that writes a fit's files and draws its card (the files layer, above this
#: one): loaded by name the first time an export method is called, as python-control's
#: ``TimeResponseData`` hands its plots to a module of their own, so that the fitting
#: package imports no file writer and ``import corliss`` loads none.
WRITER = "corliss.files.fit_output"


def _writer():
    """The module :data:`WRITER`, imported on first use."""
    return importlib.import_module(WRITER)


@dataclass
class FitResult:
    """A fit's outcome (made by :func:`fit_card`).

    Values are in each key's unit (:attr:`corliss.keys.edits.KeyRange.unit`);
    pressures SI unless named.

    Parameters
    ----------
    scene : Scene
        The scene fitted from (its values the start, unless outside the range).
    fitted_scene : Scene
        The scene with the fitted values, at its own fidelity (runnable).
    fitted_data : dict
        The fitted scene's tables (as its TOML would hold them).
    card : MeasuredCard
        The measured card.
    ranges : list of KeyRange
        The keys fitted and their bounds, in the order given.
    start, values : dict
        ``{key: value}`` at the start and at the optimum, in the key's unit.
    standard_errors : dict
        ``{key: s.e.}`` from the Jacobian (the sandwich estimate), in the key's unit;
        None for an unidentifiable key.
    unidentifiable : dict
        ``{key: why}`` of the keys the card does not determine.
    correlation : ndarray, shape (keys, keys)
        Correlation of the identifiable keys' estimates (NaN rows and columns for the
        others) [-].
    sensitivity_cosine : ndarray, shape (keys, keys)
        Cosine between the keys' columns of the Jacobian [-]: +-1 for two keys the card
        cannot tell apart (over the rows where a difference is a derivative: the
        module's notes).
    residual_rms_Pa : float
        Root mean square of the point residuals at the optimum [Pa].
    s_Pa : float
        Noise estimate, the root of the residual sum of squares over n - p [Pa].
    n_residuals, n_points : int
        Residuals (points and one area per end) and measured points [-].
    simulations : int
        Simulations run [-].
    cycles : int
        Cycles every simulation ran [-].
    wall_time_s : float
        Wall time of the fit [s].
    fidelity : str
        Tier of the final search (``fast``, or ``standard`` when refined).
    result : SteadyResult
        The simulation at the optimum.
    end_work : dict
        Per end: the measured and fitted card's m.e.p. [Pa] (area over the stroke) and
        the fitted card's work as its area in volume [J] beside the summary's.
    status : str
        The search's message.
    standard_errors_classic : dict, optional
        ``{key: s.e.}`` from ``s^2 (J^T J)^-1``, beside them (see the module's notes).
    singular_values : list of float, optional
        Singular values of the identifiable keys' Jacobian at the optimum, over the
        rows where a difference is a derivative [Pa per unit of the scaled key].
    noise_floor : float, optional
        The largest of the Jacobian columns' noise floors [Pa per unit of the scaled
        key].
    bootstrap : dict or None, optional
        ``{"samples": N, "seed": k, "standard_errors": {...}, "low": {...},
        "high": {...}}`` (2.5 and 97.5 percentiles), keys' units; None without a
        bootstrap.
    start_from : dict, optional
        ``{key: where its start came from}`` (``"scene"``, or why the middle of the
        range).
    at_bound : dict, optional
        ``{key: "low", "high" or None}``: the end of its range the fitted value lies at
        (within a thousandth of the range).
    """

    scene: Scene
    fitted_scene: Scene
    fitted_data: dict
    card: MeasuredCard
    ranges: list
    start: dict
    values: dict
    standard_errors: dict
    unidentifiable: dict
    correlation: np.ndarray
    sensitivity_cosine: np.ndarray
    residual_rms_Pa: float
    s_Pa: float
    n_residuals: int
    n_points: int
    simulations: int
    cycles: int | None
    wall_time_s: float
    fidelity: str
    result: Result
    end_work: dict
    status: str
    standard_errors_classic: dict = field(default_factory=dict)
    singular_values: list = field(default_factory=list)
    noise_floor: float = 0.0
    bootstrap: dict | None = None
    start_from: dict = field(default_factory=dict)
    at_bound: dict = field(default_factory=dict)

    def write(self, out_dir, *, plots: bool = True, units_system: str | None = None) -> dict:
        """Write ``STEM.json``, ``STEM.toml`` and ``STEM.card.png``, all of them or none
        (STEM: :func:`corliss.files.fit_output.fit_stem`, ``default.fit``).

        Parameters
        ----------
        out_dir : str or Path
            The output folder (made if missing).
        plots : bool, optional
            Whether to draw ``STEM.card.png``.
        units_system : str, optional
            ``"US"`` or ``"SI"`` for the files and figure (default: the scene's).

        Returns
        -------
        dict of str to Path
            ``{kind: path}``: ``summary``, ``scene`` and ``card`` (when drawn).
        """
        return _writer().write(self, out_dir, plots, units_system)

    def plot(self, ax=None, units_system: str | None = None) -> dict:
        """The measured card over the fitted one.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure when None.
        units_system : str, optional
            ``"US"`` (psig, inches) or ``"SI"`` (bar gauge, mm); default the scene's.

        Returns
        -------
        dict
            The matplotlib objects drawn (:func:`corliss.plot.fit_card.plot_fit_card`)
            in the one shape of every ``plot()``: ``figure``, ``axes``, ``ax``,
            ``lines`` (:func:`corliss.plot.shape.one_shape`).
        """
        return _writer().plot(self, ax, units_system)

    @property
    def keys(self) -> list[str]:
        """The fitted keys, in the order given."""
        return [r.key for r in self.ranges]

    @property
    def summary(self) -> dict:
        """The fit as plain values (the JSON of ``corliss fit --json``)."""
        params = []
        for r in self.ranges:
            k = r.key
            entry = {"key": k, "unit": r.unit or "-", "low": r.low, "high": r.high,
                     "start": self.start[k], "start_from": self.start_from.get(k),
                     "value": self.values[k], "standard_error": self.standard_errors[k],
                     "standard_error_classic": self.standard_errors_classic.get(k),
                     "identifiable": k not in self.unidentifiable,
                     "why_unidentifiable": self.unidentifiable.get(k),
                     "at_bound": self.at_bound.get(k)}
            if self.bootstrap is not None:
                entry["bootstrap_standard_error"] = self.bootstrap["standard_errors"].get(k)
                entry["bootstrap_low"] = self.bootstrap["low"].get(k)
                entry["bootstrap_high"] = self.bootstrap["high"].get(k)
            params.append(entry)

        def matrix(m):
            return [[None if not np.isfinite(v) else float(v) for v in row] for row in m]

        return {"kind": "fit", "title": self.scene.title, "card": self.card.source,
                "ends": list(self.card.ends), "parameters": params,
                "correlation": matrix(self.correlation),
                "sensitivity_cosine": matrix(self.sensitivity_cosine),
                "singular_values": [float(v) for v in self.singular_values],
                "jacobian_noise_floor": float(self.noise_floor),
                "residual_rms_Pa": self.residual_rms_Pa, "noise_estimate_Pa": self.s_Pa,
                "residuals_count": self.n_residuals, "points_count": self.n_points,
                "simulations_count": self.simulations, "cycles_per_simulation": self.cycles,
                "fidelity": self.fidelity, "wall_time_s": self.wall_time_s,
                "end_work": self.end_work, "status": self.status,
                "bootstrap_samples": None if self.bootstrap is None else
                self.bootstrap["samples"],
                "bootstrap_seed": None if self.bootstrap is None else self.bootstrap["seed"],
                "indicated_power_W": self.result.summary["indicated_power_W"],
                "indicated_work_J_per_cycle": self.result.summary["indicated_work_J_per_cycle"]}


# --- geometry of loops -------------------------------------------------------------------

def area_weights(x: np.ndarray) -> np.ndarray:
    """Trapezoid weights of a closed loop.

    Parameters
    ----------
    x : ndarray, shape (n,)
        The abscissa of the loop's points in loop order, the last joined to the first
        (any unit).

    Returns
    -------
    ndarray, shape (n,)
        Weights ``w`` in the unit of ``x``: ``sum(w * p)`` is the loop integral of
        ``p dx``, ``w[i] = (x[i+1] - x[i-1]) / 2``.
    """
    return 0.5 * (np.roll(x, -1) - np.roll(x, 1))


def loop_area(x: np.ndarray, p: np.ndarray) -> float:
    """The loop integral of ``p dx`` round a closed polygon, by trapezoids.

    Parameters
    ----------
    x : ndarray, shape (n,)
        The abscissa of the points, in loop order (any unit).
    p : ndarray, shape (n,)
        The ordinate (pressure, or any) at each point.

    Returns
    -------
    float
        The area in the unit of ``x`` times that of ``p`` (a card's work [J] for
        ``x`` in [m3] and ``p`` in [Pa]); positive for a loop traced clockwise in
        (x, p), counter-clockwise negative.
    """
    return float(np.dot(area_weights(x), p))


def loop_distance(px, py, cx, cy):
    """Signed distance of each point to a closed polyline, and the nearest point on it.

    Parameters
    ----------
    px, py : ndarray, shape (m,)
        The points (in the fit, the normalised abscissa and pressure).
    cx, cy : array_like, shape (n,)
        The polyline's vertices in order, the last joined to the first (repeated
        vertices are skipped).

    Returns
    -------
    d : ndarray, shape (m,)
        The distance, positive on the left of the polyline's direction.
    qx, qy : ndarray, shape (m,)
        The nearest point of the polyline.
    nx, ny : ndarray, shape (m,)
        The unit normal of the nearest segment, pointing to the left.
    """
    cx, cy = np.asarray(cx, float), np.asarray(cy, float)
    bx, by = np.roll(cx, -1), np.roll(cy, -1)
    keep = (bx - cx) ** 2 + (by - cy) ** 2 > 0.0
    ax, ay, bx, by = cx[keep], cy[keep], bx[keep], by[keep]
    dx, dy = bx - ax, by - ay
    L2 = dx * dx + dy * dy
    t = np.clip(((px[:, None] - ax) * dx + (py[:, None] - ay) * dy) / L2, 0.0, 1.0)
    qx, qy = ax + t * dx, ay + t * dy
    d2 = (px[:, None] - qx) ** 2 + (py[:, None] - qy) ** 2
    j = np.argmin(d2, axis=1)
    rows = np.arange(px.size)
    qx, qy = qx[rows, j], qy[rows, j]
    L = np.sqrt(L2[j])
    nx, ny = -dy[j] / L, dx[j] / L
    ex, ey = px - qx, py - qy
    sign = np.where(ex * nx + ey * ny < 0.0, -1.0, 1.0)
    return sign * np.sqrt(d2[rows, j]), qx, qy, nx, ny


# --- the problem -------------------------------------------------------------------------

def _start_value(scene, r: KeyRange) -> tuple[float, str]:
    """The scene's value of ``r.key`` in ``r.unit`` if it lies in the range, else the
    middle of the range; and where it came from."""
    raw = get_key(scene.data or {}, r.key)
    mid = 0.5 * (r.low + r.high)
    if raw is None or isinstance(raw, bool):
        return mid, "middle of the range (the scene does not give the key)"
    try:
        kv = parse_value(str(raw), r.key)
        if kv.unit == r.unit:
            v = kv.number
        else:
            baro = scene.supply.barometer_Pa
            v = float(units.to_unit(units.from_unit(kv.number, kv.unit, barometer_Pa=baro),
                                    r.unit, barometer_Pa=baro))
    except (InputError, ValueError):
        return mid, f"middle of the range (the scene's {raw!r} is not in {r.unit or '-'})"
    if not r.low <= v <= r.high:
        return mid, f"middle of the range (the scene's {raw!r} lies outside it)"
    return v, "scene"


class _Problem:
    """The measured card against the simulated one, as a function of the scaled keys."""

    def __init__(self, scene, card: MeasuredCard, ranges: list, fidelity: str,
                 progress: Callable | None):
        self.scene, self.card, self.ranges = scene, card, ranges
        self.base = scene.data
        self.progress = progress
        self.simulations = 0
        self.cache: dict = {}
        self.set_fidelity(fidelity, None)
        p_all = np.concatenate([e.p_Pa for e in card.ends.values()])
        self.P = float(np.ptp(p_all)) or float(np.max(p_all))

    def set_fidelity(self, fidelity: str, cycles: int | None) -> None:
        self.fidelity = fidelity
        self.cycles = cycles
        self.cache = {}

    def values(self, u) -> dict:
        """{key: value in its unit} at scaled keys ``u``."""
        return {r.key: r.low + float(ui) * (r.high - r.low) for r, ui in zip(self.ranges, u)}

    def data(self, u, digits: int | None = None) -> dict:
        vals = self.values(u)
        if digits is not None:
            vals = {k: float(f"{v:.{digits}g}") for k, v in vals.items()}
        return with_keys(self.base, {r.key: r.text(vals[r.key]) for r in self.ranges})

    def scene_at(self, u):
        return scene_from_dict(self.data(u), name=self.scene.name, source=self.scene.source)

    def run(self, u, cycles: int | None = None, tolerance: float | None = None):
        sc = self.scene_at(u).with_fidelity(self.fidelity)
        fid = sc.run.fidelity
        sc = sc.replace_run(fidelity=dataclasses.replace(
            fid, output_step_deg=min(fid.output_step_deg, OUTPUT_STEP_DEG),
            rtol=min(fid.rtol, SEARCH_RTOL.get(self.fidelity, fid.rtol))))
        if tolerance is not None:
            fid = dataclasses.replace(sc.run.fidelity, convergence_tolerance=tolerance,
                                      max_cycles=max(sc.run.fidelity.max_cycles, 40))
            sc = sc.replace_run(fidelity=fid)
        else:
            sc = sc.replace_run(cycles=cycles or self.cycles)
        self.simulations += 1
        try:
            return simulate(sc)
        except RunError as exc:
            where = ", ".join(f"{k} = {v:.6g}" for k, v in self.values(u).items())
            raise RunError(f"{exc} (at {where} of the fit's search)") from None

    def scales(self, result) -> dict:
        """The abscissa's scale of each end, fixed by the first result [unit of x]."""
        out = {}
        geos = {prefix: g for prefix, g, _ in result.cylinder_list}
        for end, e in self.card.ends.items():
            prefix = "lp_" if end.startswith("lp_") else ""
            g = geos.get(prefix, result.geometry)
            if e.abscissa == "piston_frac":
                out[end] = 1.0
            elif e.abscissa == "piston_m":
                out[end] = g.spec.stroke_m
            else:
                out[end] = g.swept_m3[0 if end.endswith("head") else 1]
        return out

    def sim_loop(self, result, end: str) -> tuple[np.ndarray, np.ndarray]:
        """The simulated loop of ``end`` in the measured card's abscissa (SI), without
        the closing point that repeats the first."""
        c = result.cards[end]
        abscissa = self.card.ends[end].abscissa
        if abscissa == "piston_frac":
            x = c["piston_frac"].to_numpy()
        elif abscissa == "piston_m":
            prefix = "lp_" if end.startswith("lp_") else ""
            g = {p: g for p, g, _ in result.cylinder_list}.get(prefix, result.geometry)
            x = c["piston_frac"].to_numpy() * g.spec.stroke_m
        else:
            x = c["V_m3"].to_numpy()
        p = c["p_Pa"].to_numpy()
        if x.size > 2 and x[0] == x[-1] and p[0] == p[-1]:
            x, p = x[:-1], p[:-1]
        return x, p

    def prepare(self, u0) -> None:
        """Fix the cycle count, scales and loop orientations at the start."""
        pilot = self.run(u0, tolerance=PILOT_TOLERANCE)
        missing = [e for e in self.card.ends if e not in pilot.cards]
        if missing:
            raise InputError("card", self.card.source, "ends the scene has ("
                             f"{', '.join(pilot.cards)}); the card holds {', '.join(missing)}")
        conv = pilot.cycles_to_converge
        self.cycles = (conv if conv is not None else len(pilot.cycles)) + 1
        self.xs = self.scales(pilot)
        self.orient = {}
        self.weight = {}
        for end, e in self.card.ends.items():
            xm = e.x / self.xs[end]
            a_m = loop_area(xm, e.p_Pa / self.P)
            x, p = self.sim_loop(pilot, end)
            a_s = loop_area(x / self.xs[end], p / self.P)
            self.orient[end] = -1.0 if a_m * a_s < 0 else 1.0
            self.weight[end] = 1.0 / math.sqrt(float(np.sum(area_weights(xm) ** 2)))

    def measured(self, end, override=None):
        e = self.card.ends[end]
        if override is not None and end in override:
            return override[end]
        return e.x / self.xs[end], e.p_Pa / self.P

    def cache_key(self, u) -> tuple:
        """The key of the run at ``u`` in :attr:`cache` (``u`` to 12 decimals, the tier
        and the cycles)."""
        return (tuple(np.round(np.asarray(u, float), 12)), self.fidelity, self.cycles)

    def residuals(self, u, override=None, detail=False):
        """Point residuals of every end, then one area residual per end [Pa]."""
        key = self.cache_key(u)
        res = self.cache.get(key)
        if res is None:
            res = self.run(u)
            self.cache[key] = res
        pts, areas, geo = [], [], {}
        for end in self.card.ends:
            xm, pm = self.measured(end, override)
            x, p = self.sim_loop(res, end)
            xs, ps = x / self.xs[end], p / self.P
            d, qx, qy, nx, ny = loop_distance(xm, pm, xs, ps)
            pts.append(d * self.P)
            a_m = self.orient[end] * loop_area(xm, pm)
            areas.append((loop_area(xs, ps) - a_m) * self.weight[end] * self.P)
            geo[end] = (qx, qy, nx, ny)
        r = np.concatenate(pts + [np.array(areas)])
        if self.progress is not None and override is None:
            self.progress(self.simulations, float(np.sqrt(np.mean(r ** 2))))
        return (r, res, geo) if detail else r


def _check(scene, ranges: list, card: MeasuredCard | None = None) -> None:
    """Every key at both ends of its range makes a valid scene, and the card's ends are
    the scene's (before any work)."""
    if scene.data is None:
        raise InputError("scene", scene.name, "a scene read from a file or a dict (its tables "
                         "are edited key by key)")
    if scene.run.mode != "steady":
        raise InputError("run.mode", scene.run.mode, "\"steady\": a card is fitted with the "
                         "speed held (the card's own speed, run.speed)")
    if card is not None:
        has = ("head", "crank") + (("lp_head", "lp_crank") if scene.compound else ())
        missing = [e for e in card.ends if e not in has]
        if missing or not card.ends:
            raise InputError("card", card.source, f"ends of the scene ({', '.join(has)}); "
                             f"the card holds {', '.join(card.ends) or 'none'}")
    if not ranges:
        raise InputError("--vary", None, "at least one KEY=LOW:HIGH")
    keys = [r.key for r in ranges]
    dup = sorted({k for k in keys if keys.count(k) > 1})
    if dup:
        raise InputError("--vary", dup[0], "each key once")
    for r in ranges:
        if not isinstance(r, KeyRange):
            raise InputError("--vary", r, "KEY=LOW:HIGH ranges")
        if r.key.split(".")[0] in ("run", "output"):
            raise InputError("--vary", r.key, "a key of the engine, its steam or its gear; "
                             "run and output keys are the fit's own")
        for v in (r.low, r.high):
            scene_from_dict(with_keys(scene.data, {r.key: r.text(v)}), name=scene.name)


#: Problems a pool's worker keeps (a problem is unpickled once a worker, and its cache of
#: runs kept between its tasks: :func:`corliss.studies.pool.unpickled_once`).
_KEEP_PROBLEMS = 2


def _shipped(prob: _Problem) -> tuple[str, bytes]:
    """The problem as sent to a pool's workers: pickled without its progress callback
    and its cache of runs, and the hash that names it."""
    p = copy.copy(prob)
    p.progress, p.cache, p.simulations = None, {}, 0
    blob = pickle.dumps(p, protocol=pickle.HIGHEST_PROTOCOL)
    return hashlib.sha1(blob).hexdigest(), blob


def _worker_problem(token: str, blob: bytes) -> _Problem:
    return unpickled_once("fit", token, blob, _KEEP_PROBLEMS)


def _residuals_task(token: str, blob: bytes, u: np.ndarray) -> np.ndarray:
    """A pool worker's task: the residuals at ``u`` (one simulation)."""
    return _worker_problem(token, blob).residuals(u)


def _refit_task(token: str, blob: bytes, u: np.ndarray, free: list, h: float,
                override: dict) -> tuple[np.ndarray, int]:
    """A pool worker's task: one bootstrap refit; its optimum and the simulations it
    made (runs this worker had made before for the same problem are read back from
    its cache, not made again)."""
    prob = _worker_problem(token, blob)
    n0 = prob.simulations
    ub, _ = _solve(prob, u, free, h, override)
    return ub, prob.simulations - n0


def _residuals_at(prob: _Problem, points: list, jobs: int) -> list:
    """The residuals at each of ``points``: here, one after another, when ``jobs`` is 1;
    else the runs not in the problem's cache on ``jobs`` workers of the kept pool (the
    same numbers: a run depends only on its inputs), the progress called here as each
    comes back."""
    if jobs <= 1:
        return [prob.residuals(x) for x in points]
    out: list = [None] * len(points)
    todo = []
    for i, x in enumerate(points):
        if prob.cache_key(x) in prob.cache:
            out[i] = prob.residuals(x)
        else:
            todo.append(i)
    token, blob = _shipped(prob)

    def collect(j, r):
        out[todo[j]] = r
        prob.simulations += 1
        if prob.progress is not None:
            prob.progress(prob.simulations, float(np.sqrt(np.mean(r ** 2))))

    run_tasks([(_residuals_task, (token, blob, points[i])) for i in todo], jobs, collect)
    return out


def _jacobian(prob: _Problem, u: np.ndarray, r0: np.ndarray, h: float, jobs: int = 1):
    """Central-difference Jacobian at ``u`` (each step kept inside [0, 1]), each
    column's noise floor from the second difference of the same runs, and which rows
    are smooth: their second differences within :data:`SECANT_ROW_FACTOR` of each
    column's robust scale of them (the others are secants across a corner).  The runs
    go to ``jobs`` processes (:func:`_residuals_at`)."""
    J = np.empty((r0.size, u.size))
    noise = np.empty(u.size)
    smooth = np.ones(r0.size, dtype=bool)
    steps, points = [], []
    for i in range(u.size):
        lo, hi = u[i] - h, u[i] + h
        if lo < 0.0:
            lo, hi = 0.0, 2.0 * h
        elif hi > 1.0:
            lo, hi = 1.0 - 2.0 * h, 1.0
        ua, ub, um = u.copy(), u.copy(), u.copy()
        ua[i], ub[i], um[i] = lo, hi, 0.5 * (lo + hi)
        steps.append((lo, hi, um[i] == u[i]))
        points += [ua, ub] + ([] if um[i] == u[i] else [um])
    rs = iter(_residuals_at(prob, points, jobs))
    for i, (lo, hi, at_u) in enumerate(steps):
        ra, rb = next(rs), next(rs)
        rm = r0 if at_u else next(rs)
        J[:, i] = (rb - ra) / (hi - lo)
        d2 = (rb - 2.0 * rm + ra) / (0.5 * (hi - lo))
        # pure noise e on each run gives a central difference of e/(sqrt(2) h) and a
        # second difference of sqrt(6) e / h: the central difference's noise is
        # 0.29 of the second difference's size
        # (a robust scale: a few points at the card's sharp corners, where the nearest
        # point of the simulated loop moves from one line to the next, have a large
        # second difference that is no noise)
        mad = float(np.median(np.abs(d2 - np.median(d2)))) * 1.4826
        noise[i] = mad * math.sqrt(d2.size / 12.0)
        smooth &= np.abs(d2 - np.median(d2)) <= SECANT_ROW_FACTOR * mad
    return J, noise, smooth


def _uncertainty(J: np.ndarray, noise: np.ndarray, r: np.ndarray, keys: list[str],
                 smooth: np.ndarray | None = None):
    """Standard errors of the scaled keys (sandwich), the unidentifiable ones and why,
    the correlation, the columns' cosines, the singular values, the noise floor, and
    the standard errors s^2 (J^T J)^-1 would give.  The cosines and the singular values
    (the test of directions) are of the ``smooth`` rows (all when None)."""
    n, p = J.shape
    Js = J if smooth is None else J[smooth]
    norms_s = np.linalg.norm(Js, axis=0)
    s2 = float(np.sum(r ** 2)) / max(n - p, 1)
    norms = np.linalg.norm(J, axis=0)
    floor = float(np.max(noise)) if noise.size else 0.0
    why: dict[str, str] = {}
    for i, k in enumerate(keys):
        if norms[i] <= NOISE_FACTOR * noise[i]:
            why[k] = ("the card does not change with it above the solver's noise (its "
                      f"sensitivity {norms[i]:.3g} against a noise of {noise[i]:.3g}, in Pa "
                      "over its range)")
    with np.errstate(invalid="ignore", divide="ignore"):
        cos = (Js.T @ Js) / np.outer(norms_s, norms_s)
    live = [i for i in range(p) if keys[i] not in why]
    sv = np.linalg.svd(Js[:, live], compute_uv=False) if live else np.array([])
    if len(live) > 1:
        _, svals, vt = np.linalg.svd(Js[:, live], full_matrices=False)
        for k_sv, v in zip(svals, vt):
            if k_sv <= NOISE_FACTOR * floor:
                members = [keys[live[j]] for j in range(len(live)) if abs(v[j]) > 0.3]
                if len(members) > 1:
                    for m in members:
                        others = ", ".join(o for o in members if o != m)
                        why.setdefault(m, "the card cannot tell it from " + others + ": they "
                                       "change the card together, along a direction it does "
                                       "not show above the solver's noise")
    se = np.full(p, np.nan)
    se_classic = np.full(p, np.nan)
    corr = np.full((p, p), np.nan)
    for _ in range(p):
        live = [i for i in range(p) if keys[i] not in why]
        if not live:
            break
        Jl = J[:, live]
        try:
            A = np.linalg.inv(Jl.T @ Jl)
        except np.linalg.LinAlgError:
            A = np.linalg.pinv(Jl.T @ Jl)
        classic = s2 * A
        sandwich = A @ ((Jl.T * r ** 2) @ Jl) @ A * (n / max(n - p, 1))
        cov = sandwich if COVARIANCE == "sandwich" else classic
        d = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        wide = [live[j] for j in range(len(live)) if not d[j] <= 1.0]
        if wide:
            for i in wide:
                why[keys[i]] = ("its standard error is larger than its range: the card "
                                f"pins it only to {d[live.index(i)]:.3g} of the range")
            continue
        se[:] = np.nan
        se[live] = d
        se_classic[live] = np.sqrt(np.clip(np.diag(classic), 0.0, None))
        corr[np.ix_(live, live)] = cov / np.outer(d, d)
        break
    return se, why, corr, cos, sv, floor, se_classic


def _solve(prob: _Problem, u0: np.ndarray, free: list[int], h: float, override=None):
    """least_squares over the ``free`` scaled keys from ``u0``."""
    # imported here: ``import corliss`` (and every warm run) stays clear of scipy's
    # solvers (tests/test_startup.py)
    from scipy.optimize import least_squares

    u_fixed = u0.copy()

    def fun(z):
        u = u_fixed.copy()
        u[free] = z
        return prob.residuals(u, override)

    z0 = np.clip(u0[free], 1e-6, 1.0 - 1e-6)
    sol = least_squares(fun, z0, bounds=(0.0, 1.0), method="trf", jac="2-point",
                        diff_step=h, x_scale=1.0, xtol=XTOL, ftol=FTOL, gtol=1e-8,
                        max_nfev=MAX_NFEV_PER_KEY * len(free))
    u = u_fixed.copy()
    u[free] = sol.x
    return u, sol


def fit_card(scene, card: MeasuredCard, ranges: list, *, fidelity: str = "fast",
             refine: bool = False, bootstrap: int = 0, seed: int = 0, jobs: int = 1,
             progress: Callable[[int, float], None] | None = None) -> FitResult:
    """Calibrate scene keys to a measured card (see the module's notes).

    Parameters
    ----------
    scene : Scene
        A steady scene read from a file (its tables are edited key by key); its values
        of the keys are the start (the middle of a range that does not hold them).
    card : MeasuredCard
        The measured card (:func:`corliss.fitting.card.read_card`), any of the scene's
        ends.
    ranges : list of KeyRange
        The keys to fit and their bounds (:func:`corliss.keys.edits.parse_range`).
    fidelity : str, optional
        Tier of the search: ``fast`` (default), ``standard`` or ``reference``.
    refine : bool, optional
        Repeat a ``fast`` search from its optimum on the ``standard`` tier.
    bootstrap : int, optional
        Wild-bootstrap refits of the residuals (0: none; at most 10000).
    seed : int, optional
        Seed of the bootstrap's draws.
    jobs : int, optional
        Processes [-] (default 1: here).  More run the uncertainty's Jacobian and the
        bootstrap's refits on the process's kept pool of workers
        (:mod:`corliss.studies.pool`, as a study's runs): the same values, standard
        errors and refits as on one (the search itself is one run after another).  A
        worker's refits share its runs, as one process's share all of them, so the
        count of simulations can be larger.
    progress : callable, optional
        Called after each simulation with (simulations so far, residual RMS [Pa]).

    Returns
    -------
    FitResult
        The fitted values with their standard errors (or why a key is not
        determined), the fitted scene, and the simulation at the optimum.

    Raises
    ------
    InputError
        A key the scene cannot take at an end of its range, a repeated key, a transient
        scene, a card with fewer points than keys, an end the scene does not have.
    """
    t0 = time.perf_counter()
    if fidelity not in PRESETS:
        raise InputError("--fidelity", fidelity, "one of " + ", ".join(PRESETS))
    if isinstance(bootstrap, bool) or not isinstance(bootstrap, int) or not 0 <= bootstrap <= 10000:
        raise InputError("--bootstrap", bootstrap, "a whole number of refits from 0 to 10000")
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise InputError("--jobs", jobs, "a whole number of processes, 1 or more")
    _check(scene, ranges, card)
    n_res = card.n_points + len(card.ends)
    if n_res <= len(ranges) + 1:
        raise InputError("card", card.source, f"more points ({card.n_points}) than keys to "
                         f"fit ({len(ranges)})")
    starts = {r.key: _start_value(scene, r) for r in ranges}
    u0 = np.array([(starts[r.key][0] - r.low) / (r.high - r.low) for r in ranges])
    prob = _Problem(scene, card, ranges, fidelity, progress)
    prob.prepare(u0)
    free = list(range(len(ranges)))
    u, sol = _solve(prob, u0, free, DIFF_STEP[fidelity])
    final = fidelity
    if refine and fidelity == "fast":
        final = "standard"
        prob.set_fidelity(final, None)
        prob.prepare(u)
        u, sol = _solve(prob, u, free, DIFF_STEP[final])
    r0, best, geo = prob.residuals(u, detail=True)
    n, p = r0.size, len(ranges)
    s = math.sqrt(float(np.sum(r0 ** 2)) / max(n - p, 1))
    J, noise, smooth = _jacobian(prob, u, r0, COV_STEP_FACTOR * DIFF_STEP[final], jobs)
    keys = [r.key for r in ranges]
    se_u, why, corr, cos, sv, floor, se_c = _uncertainty(J, noise, r0, keys, smooth)
    values = prob.values(u)
    spans = np.array([r.high - r.low for r in ranges])
    se = {k: (None if k in why else float(se_u[i] * spans[i])) for i, k in enumerate(keys)}
    se_classic = {k: (None if k in why else float(se_c[i] * spans[i]))
                  for i, k in enumerate(keys)}

    boot = None
    if bootstrap:
        boot = _bootstrap(prob, u, r0, geo, [i for i, k in enumerate(keys) if k not in why],
                          bootstrap, seed, DIFF_STEP[final], jobs)

    n_pts = card.n_points
    fitted_data = prob.data(u, digits=6)
    fitted_scene = scene_from_dict(fitted_data, name=scene.name, source=scene.source)
    return FitResult(
        scene=scene, fitted_scene=fitted_scene, fitted_data=fitted_data, card=card,
        ranges=list(ranges), start={k: v for k, (v, _) in starts.items()}, values=values,
        standard_errors=se, standard_errors_classic=se_classic, unidentifiable=why, correlation=corr, sensitivity_cosine=cos,
        residual_rms_Pa=float(np.sqrt(np.mean(r0[:n_pts] ** 2))), s_Pa=s, n_residuals=n,
        n_points=n_pts, simulations=prob.simulations, cycles=prob.cycles,
        wall_time_s=time.perf_counter() - t0, fidelity=final, result=best,
        end_work=_end_work(prob, best), status=str(sol.message), singular_values=list(sv),
        noise_floor=floor, bootstrap=boot,
        start_from={k: w for k, (_, w) in starts.items()},
        at_bound={r.key: (None if 1e-3 < ui < 1 - 1e-3 else ("low" if ui <= 1e-3 else "high"))
                  for r, ui in zip(ranges, u)})


def _end_work(prob: _Problem, result) -> dict:
    """Per end: the measured and fitted m.e.p. [Pa] (the loop's area over the normalised
    abscissa, times the swept volume over the stroke's) and the fitted card's work as
    the area of its loop in volume [J], beside the integrator's work [J]."""
    out = {}
    row = result.last_cycle
    geos = {prefix: g for prefix, g, _ in result.cylinder_list}
    for end, e in prob.card.ends.items():
        prefix = "lp_" if end.startswith("lp_") else ""
        g = geos.get(prefix, result.geometry)
        swept = g.swept_m3[0 if end.endswith("head") else 1]
        x, p = prob.sim_loop(result, end)
        xs = prob.xs[end]
        # m.e.p.: the area per unit of the abscissa's full span (stroke or swept volume)
        span = 1.0 if e.abscissa == "piston_frac" else (g.spec.stroke_m if e.abscissa ==
                                                        "piston_m" else swept)
        sign = 1.0 if e.abscissa != "piston_frac" and e.abscissa != "piston_m" \
            or end.endswith("head") else -1.0
        c = result.cards[end]
        work_card = loop_area(c["V_m3"].to_numpy()[:-1], c["p_Pa"].to_numpy()[:-1])
        out[end] = {
            "measured_mep_Pa": sign * prob.orient[end] * loop_area(e.x / xs, e.p_Pa) * xs / span,
            "fitted_mep_Pa": sign * loop_area(x / xs, p) * xs / span,
            "fitted_card_work_J": work_card,
            "integrated_work_J": float(row[f"work_{end}_J"])}
    return out


def _bootstrap(prob: _Problem, u: np.ndarray, r0: np.ndarray, geo: dict, free: list[int],
               samples: int, seed: int, h: float, jobs: int = 1) -> dict:
    """Wild bootstrap: cards made of the fitted loop's nearest points, each moved along
    the normal by its own residual with a random sign, each refitted from the
    optimum (the refits on ``jobs`` workers of the kept pool when more than 1; the
    draws are made here, in order, so the refits are the same)."""
    rng = np.random.default_rng(seed)
    keys = [r.key for r in prob.ranges]
    spans = np.array([r.high - r.low for r in prob.ranges])
    n_pts = prob.card.n_points
    own = r0[:n_pts] / prob.P
    overrides = []
    for _ in range(samples):
        override = {}
        start = 0
        for end in prob.card.ends:
            qx, qy, nx, ny = geo[end]
            draw = own[start:start + qx.size] * rng.choice((-1.0, 1.0), size=qx.size)
            start += qx.size
            override[end] = (qx + draw * nx, qy + draw * ny)
        overrides.append(override)
    fits: list = [u] * samples
    if free and jobs > 1 and samples > 1:
        token, blob = _shipped(prob)
        rms = float(np.sqrt(np.mean(r0 ** 2)))

        def collect(i, got):
            fits[i] = got[0]
            prob.simulations += got[1]
            if prob.progress is not None:
                prob.progress(prob.simulations, rms)

        run_tasks([(_refit_task, (token, blob, u, free, h, o)) for o in overrides], jobs,
                  collect)
    elif free:
        fits = [_solve(prob, u, free, h, o)[0] for o in overrides]
    vals = np.array([r.low for r in prob.ranges]) + np.array(fits) * spans
    return {"samples": samples, "seed": seed,
            "standard_errors": {keys[i]: float(np.std(vals[:, i], ddof=1)) if samples > 1
                                else None for i in free},
            "low": {keys[i]: float(np.percentile(vals[:, i], 2.5)) for i in free},
            "high": {keys[i]: float(np.percentile(vals[:, i], 97.5)) for i in free}}
