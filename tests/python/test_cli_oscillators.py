"""``frictionsim torque-drag --oscillator ... [--place]`` (issue 14, items 3-4, from the command line): the vibrated
broomstick, the zone of influence and the placement curve, each against the Python API (frictionsim.wells)."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import frictionsim as fs
from frictionsim import wells
from frictionsim.cli import main

SURVEY = Path(__file__).resolve().parents[2] / "examples" / "surveys" / "j_well.csv"
# the default string to the survey's 3000 m: 5" pipe over 150 m of 6 1/2" collars
STRING = fs.DrillString([fs.PipeSection(length=2850.0),
                         fs.PipeSection(outer_diameter=0.1651, inner_diameter=0.0714, length=150.0)])
CONDITIONS = dict(mud_density=1200.0, casing_shoe_depth=0.0, bit_torque=0.0, open_hole_friction=0.3,
                  cased_hole_friction=0.3)


def _files(directory: Path):
    return sorted(str(p.relative_to(directory)) for p in directory.rglob("*"))


@pytest.fixture(scope="module")
def vibrated(tmp_path_factory):
    out = tmp_path_factory.mktemp("td") / "out"
    code = main(["torque-drag", str(SURVEY), "--mu", "0.3", "--wob", "5e4", "--depth-step", "500",
                 "--oscillator", "bit-300:60e3:18", "--place", "--out", str(out)])
    return code, out


def test_writes_the_vibrated_broomstick_zone_and_placement(vibrated):
    code, out = vibrated
    assert code == 0
    assert set(_files(out)) == {"torque_drag.csv", "broomstick.csv", "trajectory.csv", "broomstick.png",
                                "well_path.png", "oscillator_broomstick.csv", "oscillator_zone.csv",
                                "oscillator_summary.csv", "oscillator_broomstick.png", "placement.csv",
                                "placement.png", "metadata.json"}
    for png in out.glob("*.png"):
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000


def test_zone_of_influence_is_the_python_api_s_and_its_elements(vibrated):
    _, out = vibrated
    model = wells.soft_string(survey := wells.read_survey(SURVEY), STRING)
    assert len(survey) > 2
    tool = fs.HydraulicOscillator(measured_depth=2700.0, force_amplitude=60e3, frequency=18.0)
    direct = model.oscillators("sliding_drilling", tool, weight_on_bit=5e4, **CONDITIONS)
    summary = pd.read_csv(out / "oscillator_summary.csv").iloc[0]
    assert summary["hook_load_change_kN"] * 1e3 == pytest.approx(direct.hook_load_change, rel=1e-9)
    assert summary["hook_load_change_kN"] > 0  # the tool takes drag away: more of the string's weight at the hook
    assert (summary["zone_top_m"], summary["zone_bottom_m"]) == pytest.approx((direct.zone_top, direct.zone_bottom))
    zone = pd.read_csv(out / "oscillator_zone.csv")
    np.testing.assert_allclose(zone["reduction"], direct.reduction, rtol=1e-9, atol=1e-12)  # %.10g
    # the zone's length is that of the elements reduced past the threshold (0.05), all inside [top, bottom]
    reduced = zone[zone["reduction"] > 0.05]
    assert (reduced["bottom_depth"] - reduced["top_depth"]).sum() == pytest.approx(summary["zone_length_m"], rel=1e-9)
    assert reduced["top_depth"].min() >= summary["zone_top_m"] - 1e-9
    assert reduced["bottom_depth"].max() <= summary["zone_bottom_m"] + 1e-9
    assert set(zone.index[zone["in_zone"]]) >= set(reduced.index)


def test_vibrated_broomstick_keeps_the_tool_at_its_height_above_the_bit(vibrated):
    _, out = vibrated
    frame = pd.read_csv(out / "oscillator_broomstick.csv")
    sliding = frame[frame["operation"] == "sliding_drilling"]
    assert np.all(sliding["hook_load_tool"] >= sliding["hook_load_plain"] - 1e-6)  # a tool only removes drag
    shallow = frame[frame["bit_depth"] < 300.0]  # the tool would be above the surface: not in the string yet
    assert (shallow["tools"] == 0).all() and np.allclose(shallow["hook_load_tool"], shallow["hook_load_plain"])
    row = frame[(frame["bit_depth"] == 1500.0) & (frame["operation"] == "sliding_drilling")].iloc[0]
    model = wells.soft_string(wells.read_survey(SURVEY), wells.string_to_depth(STRING, 1500.0))
    tool = fs.HydraulicOscillator(measured_depth=1200.0, force_amplitude=60e3, frequency=18.0)
    direct = model.oscillators("sliding_drilling", tool, weight_on_bit=5e4, **CONDITIONS)
    assert row["hook_load_tool"] == pytest.approx(direct.vibrated.hook_load, rel=1e-9)
    assert row["hook_load_plain"] == pytest.approx(direct.plain.hook_load, rel=1e-9)


def test_placement_is_place_oscillators_at_the_hook_load_of_the_weight_on_bit(vibrated):
    _, out = vibrated
    model = wells.soft_string(wells.read_survey(SURVEY), STRING)
    hook_load = model.run("sliding_drilling", weight_on_bit=5e4, **CONDITIONS).hook_load
    direct = wells.place_oscillators(model, hook_load, force_amplitude=60e3, frequency=18.0, **CONDITIONS)
    placement = pd.read_csv(out / "placement.csv")
    assert placement["best_depth"].iloc[0] == pytest.approx(direct.depths[0], rel=1e-9)  # CSV: %.10g
    np.testing.assert_allclose(placement["weight_on_bit"], direct.scan_weight_on_bit, rtol=1e-9)
    # without the tool the hook load puts exactly the requested weight on the bit
    assert placement["weight_on_bit_without"].iloc[0] == pytest.approx(5e4, rel=1e-6)
    assert placement["best_weight_on_bit"].iloc[0] >= placement["weight_on_bit"].max() - 1e-6


def test_absolute_depth_is_the_same_tool_as_height_above_the_bit(tmp_path, vibrated):
    _, out = vibrated
    assert main(["torque-drag", str(SURVEY), "--mu", "0.3", "--wob", "5e4", "--depth-step", "1500",
                 "--oscillator", "2700:60e3:18", "-q", "--out", str(tmp_path / "o")]) == 0
    pd.testing.assert_frame_equal(pd.read_csv(tmp_path / "o" / "oscillator_summary.csv"),
                                  pd.read_csv(out / "oscillator_summary.csv"))


@pytest.mark.parametrize("argv, message", [
    (["--oscillator", "bit-300:60e3"], "expected MD:FORCE:FREQ"),
    (["--oscillator", "bit-300:60e3:0"], "FREQ must be positive"),
    (["--oscillator", "3500:60e3:18"], "outside the string (0 to 3000 m MD)"),
    (["--place"], "--place needs --wob > 0"),
    (["--oscillator", "bit-300:60e3:18", "--lubricant", "obm"], "--lubricant is Table 5's row"),
])
def test_bad_oscillator_options_are_clear_errors(argv, message, tmp_path, capsys):
    try:
        code = main(["torque-drag", str(SURVEY), "--out", str(tmp_path / "o"), *argv])
    except SystemExit as exit:  # argparse's own errors
        code = exit.code
    assert code == 2 and message in capsys.readouterr().err
    assert _files(tmp_path) == []
