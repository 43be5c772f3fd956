"""The skin wall and the period's leak beside the period's figures: the tables of
docs/validation/condensation.md ("The small engine and the locomotive with the
measured coefficient"), printed as Markdown.

* Missing water against cut-off (0.1 to 0.6 of the stroke, both ends' mean, the gear's
  setting found from its valve events) and against initial pressure (40, 60, 90 and
  110 psia, the setting held at the scene's), on the small engine (the bundled 10 x 16
  in Meyer cut-off engine, 150 rpm, exhaust 2 psig, its setting 0.4 in the pressure
  series) and the locomotive (the bundled 25 x 28 in Walschaerts engine, 200 rpm, blast
  pipe 5 psig): condensation alone (the water missing at cut-off, of the steam
  supplied, without leakage), the missing water of the feed (Willans's "missing
  quantity of feed water at cut-off") without and with leakage by the period's law
  across each edge of the valve at Callendar and Nicolson's rate of leak (3 lb/h per
  psi past each closed steam edge and each closed exhaust edge of the reference valve,
  scaled to the gear's ports and faces, :mod:`corliss.engine.leak_paths`; DPJ 312,
  1899, p. 163: with the ports blocked, each end's two edges in series and the two ends
  side by side leak the valve's 3 lb/h per psi chest to exhaust), the leak into the
  ends past the steam edges as a fraction of the steam, Marks's eq. 221 for the same
  card, and the head end's surface swing; English's law (``wall_heat_model =
  "english"``, DPJ 267, 1888, p. 302) run on the same point without leakage, its water
  missing at cut-off; beside them the superheater makers' table for
  saturated locomotives (S3) and Willans's 1888 missing water (S1), read from
  ``docs/validation/condensation_measurements.csv``.
* The surface's swing on the bundled single-acting engine after Callendar and
  Nicolson's (``callendar-nicolson-single-acting``) at 44, 77 and 102 rpm beside
  their computed 11.5 and 6 K (``tests/data/callendar_nicolson_1897.csv``).
* The bundled 9 & 14 x 14 compound's per-end wall heat over a cycle under Marks's law
  (Art. 75): what each end takes during admission and its net over the cycle.

Every run is steady at the ``fast`` preset with ``wall_heat`` and the skin wall (the
compound: Marks's law at its scene's ``standard`` preset, as
``tests/test_wall_heat.py`` runs it).  Writes ``benchmarks/results/condensation_closing_note.csv``
(one row a run) as well.

Run: ``python benchmarks/condensation_closing_note.py`` (about 70 runs; some minutes).
"""

from __future__ import annotations

import copy
import sys
import tomllib
from pathlib import Path

import numpy as np
import pandas as pd

import corliss
from corliss.engine.model import build_gear, scene_events
from corliss.scene.loader import bundled_scenes, scene_from_dict

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "benchmarks" / "results" / "condensation_closing_note.csv"
ENGINES = {"small": ("meyer-cutoff", "Small engine (10 x 16 in Meyer, 150 rpm, 100 psig, "
                     "exhaust 2 psig)"),
           "locomotive": ("walschaerts-locomotive", "Locomotive (25 x 28 in Walschaerts, "
                          "200 rpm, 200 psig, blast pipe 5 psig)")}
CUTOFFS = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6)
PRESSURES_PSIA = (40, 60, 90, 110)
#: Callendar and Nicolson's rate of leak of their slide valve (DPJ 312, 1899, p. 163),
#: past each closed edge of the reference valve.
LEAK_RATE = "3 lb/h psi"
#: The setting of the pressure series where a scene has none of its own.
PRESSURE_SETTING = {"small": 0.4}


def _data(name: str) -> dict:
    return copy.deepcopy(tomllib.loads(bundled_scenes()[name].read_text()))


def _skin(data: dict, leak: bool) -> dict:
    """The scene's data with the skin wall at the fast preset, with or without the
    period's leak."""
    data["engine"]["wall_heat_model"] = "skin"
    effects = [e for e in data["run"]["effects"] if e not in ("wall_heat", "leakage")]
    data["run"]["effects"] = effects + ["wall_heat"] + (["leakage"] if leak else [])
    data["run"]["fidelity"] = "fast"
    if leak:
        data["engine"].update({"leakage_model": "period", "steam_edge_leak_rate": LEAK_RATE,
                               "exhaust_edge_leak_rate": LEAK_RATE})
    return data


def _setting_for(data: dict, cutoff: float) -> float | None:
    """The gear's setting whose two ends' mean cut-off is ``cutoff``, from the valve
    events over the setting's range, the crossing nearest the scene's own setting (none
    where the gear does not reach it)."""
    scene = scene_from_dict(data, name="cutoff-search")
    lo, hi = build_gear(scene).setting_range
    grid = np.linspace(lo, hi, 81)
    mean = []
    for row in scene_events(scene, list(grid)):
        fr = [row[e]["cutoff_frac"] if row[e]["admission_deg"] is not None else 0.0
              for e in ("head", "crank")]
        mean.append(0.5 * sum(1.0 if f is None else f for f in fr))
    d = np.array(mean) - cutoff
    own = data["valve_gear"].get("setting", 0.5 * (lo + hi))
    best = None
    for i in np.flatnonzero(d[:-1] * d[1:] <= 0.0):
        s = grid[i] + (grid[i + 1] - grid[i]) * (d[i] / (d[i] - d[i + 1]) if d[i] != d[i + 1]
                                                 else 0.0)
        if best is None or abs(s - own) < abs(best - own):
            best = float(s)
    return best


def _run(data: dict) -> dict:
    r = corliss.simulate(scene_from_dict(data, name="closing-note"))
    s = r.summary
    ends = [e for e in ("head", "crank") if f"missing_water_fraction_{e}" in s]
    mean = lambda key: float(np.mean([s[f"{key}_{e}"] for e in ends]))  # noqa: E731
    return {"cutoff_frac": float(np.mean([r.events[e]["cutoff_frac"] for e in ends])),
            "condensation_frac": mean("missing_water_fraction"),
            "feed_frac": s["missing_water_fraction_of_feed"],
            "leak_frac": s.get("valve_leakage_fraction_of_steam", 0.0),
            "marks_frac": mean("marks_missing_water_fraction"),
            "swing_K": s["wall_surface_swing_head_K"],
            "surface_mean_K": s["wall_surface_mean_head_K"],
            "periodic": s["cycles_to_converge"] is not None}


def _english(data: dict) -> float:
    """The water missing at cut-off (both ends' mean, of the steam supplied) under
    English's law, at the fast preset, without leakage."""
    data["engine"]["wall_heat_model"] = "english"
    effects = [e for e in data["run"]["effects"] if e not in ("wall_heat", "leakage")]
    data["run"]["effects"] = effects + ["wall_heat"]
    data["run"]["fidelity"] = "fast"
    s = corliss.simulate(scene_from_dict(data, name="closing-note-english")).summary
    ends = [e for e in ("head", "crank") if f"missing_water_fraction_{e}" in s]
    return float(np.mean([s[f"missing_water_fraction_{e}"] for e in ends]))


def _pair(data: dict) -> dict:
    """A point without and with the period's leak, and under English's law."""
    a = _run(_skin(copy.deepcopy(data), False))
    b = _run(_skin(copy.deepcopy(data), True))
    return {**a, "feed_with_leak_frac": b["feed_frac"], "leak_frac": b["leak_frac"],
            "english_frac": _english(copy.deepcopy(data)),
            "periodic": a["periodic"] and b["periodic"]}


def _period() -> tuple[dict, dict]:
    m = pd.read_csv(ROOT / "docs" / "validation" / "condensation_measurements.csv")
    elesco = m[m["source"].str.startswith("S3")]
    willans = m[m["source"].str.startswith("S1") & m["engine"].str.contains("SIMPLE")]
    return (dict(zip(elesco["cutoff_frac"].round(2), elesco["missing_water_frac"])),
            dict(zip(willans["p_initial_psia"].astype(int), willans["missing_water_frac"])))


def _f(v, star=False) -> str:
    return "" if v is None or (isinstance(v, float) and np.isnan(v)) else (
        f"{v:.3f}" + (" (not periodic)" if star else ""))


def main() -> int:
    """Run the points and print the tables.

    Returns
    -------
    int
        The exit status (0).
    """
    elesco, willans = _period()
    rows = []
    for which, (name, title) in ENGINES.items():
        print(f"\n**{title}**, missing water against cut-off (both ends' mean cut-off):\n")
        print("| cut-off | condensation alone (of the steam) | of the feed, no leak | "
              "of the feed, with the leak across each edge | leak (of the steam) | "
              "Marks eq. 221 | English's law (its run) | Elesco table (saturated "
              "locomotives) | surface swing [K] |")
        print("|---|---|---|---|---|---|---|---|---|")
        for c in CUTOFFS:
            base = _data(name)
            setting = _setting_for(base, c)
            if setting is None:
                print(f"| {c:.1f} | (the gear does not cut off at {c:.1f}) | | | | | | "
                      f"{_f(elesco.get(round(c, 2)))} | |")
                continue
            base["valve_gear"]["setting"] = setting
            p = _pair(base)
            rows.append({"series": "cutoff", "engine": which, "target": c, **p})
            print(f"| {p['cutoff_frac']:.2f} | {_f(p['condensation_frac'], not p['periodic'])} "
                  f"| {_f(p['feed_frac'])} | {_f(p['feed_with_leak_frac'])} | "
                  f"{_f(p['leak_frac'])} | {_f(p['marks_frac'])} | {_f(p['english_frac'])} | "
                  f"{_f(elesco.get(round(c, 2), elesco.get(0.55) if c == 0.6 else None))} | "
                  f"{p['swing_K']:.1f} |")
        print(f"\n{title}, against initial pressure (setting held):\n")
        print("| supply [psia] | cut-off | condensation alone | of the feed, no leak | "
              "of the feed, with the leak across each edge | leak (of the steam) | "
              "Marks eq. 221 | English's law (its run) | Willans 1888 (simple engine, of "
              "the feed) |")
        print("|---|---|---|---|---|---|---|---|---|")
        for psia in PRESSURES_PSIA:
            base = _data(name)
            base["supply"]["pressure"] = f"{psia} psia"
            if which in PRESSURE_SETTING:
                base["valve_gear"]["setting"] = PRESSURE_SETTING[which]
            p = _pair(base)
            rows.append({"series": "pressure", "engine": which, "target": psia, **p})
            print(f"| {psia} | {p['cutoff_frac']:.2f} | "
                  f"{_f(p['condensation_frac'], not p['periodic'])} | {_f(p['feed_frac'])} | "
                  f"{_f(p['feed_with_leak_frac'])} | {_f(p['leak_frac'])} | "
                  f"{_f(p['marks_frac'])} | {_f(p['english_frac'])} | "
                  f"{_f(willans.get(psia))} |")

    cn = pd.read_csv(ROOT / "tests" / "data" / "callendar_nicolson_1897.csv", comment="#")
    theirs = cn[cn["quantity"] == "surface_swing"].set_index("speed_rpm")["value"]
    print("\nThe surface's swing, bundled single-acting engine after Callendar and Nicolson's "
          "(0.2 cut-off, 100.5 psia, their leak):\n")
    print("| rpm | theirs, surface (computed) [K] | the skin wall, head end [K] | "
          "surface's mean [degC] |")
    print("|---|---|---|---|")
    for rpm in (44, 77, 102):
        data = _data("callendar-nicolson-single-acting")
        data["run"].update({"speed": f"{rpm} rpm", "fidelity": "fast"})
        r = corliss.simulate(scene_from_dict(data, name="cn")).summary
        rows.append({"series": "swing", "engine": "callendar-nicolson", "target": rpm,
                     "swing_K": r["wall_surface_swing_head_K"],
                     "surface_mean_K": r["wall_surface_mean_head_K"]})
        their = f"{theirs[rpm]:g}" if rpm in theirs.index else "-"
        print(f"| {rpm} | {their} | {r['wall_surface_swing_head_K']:.1f} | "
              f"{r['wall_surface_mean_head_K'] - 273.15:.1f} |")

    data = _data("marks-compound-9-14x14")
    data["run"]["effects"] = list(data["run"]["effects"]) + ["wall_heat"]
    data["engine"]["wall_heat_model"] = "marks"     # at the scene's fidelity (standard)
    row = corliss.simulate(scene_from_dict(data, name="marks-compound")).last_cycle
    print("\nThe 9 & 14 x 14 compound under Marks's law (Art. 75), per end over a cycle:\n")
    print("| end | heat taken from the steam [J] | net heat into the steam [J] | net / taken |")
    print("|---|---|---|---|")
    for end in ("head", "crank", "lp_head", "lp_crank"):
        taken, net = float(row[f"Q_to_wall_{end}_J"]), float(row[f"Q_{end}_J"])
        rows.append({"series": "marks_compound", "engine": end, "taken_J": taken, "net_J": net})
        print(f"| {end} | {taken:,.0f} | {net:,.1f} | {net / taken:.1e} |")
    OUT.parent.mkdir(parents=True, exist_ok=True)
    pd.DataFrame(rows).to_csv(OUT, index=False)
    print(f"\nwritten {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
