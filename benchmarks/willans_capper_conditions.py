"""Willans's (1888) and Capper's (1905) trials as they were run: the tables of
docs/validation/condensation.md ("Willans's and Capper's trials as they were run"),
printed as Markdown.

* Willans: the bundled 10 x 16 in Meyer engine run as his simple engine was (single-
  acting, steam on the head end only, Lineham, *A Text-Book of Mechanical
  Engineering*, App. II, note to p. 633; 400 rpm, exhausting to the atmosphere, no
  jacket, Sci. Am. Suppl. 647, 1888), at one setting (0.4 of the screw, head cut-off
  0.42) with the initial pressure of 40, 90 and 110 psia set by throttling dry
  saturated steam at constant enthalpy (Lineham, note to p. 627: "throttling the steam
  at constant expansion") from 115 psia (the least boiler pressure that gives 110
  psia; his is not stated) or 165 psia, or dry saturated steam: condensation alone
  (the head end's water missing at cut-off, of the steam, without leakage) and the
  missing water of the feed with the period's leak past each valve edge at 0.4, 3 and
  3.6 lb/h per psi (and 3.6 chest to exhaust), the range the period measured on one
  valve; then the rise from 40 psia at every setting 0.2 to 0.8 and those rates.
* Capper: the Meyer engine as bundled (horizontal, double-acting, 150 rpm, exhaust 2
  psig, setting 0.4) on saturated steam at 40, 90 and 114.7 psia, and at 114.7 psia
  superheated by 0 to 80 K: condensation alone (both ends' mean) and the missing water
  of the feed with 3 lb/h per psi past each edge.

Every run is steady at the ``fast`` preset with the skin wall; up to 150 cycles (the
wall under superheated steam settles slowly).  A run that does not settle is marked.

Run: ``python benchmarks/willans_capper_conditions.py`` (about 90 runs; a minute or
two once compiled).
"""

from __future__ import annotations

import copy
import sys
import tomllib

import corliss
from corliss.scene.loader import bundled_scenes, scene_from_dict
from corliss.thermo.steam import HEOSSteam

#: One pound-force per square inch [Pa].
PSI = 6894.757293168
WILLANS_1888 = {40: 0.117, 90: 0.248, 110: 0.30}
_HEOS = HEOSSteam()


def _throttled_K(p_psia: float, boiler_psia: float | None) -> str:
    """The scene's supply temperature: dry saturated steam at ``boiler_psia`` throttled
    at constant enthalpy to ``p_psia`` [K], or "saturated" without a boiler."""
    if boiler_psia is None:
        return "saturated"
    h = _HEOS.px(boiler_psia * PSI, 1.0).h
    return f"{_HEOS.ph(p_psia * PSI, h).T:.3f} K"


def _summary(p_psia: float, temperature: str, *, single_acting: bool, rpm: float,
             setting: float, edge: float | None, valve: float = 0.0) -> dict:
    """One steady run of the Meyer engine; ``edge`` None runs it without leakage."""
    data = copy.deepcopy(tomllib.loads(bundled_scenes()["meyer-cutoff"].read_text()))
    data["engine"]["wall_heat_model"] = "skin"
    effects = ["port_flow", "rod_angularity", "wall_heat"]
    if edge is not None:
        effects.append("leakage")
        data["engine"].update({"leakage_model": "period",
                               "steam_edge_leak_rate": f"{edge} lb/h psi",
                               "exhaust_edge_leak_rate": f"{edge} lb/h psi",
                               "valve_leak_rate": f"{valve} lb/h psi"})
    if single_acting:
        data["engine"]["steam_ends"] = "head"
        data["exhaust"]["pressure"] = "0 psig"
    data["run"].update({"effects": effects, "fidelity": "fast", "speed": f"{rpm} rpm",
                        "max_cycles": 150})
    data["valve_gear"]["setting"] = setting
    data["supply"].update({"pressure": f"{p_psia} psia", "temperature": temperature})
    return corliss.simulate(scene_from_dict(data, name="willans-capper")).summary


def _f(s: dict, key: str) -> str:
    return f"{s[key]:.3f}" + ("" if s["cycles_to_converge"] is not None else "*")


def _willans() -> None:
    print("| initial pressure [psia] | 40 | 90 | 110 | rise 40 to 90 / to 110 |")
    print("|---|---|---|---|---|")
    sat = {p: _HEOS.px(p * PSI, 1.0).T for p in WILLANS_1888}
    for boiler in (115.0, 165.0, None):
        temps = {p: _throttled_K(p, boiler) for p in WILLANS_1888}
        if boiler is not None:
            print(f"| superheat after the throttle from {boiler:g} psia [K] | " + " | ".join(
                f"{float(temps[p].split()[0]) - sat[p]:.1f}" for p in WILLANS_1888) + " | |")
        kw = dict(single_acting=True, rpm=400, setting=0.4)
        alone = {p: _summary(p, temps[p], edge=None, **kw) for p in WILLANS_1888}
        print(f"| boiler {boiler}: condensation alone | " + " | ".join(
            _f(alone[p], "missing_water_fraction_head") for p in WILLANS_1888) + " | |")
        for edge, valve in ((3.0, 0.0), (0.4, 0.0), (3.6, 3.6)):
            s = {p: _summary(p, temps[p], edge=edge, valve=valve, **kw) for p in WILLANS_1888}
            m = {p: s[p]["missing_water_fraction_of_feed"] for p in s}
            leak = [s[p]["valve_leakage_fraction_of_steam"] for p in s]
            print(f"| boiler {boiler}: of the feed, {edge} past each edge, {valve} chest to "
                  f"exhaust (leak {min(leak):.2f} to {max(leak):.2f}) | "
                  + " | ".join(_f(s[p], "missing_water_fraction_of_feed") for p in s)
                  + f" | {m[90] - m[40]:+.3f} / {m[110] - m[40]:+.3f} |")
    print("| Willans 1888, simple engine (S1) | 0.117 | 0.248 | \"nearly 0.30\" | 0.131 / 0.183 |")
    rises = []
    for setting in (0.2, 0.4, 0.6, 0.8):
        for edge, valve in ((0.4, 0.0), (3.0, 0.0), (3.6, 0.0), (3.6, 3.6)):
            s = {p: _summary(p, _throttled_K(p, 115.0), single_acting=True, rpm=400,
                             setting=setting, edge=edge, valve=valve) for p in WILLANS_1888}
            m = {p: s[p]["missing_water_fraction_of_feed"] for p in s}
            settled = all(x["cycles_to_converge"] is not None for x in s.values())
            rises += [m[90] - m[40], m[110] - m[40]]
            print(f"setting {setting}, head cut-off "
                  f"{s[40]['events']['head']['cutoff_frac']:.2f}, {edge} past each edge, "
                  f"{valve} chest to exhaust: rise {m[90] - m[40]:+.3f} / {m[110] - m[40]:+.3f}"
                  + ("" if settled else " (not settled)"))
    print(f"rises from {min(rises):+.3f} to {max(rises):+.3f}\n")


def _capper() -> None:
    kw = dict(single_acting=False, rpm=150, setting=0.4)
    print("| initial pressure [psia] | condensation alone | of the feed, with the leak | leak |")
    print("|---|---|---|---|")

    def row(label: str, p: float, temperature: str) -> None:
        a = _summary(p, temperature, edge=None, **kw)
        b = _summary(p, temperature, edge=3.0, **kw)
        alone = 0.5 * (a["missing_water_fraction_head"] + a["missing_water_fraction_crank"])
        mark = "" if a["cycles_to_converge"] is not None else "*"
        print(f"| {label} | {alone:.3f}{mark} | {_f(b, 'missing_water_fraction_of_feed')} | "
              f"{b['valve_leakage_fraction_of_steam']:.3f} |")

    for p in (40, 90, 114.7):
        row(f"{p}, saturated", p, "saturated")
    t_sat = _HEOS.px(114.7 * PSI, 1.0).T
    for dt in (10, 20, 40, 80):
        row(f"114.7, {dt} K superheat", 114.7, f"{t_sat + dt:.3f} K")


def main() -> int:
    """Run the points and print the tables (a trailing * marks a run not settled).

    Returns
    -------
    int
        The exit status (0).
    """
    print("Willans's conditions (Meyer engine single-acting, 400 rpm, exhaust 0 psig):\n")
    _willans()
    print("Capper's pair (Meyer engine as bundled, 150 rpm, setting 0.4):\n")
    _capper()
    return 0


if __name__ == "__main__":
    sys.exit(main())
