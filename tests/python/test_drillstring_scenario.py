"""Scenario files of rig type "drillstring" (frictionsim.scenario.rigs.DrillStringKind): the example file parses
into the tables' keys, a small case runs and its summary and map are the library's own measures of the same rig
built by hand, and bad keys are refused at their dotted path."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import frictionsim as fs
from frictionsim import drillstring as ds
from frictionsim import scenario

EXAMPLE = Path(__file__).resolve().parent.parent.parent / "examples" / "scenarios" / "drillstring_stick_slip.toml"

SMALL = """
title = "small string"
[rig]
type = "drillstring"
sections = [{ length = 900.0 }, { length = 100.0, outer_diameter = 0.1651, inner_diameter = 0.0714 }]
bit = { viscous_damping = 20.0 }
weight_on_bit = 6e4
elements = 5
inclination = 1.0
damping_time = 2e-3
surface_speed = 4.0
top_drive_inertia = 300.0
proportional_gain = 3e3
integral_gain = 1e3
[friction]
type = "coulomb"
mu = 0.2
mu_static = 0.3
[solver]
t_end = 12.0
rtol = 1e-8
[analysis]
transient = 4.0
surface_speeds = [2.0, 8.0]
weights_on_bit = [3e4, 9e4]
"""


def test_the_example_file_parses_into_the_tables_keys():
    parsed = scenario.load(EXAMPLE)
    assert [c.name for c in parsed.cases] == ["pi_top_drive", "stiff_top_drive"]
    first, second = parsed.cases
    assert first.rig.type == "drillstring" and first.kind.analysis is scenario.analyses.STICK_SLIP
    assert first.rig.params["sections"][1] == {"length": 200.0, "outer_diameter": 0.1651, "inner_diameter": 0.0714}
    assert second.rig.params["top_drive"] == "prescribed_speed" and first.rig.params["elements"] == 30
    assert first.analysis.surface_speeds == (3.0, 6.0, 10.0, 15.0)
    rig = first.build()
    assert isinstance(rig, fs.StringRig) and rig.string.length == 3000.0 and rig.weight_on_bit == 100e3
    assert rig.bit.static_coefficient == 0.8 and rig.friction.mu == 0.2
    # every StringRig keyword is a scenario key (read from the class), and the sections take PipeSection's
    keys = scenario.rig_kind("drillstring").keys
    assert {p.name for p in fs.StringRig.parameters} <= set(keys) and {"sections", "bit", "elements"} <= set(keys)
    assert parsed.output.plots == ("bit_speed", "stick_slip_map")


def test_a_small_case_runs_and_measures_what_the_library_measures(tmp_path):
    parsed = scenario.loads(SMALL, name="small")
    done = scenario.run(parsed)
    run = done.runs[0]
    # the same rig by hand, the same run, the same measures
    pipe = fs.PipeSection(length=900.0)
    collars = fs.PipeSection(length=100.0, outer_diameter=0.1651, inner_diameter=0.0714)
    rig = fs.StringRig(fs.DrillString([pipe, collars]), fs.Coulomb(0.2, 0.3),
                       bit=fs.NavarroLopezBit(viscous_damping=20.0), weight_on_bit=6e4, elements=5, inclination=1.0,
                       damping_time=2e-3, surface_speed=4.0, top_drive_inertia=300.0, proportional_gain=3e3,
                       integral_gain=1e3)
    assert repr(run.rig) == repr(rig)
    result = fs.simulate(rig, 12.0, rtol=1e-8, output_times=parsed.cases[0].output_times())
    assert np.array_equal(result.states, run.result.states)
    expected = ds.stick_slip(rig, result, transient=4.0)
    summary = done.summary().iloc[0]
    assert summary["peak_ratio"] == expected.peak_ratio and summary["bit_stuck_fraction"] == expected.stuck_fraction
    assert summary["bit_sticks"] == expected.sticks and summary["weight_on_bit_N"] == 6e4
    # the map: each point is the rig at (w_set, W) from rest; the heavier, slower corner sticks, the lighter,
    # faster one does not
    m = run.map
    assert m.peak_ratio.shape == (2, 2) and not m.failed.any()
    point = ds.stick_slip_point(rig=rig, surface_speed=8.0, weight_on_bit=3e4, t_end=12.0, transient=4.0, rtol=1e-8)
    assert m.peak_ratio[1, 0] == point["peak_ratio"] and m.sticks[1, 0] == bool(point["sticks"])
    assert m.sticks[0, 1] and m.stuck_fraction[0, 1] > m.stuck_fraction[1, 0]
    # outputs
    written = {p.name for p in done.write(tmp_path)}
    assert {"coulomb.csv", "summary.csv", "stick_slip_map_coulomb.csv", "bit_speed.png",
            "stick_slip_map_coulomb.png", "scenario.toml"} <= written
    series = pd.read_csv(tmp_path / "coulomb.csv")
    assert {"omega_0", "omega_5", "surface_torque", "bit_torque", "stuck_contacts", "wall_friction_torque"} <= set(
        series.columns)
    table = pd.read_csv(tmp_path / "stick_slip_map_coulomb.csv")
    assert len(table) == 4 and {"surface_speed", "weight_on_bit", "peak_ratio", "sticks"} <= set(table.columns)


def _with(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


@pytest.mark.parametrize("old, new, key", [
    ("{ length = 900.0 }", "{ lenght = 900.0 }", "rig.sections[1].lenght"),
    ("inner_diameter = 0.0714 }", "inner_diameter = 0.2 }", "rig.sections[2].inner_diameter"),
    ("{ length = 900.0 }", "{ length = -900.0 }", "rig.sections[1].length"),
    ("sections = [{ length = 900.0 }, ", "sections = [", None),  # still valid: one section
    ("bit = { viscous_damping = 20.0 }", "bit = { static_coefficient = 0.1 }", "rig.bit.static_coefficient"),
    ("bit = { viscous_damping = 20.0 }", "bit = 3.0", "rig.bit"),
    ("weight_on_bit = 6e4", "weight_on_bit = -1.0", "rig.weight_on_bit"),
    ("elements = 5", "elements = 0", "rig.elements"),
    ("elements = 5", "elements = 2.5", "rig.elements"),
    ("inclination = 1.0", "inclination = 1.0\nmud_density = 9000.0", "rig.mud_density"),
    ("inclination = 1.0", "inclination = 1.0\ncontact_nodes = [0, 2]", "rig.contact_nodes"),
    ("inclination = 1.0", "inclination = 1.0\ntop_drive = \"diesel\"", "rig.top_drive"),
    ("inclination = 1.0", "inclination = 1.0\nwobble = 1.0", "rig.wobble"),
    ("surface_speeds = [2.0, 8.0]\n", "", "analysis.surface_speeds"),
    ("surface_speeds = [2.0, 8.0]", "surface_speeds = [2.0, -8.0]", "analysis.surface_speeds[2]"),
    ("transient = 4.0", "transient = 12.0", "analysis.transient"),
    ("transient = 4.0", "stick_speed = 0.1", "analysis.stick_speed"),
])
def test_bad_keys_are_refused_at_their_path(old, new, key):
    text = _with(SMALL, old, new)
    if key is None:
        assert scenario.loads(text).cases[0].build().string.length == 100.0
        return
    with pytest.raises(scenario.ScenarioError) as error:
        scenario.loads(text)
    assert error.value.key == key, error.value


def test_a_map_needs_a_bit_and_the_bit_its_weight():
    no_bit = _with(_with(SMALL, "bit = { viscous_damping = 20.0 }\n", ""), "weight_on_bit = 6e4\n", "")
    with pytest.raises(scenario.ScenarioError) as error:
        scenario.loads(no_bit)
    assert error.value.key == "analysis.surface_speeds" and "bit on bottom" in error.value.rule
    with pytest.raises(scenario.ScenarioError) as error:
        scenario.loads(_with(SMALL, "weight_on_bit = 6e4\n", ""))
    assert error.value.key == "rig.weight_on_bit"
    off_bottom = no_bit.split("[analysis]")[0]  # no map: a string off bottom runs
    run = scenario.run(scenario.loads(off_bottom)).runs[0]
    assert run.rig.bit is None and run.map is None and not run.stick_slip.sticks


def test_drill_strings_and_torsional_rigs_do_not_share_a_file():
    text = SMALL.split("[analysis]")[0] + '[[case]]\nname = "string"\n[[case]]\nname = "disc"\nrig = { type = "torsional" }\n'
    with pytest.raises(scenario.ScenarioError) as error:
        scenario.loads(text)
    assert error.value.key == "case[2].rig.type"


def test_the_example_runs_from_the_command_line(tmp_path, capsys):
    from frictionsim.cli import main

    out = tmp_path / "out"
    assert main(["run", str(EXAMPLE), "--out", str(out)]) == 0
    names = {p.name for p in out.iterdir()}
    assert names == {"pi_top_drive.csv", "stiff_top_drive.csv", "summary.csv", "scenario.toml", "metadata.json",
                     "bit_speed.png",
                     "stick_slip_map_pi_top_drive.csv", "stick_slip_map_pi_top_drive.png",
                     "stick_slip_map_stiff_top_drive.csv", "stick_slip_map_stiff_top_drive.png"}
    summary = pd.read_csv(out / "summary.csv").set_index("case")
    assert summary["bit_sticks"].all()  # the example's point is a stick-slip point
    # the stiff drive holds the surface speed exactly
    series = pd.read_csv(out / "stiff_top_drive.csv")
    assert np.all(series["omega_0"] == 6.0) and summary.loc["stiff_top_drive", "surface_peak_ratio"] == 1.0
    assert "peak bit / w_set" in capsys.readouterr().out
