"""How a rig kind's runs are measured, summarised and plotted.

Each :class:`~frictionsim.scenario.rigs.RigKind` names one analysis; a scenario file's cases all share one (their
summaries and plots differ), and its ``[analysis]`` keys are the analysis's:

* :data:`CYCLE_MEAN` (axial and kinematic rigs, paper 000): the mean friction force F_df over whole vibration cycles,
  :class:`CaseRun`; plots of friction force, hysteresis and drive force against time.
* :data:`LIMIT_CYCLE` (the torsional rig, paper 001): the limit cycle of the disc speed
  (:func:`frictionsim.torsional.limit_cycle`), :class:`LimitCycleRun`; plots of disc speed, friction-torque
  hysteresis and the disc's phase portrait (documented with the torsional rig kind,
  :class:`frictionsim.scenario.rigs.Torsional`).
* :data:`STICK_SLIP` (drill strings, :class:`frictionsim.StringRig`): the bit's stick-slip after the transient
  (:func:`frictionsim.drillstring.stick_slip`) and, where asked, the stick-slip map over surface speed and weight on
  bit (:func:`frictionsim.drillstring.stick_slip_map`), :class:`StringRun`; plots of bit and surface speed and
  torque, and of the map.
"""

from __future__ import annotations

import abc
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from ..atomic import write_csv
from .._core import PowerLawCoefficient, whole_cycle_window
from ..errors import InvalidParameterError
from .text import article, join

#: SI units of the rig kinds' derived time-series columns (:meth:`frictionsim.scenario.rigs.RigKind.columns`); the
#: states' units are the rig's and its law's own (:attr:`frictionsim.Result.units`).
KIND_COLUMN_UNITS: Dict[str, str] = {
    "surface_position": "m", "surface_velocity": "m/s", "relative_displacement": "m", "relative_velocity": "m/s",
    "drive_force": "N", "disc_acceleration": "rad/s^2", "friction_torque": "N m", "shaft_torque": "N m",
    "voltage": "V", "surface_torque": "N m", "bit_torque": "N m", "wall_friction_torque": "N m",
}

__all__ = ["Analysis", "CYCLE_MEAN", "CaseRun", "CycleMean", "LIMIT_CYCLE", "LimitCycle", "LimitCycleRun",
           "STICK_SLIP", "StickSlipAnalysis", "StringRun"]

Window = Optional[Tuple[float, float]]


# ------------------------------------------------------------------------------------------------------ runs
@dataclass
class _Run:
    case: Any  #: frictionsim.scenario.Case
    rig: Any  #: the rig object
    result: Any  #: frictionsim.Result

    @property
    def normal_force(self) -> float:
        """The normal force [N]: F_N, or N2 on the torsional disc."""
        return float(self.rig.normal_force)

    def timeseries(self):
        """pandas DataFrame: t [s], the rig's states (SI), the columns of its kind
        (:meth:`frictionsim.scenario.rigs.RigKind.columns`) and mode; ``attrs["units"]``: each column's unit."""
        import pandas as pd

        r = self.result
        columns: Dict[str, np.ndarray] = {"t": r.t}
        columns.update((name, r[name]) for name in r.state_names)
        columns.update(self.case.kind.columns(self))
        columns["mode"] = r.mode
        frame = pd.DataFrame(columns)
        units = {name: unit for name, unit in KIND_COLUMN_UNITS.items() if name in columns}
        units.update((name, unit) for name, unit in r.units.items() if name in columns)
        frame.attrs["units"] = units
        return frame


@dataclass
class CaseRun(_Run):
    """A simulated case: the :class:`frictionsim.Result`, the rig object and the mean friction F_df [N]."""

    mean_friction: float  #: F_df [N], mean over whole cycles
    window: Tuple[float, float, int]  #: (t_a [s], t_b [s], cycles)
    wall_time: float  #: s

    @property
    def velocity_ratio(self) -> float:
        """v_a / v_d [-] (eq 16-17), NaN for a sampled velocity or v_d = 0."""
        return self.case.kind.velocity_ratio(self)

    def summary(self) -> Dict[str, Any]:
        """One summary row: F_df [N], mu_df = F_df / F_N, reduction against mu F_N [%], events, steps, ..."""
        normal, mu = self.normal_force, self.case.friction.mu
        ratio = self.velocity_ratio
        table5 = math.nan
        if self.case.lubricant and math.isfinite(ratio):
            table5 = float(PowerLawCoefficient.from_table5(self.case.lubricant).coefficient(ratio, 1.0)) * normal
        return {
            "case": self.case.name, "law": self.case.friction.label, "rig": self.case.rig.type,
            "F_N_N": normal, "mu": mu, "mu_F_N_N": mu * normal, "F_df_N": self.mean_friction,
            "mu_df": self.mean_friction / normal,
            "reduction_percent": 100.0 * (1.0 - self.mean_friction / (mu * normal)),
            "velocity_ratio": ratio, "F_df_table5_N": table5, "window_start_s": self.window[0],
            "window_end_s": self.window[1], "cycles": self.window[2], "events": len(self.result.events),
            "steps": int(self.result.stats["steps"]), "t_end_s": self.case.solver.t_end,
        }


@dataclass
class LimitCycleRun(_Run):
    """A simulated torsional case: the :class:`frictionsim.Result`, the rig object and its limit cycle."""

    cycle: Any  #: frictionsim.torsional.LimitCycle
    wall_time: float  #: s

    @property
    def reference_speed(self) -> float:
        """w_ref [rad/s]."""
        return float(self.rig.reference_speed)

    def analysis_window(self) -> Tuple[float, float]:
        """(t_a, t_b) [s]: the whole cycles measured, or [transient, t_end] when no cycle was found."""
        if self.cycle.cycles > 0:
            return float(self.cycle.start), float(self.cycle.end)
        return LIMIT_CYCLE.transient(self.case), float(self.result.t[-1])

    @property
    def mean_friction_torque(self) -> float:
        """Time average of T_f2 [N m] over :meth:`analysis_window` (trapezoid on the output grid)."""
        t, torque = self.result.t, self.result.friction_force
        t_a, t_b = self.analysis_window()
        inside = (t >= t_a) & (t <= t_b)
        if inside.sum() < 2:
            return math.nan
        t, torque = t[inside], torque[inside]
        return float(np.sum(0.5 * (torque[1:] + torque[:-1]) * np.diff(t)) / (t[-1] - t[0]))

    def operating_point(self) -> Optional[Tuple[float, float]]:
        """(twist [rad], w_ref [rad/s]) about which the disc moves: mean T_f2 / k2 over the measured window (the
        mean of S = k2 twist + d2 (w3 - w2) is the mean friction torque, and w3 - w2 averages to zero over whole
        cycles). Derived from the run, so it holds for every law; None when the window holds too few samples."""
        torque = self.mean_friction_torque
        if not math.isfinite(torque):
            return None
        return torque / float(self.rig.shaft_stiffness), self.reference_speed

    def summary(self) -> Dict[str, Any]:
        """One summary row: the limit cycle (frequency, period, peak / trough / mean disc speed, stick fraction),
        the mean friction torque over the measured cycles, and the run's counters."""
        c, w_ref = self.cycle, self.reference_speed
        t_a, t_b = self.analysis_window()
        return {
            "case": self.case.name, "law": self.case.friction.label, "rig": self.case.rig.type,
            "reference_speed_rad_s": w_ref, "normal_force_N": self.normal_force,
            "stick_slip": bool(c.stick_slip), "frequency_Hz": c.frequency, "period_s": c.period,
            "peak_speed_rad_s": c.peak, "trough_speed_rad_s": c.trough, "mean_speed_rad_s": c.mean,
            "peak_ratio": c.peak / w_ref if w_ref != 0 else math.nan, "stick_fraction": c.stick_fraction,
            "severity": c.severity,
            "mean_friction_torque_Nm": self.mean_friction_torque, "cycles": int(c.cycles),
            "natural_frequency_Hz": float(self.rig.natural_frequency),
            "stick_speed_rad_s": LIMIT_CYCLE.stick_speed(self.case), "transient_s": LIMIT_CYCLE.transient(self.case),
            "window_start_s": t_a, "window_end_s": t_b,
            "events": len(self.result.events), "steps": int(self.result.stats["steps"]),
            "t_end_s": self.case.solver.t_end,
        }


@dataclass
class StringRun(_Run):
    """A simulated drill-string case: the :class:`frictionsim.Result`, the rig, the bit's stick-slip after the
    transient (:class:`frictionsim.drillstring.StickSlip`) and the stick-slip map where one was asked for."""

    stick_slip: Any  #: frictionsim.drillstring.StickSlip
    map: Any  #: frictionsim.drillstring.StickSlipMap or None
    wall_time: float  #: s

    @property
    def normal_force(self) -> float:
        """The sum of the wall contacts' normal forces [N] (NaN for a TorsionalString, whose walls carry a
        friction torque per length, A&S eq 6)."""
        forces = getattr(self.rig, "normal_forces", None)
        return float(np.sum(forces)) if forces is not None else math.nan

    def summary(self) -> Dict[str, Any]:
        """One summary row: set speed, weight on bit, peak / mean bit speed over w_set, the bit's stuck fraction,
        the surface speed's peak over w_set, the stuck wall contacts at the end, and the run's counters."""
        from .. import drillstring as ds

        m, rig = self.stick_slip, self.rig
        weight = rig.weight_on_bit
        return {
            "case": self.case.name, "law": self.case.friction.label, "rig": self.case.rig.type,
            "treatment": self.case.rig.params.get("treatment", "exact"),
            "surface_speed_rad_s": ds.set_speed(rig),
            "weight_on_bit_N": float(weight) if weight is not None and weight > 0 else math.nan,
            "elements": int(rig.elements), "wall_contacts": ds.wall_contacts(rig),
            "wall_normal_force_N": self.normal_force, "bit_sticks": bool(m.sticks), "peak_ratio": m.peak_ratio,
            "mean_ratio": m.mean_ratio, "bit_stuck_fraction": m.stuck_fraction,
            "surface_peak_ratio": m.surface_peak_ratio, "stuck_contacts_end": int(self.result.mode[-1]),
            "transient_s": STICK_SLIP.transient(self.case), "events": len(self.result.events),
            "steps": int(self.result.stats["steps"]), "t_end_s": self.case.solver.t_end,
        }


# -------------------------------------------------------------------------------------------------- analyses
class Analysis(abc.ABC):
    """What a scenario's ``[analysis]`` takes (:attr:`keys`), how it is checked, what a run measures, which summary
    columns ``frictionsim run`` prints and how the plots are drawn."""

    #: [analysis] key -> value type
    keys: Dict[str, type] = {}
    #: printed under the summary table
    summary_note = ""

    def unknown_note(self, kind) -> str:
        """Words after "unknown key" for an [analysis] key that ``kind`` (a RigKind) does not take."""
        return ""

    def plots_note(self, kinds: Sequence[str]) -> str:
        """Words after the list of plots a file of rig ``kinds`` may ask for."""
        return ""

    def check(self, parser, case, paths: Mapping[str, str]) -> None:
        """Raise ``parser.error(...)`` where ``case``'s analysis cannot work (``paths``: key -> dotted path, with
        "_section" and "t_end")."""

    @abc.abstractmethod
    def window(self, case) -> Tuple[float, float, int]:
        """(t_a, t_b, cycles): the whole vibration cycles [s] a case's mean is taken over."""

    def output_times(self, case) -> np.ndarray:
        """The output times [s] of ``case``'s run."""
        return case.solver.grid()

    @abc.abstractmethod
    def measure(self, case, rig, result, wall_time: float):
        """The run record of a completed simulation."""

    @abc.abstractmethod
    def summary_columns(self, summary) -> List[Tuple[str, str, str]]:
        """(column, header, format) of the summary table ``frictionsim run`` prints."""

    def plot_window(self, runs: Sequence[Any], plot_window: Window) -> Window:
        """The time window [s] of every plot (None: each plot has its own default)."""
        return plot_window

    @abc.abstractmethod
    def write_plots(self, runs: Sequence[Any], traces: Sequence, wanted: Sequence[str], directory: Path, *,
                    title: str, plot_window: Window) -> List[Path]:
        """Write the PNGs of ``wanted`` into ``directory``; ``traces`` are (label, timeseries) per run."""

    def write_tables(self, runs: Sequence[Any], directory: Path) -> List[Path]:
        """CSV tables of the analysis beyond the time series and the summary (written with the summary)."""
        return []


class CycleMean(Analysis):
    """The mean friction force F_df over ``cycles`` whole cycles of the vibration period after ``transient``."""

    keys = {"transient": float, "cycles": int, "period": float}
    summary_note = "F_df: mean friction over whole cycles; reduction = 1 - F_df / (mu F_N)"
    PLOT_CYCLES = 3  #: the default plot window: the last 3 vibration cycles of the first case

    def check(self, parser, case, paths: Mapping[str, str]) -> None:
        fallback = paths["_section"]
        if case.period is None:
            raise parser.error(join(fallback, "period"), f"missing required value: {case.kind.describe(case.rig)} "
                                                         f"has no vibration period (s) to average over")
        a = case.analysis
        if a.transient is None and a.cycles and a.cycles * case.period > case.solver.t_end:
            raise parser.error(paths["cycles"], f"the last {a.cycles} cycles ({a.cycles * case.period:g} s) must "
                                                f"fit in t_end = {case.solver.t_end:g} s")
        try:
            case.window()
        except InvalidParameterError as error:
            raise parser.engine(error, paths, paths.get("transient", paths.get("cycles", fallback))) from None

    def window(self, case) -> Tuple[float, float, int]:
        period, t_end, a = case.period, case.solver.t_end, case.analysis
        transient = a.transient
        if transient is None:
            transient = t_end - a.cycles * period if a.cycles else 0.5 * t_end
        return tuple(whole_cycle_window(0.0, t_end, period, transient, int(a.cycles or 0)))

    def output_times(self, case) -> np.ndarray:
        t_a, t_b, _ = case.window()
        return np.union1d(case.solver.grid(), [t_a, t_b])

    def measure(self, case, rig, result, wall_time: float) -> CaseRun:
        t_a, t_b, cycles = case.window()
        mean = result.mean_over_cycles(period=case.period, transient=t_a, cycles=cycles)
        return CaseRun(case, rig, result, float(mean), (t_a, t_b, cycles), wall_time)

    def summary_columns(self, summary) -> List[Tuple[str, str, str]]:
        columns = [("case", "case", "s"), ("law", "law", "s"), ("F_N_N", "F_N [N]", ".4g"),
                   ("mu_F_N_N", "mu F_N [N]", ".4g"), ("F_df_N", "F_df [N]", ".5g"), ("mu_df", "mu_df", ".4g"),
                   ("reduction_percent", "reduction [%]", ".2f")]
        if summary["F_df_table5_N"].notna().any():
            columns.append(("F_df_table5_N", "Table 5 F_df [N]", ".4g"))
        return columns + [("events", "events", "d"), ("steps", "steps", "d")]

    def plot_window(self, runs: Sequence[CaseRun], plot_window: Window) -> Window:
        if plot_window is not None:
            return plot_window
        first = runs[0].case
        t_end = first.solver.t_end
        return (max(0.0, t_end - self.PLOT_CYCLES * first.period), t_end)

    def write_plots(self, runs, traces, wanted, directory, *, title, plot_window):
        from .. import plots

        makers = {"friction_force": plots.friction_force_figure, "hysteresis": plots.hysteresis_figure,
                  "drive_force": plots.drive_force_figure}
        window = self.plot_window(runs, plot_window)
        return [plots.save(makers[plot](traces, title=title, window=window), directory / f"{plot}.png")
                for plot in wanted]


class LimitCycle(Analysis):
    """The limit cycle of the disc speed after ``transient`` [s] (default t_end / 2), with ``stick_speed``
    [rad/s] (default 0.01) the |w2| counted as stuck (:func:`frictionsim.torsional.limit_cycle`)."""

    keys = {"transient": float, "stick_speed": float}
    DEFAULT_STICK_SPEED = 1e-2  #: rad/s, as frictionsim.torsional.limit_cycle
    TIME_SERIES_WINDOW = 10.0  #: s: the default window of the disc_speed plot ends at t_end
    SUMMARY_COLUMNS = [("case", "case", "s"), ("law", "law", "s"), ("reference_speed_rad_s", "w_ref [rad/s]", ".4g"),
                       ("normal_force_N", "N2 [N]", ".4g"), ("frequency_Hz", "f [Hz]", ".4f"),
                       ("period_s", "period [s]", ".4f"), ("peak_speed_rad_s", "peak [rad/s]", ".4g"),
                       ("trough_speed_rad_s", "trough [rad/s]", ".3g"), ("stick_fraction", "stick", ".3f"),
                       ("severity", "severity", ".3f"), ("mean_friction_torque_Nm", "mean T_f2 [N m]", ".4f"),
                       ("cycles", "cycles", "d"), ("events", "events", "d"), ("steps", "steps", "d")]
    summary_note = ("limit cycle of the disc speed w2 over whole cycles after the transient: f = stick-slip "
                    "frequency, stick = share of the time with |w2| <= stick_speed, severity = (peak - trough) / "
                    "(2 mean); mean T_f2 over the same cycles")

    def unknown_note(self, kind) -> str:
        return f" for {article(kind.name)} {kind.name} rig (its limit cycle)"

    def plots_note(self, kinds: Sequence[str]) -> str:
        return f" for {' / '.join(kinds)} rigs"

    @staticmethod
    def transient(case) -> float:
        """The start [s] of the limit-cycle analysis: analysis.transient, else t_end / 2."""
        a = case.analysis
        return float(a.transient) if a.transient is not None else 0.5 * case.solver.t_end

    def stick_speed(self, case) -> float:
        """|w2| [rad/s] at or below which the disc counts as stuck: analysis.stick_speed, else 0.01 rad/s."""
        a = case.analysis
        return float(a.stick_speed) if a.stick_speed is not None else self.DEFAULT_STICK_SPEED

    def check(self, parser, case, paths: Mapping[str, str]) -> None:
        transient, t_end = case.analysis.transient, case.solver.t_end
        if transient is not None and not (math.isfinite(transient) and 0.0 <= transient < t_end):
            raise parser.error(paths["transient"], f"must be >= 0 and < t_end = {t_end:g} s (got {transient:g})")

    def window(self, case) -> Tuple[float, float, int]:
        raise ValueError(f"a {case.rig.type} case has no vibration period: its limit cycle is measured after the run")

    def measure(self, case, rig, result, wall_time: float) -> LimitCycleRun:
        from ..torsional import limit_cycle

        cycle = limit_cycle(result, self.transient(case), stick_speed=self.stick_speed(case))
        return LimitCycleRun(case, rig, result, cycle, wall_time)

    def summary_columns(self, summary) -> List[Tuple[str, str, str]]:
        return list(self.SUMMARY_COLUMNS)

    def default_windows(self, runs: Sequence[LimitCycleRun]) -> Dict[str, Tuple[float, float]]:
        """Plot name -> (t_start, t_end) [s] where output.plot_window is not given: the last 10 s for disc_speed,
        [transient, t_end] for the others."""
        t_end = min(run.case.solver.t_end for run in runs)
        cycle = (min(max(self.transient(run.case) for run in runs), t_end), t_end)
        return {"disc_speed": (max(0.0, t_end - self.TIME_SERIES_WINDOW), t_end),
                "friction_torque_hysteresis": cycle, "phase_portrait": cycle}

    def write_plots(self, runs, traces, wanted, directory, *, title, plot_window):
        from .. import plots

        windows = self.default_windows(runs)
        makers = {
            "disc_speed": lambda window: plots.disc_speed_figure(
                traces, title=title, window=window, reference_speeds=[run.reference_speed for run in runs]),
            "friction_torque_hysteresis": lambda window: plots.friction_torque_hysteresis_figure(
                traces, title=title, window=window),
            "phase_portrait": lambda window: plots.phase_portrait_figure(
                traces, title=title, window=window, equilibria=[run.operating_point() for run in runs],
                natural_frequency=float(runs[0].rig.natural_frequency)),
        }
        return [plots.save(makers[plot](plot_window or windows[plot]), directory / f"{plot}.png") for plot in wanted]


class StickSlipAnalysis(Analysis):
    """A drill string's stick-slip at the bit after ``transient`` [s] (default t_end / 2), and where
    ``surface_speeds`` [rad/s] and ``weights_on_bit`` [N] are given, its stick-slip map over that grid (each point a
    run of the case's rig from rest, as long as the case's)."""

    keys = {"transient": float, "surface_speeds": list, "weights_on_bit": list}
    SUMMARY_COLUMNS = [("case", "case", "s"), ("law", "law", "s"), ("surface_speed_rad_s", "w_set [rad/s]", ".4g"),
                       ("weight_on_bit_N", "W [N]", ".4g"), ("elements", "N", "d"),
                       ("peak_ratio", "peak bit / w_set", ".3f"), ("mean_ratio", "mean bit / w_set", ".3f"),
                       ("bit_stuck_fraction", "bit stuck", ".3f"), ("surface_peak_ratio", "peak top / w_set", ".3f"),
                       ("events", "events", "d"), ("steps", "steps", "d")]
    summary_note = ("bit speed after the transient against the set surface speed w_set: peak and time mean, and the "
                    "share of the time the bit is stuck (exactly at rest)")
    TIME_SERIES_WINDOW = 30.0  #: s: the default window of the bit_speed plot ends at t_end

    def unknown_note(self, kind) -> str:
        return f" for {article(kind.name)} {kind.name} rig (its stick-slip)"

    def plots_note(self, kinds: Sequence[str]) -> str:
        return f" for {' / '.join(kinds)} rigs"

    @staticmethod
    def transient(case) -> float:
        """The start [s] of the measures: analysis.transient, else t_end / 2."""
        a = case.analysis
        return float(a.transient) if a.transient is not None else 0.5 * case.solver.t_end

    def check(self, parser, case, paths: Mapping[str, str]) -> None:
        a, t_end = case.analysis, case.solver.t_end
        if a.transient is not None and not (math.isfinite(a.transient) and 0.0 <= a.transient < t_end):
            raise parser.error(paths["transient"], f"must be >= 0 and < t_end = {t_end:g} s (got {a.transient:g})")
        grid = {key: getattr(a, key) for key in ("surface_speeds", "weights_on_bit")}
        given = [key for key, value in grid.items() if value is not None]
        if len(given) == 1:
            missing = next(key for key in grid if key not in given)
            raise parser.error(join(paths["_section"], missing), f"missing required value: a stick-slip map needs "
                                                                 f"both surface_speeds and weights_on_bit")
        for key in given:
            values = grid[key]
            if not values:
                raise parser.error(paths[key], "must hold at least one value")
            for i, value in enumerate(values):
                if not (math.isfinite(value) and value > 0.0):
                    raise parser.error(f"{paths[key]}[{i + 1}]", f"must be positive and finite (got {value:g})")
        if given and case.kind.time_stepping(case.rig):
            raise parser.error(paths[given[0]], f"a stick-slip map runs the exact treatment only (got treatment "
                                                f"{case.rig.params['treatment']!r})")
        if given and "bit" not in case.rig.params:
            raise parser.error(paths[given[0]], "a stick-slip map needs a bit on bottom (give rig.bit and "
                                                "rig.weight_on_bit)")

    def window(self, case) -> Tuple[float, float, int]:
        raise ValueError(f"a {case.rig.type} case has no vibration period: its stick-slip is measured after the run")

    def measure(self, case, rig, result, wall_time: float) -> StringRun:
        from concurrent.futures import ThreadPoolExecutor

        from .. import drillstring as ds

        transient = self.transient(case)
        measures = ds.stick_slip(rig, result, transient)
        grid = None
        a = case.analysis
        if a.surface_speeds is not None:
            # each point's run keeps the case's wall-clock budget (solver.timeout, or --timeout): a point that runs
            # out is marked timed out in the map and the others still run
            budget = {} if case.solver.timeout is None else {"timeout": case.solver.timeout}
            with ThreadPoolExecutor(2) as executor:  # the engine releases the GIL: the points run in parallel
                grid = ds.stick_slip_map(rig, a.surface_speeds, a.weights_on_bit, t_end=case.solver.t_end,
                                         transient=transient, rtol=case.solver.rtol, executor=executor, **budget)
        return StringRun(case, rig, result, measures, grid, wall_time)

    @staticmethod
    def map_failures(run: "StringRun") -> List[Tuple[int, str]]:
        """(point index in C order, reason) of the map's points that failed or ran out of their timeout."""
        grid = run.map
        if grid is None:
            return []
        timed_out = getattr(grid, "timed_out", None)
        out = []
        for i, value in enumerate(grid.sweep.values):
            if isinstance(value, BaseException):
                out.append((i, f"{type(value).__name__}: {value}"))
            elif timed_out is not None and timed_out.flat[i]:
                out.append((i, f"timed out: its run passed timeout = {run.case.solver.timeout:g} s"))
        return out

    def summary_columns(self, summary) -> List[Tuple[str, str, str]]:
        return list(self.SUMMARY_COLUMNS)

    def write_tables(self, runs, directory: Path) -> List[Path]:
        """stick_slip_map_<case>.csv of every case with a map."""
        written = []
        for run in runs:
            if run.map is not None:
                written.append(write_csv(run.map.to_pandas(), directory / f"stick_slip_map_{run.case.name}.csv"))
        return written

    def write_plots(self, runs, traces, wanted, directory, *, title, plot_window):
        from .. import drillstring as ds
        from .. import plots

        t_end = min(run.case.solver.t_end for run in runs)
        window = plot_window or (max(0.0, t_end - self.TIME_SERIES_WINDOW), t_end)
        written = []
        if "bit_speed" in wanted:
            figure = ds.speeds_panels_figure([(label, run.rig, run.result) for (label, _), run in zip(traces, runs)],
                                             title=title, window=window)
            written.append(plots.save(figure, directory / "bit_speed.png"))
        if "stick_slip_map" in wanted:
            for run in runs:
                if run.map is not None:
                    figure = ds.string_stick_slip_map_figure(run.map, title=f"{title}: {run.case.name}",
                                                             point=(ds.set_speed(run.rig),
                                                                    float(run.rig.weight_on_bit)))
                    written.append(plots.save(figure, directory / f"stick_slip_map_{run.case.name}.png"))
        return written


CYCLE_MEAN = CycleMean()
LIMIT_CYCLE = LimitCycle()
STICK_SLIP = StickSlipAnalysis()
