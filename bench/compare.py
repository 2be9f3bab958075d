#!/usr/bin/env python3
"""frictionsim against the tools users would otherwise pick, at equal accuracy (issue 5): one run, one table.

Two scenarios, each solved by every tool available here:

  A. axial_dahl    paper 000's axial vibrating-sliding rig with Dahl friction, 2 s from rest; the answer is the
                   mean friction force over the last 10 whole vibration cycles,
                   F_df = (I(2) - I(2 - 10/f)) / (10/f), I the friction impulse.
  B. spring_block  Coulomb stick-slip of a spring-pulled block, 20 s from rest (stuck), with events; the answers
                   are x(20) and the mean friction force I(20) / 20.

Tools: frictionsim's C++ Google Benchmark binary (build/bench/integrators), frictionsim from Python
(fs.simulate), SciPy solve_ivp with a Python right-hand side (RK45, DOP853, LSODA, BDF, Radau; stick-slip by
terminal events and a restart loop), scikit-sundae (CVODE with a Python right-hand side and its root-finding
events), sundials4py where it installs, and the hand-written C program on CVODE
(build/bench/reference/cvode_reference, bench/reference/).

Equal accuracy: a converged reference is computed first at very tight tolerance (frictionsim Dormand-Prince at
rtol 1e-13, cross-checked with SciPy DOP853 at rtol 1e-12). Every tool then runs on the tolerance grid
rtol = 10^(-K/10), K = 40, 45, ..., 130 (atol = 1e-4 rtol), from loose to tight, and is timed at the loosest K
whose answers are all within --accuracy (default 1e-5) relative of the reference, and so is the next tighter
grid point (a chance zero crossing of the error does not count). So speed is never bought with a wrong answer.

C. A sweep of 1000 axial-rig simulations from Python (fs.sweep on a ThreadPoolExecutor) on 1 and 2 threads.

Prints the machine, the date, the Markdown tables and the issue's targets (met / not met, with the measured
ratio: never asserted), and writes compare.md and compare.json (every scan point and timing) to --out
(default out/bench). scripts/bench sets everything up and runs this file; --quick is a fast smoke run.
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import datetime as _dt
import gc
import json
import math
import os
import platform
import subprocess
import sys
import time
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

import frictionsim as fs

REPO = Path(__file__).resolve().parents[1]

#: The tolerance grid: rtol = 10^(-K/10), atol = ATOL_FACTOR * rtol.
GRID = tuple(range(40, 135, 5))
ATOL_FACTOR = 1e-4


def rtol_of(k: int) -> float:
    return 10.0 ** (-k / 10.0)


# =============================================================================================== the scenarios
@dataclass(frozen=True)
class AxialDahl:
    """Scenario A (SI): paper 000's rig, fs.AxialVibrationRig(friction=fs.Dahl(0.41, 4e4)) with its defaults."""

    key = "axial_dahl"
    title = "A. Axial rig with Dahl friction: 2 s, mean friction over the last 10 cycles"
    quantities = ("mean_friction",)
    cpp_family = "axial_dahl_tolerance"
    cpp_methods = ("dormand_prince", "cvode_bdf", "cvode_adams")

    m = 0.2          # kg
    k_d = 2e4        # N/m
    mu = 0.41
    F_N = 90.0       # N
    k_t = 4e4        # N/m
    u0 = 5e-3        # m
    f = 17.0         # Hz
    v_d = 1e-3       # m/s
    t_end = 2.0      # s
    cycles = 10

    @property
    def window_start(self) -> float:
        return self.t_end - self.cycles / self.f

    def rig(self):
        return fs.AxialVibrationRig(friction=fs.Dahl(self.mu, self.k_t))

    def frictionsim(self, method: str, rtol: float, atol: float, rig=None) -> Dict[str, Any]:
        r = fs.simulate(self.rig() if rig is None else rig, self.t_end, method=method, rtol=rtol, atol=atol,
                        output_times=[self.window_start, self.t_end])
        impulse = r["friction_impulse"]
        return {"mean_friction": (impulse[-1] - impulse[0]) / (self.t_end - self.window_start), "stats": r.stats,
                "events": r.stats["events"]}


@dataclass(frozen=True)
class SpringBlock:
    """Scenario B (SI): Coulomb stick-slip; fs.AxialVibrationRig with amplitude 0 is the spring block."""

    key = "spring_block"
    title = "B. Spring-block Coulomb stick-slip with events: 20 s, x(20) and mean friction"
    quantities = ("mean_friction", "final_position")
    cpp_family = "coulomb_stick_slip_tolerance"
    cpp_methods = ("dormand_prince", "cvode_bdf")

    m = 0.5          # kg
    k = 200.0        # N/m
    v_p = 0.05       # m/s, pull velocity of the spring's end
    g = 9.81         # m/s^2
    mu_k = 0.4
    mu_s = 0.6
    t_end = 20.0     # s

    @property
    def N(self) -> float:
        return self.m * self.g

    def rig(self):
        return fs.AxialVibrationRig(friction=fs.Coulomb(self.mu_k, self.mu_s), mass=self.m, drive_stiffness=self.k,
                                    sliding_velocity=self.v_p, amplitude=0.0, normal_force=self.N)

    def frictionsim(self, method: str, rtol: float, atol: float, rig=None) -> Dict[str, Any]:
        r = fs.simulate(self.rig() if rig is None else rig, self.t_end, method=method, rtol=rtol, atol=atol,
                        output_times=[self.t_end])
        return {"final_position": float(r["position"][-1]),
                "mean_friction": float(r["friction_impulse"][-1]) / self.t_end, "stats": r.stats,
                "events": r.stats["events"]}


A = AxialDahl()
B = SpringBlock()
SCENARIOS = {A.key: A, B.key: B}
QUANTITY_LABEL = {"mean_friction": "mean friction [N]", "final_position": "x(20) [m]"}


# =============================================================================================== the peers' equations
# Written as a user of each tool would: plain Python floats, one function per mode, the tool's own events.

_W = 2.0 * math.pi * A.f
_C = A.k_t / (A.mu * A.F_N)
_cos = math.cos


def axial_dahl_rhs(t, y):
    """SciPy form: x' = v, m v' = k_d (v_d t - x) - k_t z, z' = v_r (1 - c sgn(v_r) z), I' = k_t z."""
    x, v, z, _ = y.tolist()
    v_r = v - A.u0 * _W * _cos(_W * t)
    force = A.k_t * z
    return [v, (A.k_d * (A.v_d * t - x) - force) / A.m, v_r - _C * abs(v_r) * z, force]


def axial_dahl_rhs_inplace(t, y, yp):
    """scikit-sundae form (fills yp)."""
    x, v, z, _ = y.tolist()
    v_r = v - A.u0 * _W * _cos(_W * t)
    force = A.k_t * z
    yp[0] = v
    yp[1] = (A.k_d * (A.v_d * t - x) - force) / A.m
    yp[2] = v_r - _C * abs(v_r) * z
    yp[3] = force


# Spring block, states (x, v, I); mode 0 stick, +1 / -1 slip in +x / -x. Leine's switch model:
#   slip -> at v = 0: stick if |F_s| <= mu_s N, else slip in the direction of F_s (v := 0 either way);
#   stick -> slip in the direction of F_s when |F_s| exceeds mu_s N.
_SB_FK = B.mu_k * B.N   # kinetic friction force, N
_SB_FS = B.mu_s * B.N   # static friction limit, N


def _sb_rhs_stick(t, y):
    return [0.0, 0.0, B.k * (B.v_p * t - y[0])]


def _sb_rhs_plus(t, y):
    x, v, _ = y.tolist()
    return [v, (B.k * (B.v_p * t - x) - _SB_FK) / B.m, _SB_FK]


def _sb_rhs_minus(t, y):
    x, v, _ = y.tolist()
    return [v, (B.k * (B.v_p * t - x) + _SB_FK) / B.m, -_SB_FK]


def _sb_break_plus(t, y):
    return B.k * (B.v_p * t - y[0]) - _SB_FS


def _sb_break_minus(t, y):
    return -B.k * (B.v_p * t - y[0]) - _SB_FS


for _fn, _direction in ((_sb_break_plus, 1), (_sb_break_minus, 1)):
    _fn.terminal, _fn.direction = True, _direction
_sb_v_falling = lambda t, y: y[1]  # noqa: E731 - solve_ivp reads attributes off the callable
_sb_v_rising = lambda t, y: y[1]  # noqa: E731
_sb_v_falling.terminal, _sb_v_falling.direction = True, -1
_sb_v_rising.terminal, _sb_v_rising.direction = True, 1

_SB_SCIPY = {0: (_sb_rhs_stick, [_sb_break_plus, _sb_break_minus]),
             1: (_sb_rhs_plus, [_sb_v_falling]),
             -1: (_sb_rhs_minus, [_sb_v_rising])}


def spring_block_switch(mode: int, t: float, y: np.ndarray) -> int:
    """The mode after an event in `mode` at (t, y); sets v = 0 exactly."""
    y[1] = 0.0
    spring = B.k * (B.v_p * t - y[0])
    if mode != 0 and abs(spring) <= _SB_FS:
        return 0
    return 1 if spring > 0 else -1


MAX_SEGMENTS = 100_000  # a peer's restart loop stops there (chattering)


# =============================================================================================== outcomes
@dataclass
class Outcome:
    """One simulation of one tool at one grid point."""

    k: int
    values: Dict[str, float] = field(default_factory=dict)
    seconds: Optional[float] = None       # one run (the scan), not the timing
    steps: Optional[int] = None
    rhs: Optional[int] = None
    jac: Optional[int] = None
    events: Optional[int] = None
    error: Optional[str] = None
    rel_errors: Dict[str, float] = field(default_factory=dict)
    ok: bool = False

    def as_dict(self) -> Dict[str, Any]:
        return {"K": self.k, "rtol": rtol_of(self.k), "atol": ATOL_FACTOR * rtol_of(self.k), **self.values,
                "rel_errors": self.rel_errors, "ok": self.ok, "seconds_one_run": self.seconds, "steps": self.steps,
                "rhs_evaluations": self.rhs, "jacobian_evaluations": self.jac, "events": self.events,
                "error": self.error}


@dataclass
class Timing:
    seconds: float                  # the best time per simulation
    samples: List[float]            # time per simulation of each repetition
    runs_per_sample: int
    how: str

    def as_dict(self) -> Dict[str, Any]:
        return {"seconds": self.seconds, "samples": self.samples, "runs_per_sample": self.runs_per_sample,
                "how": self.how}


@dataclass
class Settings:
    accuracy: float = 1e-5
    repeats: int = 5                # timing repetitions (each a batch of runs)
    min_batch: float = 0.2          # s: a repetition runs the simulation at least this long
    max_timing_seconds: float = 20.0  # s: a tool's timing stops adding repetitions past this
    max_run_seconds: float = 30.0   # s: the tolerance scan of a tool stops when one run takes longer
    cpp_min_time: float = 0.2       # s: Google Benchmark --benchmark_min_time of the timing run
    cpp_scan_min_time: float = 0.01
    reference_k: int = 130
    crosscheck_rtol: float = 1e-12
    crosscheck_atol: float = 1e-14
    scipy_methods: Tuple[str, ...] = ("RK45", "DOP853", "LSODA", "BDF", "Radau")
    sweep_shape: Tuple[int, int] = (40, 25)
    sweep_repeats: int = 2
    paired_rounds: int = 6          # Python / C++: rounds of one C++ batch then one Python batch
    grid: Tuple[int, ...] = GRID


def best_time(fn: Callable[[], Any], settings: Settings, first: Optional[float] = None) -> Timing:
    """Best time per call of fn over repetitions, each a batch of calls lasting >= settings.min_batch (GC off)."""
    if first is None:
        t0 = time.perf_counter()
        fn()  # warm-up and calibration
        first = time.perf_counter() - t0
    first = max(first, 1e-7)
    runs = max(1, math.ceil(settings.min_batch / first))
    repeats = settings.repeats
    if first * runs * repeats > settings.max_timing_seconds:
        repeats = max(1, min(repeats, int(settings.max_timing_seconds / (first * runs))))
    samples = []
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        for _ in range(repeats):
            t0 = time.perf_counter()
            for _ in range(runs):
                fn()
            samples.append((time.perf_counter() - t0) / runs)
    finally:
        if was_enabled:
            gc.enable()
    return Timing(min(samples), samples, runs,
                  f"best of {repeats} repetitions of {runs} run{'s' if runs > 1 else ''} (time.perf_counter)")


# =============================================================================================== the tools
class Tool:
    """One tool / method on one scenario."""

    family = ""
    method = ""
    note = ""

    def __init__(self, scenario) -> None:
        self.scenario = scenario

    @property
    def label(self) -> str:
        return f"{self.family} / {self.method}" if self.method else self.family

    def unavailable(self) -> Optional[str]:
        return None

    def run(self, k: int) -> Outcome:
        raise NotImplementedError

    def time(self, k: int, outcome: Outcome, settings: Settings) -> Timing:
        raise NotImplementedError

    def max_k(self) -> int:
        return GRID[-1]


# ---------------------------------------------------------------------------------------------- frictionsim C++
class CppBenchmark:
    """build/bench/integrators: one scan run over every grid point, then one timing run per chosen point."""

    def __init__(self, binary: Path, settings: Settings) -> None:
        self.binary = binary
        self.settings = settings
        self.scans: Dict[str, Dict[Tuple[str, int], Outcome]] = {}
        self.raw: Dict[str, Any] = {}

    def available(self) -> Optional[str]:
        if not self.binary.is_file() or not os.access(self.binary, os.X_OK):
            return f"{self.binary} is missing (scripts/bench builds it: target bench_integrators)"
        return None

    def _call(self, regex: str, extra: Sequence[str]) -> Dict[str, Any]:
        command = [str(self.binary), f"--benchmark_filter={regex}", "--benchmark_format=json", *extra]
        done = subprocess.run(command, capture_output=True, text=True, check=False)
        if done.returncode != 0:
            raise RuntimeError(f"{' '.join(command)} failed ({done.returncode}): {done.stderr.strip()[-500:]}")
        return json.loads(done.stdout)  # Google Benchmark writes NaN for undefined counters: json accepts it

    @staticmethod
    def _seconds(row: Dict[str, Any]) -> float:
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[row.get("time_unit", "ns")]
        return float(row["real_time"]) * scale

    def scan(self, scenario) -> Dict[Tuple[str, int], Outcome]:
        if scenario.key not in self.scans:
            methods = "|".join(scenario.cpp_methods)
            ks = "|".join(str(k) for k in self.settings.grid)
            data = self._call(f"^{scenario.cpp_family}/({methods})/({ks})$",
                              [f"--benchmark_min_time={self.settings.cpp_scan_min_time}"])
            self.raw[f"{scenario.key}_scan"] = data
            out: Dict[Tuple[str, int], Outcome] = {}
            for row in data["benchmarks"]:
                if row.get("run_type", "iteration") != "iteration":
                    continue
                _, method, k = row["name"].split("/")
                if "error_occurred" in row and row["error_occurred"]:
                    out[(method, int(k))] = Outcome(int(k), error=row.get("error_message", "error"))
                    continue
                values = {"mean_friction": float(row["value"])} if scenario is A else {
                    "final_position": float(row["value"]), "mean_friction": float(row["mean_friction"])}
                out[(method, int(k))] = Outcome(int(k), values, seconds=self._seconds(row), steps=int(row["steps"]),
                                                rhs=int(row["rhs"]), jac=int(row["jac"]), events=int(row["events"]))
            self.scans[scenario.key] = out
        return self.scans[scenario.key]

    def time(self, scenario, method: str, k: int, repeats: Optional[int] = None) -> Timing:
        repeats = repeats or self.settings.repeats
        data = self._call(f"^{scenario.cpp_family}/{method}/{k}$",
                          [f"--benchmark_min_time={self.settings.cpp_min_time}",
                           f"--benchmark_repetitions={repeats}", "--benchmark_report_aggregates_only=false"])
        self.raw[f"{scenario.key}_{method}_{k}_timing"] = data
        rows = [r for r in data["benchmarks"] if r.get("run_type", "iteration") == "iteration"]
        samples = [self._seconds(r) for r in rows]
        iterations = int(min(r["iterations"] for r in rows))
        return Timing(min(samples), samples, iterations,
                      f"Google Benchmark: best of {len(rows)} repetitions (each the mean of >= {iterations} "
                      "iterations, real time)")


class FrictionsimCpp(Tool):
    family = "frictionsim C++"

    def __init__(self, scenario, method: str, bench: CppBenchmark) -> None:
        super().__init__(scenario)
        self.method = method
        self.bench = bench

    def unavailable(self) -> Optional[str]:
        return self.bench.available()

    def max_k(self) -> int:
        ks = [k for (m, k) in self.bench.scan(self.scenario) if m == self.method]
        return max(ks) if ks else GRID[-1]

    def run(self, k: int) -> Outcome:
        found = self.bench.scan(self.scenario).get((self.method, k))
        if found is None:
            return Outcome(k, error="no such benchmark at this K")
        return Outcome(found.k, dict(found.values), found.seconds, found.steps, found.rhs, found.jac, found.events,
                       found.error)

    def time(self, k: int, outcome: Outcome, settings: Settings) -> Timing:
        return self.bench.time(self.scenario, self.method, k, repeats=settings.repeats)


# ---------------------------------------------------------------------------------------------- frictionsim Python
class FrictionsimPython(Tool):
    family = "frictionsim Python"

    def __init__(self, scenario, method: str) -> None:
        super().__init__(scenario)
        self.method = method

    def _simulate(self, k: int) -> Dict[str, Any]:
        # the rig is built once, outside the timing, as the C++ benchmark does
        if not hasattr(self, "_rig"):
            self._rig = self.scenario.rig()
        return self.scenario.frictionsim(self.method, rtol_of(k), ATOL_FACTOR * rtol_of(k), self._rig)

    def run(self, k: int) -> Outcome:
        t0 = time.perf_counter()
        r = self._simulate(k)
        seconds = time.perf_counter() - t0
        stats = r["stats"]
        return Outcome(k, {q: float(r[q]) for q in self.scenario.quantities}, seconds, stats["steps"],
                       stats["rhs_evaluations"], stats["jacobian_evaluations"], r["events"])

    def time(self, k: int, outcome: Outcome, settings: Settings) -> Timing:
        return best_time(lambda: self._simulate(k), settings)


# ---------------------------------------------------------------------------------------------- SciPy
class PythonPeer(Tool):
    """A peer driven from Python through ``_solve(rtol, atol, count_steps=False)``, which returns the scenario's
    quantities with nfev, njev, events and steps (None where the tool reports none)."""

    def run(self, k: int) -> Outcome:
        t0 = time.perf_counter()
        r = self._solve(rtol_of(k), ATOL_FACTOR * rtol_of(k))
        seconds = time.perf_counter() - t0
        return Outcome(k, {q: r[q] for q in self.scenario.quantities}, seconds, r.get("steps"), r["nfev"], r["njev"],
                       r["events"])

    def complete(self, outcome: Outcome) -> None:
        """Steps of the axial run, where the timed run does not report them: the same solve, counting steps."""
        if self.scenario is A and outcome.steps is None:
            rtol = rtol_of(outcome.k)
            outcome.steps = self._solve(rtol, ATOL_FACTOR * rtol, count_steps=True)["steps"]

    def time(self, k: int, outcome: Outcome, settings: Settings) -> Timing:
        rtol, atol = rtol_of(k), ATOL_FACTOR * rtol_of(k)
        return best_time(lambda: self._solve(rtol, atol), settings, first=outcome.seconds)


class Scipy(PythonPeer):
    family = "SciPy solve_ivp"

    def __init__(self, scenario, method: str) -> None:
        super().__init__(scenario)
        self.method = method
        self.note = "Python rhs" + (", finite-difference Jacobian" if method in ("BDF", "Radau", "LSODA") else "")
        if scenario is B:
            self.note += "; terminal events + restart loop"

    def _solve(self, rtol: float, atol: float, count_steps: bool = False) -> Dict[str, Any]:
        from scipy.integrate import solve_ivp

        if self.scenario is A:
            t_eval = None if count_steps else [A.window_start, A.t_end]
            sol = solve_ivp(axial_dahl_rhs, (0.0, A.t_end), np.zeros(4), method=self.method, rtol=rtol, atol=atol,
                            t_eval=t_eval)
            if sol.status != 0:
                raise RuntimeError(sol.message)
            out = {"nfev": sol.nfev, "njev": sol.njev, "events": None}
            if count_steps:
                out["steps"] = len(sol.t) - 1
            else:
                out["mean_friction"] = (sol.y[3, -1] - sol.y[3, 0]) / (A.t_end - A.window_start)
            return out
        t, y, mode = 0.0, np.zeros(3), 0
        steps = nfev = njev = events = 0
        for _ in range(MAX_SEGMENTS):
            fun, event_functions = _SB_SCIPY[mode]
            sol = solve_ivp(fun, (t, B.t_end), y, method=self.method, rtol=rtol, atol=atol, events=event_functions)
            if sol.status < 0:
                raise RuntimeError(sol.message)
            steps += len(sol.t) - 1
            nfev += sol.nfev
            njev += sol.njev
            if sol.status == 0:
                y = sol.y[:, -1]
                break
            i = next(i for i, te in enumerate(sol.t_events) if te.size)
            t, y = float(sol.t_events[i][0]), np.array(sol.y_events[i][0], dtype=float)
            mode = spring_block_switch(mode, t, y)
            events += 1
        else:
            raise RuntimeError(f"more than {MAX_SEGMENTS} restarts")
        return {"final_position": float(y[0]), "mean_friction": float(y[2]) / B.t_end, "nfev": nfev, "njev": njev,
                "events": events, "steps": steps}



# ---------------------------------------------------------------------------------------------- scikit-sundae
def _sksundae_version() -> Optional[str]:
    try:
        import sksundae
    except ImportError:
        return None
    return f"{sksundae.__version__} (SUNDIALS {getattr(sksundae, 'SUNDIALS_VERSION', '?')})"


class SciKitSundae(PythonPeer):
    family = "scikit-sundae"

    def __init__(self, scenario, method: str) -> None:
        super().__init__(scenario)
        self.method = method  # "BDF" or "Adams"
        self.note = "CVODE, Python rhs, dense linear solver, difference-quotient Jacobian"
        if scenario is B:
            self.note += "; root-finding events + restart loop"

    def unavailable(self) -> Optional[str]:
        if _sksundae_version() is None:
            return "not installed (pip install scikit-sundae, or the bench extra: pip install '.[bench]')"
        return None

    def _solve(self, rtol: float, atol: float, count_steps: bool = False) -> Dict[str, Any]:
        from sksundae.cvode import CVODE

        options = {"method": self.method, "rtol": rtol, "atol": atol, "max_num_steps": 10_000_000}
        if self.scenario is A:
            tspan = np.array([0.0, A.t_end] if count_steps else [0.0, A.window_start, A.t_end])
            soln = CVODE(axial_dahl_rhs_inplace, **options).solve(tspan, np.zeros(4))
            if not soln.success:
                raise RuntimeError(soln.message)
            out = {"nfev": soln.nfev, "njev": soln.njev, "events": None}
            if count_steps:  # a two-point tspan returns every internal step
                out["steps"] = len(soln.t) - 1
            else:
                out["mean_friction"] = (soln.y[-1, 3] - soln.y[-2, 3]) / (A.t_end - A.window_start)
            return out
        solvers = _sksundae_spring_block_solvers(options)
        t, y, mode = 0.0, np.zeros(3), 0
        steps = nfev = njev = events = 0
        for _ in range(MAX_SEGMENTS):
            soln = solvers[mode].solve(np.array([t, B.t_end]), y)
            if not soln.success:
                raise RuntimeError(soln.message)
            steps += len(soln.t) - 1
            nfev += soln.nfev
            njev += soln.njev
            if soln.status != 2:  # 2: stopped at an event
                y = np.array(soln.y[-1], dtype=float)
                break
            # the last entry: scikit-sundae 1.2 keeps the events of earlier solve() calls of the same solver
            t, y = float(soln.t_events[-1]), np.array(soln.y_events[-1], dtype=float)
            mode = spring_block_switch(mode, t, y)
            events += 1
        else:
            raise RuntimeError(f"more than {MAX_SEGMENTS} restarts")
        return {"final_position": float(y[0]), "mean_friction": float(y[2]) / B.t_end, "nfev": nfev, "njev": njev,
                "events": events, "steps": steps}



def _sb_events_stick(t, y, events):
    spring = B.k * (B.v_p * t - y[0])
    events[0] = spring - _SB_FS
    events[1] = -spring - _SB_FS


def _sb_rhs_inplace(mode: int):
    def rhs(t, y, yp):
        if mode == 0:
            yp[0] = 0.0
            yp[1] = 0.0
            yp[2] = B.k * (B.v_p * t - y[0])
            return
        x, v, _ = y.tolist()
        yp[0] = v
        yp[1] = (B.k * (B.v_p * t - x) - mode * _SB_FK) / B.m
        yp[2] = mode * _SB_FK
    return rhs


def _sksundae_spring_block_solvers(options: Dict[str, Any]):
    from sksundae.cvode import CVODE

    stick = _sb_events_stick
    stick.terminal, stick.direction = [True, True], [1, 1]

    def falling(t, y, events):
        events[0] = y[1]

    def rising(t, y, events):
        events[0] = y[1]

    falling.terminal, falling.direction = [True], [-1]
    rising.terminal, rising.direction = [True], [1]
    return {0: CVODE(_sb_rhs_inplace(0), eventsfn=stick, num_events=2, **options),
            1: CVODE(_sb_rhs_inplace(1), eventsfn=falling, num_events=1, **options),
            -1: CVODE(_sb_rhs_inplace(-1), eventsfn=rising, num_events=1, **options)}


# ---------------------------------------------------------------------------------------------- sundials4py
SUNDIALS4PY_NOTE = ("sundials4py (SUNDIALS' official bindings, 7.9.0 on PyPI) publishes only cp312-abi3 wheels: "
                    "`pip install sundials4py` finds no distribution for Python < 3.12")


class Sundials4py(Tool):
    family = "sundials4py"

    def unavailable(self) -> Optional[str]:
        try:
            import sundials4py  # noqa: F401
        except ImportError:
            return f"not installed on Python {platform.python_version()}: {SUNDIALS4PY_NOTE}"
        # Installed (Python >= 3.12): its API could not be exercised on the Python this comparison was written
        # on, so there is no adapter yet rather than an untested one.
        return ("installed, but compare.py has no sundials4py adapter yet (written on Python 3.11, where it cannot "
                "install)")


# ---------------------------------------------------------------------------------------------- the C program
class CReference(Tool):
    family = "C program on CVODE"

    def __init__(self, scenario, binary: Path, method: str, jacobian: Optional[str] = None,
                 events: bool = False) -> None:
        super().__init__(scenario)
        self.binary = binary
        self.base_method = method
        self.jacobian = jacobian
        self.events = events
        parts = [method]
        if jacobian:
            parts.append(f"{jacobian} Jacobian")
        if scenario is A:
            parts.append("kink as root" if events else "steps across kink")
        self.method = ", ".join(parts)
        self.note = "bench/reference/cvode_reference.c" + ("; CVodeRootInit events + CVodeReInit" if
                                                          (events or scenario is B) else "")

    def unavailable(self) -> Optional[str]:
        if not self.binary.is_file() or not os.access(self.binary, os.X_OK):
            return f"{self.binary} is missing (bench/reference/, target bench_cvode_reference)"
        return None

    def _call(self, k: int, repeat: int) -> Dict[str, Any]:
        command = [str(self.binary), "--scenario", self.scenario.key, "--rtol", repr(rtol_of(k)),
                   "--atol", repr(ATOL_FACTOR * rtol_of(k)), "--method", self.base_method, "--repeat", str(repeat)]
        if self.jacobian:
            command += ["--jacobian", self.jacobian]
        if self.events:
            command.append("--events")
        done = subprocess.run(command, capture_output=True, text=True, check=False)
        if done.returncode != 0:
            raise RuntimeError(f"exit {done.returncode}: {done.stderr.strip()[-300:]}")
        return json.loads(done.stdout.strip().splitlines()[-1])

    def run(self, k: int) -> Outcome:
        r = self._call(k, 1)
        return Outcome(k, {q: float(r[q]) for q in self.scenario.quantities}, float(r["seconds_per_run"]),
                       int(r["steps"]), int(r["rhs_evaluations"]), int(r["jacobian_evaluations"]), int(r["events"]))

    def time(self, k: int, outcome: Outcome, settings: Settings) -> Timing:
        first = max(outcome.seconds or 1e-3, 1e-7)
        repeat = int(min(1_000_000, max(1, math.ceil(settings.min_batch / first))))
        samples = []
        for _ in range(settings.repeats):
            samples.append(float(self._call(k, repeat)["seconds_per_run"]))
            if sum(samples) * repeat > settings.max_timing_seconds:
                break
        return Timing(min(samples), samples, repeat,
                      f"its own --repeat {repeat}: best single run (CLOCK_MONOTONIC), best of {len(samples)} calls")


# =============================================================================================== the search
@dataclass
class Entry:
    """A tool's tolerance scan, its chosen grid point and the timing there."""

    tool: Tool
    skipped: Optional[str] = None
    scan: List[Outcome] = field(default_factory=list)
    chosen: Optional[Outcome] = None
    timing: Optional[Timing] = None
    stop_reason: Optional[str] = None
    extra: Dict[str, Any] = field(default_factory=dict)

    @property
    def seconds(self) -> Optional[float]:
        return self.timing.seconds if self.timing else None

    def as_dict(self) -> Dict[str, Any]:
        return {"tool": self.tool.family, "method": self.tool.method, "note": self.tool.note, "skipped": self.skipped,
                "stop_reason": self.stop_reason, "chosen": self.chosen.as_dict() if self.chosen else None,
                "timing": self.timing.as_dict() if self.timing else None,
                "scan": [o.as_dict() for o in self.scan], **self.extra}


def check(outcome: Outcome, reference: Dict[str, float], quantities: Sequence[str], accuracy: float) -> None:
    if outcome.error is not None:
        outcome.ok = False
        return
    outcome.rel_errors = {q: abs(outcome.values[q] - reference[q]) / abs(reference[q]) for q in quantities}
    outcome.ok = all(math.isfinite(e) and e <= accuracy for e in outcome.rel_errors.values())


def search(tool: Tool, reference: Dict[str, float], settings: Settings, log: Callable[[str], None]) -> Entry:
    """Scan the grid from loose to tight; choose the loosest K that passes with its tighter neighbour passing."""
    entry = Entry(tool)
    reason = tool.unavailable()
    if reason:
        entry.skipped = reason
        log(f"  {tool.label}: skipped: {reason}")
        return entry
    ks = [k for k in settings.grid if k <= tool.max_k()]
    for i, k in enumerate(ks):
        try:
            outcome = tool.run(k)
        except Exception as error:  # noqa: BLE001 - a peer failing at one tolerance is data, not a crash
            outcome = Outcome(k, error=f"{type(error).__name__}: {error}")
        check(outcome, reference, tool.scenario.quantities, settings.accuracy)
        entry.scan.append(outcome)
        if outcome.ok and len(entry.scan) >= 2 and entry.scan[-2].ok:
            entry.chosen = entry.scan[-2]
            break
        if outcome.ok and i == len(ks) - 1:  # the tightest grid point: nothing tighter to confirm with
            entry.chosen = outcome
        if outcome.seconds is not None and outcome.seconds > settings.max_run_seconds and entry.chosen is None:
            entry.stop_reason = (f"stopped at rtol {rtol_of(k):.0e}: one run took {outcome.seconds:.1f} s "
                                 f"(> --max-run-seconds {settings.max_run_seconds:g})")
            break
    if entry.chosen is None:
        last = entry.scan[-1] if entry.scan else None
        entry.stop_reason = entry.stop_reason or (
            f"no rtol >= {rtol_of(ks[-1]):.0e} met {settings.accuracy:g}" +
            (f" (last: {last.error})" if last is not None and last.error else ""))
        log(f"  {tool.label}: {entry.stop_reason}")
        return entry
    complete = getattr(tool, "complete", None)
    if complete is not None:
        complete(entry.chosen)
    entry.timing = tool.time(entry.chosen.k, entry.chosen, settings)
    log(f"  {tool.label}: rtol {rtol_of(entry.chosen.k):.1e}, {fmt_time(entry.seconds)} per simulation "
        f"({entry.timing.how})")
    return entry


# =============================================================================================== references
def reference_values(scenario, settings: Settings, log: Callable[[str], None]) -> Dict[str, Any]:
    k = settings.reference_k
    rtol, atol = rtol_of(k), ATOL_FACTOR * rtol_of(k)
    r = scenario.frictionsim("dormand_prince", rtol, atol)
    values = {q: float(r[q]) for q in scenario.quantities}
    out: Dict[str, Any] = {"values": values, "how": f"frictionsim dormand_prince, rtol {rtol:.0e}, atol {atol:.0e}"}
    # the cross-check: an independent implementation on another integrator
    from scipy.integrate import solve_ivp

    c_rtol, c_atol = settings.crosscheck_rtol, settings.crosscheck_atol
    t0 = time.perf_counter()
    if scenario is A:
        sol = solve_ivp(axial_dahl_rhs, (0.0, A.t_end), np.zeros(4), method="DOP853", rtol=c_rtol, atol=c_atol,
                        t_eval=[A.window_start, A.t_end])
        check_values = {"mean_friction": (sol.y[3, -1] - sol.y[3, 0]) / (A.t_end - A.window_start)}
    else:
        r = Scipy(B, "DOP853")._solve(c_rtol, c_atol)
        check_values = {q: r[q] for q in B.quantities}
    seconds = time.perf_counter() - t0
    agreement = {q: abs(check_values[q] - values[q]) / abs(values[q]) for q in scenario.quantities}
    out["crosscheck"] = {"how": f"SciPy DOP853 (Python rhs{', events' if scenario is B else ''}), rtol {c_rtol:.0e}, "
                                f"atol {c_atol:.0e}", "values": check_values, "rel_difference": agreement,
                         "seconds": seconds}
    worst = max(agreement.values())
    if worst > settings.accuracy / 10:
        log(f"  WARNING: the reference and its cross-check differ by {worst:.1e} relative, more than a tenth of "
            f"the accuracy target {settings.accuracy:g}")
    log(f"  reference {scenario.key}: {values} ({out['how']}); {out['crosscheck']['how']} agrees to {worst:.1e}")
    return out


# =============================================================================================== the sweep
def run_sweep(settings: Settings, log: Callable[[str], None]) -> Dict[str, Any]:
    from frictionsim.sweeps import axial_mean_friction

    n_amplitude, n_frequency = settings.sweep_shape
    grid = {"amplitude": np.linspace(1e-3, 5e-3, n_amplitude).tolist(),       # m
            "frequency": np.linspace(10.0, 25.0, n_frequency).tolist()}       # Hz
    fixed = {"friction": fs.Dahl(0.41, 4e4)}
    points = n_amplitude * n_frequency
    # warm-up (thread start, first-call costs)
    with cf.ThreadPoolExecutor(2) as pool:
        fs.sweep(axial_mean_friction, {"amplitude": grid["amplitude"][:2], "frequency": grid["frequency"][:2]},
                 fixed=fixed, executor=pool, progress=False)
    seconds: Dict[int, List[float]] = {1: [], 2: []}
    values: Dict[int, np.ndarray] = {}
    for _ in range(settings.sweep_repeats):
        for threads in (1, 2):
            with cf.ThreadPoolExecutor(threads) as pool:
                t0 = time.perf_counter()
                result = fs.sweep(axial_mean_friction, grid, fixed=fixed, executor=pool, progress=False)
                seconds[threads].append(time.perf_counter() - t0)
            array = result.as_array()
            if threads in values and not np.array_equal(values[threads], array, equal_nan=True):
                log("  WARNING: a repeated sweep gave different values")
            values[threads] = array
    identical = bool(np.array_equal(values[1], values[2], equal_nan=True))
    best = {n: min(s) for n, s in seconds.items()}
    speedup = best[1] / best[2]
    log(f"  sweep of {points}: 1 thread {best[1]:.2f} s, 2 threads {best[2]:.2f} s, speedup {speedup:.2f}x, "
        f"identical: {identical}")
    return {"points": points, "grid": {"amplitude [m]": [grid["amplitude"][0], grid["amplitude"][-1], n_amplitude],
                                       "frequency [Hz]": [grid["frequency"][0], grid["frequency"][-1], n_frequency]},
            "point_function": "frictionsim.sweeps.axial_mean_friction(friction=Dahl(0.41, 4e4)), 2 s, rtol 1e-8, "
                              "automatic method",
            "seconds": {str(n): s for n, s in seconds.items()}, "best_seconds": {str(n): s for n, s in best.items()},
            "speedup": speedup, "identical": identical, "failed": int(np.isnan(values[1]).sum()),
            "per_simulation_seconds_1_thread": best[1] / points}


# =============================================================================================== formatting
def fmt_time(seconds: Optional[float]) -> str:
    if seconds is None:
        return "—"
    if seconds >= 1.0:
        return f"{seconds:.2f} s"
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds * 1e6:.3g} µs"


def fmt_ratio(numerator: Optional[float], denominator: Optional[float]) -> str:
    if numerator is None or denominator is None or denominator <= 0:
        return "—"
    r = numerator / denominator
    return f"{r:.3g}×" if r < 100 else f"{r:.0f}×"


def fmt_int(n: Optional[int]) -> str:
    return "—" if n is None else f"{n:,}"


def markdown_table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def best_of_family(entries: Sequence[Entry], family: str) -> Optional[Entry]:
    timed = [e for e in entries if e.tool.family == family and e.seconds is not None]
    return min(timed, key=lambda e: e.seconds) if timed else None


FAMILIES = ("frictionsim C++", "frictionsim Python", "SciPy solve_ivp", "scikit-sundae", "sundials4py",
            "C program on CVODE")


def value_columns(scenario, outcome: Optional[Outcome]) -> List[str]:
    cells = []
    for q in scenario.quantities:
        if outcome is None or q not in outcome.values:
            cells += ["—", "—"]
        else:
            cells += [f"{outcome.values[q]:.10g}", f"{outcome.rel_errors.get(q, math.nan):.1e}"]
    return cells


def scenario_tables(scenario, entries: Sequence[Entry], reference: Dict[str, Any], settings: Settings) -> str:
    cpp = best_of_family(entries, "frictionsim C++")
    py = best_of_family(entries, "frictionsim Python")
    quantity_header = []
    for q in scenario.quantities:
        quantity_header += [QUANTITY_LABEL[q], "rel. error"]
    header = ["tool / method", "rtol", "time / simulation", "× frictionsim C++", "× frictionsim Python", "steps",
              "rhs evals", *quantity_header]
    if scenario is B:
        header.append("events")
    rows: List[List[str]] = []
    missing: List[str] = []
    for family in FAMILIES:
        best = best_of_family(entries, family)
        if best is None:
            mine = [e for e in entries if e.tool.family == family]
            why = next((e.skipped for e in mine if e.skipped), None) or "; ".join(
                f"{e.tool.method}: {e.stop_reason}" for e in mine if e.stop_reason) or "not run"
            missing.append(f"- {family}: {why}")
            row = [family, "—", "not measured (below)"] + ["—"] * (len(header) - 3)
            rows.append(row)
            continue
        c = best.chosen
        row = [best.tool.label, f"{rtol_of(c.k):.1e}", fmt_time(best.seconds),
               fmt_ratio(best.seconds, cpp.seconds if cpp else None),
               fmt_ratio(best.seconds, py.seconds if py else None), fmt_int(c.steps), fmt_int(c.rhs),
               *value_columns(scenario, c)]
        if scenario is B:
            row.append(fmt_int(c.events))
        rows.append(row)
    ref = reference["values"]
    text = [f"### {scenario.title}", "",
            f"Each tool at the loosest rtol = 10^(-K/10) (atol = 1e-4 rtol) on K = {settings.grid[0]}, "
            f"{settings.grid[1]}, ..., {settings.grid[-1]} whose answers are within {settings.accuracy:g} relative "
            "of the reference (and so are the next tighter grid point's); per tool its fastest method. "
            "× = the tool's time over frictionsim's.", "",
            markdown_table(header, rows), ""]
    if missing:
        text += ["Not measured:", *missing, ""]
    text += ["Reference: " + ", ".join(f"{QUANTITY_LABEL[q]} = {ref[q]:.13g}" for q in scenario.quantities) +
            f" ({reference['how']}); {reference['crosscheck']['how']} agrees to "
            f"{max(reference['crosscheck']['rel_difference'].values()):.1e} relative.", ""]
    text += [f"Warning: {w}" for w in consistency_warnings(scenario, entries)]
    # every method
    detail_header = ["tool / method", "rtol", "time / simulation", "× frictionsim C++", "steps", "rhs evals",
                     "Jacobians", *quantity_header, "note"]
    detail_rows = []
    for e in entries:
        if e.chosen is None:
            detail_rows.append([e.tool.label] + ["—"] * (len(detail_header) - 2) +
                               ["not measured: " + (e.skipped or e.stop_reason or "")])
            continue
        c = e.chosen
        detail_rows.append([e.tool.label, f"{rtol_of(c.k):.1e}", fmt_time(e.seconds),
                            fmt_ratio(e.seconds, cpp.seconds if cpp else None), fmt_int(c.steps), fmt_int(c.rhs),
                            fmt_int(c.jac), *value_columns(scenario, c), e.tool.note])
    text += ["Every method:", "", markdown_table(detail_header, detail_rows), ""]
    return "\n".join(text)


def consistency_warnings(scenario, entries: Sequence[Entry]) -> List[str]:
    """The C++ benchmark and the Python extension are one engine: at the same method and K they must agree."""
    out = []
    cpp = {(e.tool.method, o.k): o for e in entries if e.tool.family == "frictionsim C++" for o in e.scan}
    for e in entries:
        if e.tool.family != "frictionsim Python":
            continue
        for o in e.scan:
            other = cpp.get((e.tool.method, o.k))
            if other is None or o.error or other.error:
                continue
            for q in scenario.quantities:
                difference = abs(o.values[q] - other.values[q]) / abs(other.values[q])
                if difference > 1e-9 or o.steps != other.steps:
                    out.append(f"frictionsim C++ and Python differ at {e.tool.method}, rtol {rtol_of(o.k):.1e}: "
                               f"{q} {other.values[q]!r} vs {o.values[q]!r}, steps {other.steps} vs {o.steps}; "
                               "one of the two builds is stale (rebuild both from the same tree)")
                    return out
    return out


def python_vs_cpp(scenario, entries: Sequence[Entry], settings: Settings) -> Dict[str, Any]:
    """frictionsim from Python over the C++ benchmark, same method and tolerance: at the chosen point and 1e-8.

    The two are timed side by side: rounds of one C++ repetition then one Python batch, so that both see the same
    machine (a VM's speed drifts by 10-50 % over the minutes between two tools' timings). The ratio is the best
    Python batch over the best C++ repetition; the per-round ratios are kept too."""
    cpp = best_of_family(entries, "frictionsim C++")
    if cpp is None:
        return {}
    out: Dict[str, Any] = {"method": cpp.tool.method, "rounds": settings.paired_rounds,
                           "how": "interleaved: each round one Google Benchmark repetition, then one Python batch "
                                  f"of >= {settings.min_batch:g} s; best of each over the rounds"}
    py_tool = FrictionsimPython(scenario, cpp.tool.method)
    one_batch = replace(settings, repeats=1)
    points = [("equal accuracy", cpp.chosen.k)]
    if 80 != cpp.chosen.k:
        points.append(("fixed tolerance", 80))
    for label, k in points:
        cpp_samples, py_samples = [], []
        for _ in range(max(1, settings.paired_rounds)):
            cpp_samples.append(cpp.tool.time(k, Outcome(k), one_batch).seconds)
            py_samples.append(py_tool.time(k, Outcome(k), one_batch).seconds)
        out[label] = {"K": k, "rtol": rtol_of(k), "python_seconds": min(py_samples), "cpp_seconds": min(cpp_samples),
                      "ratio": min(py_samples) / min(cpp_samples),
                      "round_ratios": [p / c for p, c in zip(py_samples, cpp_samples)],
                      "python_samples": py_samples, "cpp_samples": cpp_samples}
    return out


# =============================================================================================== the run
def machine() -> Dict[str, Any]:
    model = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:
        usable = os.cpu_count()
    versions = {"python": platform.python_version(), "frictionsim": fs.__version__, "numpy": np.__version__}
    try:
        import scipy

        versions["scipy"] = scipy.__version__
    except ImportError:
        pass
    if _sksundae_version():
        versions["scikit-sundae"] = _sksundae_version()
    return {"date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"), "nproc": usable,
            "cpu_count": os.cpu_count(), "cpu_model": model, "platform": platform.platform(),
            "load_average_at_start": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
            "versions": versions}


def tools_for(scenario, bench: CppBenchmark, reference_binary: Path, settings: Settings) -> List[Tool]:
    tools: List[Tool] = [FrictionsimCpp(scenario, m, bench) for m in scenario.cpp_methods]
    tools += [FrictionsimPython(scenario, m) for m in scenario.cpp_methods]
    tools += [Scipy(scenario, m) for m in settings.scipy_methods]
    tools += [SciKitSundae(scenario, m) for m in ("BDF", "Adams")]
    tools.append(Sundials4py(scenario))
    if scenario is A:
        variants = [("adams", None, False), ("adams", None, True), ("bdf", None, False), ("bdf", None, True),
                    ("bdf", "analytic", True)]
    else:
        variants = [("adams", None, False), ("bdf", None, False), ("bdf", "analytic", False)]
    tools += [CReference(scenario, reference_binary, m, j, e) for m, j, e in variants]
    return tools


def targets(results: Dict[str, Any]) -> List[Dict[str, Any]]:
    """The issue's targets on scenario A: measured, met / not met. Never asserted."""
    out = []
    a = results["scenarios"].get(A.key)
    if a is not None:
        best = a["best"]
        base = best.get("frictionsim C++") or best.get("frictionsim Python")
        base_name = "frictionsim C++" if best.get("frictionsim C++") else "frictionsim Python"
        for family, goal in (("SciPy solve_ivp", 100.0), ("scikit-sundae", 50.0), ("C program on CVODE", 5.0)):
            peer = best.get(family)
            target = f"{base_name} >= {goal:g}x faster than {family}'s fastest (A)"
            if base is None or peer is None:
                out.append({"target": target, "measured": None, "met": None, "detail": "not measured"})
                continue
            ratio = peer["seconds"] / base["seconds"]
            out.append({"target": target, "measured": ratio, "met": ratio >= goal,
                        "detail": f"{peer['label']} {fmt_time(peer['seconds'])} / {fmt_time(base['seconds'])}"})
        pvc = a.get("python_vs_cpp", {}).get("equal accuracy")
        target = "frictionsim Python within 1.1x of the C++ benchmark (A, 2 s, same method and tolerance)"
        if pvc:
            out.append({"target": target, "measured": pvc["ratio"], "met": pvc["ratio"] <= 1.1,
                        "detail": f"{fmt_time(pvc['python_seconds'])} / {fmt_time(pvc['cpp_seconds'])} at rtol "
                                  f"{pvc['rtol']:.1e}"})
        else:
            out.append({"target": target, "measured": None, "met": None, "detail": "not measured"})
    sweep = results.get("sweep")
    target = "sweep of 1000 axial-rig simulations >= 1.8x faster on 2 threads than on 1"
    if sweep:
        out.append({"target": target.replace("1000", str(sweep["points"])), "measured": sweep["speedup"],
                    "met": sweep["speedup"] >= 1.8,
                    "detail": f"{sweep['best_seconds']['1']:.2f} s / {sweep['best_seconds']['2']:.2f} s, results "
                              f"{'identical' if sweep['identical'] else 'DIFFERENT'}"})
    else:
        out.append({"target": target, "measured": None, "met": None, "detail": "not run"})
    return out


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", type=Path, default=REPO / "out" / "bench", help="output directory (out/bench)")
    parser.add_argument("--build-dir", type=Path,
                        default=Path(os.environ.get("FRICTIONSIM_BUILD_DIR", REPO / "build")),
                        help="the C++ build with bench/integrators and bench/reference/cvode_reference "
                             "($FRICTIONSIM_BUILD_DIR or build/)")
    parser.add_argument("--reference-binary", type=Path,
                        help="the C CVODE program (default BUILD_DIR/bench/reference/cvode_reference)")
    parser.add_argument("--quick", action="store_true",
                        help="a fast smoke run (accuracy 1e-3, coarse grid, one repetition, 40-point sweep): "
                             "exercises every tool, its numbers are not the comparison")
    parser.add_argument("--scenarios", default="axial_dahl,spring_block", help="comma-separated: axial_dahl, "
                                                                               "spring_block")
    parser.add_argument("--no-sweep", action="store_true", help="skip the threaded sweep (C)")
    parser.add_argument("--accuracy", type=float, help="relative accuracy every answer must meet (1e-5)")
    parser.add_argument("--repeats", type=int, help="timing repetitions per tool (5)")
    parser.add_argument("--max-run-seconds", type=float,
                        help="stop a tool's tolerance scan when one run takes longer (30 s)")
    args = parser.parse_args(argv)

    settings = Settings()
    if args.quick:
        settings = Settings(accuracy=1e-3, repeats=1, min_batch=0.0, max_timing_seconds=2.0, max_run_seconds=2.0,
                            cpp_min_time=0.001, cpp_scan_min_time=0.001, reference_k=110, crosscheck_rtol=1e-9,
                            crosscheck_atol=1e-13, scipy_methods=("RK45", "LSODA"),
                            sweep_shape=(5, 8), sweep_repeats=1, paired_rounds=1, grid=tuple(range(40, 125, 10)))
    if args.accuracy is not None:
        settings.accuracy = args.accuracy
    if args.repeats is not None:
        settings.repeats = max(1, args.repeats)
    if args.max_run_seconds is not None:
        settings.max_run_seconds = args.max_run_seconds
    scenario_keys = [s.strip() for s in args.scenarios.split(",") if s.strip()]
    unknown = [s for s in scenario_keys if s not in SCENARIOS]
    if unknown:
        parser.error(f"--scenarios: unknown {', '.join(unknown)} (axial_dahl, spring_block)")

    def log(message: str) -> None:
        print(message, file=sys.stderr, flush=True)

    # SciPy's finite-difference Jacobian (BDF, Radau) warns of overflows while it adapts its increments
    warnings.filterwarnings("ignore", category=RuntimeWarning, module=r"scipy\.integrate")
    started = time.perf_counter()
    info = machine()
    build_dir = args.build_dir.resolve()
    bench = CppBenchmark(build_dir / "bench" / "integrators", settings)
    reference_binary = (args.reference_binary or build_dir / "bench" / "reference" / "cvode_reference").resolve()
    log(f"frictionsim comparison{' (--quick)' if args.quick else ''}: {info['date']}, {info['cpu_model']}, "
        f"nproc {info['nproc']}, load {info['load_average_at_start']}")
    log(f"  C++ benchmark: {bench.binary}{'' if bench.available() is None else ' (missing)'}; C program: "
        f"{reference_binary}{'' if reference_binary.is_file() else ' (missing)'}")

    results: Dict[str, Any] = {"machine": info, "settings": {
        "quick": args.quick, "accuracy": settings.accuracy, "grid_K": list(settings.grid), "atol_factor": ATOL_FACTOR,
        "repeats": settings.repeats, "min_batch_seconds": settings.min_batch,
        "max_run_seconds": settings.max_run_seconds, "build_dir": str(build_dir)}, "scenarios": {},
        "notes": {"sundials4py": SUNDIALS4PY_NOTE}}
    sections = []
    for key in scenario_keys:
        scenario = SCENARIOS[key]
        log(f"\n{scenario.title}")
        reference = reference_values(scenario, settings, log)
        entries = [search(tool, reference["values"], settings, log)
                   for tool in tools_for(scenario, bench, reference_binary, settings)]
        for warning in consistency_warnings(scenario, entries):
            log(f"  WARNING: {warning}")
        log("  frictionsim Python / C++ ...")
        pvc = python_vs_cpp(scenario, entries, settings)
        best = {}
        for family in FAMILIES:
            b = best_of_family(entries, family)
            if b is not None:
                best[family] = {"label": b.tool.label, "seconds": b.seconds, "K": b.chosen.k,
                                "rtol": rtol_of(b.chosen.k), "values": b.chosen.values}
        results["scenarios"][key] = {"title": scenario.title, "reference": reference, "best": best,
                                     "python_vs_cpp": pvc, "entries": [e.as_dict() for e in entries]}
        table = scenario_tables(scenario, entries, reference, settings)
        if pvc:
            lines = [f"frictionsim Python / C++ ({pvc['method']}, the same simulation, {pvc['how']}, "
                     f"{pvc['rounds']} rounds): " + "; ".join(
                         f"{label} (rtol {v['rtol']:.1e}): {fmt_time(v['python_seconds'])} / "
                         f"{fmt_time(v['cpp_seconds'])} = {v['ratio']:.3f} (per round "
                         f"{min(v['round_ratios']):.2f}-{max(v['round_ratios']):.2f})"
                         for label, v in pvc.items() if isinstance(v, dict))]
            table += "\n" + "\n".join(lines) + "\n"
        sections.append(table)

    if not args.no_sweep:
        log("\nC. sweep")
        results["sweep"] = run_sweep(settings, log)
        s = results["sweep"]
        sections.append("\n".join([
            f"### C. Sweep of {s['points']} axial-rig simulations from Python", "",
            f"`fs.sweep({s['point_function'].split('(')[0]}, amplitude {s['grid']['amplitude [m]'][0]:g}-"
            f"{s['grid']['amplitude [m]'][1]:g} m x frequency {s['grid']['frequency [Hz]'][0]:g}-"
            f"{s['grid']['frequency [Hz]'][1]:g} Hz, executor=ThreadPoolExecutor(n))`, "
            f"Dahl(0.41, 4e4), 2 s each, rtol 1e-8; best of {len(s['seconds']['1'])}.", "",
            markdown_table(["threads", "wall time", "per simulation", "speedup", "results"],
                           [["1", f"{s['best_seconds']['1']:.2f} s", fmt_time(s['best_seconds']['1'] / s['points']),
                             "1", ""],
                            ["2", f"{s['best_seconds']['2']:.2f} s", fmt_time(s['best_seconds']['2'] / s['points']),
                             f"{s['speedup']:.2f}×", "identical to 1 thread" if s["identical"] else "DIFFERENT"]]),
            ""]))

    results["targets"] = targets(results)
    def measured(t: Dict[str, Any]) -> str:
        if t["measured"] is None:
            return "—"
        return f"{t['measured']:.3g}×" if "x faster" in t["target"] else f"{t['measured']:.3g}"

    status = {True: "met", False: "not met", None: "not measured"}
    target_rows = [[t["target"], measured(t), status[t["met"]], t["detail"]] for t in results["targets"]]
    results["seconds_total"] = time.perf_counter() - started
    head = [f"## frictionsim against its peers{' (--quick: a smoke run, not the comparison)' if args.quick else ''}",
            "",
            f"Machine: {info['cpu_model']}, nproc {info['nproc']}, {info['platform']}; load average at start "
            f"{', '.join(f'{x:.2f}' for x in info['load_average_at_start'] or [])}. Date: {info['date']}. "
            + ", ".join(f"{k} {v}" for k, v in info["versions"].items()) + ".", ""]
    text = "\n".join(head + sections + ["### Targets (issue 5; measured, never asserted)", "",
                                        markdown_table(["target", "measured", "status", "detail"], target_rows), "",
                                        f"Whole run: {results['seconds_total']:.0f} s.", ""])
    print(text)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "compare.md").write_text(text)
    (args.out / "compare.json").write_text(json.dumps(results, indent=1, default=str))
    if bench.raw:
        (args.out / "integrators.json").write_text(json.dumps(bench.raw, indent=1))
    log(f"\nwrote {args.out / 'compare.md'}, {args.out / 'compare.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
