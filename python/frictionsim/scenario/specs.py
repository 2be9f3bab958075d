"""The parsed form of a scenario: frozen dataclasses of SI values (see :mod:`frictionsim.scenario` for the
schema; a value the file gives with a unit, ``"55 rpm"``, is converted by the parser with :mod:`frictionsim.units`).
What depends on the rig type is asked of its :class:`~frictionsim.scenario.rigs.RigKind`."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Optional, Tuple

import numpy as np

from ..simulation import SOLVER_DEFAULTS
from . import rigs

__all__ = ["AnalysisSpec", "Case", "FrictionSpec", "OutputSpec", "RigSpec", "Scenario", "SolverSpec", "TABLES"]

TABLES = ("timeseries", "summary")


@dataclass(frozen=True)
class FrictionSpec:
    """A friction law: ``type`` and the constructor's keyword arguments (SI units; numbers, and for "hysteretic"
    two tuples of 6 numbers and the branch_gap string)."""

    type: str
    params: Dict[str, Any]

    @property
    def label(self) -> str:
        """The class name, e.g. "Dahl"."""
        return rigs.friction_type(self.type).label

    @property
    def mu(self) -> float:
        """The (kinetic) friction coefficient mu [-] (NaN for the torque laws "hysteretic" and "fig7")."""
        return float(self.params["mu"]) if "mu" in self.params else math.nan

    def build(self):
        """The law object, e.g. ``frictionsim.Dahl(mu=0.41, tangential_stiffness=4e4)``."""
        return rigs.friction_type(self.type).make(**self.params)


@dataclass(frozen=True)
class RigSpec:
    """A rig: ``type`` (a key of :data:`frictionsim.scenario.rigs.RIG_KINDS`: "axial" | "kinematic" | "torsional")
    and its parameters in SI units (only the keys given)."""

    type: str
    params: Dict[str, Any]
    #: (t [s], v_r [m/s]) read from a kinematic rig's velocity_file
    samples: Optional[Tuple[np.ndarray, np.ndarray]] = field(default=None, compare=False, repr=False)

    @property
    def kind(self) -> "rigs.RigKind":
        """The registered rig kind of ``type``."""
        return rigs.rig_kind(self.type)

    def with_params(self, **changes: Any) -> "RigSpec":
        """A copy with some parameters changed (validated when the case is built)."""
        return dataclasses.replace(self, params={**self.params, **changes})

    @property
    def harmonic(self) -> bool:
        """Whether the rig vibrates harmonically (axial, or kinematic without a velocity_file)."""
        return self.kind.harmonic(self)

    def build(self, friction):
        """The rig object with the given law object."""
        return self.kind.build(self, friction)


@dataclass(frozen=True)
class SolverSpec:
    """Solver settings: t_end [s], method, rtol, atol, and output_points or output_step [s]."""

    t_end: float
    method: str = "automatic"
    rtol: float = SOLVER_DEFAULTS.rtol
    atol: float = SOLVER_DEFAULTS.atol
    output_points: Optional[int] = 2001
    output_step: Optional[float] = None
    timeout: Optional[float] = None  #: wall-clock budget of each run [s]
    step: Optional[float] = None  #: a time-stepped rig's fixed step [s] (None: the engine's)

    def grid(self) -> np.ndarray:
        """The requested output times [s] over [0, t_end]."""
        if self.output_step is not None:
            times = np.arange(0.0, self.t_end, self.output_step)
            return np.append(times[times < self.t_end * (1 - 1e-12)], self.t_end)
        return np.linspace(0.0, self.t_end, int(self.output_points or 2))


@dataclass(frozen=True)
class AnalysisSpec:
    """Averaging window: transient [s], cycles, period [s]; torsional rigs: transient [s] and stick_speed
    [rad/s] of the limit cycle; drill strings: transient [s] and the stick-slip map's grid (None: see the module
    docstring)."""

    transient: Optional[float] = None
    cycles: Optional[int] = None
    period: Optional[float] = None
    stick_speed: Optional[float] = None
    #: drill strings: the stick-slip map's grid, w_set [rad/s] x weight on bit [N] (None: no map)
    surface_speeds: Optional[Tuple[float, ...]] = None
    weights_on_bit: Optional[Tuple[float, ...]] = None


@dataclass(frozen=True)
class OutputSpec:
    """What ``frictionsim run`` writes, and where (directory relative to the working directory)."""

    directory: Optional[str] = None
    tables: Tuple[str, ...] = TABLES
    plots: Tuple[str, ...] = rigs.PLOTS
    plot_window: Optional[Tuple[float, float]] = None


@dataclass(frozen=True)
class Case:
    """One rig with one friction law, its solver settings and averaging window."""

    name: str
    rig: RigSpec
    friction: FrictionSpec
    solver: SolverSpec
    analysis: AnalysisSpec = AnalysisSpec()
    lubricant: Optional[str] = None
    description: str = ""

    def build(self):
        """The rig object (with its law)."""
        return self.rig.build(self.friction.build())

    @property
    def kind(self) -> "rigs.RigKind":
        """The rig's kind: its analysis, time series, summary and plots."""
        return self.rig.kind

    @property
    def torsional(self) -> bool:
        """A torsional rig: analysed by its limit cycle (:class:`frictionsim.scenario.analyses.LimitCycle`)."""
        return self.kind.torsional

    @property
    def period(self) -> Optional[float]:
        """Averaging period [s]: analysis.period, else the rig's vibration period 1/f."""
        if self.analysis.period is not None:
            return self.analysis.period
        return self.kind.vibration_period(self.rig)

    def window(self) -> Tuple[float, float, int]:
        """(t_a, t_b, cycles): the whole cycles [s] the mean friction is taken over (not for torsional rigs,
        whose cycles are found in the result: :class:`frictionsim.scenario.analyses.LimitCycleRun`)."""
        return self.kind.analysis.window(self)

    def output_times(self) -> np.ndarray:
        """The solver grid plus the window ends [s], so the cycle mean needs no interpolation (torsional: the
        grid)."""
        return self.kind.analysis.output_times(self)


@dataclass(frozen=True)
class Scenario:
    """A parsed scenario file: its cases and outputs. ``name`` is the file stem."""

    name: str
    cases: Tuple[Case, ...]
    output: OutputSpec = OutputSpec()
    title: str = ""
    description: str = ""
    source: Optional[Path] = None
    #: the TOML text it was parsed from (copied into the output directory as scenario.toml)
    text: Optional[str] = field(default=None, compare=False, repr=False)
