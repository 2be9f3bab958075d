"""Running scenario cases and writing their outputs (tables as CSV, netCDF or parquet, the scenario text, PNG plots
and always ``metadata.json``: the provenance of every case). How a run is measured, summarised and plotted is its rig
kind's analysis (:mod:`frictionsim.scenario.analyses`)."""

from __future__ import annotations

import dataclasses
import json
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, Iterable, List, Optional, Tuple, Union

import numpy as np

from ..atomic import atomic_path, write_csv, write_text
from ..errors import InvalidParameterError
from ..simulation import simulate
from .specs import Case, Scenario
from .staging import OutputExistsError, staged_directory

__all__ = ["FORMATS", "OutputExistsError", "ScenarioRun", "budget_failure", "run", "run_case", "with_timeout"]

#: Table formats of :meth:`ScenarioRun.write`: csv (always there), netcdf and parquet (the extra frictionsim[io]).
FORMATS = ("csv", "netcdf", "parquet")
_SUFFIX = {"csv": ".csv", "netcdf": ".nc", "parquet": ".parquet"}


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
                      timeout=s.timeout, step=s.step)
    return case.kind.analysis.measure(case, rig, result, time.perf_counter() - start)


def with_timeout(case: Case, timeout: Optional[float]) -> Case:
    """``case`` with its solver.timeout [s] replaced by ``timeout`` (None: as it is), e.g. ``--timeout``'s; the
    budget holds for each of its runs (a stick-slip map's points too)."""
    if timeout is None:
        return case
    return dataclasses.replace(case, solver=dataclasses.replace(case.solver, timeout=timeout))


def budget_failure(case: Case, run: Any) -> Optional[str]:
    """Why a completed run counts as failed (None: it does not): it ran past its solver.timeout, or ended short
    of t_end. The engine reads its clock only every 20 ms, so a run shorter than that finishes whatever its budget,
    and a timeout of 1e-6 s must not pass as a success."""
    timeout = case.solver.timeout
    if timeout is not None and run.wall_time > timeout:
        return f"wall-clock budget exceeded: the run took {run.wall_time:.3g} s of timeout = {timeout:g} s"
    result = getattr(run, "result", None)
    if result is not None and not result.completed:
        return f"the run stopped at t = {result.t_reached:.9g} s of t_end = {case.solver.t_end:g} s: {result.message}"
    return None


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

    def metadata(self, *, command: Union[str, Iterable[str], None] = None) -> Dict[str, Any]:
        """The provenance record of the run (:func:`frictionsim.provenance.collect`): the rigs by case name, and per
        case (``cases``) its solver options, solver stats, start time (UTC) and wall time."""
        from .. import provenance

        record = provenance.collect(command=command, rigs={run.case.name: run.rig for run in self.runs},
                                    extra={"scenario": {"name": self.scenario.name, "title": self.scenario.title,
                                                        "source": None if self.scenario.source is None
                                                        else str(self.scenario.source)}})
        record["cases"] = []
        for run in self.runs:
            case = run.result.metadata
            record["cases"].append({"name": run.case.name, "law": run.case.friction.label,
                                    "created_utc": case.get("created_utc"),
                                    "solver_options": case.get("solver_options", {}),
                                    "solver_stats": case.get("solver_stats", {}),
                                    "wall_time_s": float(run.wall_time)})
        return record

    def write(self, directory: Union[str, Path], format: str = "csv", *,
              command: Union[str, Iterable[str], None] = None, overwrite: bool = False) -> List[Path]:
        """Write the tables and PNG plots chosen in ``output`` into ``directory`` (made if missing), and always
        ``metadata.json`` (:meth:`metadata`, with ``command`` when given). All at once: written beside it first
        and moved in when every file is done (:func:`frictionsim.scenario.staging.staged_directory`).

        ``overwrite``: replace files of those names already in ``directory``. Default False: an earlier run's
        outputs are not lost to a repeated call unless it says so; :class:`OutputExistsError` (a FileExistsError)
        names the file and nothing is written (the command line's ``--force``).

        ``format``: the tables as "csv", "netcdf" (one file per case: the run's Dataset, events and units included,
        with its derived columns; the summary over ``case``; provenance in the attributes) or "parquet" (the
        provenance in the schema's metadata). netcdf and parquet need the extra frictionsim[io]; the analysis's
        own extra tables (a stick-slip map) stay CSV.
        """
        if not isinstance(format, str) or format not in FORMATS:
            raise InvalidParameterError(f"format must be one of {', '.join(FORMATS)} (got {format!r})", "format")
        if format == "netcdf":  # the missing extra is reported before anything is written
            from ..io import netcdf_engine, require_xarray

            require_xarray()
            netcdf_engine()
        elif format == "parquet":
            from ..io import parquet_engine

            parquet_engine()
        directory = Path(directory)
        with staged_directory(directory, overwrite=overwrite) as stage:
            written = self._write_into(stage, format, command)
            return [directory / path.relative_to(stage) for path in written]

    def _write_into(self, directory: Path, format: str, command: Union[str, Iterable[str], None]) -> List[Path]:
        output, written = self.scenario.output, []
        record = self.metadata(command=command)
        frames = [(run.case.name, run.case.friction.label, run.timeseries()) for run in self.runs]
        if "timeseries" in output.tables:
            for run, (name, _, frame) in zip(self.runs, frames):
                written.append(directory / f"{name}{_SUFFIX[format]}")
                _write_timeseries(run, frame, written[-1], format)
        if "summary" in output.tables:
            written.append(directory / f"summary{_SUFFIX[format]}")
            _write_summary(self.summary(), written[-1], format, record)
            written += self.analysis.write_tables(self.runs, directory)
        if self.scenario.text is not None and all(c.rig.samples is None for c in self.scenario.cases):
            # what was run, re-runnable with `frictionsim run` (not with a relative velocity_file: it would move)
            written.append(directory / "scenario.toml")
            write_text(written[-1], self.scenario.text)
        title = self.scenario.title or self.scenario.name
        traces = [(f"{name} ({label})" if name.lower() != label.lower() else label, frame)
                  for name, label, frame in frames]
        written += self.analysis.write_plots(self.runs, traces, output.plots, directory, title=title,
                                             plot_window=output.plot_window)
        from ..provenance import write_metadata

        return written + [write_metadata(directory, record)]


def _write_timeseries(run, frame, path: Path, format: str) -> None:
    if format == "csv":
        _write_csv(frame, path)
    elif format == "parquet":
        _write_parquet(frame, path, run.result.metadata)
    else:
        from ..io import state_units, write_netcdf

        dataset = run.result.to_xarray()
        for column in frame.columns:  # the rig kind's derived columns (relative velocity, drive force, ...)
            if column not in dataset.variables and column != "t":
                unit = state_units(column, frame)
                dataset[column] = ("time", frame[column].to_numpy(), {} if unit is None else {"units": unit})
        write_netcdf(dataset, path)


def _write_summary(summary, path: Path, format: str, record: Dict[str, Any]) -> None:
    if format == "csv":
        write_csv(summary, path)
    elif format == "parquet":
        _write_parquet(summary, path, record)
    else:
        from ..io import metadata_attrs, write_netcdf

        dataset = summary.set_index("case").to_xarray()
        dataset.attrs.update(metadata_attrs(record, title="frictionsim scenario summary"))
        write_netcdf(dataset, path)


def _write_parquet(frame, path: Path, record: Dict[str, Any]) -> None:
    """``frame`` as parquet with the provenance record (JSON) in the file's key-value metadata under
    "frictionsim" (read back with ``pyarrow.parquet.read_schema(path).metadata[b"frictionsim"]``)."""
    from ..io import parquet_engine

    engine = parquet_engine()
    text = json.dumps(record, allow_nan=False)
    if engine == "pyarrow":
        import pyarrow as pa
        import pyarrow.parquet as pq

        table = pa.Table.from_pandas(frame, preserve_index=False)
        table = table.replace_schema_metadata({**(table.schema.metadata or {}), b"frictionsim": text.encode()})
        with atomic_path(path) as temporary:
            pq.write_table(table, temporary)
    else:  # fastparquet
        with atomic_path(path) as temporary:
            frame.to_parquet(temporary, engine=engine, index=False, custom_metadata={"frictionsim": text})


def _write_csv(frame, path: Path) -> None:
    """``frame.to_csv(path, index=False, float_format="%.10g")``, the same text, through numpy's C-level loop
    for purely numeric frames without NaN (3x faster: a torsional run writes 40001 rows of 17 columns)."""
    kinds = [frame[c].dtype.kind for c in frame.columns]
    values = frame.to_numpy(dtype=float) if all(k in "fiu" for k in kinds) else None
    if values is None or np.isnan(values).any():
        write_csv(frame, path)
        return
    fmt = ",".join("%.10g" if k == "f" else "%d" for k in kinds)
    with atomic_path(path) as temporary:
        np.savetxt(temporary, values, fmt=fmt, delimiter=",", header=",".join(map(str, frame.columns)), comments="",
                   encoding="utf-8")
