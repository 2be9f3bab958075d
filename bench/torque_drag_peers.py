#!/usr/bin/env python3
"""Soft-string torque and drag against the Python peers (issue 14, item 6): one operation on a 6 km well at 1 m
elements, side by side in one run.

The well: vertical to 2000 m, built at 3 deg/30 m to horizontal (heel at 2954.9 m MD), a lateral to 6000 m,
azimuth 0; 5" x 4.276" drill pipe (SG 7.85) over the whole 6000 m; SG 1.2 mud; friction factor 0.3 everywhere.
The operation: pulling out of the hole (pick-up hook load), bit off bottom. Every tool gets the same 6001 nodes
(frictionsim's SoftString with 6000 elements; the peers' survey stations are those nodes):

  frictionsim C++       bench/torque_drag.bench.cpp (Google Benchmark; SoftString::run reusing its result), both
                        methods: Johancsik's step and Aadnoy's closed form
  frictionsim Python    fs.SoftString(...).run("trip_out"), both methods where the build has SoftString(method=)
  welleng               welleng.torque_drag.TorqueDrag(survey, wellbore, bha, fluid_density): its constructor
                        computes pick-up, slack-off and rotating in one go (no single operation to ask for)
  torque-drag           torque_drag.calc(trajectory, dimensions, densities, case="hoisting", fric=[0.3] * n):
                        friction as a list (a scalar would be replaced by 0.24; tests/python/
                        test_torque_drag_peers.py)

Times are CPU times (time.process_time for Python; Google Benchmark's cpu_time for C++), the median of
--repeats repetitions, each repetition a batch of calls long enough to time (>= 50 ms, or one call). The set-up
(surveys, models, trajectories) is outside the timing: each tool is timed on what it recomputes per operation.
The hook loads are printed beside the times and agree up to the tools' conventions (tests/python/test_wells.py
and test_torque_drag_peers.py reproduce each): torque-drag within 0.1 % (g = 9.81, an inch of 1/39.37 m, one
course of pipe weight missing); welleng's rotating hook load to round-off, its pick-up some 12 % above in this
90-degree build, where it adds the tension's and the weight's side forces instead of letting them cancel.

Prints a table with the ratio of each time to frictionsim C++ (Johancsik) and writes torque_drag_peers.csv to
--out (a directory, default out/bench). scripts/bench runs it after building bench/torque_drag.
"""

from __future__ import annotations

import argparse
import csv
import datetime as _dt
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, List, Optional

import numpy as np

import frictionsim as fs

REPO = Path(__file__).resolve().parents[1]
LENGTH, ELEMENTS, MU, MUD_SG, STEEL_SG = 6000.0, 6000, 0.3, 1.2, 7.85
OD, ID, HOLE = 5.0 * 0.0254, 4.276 * 0.0254, 0.2159  # m
G = 9.80665


@dataclass
class Row:
    tool: str
    method: str
    operation: str
    cpu_seconds: float  # per operation, median
    hook_load_kN: float
    repetitions: int
    note: str = ""


def survey() -> fs.Survey:
    radius = 30.0 / (3.0 * math.pi / 180.0)
    heel = 2000.0 + radius * math.pi / 2.0
    return fs.Survey(np.array([0.0, 2000.0, heel, LENGTH]), np.array([0.0, 0.0, math.pi / 2, math.pi / 2]),
                     np.zeros(4))


def pipe() -> fs.PipeSection:
    return fs.PipeSection(length=LENGTH, outer_diameter=OD, inner_diameter=ID, density=STEEL_SG * 1000.0)


def conditions() -> dict:
    return dict(mud_density=MUD_SG * 1000.0, open_hole_friction=MU, cased_hole_friction=MU, hole_diameter=HOLE)


def cpu_time(call: Callable[[], object], repeats: int, batch_seconds: float = 0.05) -> float:
    """Median CPU seconds per call over `repeats` batches; a batch repeats the call until it lasts batch_seconds."""
    start = time.process_time()
    call()
    once = max(time.process_time() - start, 1e-7)
    batch = max(1, int(batch_seconds / once))
    times = []
    for _ in range(repeats):
        start = time.process_time()
        for _ in range(batch):
            call()
        times.append((time.process_time() - start) / batch)
    return statistics.median(times)


def has_method_keyword() -> bool:
    try:
        fs.SoftString(fs.Survey([0.0, 10.0], [0.0, 0.0], [0.0, 0.0]), fs.DrillString([fs.PipeSection(length=10.0)]),
                      1, method="aadnoy")
    except TypeError:
        return False
    return True


# ------------------------------------------------------------------------------------------------------ the tools
def bench_cpp(binary: Path, repeats: int) -> List[Row]:
    if not binary.exists():
        print(f"  frictionsim C++: {binary} not built (cmake --build <dir> --target bench_torque_drag): skipped")
        return []
    # trip_out is Operation 1; the second argument the method (0 johancsik, 1 aadnoy)
    out = subprocess.run([str(binary), "--benchmark_filter=BM_torque_drag/1/", "--benchmark_format=json",
                          f"--benchmark_repetitions={repeats}", "--benchmark_report_aggregates_only=true"],
                         check=True, capture_output=True, text=True).stdout
    rows = []
    for b in json.loads(out)["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
        method = "aadnoy" if b["run_name"].endswith("/1") else "johancsik"
        rows.append(Row("frictionsim C++", method, "trip_out", b["cpu_time"] * scale, b["hook_kN"], repeats))
    return rows


def bench_python(repeats: int) -> List[Row]:
    rows = []
    methods = ["johancsik"] + (["aadnoy"] if has_method_keyword() else [])
    for method in methods:
        kwargs = {} if method == "johancsik" else {"method": method}
        model = fs.SoftString(survey(), fs.DrillString([pipe()]), ELEMENTS, **kwargs)
        c = conditions()
        seconds = cpu_time(lambda: model.run("trip_out", **c), repeats)
        rows.append(Row("frictionsim Python", method, "trip_out", seconds, model.run("trip_out", **c).hook_load / 1e3,
                        repeats, "result arrays copied to NumPy"))
    if len(methods) == 1:
        print("  frictionsim Python: this build has no SoftString(method=...): Aadnoy's method from C++ only")
    return rows


def nodes():
    model = fs.SoftString(survey(), fs.DrillString([pipe()]), ELEMENTS)
    depth = np.asarray(model.node_depths)
    at = survey().interpolate(depth)
    return depth, np.asarray(at["inclination"]), np.asarray(at["azimuth"])


def bench_welleng(repeats: int) -> List[Row]:
    try:
        import welleng as we
        from welleng.architecture import BHA, WellBore
        from welleng.torque_drag import TorqueDrag
    except ImportError:
        print("  welleng: not installed (pip install 'frictionsim[wells]'): skipped")
        return []
    depth, inc, azi = nodes()
    hole = WellBore("hole", 0.0, LENGTH, method="top_down")
    hole.add_section(id=HOLE, coeff_friction_sliding=MU, bottom=LENGTH)
    string = BHA("pipe", 0.0, LENGTH, method="top_down")
    p = pipe()
    string.add_section(od=OD, id=ID, unit_weight=p.mass_per_length * G, density=STEEL_SG, bottom=LENGTH)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        their_survey = we.survey.Survey(md=depth, inc=inc, azi=azi, deg=False)
        result = TorqueDrag(their_survey, hole, string, fluid_density=MUD_SG)
        seconds = cpu_time(lambda: TorqueDrag(their_survey, hole, string, fluid_density=MUD_SG), repeats)
    # the check of like for like: with no axial friction (rotating) the hook loads agree to round-off; the pick-up
    # differs in the build only, where welleng adds the tension's and the weight's side forces (|F kappa + w sin I|)
    # instead of letting them cancel (tests/python/test_wells.py reproduces both)
    ours = fs.SoftString(survey(), fs.DrillString([p]), ELEMENTS).run("rotating_off_bottom", **conditions())
    print(f"  welleng: rotating hook load {result.tension['rotating'][0] / 1e3:.4f} kN, frictionsim "
          f"{ours.hook_load / 1e3:.4f} kN; its pick-up differs by its build-section convention")
    return [Row("welleng", "TorqueDrag", "pickup+slackoff+rotating", seconds, result.tension["pickup"][0] / 1e3,
                repeats, f"welleng {we.__version__}; all three operations per call; pick-up adds the build's "
                         "tension and weight side forces")]


def bench_torque_drag(repeats: int) -> List[Row]:
    try:
        import torque_drag as td
    except ImportError:
        print("  torque-drag: not installed (pip install 'frictionsim[bench]'): skipped")
        return []
    depth, inc, azi = nodes()
    inc_deg, azi_deg = np.degrees(inc), np.degrees(azi)
    trajectory = []
    for i in range(len(depth)):
        delta = ({"md": 0.0, "inc": 0.0, "azi": 0.0} if i == 0 else
                 {"md": float(depth[i] - depth[i - 1]), "inc": float(inc_deg[i] - inc_deg[i - 1]),
                  "azi": float(azi_deg[i] - azi_deg[i - 1])})
        trajectory.append({"md": float(depth[i]), "inc": float(inc_deg[i]), "azi": float(azi_deg[i]),
                           "delta": delta})
    dims = {"pipe": {"od": 5.0, "id": 4.276, "length": LENGTH, "shoe": LENGTH}, "odAnn": HOLE / 0.0254}
    fric = [MU] * len(depth)

    def call():
        return td.calc(trajectory, dims, densities={"rhof": MUD_SG, "rhod": STEEL_SG}, case="hoisting", fric=fric)

    seconds = cpu_time(call, repeats)
    return [Row("torque-drag", "calc", "hoisting", seconds, call().force["hoisting"][0], repeats,
                "torque-drag 0.1.1; fric as a list (a scalar becomes 0.24)")]


# ------------------------------------------------------------------------------------------------------ report
def report(rows: List[Row], out: Path) -> None:
    reference = next((r for r in rows if r.tool == "frictionsim C++" and r.method == "johancsik"), None)
    base = reference.cpu_seconds if reference else None
    hook = reference.hook_load_kN if reference else None
    header = f"{'tool':<20} {'method':<11} {'operation':<26} {'CPU time / op':>14} {'x C++':>9} {'hook load kN':>13}"
    print(header)
    print("-" * len(header))
    for r in rows:
        ratio = f"{r.cpu_seconds / base:9.1f}" if base else f"{'-':>9}"
        t = r.cpu_seconds
        shown = f"{t * 1e6:10.1f} us" if t < 1e-3 else f"{t * 1e3:10.2f} ms" if t < 1.0 else f"{t:10.3f} s "
        dev = f" ({(r.hook_load_kN / hook - 1) * 100:+.2f} %)" if hook else ""
        print(f"{r.tool:<20} {r.method:<11} {r.operation:<26} {shown:>14} {ratio} {r.hook_load_kN:13.3f}{dev}")
    out.mkdir(parents=True, exist_ok=True)
    path = out / "torque_drag_peers.csv"
    with path.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["tool", "method", "operation", "cpu_seconds_per_operation", "ratio_to_frictionsim_cpp",
                         "hook_load_kN", "repetitions", "note"])
        for r in rows:
            writer.writerow([r.tool, r.method, r.operation, f"{r.cpu_seconds:.6g}",
                             f"{r.cpu_seconds / base:.4g}" if base else "", f"{r.hook_load_kN:.6f}", r.repetitions,
                             r.note])
    print(f"\nwritten: {path}")


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bench", type=Path, default=REPO / "build" / "bench" / "torque_drag",
                        help="the Google Benchmark binary of bench/torque_drag.bench.cpp")
    parser.add_argument("--out", type=Path, default=REPO / "out" / "bench", help="directory for the CSV")
    parser.add_argument("--repeats", type=int, default=7, help="repetitions (the median is reported)")
    parser.add_argument("--quick", action="store_true", help="3 repetitions")
    args = parser.parse_args(argv)
    repeats = 3 if args.quick else args.repeats
    print(f"torque and drag, 6 km well at 1 m elements, pulling out; {_dt.datetime.now().isoformat(timespec='seconds')}"
          f"; {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.2f}; "
          f"Python {platform.python_version()}, frictionsim {getattr(fs, '__version__', '?')}")
    rows: List[Row] = []
    for bench in (lambda: bench_cpp(args.bench, repeats), lambda: bench_python(repeats),
                  lambda: bench_welleng(repeats), lambda: bench_torque_drag(repeats)):
        rows += bench()
    report(rows, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
