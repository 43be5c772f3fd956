"""The result of the throttling-versus-cut-off study (:func:`corliss.studies.compare.compare`).

Kept apart from :mod:`corliss.engine.result` (whose base class it extends) so the study
and the steady run's summary change independently.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
import pandas as pd

from corliss.engine.result import Result, willans_fit

#: Columns of the ``points`` table, in order (``brake_power_W`` with ``friction``;
#: ``steam_rate_kg_per_h`` and the water rate count a jacket's steam with the feed).
POINT_COLUMNS = ("load_frac", "variant", "condensation", "knob", "status", "knob_frac",
                 "speed_rpm", "target_power_W", "indicated_power_W", "brake_power_W",
                 "steam_rate_kg_per_h", "water_rate_kg_per_kWh", "cutoff_head_frac",
                 "chest_pressure_admission_Pa", "missing_water_frac", "power_error_frac")


@dataclass
class CompareResult(Result[dict[str, Any]]):
    """One engine governed by throttling and by cut-off across its load range.

    Parameters
    ----------
    scene, property_tier, rhs_evaluations, wall_time_s
        As for :class:`~corliss.engine.result.Result` (``wall_time_s`` [s]).
    timeseries, cycles : DataFrame
        Both the ``points`` table (one row per load, variant and condensation).
    loads : list of float
        The loads run, fractions of the rated power [-].
    variants : dict
        Per variant: its knob, the knob's range and the other knob's fixed value.
    rated_power_W : float
        The power the loads are fractions of [W] (brake with ``friction``).
    brake : bool
        Whether the loads are brake power (the scene names ``friction``).
    runs : int
        Steady runs made [-].
    chest_volume_m3, pipe_diameter_m : float
        The steam chest [m3] and pipe [m] both variants have.
    workers : int
        Processes used [-].
    droop : bool
        Whether each load ran at its governor's speed (``speed_rpm`` in the table).
    chest_source : str
        Where the chest volume came from: ``"scene"`` (its supply), ``"compare"`` (the
        ``[compare]`` section or an argument) or ``"default"``
        (:data:`~corliss.engine.compare.DEFAULT_CHEST_OF_SWEPT` of the swept volume).

    Notes
    -----
    Tables: ``points``: one row per load, variant and condensation (:data:`POINT_COLUMNS`);
    ``willans``: the least-squares Willans line of each variant and condensation,
    steam = intercept + slope x indicated power (slope as kg/kWh: the steam of each
    further kilowatt);
    ``verdict``: per load and condensation, the steam of each governing and the saving
    of cut-off governing over throttling (negative: throttling uses less).
    """

    kind: ClassVar[str] = "compare"
    TABLES: ClassVar[tuple[str, ...]] = ("points", "willans", "verdict")
    FIGURES: ClassVar[tuple[str, ...]] = ("compare",)

    loads: list = field(default_factory=list)
    variants: dict = field(default_factory=dict)
    rated_power_W: float = float("nan")
    brake: bool = False
    runs: int = 0
    chest_volume_m3: float = float("nan")
    pipe_diameter_m: float = float("nan")
    workers: int = 1
    droop: bool = False
    chest_source: str = "default"

    @property
    def points(self) -> pd.DataFrame:
        """One row per operating point (see the class's tables)."""
        return self._table_points()

    def _table_points(self) -> pd.DataFrame:
        cols = [c for c in POINT_COLUMNS if c in self.cycles.columns]
        return self.cycles[cols].reset_index(drop=True)

    def _table_willans(self) -> pd.DataFrame:
        rows = []
        pts = self.cycles
        for (var, cond), g in pts[pts["status"] == "found"].groupby(
                ["variant", "condensation"], sort=False):
            if len(g) < 2:
                continue
            a, b, r2 = willans_fit(g)
            rows.append({"variant": var, "condensation": cond,
                         "willans_intercept_kg_per_h": a,
                         # kg/h per W is kg/Wh: x 1000 kg/kWh
                         "willans_slope_kg_per_kWh": b * 1000.0,
                         "willans_r2_frac": r2})
        return pd.DataFrame(rows, columns=["variant", "condensation",
                                           "willans_intercept_kg_per_h",
                                           "willans_slope_kg_per_kWh", "willans_r2_frac"])

    @property
    def willans(self) -> pd.DataFrame:
        """The Willans line of each variant and condensation (the ``willans`` table)."""
        return self._table_willans()

    def _table_verdict(self) -> pd.DataFrame:
        pts = self.cycles
        rows = []
        for cond in dict.fromkeys(pts["condensation"]):
            for load in self.loads:
                sel = pts[(pts["condensation"] == cond) & (pts["load_frac"] == load)
                          & (pts["status"] == "found")].set_index("variant")
                thr = (float(sel.loc["throttling", "steam_rate_kg_per_h"])
                       if "throttling" in sel.index else np.nan)
                cut = (float(sel.loc["cutoff", "steam_rate_kg_per_h"])
                       if "cutoff" in sel.index else np.nan)
                saving = (thr - cut) / thr if np.isfinite(thr) and np.isfinite(cut) else np.nan
                winner = ("undecided" if not np.isfinite(saving) else
                          "cutoff" if saving > 0 else "throttling" if saving < 0 else "even")
                rows.append({"load_frac": load, "condensation": cond,
                             "throttling_steam_rate_kg_per_h": thr,
                             "cutoff_steam_rate_kg_per_h": cut,
                             "cutoff_saving_frac": saving, "winner": winner})
        return pd.DataFrame(rows)

    @property
    def verdict(self) -> pd.DataFrame:
        """Which governing uses less steam at each load (the ``verdict`` table)."""
        return self._table_verdict()

    def _make_summary(self) -> dict:
        s = self.scene
        w = self.willans
        v = self.verdict
        return {"title": s.title, "kind": self.kind, "loads": list(self.loads),
                "fidelity": s.run.fidelity.name, "property_tier": self.property_tier,
                "rated_power_W": self.rated_power_W,
                "power_basis": "brake" if self.brake else "indicated",
                "speed_rpm": s.run.speed_rad_s * 60.0 / (2.0 * np.pi),
                "governor_droop_applied": self.droop,
                "speed_basis": "governor_droop" if self.droop else "constant",
                "variants": self.variants, "chest_volume_m3": self.chest_volume_m3,
                "chest_volume_source": self.chest_source,
                "willans_negative_intercepts": [
                    f"{r.variant}/{r.condensation}" for r in w.itertuples()
                    if r.willans_intercept_kg_per_h < 0.0],
                "pipe_diameter_m": self.pipe_diameter_m,
                "willans": w.replace({np.nan: None}).to_dict(orient="records"),
                "verdict": v.replace({np.nan: None}).to_dict(orient="records"),
                "unreached_points": int((self.cycles["status"] != "found").sum()),
                "runs": self.runs, "workers": self.workers, "wall_time_s": self.wall_time_s}
