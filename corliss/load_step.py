"""What a transient run hands back: speed and governor histories, the per-turn table,
the load-step metrics and the cards before and after the step; CSV + meta, PNG, JSON.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from corliss import units
from corliss.engine.speed_metrics import load_step_metrics, step_time_of
from corliss.results import _jsonable, _write_atomic, write_csv


@dataclass
class LoadStepResult:
    """A transient run.

    Attributes
    ----------
    scene : Scene
    timeseries : DataFrame
        Rows at the scene's ``record`` decimation: ``time_s``, ``crank_angle_deg``,
        ``speed_rpm``, ``governor_z``, ``actuator`` and (every step or degree) the
        cylinder pressures ``p_head_Pa``, ``p_crank_Pa``.
    cycles : DataFrame
        One row per turn: times, mean speed, indicated and load power, steam, governor
        position and what it set (throttle opening, or gear setting and cut-off).
    """

    scene: object
    timeseries: pd.DataFrame
    cycles: pd.DataFrame
    geometry: object
    property_tier: str
    wall_time_s: float
    nfev: int
    stalled: bool
    tables: object = None
    chest: object = None
    exhaust: object = None
    _summary: dict | None = field(default=None, repr=False)

    @property
    def step_time_s(self) -> float | None:
        return step_time_of(self.scene.load)

    @property
    def metrics(self) -> dict:
        return load_step_metrics(self.cycles, self.step_time_s, self.scene.run.settling_band)

    @property
    def summary(self) -> dict:
        if self._summary is None:
            s = self.scene
            c = self.cycles
            gov = None
            if s.governor is not None:
                mech = self.tables.mechanism
                gov = {"type": s.governor_type, "acts_on": mech.acts_on,
                       "z_at_start": self.tables.z0}
            self._summary = {
                "title": s.title, "mode": "transient", "model": s.run.model,
                "effects": list(s.run.effects), "fidelity": s.run.fidelity.name,
                "property_tier": self.property_tier,
                "initial_speed_rpm": s.run.speed_rpm, "duration_s": s.run.duration_s,
                "simulated_s": float(c["t_end_s"].iloc[-1]), "turns": int(len(c)),
                "flywheel_inertia_kg_m2": s.flywheel.inertia_kg_m2,
                "load_torque_N_m": s.load.torque_N_m, "load_kind": s.load.kind,
                "load_speed_law": s.load.speed_law, "step_time_s": self.step_time_s,
                "governor": gov, "stalled": self.stalled,
                **self.metrics,
                "final_indicated_power_W": float(c["indicated_power_W"].iloc[-5:].mean()),
                "final_steam_rate_kg_per_h": float(c["steam_rate_kg_per_h"].iloc[-5:].mean()),
                "wall_time_s": self.wall_time_s, "nfev": self.nfev,
            }
        return self._summary

    def cards(self) -> dict[str, pd.DataFrame]:
        """Head and crank cards of the turn before the step and of the last turn:
        ``{"before": {"head": frame, "crank": frame}, "after": ...}`` with ``V_m3``,
        ``p_Pa``; empty when the time series has no pressures (``record = "cycle"``)."""
        ts = self.timeseries
        if "p_head_Pa" not in ts:
            return {}
        c = self.cycles
        t_step = self.step_time_s
        k_last = int(c["cycle"].iloc[-1])
        if t_step is not None and (c["t_end_s"] <= t_step).any():
            k_before = int(c.loc[c["t_end_s"] <= t_step, "cycle"].iloc[-1])
        else:
            k_before = int(c["cycle"].iloc[0])
        out = {}
        for label, k in (("before", k_before), ("after", k_last)):
            rows = ts[ts["cycle"] == k]
            th = np.radians(rows["crank_angle_deg"].to_numpy())
            vh, vc = self.geometry.volumes_m3(th)
            out[label] = {"head": pd.DataFrame({"V_m3": vh, "p_Pa": rows["p_head_Pa"].to_numpy()}),
                          "crank": pd.DataFrame({"V_m3": vc, "p_Pa": rows["p_crank_Pa"].to_numpy()}),
                          "cycle": k}
        return out

    def write(self, out_dir: str | Path) -> dict[str, Path]:
        """Write the time series and per-turn CSVs with meta, the load-step PNG and the
        summary JSON."""
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from corliss.plot import plot_load_step
        out_dir = Path(out_dir)
        stem = self.scene.name
        files = {"timeseries": write_csv(self, self.timeseries, out_dir / f"{stem}.timeseries.csv"),
                 "cycles": write_csv(self, self.cycles, out_dir / f"{stem}.cycles.csv")}
        fig = plot_load_step(self)["figure"]
        png = out_dir / f"{stem}.loadstep.png"
        _write_atomic(png, lambda p: fig.savefig(p, dpi=120, bbox_inches="tight", format="png"))
        plt.close(fig)
        files["loadstep"] = png
        sj = out_dir / f"{stem}.summary.json"
        _write_atomic(sj, lambda p: Path(p).write_text(json.dumps(_jsonable(self.summary),
                                                                  indent=2)))
        files["summary"] = sj
        return files


def print_summary(result: LoadStepResult, files: dict) -> None:
    """The CLI's short account of a transient run."""
    s = result.summary
    us = result.scene.output.units == "US"
    print(s["title"])
    gov = s["governor"]
    print(f"  transient, {s['simulated_s']:.2f} s in {s['turns']} turns, "
          f"governor {gov['type'] + ' (' + gov['acts_on'] + ')' if gov else 'none'}, "
          f"fidelity {s['fidelity']}")
    pw = s["final_indicated_power_W"]
    print(f"  final speed      {s['final_speed_rpm']:.2f} rpm, "
          + (f"{pw / units.HP_W:.1f} ihp" if us else f"{pw / 1e3:.1f} kW"))
    if s.get("speed_before_rpm") is not None:
        print(f"  load step at     {s['step_time_s']:.3g} s: speed before "
              f"{s['speed_before_rpm']:.2f} rpm, regulation {100 * s['regulation']:+.2f} %")
        print(f"  largest change   {s['max_deviation_rpm']:+.2f} rpm "
              f"({100 * s['max_deviation_frac']:+.2f} %) at {s['time_of_max_deviation_s']:.2f} s "
              "after the step")
        st = s["settling_time_s"]
        print("  settling         " + ("not settled by the end" if st is None else
                                        f"{st:.2f} s to within "
                                        f"{100 * result.scene.run.settling_band:g} %"))
    if s["hunting"]:
        print(f"  HUNTING          period {s['hunting_period_s']:.2f} s, governor swing "
              f"{100 * s['governor_swing']:.1f} % of travel")
    if s["stalled"]:
        print("  STALLED          the load stopped the engine")
    print(f"  wall time        {s['wall_time_s']:.2f} s")
    for kind, path in files.items():
        print(f"  wrote {kind:10s} {path}")
