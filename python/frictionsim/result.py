"""The result of a simulation: time, named states, friction force, contact mode and the event log, as NumPy arrays.

Everything is copied once out of the C++ engine, so a Result pickles (process pools, dask) and outlives the rig.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any, Dict, Iterator, List, Optional

import numpy as np

from ._core import EventLog, mean_from_integral, RawResult, whole_cycle_window
from .outputs import output_units

__all__ = ["Event", "Result"]


@dataclass(frozen=True, eq=False)
class Event:
    """One switch of the hybrid system, e.g. a stick -> slip transition or a reversal of v_r; or one crossing of
    a stop condition (``stop_condition >= 0``, in :attr:`Result.stop_events`)."""

    time: float  #: t [s]
    name: str  #: the switching function that fired, e.g. "relative_velocity", "stick_force"
    switching_function: int  #: its index
    mode_before: int
    mode_after: int
    mode_before_name: str  #: e.g. "stick", "slip_positive"
    mode_after_name: str
    #: The state just before the switch and just after it (a switch may project it, e.g. a speed set to exactly
    #: zero on entering stick); None when the run was made with ``record_event_states=False``.
    state_before: Optional[np.ndarray] = None
    state_after: Optional[np.ndarray] = None
    stop_condition: int = -1  #: index of the stop condition that crossed, -1 for a switch
    direction: int = 0  #: a stop condition's crossing: -1 falling, +1 rising (0: a mode condition)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Event):
            return NotImplemented
        return all(_same(getattr(self, f.name), getattr(other, f.name)) for f in fields(self))

    __hash__ = None  # type: ignore[assignment]  # holds arrays


def _same(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return a is not None and b is not None and np.array_equal(a, b)
    return a == b


class Result:
    """Output of :func:`frictionsim.simulate`.

    Attributes
    ----------
    t : ndarray, s
        Output times (every internal step, or the requested ``output_times``).
    states : ndarray, shape (len(t), len(state_names))
        State trajectories in SI units; also by name: ``result["velocity"]`` or ``result.velocity``.
    state_names : list of str
    friction_force : ndarray, N
        Friction force on the body (positive opposing positive relative velocity).
    mode : ndarray of int
        Contact mode at each row: -1 slip negative, 0 stick (or smooth), +1 slip positive.
    events : list of Event
        The event log: every located switch, in order, with the state before and after it.
    stop_events : list of Event
        The crossings of the run's stop conditions (``simulate(events=...)``), in time order.
    t_events, y_events : list of ndarray
        SciPy's layout of ``stop_events``: per stop condition, the times [s] and the states (one row each).
    stats : dict
        Solver counters: steps, rhs_evaluations, jacobian_evaluations, guard_evaluations, error_test_failures,
        restarts, events.
    completed : bool
        False for the partial result of a failed run (see :class:`frictionsim.SimulationError`).
    status : int
        SciPy's: 0 the run reached t_end, 1 a terminal stop condition ended it, -1 it failed.
    message : str
        What ``status`` means for this run.
    warnings : list of str
        Why a completed result may be unreliable (e.g. a loose rtol); each was also issued as an
        :class:`frictionsim.AccuracyWarning`.
    t_reached : float, s
    period : float or None, s
        The rig's vibration period, the default of :meth:`mean_over_cycles`.
    units : dict
        Column -> SI unit, as the rig and its law declare them (:func:`frictionsim.outputs.output_units`).
    metadata : dict
        Provenance of the run (:func:`frictionsim.provenance.collect`): version, rig and law ``repr``, solver
        options and stats, time, platform; the ``attrs`` of :meth:`to_netcdf`.
    """

    def __init__(self, raw: "RawResult", period: Optional[float] = None) -> None:
        self.t: np.ndarray = raw.t
        self.states: np.ndarray = raw.states
        self.state_names: List[str] = list(raw.state_names)
        self.friction_force: np.ndarray = raw.friction_force
        self.mode: np.ndarray = raw.mode
        # The event log is moved out of the engine's result (its columns are copies already and go with it) and
        # turned into tuples and Event objects on first access: a run with hundreds of switches would otherwise
        # spend 2 % of a millisecond-long simulation making them (bench/compare.py measured it)
        self._event_log: Optional["EventLog"] = raw.take_event_log()
        self._events: Optional[List[Event]] = None
        self._stop_log: Optional["EventLog"] = raw.take_stop_events()
        self._stop_events: Optional[List[Event]] = None
        self.stats: Dict[str, int] = dict(raw.stats)
        self.completed: bool = bool(raw.completed)
        self.status: int = int(raw.status)
        self.message: str = str(raw.message)
        #: How many stop conditions the run had (so that t_events has one entry each, crossed or not).
        self.stop_condition_count: int = 0
        self.warnings: List[str] = list(raw.warnings)
        self.t_reached: float = float(raw.t_reached)
        self.period: Optional[float] = period
        # (rig, options, POSIX time, stop conditions) of the run, set by simulate(); the provenance record is made
        # from them on first use (tens of microseconds: too dear for every run of a sweep). Rigs are immutable, so
        # the record made later is the run's.
        self._run: Optional[tuple] = None
        self._metadata: Optional[Dict[str, Any]] = None
        self._units: Optional[Dict[str, str]] = None
        for array in (self.t, self.states, self.friction_force, self.mode):
            array.setflags(write=False)  # shared views: a caller's edit must not corrupt the result

    @property
    def events(self) -> List[Event]:
        """The event log: every located switch, in order."""
        if self._events is None:  # threads racing here build equal lists: no lock needed
            self._events = [Event(*row) for row in self._event_log.rows]
        return self._events

    @property
    def stop_events(self) -> List[Event]:
        """The crossings of the run's stop conditions, in time order."""
        if self._stop_events is None:
            self._stop_events = [Event(*row) for row in self._stop_log.rows]
        return self._stop_events

    def __getstate__(self) -> dict:
        state = self.__dict__.copy()
        state["_events"] = self.events  # the engine's event log does not pickle: the Events do
        state["_event_log"] = None
        state["_stop_events"] = self.stop_events
        state["_stop_log"] = None
        state["_metadata"] = self.metadata  # the rig need not pickle (a CallableLaw's function): its record does
        state["_units"] = self.units
        state["_run"] = None
        return state

    def __setstate__(self, state: dict) -> None:
        state.setdefault("_run", None)  # a Result pickled before provenance existed
        state.setdefault("_metadata", None)
        state.setdefault("_units", {})
        self.__dict__.update(state)

    # ------------------------------------------------------------------ provenance and labelled outputs
    @property
    def metadata(self) -> Dict[str, Any]:
        """The provenance record of the run (:func:`frictionsim.provenance.collect`), JSON-safe; its
        ``created_utc`` is when the run started (``error.partial`` of a failed run records it too; a Result made
        otherwise records no rig or options)."""
        if self._metadata is None:
            from . import provenance

            rig, options, started, conditions = self._run if self._run is not None else (None, None, None, ())
            if options is not None:  # the conditions as given: SolverOptions.stop_conditions does not read back
                options = dict(provenance.solver_options_record(options),
                               stop_conditions=[repr(condition) for condition in conditions])
            record = provenance.collect(rigs=() if rig is None else [rig], solver_options=options, stats=self.stats)
            if started is not None:
                record["created_utc"] = provenance.utc_time(started)
            self._metadata = record
        return self._metadata

    @metadata.setter
    def metadata(self, record: Dict[str, Any]) -> None:
        self._metadata = dict(record)

    @property
    def units(self) -> Dict[str, str]:
        """Column (``t``, a state, ``friction_force``) -> its SI unit, as the run's rig and its law declare them
        (:func:`frictionsim.outputs.output_units`); {} for a Result made without a rig."""
        if self._units is None:
            if self._run is None:
                return {}
            self._units = output_units(self._run[0])
        return self._units

    def to_xarray(self):
        """The result as a labelled xarray Dataset (:func:`frictionsim.io.result_dataset`).

        Returns
        -------
        xarray.Dataset
            The states, friction force and mode over ``time`` [s] with their units, the event log over ``event``,
            the stop conditions' crossings over ``stop_event``; ``attrs`` hold the provenance (:attr:`metadata`).

        Raises
        ------
        ImportError
            Without xarray (``pip install 'frictionsim[io]'``).
        """
        from .io import result_dataset

        return result_dataset(self)

    def to_netcdf(self, path, *, engine: Optional[str] = None):
        """Write :meth:`to_xarray` as a netCDF file, its provenance in the global attributes.

        Parameters
        ----------
        path : str or pathlib.Path
            The file to write.
        engine : {"h5netcdf", "netcdf4", "scipy"}, optional
            The writer: the netCDF-4 ones (default the first installed), or "scipy" for netCDF-3.

        Returns
        -------
        pathlib.Path
            ``path``; read it back with :func:`frictionsim.io.open_dataset`.

        Raises
        ------
        ImportError
            Without xarray or the writer (``pip install 'frictionsim[io]'``).
        InvalidParameterError (a ValueError)
            An unknown ``engine``.
        """
        from .io import write_netcdf

        return write_netcdf(self.to_xarray(), path, engine)

    def plot(self, columns=None, ax=None, **kwargs):
        """Columns against time t [s] (:func:`frictionsim.plots.time_series_axes`).

        Parameters
        ----------
        columns : str or sequence of str, optional
            Names of states, "friction_force" or "mode" (default the friction force).
        ax : matplotlib.axes.Axes, optional
            Drawn into; default a new figure (not registered with pyplot).
        **kwargs
            Style keywords for matplotlib's ``plot`` (color, linewidth, ...).

        Returns
        -------
        matplotlib.axes.Axes
            The Axes drawn on.
        """
        from .plots import time_series_axes

        return time_series_axes(self, columns, ax=ax, **kwargs)

    # ------------------------------------------------------------------ SciPy's OdeResult names
    @property
    def y(self) -> np.ndarray:
        """The states in SciPy's layout, shape (len(state_names), len(t)): ``y[i]`` is state i over time."""
        return self.states.T

    @property
    def success(self) -> bool:
        """True when the run reached t_end or a terminal stop condition (SciPy: status >= 0)."""
        return self.status >= 0

    @property
    def nfev(self) -> int:
        """Right-hand-side evaluations."""
        return int(self.stats["rhs_evaluations"])

    @property
    def njev(self) -> int:
        """Jacobian evaluations (implicit methods)."""
        return int(self.stats["jacobian_evaluations"])

    @property
    def t_events(self) -> List[np.ndarray]:
        """Per stop condition, the times [s] of its crossings (SciPy's t_events)."""
        return [np.array([e.time for e in self.stop_events if e.stop_condition == k], dtype=float)
                for k in range(self._condition_count())]

    @property
    def y_events(self) -> List[np.ndarray]:
        """Per stop condition, the state at each of its crossings, shape (crossings, states) (SciPy's y_events);
        empty when the run was made with ``record_event_states=False``."""
        out = []
        for k in range(self._condition_count()):
            rows = [e.state_after for e in self.stop_events if e.stop_condition == k and e.state_after is not None]
            out.append(np.array(rows, dtype=float).reshape(len(rows), len(self.state_names)))
        return out

    def _condition_count(self) -> int:
        crossed = max((e.stop_condition for e in self.stop_events), default=-1) + 1
        return max(self.stop_condition_count, crossed)

    def events_frame(self, stop_events: bool = False):
        """The event log (or the stop conditions' crossings) as a pandas DataFrame: one row per event with its time,
        name, modes, and the state before and after it (columns ``<state>_before``, ``<state>_after``)."""
        import pandas as pd

        events = self.stop_events if stop_events else self.events
        frame = pd.DataFrame({
            "time": [e.time for e in events], "name": [e.name for e in events],
            "switching_function": [e.switching_function for e in events],
            "mode_before": [e.mode_before_name for e in events], "mode_after": [e.mode_after_name for e in events],
        })
        for side in ("before", "after"):
            for i, state in enumerate(self.state_names):
                frame[f"{state}_{side}"] = [np.nan if getattr(e, "state_" + side) is None
                                            else float(getattr(e, "state_" + side)[i]) for e in events]
        return frame

    # ------------------------------------------------------------------ named access
    def __getitem__(self, name: str) -> np.ndarray:
        """A state column by name, or "t", "friction_force", "mode"."""
        if name in ("t", "friction_force", "mode"):
            return getattr(self, name)
        try:
            return self.states[:, self.state_names.index(name)]
        except ValueError:
            raise KeyError(f"Result has no state {name!r}; states: {', '.join(self.state_names)}") from None

    def __getattr__(self, name: str) -> np.ndarray:
        # only reached for names that are not attributes: the state columns
        names = self.__dict__.get("state_names", ())
        if name in names:
            return self.states[:, names.index(name)]
        raise AttributeError(f"Result has no attribute or state {name!r}")

    def __contains__(self, name: str) -> bool:
        return name in self.state_names

    def __iter__(self) -> Iterator[str]:
        return iter(self.state_names)

    def __len__(self) -> int:
        return len(self.t)

    def __repr__(self) -> str:
        status = "completed" if self.completed else f"stopped at t = {self.t_reached:g} s"
        span = f"t = [{self.t[0]:g}, {self.t[-1]:g}] s" if len(self.t) else "no rows"  # a run that failed at once
        return f"Result({len(self.t)} rows, {span}, states = {self.state_names}, {len(self.events)} events, {status})"

    # ------------------------------------------------------------------ analysis
    def mean_over_cycles(self, period: Optional[float] = None, transient: float = 0.0,
                         cycles: Optional[int] = None) -> float:
        """Mean friction force [N] over whole cycles after ``transient`` seconds.

        This is F_df of paper 000 (Table 4, "the average sliding friction force in a vibration cycle"). It is
        computed from the solver-integrated friction impulse int F dt, so it is exact to solver tolerance even
        though the friction force jumps at every reversal.

        Parameters
        ----------
        period : float, s, optional
            Cycle length; default the rig's vibration period.
        transient : float, s
            Time skipped at the start of the record.
        cycles : int, optional
            Number of whole cycles; default as many as fit after the transient.
        """
        if period is None:
            period = self.period
        if period is None:
            raise ValueError("period: this rig has no vibration period; pass period= (s)")
        if cycles is not None and (isinstance(cycles, bool) or not isinstance(cycles, (int, np.integer))
                                   or cycles < 1):
            raise ValueError(f"cycles must be None or an integer >= 1 (got {cycles!r})")
        t_a, t_b, _ = whole_cycle_window(float(self.t[0]), float(self.t[-1]), float(period),
                                               float(transient), int(cycles or 0))
        return mean_from_integral(self.t, self["friction_impulse"], t_a, t_b)

    def to_pandas(self):
        """A pandas DataFrame indexed by t [s]: one column per state, friction_force [N] and mode."""
        import pandas as pd

        frame = pd.DataFrame(self.states.copy(), columns=self.state_names, index=pd.Index(self.t.copy(), name="t"))
        frame["friction_force"] = self.friction_force
        frame["mode"] = self.mode
        return frame
