"""Sampling designs of a study: which scenes to run.

A design is a table of values of the varied scene keys, one row a run, each key's
values in the unit the user wrote (:mod:`corliss.keys.edits`):

- ``grid``: the full factorial of every key's levels (``KEY=LOW:HIGH`` at ``levels``
  evenly spaced values, ends included, or ``KEY=a,b,c``), the first key varying
  slowest;
- ``lhs``: a Latin hypercube of ``n`` runs (McKay, Beckman and Conover,
  *Technometrics* 21 (1979) 239-245): each key's probability range cut into ``n``
  equal strata, one run in each, the strata paired at random across keys
  (:class:`scipy.stats.qmc.LatinHypercube`); a key with a distribution gets its
  values through the inverse distribution function, so its strata are of equal
  probability;
- ``monte_carlo``: ``n`` independent draws of every key from its distribution
  (``KEY=LOW:HIGH`` uniform, ``normal(MEAN,SD)``, ``triangular(LOW,MODE,HIGH)``).

Both random designs are drawn from :func:`numpy.random.default_rng` seeded with
``seed``: the same seed gives the same runs, on any machine with the same numpy and
scipy.  Every value is rounded to :data:`SIGNIFICANT_DIGITS` significant digits, the
digits the study's CSV writes, so the scene rebuilt from a row of the CSV is the scene
that was run, to the last bit.
"""

from __future__ import annotations

import itertools
import re
from dataclasses import dataclass

import numpy as np

from corliss.errors import InputError
from corliss.keys.edits import KeyRange, KeyValues, parse_distribution, parse_range, parse_values

#: The designs a study knows.
DESIGNS = ("grid", "lhs", "monte_carlo")
#: Significant digits every sampled value is rounded to [-] (those of the CSV's floats).
SIGNIFICANT_DIGITS = 9
#: Most runs a study may ask for (a million fits a cluster, not this process's memory
#: of rows beyond it) [-].
MAX_RUNS = 10_000_000
#: Probabilities are kept this far inside (0, 1), so a normal key's inverse is finite.
_U_EDGE = 1e-12


def quantize(x):
    """Values rounded to :data:`SIGNIFICANT_DIGITS` significant digits (what the CSV holds).

    Parameters
    ----------
    x : float or array_like
        Values in any unit.

    Returns
    -------
    ndarray
        The rounded values as floats, shaped as ``x``.
    """
    return np.array([float(f"{v:.{SIGNIFICANT_DIGITS}g}") for v in np.ravel(x)]).reshape(
        np.shape(x))


def column_of(spec) -> str:
    """The table's column for a varied key: its dotted name and its unit.

    Named as the package names columns (``valve_gear.lap_in``, ``run.speed_rpm``;
    ``_frac`` for a dimensionless key, ``engine.clearance_frac``); in the unit,
    characters other than letters and digits become ``_`` (``supply.pressure_psig``).

    Parameters
    ----------
    spec : KeyRange or KeyValues or KeyDistribution
        The varied key (its ``key`` and ``unit``).

    Returns
    -------
    str
        The column's name.
    """
    unit = re.sub(r"[^A-Za-z0-9]+", "_", spec.unit).strip("_") if spec.unit else "frac"
    return f"{spec.key}_{unit}"


@dataclass(frozen=True)
class Design:
    """The runs of a study (made by :func:`make_design`).

    Parameters
    ----------
    kind : str
        ``"grid"``, ``"lhs"`` or ``"monte_carlo"``.
    specs : tuple
        The varied keys, each a :class:`~corliss.keys.edits.KeyRange`,
        :class:`~corliss.keys.edits.KeyValues` or
        :class:`~corliss.keys.edits.KeyDistribution`, in the order given.
    values : ndarray, shape (runs, keys)
        Each key's values in its spec's unit, rounded by :func:`quantize`.
    seed : int or None
        The random designs' seed; None for a grid.
    """

    kind: str
    specs: tuple
    values: np.ndarray
    seed: int | None

    @property
    def runs(self) -> int:
        """Runs in the design [-]."""
        return int(self.values.shape[0])

    @property
    def columns(self) -> list[str]:
        """The table's column of each varied key (:func:`column_of`)."""
        return [column_of(s) for s in self.specs]

    def changes(self, i: int) -> dict:
        """What run ``i`` sets in the base scene.

        Parameters
        ----------
        i : int
            The run's number in the design, from 0.

        Returns
        -------
        dict
            ``{dotted key: scene value}``, each value a quantity string in its key's
            unit (``"0.85 in"``), or a float for a dimensionless key, for
            :func:`corliss.keys.edits.with_keys`.
        """
        return {s.key: s.text(float(v)) for s, v in zip(self.specs, self.values[i])}

    def describe(self) -> list[dict]:
        """Each varied key as plain data (for the meta file and the summary).

        Returns
        -------
        list of dict
            Per key, in order: ``key``, ``unit``, ``column`` and either ``kind =
            "range"`` with ``low`` and ``high``, ``kind = "levels"`` with ``values``, or
            the distribution's ``kind`` with its ``params`` (in the key's unit).
        """
        out = []
        for s, col in zip(self.specs, self.columns):
            d = {"key": s.key, "unit": s.unit, "column": col}
            if isinstance(s, KeyRange):
                d.update(kind="range", low=s.low, high=s.high)
            elif isinstance(s, KeyValues):
                d.update(kind="levels", values=list(s.values))
            else:
                d.update(kind=s.kind, params=list(s.params))
            out.append(d)
        return out


def _check_n(flag: str, n) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 1 <= n <= MAX_RUNS:
        raise InputError(flag, n, f"a whole number of runs from 1 to {MAX_RUNS:,}")
    return int(n)


def _distinct(specs) -> None:
    seen = set()
    for s in specs:
        if s.key in seen:
            raise InputError("--vary", s.key, "each key varied once")
        seen.add(s.key)


def make_design(vary, *, grid: bool = False, levels: int = 3, lhs: int | None = None,
                monte_carlo: int | None = None, seed: int | None = 0) -> Design:
    """The runs of a study from its ``--vary`` options.

    Parameters
    ----------
    vary : sequence of str
        ``KEY=LOW:HIGH``, ``KEY=a,b,c`` (grid only) or ``KEY=normal(MEAN,SD)UNIT`` and
        ``KEY=triangular(LOW,MODE,HIGH)UNIT`` (random designs only), one per key.
    grid : bool, optional
        The full factorial design.
    levels : int, optional
        Levels of every ``LOW:HIGH`` key of a grid [-], ends included (2 or more).
    lhs, monte_carlo : int, optional
        Runs of a Latin hypercube or of a Monte Carlo design [-].
    seed : int, optional
        Seed of the random designs (default 0: reproducible; None draws a fresh one,
        recorded in the design).

    Returns
    -------
    Design
        The design: its kind, the keys' specs, the runs' values (rounded to
        :data:`SIGNIFICANT_DIGITS`) and the seed (None for a grid).

    Raises
    ------
    InputError
        Naming the option: not exactly one design, no key, a key twice, a grid with a
        distribution or a random design with a list, a bad count.
    """
    chosen = [name for name, on in (("--grid", grid), ("--lhs", lhs is not None),
                                    ("--monte-carlo", monte_carlo is not None)) if on]
    if len(chosen) != 1:
        raise InputError("design", " ".join(chosen) or None,
                         "exactly one of --grid, --lhs N or --monte-carlo N")
    if isinstance(vary, str):
        vary = [vary]
    if not vary:
        raise InputError("--vary", None, "one or more KEY=LOW:HIGH, e.g. "
                         "--vary valve_gear.lap=0.8:1.2in")
    if grid:
        if isinstance(levels, bool) or not isinstance(levels, (int, np.integer)) or levels < 2:
            raise InputError("--levels", levels, "a whole number of levels, 2 or more")
        grid_specs: list[KeyValues | KeyRange] = []
        for v in vary:
            rhs = v.split("=", 1)[-1] if isinstance(v, str) else ""
            if "(" in rhs:
                raise InputError("--vary", v, "LOW:HIGH or a list a,b,c for a grid (a "
                                 "distribution is for --lhs or --monte-carlo)")
            grid_specs.append(parse_values(v) if "," in rhs else parse_range(v))
        _distinct(grid_specs)
        axes = [quantize(s.values if isinstance(s, KeyValues) else
                         np.linspace(s.low, s.high, int(levels))) for s in grid_specs]
        n = int(np.prod([len(a) for a in axes], dtype=float))
        if n > MAX_RUNS:
            raise InputError("--levels", levels, f"a grid of at most {MAX_RUNS:,} runs "
                             f"(this one has {n:,})")
        values = np.array(list(itertools.product(*axes)), dtype=float)
        return Design("grid", tuple(grid_specs), values.reshape(n, len(grid_specs)), None)
    specs = []
    for v in vary:
        rhs = v.split("=", 1)[-1] if isinstance(v, str) else ""
        if "," in rhs and "(" not in rhs:
            raise InputError("--vary", v, "LOW:HIGH or a distribution for a random design "
                             "(a list of levels is for --grid)")
        specs.append(parse_distribution(v))
    _distinct(specs)
    if seed is None:
        entropy: int = np.random.SeedSequence().entropy  # type: ignore[assignment]  # a fresh sequence's entropy is an int
        seed = int(entropy % (2 ** 32))
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise InputError("--seed", seed, "a whole number, 0 or more")
    rng = np.random.default_rng(int(seed))
    if lhs is not None:
        n = _check_n("--lhs", lhs)
        from scipy.stats import qmc
        u = qmc.LatinHypercube(d=len(specs), rng=rng).random(n)
        kind = "lhs"
    else:
        n = _check_n("--monte-carlo", monte_carlo)
        u = rng.random((n, len(specs)))
        kind = "monte_carlo"
    u = np.clip(u, _U_EDGE, 1.0 - _U_EDGE)
    values = np.column_stack([quantize(s.ppf(u[:, j])) for j, s in enumerate(specs)])
    return Design(kind, tuple(specs), values, int(seed))
