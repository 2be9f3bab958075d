#!/usr/bin/env python3
"""Aarsnes-Shor Well B side by side in one run: frictionsim's Moreau-Jean string against the published explicit
scheme in plain C, as ratios (issue 22 item 3).

Three programs, each in its own process per round, in alternating order (round k starts with a different one), the
best CPU time of the rounds kept for each:

  C port      build/bench/reference/aarsnes_shor (bench/reference/aarsnes_shor.c, -O2): the published scheme at its
              grid (1000 cells), its CFL sub-step (1/1200 s) and its PI sampled every 0.01 s;
  C++         build/bench/wellb_side_by_side (bench/wellb_side_by_side.cpp): TorsionalString::simulate on the same
              well (collar as published, collar wave speed as the code's) at --elements N and each --steps h;
  Python      the same run through frictionsim's Python binding (fs.aarsnes_shor_well_b, fs.simulate), timed
              around the call with time.process_time (skipped, and said so, where the binding is not there).

Each program times only its simulation (its CPU time, CLOCK_PROCESS_CPUTIME_ID / process_time), from rest to
--t-end (150 s), and reports the limit cycle (bit peak, period, motor torque extremes, after 15 s): the same well
is checked (--peak-tolerance, --period-tolerance) before any ratio is printed. A ratio is the C port's time over
the other's (above 1: faster than the C port). --convergence adds the grid study: the bit peak at 250 .. 4000
elements and steps 10 .. 1 ms against 4000 elements at 0.5 ms, the coarsest grid within 1 % and its ratio.
--check runs the physics comparison only (60 s), for ctest. Writes --out/wellb_side_by_side.{md,json}.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

PYTHON_SIDE = r"""
import json, sys, time
import frictionsim as fs
elements, step, t_end = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
# HOOK (issue 22 items 1-2, helpers pyfield / engine): the Python entry of the Moreau-Jean string,
# fs.aarsnes_shor_well_b -> fs.TorsionalString run by fs.simulate(..., method="moreau_jean", step=). Where the binding
# is not there this raises, and the harness reports the Python side as not run.
model = fs.aarsnes_shor_well_b(elements=elements)
samples = round(t_end / 0.01)
outputs = [k * 0.01 for k in range(samples + 1)]  # as the C++ run records: every 0.01 s
start = time.process_time()
result = fs.simulate(model, t_end, method="moreau_jean", step=step, output_times=outputs)
cpu = time.process_time() - start
print(json.dumps({"cpu_seconds": cpu, "time": [float(t) for t in result.t],
                  "bit_speed": [float(w) for w in result["bit_speed"]]}))
"""


def run_json(cmd: list[str]) -> dict:
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def cycle_means(time_s: list[float], bit: list[float]) -> tuple[float, float, int]:
    """Mean bit peak and period over the cycles starting after 15 s (a cycle starts when the bit passes 5 rad/s
    after resting below 0.5 rad/s), as aarsnes_shor.c and wellb_side_by_side.cpp count them."""
    peak = period = 0.0
    cycles, armed, last = 0, True, -1
    for k, w in enumerate(bit):
        if w < 0.5:
            armed = True
        if armed and w > 5.0:
            armed = False
            if last >= 0 and time_s[last] >= 15.0:
                peak += max(bit[last:k])
                period += time_s[k] - time_s[last]
                cycles += 1
            last = k
    return (peak / cycles, period / cycles, cycles) if cycles else (0.0, 0.0, 0)


class Side:
    """One program of the comparison: its command and the best of its rounds."""

    def __init__(self, label: str, cmd: list[str] | None, python: bool = False):
        self.label, self.cmd, self.python = label, cmd, python
        self.times: list[float] = []
        self.summary: dict = {}
        self.error = ""

    def round(self) -> None:
        if self.error:
            return
        try:
            d = run_json(self.cmd)
        except (subprocess.CalledProcessError, json.JSONDecodeError, IndexError) as e:
            err = getattr(e, "stderr", "") or str(e)
            self.error = err.strip().splitlines()[-1] if err.strip() else str(e)
            return
        if self.python:
            peak, period, cycles = cycle_means(d.pop("time"), d.pop("bit_speed"))
            d.update(bit_peak=peak, period=period, cycles=cycles)
        self.times.append(d["cpu_seconds"])
        self.summary = d

    @property
    def best(self) -> float:
        return min(self.times) if self.times else float("nan")


def same_well(a: dict, b: dict, peak_tol: float, period_tol: float) -> list[str]:
    problems = []
    for key, tol in (("bit_peak", peak_tol), ("period", period_tol)):
        rel = abs(a[key] - b[key]) / abs(b[key]) if b.get(key) else float("inf")
        if not rel <= tol:
            problems.append(f"{key}: {a[key]:.4f} against the C port's {b[key]:.4f} ({100 * rel:.2f} % > {100 * tol} %)")
    return problems


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build-dir", default="build")
    ap.add_argument("--python", default=sys.executable, help="the interpreter with frictionsim installed")
    ap.add_argument("--t-end", type=float, default=150.0)
    ap.add_argument("--elements", type=int, default=1000)
    ap.add_argument("--steps", default="0.002,0.005,0.01", help="frictionsim's steps h [s], comma-separated")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--peak-tolerance", type=float, default=0.02)
    ap.add_argument("--period-tolerance", type=float, default=0.03)
    ap.add_argument("--convergence", action="store_true", help="also the bit peak against the grid and the step")
    ap.add_argument("--check", action="store_true", help="the physics comparison only (exit 1 on a mismatch)")
    ap.add_argument("--out", default="out/bench")
    args = ap.parse_args()

    build = Path(args.build_dir)
    c_port = build / "bench" / "reference" / "aarsnes_shor"
    cpp = build / "bench" / "wellb_side_by_side"
    t_end = 60.0 if args.check else args.t_end
    steps = [float(s) for s in args.steps.split(",")]

    sides = [Side("C port (published scheme, 1000 cells, 1/1200 s)", [str(c_port), "--t-end", str(t_end)])]
    for h in steps:
        sides.append(Side(f"frictionsim C++, {args.elements} elements, h = {1e3 * h:g} ms",
                          [str(cpp), "--elements", str(args.elements), "--step", repr(h), "--t-end", str(t_end)]))
    if not args.check:
        for h in steps:
            sides.append(Side(f"frictionsim Python, {args.elements} elements, h = {1e3 * h:g} ms",
                              [args.python, "-c", PYTHON_SIDE, str(args.elements), repr(h), str(t_end)], python=True))

    rounds = 1 if args.check else args.rounds
    for k in range(rounds):
        order = sides[k % len(sides):] + sides[:k % len(sides)]  # alternate who runs first
        for s in order:
            s.round()
        print(f"round {k + 1}/{rounds}: " + ", ".join(f"{s.best:.3f}" for s in sides), file=sys.stderr)

    ref = sides[0]
    if ref.error:
        print(f"the C port did not run: {ref.error}", file=sys.stderr)
        return 1
    problems = []
    for s in sides[1:]:
        if s.times:
            problems += [f"{s.label}: {p}" for p in same_well(s.summary, ref.summary, args.peak_tolerance,
                                                               args.period_tolerance)]
    cpp_sides = [s for s in sides[1:] if not s.python]
    if any(s.error for s in cpp_sides):
        problems += [f"{s.label}: {s.error}" for s in cpp_sides if s.error]
    if problems:
        print("not the same well:\n  " + "\n  ".join(problems), file=sys.stderr)
        return 1
    if args.check:
        for s in sides:
            print(f"{s.label}: bit peak {s.summary['bit_peak']:.4f} rad/s, period {s.summary['period']:.3f} s, "
                  f"motor torque {s.summary['min_motor_torque'] / 1e3:.2f}-{s.summary['max_motor_torque'] / 1e3:.2f} kN m")
        print("1 passed, 0 failed")
        return 0

    lines = [f"Aarsnes-Shor Well B, {t_end:g} s from rest, CPU time of the simulation, best of {rounds} alternating "
             f"rounds ({time.strftime('%Y-%m-%d %H:%M')}, {platform.node()}, {os.cpu_count()} CPUs, load "
             f"{os.getloadavg()[0]:.1f})", "",
             "| program | best CPU s | x the C port's speed | bit peak rad/s | period s | motor torque kN m |",
             "|---|---|---|---|---|---|"]
    for s in sides:
        if s.error or not s.times:
            lines.append(f"| {s.label} | not run: {s.error} | | | | |")
            continue
        d = s.summary
        torque = (f"{d['min_motor_torque'] / 1e3:.2f}-{d['max_motor_torque'] / 1e3:.2f}"
                  if "max_motor_torque" in d else "")
        lines.append(f"| {s.label} | {s.best:.3f} | {ref.best / s.best:.2f} | {d['bit_peak']:.3f} | "
                     f"{d['period']:.3f} | {torque} |")
    for h in steps:
        c = next(s for s in sides if not s.python and s.label.endswith(f"h = {1e3 * h:g} ms") and s is not ref)
        p = next((s for s in sides if s.python and s.label.endswith(f"h = {1e3 * h:g} ms")), None)
        if p is not None and p.times and c.times:
            lines.append(f"\nPython / C++ at h = {1e3 * h:g} ms: {p.best / c.best:.3f}")

    report = {"t_end": t_end, "rounds": rounds,
              "sides": [{"label": s.label, "best_cpu_seconds": s.best, "all": s.times, "summary": s.summary,
                         "error": s.error} for s in sides]}
    if args.convergence:
        lines += ["", convergence(cpp, ref, t_end, report)]
    text = "\n".join(lines)
    print(text)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "wellb_side_by_side.md").write_text(text + "\n")
    (out / "wellb_side_by_side.json").write_text(json.dumps(report, indent=1) + "\n")
    return 0


def convergence(cpp: Path, ref: Side, t_end: float, report: dict) -> str:
    """The bit peak against N and h, relative to 4000 elements at 0.5 ms; each run once (its time a rough guide)."""
    fine = run_json([str(cpp), "--elements", "4000", "--step", "0.0005", "--t-end", str(t_end)])
    rows, table = [], ["| elements | h ms | bit peak rad/s | vs 4000 / 0.5 ms | period s | CPU s | x the C port |",
                       "|---|---|---|---|---|---|---|"]
    for n in (250, 500, 1000, 2000, 4000):
        for h in (0.01, 0.005, 0.002, 0.001):
            d = run_json([str(cpp), "--elements", str(n), "--step", repr(h), "--t-end", str(t_end)])
            rel = d["bit_peak"] / fine["bit_peak"] - 1.0
            rows.append(dict(elements=n, step=h, bit_peak=d["bit_peak"], relative=rel, period=d["period"],
                             cpu_seconds=d["cpu_seconds"]))
            table.append(f"| {n} | {1e3 * h:g} | {d['bit_peak']:.4f} | {100 * rel:+.2f} % | {d['period']:.3f} | "
                         f"{d['cpu_seconds']:.3f} | {ref.best / d['cpu_seconds']:.2f} |")
    report["convergence"] = {"reference": fine, "runs": rows}
    within = [r for r in rows if abs(r["relative"]) <= 0.01]
    cheapest = min(within, key=lambda r: r["cpu_seconds"]) if within else None
    head = (f"Convergence (reference 4000 elements, h = 0.5 ms: bit peak {fine['bit_peak']:.4f} rad/s, period "
            f"{fine['period']:.3f} s; the C port at its grid: {ref.summary['bit_peak']:.4f} rad/s, "
            f"{100 * (ref.summary['bit_peak'] / fine['bit_peak'] - 1):+.2f} %)")
    tail = (f"\nCheapest run within 1 % of the reference: {cheapest['elements']} elements at h = "
            f"{1e3 * cheapest['step']:g} ms, {ref.best / cheapest['cpu_seconds']:.1f} x the C port's speed (one run)"
            if cheapest else "\nNo run within 1 %.")
    return head + "\n\n" + "\n".join(table) + tail


if __name__ == "__main__":
    sys.exit(main())
