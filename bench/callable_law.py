#!/usr/bin/env python3
"""The cost of a friction law written in Python (fs.CallableLaw) against the same law in C++ (fs.Dahl).

The simulation is bench/compare.py's scenario A: paper 000's axial rig with Dahl friction (mu 0.41, k_t 4e4 N/m,
the rig's Fig. 7(a) defaults), 2 s from rest, the answer being the mean friction force over the last 10 cycles.
It runs once with fs.Dahl and once with fs.CallableLaw(dahl_force, dahl_rate), Dahl's equations in Python
(F = k_t z, dz/dt = v_r (1 - k_t z sgn(v_r) / (mu N))), per integrator.

Timing: interleaved rounds (a batch of fs.Dahl runs, then a batch of CallableLaw runs, each batch lasting at least
--min-batch seconds, GC off), best of the rounds per law. The law calls are counted in a separate run whose
callables count themselves (the same trajectory, so the same calls). The cost per call is the extra time of the
CallableLaw run over the fs.Dahl run divided by the number of law calls. The runs are not step-for-step
identical (fs.Dahl locates its kink at v_r = 0 as an event, the callable law has none and its error control takes
a few more steps), so a second figure first scales the fs.Dahl time to the CallableLaw run's right-hand-side
evaluations: what is left is the calls alone. The floor beside it is what the two Python functions cost called
from a Python loop with the same arguments (no GIL hand-over, no C++); the difference is the bridge: re-acquiring
the GIL, boxing three floats, the call and the check of the result.

Prints the machine, a Markdown table and the per-call cost; --json PATH also writes the numbers.
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import sys
import time
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence

import frictionsim as fs

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare import A, fmt_time, machine, markdown_table  # noqa: E402  (bench/compare.py: one style, one scenario)

MU, K_T = A.mu, A.k_t
METHODS = ("dormand_prince", "cvode_bdf", "cvode_adams")


def dahl_force(v_r: float, normal_force: float, z: float) -> float:
    return K_T * z


def dahl_rate(v_r: float, normal_force: float, z: float) -> float:
    sign = (v_r > 0.0) - (v_r < 0.0)
    return v_r * (1.0 - K_T * z * sign / (MU * normal_force))


class Counted:
    """dahl_force and dahl_rate that count their calls."""

    def __init__(self) -> None:
        self.force_calls = 0
        self.rate_calls = 0

    def force(self, v_r: float, normal_force: float, z: float) -> float:
        self.force_calls += 1
        return K_T * z

    def rate(self, v_r: float, normal_force: float, z: float) -> float:
        self.rate_calls += 1
        sign = (v_r > 0.0) - (v_r < 0.0)
        return v_r * (1.0 - K_T * z * sign / (MU * normal_force))


def run(law, method: str, rtol: float) -> fs.Result:
    rig = fs.AxialVibrationRig(friction=law)  # the Fig. 7(a) defaults, as scenario A
    return fs.simulate(rig, A.t_end, method=method, rtol=rtol, atol=1e-4 * rtol,
                       output_times=[A.window_start, A.t_end])


def mean_friction(result: fs.Result) -> float:
    impulse = result["friction_impulse"]
    return float((impulse[-1] - impulse[0]) / (A.t_end - A.window_start))


def batch_size(fn: Callable[[], Any], min_batch: float) -> int:
    t0 = time.perf_counter()
    fn()  # warm-up and calibration
    first = max(time.perf_counter() - t0, 1e-7)
    return max(1, math.ceil(min_batch / first))


def interleaved(fns: Dict[str, Callable[[], Any]], rounds: int, min_batch: float) -> Dict[str, List[float]]:
    """Seconds per call of each fn, one sample per round; the fns take turns within every round (GC off)."""
    runs = {name: batch_size(fn, min_batch) for name, fn in fns.items()}
    samples: Dict[str, List[float]] = {name: [] for name in fns}
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        for _ in range(rounds):
            for name, fn in fns.items():
                t0 = time.perf_counter()
                for _ in range(runs[name]):
                    fn()
                samples[name].append((time.perf_counter() - t0) / runs[name])
    finally:
        if was_enabled:
            gc.enable()
    return samples


def python_floor(force_calls: int, rate_calls: int, rounds: int) -> float:
    """Best time of calling dahl_force force_calls times and dahl_rate rate_calls times from a Python loop."""
    v, n, z = 0.3, A.F_N, 1e-4
    best = math.inf
    for _ in range(rounds):
        t0 = time.perf_counter()
        for _ in range(force_calls):
            dahl_force(v, n, z)
        for _ in range(rate_calls):
            dahl_rate(v, n, z)
        best = min(best, time.perf_counter() - t0)
    return best


def measure(method: str, rtol: float, rounds: int, min_batch: float, log: Callable[[str], None]) -> Dict[str, Any]:
    cpp_law = fs.Dahl(MU, K_T)
    python_law = fs.CallableLaw(dahl_force, dahl_rate, name="dahl_py")
    counted = Counted()
    counted_result = run(fs.CallableLaw(counted.force, counted.rate), method, rtol)
    reference, mine = run(cpp_law, method, rtol), run(python_law, method, rtol)
    calls = counted.force_calls + counted.rate_calls
    log(f"  {method}: {calls:,} law calls; timing {rounds} interleaved rounds ...")
    samples = interleaved({"dahl": lambda: run(cpp_law, method, rtol),
                           "callable": lambda: run(python_law, method, rtol)}, rounds, min_batch)
    best = {name: min(s) for name, s in samples.items()}
    floor = python_floor(counted.force_calls, counted.rate_calls, max(3, rounds // 2))
    extra = best["callable"] - best["dahl"]
    rhs_ratio = mine.stats["rhs_evaluations"] / reference.stats["rhs_evaluations"]
    calls_alone = best["callable"] - best["dahl"] * rhs_ratio  # fs.Dahl's time scaled to as many evaluations
    return {
        "method": method, "rtol": rtol,
        "mean_friction": {"dahl": mean_friction(reference), "callable": mean_friction(mine)},
        "counted_run_identical": mean_friction(counted_result) == mean_friction(mine),
        "stats": {"dahl": reference.stats, "callable": mine.stats},
        "force_calls": counted.force_calls, "state_derivative_calls": counted.rate_calls, "law_calls": calls,
        "seconds": best, "samples": samples, "slowdown": best["callable"] / best["dahl"],
        "per_call_seconds": extra / calls, "per_call_seconds_same_evaluations": calls_alone / calls,
        "python_floor_seconds": floor, "python_floor_per_call_seconds": floor / calls,
        "bridge_per_call_seconds": (calls_alone - floor) / calls,
    }


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--methods", default=",".join(METHODS[:2]),
                        help=f"comma-separated integrators ({', '.join(METHODS)}); default dormand_prince,cvode_bdf")
    parser.add_argument("--rtol", type=float, default=1e-8, help="relative tolerance (atol = 1e-4 rtol); 1e-8")
    parser.add_argument("--rounds", type=int, default=7, help="interleaved timing rounds; best of them (7)")
    parser.add_argument("--min-batch", type=float, default=0.2, help="seconds each batch of runs lasts at least")
    parser.add_argument("--quick", action="store_true", help="a smoke run: 1 round, no batching")
    parser.add_argument("--json", type=Path, help="also write the numbers to this file")
    args = parser.parse_args(argv)
    methods = [m.strip() for m in args.methods.split(",") if m.strip()]
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        parser.error(f"--methods: unknown {', '.join(unknown)} ({', '.join(METHODS)})")
    rounds, min_batch = (1, 0.0) if args.quick else (max(1, args.rounds), args.min_batch)

    def log(message: str) -> None:
        print(message, file=sys.stderr, flush=True)

    info = machine()
    log(f"fs.CallableLaw against fs.Dahl{' (--quick)' if args.quick else ''}: {info['date']}, {info['cpu_model']}, "
        f"nproc {info['nproc']}, load {info['load_average_at_start']}")
    results = [measure(m, args.rtol, rounds, min_batch, log) for m in methods]

    rows = []
    for r in results:
        rows.append([r["method"], fmt_time(r["seconds"]["dahl"]), fmt_time(r["seconds"]["callable"]),
                     f"{r['slowdown']:.1f}×", f"{r['force_calls']:,} + {r['state_derivative_calls']:,}",
                     f"{r['stats']['dahl']['rhs_evaluations']:,} / {r['stats']['callable']['rhs_evaluations']:,}",
                     f"{r['per_call_seconds'] * 1e6:.3f} µs",
                     f"{r['per_call_seconds_same_evaluations'] * 1e6:.3f} µs",
                     f"{r['python_floor_per_call_seconds'] * 1e6:.3f} µs",
                     f"{r['bridge_per_call_seconds'] * 1e6:.3f} µs",
                     f"{r['mean_friction']['dahl']:.6g} / {r['mean_friction']['callable']:.6g}"])
    text = "\n".join([
        f"## fs.CallableLaw against fs.Dahl{' (--quick: a smoke run)' if args.quick else ''}", "",
        f"Machine: {info['cpu_model']}, nproc {info['nproc']}, {info['platform']}; load average at start "
        f"{', '.join(f'{x:.2f}' for x in info['load_average_at_start'] or [])}. Date: {info['date']}. "
        + ", ".join(f"{k} {v}" for k, v in info["versions"].items()) + ".", "",
        f"{A.title.split(': ')[0][3:]}, {A.t_end:g} s, rtol {args.rtol:.0e}; best of {rounds} interleaved "
        f"round{'s' if rounds > 1 else ''} per law. Per call = (CallableLaw run - fs.Dahl run) / law calls; at "
        "equal evaluations: fs.Dahl's time scaled to the CallableLaw run's rhs evaluations first; the Python floor "
        "is the two functions called from a Python loop; the bridge is per call at equal evaluations minus the "
        "floor.", "",
        markdown_table(["method", "fs.Dahl", "CallableLaw", "slowdown", "law calls (force + dz/dt)",
                        "rhs evaluations (Dahl / Callable)", "per call", "per call at equal evaluations",
                        "Python floor", "bridge",
                        "mean friction [N] (Dahl / Callable)"], rows), ""])
    print(text)
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({"machine": info, "results": results}, indent=1, default=str))
    return 0


if __name__ == "__main__":
    sys.exit(main())
