"""Marks's constant as a period calibration of the skin wall.

Marks's eq. 221 (Relative Proportions, Art. 75, p. 190; constant Art. 82, p. 209)
gives the steam condensed per stroke from the temperature fall, the iron exposed and
the time of exposure, averaged over the engines of his concordant experiments.  With
``condensing_coefficient = "marks"`` the skin wall's coefficient of condensation and
evaporation is set, for the scene's own engine, so that the model's missing water at
cut-off (head end, read from the steam's state) equals the fraction eq. 221 gives for
the same card (``marks_missing_water_fraction_head``), both from one converged run.
"""

from __future__ import annotations

import dataclasses
import logging
import math

log = logging.getLogger(__name__)

#: The coefficient's search range [W/(m2 K)]: Nusselt's drained film's order down to
#: a tenth of it, and dropwise condensation's.
LOWEST, HIGHEST = 1.0e3, 3.0e5


def marks_coefficient(scene, run, *, tol: float = 0.01, max_runs: int = 12) -> float:
    """Marks's condensing coefficient for the scene's own engine.

    The coefficient at which the skin wall's missing water at cut-off (head end) is
    Marks's eq. 221's for the same card (Relative Proportions, Art. 75, p. 190), to
    ``tol`` of it: a regula falsi (Illinois) on the logarithm of the coefficient,
    bracketed by :data:`LOWEST` and :data:`HIGHEST` (the missing water rises with the
    coefficient).

    Parameters
    ----------
    scene : Scene
        The scene whose engine is calibrated; its ``engine.condensing_W_m2K`` is
        replaced at each trial.
    run : callable
        The steady runner, ``run(scene) -> result``; the result's ``summary`` holds
        ``missing_water_fraction_head`` and ``marks_missing_water_fraction_head``.
    tol : float
        Tolerance on the logarithm of the ratio of the two missing waters [-] (about
        a relative tolerance on the ratio).
    max_runs : int
        Most trial runs after the two at the bounds.

    Returns
    -------
    float
        The coefficient of condensation and evaporation [W/(m2 K)]; the nearer bound
        when eq. 221 lies outside what the range gives.
    """
    def gap(h):
        eng = dataclasses.replace(scene.engine, condensing_W_m2K=h)
        s = run(dataclasses.replace(scene, engine=eng)).summary
        return math.log(s["missing_water_fraction_head"]
                        / s["marks_missing_water_fraction_head"])

    a, b = math.log(LOWEST), math.log(HIGHEST)
    fa, fb = gap(LOWEST), gap(HIGHEST)
    if fa >= 0.0:
        return LOWEST
    if fb <= 0.0:
        return HIGHEST
    for _ in range(max_runs):
        c = b - fb * (b - a) / (fb - fa)          # regula falsi (Illinois), in log h
        fc = gap(math.exp(c))
        if abs(fc) < tol:
            break
        if fc * fb < 0.0:
            a, fa = b, fb
        else:
            fa *= 0.5
        b, fb = c, fc
    log.info("condensing coefficient set by Marks's eq. 221: %.4g W/(m2 K)", math.exp(c))
    return math.exp(c)
