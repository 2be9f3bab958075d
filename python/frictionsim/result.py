"""The result of a simulation: time, named states, friction force, contact mode and the event log, as NumPy arrays.

Everything is copied once out of the C++ engine, so a Result pickles (process pools, dask) and outlives the rig.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, Iterator, List, Optional

import numpy as np

from . import _core

__all__ = ["Event", "Result"]


@dataclass(frozen=True)
class Event:
    """One switch of the hybrid system, e.g. a stick -> slip transition or a reversal of v_r."""

    time: float  #: t [s]
    name: str  #: the switching function that fired, e.g. "relative_velocity", "stick_force"
    switching_function: int  #: its index
    mode_before: int
    mode_after: int
    mode_before_name: str  #: e.g. "stick", "slip_positive"
    mode_after_name: str


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
        The event log: every located switch, in order.
    stats : dict
        Solver counters: steps, rhs_evaluations, jacobian_evaluations, guard_evaluations, error_test_failures,
        restarts, events.
    completed : bool
        False for the partial result of a failed run (see :class:`frictionsim.SimulationError`).
    warnings : list of str
        Why a completed result may be unreliable (e.g. a loose rtol); each was also issued as an
        :class:`frictionsim.AccuracyWarning`.
    t_reached : float, s
    period : float or None, s
        The rig's vibration period, the default of :meth:`mean_over_cycles`.
    """

    def __init__(self, raw: "_core.RawResult", period: Optional[float] = None) -> None:
        self.t: np.ndarray = raw.t
        self.states: np.ndarray = raw.states
        self.state_names: List[str] = list(raw.state_names)
        self.friction_force: np.ndarray = raw.friction_force
        self.mode: np.ndarray = raw.mode
        # The event log is moved out of the engine's result (its columns are copies already and go with it) and
        # turned into tuples and Event objects on first access: a run with hundreds of switches would otherwise
        # spend 2 % of a millisecond-long simulation making them (bench/compare.py measured it)
        self._event_log: Optional["_core.EventLog"] = raw.take_event_log()
        self._events: Optional[List[Event]] = None
        self.stats: Dict[str, int] = dict(raw.stats)
        self.completed: bool = bool(raw.completed)
        self.warnings: List[str] = list(raw.warnings)
        self.t_reached: float = float(raw.t_reached)
        self.period: Optional[float] = period
        for array in (self.t, self.states, self.friction_force, self.mode):
            array.setflags(write=False)  # shared views: a caller's edit must not corrupt the result

    @property
    def events(self) -> List[Event]:
        """The event log: every located switch, in order."""
        if self._events is None:  # threads racing here build equal lists: no lock needed
            self._events = [Event(*row) for row in self._event_log.rows]
        return self._events

    def __getstate__(self) -> dict:
        state = self.__dict__.copy()
        state["_events"] = self.events  # the engine's event log does not pickle: the Events do
        state["_event_log"] = None
        return state

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
        t_a, t_b, _ = _core.whole_cycle_window(float(self.t[0]), float(self.t[-1]), float(period),
                                               float(transient), int(cycles or 0))
        return _core.mean_from_integral(self.t, self["friction_impulse"], t_a, t_b)

    def to_pandas(self):
        """A pandas DataFrame indexed by t [s]: one column per state, friction_force [N] and mode."""
        import pandas as pd

        frame = pd.DataFrame(self.states.copy(), columns=self.state_names, index=pd.Index(self.t.copy(), name="t"))
        frame["friction_force"] = self.friction_force
        frame["mode"] = self.mode
        return frame
