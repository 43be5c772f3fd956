"""Whether a steady run's mass and energy balances close: a run whose cycle does not
conserve the steam it passes is not a result, whatever its work settled to.

A periodic cycle takes in at the supply what it gives to the exhaust, and the
enthalpy it takes in is its work, its exhaust's enthalpy and the heat to its walls
(the first law over a cycle of a control volume that returns to its state); the
summary's ``mass_balance_error`` and ``energy_balance_error`` are those sums'
imbalances against the steam and enthalpy supplied.  Their size on a converged run
is set by the integrator's and the periodicity's tolerance: on the bundled steady
scenes, measured, they are at most 2.5 times the preset's ``convergence_tolerance``
(the nine-cylinder compound, fast: 0.0025 and 0.0028 against 0.001; standard: 1.7e-4
against 1e-4) and mostly below it.  :data:`BALANCE_FACTOR` times the tolerance
leaves room for that and still fails a compound whose huge receiver has not filled
(a mass-balance error of 0.89 with the work periodic to 2.4e-4).
"""

from __future__ import annotations

#: A run's balance errors may be this many times its fidelity's convergence tolerance.
BALANCE_FACTOR = 10.0
#: The least tolerance of a balance, whatever the fidelity asks [-]: the reference
#: preset's 1e-6 periodicity is below what its quadratures of the flows resolve.
BALANCE_FLOOR = 1e-4


def balance_tolerance(convergence_tolerance: float) -> float:
    """The largest balance error a run may have and be a result [-].

    Parameters
    ----------
    convergence_tolerance : float
        The run's periodicity tolerance [-].

    Returns
    -------
    float
        ``max(BALANCE_FACTOR * convergence_tolerance, BALANCE_FLOOR)`` [-].
    """
    return max(BALANCE_FACTOR * convergence_tolerance, BALANCE_FLOOR)


def balance_failure(summary: dict) -> str | None:
    """Why a steady run's balances fail it, or None when they close.

    Parameters
    ----------
    summary : dict
        A steady result's summary: ``mass_balance_error``, ``energy_balance_error``
        (None where not defined), ``convergence_tolerance`` and
        ``steam_per_cycle_kg`` (a run through which no steam passes net is not judged:
        the errors are fractions of that steam).

    Returns
    -------
    str or None
        A sentence naming the largest error, its value and the tolerance; None if
        every error is within it (or none is defined).
    """
    if not (summary.get("steam_per_cycle_kg") or 0.0) > 0.0:
        # no steam through the engine net (a valve that barely opens, an engine driven
        # far past its speed pumping back): the errors' scale, the steam supplied, is
        # a small difference itself, and the run reports no water rate to trust
        return None
    tol = balance_tolerance(float(summary["convergence_tolerance"]))
    found = {k: summary.get(k) for k in ("mass_balance_error", "energy_balance_error")}
    errors = {k: float(v) for k, v in found.items() if v is not None}
    if not errors:
        return None
    worst = max(errors, key=lambda k: errors[k] if errors[k] == errors[k] else float("inf"))
    v = errors[worst]
    if v <= tol:
        return None
    what = worst.removesuffix("_error").replace("_", " ")
    return (f"the {what} does not close: its error is {v:.3g} against a tolerance of "
            f"{tol:.3g} ({BALANCE_FACTOR:g} times the periodicity tolerance)")
