"""Running scenario cases and writing their outputs (CSV tables, the scenario text, PNG plots). How a run is
measured, summarised and plotted is its rig kind's analysis (:mod:`frictionsim.scenario.analyses`)."""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, List, Optional, Tuple, Union

import numpy as np

from ..simulation import simulate
from .specs import Case, Scenario

__all__ = ["ScenarioRun", "run", "run_case"]


def run_case(case: Case):
    """Simulate one case and measure it as its rig kind's analysis does: the mean friction over the analysis
    window (:class:`~frictionsim.scenario.CaseRun`), or for torsional rigs the limit cycle
    (:class:`~frictionsim.scenario.LimitCycleRun`).

    Raises :class:`frictionsim.SimulationError` (``time_reached``) when the integration stops early.
    """
    rig = case.build()
    s = case.solver
    start = time.perf_counter()
    result = simulate(rig, s.t_end, method=s.method, rtol=s.rtol, atol=s.atol, output_times=case.output_times(),
                      timeout=s.timeout)
    return case.kind.analysis.measure(case, rig, result, time.perf_counter() - start)


def run(scenario: Scenario) -> "ScenarioRun":
    """Simulate every case (serially; each takes milliseconds). Writes nothing."""
    return ScenarioRun(scenario, [run_case(case) for case in scenario.cases])


@dataclass
class ScenarioRun:
    """All cases of a scenario, simulated."""

    scenario: Scenario
    runs: List[Any]  #: CaseRun, or LimitCycleRun for torsional rigs

    @property
    def analysis(self):
        """The analysis its cases share (:mod:`frictionsim.scenario.analyses`)."""
        return self.scenario.cases[0].kind.analysis

    @property
    def torsional(self) -> bool:
        """Torsional rigs (a file's cases are all torsional or none)."""
        return bool(self.runs) and self.runs[0].case.torsional

    def summary(self):
        """pandas DataFrame, one ``summary()`` row per case."""
        import pandas as pd

        return pd.DataFrame([run.summary() for run in self.runs])

    def plot_window(self) -> Optional[Tuple[float, float]]:
        """output.plot_window, else the last 3 vibration cycles of the first case [s] (torsional: None, each
        plot has its own default window)."""
        return self.analysis.plot_window(self.runs, self.scenario.output.plot_window)

    def write(self, directory: Union[str, Path]) -> List[Path]:
        """Write the CSV tables and PNG plots chosen in ``output`` into ``directory`` (which must exist)."""
        directory = Path(directory)
        output, written = self.scenario.output, []
        frames = [(run.case.name, run.case.friction.label, run.timeseries()) for run in self.runs]
        if "timeseries" in output.tables:
            for name, _, frame in frames:
                written.append(directory / f"{name}.csv")
                _write_csv(frame, written[-1])
        if "summary" in output.tables:
            written.append(directory / "summary.csv")
            self.summary().to_csv(written[-1], index=False, float_format="%.10g")
            written += self.analysis.write_tables(self.runs, directory)
        if self.scenario.text is not None and all(c.rig.samples is None for c in self.scenario.cases):
            # what was run, re-runnable with `frictionsim run` (not with a relative velocity_file: it would move)
            written.append(directory / "scenario.toml")
            written[-1].write_text(self.scenario.text, encoding="utf-8")
        title = self.scenario.title or self.scenario.name
        traces = [(f"{name} ({label})" if name.lower() != label.lower() else label, frame)
                  for name, label, frame in frames]
        return written + self.analysis.write_plots(self.runs, traces, output.plots, directory, title=title,
                                                   plot_window=output.plot_window)


def _write_csv(frame, path: Path) -> None:
    """``frame.to_csv(path, index=False, float_format="%.10g")``, the same text, through numpy's C-level loop
    for purely numeric frames without NaN (3x faster: a torsional run writes 40001 rows of 17 columns)."""
    kinds = [frame[c].dtype.kind for c in frame.columns]
    values = frame.to_numpy(dtype=float) if all(k in "fiu" for k in kinds) else None
    if values is None or np.isnan(values).any():
        frame.to_csv(path, index=False, float_format="%.10g")
        return
    fmt = ",".join("%.10g" if k == "f" else "%d" for k in kinds)
    np.savetxt(path, values, fmt=fmt, delimiter=",", header=",".join(map(str, frame.columns)), comments="",
               encoding="utf-8")
