"""Whether a completed run is physically sound: the failures a script must not miss.

A run can end without an error and still describe no working engine: the card does
negative work (the piston drives the steam, as a locomotive's cylinder at a speed its
ports cannot fill), a steady run never became periodic, the load stopped the engine,
the governor let it run away above its range or hunts, or a run asked to go on until
settled did not settle.  Each is reported in the summary's ``failures`` list
(``{"failure": name, "reason": words}``) and the command exits with
:data:`EXIT_PHYSICAL` after writing every file (``docs/exit-codes.md``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from corliss.keys import units

#: Exit status of a run that completed, its files written, but failed physically.
EXIT_PHYSICAL = 4

#: How far above the speed at which the governor balances at its top stop the final
#: speed may lie before the run counts as run away [fraction]: the settling band of a
#: load step is 2 %, and a governor at its stop with the speed 5 % above its range has
#: lost control of the engine.
RUN_AWAY_MARGIN = 0.05

#: The governor counts as at its top stop above this coordinate [-].
TOP_STOP_Z = 0.99


def _fail(name: str, reason: str) -> dict:
    return {"failure": name, "reason": reason}


def steady_failures(summary: Mapping[str, Any], fixed_cycles: bool = False) -> list[dict]:
    """The failures of a steady run.

    Parameters
    ----------
    summary : dict
        The steady summary (``indicated_power_W``, ``steam_rate_kg_per_h``,
        ``cycles_to_converge``, ``periodicity_residuals``, ``convergence_tolerance``).
    fixed_cycles : bool, optional
        The run was asked for a fixed number of cycles (periodicity not sought).

    Returns
    -------
    list of dict
        ``negative_work`` (indicated power at or below zero), ``negative_steam`` (steam
        flows back into the supply over a cycle), ``not_periodic`` (the cycle did not
        repeat within the tolerance).
    """
    out = []
    p = summary["indicated_power_W"]
    if not p > 0.0:
        out.append(_fail("negative_work", f"the card does no net work ({p:.4g} W indicated): "
                         "the engine absorbs power at this speed and setting"))
    m = summary["steam_rate_kg_per_h"]
    if m < 0.0:
        out.append(_fail("negative_steam", f"steam flows back into the supply "
                         f"({m:.4g} kg/h): the cylinder pumps"))
    res = summary.get("periodicity_residuals") or {}
    if not fixed_cycles and summary.get("cycles_to_converge") is None and res:
        wall = ("; the wall has no periodic state: its balance over a cycle jumps"
                if summary.get("wall_periodic_state") else "")
        out.append(_fail("not_periodic", f"the cycle did not become periodic (largest "
                         f"residual {max(res.values()):.2g}, tolerance "
                         f"{summary['convergence_tolerance']:.2g}{wall})"))
    return out


def transient_failures(summary: Mapping[str, Any], mechanism, z_end: float | None,
                       until_settled: bool = False) -> list[dict]:
    """The failures of a transient run.

    Parameters
    ----------
    summary : dict
        The transient summary (``stalled``, ``hunting``, ``settled``,
        ``final_speed_rpm``, ``final_indicated_power_W``).
    mechanism : GovernorMechanism or None
        The governor, tabulated (None for a free engine).
    z_end : float or None
        The governor's coordinate in the last turn [-].
    until_settled : bool, optional
        The run was asked to go on until the speed settled.

    Returns
    -------
    list of dict
        ``stalled``, ``run_away`` (the governor at its top stop and the speed more than
        :data:`RUN_AWAY_MARGIN` above the speed at which it balances there),
        ``hunting``, ``negative_work`` (final indicated power at or below zero),
        ``not_settled`` (only when settling was asked).
    """
    out = []
    if summary.get("stalled"):
        out.append(_fail("stalled", "the load stopped the engine"))
    n = summary["final_speed_rpm"]
    if mechanism is not None and z_end is not None and z_end >= TOP_STOP_Z:
        # a governed run only: a steady run's verdict loads no governor
        from corliss.governors.operating_point import characteristic_speed
        top = characteristic_speed(mechanism, 1.0) / units.RPM_RAD_S
        if n > (1.0 + RUN_AWAY_MARGIN) * top:
            out.append(_fail("run_away", f"the governor is at its top stop and the speed "
                             f"({n:.4g} rpm) is above its range (it balances there at "
                             f"{top:.4g} rpm): it has lost control of the engine"))
    if summary.get("hunting"):
        out.append(_fail("hunting", f"the governor hunts (period "
                         f"{summary['hunting_period_s']:.3g} s)"))
    if not summary["final_indicated_power_W"] > 0.0 and not summary.get("stalled"):
        out.append(_fail("negative_work", "the cylinders do no net work at the end of the "
                         f"run ({summary['final_indicated_power_W']:.4g} W indicated)"))
    if until_settled and not summary.get("settled"):
        out.append(_fail("not_settled", "the speed had not settled when the run reached "
                         "run.max_duration"))
    return out
