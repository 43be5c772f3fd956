"""Missing water of the skin wall against cut-off, initial pressure, speed, superheat
and jacket, on a small engine and a locomotive cylinder (docs/validation/condensation.md).

The small engine is the bundled 10 x 16 in Meyer cut-off engine (150 rpm, exhaust 2
psig), its cut-off set by the blocks' screw; the locomotive cylinder the bundled 25 x 28
in Walschaerts engine (200 rpm, blast pipe 5 psig), its cut-off by the reverser.  Each
point is a steady run at the ``fast`` preset with ``wall_heat`` and the default wall
model.  Writes ``benchmarks/results/condensation_study.csv``: the head end's cut-off,
missing water at cut-off read from the steam's state and from the card (dry saturated
steam at the card's pressure), Marks's eq. 221 for the same card, pV at mid-expansion
over pV at cut-off, the surface's swing and the water rate.

The ``exhaust`` series holds the supply and cut-off and lowers the back pressure
(16.7, 10 and 4 psia); ``ideal_ports`` is the small engine at 0.4 of the screw with
ideal ports (no ``port_flow``: the wall of :class:`corliss.engine.wall.IdealPortWall`).

Run: ``python benchmarks/condensation_study.py`` (two or three minutes).
"""

from __future__ import annotations

import copy
import sys
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd

import corliss
from corliss.scene.loader import bundled_scenes, scene_from_dict

OUT = Path(__file__).resolve().parent / "results" / "condensation_study.csv"
ENGINES = {"small": "meyer-cutoff", "locomotive": "walschaerts-locomotive"}


def run_point(which: str, changes: dict, fidelity: str = "fast") -> dict:
    """One steady run of ``which`` ("small" or "locomotive") with the skin wall and
    ``changes = {section: {key: value}}``; the row of the study."""
    data = copy.deepcopy(tomllib.loads(bundled_scenes()[ENGINES[which]].read_text()))
    data["run"]["effects"] = list(data["run"]["effects"]) + ["wall_heat"]
    data["run"]["fidelity"] = fidelity
    for section, values in changes.items():
        data.setdefault(section, {}).update(values)
    r = corliss.simulate(scene_from_dict(data, name=f"study-{which}"))
    s = r.summary
    ev = r.events["head"]
    last = r.timeseries[r.timeseries["cycle"] == r.timeseries["cycle"].max()]
    ang = np.mod(last["crank_angle_deg"].to_numpy(), 360.0)
    ang, idx = np.unique(ang, return_index=True)
    pv = (last["p_head_Pa"].to_numpy() * last["V_head_m3"].to_numpy())[idx]
    c = ev["cutoff_deg"]
    mid = c + 0.5 * ((ev["release_deg"] - c) % 360.0)
    return {"engine": which, "cutoff_frac": ev["cutoff_frac"],
            "p_initial_Pa": r.chest.p, "speed_rpm": r.scene.run.speed_rad_s * 30 / np.pi,
            "supply_T_K": r.chest.T, "jacket": r.scene.engine.jacket,
            "missing_water_frac": s["missing_water_fraction_head"],
            "card_missing_water_frac": s["card_missing_water_fraction_head"],
            "marks_missing_water_frac": s["marks_missing_water_fraction_head"],
            "pV_mid_over_cutoff_frac": float(np.interp(mid, ang, pv, period=360.0)
                                             / np.interp(c, ang, pv, period=360.0)),
            "wall_swing_K": s["wall_surface_swing_head_K"],
            "wall_min_K": float(last["T_wall_head_K"].min()),
            "exhaust_T_K": r.exhaust.T,
            # where the wall gives its heat back: the heat into the steam from cut-off
            # to release and from release to compression [J]
            "heat_expansion_J": s["heat_into_steam_expansion_head_J"],
            "heat_exhaust_J": s["heat_into_steam_exhaust_head_J"],
            "missing_water_per_stroke_kg": s["missing_water_per_stroke_head_kg"],
            "water_rate_kg_per_kWh": s["water_rate_kg_per_kWh"],
            "periodic": s["cycles_to_converge"] is not None}


#: The study: (series, engine, changes).
POINTS = (
    [("cutoff", "small", {"valve_gear": {"setting": v}}) for v in (1.0, 0.8, 0.6, 0.4, 0.2, 0.0)]
    + [("cutoff", "locomotive", {"valve_gear": {"setting": v}})
       for v in (0.05, 0.1, 0.15, 0.25, 0.4, 0.6)]
    + [("pressure", e, {"valve_gear": {"setting": 0.4}, "supply": {"pressure": f"{p} psia"}})
       for e in ENGINES for p in (40, 60, 90, 110)]
    + [("speed", "small", {"valve_gear": {"setting": 0.4}, "run": {"speed": f"{n} rpm"}})
       for n in (60, 100, 150, 200, 300)]
    + [("superheat", "small", {"valve_gear": {"setting": 0.4},
                               "supply": {"temperature": f"{337.9 + d} degF"}})
       for d in (0, 50, 100, 150, 250)]
    + [("jacket", "small", {"valve_gear": {"setting": 0.4}, "engine": {"jacket": j}})
       for j in ("none", "barrel")]
    + [("exhaust", e, {"valve_gear": {"setting": s}, "exhaust": {"pressure": f"{p} psia"}})
       for e, s in (("small", 0.4), ("locomotive", 0.4)) for p in (16.7, 10, 4)]
    # the skin wall with ideal ports (no port_flow), beside the port-flow point above
    + [("ideal_ports", "small", {"valve_gear": {"setting": 0.4},
                                 "run": {"effects": ["rod_angularity", "wall_heat"]}})]
)


def main() -> pd.DataFrame:
    rows = []
    for series, engine, changes in POINTS:
        rows.append({"series": series, **run_point(engine, changes)})
        print(rows[-1], file=sys.stderr)
    frame = pd.DataFrame(rows)
    OUT.parent.mkdir(parents=True, exist_ok=True)
    frame.to_csv(OUT, index=False, float_format="%.5g")
    return frame


if __name__ == "__main__":
    print(main().to_string())
