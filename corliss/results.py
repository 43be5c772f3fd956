"""What a run hands back: time series, per-cycle table, cards, summary; CSV + meta.

Inside, every frame is SI with the unit in each column name (``p_head_Pa``).  On
output the scene's ``[output] units`` chooses US (psia, ft3, degF, lb, ft lbf) or SI
(kPa absolute, m3, degC, kg, J); column names carry the unit either way, and a
``.meta.json`` beside each CSV records the package and CoolProp versions, the
property tier, the resolved scene, the unit of every column and the time.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from corliss import units

#: SI suffix -> (US suffix, US unit, SI suffix, SI unit) for output frames.
_OUTPUT_UNITS = {
    "Pa": ("psia", "psia", "kPa_abs", "kPa"),
    "m3": ("ft3", "ft3", "m3", "m3"),
    "K": ("degF", "degF", "degC", "degC"),
    "kg": ("lb", "lb", "kg", "kg"),
    "J": ("ft_lbf", "ft lbf", "J", "J"),
}


#: Multi-part suffixes: suffix -> (US suffix, US unit, SI suffix, SI unit, factor from the
#: column's unit to SI proper before conversion).
_OUTPUT_UNITS_LONG = {
    "N_m": ("lbf_ft", "lbf ft", "N_m", "N m", 1.0),
    "kg_per_h": ("lb_per_h", "lb/h", "kg_per_h", "kg/h", 1.0 / 3600.0),
}
#: Suffixes that stay as they are, with their unit for the meta file.
_PLAIN_UNITS = {"deg": "deg", "s": "s", "rpm": "rev/min", "frac": "- (fraction)",
                "W": "W"}


def convert_frame(df: pd.DataFrame, system: str, barometer_Pa: float) -> tuple[pd.DataFrame, dict]:
    """A copy of an SI frame in ``system`` ("US" or "SI") and the unit of each column."""
    out = {}
    col_units = {}
    for col in df.columns:
        base, _, suffix = col.rpartition("_")
        long = next((k for k in _OUTPUT_UNITS_LONG if col.endswith("_" + k)), None)
        factor = 1.0
        if long is not None:
            base = col[: -len(long) - 1]
            us_sfx, us_unit, si_sfx, si_unit, factor = _OUTPUT_UNITS_LONG[long]
        elif base and suffix in _OUTPUT_UNITS:
            us_sfx, us_unit, si_sfx, si_unit = _OUTPUT_UNITS[suffix]
        else:
            out[col] = df[col].to_numpy()
            col_units[col] = _PLAIN_UNITS.get(suffix, "-") if base else "-"
            if suffix == "W" and system == "US":     # powers in horse-power
                name = f"{base}_hp"
                out.pop(col)
                col_units.pop(col)
                out[name] = units.to_unit(df[col].to_numpy(dtype=float), "hp")
                col_units[name] = "hp"
            continue
        sfx, unit = (us_sfx, us_unit) if system == "US" else (si_sfx, si_unit)
        name = f"{base}_{sfx}"
        out[name] = units.to_unit(df[col].to_numpy(dtype=float) * factor, unit,
                                  barometer_Pa=barometer_Pa)
        col_units[name] = unit + (" absolute" if suffix == "Pa" else "")
    return pd.DataFrame(out), col_units


def package_version() -> str:
    from importlib.metadata import PackageNotFoundError, version
    try:
        return version("corliss")
    except PackageNotFoundError:  # running from a source tree
        return "0+unknown"


def _write_atomic(path: Path, write) -> None:
    """Write through a temporary file in the same directory, then rename."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


@dataclass
class Result:
    """The outcome of :func:`corliss.simulate`.

    Attributes
    ----------
    scene : Scene
    events : dict
        Valve events of each end (the JSON contract).
    timeseries : DataFrame
        State of both ends over every simulated cycle, SI.
    cycles : DataFrame
        One row per cycle: work, mass and enthalpy from the chest and the exhaust.
    cycles_to_converge : int or None
        Cycles until the indicated work was periodic (None if ``cycles`` fixed it).
    """

    scene: object
    events: dict
    geometry: object
    chest: object
    exhaust: object
    property_tier: str
    timeseries: pd.DataFrame
    cycles: pd.DataFrame
    cycles_to_converge: int | None
    portmap: object
    nfev: int
    wall_time_s: float
    ideal_cards: dict | None = None
    cylinders: list | None = None     # (column prefix, geometry, crank lead [rad])
    lp_events: dict | None = None     # a compound's LP valve events
    _summary: dict | None = field(default=None, repr=False)

    @property
    def cylinder_list(self) -> list:
        """(prefix, geometry, crank lead [rad]) of every cylinder; "" is the (HP) first."""
        return self.cylinders or [("", self.geometry, 0.0)]

    # --- derived quantities -------------------------------------------------------
    @property
    def last_cycle(self) -> pd.Series:
        return self.cycles.iloc[-1]

    @property
    def cards(self) -> dict[str, pd.DataFrame]:
        """Card of each end over the last cycle: piston fraction, volume, pressure (SI).

        ``piston_frac`` is the piston position as a fraction of the stroke from the
        head-end dead centre, the abscissa of an indicator card.
        """
        if self.ideal_cards is not None:
            out = {}
            for end, df in self.ideal_cards.items():
                frac = df["frac"] if end == "head" else 1.0 - df["frac"]
                out[end] = pd.DataFrame({"piston_frac": frac.to_numpy(),
                                         "V_m3": df["V_m3"].to_numpy(),
                                         "p_Pa": df["p_Pa"].to_numpy()})
            return out
        ts = self.timeseries[self.timeseries["cycle"] == self.timeseries["cycle"].max()]
        th = np.radians(ts["crank_angle_deg"].to_numpy()) % (2 * math.pi)
        out = {}
        for prefix, geo, phase in self.cylinder_list:
            frac = geo.fraction(th + phase)
            for end in ("head", "crank"):
                out[prefix + end] = pd.DataFrame({
                    # the cylinder's own crank angle, in which its events are given
                    "crank_angle_deg": ts["crank_angle_deg"].to_numpy() + math.degrees(phase),
                    "piston_frac": frac,
                    "V_m3": ts[f"V_{prefix}{end}_m3"].to_numpy(),
                    "p_Pa": ts[f"p_{prefix}{end}_Pa"].to_numpy()})
        return out

    @property
    def crank_effort(self) -> pd.DataFrame:
        """Torque on the shaft over the last cycle (SI).

        Columns: crank angle, steam force on the piston, the inertia force of the
        reciprocating masses (``inertia`` effect), the indicated torque they make, the
        friction torque (``friction`` effect) and the net torque left for the load.
        """
        from corliss.engine import crank_effort as ce
        ts = self.timeseries[self.timeseries["cycle"] == self.timeseries["cycle"].max()]
        th = np.radians(ts["crank_angle_deg"].to_numpy())
        run, spec = self.scene.run, self.geometry.spec
        cols = {"crank_angle_deg": ts["crank_angle_deg"].to_numpy()}
        total = np.zeros(th.size)
        for prefix, g, phase in self.cylinder_list:
            force = ce.piston_force_N(g, ts[f"p_{prefix}head_Pa"].to_numpy(),
                                      ts[f"p_{prefix}crank_Pa"].to_numpy(),
                                      self.scene.supply.barometer_Pa)
            cols[f"{prefix}steam_force_N"] = force
            if run.has("inertia"):
                f_in = ce.inertia_force_N(g, th + phase, run.speed_rad_s,
                                          spec.reciprocating_mass_kg)
                cols[f"{prefix}inertia_force_N"] = f_in
                force = force + f_in
            total = total + ce.torque_N_m(g, th + phase, force)
        cols["torque_N_m"] = total
        net = cols["torque_N_m"]
        if run.has("friction"):
            tf = spec.friction_torque_N_m + spec.friction_N_m_s * run.speed_rad_s
            cols["friction_torque_N_m"] = np.full(th.size, tf)
            net = net - tf
        cols["net_torque_N_m"] = net
        return pd.DataFrame(cols)

    def _effort_summary(self, work_J: float) -> dict:
        from corliss.engine.crank_effort import energy_fluctuation_J
        ce = self.crank_effort
        th = np.radians(ce["crank_angle_deg"].to_numpy())
        dE = energy_fluctuation_J(th, ce["torque_N_m"].to_numpy())
        out = {"max_torque_N_m": float(ce["torque_N_m"].max()),
               "min_torque_N_m": float(ce["torque_N_m"].min()),
               "mean_torque_N_m": work_J / (2 * math.pi),
               "energy_fluctuation_J": dE,
               # Marks Art. 57, Table IV: spread over the work of one stroke of one cylinder
               "fluctuation_coefficient_c": (dE / (0.5 * work_J / len(self.cylinder_list))
                                             if work_J > 0 else None)}
        run = self.scene.run
        row = self.last_cycle
        rev_per_h = run.speed_rad_s / (2 * math.pi) * 3600.0
        valve_leaks = [k for k in row.index if k.startswith("m_valve_leak_")]
        if valve_leaks:
            out["valve_leakage_kg_per_h"] = float(sum(row[k] for k in valve_leaks)) * rev_per_h
        if "m_piston_leak_kg" in row:
            out["piston_leakage_net_kg_per_cycle"] = float(row["m_piston_leak_kg"])
        if "Q_head_J" in row:
            out.update(self._condensation_summary())
        if "p_chest_Pa" in self.timeseries:
            last = self.timeseries[self.timeseries["cycle"] == self.timeseries["cycle"].max()]
            out["chest_pressure_mean_Pa"] = float(last["p_chest_Pa"].mean())
            out["chest_pressure_min_Pa"] = float(last["p_chest_Pa"].min())
        if run.has("friction"):
            spec = self.geometry.spec
            tf = spec.friction_torque_N_m + spec.friction_N_m_s * run.speed_rad_s
            indicated = work_J * run.speed_rad_s / (2 * math.pi)
            brake = indicated - tf * run.speed_rad_s
            out.update({"friction_torque_N_m": tf, "friction_power_W": tf * run.speed_rad_s,
                        "friction_work_J_per_cycle": tf * 2 * math.pi,
                        "brake_power_W": brake, "brake_power_hp": brake / units.HP_W,
                        "mechanical_efficiency": brake / indicated if indicated > 0 else None})
        return out

    def _compound_summary(self) -> dict:
        """Power of each cylinder; for a compound, LP mean pressures and the receiver's."""
        if len(self.cylinder_list) < 2:
            return {}
        if self.scene.compound is None:
            row = self.last_cycle
            rev_per_s = self.scene.run.speed_rad_s / (2 * math.pi)
            return {"cylinder_powers_W": [float(row[f"work_{p}head_J"] + row[f"work_{p}crank_J"])
                                          * rev_per_s for p, _, _ in self.cylinder_list]}
        row = self.last_cycle
        rev_per_s = self.scene.run.speed_rad_s / (2 * math.pi)
        _, lp, _ = self.cylinder_list[1]
        w_lp = float(row["work_lp_head_J"] + row["work_lp_crank_J"])
        w_hp = float(row["work_head_J"] + row["work_crank_J"])
        last = self.timeseries[self.timeseries["cycle"] == self.timeseries["cycle"].max()]
        return {"hp_power_W": w_hp * rev_per_s, "lp_power_W": w_lp * rev_per_s,
                "lp_mep_head_Pa": float(row["work_lp_head_J"]) / lp.swept_m3[0],
                "lp_mep_crank_Pa": float(row["work_lp_crank_J"]) / lp.swept_m3[1],
                "receiver_pressure_mean_Pa": float(last["p_receiver_Pa"].mean()),
                "receiver_pressure_min_Pa": float(last["p_receiver_Pa"].min()),
                "receiver_pressure_max_Pa": float(last["p_receiver_Pa"].max())}

    def _condensation_summary(self) -> dict:
        """Initial condensation as the engineers of the time measured it (Marks Art. 74).

        Per end: the heat the steam gave the walls over the cycle; the wet fraction of
        the cylinder's contents at cut-off; and the "missing water": the steam supplied
        less the steam the card shows at cut-off (volume at cut-off times the density
        of dry saturated steam at the card's pressure there, less the cushion steam shut
        in at compression, Marks eq. 219a), as a fraction of the steam supplied; and
        beside it the fraction Marks's law of condensation predicts (eq. 221).
        """
        from corliss.engine.condensation import marks_condensation_kg
        from corliss.thermo.steam import HEOSSteam
        sat = HEOSSteam()
        row = self.last_cycle
        ts = self.timeseries[self.timeseries["cycle"] == self.timeseries["cycle"].max()]
        ang = np.mod(ts["crank_angle_deg"].to_numpy(), 360.0)
        ang, idx = np.unique(ang, return_index=True)
        out = {}
        for end in ("head", "crank"):
            out[f"heat_to_walls_{end}_J_per_cycle"] = float(row[f"Q_to_wall_{end}_J"])
            out[f"wall_temperature_{end}_K"] = float(row[f"T_wall_{end}_K"])
            ev = self.events[end]
            if ev["cutoff_deg"] is None or ev["compression_deg"] is None:
                continue

            def at(col, deg):
                return float(np.interp(deg, ang, ts[col].to_numpy()[idx], period=360.0))

            c, k = ev["cutoff_deg"], ev["compression_deg"]
            out[f"wet_fraction_at_cutoff_{end}"] = 1.0 - at(f"x_{end}", c)
            shown = (at(f"V_{end}_m3", c) * sat.px(at(f"p_{end}_Pa", c), 1.0).rho
                     - at(f"V_{end}_m3", k) * sat.px(at(f"p_{end}_Pa", k), 1.0).rho)
            supplied = float(row[f"m_chest_{end}_kg"])
            out[f"missing_water_fraction_{end}"] = (supplied - shown) / supplied
            # the period's prediction beside the model's (Marks eq. 221)
            e_idx = 0 if end == "head" else 1
            vc, vs = self.geometry.clearance_m3[e_idx], self.geometry.swept_m3[e_idx]
            e_true = (vc + vs * ev["cutoff_frac"]) / (vc + vs)
            cond = marks_condensation_kg(
                self.geometry.spec.bore_m, self.geometry.spec.stroke_m,
                2.0 * self.scene.run.speed_rad_s / (2 * math.pi), e_true,
                sat.t_sat(at(f"p_{end}_Pa", c)), self.exhaust.T)
            out[f"marks_missing_water_fraction_{end}"] = cond / (cond + shown)
        return out

    @property
    def summary(self) -> dict:
        """The run's summary: the JSON contract keys and more (all SI unless named)."""
        if self._summary is None:
            self._summary = self._make_summary()
        return self._summary

    def _make_summary(self) -> dict:
        run = self.scene.run
        row = self.last_cycle
        w_h, w_c = float(row["work_head_J"]), float(row["work_crank_J"])
        w = float(row["work_J"]) if "work_J" in row else w_h + w_c
        rev_per_s = run.speed_rad_s / (2 * math.pi)
        power = w * rev_per_s
        sw_h, sw_c = self.geometry.swept_m3
        # what crossed the engine's boundary: from the supply, from (minus: to) the exhaust
        steam_cycle = float(row["m_supply_kg"])
        steam_rate = steam_cycle * rev_per_s * 3600.0
        m_exh = float(row["m_exhaust_kg"])
        H_in = float(row["H_supply_J"])
        H_ex = float(row["H_exhaust_J"])
        p_peak = float(np.nanmax(np.concatenate([c["p_Pa"].to_numpy() for c in self.cards.values()])))
        mass_err = abs(steam_cycle + m_exh) / abs(steam_cycle) if steam_cycle else None
        Q = sum(float(row[c]) for c in row.index if c.startswith("Q_") and "to_wall" not in c)
        energy_err = (abs(H_in + H_ex + Q - w) / abs(H_in) if math.isfinite(H_ex) and H_in
                      else None)
        power_kW = power / 1000.0
        ihp = power / units.HP_W

        def ratio(a, b):
            return a / b if b > 0 else None

        return {
            "title": self.scene.title,
            "model": run.model,
            "effects": list(run.effects),
            "fidelity": run.fidelity.name,
            "property_tier": self.property_tier,
            "speed_rpm": run.speed_rpm,
            "indicated_power_W": power,
            "indicated_power_hp": ihp,
            "indicated_work_J_per_cycle": w,
            "mep_head_Pa": w_h / sw_h,
            "mep_crank_Pa": w_c / sw_c,
            # over all cylinders; a compound's is referred to its LP cylinder (Marks Art. 90)
            "mep_mean_Pa": w / (sum(self.cylinder_list[-1][1].swept_m3)
                                if self.scene.compound is not None else
                                sum(sum(g.swept_m3) for _, g, _ in self.cylinder_list)),
            "steam_per_cycle_kg": steam_cycle,
            "steam_rate_kg_per_h": steam_rate,
            "water_rate_kg_per_kWh": ratio(steam_rate, power_kW),
            "water_rate_lb_per_ihp_h": ratio(steam_rate / units.POUND_kg, ihp),
            "peak_pressure_Pa": p_peak,
            "supply_pressure_Pa": self.chest.p,
            "exhaust_pressure_Pa": self.exhaust.p,
            "cycles_simulated": int(len(self.cycles)),
            "cycles_to_converge": self.cycles_to_converge,
            "mass_balance_error": mass_err,
            "energy_balance_error": energy_err,
            "rhs_evaluations": self.nfev,
            "wall_time_s": self.wall_time_s,
            **self._effort_summary(w),
            **self._compound_summary(),
            "events": self.events,
            **({"lp_events": self.lp_events} if self.lp_events is not None else {}),
        }

    # --- output -------------------------------------------------------------------
    def meta(self, columns: dict | None = None, file: str | None = None) -> dict:
        """Metadata for a CSV: versions, property tier, resolved scene, units, time."""
        return csv_meta(self, columns, file)

    def to_csv(self, path: str | Path, table: str = "timeseries", units_system: str | None = None) -> Path:
        """Write the time series (or ``table="cycles"``) as CSV with a ``.meta.json`` beside it.

        Returns the CSV path.  Both files are written atomically.
        """
        df = self.timeseries if table == "timeseries" else self.cycles
        return write_csv(self, df, path, units_system)

    def plot_card(self, ax=None, units_system: str | None = None):
        """Period-style indicator card of both ends; see :func:`corliss.plot.plot_card`."""
        from corliss.plot import plot_card
        return plot_card(self, ax=ax, units_system=units_system)

    def write(self, out_dir: str | Path) -> dict[str, Path]:
        """Write the card PNG, the time-series and per-cycle CSVs with meta, and summary JSON."""
        out_dir = Path(out_dir)
        stem = self.scene.name
        files = {
            "timeseries": self.to_csv(out_dir / f"{stem}.timeseries.csv"),
            "cycles": self.to_csv(out_dir / f"{stem}.cycles.csv", table="cycles"),
        }
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from corliss.plot import plot_card, plot_crank_effort
        figures = [("card", plot_card, (9, 5.5)), ("effort", plot_crank_effort, (9, 4.5))]
        if self.scene.compound is not None:
            figures.append(("lp_card", lambda r, ax: plot_card(r, ax=ax, prefix="lp_"), (9, 5.5)))
        for kind, draw, size in figures:
            fig, ax = plt.subplots(figsize=size)
            draw(self, ax=ax)
            png = out_dir / f"{stem}.{kind}.png"
            _write_atomic(png, lambda p: fig.savefig(p, dpi=130, bbox_inches="tight",
                                                     format="png"))
            plt.close(fig)
            files[kind] = png
        sj = out_dir / f"{stem}.summary.json"
        _write_atomic(sj, lambda p: Path(p).write_text(json.dumps(_jsonable(self.summary), indent=2)))
        files["summary"] = sj
        return files


def csv_meta(result, columns: dict | None = None, file: str | None = None) -> dict:
    """Metadata for a CSV of any result with ``scene``, ``property_tier`` and ``summary``:
    versions, property tier, resolved scene, units of every column, time written."""
    from corliss.thermo.steam import coolprop_version
    return {
        "file": file,
        "corliss_version": package_version(),
        "coolprop_version": coolprop_version(),
        "property_backend": result.property_tier,
        "created_utc": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "units_system": result.scene.output.units,
        "pressure": "absolute",
        "columns": columns,
        "scene_file": result.scene.source,
        "scene": _jsonable(result.scene.resolved()),
        "summary": _jsonable(result.summary),
    }


def write_csv(result, df: pd.DataFrame, path: str | Path, units_system: str | None = None) -> Path:
    """Write an SI frame of ``result`` as CSV in the output units, with its ``.meta.json``;
    both atomically.  Returns the CSV path."""
    path = Path(path)
    system = units_system or result.scene.output.units
    out, col_units = convert_frame(df, system, result.scene.supply.barometer_Pa)
    _write_atomic(path, lambda p: out.to_csv(p, index=False, float_format="%.9g"))
    meta = csv_meta(result, col_units, path.name)
    _write_atomic(path.with_suffix(".meta.json"),
                  lambda p: Path(p).write_text(json.dumps(meta, indent=2)))
    return path


def _jsonable(obj):
    """Turn numpy scalars, tuples and NaN into plain JSON values."""
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        f = float(obj)
        return f if math.isfinite(f) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def summary_json(summary: dict) -> str:
    """The summary as the JSON text of ``corliss run --json``."""
    return json.dumps(_jsonable(summary), indent=2)
