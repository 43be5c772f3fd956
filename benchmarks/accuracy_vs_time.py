"""What accuracy costs in time: every fidelity knob against a converged reference.

For each scene (the default slide-valve card; an engine at short cut-off; a
high-speed engine exhausting wet into a condenser) it runs every setting (the
presets, a sweep of integrator tolerance, and the cheaper model levels) and reports,
per setting: wall time per simulated cycle (median of repeats) and the error against
the reference in indicated power, peak pressure, steam rate and card shape (RMS
pressure difference over the cycle, as a percentage of supply pressure).  In the same
run it times the straightforward baseline (``baseline_propssi.py``) on the default
scene and reports the speed ratio.

Usage::

    python benchmarks/accuracy_vs_time.py [--repeats 5] [--out benchmarks/results]

Writes ``accuracy_vs_time.csv`` and ``accuracy_vs_time.png`` in the output directory.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

import corliss
from corliss.engine.options import PRESETS

HERE = Path(__file__).resolve().parent
SCENES = {
    "default": HERE.parent / "scenes" / "default.toml",
    "short-cutoff": HERE / "scenes" / "short-cutoff.toml",
    "high-speed-condensing": HERE.parent / "scenes" / "high-speed-condensing.toml",
}


def settings(scene):
    """(label, scene) for every setting of the study."""
    out = [(f"preset {name}", scene.with_fidelity(name)) for name in PRESETS]
    base = PRESETS["standard"]
    for rtol in (1e-3, 1e-4, 1e-5, 1e-6, 1e-8):
        fid = dataclasses.replace(base, name="custom", method="dopri5", rtol=rtol)
        out.append((f"table dopri5 rtol {rtol:.0e}", scene.replace_run(fidelity=fid)))
    for rtol in (1e-3, 1e-4, 1e-5, 1e-6):
        fid = dataclasses.replace(base, name="custom", method="rosenbrock", rtol=rtol)
        out.append((f"table rosenbrock rtol {rtol:.0e}", scene.replace_run(fidelity=fid)))
    for method, rtols in (("ros4", (1e-4, 1e-5, 7e-6)), ("rodas3", (1e-4, 1e-5, 5e-6)),
                          ("rodas4", (1e-4, 1e-5, 3e-6, 2e-6))):
        for rtol in rtols:
            fid = dataclasses.replace(base, name="custom", method=method, rtol=rtol)
            out.append((f"table {method} rtol {rtol:.0e}", scene.replace_run(fidelity=fid)))
    for step in (2.0, 1.0, 0.5, 0.25):
        fid = dataclasses.replace(base, name="custom", method="rk4", step_deg=step)
        out.append((f"table rk4 step {step:g} deg", scene.replace_run(fidelity=fid)))
    for rtol in (1e-4, 1e-6, 1e-8):
        fid = dataclasses.replace(base, name="custom", properties="heos", method="LSODA", rtol=rtol)
        out.append((f"heos LSODA rtol {rtol:.0e}", scene.replace_run(fidelity=fid)))
    fid = dataclasses.replace(base, name="custom", properties="perfect")
    out.append(("perfect steam dopri5 1e-6", scene.replace_run(fidelity=fid)))
    out.append(("ideal ports (no port_flow)",
                scene.replace_run(effects=tuple(e for e in scene.run.effects if e != "port_flow"))))
    out.append(("ideal card, isentropic", scene.replace_run(model="ideal", expansion="isentropic")))
    out.append(("ideal card, hyperbolic", scene.replace_run(model="ideal", expansion="hyperbolic")))
    return out


def reference_halving(scene) -> float:
    """Relative change of indicated power when the reference preset's rtol is halved:
    the evidence that the reference is converged."""
    ref = PRESETS["reference"]
    a = corliss.simulate(scene.replace_run(fidelity=ref)).summary["indicated_power_W"]
    half = dataclasses.replace(ref, name="custom", rtol=ref.rtol / 2)
    b = corliss.simulate(scene.replace_run(fidelity=half)).summary["indicated_power_W"]
    return abs(b / a - 1)


def marginal_ms_per_cycle(scene, repeats):
    """Cost of one more cycle [ms]: (time of 6 cycles - time of 2) / 4, median of repeats.

    Separates the per-cycle price from the fixed set-up (gear tabulation, table load,
    output frames), which the plain wall time per cycle spreads over few cycles.
    Returns the wall time and the process's CPU time (steadier on a shared machine,
    where the wall time counts the other processes' turns), and the right-hand-side
    evaluations of one more cycle.
    """
    if scene.run.model == "ideal":   # algebraic: no cycles to add
        c0 = time.process_time()
        r = corliss.simulate(scene)
        return 1e3 * r.summary["wall_time_s"], 1e3 * (time.process_time() - c0), 0.0
    t, c, n = [], [], []
    for _ in range(repeats):
        c0 = time.process_time()
        r2 = corliss.simulate(scene.replace_run(cycles=2))
        c1 = time.process_time()
        r6 = corliss.simulate(scene.replace_run(cycles=6))
        c2 = time.process_time()
        t.append((r6.wall_time_s - r2.wall_time_s) / 4.0)
        c.append(((c2 - c1) - (c1 - c0)) / 4.0)
        n.append((r6.summary.get("rhs_evaluations", 0) - r2.summary.get("rhs_evaluations", 0))
                 / 4.0)
    return 1e3 * statistics.median(t), 1e3 * statistics.median(c), statistics.median(n)


def first_run_cost(scene_path) -> dict:
    """Wall time of ``corliss run`` in a fresh process with empty numba and table caches,
    then again with the caches warm [s]: what the first run on a machine pays."""
    import os
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, NUMBA_CACHE_DIR=os.path.join(tmp, "numba"),
                   CORLISS_CACHE=os.path.join(tmp, "corliss"))
        out = {}
        for label in ("first_run_s", "second_run_s"):
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "corliss.cli.commands", "run", str(scene_path), "--out",
                            os.path.join(tmp, "out"), "--json"], env=env, check=True,
                           capture_output=True)
            out[label] = time.perf_counter() - t0
    return out


def reference(scene):
    fid = dataclasses.replace(PRESETS["reference"], name="study reference", rtol=1e-10,
                              convergence_tolerance=1e-8, max_cycles=80)
    return corliss.simulate(scene.replace_run(fidelity=fid))


def card_on_grid(result, end):
    """Pressure of one end over the last cycle on a 1-degree grid [Pa]."""
    c = result.cards[end]
    if "crank_angle_deg" in c:
        ang = np.mod(c["crank_angle_deg"].to_numpy(), 360.0)
    else:   # ideal card: use its time series
        ts = result.timeseries
        ang, p = np.mod(ts["crank_angle_deg"].to_numpy(), 360.0), ts[f"p_{end}_Pa"].to_numpy()
        c = pd.DataFrame({"p_Pa": p})
    ang, idx = np.unique(ang, return_index=True)
    p = c["p_Pa"].to_numpy()[idx]
    return np.interp(np.arange(360.0), ang, p, period=360.0)


def errors(r, ref):
    s, t = r.summary, ref.summary
    rms = math.sqrt(np.mean(np.concatenate([(card_on_grid(r, e) - card_on_grid(ref, e)) ** 2
                                            for e in ("head", "crank")])))
    return {
        "err_power_pct": 100 * abs(s["indicated_power_W"] / t["indicated_power_W"] - 1),
        "err_peak_pressure_pct": 100 * abs(s["peak_pressure_Pa"] / t["peak_pressure_Pa"] - 1),
        "err_steam_rate_pct": 100 * abs(s["steam_rate_kg_per_h"] / t["steam_rate_kg_per_h"] - 1),
        "err_card_rms_pct_of_supply": 100 * rms / t["supply_pressure_Pa"],
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--out", default=str(HERE / "results"))
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    halving = {}
    for sname, path in SCENES.items():
        scene = corliss.load_scene(path)
        ref = reference(scene)
        print(f"{sname}: reference {ref.summary['indicated_power_hp']:.4f} ihp after "
              f"{ref.summary['cycles_to_converge']} cycles", file=sys.stderr)
        halving[sname] = reference_halving(scene)
        print(f"  reference preset, rtol halved: power changes by "
              f"{100 * halving[sname]:.2e} %", file=sys.stderr)
        for label, sc in settings(scene):
            times = []
            for _ in range(args.repeats):
                r = corliss.simulate(sc)
                times.append(r.summary["wall_time_s"] / r.summary["cycles_simulated"])
            wall, cpu, nfev = marginal_ms_per_cycle(sc, args.repeats)
            row = {"scene": sname, "setting": label,
                   "reference_halving_change_pct": 100 * halving[sname],
                   "ms_per_cycle": 1e3 * statistics.median(times),
                   "marginal_ms_per_cycle": wall, "marginal_cpu_ms_per_cycle": cpu,
                   "marginal_rhs_per_cycle": nfev,
                   "load_average_1min": os.getloadavg()[0],
                   "cycles": r.summary["cycles_simulated"], **errors(r, ref)}
            rows.append(row)
            print(f"  {label:28s} {row['ms_per_cycle']:8.2f} ms/cycle "
                  f"({row['marginal_ms_per_cycle']:6.2f} marginal, {cpu:6.2f} CPU)  power err "
                  f"{row['err_power_pct']:.4f} %  steam err {row['err_steam_rate_pct']:.4f} %",
                  file=sys.stderr)
    sys.path.insert(0, str(HERE))
    import baseline_propssi
    base_times = [baseline_propssi.run(3)[0] for _ in range(args.repeats)]
    base = 1e3 * statistics.median(base_times)
    df = pd.DataFrame(rows)
    std = df[(df.scene == "default") & (df.setting == "preset standard")]["ms_per_cycle"].iloc[0]
    df["baseline_ms_per_cycle_default_scene"] = base
    first = first_run_cost(SCENES["default"])
    for k, v in first.items():
        df[k] = v
    print(f"first run on a machine (compile + table build): {first['first_run_s']:.1f} s; "
          f"second run: {first['second_run_s']:.1f} s", file=sys.stderr)
    df.to_csv(out / "accuracy_vs_time.csv", index=False, float_format="%.6g")
    print(f"baseline (solve_ivp + PropsSI) {base:.1f} ms/cycle; standard preset {std:.1f} "
          f"ms/cycle: {base / std:.1f} x faster", file=sys.stderr)
    plot(df, base, out / "accuracy_vs_time.png")
    return 0


def plot(df, base_ms, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    for ax, col, label in ((axes[0], "err_power_pct", "error in indicated power [%]"),
                           (axes[1], "err_card_rms_pct_of_supply", "card RMS error [% of supply]")):
        for (sname, g), m in zip(df.groupby("scene"), "os^"):
            ax.loglog(g["marginal_ms_per_cycle"], g[col].clip(lower=1e-6), m, label=sname, ms=6,
                      alpha=0.8)
            for _, row in g[g.setting.str.startswith("preset")].iterrows():
                ax.annotate(row.setting.split()[1], (row.marginal_ms_per_cycle, max(row[col], 1e-6)),
                            fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.axvline(base_ms, color="0.5", ls="--", lw=0.8)
        ax.text(base_ms, ax.get_ylim()[1], " baseline", fontsize=7, va="top", color="0.4")
        ax.set_xlabel("wall time per simulated cycle, marginal [ms]")
        ax.set_ylabel(label)
        ax.grid(True, which="both", color="0.92", lw=0.5)
    axes[0].legend(fontsize=8)
    fig.suptitle("corliss: accuracy against time (errors floored at 1e-6 %)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
