"""Smoke test of bench/compare.py (issue 5's comparison) in its --quick mode.

It runs when its inputs exist: the source tree's bench/compare.py and the C++ Google Benchmark binary
($FRICTIONSIM_BUILD_DIR or build/, bench/integrators; scripts/test builds it). Peers that are not installed
(scikit-sundae, sundials4py) or not built (the C program) are reported as not measured by compare.py itself. Only
that the comparison runs and that every answer it timed meets its accuracy target is checked: the speed targets
are measured, never asserted.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
COMPARE = ROOT / "bench" / "compare.py"
BUILD_DIR = Path(os.environ.get("FRICTIONSIM_BUILD_DIR", ROOT / "build"))
BENCHMARK = BUILD_DIR / "bench" / "integrators"


def _inputs_missing() -> str:
    if not COMPARE.is_file():
        return f"{COMPARE} is not there (not a source checkout)"
    if not (BENCHMARK.is_file() and os.access(BENCHMARK, os.X_OK)):
        return f"{BENCHMARK} is not built (scripts/test or scripts/bench builds it)"
    return ""


@pytest.mark.skipif(bool(_inputs_missing()), reason=_inputs_missing() or "inputs present")
def test_compare_quick_runs_and_every_timed_answer_is_accurate(tmp_path):
    pytest.importorskip("scipy")
    done = subprocess.run(
        [sys.executable, str(COMPARE), "--quick", "--out", str(tmp_path), "--build-dir", str(BUILD_DIR)],
        capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    markdown = (tmp_path / "compare.md").read_text()
    assert markdown.strip() in done.stdout
    assert "### Targets" in markdown and "nproc" in markdown

    results = json.loads((tmp_path / "compare.json").read_text())
    accuracy = results["settings"]["accuracy"]
    assert results["settings"]["quick"] is True
    for key, quantities in (("axial_dahl", {"mean_friction"}), ("spring_block", {"mean_friction", "final_position"})):
        scenario = results["scenarios"][key]
        reference = scenario["reference"]
        assert set(reference["values"]) == quantities
        assert max(reference["crosscheck"]["rel_difference"].values()) < accuracy / 10  # independent check agrees
        timed = [e for e in scenario["entries"] if e["timing"] is not None]
        families = {e["tool"] for e in timed}
        assert {"frictionsim C++", "frictionsim Python", "SciPy solve_ivp"} <= families
        for entry in timed:
            chosen = entry["chosen"]
            assert chosen["ok"], entry
            assert set(chosen["rel_errors"]) == quantities
            assert max(chosen["rel_errors"].values()) <= accuracy  # speed is never bought with a wrong answer
            assert entry["timing"]["seconds"] > 0
            # the chosen point is confirmed by the next tighter one, unless it is the last scanned
            scanned = [o["K"] for o in entry["scan"]]
            index = scanned.index(chosen["K"])
            assert index == len(scanned) - 1 or entry["scan"][index + 1]["ok"]
        for entry in scenario["entries"]:  # an entry is timed, skipped with a reason, or says why it stopped
            assert entry["timing"] is not None or entry["skipped"] or entry["stop_reason"]
        paired = scenario["python_vs_cpp"]["equal accuracy"]
        assert paired["ratio"] == min(paired["python_samples"]) / min(paired["cpp_samples"]) > 0
        assert len(paired["round_ratios"]) == scenario["python_vs_cpp"]["rounds"]  # timed side by side

    sweep = results["sweep"]
    assert sweep["identical"] and sweep["failed"] == 0 and sweep["speedup"] > 0
    assert [t["met"] in (True, False, None) for t in results["targets"]] == [True] * len(results["targets"])
    assert len(results["targets"]) == 5
