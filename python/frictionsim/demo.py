"""The built-in demo, ``frictionsim demo``: paper 000's axial vibrating-sliding rig (shale on 45 steel), paper
001's torsional drill-string rig and a field-scale drill string.

1. Fig. 7: the dry case (Table 4 run VS3: u0 = 5 mm, f = 17 Hz, v_d = 60 mm/min, F_N = 90 N) and the OBM case
   (VS17: u0 = 4 mm, f = 20 Hz, F_N = 30 N) with Coulomb (eq 8) and Dahl (eq 9) friction side by side: each is a
   scenario file (:data:`BUILTIN_SCENARIOS`, package data that examples/scenarios/fig7_*.toml link to) run as
   ``frictionsim run`` runs it, into ``<out>/fig7_dry/`` and ``<out>/fig7_obm/``.
2. Friction reduction: the mean friction F_df with vibration against the same case without vibration (u0 = 0,
   F_sf), per law, next to Table 4's measured F_df and F_sf and the Table 5 power law (eq 17) for those runs
   (:func:`frictionsim.axial.table4_comparison`, ``fig7_friction_reduction.csv``).
3. A sweep over the vibration amplitude (velocity ratio v_d/v_a) as in examples/axial_rig_demo.cpp: the
   closed form 1 - (2/pi) asin(v_d/v_a) of the kinematic Coulomb rig, the simulated kinematic rig, and the axial
   rig with Coulomb and Dahl friction (:func:`frictionsim.axial.reduction_sweep`; ``friction_reduction.csv``, the
   C++ demo's file with more columns, and ``friction_reduction.png``).
4. The Table 5 refit: :func:`frictionsim.fit.fit_power_law` on :func:`frictionsim.data.table4` beside the
   printed Table 5 (``table5_refit.csv``) and the log-log plot of Fig. 11 (``fig11_power_law.png``).
5. Paper 001, into ``<out>/paper001/``: the built-in scenario ``fig7_torsional`` (the Fig. 7 operating point,
   w_ref = 5.76 rad/s and N2 = 35 N, with the eq 6, Stribeck and LuGre laws; ``paper001/fig7_torsional/``: time
   series, summary, disc speed, friction-torque hysteresis and phase-portrait plots); the limit cycle of every
   law of :func:`frictionsim.torsional.fig7_laws` against the paper's 0.83 / 0.84 Hz, 13.55 / 14 rad/s and
   f_n = 0.789 Hz (:func:`frictionsim.torsional.compare_laws`, ``law_comparison.csv`` and ``.png``); and the
   stick-slip map over w_ref and N2 with the eq 6 law (:func:`frictionsim.torsional.stick_slip_map` on two
   threads, 40 s per point, ``stick_slip_map.csv`` and ``.png``).
6. A field string (issue 13), into ``<out>/field_string/``: 2800 m of 5" drill pipe above 200 m of 6 1/2" collars
   in a 60 degree hole, lumped into 30 elements (100 m), Coulomb wall friction at every node (mu = 0.2, mu_s =
   0.25) under the buoyed weight's normal force, PI top drive, the Navarro-Lopez velocity-weakening bit on bottom
   (:func:`field_rig`); its stick-slip map over surface speed and weight on bit
   (:func:`frictionsim.drillstring.stick_slip_map`, 60 s from rest per point, measured after 30 s:
   ``stick_slip_map.csv`` and ``.png``) and, at one stick-slip point, bit and surface speed and torque over time
   (``time_series.csv``, ``speeds.png``). Then Well B (Aarsnes & Shor 2018) at field resolution through the
   drillstring scenario's captured treatment (the built-in scenario ``well_b_captured``: a TorsionalString, 40 s,
   1000 elements; --quick 500): ``well_b_captured.csv`` and ``.png`` (:func:`well_b_captured`).
7. A horizontal well (issue 14), into ``<out>/horizontal_well/``: the example survey with a 3 km lateral
   (examples/surveys/horizontal_3km.csv), 4700 m of 5" pipe over 150 m of 6 1/2" collars, soft-string torque and
   drag: the broomstick over friction factors 0.15-0.35 with, beside tripping, the string slid in at the drilling
   rate (no weight on bit) without and with a 60 kN hydraulic oscillator 300 m above the bit (at trip speed the
   tool's ~0.2 m/s vibration does not reverse the sliding, so it changes nothing there: ``broomstick.csv``,
   ``broomstick.png``), and the tool's placement while sliding at the hook load that puts 20 kN on the bit without
   it (:func:`frictionsim.wells.place_oscillators`: ``placement.csv``,
   ``placement.png``).

Scenario choices follow examples/axial_rig_demo.cpp (the C++ demo): m = 0.2 kg, k_d = 2e4 N/m, mu = 0.41 (dry) and
0.27 (OBM), Dahl k_t = 40 N/mm (Fig. 10), 2 s with the mean over the last 10 cycles; sweep ratios 0.05-1.5,
kinematic runs over 5 cycles, axial runs averaged over 10 cycles after 8 s. Everything is simulated before
anything is written (:func:`compute`, then :meth:`Demo.write`).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from pathlib import Path
from importlib import resources
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from .atomic import write_csv
from . import drillstring as ds
from .axial import NO_VIBRATION_T_END, SWEEP_SETTLE, reduction_sweep, table4_comparison
from .scenario import Scenario, ScenarioRun, loads, run
from .scenario.analyses import STICK_SLIP
from .torsional import FIG7 as PAPER001_FIG7

__all__ = ["BUILTIN_SCENARIOS", "STAGES", "Demo", "FieldString", "HorizontalWell", "Paper001", "builtin_scenario",
           "compute", "field_rig", "field_string", "format_table", "horizontal_well", "paper001", "table5_refit"]

#: The built-in scenarios: package data (python/frictionsim/scenarios/), linked from examples/scenarios/.
BUILTIN_SCENARIOS = ("fig7_dry_coulomb_vs_dahl", "fig7_obm", "fig7_torsional")
#: output subdirectory -> built-in scenario
FIG7 = {"fig7_dry": "fig7_dry_coulomb_vs_dahl", "fig7_obm": "fig7_obm"}

#: v_d / v_a of the sweep: examples/axial_rig_demo.cpp's ratios (the quick demo takes every other one)
SWEEP_RATIOS = (0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 0.95, 1.5)
QUICK_SWEEP_RATIOS = (0.1, 0.4, 0.8, 1.5)

#: Paper 001: the built-in torsional scenario, and the stick-slip map grid (w_ref [rad/s] x N2 [N]; --quick: smaller)
PAPER001_SCENARIO = "fig7_torsional"
MAP_REFERENCE_SPEEDS = (2.0, 4.0, 5.76, 8.0, 10.0, 12.0, 15.0, 18.0, 21.0, 24.0)
MAP_NORMAL_FORCES = (15.0, 25.0, 35.0, 50.0, 70.0)
QUICK_MAP_REFERENCE_SPEEDS = (2.0, 5.76, 10.0, 18.0)
QUICK_MAP_NORMAL_FORCES = (15.0, 35.0, 70.0)
MAP_T_END, MAP_TRANSIENT = 40.0, 20.0  #: s per map point, as Fig. 7's scenario
MAP_THREADS = 2

#: The field string's map: surface speed w_set [rad/s] x weight on bit W [N] (--quick: smaller), the time series'
#: point (a stick-slip point), and the run length and transient [s]
FIELD_SPEEDS = (2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 15.0)
FIELD_WEIGHTS = (25e3, 50e3, 100e3, 150e3)
QUICK_FIELD_SPEEDS = (3.0, 6.0, 10.0, 15.0)
QUICK_FIELD_WEIGHTS = (50e3, 150e3)
FIELD_POINT = (6.0, 100e3)
FIELD_T_END, FIELD_TRANSIENT = 60.0, 30.0


def builtin_scenario(name: str) -> Scenario:
    """A built-in scenario, parsed by :func:`frictionsim.scenario.loads` (the one schema)."""
    text = resources.files("frictionsim").joinpath("scenarios", f"{name}.toml").read_text(encoding="utf-8")
    return loads(text, source=f"<built-in {name}.toml>", name=name)


def format_table(frame, columns: Sequence[Tuple[str, str, str]]) -> str:
    """Fixed-width text of ``frame``'s ``(column, header, format)`` columns; NaN prints as "-"."""
    cells = [[header for _, header, _ in columns]]
    for _, row in frame.iterrows():
        cells.append([("-" if isinstance(row[c], float) and math.isnan(row[c]) else format(row[c], f))
                      for c, _, f in columns])
    widths = [max(len(r[i]) for r in cells) for i in range(len(columns))]
    lines = ["  ".join(v.ljust(widths[i]) if i == 0 else v.rjust(widths[i]) for i, v in enumerate(r)) for r in cells]
    return "\n".join(line.rstrip() for line in lines)


def table5_refit():
    """Table 5 as printed beside its refit from Table 4 (:func:`frictionsim.fit.fit_power_law`), per lubricant.

    Columns: lubricant, lubricant_printed, slope_printed, slope_refit (= c), slope_stderr, intercept_printed,
    intercept_refit (= log10 eta'), intercept_stderr, eta_prime_printed, eta_prime_refit, eta_prime_stderr,
    eta_eq15_refit (eq 15's eta = eta' (2 pi)^c), eta_eq15_stderr, r_squared_printed, r_squared_refit,
    adjusted_r_squared_refit, n_runs, velocity_ratio_min, velocity_ratio_max (v_a/v_d fitted). The standard
    errors are fit_power_law's (least squares, one standard error; the paper prints none): five runs per line
    leave them wide, and a refit without them reads as more certain than Table 4 allows.
    """
    import pandas as pd

    from .data import table4, table5
    from .fit import fit_power_law

    fits = fit_power_law(table4())
    printed = table5().set_index("lubricant")
    frame = pd.DataFrame({
        "lubricant_printed": printed["lubricant_printed"],
        "slope_printed": printed["slope"], "slope_refit": fits["slope"], "slope_stderr": fits["slope_stderr"],
        "intercept_printed": printed["intercept"], "intercept_refit": fits["intercept"],
        "intercept_stderr": fits["intercept_stderr"],
        "eta_prime_printed": printed["eta_prime"], "eta_prime_refit": fits["eta_prime"],
        "eta_prime_stderr": fits["eta_prime_stderr"],
        "eta_eq15_refit": fits["eta_eq15"], "eta_eq15_stderr": fits["eta_eq15_stderr"],
        "r_squared_printed": printed["r_squared"], "r_squared_refit": fits["r_squared"],
        "adjusted_r_squared_refit": fits["adjusted_r_squared"], "n_runs": fits["n_runs"],
        "velocity_ratio_min": fits["velocity_ratio_min"], "velocity_ratio_max": fits["velocity_ratio_max"],
    }, index=fits.index)
    frame.index.name = "lubricant"
    return frame.reset_index()


TABLE5_COLUMNS = [("lubricant", "lubricant", "s"), ("slope_printed", "slope (printed)", "g"),
                  ("slope_refit", "refit", ".5f"), ("slope_stderr", "+-", ".3f"),
                  ("intercept_printed", "intercept (printed)", "g"), ("intercept_refit", "refit", ".5f"),
                  ("intercept_stderr", "+-", ".3f"), ("eta_prime_printed", "eta' (printed)", "g"),
                  ("eta_prime_refit", "refit", ".4f"), ("eta_prime_stderr", "+-", ".3f"),
                  ("r_squared_printed", "R^2 (printed)", "g"), ("r_squared_refit", "refit", ".4f"),
                  ("adjusted_r_squared_refit", "adj. R^2", ".4f")]


def table5_report(refit) -> str:
    """The refit table as text (printed values as printed), with a note on the R^2 column."""
    return ("Table 5 refit from Table 4 (least squares log10 mu_df = c log10(v_a/v_d) + log10 eta', per lubricant)\n"
            + format_table(refit, TABLE5_COLUMNS)
            + "\nslopes and intercepts reproduce Table 5; +- one standard error of the refit (least squares, five "
              "runs per line; the paper prints none); the printed R^2 are 0.04-0.09 below the fits' R^2 "
              "(closest: adjusted R^2; see frictionsim.fit.power_law)")


def _reduction_rows(subdir: str, scenario_run: ScenarioRun) -> List[dict]:
    """Each case beside Table 4 and Table 5 (:func:`frictionsim.axial.table4_comparison`, with the case's rig, law
    and solver settings)."""
    rows = []
    for r in scenario_run.runs:
        case = r.case
        rows.append({"case": subdir, "law": case.friction.label, **table4_comparison(
            r.rig.friction, lubricant=case.lubricant, t_end=case.solver.t_end, cycles=case.analysis.cycles,
            method=case.solver.method, rtol=case.solver.rtol, atol=case.solver.atol, **case.rig.params)})
    return rows


REDUCTION_COLUMNS = [("case", "case", "s"), ("law", "law", "s"), ("F_df_sim_N", "F_df sim [N]", ".4g"),
                     ("F_sf_sim_N", "F_sf sim [N]", ".4g"), ("reduction_sim_percent", "reduction sim [%]", ".2f"),
                     ("table4_run", "Table 4", "s"), ("F_df_table4_N", "F_df [N]", ".2f"),
                     ("F_sf_table4_N", "F_sf [N]", ".2f"), ("reduction_table4_percent", "reduction [%]", ".2f"),
                     ("F_df_table5_N", "Table 5 F_df [N]", ".2f")]


def _sweep(dry: ScenarioRun, ratios: Sequence[float]):
    """Friction reduction 1 - F_df/(mu F_N) against v_d/v_a on the dry Fig. 7 case's rig and laws
    (:func:`frictionsim.axial.reduction_sweep`, as axial_rig_demo.cpp)."""
    coulomb = next(r.case for r in dry.runs if r.case.friction.type == "coulomb")
    laws = {r.case.friction.type: r.rig.friction for r in dry.runs}
    return reduction_sweep(ratios, mu=coulomb.friction.mu, laws=laws, lubricant=coulomb.lubricant,
                           method=coulomb.solver.method, rtol=coulomb.solver.rtol, atol=coulomb.solver.atol,
                           **coulomb.rig.params)


SWEEP_COLUMNS = [("velocity_ratio", "v_d/v_a", ".5g"), ("amplitude_mm", "u0 [mm]", ".4g"),
                 ("coulomb_closed_form", "Coulomb exact", ".2%"), ("kinematic_coulomb", "kinematic sim", ".2%"),
                 ("axial_coulomb", "axial Coulomb", ".2%"), ("axial_dahl", "axial Dahl", ".2%"),
                 ("table5_dry", "Table 5 dry", ".2%"), ("table4_dry", "Table 4 dry", ".2%")]


LAW_COLUMNS = [("law", "law", "s"), ("stick_slip_text", "stick-slip", "s"), ("frequency", "f [Hz]", ".4f"),
               ("frequency_ratio", "f / f_n", ".3f"), ("peak", "peak [rad/s]", ".4g"),
               ("trough", "trough [rad/s]", ".3g"), ("stick_fraction", "stick", ".3f"),
               ("events", "events", ".0f"), ("steps", "steps", ".0f")]


@dataclass
class Paper001:
    """Paper 001's part of the demo: the Fig. 7 scenario, the law comparison and the stick-slip map."""

    fig7: ScenarioRun  #: the built-in fig7_torsional scenario, run
    laws: "object"  #: pandas DataFrame of frictionsim.torsional.compare_laws (law_comparison.csv)
    map: "object"  #: frictionsim.torsional.StickSlipMap (stick_slip_map.csv)
    map_seconds: float  #: wall time of the map [s]

    def law_table(self):
        """The law comparison with the paper's Fig. 7 values as two extra rows (for printing)."""
        import pandas as pd

        laws = self.laws.copy()
        natural = float(laws["natural_frequency"].iloc[0])
        laws["frequency_ratio"] = laws["frequency"] / natural
        laws["stick_slip_text"] = np.where(laws["stick_slip"], "yes", "no")
        paper = [{"law": f"paper 001 {kind}", "stick_slip_text": "yes", "frequency": PAPER001_FIG7[f"frequency_{kind}"],
                  "frequency_ratio": PAPER001_FIG7[f"frequency_{kind}"] / natural,
                  "peak": PAPER001_FIG7[f"peak_{kind}"]} for kind in ("measured", "simulated")]
        return pd.concat([laws, pd.DataFrame(paper)], ignore_index=True)

    def map_text(self) -> str:
        """The map as text: rows N2, columns w_ref; peak disc speed / w_ref, * where the disc sticks."""
        m = self.map
        header = "N2 [N] \\ w_ref [rad/s]"
        cells = [[header] + [f"{w:g}" for w in m.reference_speeds]]
        for j, force in enumerate(m.normal_forces):
            cells.append([f"{force:g}"] + ["failed" if m.failed[i, j] else
                                           ("*" if m.stick_slip[i, j] else " ") + f"{m.peak_ratio[i, j]:.2f}"
                                           for i in range(len(m.reference_speeds))])
        widths = [max(len(r[k]) for r in cells) for k in range(len(cells[0]))]
        return "\n".join("  ".join(v.ljust(widths[k]) if k == 0 else v.rjust(widths[k]) for k, v in enumerate(r))
                         for r in cells)

    def report(self, quick: bool) -> List[str]:
        rig = self.fig7.runs[0].rig
        summary = self.fig7.summary()
        analysis = self.fig7.analysis
        m = self.map
        return [
            "paper 001: torsional drill-string rig (DC motor + PI speed control, gear 8:1, shaft, disc; eqs 1-6, "
            "Tables 1-2)",
            f"4. Fig. 7 operating point: w_ref = {rig.reference_speed:g} rad/s, N2 = {rig.normal_force:g} N, "
            f"{self.fig7.runs[0].case.solver.t_end:g} s from rest, limit cycle after "
            f"{summary['transient_s'].iloc[0]:g} s (scenario fig7_torsional)",
            format_table(summary, [c for c in analysis.summary_columns(summary) if c[0] not in ("steps",)]),
            "   " + analysis.summary_note,
            "",
            "5. Friction laws at the Fig. 7 point (frictionsim.torsional.fig7_laws; chosen sets, the paper prints "
            "none), against paper 001 Fig. 7;",
            f"   f_n = sqrt(k2/J2)/2 pi = {float(self.laws['natural_frequency'].iloc[0]):.3f} Hz: laws of speed "
            "alone stay below it, eq 6's negative acceleration coefficient lifts f above it",
            format_table(self.law_table(), LAW_COLUMNS),
            "",
            f"6. Stick-slip map, eq 6 law: peak disc speed / w_ref, * = the disc sticks in the limit cycle "
            f"({m.stick_slip.sum()} of {m.stick_slip.size} points"
            + (f", {m.failed.sum()} failed" if m.failed.any() else "")
            + f"; {MAP_T_END:g} s per point, limit cycle after "
            f"{MAP_TRANSIENT:g} s;",
            f"   {m.stick_slip.size} simulations on {MAP_THREADS} threads in {self.map_seconds:.2f} s"
            + ("; --quick grid" if quick else "") + ")",
            self.map_text(),
        ]

    def write(self, directory: Path) -> List[Path]:
        """Write paper001/: fig7_torsional/ (the scenario's outputs), law_comparison.csv/.png,
        stick_slip_map.csv/.png."""
        from . import plots

        (directory / PAPER001_SCENARIO).mkdir(parents=True)
        written = self.fig7.write(directory / PAPER001_SCENARIO)
        written.append(write_csv(self.laws, directory / "law_comparison.csv"))
        written.append(write_csv(self.map.to_pandas(), directory / "stick_slip_map.csv"))
        written.append(plots.save(plots.law_comparison_figure(self.laws), directory / "law_comparison.png"))
        written.append(plots.save(plots.stick_slip_map_figure(
            self.map, title="eq 6 law (fig7_friction), 40 s from rest per point, limit cycle after 20 s",
            point=(PAPER001_FIG7["reference_speed"], PAPER001_FIG7["normal_force"])),
            directory / "stick_slip_map.png"))
        return written


def paper001(quick: bool = False) -> Paper001:
    """Paper 001's part of the demo (writes nothing): the Fig. 7 scenario, the law comparison, the stick-slip map
    (``quick``: a 4 x 3 grid instead of 10 x 5)."""
    from concurrent.futures import ThreadPoolExecutor

    from .torsional import compare_laws, stick_slip_map

    fig7 = run(builtin_scenario(PAPER001_SCENARIO))
    laws = compare_laws()
    speeds = QUICK_MAP_REFERENCE_SPEEDS if quick else MAP_REFERENCE_SPEEDS
    forces = QUICK_MAP_NORMAL_FORCES if quick else MAP_NORMAL_FORCES
    start = time.perf_counter()
    with ThreadPoolExecutor(MAP_THREADS) as executor:
        grid = stick_slip_map(speeds, forces, t_end=MAP_T_END, transient=MAP_TRANSIENT, executor=executor,
                              errors="collect")
    return Paper001(fig7, laws, grid, time.perf_counter() - start)


def field_rig(surface_speed: float = FIELD_POINT[0], weight_on_bit: float = FIELD_POINT[1]) -> "ds.StringRig":
    """The demo's field string (see the module docstring, item 6) at (w_set [rad/s], W [N])."""
    from . import Coulomb

    return ds.StringRig(ds.field_string(2800.0, 200.0), Coulomb(0.2, 0.25), bit=ds.NavarroLopezBit(),
                        weight_on_bit=weight_on_bit, elements=30, inclination=math.radians(60.0),
                        damping_time=2e-3, surface_speed=surface_speed, torque_limit=8e4)


@dataclass
class FieldString:
    """The field string's part of the demo: one stick-slip point over time and the stick-slip map."""

    rig: "ds.StringRig"  #: at FIELD_POINT
    result: "object"  #: its Result
    measures: "ds.StickSlip"
    map: "ds.StickSlipMap"
    map_seconds: float  #: wall time of the map [s]
    #: Well B at field resolution through the captured treatment (the built-in scenario well_b_captured): a
    #: frictionsim.scenario.StringRun of a TorsionalString
    captured: Any = None

    def time_series(self):
        import pandas as pd

        r, rig = self.result, self.rig
        return pd.DataFrame({"t_s": r.t, "surface_speed_rad_s": ds.surface_speed(rig, r),
                             "bit_speed_rad_s": ds.bit_speed(rig, r), "surface_torque_Nm": ds.surface_torque(rig, r),
                             "bit_torque_Nm": ds.bit_torque(rig, r), "stuck_contacts": ds.stuck_contacts(r)})

    def map_text(self) -> str:
        """Rows W [kN], columns w_set: peak bit speed / w_set, * where the bit sticks."""
        m = self.map
        cells = [["W [kN] \\ w_set [rad/s]"] + [f"{w:g}" for w in m.surface_speeds]]
        for j, weight in enumerate(m.weights_on_bit):
            cells.append([f"{weight / 1e3:g}"] + ["failed" if m.failed[i, j] else
                                                  ("*" if m.sticks[i, j] else " ") + f"{m.peak_ratio[i, j]:.2f}"
                                                  for i in range(len(m.surface_speeds))])
        widths = [max(len(r[k]) for r in cells) for k in range(len(cells[0]))]
        return "\n".join("  ".join(v.ljust(widths[k]) if k == 0 else v.rjust(widths[k]) for k, v in enumerate(r))
                         for r in cells)

    def report(self, quick: bool) -> List[str]:
        rig, m, x = self.rig, self.map, self.measures
        return [
            f"field string (issue 13): {rig.string.length:g} m (2800 m 5\" pipe + 200 m 6 1/2\" collars), 60 deg "
            f"hole, {rig.elements} elements, Coulomb walls mu = 0.2 / mu_s = 0.25 at {len(rig.contact_nodes)} nodes, "
            "PI top drive, Navarro-Lopez bit",
            f"7. w_set = {rig.surface_speed:g} rad/s, W = {rig.weight_on_bit / 1e3:g} kN, {FIELD_T_END:g} s from rest "
            f"({len(self.result.events)} switches): after {FIELD_TRANSIENT:g} s the bit peaks at "
            f"{x.peak_ratio:.2f} w_set, averages {x.mean_ratio:.2f} w_set and is stuck {100 * x.stuck_fraction:.0f} % "
            "of the time",
            f"8. Stick-slip map: peak bit speed / w_set, * = the bit sticks after {FIELD_TRANSIENT:g} s "
            f"({int(m.sticks.sum())} of {m.sticks.size} points; {m.sticks.size} simulations of {FIELD_T_END:g} s on "
            f"{MAP_THREADS} threads in {self.map_seconds:.2f} s" + ("; --quick grid" if quick else "") + ")",
            self.map_text(),
            *self.captured_report(),
        ]

    def captured_report(self) -> List[str]:
        if self.captured is None:
            return []
        run, x = self.captured, self.captured.stick_slip
        rig = run.rig
        return [f"9. Well B (Aarsnes & Shor 2018) at field resolution, treatment captured: {rig.elements} elements "
                f"({rig.nodes} wall contacts captured by Moreau-Jean, step {run.case.solver.step:g} s), "
                f"{run.case.solver.t_end:g} s in {run.wall_time:.2f} s: after {STICK_SLIP.transient(run.case):g} s "
                f"the bit peaks at {x.peak_ratio:.2f} w_set and is below {rig.slow_speed:g} rad/s "
                f"{100 * x.stuck_fraction:.0f} % of the time (break-off torque, A&S eq 27: "
                f"{rig.breakoff_torque / 1e3:.2f} kN m; period estimate, eq 40: {rig.period_estimate:.1f} s)"]

    def write(self, directory: Path) -> List[Path]:
        """Write field_string/: time_series.csv, speeds.png, stick_slip_map.csv/.png, and Well B's captured run
        (well_b_captured.csv, well_b_captured.png)."""
        from . import plots

        directory.mkdir(parents=True)
        written = [directory / "time_series.csv", directory / "stick_slip_map.csv"]
        write_csv(self.time_series(), written[0])
        write_csv(self.map.to_pandas(), written[1])
        rig = self.rig
        written.append(plots.save(ds.speeds_figure(
            rig, self.result, title=f"field string at w_set = {rig.surface_speed:g} rad/s, W = "
                                    f"{rig.weight_on_bit / 1e3:g} kN: torsional stick-slip of the bit"),
            directory / "speeds.png"))
        written.append(plots.save(ds.string_stick_slip_map_figure(
            self.map, title=f"field string, {FIELD_T_END:g} s from rest per point, measured after "
                            f"{FIELD_TRANSIENT:g} s", point=FIELD_POINT), directory / "stick_slip_map.png"))
        if self.captured is not None:
            run = self.captured
            written.append(write_csv(run.timeseries(), directory / "well_b_captured.csv"))
            written.append(plots.save(ds.speeds_panels_figure(
                [(f"{run.rig.elements} elements, captured", run.rig, run.result)],
                title="Well B (Aarsnes & Shor 2018), wall contacts captured by Moreau-Jean"),
                directory / "well_b_captured.png"))
        return written


def field_string(quick: bool = False) -> FieldString:
    """The field string's part of the demo (writes nothing)."""
    from concurrent.futures import ThreadPoolExecutor

    from .simulation import simulate

    rig = field_rig()
    result = simulate(rig, FIELD_T_END, rtol=1e-6)
    measures = ds.stick_slip(rig, result, FIELD_TRANSIENT)
    speeds = QUICK_FIELD_SPEEDS if quick else FIELD_SPEEDS
    weights = QUICK_FIELD_WEIGHTS if quick else FIELD_WEIGHTS
    start = time.perf_counter()
    with ThreadPoolExecutor(MAP_THREADS) as executor:
        grid = ds.stick_slip_map(rig, speeds, weights, t_end=FIELD_T_END, transient=FIELD_TRANSIENT, rtol=1e-6,
                                 executor=executor)
    map_seconds = time.perf_counter() - start
    return FieldString(rig, result, measures, grid, map_seconds, well_b_captured(quick))


def well_b_captured(quick: bool = False):
    """The built-in scenario well_b_captured run (500 elements, 40 s; the full demo: 1000, A&S's grid)."""
    from .scenario import run_case

    case = builtin_scenario("well_b_captured").cases[0]
    if not quick:
        case = dataclasses.replace(case, rig=case.rig.with_params(elements=1000))
    return run_case(case)


#: The horizontal well's case: friction factors of the broomstick, the tool (force amplitude [N], height above
#: the bit [m]), the weight on bit the plain string slides with [N].
WELL_FRICTION_FACTORS = (0.15, 0.25, 0.35)
WELL_TOOL_FORCE, WELL_TOOL_ABOVE_BIT, WELL_SLIDING_WOB = 60e3, 300.0, 20e3


@dataclass
class HorizontalWell:
    """The horizontal well's torque and drag with and without a hydraulic oscillator, and its placement."""

    chart: "object"  #: frictionsim.wells.Broomstick without the tool
    with_tool: "object"  #: pandas DataFrame: bit_depth, friction_factor, hook_load_plain / hook_load_tool sliding in
    placement: "object"  #: frictionsim.wells.Placement
    string_length: float

    def report(self, quick: bool) -> List[str]:
        p = self.placement
        deepest = self.with_tool[self.with_tool["bit_depth"] == self.with_tool["bit_depth"].max()]
        rows = []
        for mu in WELL_FRICTION_FACTORS:
            _, trip = self.chart.hook_loads("trip_in", mu)
            row = deepest[deepest["friction_factor"] == mu].iloc[0]
            rows.append(f"   mu = {mu:g}: tripping in {trip[-1] / 1e3:8.1f} kN; sliding in "
                        f"{row['hook_load_plain'] / 1e3:8.1f} kN, with the tool {row['hook_load_tool'] / 1e3:8.1f} kN")
        return [
            f"horizontal well (issue 14): examples/surveys/horizontal_3km.csv, {self.string_length:g} m string, "
            f"soft-string torque and drag; a {WELL_TOOL_FORCE / 1e3:g} kN hydraulic oscillator "
            f"{WELL_TOOL_ABOVE_BIT:g} m above the bit",
            "9. Hook load at TD (broomstick, open and cased hole at the same factor; sliding: at the drilling rate, "
            "no weight on bit):",
            *rows,
            f"10. Placement while sliding at {p.hook_load / 1e3:.1f} kN hook load ({WELL_SLIDING_WOB / 1e3:g} kN on "
            f"the bit without a tool): best at {p.depths[0]:.0f} m MD ({self.string_length - p.depths[0]:.0f} m above "
            f"the bit), {p.weight_on_bit / 1e3:.1f} kN on the bit ({p.evaluations} evaluations of the C++ objective)",
        ]

    def write(self, directory: Path) -> List[Path]:
        """Write horizontal_well/: broomstick.csv/.png, placement.csv/.png."""
        import pandas as pd

        from . import plots

        directory.mkdir(parents=True)
        written = [directory / "broomstick.csv", directory / "placement.csv"]
        frame = self.chart.frame.assign(tool=False)
        sliding = [self.with_tool.rename(columns={f"hook_load_{k}": "hook_load"})
                   .drop(columns=[f"hook_load_{'tool' if k == 'plain' else 'plain'}"])
                   .assign(operation="sliding_drilling", surface_torque=np.nan, tool=k == "tool")
                   for k in ("plain", "tool")]
        write_csv(pd.concat([frame, *sliding], ignore_index=True), written[0])
        write_csv(pd.DataFrame({"tool_depth": self.placement.scan_depths,
                                "weight_on_bit": self.placement.scan_weight_on_bit}), written[1])
        ax = plots.broomstick_axes(self.chart, title="horizontal well, 3 km lateral")
        for k, mu in enumerate(WELL_FRICTION_FACTORS):
            rows = self.with_tool[self.with_tool["friction_factor"] == mu]
            # sliding in without the tool is the slack-off line (Coulomb friction does not depend on the speed)
            ax.plot(rows["hook_load_tool"] / 1e3, rows["bit_depth"], color="darkorange", linewidth=1.2,
                    linestyle=["-", "--", "-."][k % 3], label=f"sliding in with the oscillator, mu = {mu:g}")
        ax.legend(fontsize=7, loc="upper right")
        written.append(plots.save(ax.figure, directory / "broomstick.png"))
        written.append(plots.save(plots.placement_axes(self.placement, title="hydraulic oscillator placement").figure,
                                  directory / "placement.png"))
        return written


def horizontal_well(quick: bool = False) -> HorizontalWell:
    """The horizontal well's part of the demo (writes nothing)."""
    from . import wells
    from ._core import DrillString, HydraulicOscillator, PipeSection

    survey = wells.read_survey(resources.files("frictionsim").joinpath("data", "horizontal_3km.csv"))
    string = DrillString([PipeSection(length=4700.0),
                          PipeSection(outer_diameter=0.1651, inner_diameter=0.0714, length=150.0)])
    step = 150.0 if quick else 50.0
    chart = wells.broomstick(survey, string, WELL_FRICTION_FACTORS, depth_step=step)
    rows = []
    for depth in sorted(set(chart.frame["bit_depth"])):
        if depth <= WELL_TOOL_ABOVE_BIT:
            continue
        model = wells.soft_string(survey, wells.string_to_depth(string, depth))
        tool = HydraulicOscillator(measured_depth=depth - WELL_TOOL_ABOVE_BIT, force_amplitude=WELL_TOOL_FORCE)
        for mu in WELL_FRICTION_FACTORS:
            r = model.oscillators("sliding_drilling", tool, weight_on_bit=0.0, open_hole_friction=mu,
                                  cased_hole_friction=mu)
            rows.append({"bit_depth": depth, "friction_factor": mu, "hook_load_plain": r.plain.hook_load,
                         "hook_load_tool": r.vibrated.hook_load})
    import pandas as pd

    model = wells.soft_string(survey, string)
    mu = dict(open_hole_friction=0.25, cased_hole_friction=0.25)
    hook_load = model.run("sliding_drilling", weight_on_bit=WELL_SLIDING_WOB, **mu).hook_load
    placement = wells.place_oscillators(model, hook_load, force_amplitude=WELL_TOOL_FORCE,
                                        scan_points=20 if quick else 60, **mu)
    return HorizontalWell(chart, pd.DataFrame(rows), placement, string.length)


@dataclass
class Demo:
    """Everything the demo computed; :meth:`report` is what it prints, :meth:`write` what it writes."""

    fig7: Dict[str, ScenarioRun]
    reduction: "object"  #: pandas DataFrame (fig7_friction_reduction.csv)
    sweep: "object"  #: pandas DataFrame (friction_reduction.csv), reductions as fractions
    refit: "object"  #: pandas DataFrame (table5_refit.csv)
    paper001: Paper001
    field: FieldString
    well: HorizontalWell
    quick: bool
    elapsed: float  #: s of simulation and fitting

    def report(self) -> str:
        dry = self.fig7["fig7_dry"].runs[0].rig
        lines = [
            "frictionsim demo: paper 000, axial vibrating-sliding rig (shale on 45 steel, eqs 5-9)"
            + (" [quick]" if self.quick else ""),
            f"scenario choices of examples/axial_rig_demo.cpp: m = {dry.mass:g} kg, k_d = {dry.drive_stiffness:g} N/m, "
            f"v_d = {dry.sliding_velocity * 6e4:g} mm/min, Dahl k_t = 40 N/mm (Fig. 10); 2 s, mean over the last "
            "10 cycles",
            "",
            "1. Fig. 7 cases: mean friction over whole cycles with vibration (F_df) and without (F_sf: u0 = 0, "
            f"{NO_VIBRATION_T_END:g} s),",
            "   against Table 4's measured F_df, F_sf and the Table 5 power law mu_df = eta' (v_a/v_d)^c F_N",
            format_table(self.reduction, REDUCTION_COLUMNS),
            "",
            f"2. Friction reduction 1 - F_df/(mu F_N) vs v_d/v_a (dry: mu = 0.41, F_N = {dry.normal_force:g} N, "
            f"f = {dry.frequency:g} Hz, v_d = {dry.sliding_velocity:g} m/s;",
            "   ratios of axial_rig_demo.cpp plus Table 4 VS3's; kinematic: 5 cycles; axial: 10 cycles after "
            f"{SWEEP_SETTLE:g} s;",
            "   Table 5 only inside its fitted 160 <= v_a/v_d <= 2564; Table 4: measured 1 - F_df/F_sf)",
            format_table(self.sweep, SWEEP_COLUMNS),
            "",
            "3. " + table5_report(self.refit),
            "",
            *self.paper001.report(self.quick),
            "",
            *self.field.report(self.quick),
            "",
            *self.well.report(self.quick),
            "",
            f"simulated and fitted in {self.elapsed:.2f} s",
        ]
        return "\n".join(lines)

    def write(self, directory: Union[str, Path]) -> List[Path]:
        """Write the CSVs and PNGs into ``directory`` (which must exist)."""
        from . import plots

        directory, written = Path(directory), []
        for subdir, scenario_run in self.fig7.items():
            (directory / subdir).mkdir()
            written += scenario_run.write(directory / subdir)
        for name, frame in (("fig7_friction_reduction.csv", self.reduction), ("friction_reduction.csv", self.sweep),
                            ("table5_refit.csv", self.refit)):
            written.append(write_csv(frame, directory / name))
        figure = plots.reduction_sweep_figure(
            self.sweep, [("coulomb_closed_form", "Coulomb closed form 1 - (2/pi) asin(v_d/v_a)"),
                         ("kinematic_coulomb", "kinematic rig, Coulomb"), ("axial_coulomb", "axial rig, Coulomb"),
                         ("axial_dahl", "axial rig, Dahl k_t = 40 N/mm"), ("table5_dry", "Table 5 dry (eq 17)"),
                         ("table4_dry", "Table 4 VS3, measured 1 - F_df/F_sf")],
            title="friction reduction vs velocity ratio, dry: mu = 0.41, F_N = 90 N, f = 17 Hz "
                  "(paper 000 Fig. 7(a) rig)")
        written.append(plots.save(figure, directory / "friction_reduction.png"))
        written.append(write_fig11(directory))
        written += self.paper001.write(directory / "paper001")
        written += self.field.write(directory / "field_string")
        written += self.well.write(directory / "horizontal_well")
        return written


def write_fig11(directory: Union[str, Path]) -> Path:
    """Paper 000 Fig. 11 (Table 4 points, refit and printed Table 5 lines) as fig11_power_law.png."""
    from . import plots
    from .data import table4, table5
    from .fit import fit_power_law

    figure = plots.power_law_figure(table4(), fit_power_law(table4()), table5())
    return plots.save(figure, Path(directory) / "fig11_power_law.png")


#: The demo's parts, in the order :func:`compute` runs them (its ``progress`` callback gets each name when done).
STAGES = ("Fig. 7 cases", "friction reduction", "amplitude sweep", "Table 5 refit", "paper 001", "field string",
          "horizontal well")


def compute(quick: bool = False, progress: Optional[Callable[[str], None]] = None) -> Demo:
    """Run every simulation and fit of the demo; writes nothing. ``quick`` halves the sweep and shrinks the
    stick-slip map. ``progress(stage)`` is called as each of :data:`STAGES` is done (the command line's progress
    bar)."""
    import pandas as pd

    done = progress if progress is not None else (lambda stage: None)
    start = time.perf_counter()
    fig7 = {subdir: run(builtin_scenario(name)) for subdir, name in FIG7.items()}
    done(STAGES[0])
    reduction = pd.DataFrame([row for subdir, r in fig7.items() for row in _reduction_rows(subdir.split("_")[1], r)])
    done(STAGES[1])
    sweep = _sweep(fig7["fig7_dry"], QUICK_SWEEP_RATIOS if quick else SWEEP_RATIOS)
    done(STAGES[2])
    refit = table5_refit()
    done(STAGES[3])
    torsional = paper001(quick)
    done(STAGES[4])
    field = field_string(quick)
    done(STAGES[5])
    well = horizontal_well(quick)
    done(STAGES[6])
    return Demo(fig7, reduction, sweep, refit, torsional, field, well, quick, time.perf_counter() - start)
