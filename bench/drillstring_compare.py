#!/usr/bin/env python3
"""Field-scale drill strings, measured side by side in one run (issue 13, item 5); writes a Markdown table.

1. Runs bench/drillstring.bench.cpp's binary (Google Benchmark, JSON) and reads, per benchmark, the CPU time of one
   run and the counters (steps, rhs, events, the answers: bit and top-drive angles at t_end, bit peak speed).
2. Fits the exponent p of cost per simulated second ~ N^p over N = 10 .. 1000 for each integrator on the
   event-driven string (string_rig/<integrator>/N) and for Moreau-Jean time-stepping (aarsnes_shor/sweep_...).
3. Runs the same 300-element, 3 km string in SciPy's solve_ivp (BDF with jac_sparsity and a terminal event per
   switch, restarted after each), written here from the model's equations (drillstring/string_rig.hpp's header
   comment, sections.hpp's lumping, bit_rock.hpp's velocity-weakening bit), not from the C++ code, over the
   window of bench's string_rig/window4s_* runs (the first 4 s: the torsional wave runs down the string and its
   300 wall contacts break free one by one) and, with --full, over the whole 60 s.
4. Ratios at equal accuracy: each run's answer (top-drive angle at the window's end, and the bit angle at 60 s) is
   compared with Dormand-Prince at rtol 1e-10 (string_rig/window4s_reference, string_rig/reference).

Run by nobody in CI (minutes; quiet machine wanted):
    .venv/bin/python bench/drillstring_compare.py [--bench build-bench/bench/drillstring] [--json saved.json]
        [--full] [--out out/bench]
It prints the table and writes drillstring.md and drillstring.json to --out.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path
from typing import Dict, List, Optional, Tuple

import numpy as np

REPO = Path(__file__).resolve().parents[1]

# ---- the model, from its equations ---------------------------------------------------------------------------------
#   J_i w_i' = S_i - T_wall,i [- T_bit at node N],  S_i = tau_i - tau_{i-1} [+ T_m at node 0],
#   tau_e = k_e (th_{e+1} - th_e) + beta k_e (w_{e+1} - w_e),  T_m = k_p (w_set - w_0) + k_i int (w_set - w_0) dt.
# Wall contact i (nodes 1 .. N-1): Coulomb, slipping torque r_i mu N_i sgn, stuck while |S_i| <= r_i mu_s N_i
# (Leine's switch model: a slipping node reaching w = 0 sticks if it can be held, else reverses). Bit (node N):
# T = c_b w + R_b W mu_b(w) sgn, mu_b = mu_cb + (mu_sb - mu_cb) exp(-gamma |w| / v_f), stuck while
# |S_N| <= R_b W mu_sb. Lumped string: N equal elements; each element's inertia and mass half to each end node;
# an element across a section boundary is its pieces' springs in series; a boundary node touches with the larger OD.

GRAVITY = 9.80665


class Section:
    def __init__(self, od: float, id_: float, length: float, e: float = 210e9, g: float = 80.8e9, rho: float = 7850.0):
        self.od, self.id, self.length, self.e, self.g, self.rho = od, id_, length, e, g, rho

    @property
    def area(self) -> float:
        return math.pi / 4.0 * (self.od**2 - self.id**2)

    @property
    def polar(self) -> float:
        return math.pi / 32.0 * (self.od**4 - self.id**4)


class ThreeKmString:
    """bench/drillstring.bench.cpp's three_km_string(N): 2800 m of 5" pipe, 200 m of 6.5" collars, 0.5 rad hole."""

    inclination = 0.5
    mud_density = 1200.0
    beta = 2e-3
    top_drive_inertia = 500.0
    kp, ki, w_set, torque_limit = 3e3, 1e3, 3.0, 6e4
    mu, mu_static = 0.2, 0.3
    bit_radius, mu_cb, mu_sb, gamma_b, v_f, c_b, wob = 0.155575, 0.5, 0.8, 0.9, 1.0, 50.0, 1.5e5

    def __init__(self, elements: int):
        self.sections = [Section(0.127, 0.1086, 2800.0), Section(0.1651, 0.0714, 200.0)]
        n = self.n = elements
        total = sum(s.length for s in self.sections)
        dx = total / n
        inertia = np.zeros(n + 1)
        buoyed = np.zeros(n + 1)
        k = np.zeros(n)
        for e in range(n):
            a, b = total * e / n, total * (e + 1) / n
            compliance = j = m = 0.0
            top = 0.0
            for s in self.sections:
                lo, hi = max(a, top), min(b, top + s.length)
                top += s.length
                if hi <= lo:
                    continue
                compliance += (hi - lo) / (s.g * s.polar)
                j += (hi - lo) * s.rho * s.polar
                m += (hi - lo) * (s.rho - self.mud_density) * s.area
            k[e] = 1.0 / compliance
            inertia[e] += j / 2
            inertia[e + 1] += j / 2
            buoyed[e] += m / 2
            buoyed[e + 1] += m / 2
        inertia[0] += self.top_drive_inertia
        radius = np.zeros(n + 1)
        for i in range(n + 1):
            at, top = dx * i, 0.0
            for s in self.sections:
                if top - 1e-9 * dx <= at <= top + s.length + 1e-9 * dx:
                    radius[i] = max(radius[i], s.od / 2)
                top += s.length
        self.k, self.inertia = k, inertia
        normal = buoyed * GRAVITY * math.sin(self.inclination)
        self.contacts = np.arange(1, n)  # node N carries the bit
        self.kinetic = (radius * self.mu * normal)[1:n]
        self.static = (radius * self.mu_static * normal)[1:n]
        self.bit_static = self.bit_radius * self.wob * self.mu_sb

    # state y = [int e, th_0, w_0, th_1, w_1, ...]: banded, as the C++ rig orders it
    def size(self) -> int:
        return 1 + 2 * (self.n + 1)

    def shaft_torques(self, y: np.ndarray) -> np.ndarray:
        th, w = y[1::2], y[2::2]
        tau = self.k * (np.diff(th) + self.beta * np.diff(w))
        s = np.zeros(self.n + 1)
        s[:-1] += tau
        s[1:] -= tau
        s[0] += self.kp * (self.w_set - w[0]) + self.ki * y[0]
        return s

    def bit_slip_torque(self, w: float, direction: int) -> float:
        mu_b = self.mu_cb + (self.mu_sb - self.mu_cb) * math.exp(-self.gamma_b * abs(w) / self.v_f)
        return self.c_b * w + self.bit_radius * self.wob * mu_b * direction

    def rhs(self, y: np.ndarray, modes: np.ndarray, bit_mode: int) -> np.ndarray:
        """modes: per wall contact -1, 0 (stuck), +1; bit_mode likewise."""
        s = self.shaft_torques(y)
        w = y[2::2]
        acc = s.copy()
        acc[1:-1] -= self.kinetic * modes
        stuck = np.zeros(self.n + 1, dtype=bool)
        stuck[1:-1] = modes == 0
        if bit_mode == 0:
            stuck[-1] = True
        else:
            acc[-1] -= self.bit_slip_torque(w[-1], bit_mode)
        acc /= self.inertia
        acc[stuck] = 0.0
        dy = np.empty_like(y)
        dy[0] = self.w_set - w[0]
        dy[1::2] = np.where(stuck, 0.0, w)
        dy[2::2] = acc
        return dy

    def guards(self, y: np.ndarray, modes: np.ndarray, bit_mode: int) -> np.ndarray:
        """One per contact and the bit, scaled to O(1), positive inside the current mode: a stuck contact until
        |S| reaches its static bound, a slipping one until its speed reaches zero."""
        s = self.shaft_torques(y)
        w = y[2::2]
        g = np.empty(self.n)
        wall = np.where(modes == 0, 1.0 - np.abs(s[1:-1]) / self.static, modes * w[1:-1])
        g[:-1] = wall
        g[-1] = 1.0 - abs(s[-1]) / self.bit_static if bit_mode == 0 else bit_mode * w[-1]
        return g

    def jac_sparsity(self):
        from scipy.sparse import lil_matrix

        m = lil_matrix((self.size(), self.size()), dtype=np.int8)
        m[0, 2] = 1
        m[2, 0] = 1
        for i in range(self.n + 1):
            th, w = 1 + 2 * i, 2 + 2 * i
            m[th, w] = 1
            for j in (i - 1, i, i + 1):
                if 0 <= j <= self.n:
                    m[w, 1 + 2 * j] = 1
                    m[w, 2 + 2 * j] = 1
        return m.tocsr()


def scipy_run(elements: int, t_end: float, rtol: float = 1e-6, atol: float = 1e-8) -> Dict[str, float]:
    """The hybrid run: solve_ivp (BDF, jac_sparsity) until a guard reaches zero (terminal event), switch, restart."""
    from scipy.integrate import solve_ivp

    rig = ThreeKmString(elements)
    y = np.zeros(rig.size())
    modes = np.zeros(elements - 1, dtype=int)
    bit_mode = 0
    sparsity = rig.jac_sparsity()
    t, events, bit_sticks, steps, rhs_calls, max_torque = 0.0, 0, 0, 0, 0, 0.0
    bit_peak = 0.0
    started = time.process_time()
    while t < t_end:
        def f(_t, yy):
            return rig.rhs(yy, modes, bit_mode)

        def event(_t, yy):
            return float(np.min(rig.guards(yy, modes, bit_mode)))

        event.terminal = True
        event.direction = -1
        sol = solve_ivp(f, (t, t_end), y, method="BDF", rtol=rtol, atol=atol, jac_sparsity=sparsity, events=event)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {sol.t[-1]}: {sol.message}")
        steps += sol.t.size - 1
        rhs_calls += sol.nfev
        motor = rig.kp * (rig.w_set - sol.y[2]) + rig.ki * sol.y[0]
        max_torque = max(max_torque, float(np.max(np.abs(motor))))
        bit_peak = max(bit_peak, float(np.max(sol.y[-1])))
        if sol.status == 0:
            y, t = sol.y[:, -1], t_end
            break
        t, y = float(sol.t_events[0][0]), sol.y_events[0][0].copy()
        g = rig.guards(y, modes, bit_mode)
        fired = np.flatnonzero(g <= max(1e-9, float(np.min(g)) + 1e-12))
        s = rig.shaft_torques(y)
        for c in fired:  # Leine's switch model, contact by contact (they couple only through springs)
            node = c + 1
            previous = modes[c] if c < elements - 1 else bit_mode
            bound = rig.static[c] if c < elements - 1 else rig.bit_static
            if previous == 0:
                new = 1 if s[node] > 0 else -1  # breaks away in the direction of the torque on it
            else:
                new = 0 if abs(s[node]) <= bound else (1 if s[node] > 0 else -1)
            if new == 0:
                y[2 + 2 * node] = 0.0
            if c < elements - 1:
                modes[c] = new
            else:
                bit_sticks += int(new == 0)
                bit_mode = new
            events += 1
    cpu = time.process_time() - started
    if max_torque >= rig.torque_limit:
        raise RuntimeError("the motor torque reached its limit: the SciPy model leaves the limit out")
    return {
        "t_end": t_end, "cpu_s": cpu, "steps": steps, "rhs": rhs_calls, "events": events, "bit_sticks": bit_sticks,
        "top_angle": float(y[1]), "bit_angle": float(y[1 + 2 * elements]), "bit_peak": bit_peak,
    }


# ---- the benchmark binary -------------------------------------------------------------------------------------------

UNIT = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def run_bench(binary: Path, bench_filter: str) -> dict:
    cmd = [str(binary), "--benchmark_format=json", f"--benchmark_filter={bench_filter}"]
    print("running", " ".join(cmd), file=sys.stderr, flush=True)
    out = subprocess.run(cmd, check=True, stdout=subprocess.PIPE, text=True)
    return json.loads(out.stdout)


def runs_of(bench: dict) -> Dict[str, dict]:
    """name -> {cpu_s: CPU seconds of one run, and the counters}."""
    runs = {}
    for b in bench["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration":
            continue
        r = {k: v for k, v in b.items() if isinstance(v, (int, float))}
        r["cpu_s"] = b["cpu_time"] * UNIT[b.get("time_unit", "ns")]
        runs[b["name"]] = r
    return runs


def fit_exponent(points: List[Tuple[float, float]]) -> float:
    """Least-squares slope of log(cost) against log(N)."""
    x = np.log([p[0] for p in points])
    y = np.log([p[1] for p in points])
    return float(np.polyfit(x, y, 1)[0])


def family(runs: Dict[str, dict], prefix: str) -> Dict[str, List[Tuple[float, dict]]]:
    """prefix/<name>/<N>[/...] -> name -> [(N, run)]."""
    out: Dict[str, List[Tuple[float, dict]]] = {}
    for name, r in runs.items():
        parts = name.split("/")
        if parts[0] != prefix or len(parts) < 3 or parts[1].startswith(("window4s_", "full60s_")):
            continue
        out.setdefault(parts[1], []).append((float(parts[2]), r))
    for v in out.values():
        v.sort(key=lambda p: p[0])
    return out


def fmt(x: Optional[float], digits: int = 3) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return f"{x:.{digits}g}"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bench", type=Path, default=REPO / "build-bench" / "bench" / "drillstring")
    ap.add_argument("--json", type=Path, help="a saved run of the benchmark binary (--benchmark_format=json)")
    ap.add_argument("--filter", default=".", help="--benchmark_filter for the binary")
    ap.add_argument("--window", type=float, default=4.0, help="SciPy's window, s (the bench's window4s runs)")
    ap.add_argument("--full", action="store_true", help="also run SciPy over the whole 60 s")
    ap.add_argument("--no-scipy", action="store_true")
    ap.add_argument("--out", type=Path, default=REPO / "out" / "bench")
    args = ap.parse_args()

    saved = json.loads(args.json.read_text()) if args.json else None
    # a raw run of the binary, or this script's drillstring.json (whose SciPy runs are then reused)
    bench = (saved.get("bench", saved) if saved else run_bench(args.bench, args.filter))
    reused = saved if saved and "bench" in saved else {}
    runs = runs_of(bench)
    lines: List[str] = []
    ctx = bench.get("context", {})
    lines.append(f"# Drill strings (issue 13, item 5): {_dt.datetime.now().isoformat(timespec='minutes')}")
    lines.append("")
    lines.append(f"Machine: {platform.node()}, {ctx.get('num_cpus', os.cpu_count())} CPUs at "
                 f"{ctx.get('mhz_per_cpu', '?')} MHz, load {ctx.get('load_avg', '?')}; times are CPU seconds of one "
                 "run on one core (bench/drillstring.bench.cpp, this script's SciPy runs).")
    lines.append("")

    # 1. cost against N
    lines.append("## Cost per simulated second against N (3 km string, its first 10 s; Moreau-Jean: Well B, 60 s, "
                 "h = 2 ms)")
    lines.append("")
    sweeps = family(runs, "string_rig")
    mj = {k: v for k, v in family(runs, "aarsnes_shor").items() if k.startswith("sweep")}
    sizes = sorted({n for fam in (sweeps, mj) for v in fam.values() for n, _ in v})
    lines.append("| integrator | " + " | ".join(f"N = {int(n)}" for n in sizes) + " | exponent |")
    lines.append("|---|" + "---|" * (len(sizes) + 1))
    exponents = {}
    for label, fam, t_key in (("", sweeps, "t_end"), ("moreau_jean ", mj, None)):
        for name, pts in fam.items():
            cost = {n: r["cpu_s"] / (r[t_key] if t_key else 60.0) for n, r in pts}
            p = fit_exponent(list(cost.items())) if len(cost) >= 3 else float("nan")
            exponents[label + name] = p
            lines.append(f"| {label}{name} | " + " | ".join(fmt(cost.get(n)) for n in sizes) + f" | {fmt(p, 2)} |")
    lines.append("")
    lines.append("Seconds of CPU per simulated second; exponent: least-squares slope of log cost against log N.")
    lines.append("")
    lines.append("Where the exponent comes from (event-driven runs): microseconds per step, and steps / events, "
                 "against N; the exponent of the cost of a step.")
    lines.append("")
    lines.append("| integrator | " + " | ".join(f"N = {int(n)}" for n in sizes) + " | per-step exponent |")
    lines.append("|---|" + "---|" * (len(sizes) + 1))
    for name, pts in sweeps.items():
        per_step = {n: 1e6 * r["cpu_s"] / r["steps"] for n, r in pts}
        p = fit_exponent(list(per_step.items())) if len(per_step) >= 3 else float("nan")
        exponents[name + " per step"] = p
        cells = {n: f"{fmt(per_step[n])} us, {int(r['steps'])} / {int(r['events'])}" for n, r in pts}
        lines.append(f"| {name} | " + " | ".join(cells.get(n, "-") for n in sizes) + f" | {fmt(p, 2)} |")
    lines.append("")

    # 2. the 300-element case, 60 s
    full = {k.split("/")[1][len("full60s_"):]: r for k, r in runs.items()
            if k.startswith("string_rig/full60s_") and k.endswith("/300")}
    ref60 = full.pop("reference", None)
    lines.append("## The 3 km / 300-element / 60 s on-bottom stick-slip case")
    lines.append("")
    lines.append("| run | sim s per CPU s | steps | events | bit sticks | bit angle at 60 s, rad | vs reference |")
    lines.append("|---|---|---|---|---|---|---|")
    for name, r in full.items():
        err = abs(r["bit_angle"] - ref60["bit_angle"]) / abs(ref60["bit_angle"]) if ref60 else None
        lines.append(f"| {name} | {fmt(r['t_end'] / r['cpu_s'])} | {int(r['steps'])} | {int(r['events'])} | "
                     f"{int(r['bit_sticks'])} | {r['bit_angle']:.6f} | {fmt(err, 2)} |")
    scipy_full = reused.get("scipy_full")
    if args.full and not args.no_scipy and not scipy_full:
        scipy_full = scipy_run(300, 60.0)
    if scipy_full:
        r = scipy_full
        err = abs(r["bit_angle"] - ref60["bit_angle"]) / abs(ref60["bit_angle"]) if ref60 else None
        lines.append(f"| SciPy BDF (jac_sparsity, events) | {fmt(r['t_end'] / r['cpu_s'])} | {r['steps']} | "
                     f"{r['events']} | {r['bit_sticks']} | {r['bit_angle']:.6f} | {fmt(err, 2)} |")
    if ref60:
        lines.append(f"| reference (Dormand-Prince, rtol 1e-10) | {fmt(ref60['t_end'] / ref60['cpu_s'])} | "
                     f"{int(ref60['steps'])} | {int(ref60['events'])} | {int(ref60['bit_sticks'])} | "
                     f"{ref60['bit_angle']:.6f} | 0 |")
    lines.append("")

    # 3. the window: dense CVODE and SciPy side by side
    window = {k.split("/")[1][len("window4s_"):]: r for k, r in runs.items()
              if k.startswith("string_rig/window4s_") and k.endswith("/300")}
    ref = window.pop("reference", None)
    scipy_window = reused.get("scipy_window")
    if not args.no_scipy and not scipy_window:
        scipy_window = scipy_run(300, args.window)
    if scipy_window:
        window["scipy_bdf_jac_sparsity"] = scipy_window
    lines.append(f"## The 300-element string over its first {fmt(args.window)} s, every integrator (rtol 1e-6)")
    lines.append("")
    lines.append("| run | CPU s | sim s per CPU s | steps | rhs | events | top-drive angle, rad | vs reference |")
    lines.append("|---|---|---|---|---|---|---|---|")
    for name, r in window.items():
        err = abs(r["top_angle"] - ref["top_angle"]) / abs(ref["top_angle"]) if ref else None
        lines.append(f"| {name} | {fmt(r['cpu_s'])} | {fmt(r['t_end'] / r['cpu_s'])} | {int(r['steps'])} | "
                     f"{int(r['rhs'])} | {int(r['events'])} | {r['top_angle']:.8f} | {fmt(err, 2)} |")
    lines.append("")

    # 4. Aarsnes-Shor Well B
    lines.append("## Aarsnes-Shor Well B, 60 s (Moreau-Jean; limit-cycle means after 15 s)")
    lines.append("")
    lines.append("| run | N | h, ms | sim s per CPU s | bit peak, rad/s | vs finest | period, s | switches |")
    lines.append("|---|---|---|---|---|---|---|---|")
    well_b = [(k, r) for k, r in runs.items() if k.startswith("aarsnes_shor/") and "sweep" not in k]
    finest = min((r for _, r in well_b if r.get("bit_peak")), key=lambda r: r["step_ms"] / r["elements"], default=None)
    for name, r in well_b:
        dev = abs(r["bit_peak"] - finest["bit_peak"]) / finest["bit_peak"] if finest else None
        lines.append(f"| {name.split('/')[1]} | {int(r['elements'])} | {fmt(r['step_ms'])} | "
                     f"{fmt(60.0 / r['cpu_s'])} | {fmt(r['bit_peak'], 5)} | {fmt(dev, 2)} | {fmt(r['period'], 4)} | "
                     f"{int(r['switches'])} |")
    lines.append("")

    # 5. the targets
    lines.append("## Targets (measured, never asserted)")
    lines.append("")
    b300 = min(((k, r["cpu_s"] / r["t_end"]) for k, r in full.items()), key=lambda p: p[1], default=None)
    if b300:
        lines.append(f"- 3 km / 300 elements / 60 s faster than real time: {fmt(1.0 / b300[1])}x ({b300[0]}); "
                     "target 10x")
        if "cvode_band" in full:
            lines.append(f"  (CVODE band: {fmt(full['cvode_band']['t_end'] / full['cvode_band']['cpu_s'])}x)")
    if window:
        fastest = min(((k, r) for k, r in window.items() if k != "scipy_bdf_jac_sparsity"),
                      key=lambda p: p[1]["cpu_s"], default=None)
        if fastest and scipy_window:
            lines.append(f"- against SciPy (first {fmt(args.window)} s): "
                         f"{fmt(scipy_window['cpu_s'] / fastest[1]['cpu_s'])}x ({fastest[0]}); target 50x")
        if fastest and "cvode_dense" in window:
            lines.append(f"- against dense CVODE (first {fmt(args.window)} s): "
                         f"{fmt(window['cvode_dense']['cpu_s'] / fastest[1]['cpu_s'])}x; target 5x")
    if scipy_full and b300:
        lines.append(f"- against SciPy over 60 s: {fmt(scipy_full['cpu_s'] / (b300[1] * 60.0))}x ({b300[0]}); "
                     "target 50x")
    for key, what in (("aarsnes_shor/inclusion/1000/5", "h = 2 ms"), ("aarsnes_shor/inclusion/1000/2", "h = 5 ms")):
        if key in runs:
            lines.append(f"- Well B at 1000 cells ({what}): {fmt(60.0 / runs[key]['cpu_s'])} sim s per CPU s; "
                         "target 200")
    for name, p in exponents.items():
        lines.append(f"- exponent {name}: {fmt(p, 2)} (target close to 1)")
    text = "\n".join(lines) + "\n"
    print(text)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "drillstring.md").write_text(text)
    (args.out / "drillstring.json").write_text(json.dumps(
        {"bench": bench, "scipy_window": scipy_window, "scipy_full": scipy_full, "exponents": exponents}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
