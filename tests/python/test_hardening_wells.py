"""Issue 23's defects of the WELLS surface (helper wells): torque and drag, the soft string, surveys and hydraulic
oscillators, each with the issue's reproducer. 1. every class of bindings/wells.cpp refuses an unconstructed
instance however it is reached (through the class, the interpreter's slots, as an argument); 2. Ctrl-C stops the
dynamic vibration runs and the loops over them; 3. work that grows with an input is estimated and refused before it
starts; 4. read_survey reads UTF-16 and Latin-1 and refuses what is no survey naming the path; 5. the parameter the
user gave is the one named, in the right kind of error; 6. the results pickle (they cross process pools)."""

from __future__ import annotations

import concurrent.futures as cf
import itertools
import math
import multiprocessing
import os
import pickle
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import _core, wells
from frictionsim.cli import main

ROOT = Path(__file__).resolve().parents[2]
S_WELL = ROOT / "examples" / "surveys" / "s_well.csv"
HORIZONTAL = ROOT / "examples" / "surveys" / "horizontal_3km.csv"

#: The classes bindings/wells.cpp binds (read from _core by name below).
WELL_CLASSES = ("Survey", "TorqueDragResult", "OscillatorResponse", "HydraulicOscillator", "OscillatorDragResult",
                "SoftString")

#: A small well (the fixtures' and the children's): 1400 m of drill pipe, vertical to 500 m then built to 45 deg.
SETUP = """
import frictionsim as fs
from frictionsim import _core, wells
SURVEY = fs.Survey.from_degrees([0.0, 500.0, 1500.0], [0.0, 0.0, 45.0], [0.0, 0.0, 30.0])
STRING = fs.DrillString([fs.PipeSection(length=1400.0)])
MODEL = fs.SoftString(SURVEY, STRING, 20)
TOOL = fs.HydraulicOscillator(measured_depth=700.0, force_amplitude=10e3)
"""
exec(SETUP)  # the same objects here


def _child(code: str, *args: str, timeout: float = 120.0) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, timeout=timeout,
                          cwd=ROOT)


# ------------------------------------------------------------------------------- 1. unconstructed instances
WALK = SETUP + r"""
import pickle, sys
GOOD = {"Survey": lambda: SURVEY, "SoftString": lambda: MODEL, "HydraulicOscillator": lambda: TOOL,
        "TorqueDragResult": lambda: MODEL.run("trip_out"),
        "OscillatorDragResult": lambda: MODEL.oscillators("trip_out", TOOL),
        "OscillatorResponse": lambda: MODEL.oscillator_response("trip_out", TOOL, transient=0.05, cycles=1)}


def bare(name):
    cls = getattr(_core, name)
    return cls.__new__(cls)


def calls_of(name):
    # every attribute of the class's __dict__ with a bare instance as self, and as the first argument
    cls, good = getattr(_core, name), GOOD[name]()
    out = []
    for attr, value in vars(cls).items():
        if isinstance(value, property):
            out.append((attr + ".fget(bare)", lambda v=value: v.fget(bare(name))))
        elif isinstance(value, staticmethod):
            out.append((attr + "(bare, bare, bare)", lambda a=attr: getattr(cls, a)(bare(name), bare(name), bare(name))))
        elif attr == "__init__":
            out.append(("__init__(new, bare)", lambda: cls.__init__(cls.__new__(cls), bare(name))))
            out.append(("__init__(new, keyword=bare)", lambda: cls.__init__(cls.__new__(cls), plain=bare(name))))
        elif attr == "__getattribute__":  # bindings/module.cpp's guard: (self, name)
            out.append(("__getattribute__(bare, '__class__')", lambda v=value: v(bare(name), "__class__")))
        elif callable(value):
            out.append((attr + "(bare)", lambda v=value: v(bare(name))))
            if attr != "__repr__":  # bindings/module.cpp's: its one argument is self
                out.append((attr + "(good, bare)", lambda v=value: v(good, bare(name))))
    if "__len__" in vars(cls):  # the slots the interpreter calls without an attribute lookup
        out += [("len(bare)", lambda: len(bare(name))), ("bool(bare)", lambda: bool(bare(name)))]
    out.append(("pickle.dumps(bare)", lambda: pickle.dumps(bare(name))))
    if name == "Survey":  # the issue's 30-byte pickle
        empty = b"\x80\x02cfrictionsim._core\nSurvey\n)\x81."
        out += [("bool(empty pickle)", lambda: bool(pickle.loads(empty))),
                ("repr(empty pickle)", lambda: repr(pickle.loads(empty)))]
    return out


def argument_calls():
    tool = lambda: bare("HydraulicOscillator")
    plain = MODEL.run("trip_out")
    fields = dict(plain=plain, vibrated=plain, vibration_amplitude=[0.0] * 20, axial_factor=[1.0] * 20,
                  circumferential_factor=[1.0] * 20, reduction=[0.0] * 20, zone_top=0.0, zone_bottom=0.0,
                  zone_length=0.0, coupling_passes=1, converged=True, source="wave", responses=[])
    return [
        ("oscillators(op, bare tool)", lambda: MODEL.oscillators("trip_out", tool())),  # a zero result before
        ("oscillators(op, [bare tool])", lambda: MODEL.oscillators("trip_out", [tool()])),
        ("oscillators(op, bare tool, dynamic)", lambda: MODEL.oscillators("trip_out", tool(), vibration="dynamic")),
        ("sliding_weight_on_bit(h, bare tool)", lambda: MODEL.sliding_weight_on_bit(1e5, tool())),
        ("oscillator_response(op, bare tool)", lambda: MODEL.oscillator_response("trip_out", tool())),
        ("SoftString(bare survey, ...)", lambda: fs.SoftString(bare("Survey"), STRING, 20)),
        ("OscillatorDragResult(plain=bare)", lambda: wells.OscillatorDragResult(**{**fields, "plain": bare("TorqueDragResult")})),
        ("OscillatorDragResult(responses=[bare])",
         lambda: wells.OscillatorDragResult(**{**fields, "responses": [bare("OscillatorResponse")]})),
        ("frequency_scan(model, bare tool)", lambda: wells.frequency_scan(MODEL, tool(), [18.0])),
        ("frequency_scan(bare model, tool)", lambda: wells.frequency_scan(bare("SoftString"), TOOL, [18.0])),
        ("trajectory(bare survey)", lambda: wells.trajectory(bare("Survey"))),
    ]


calls = argument_calls() if sys.argv[1] == "arguments" else calls_of(sys.argv[1])
for label, call in calls:
    print("trying", label, flush=True)  # the last line before a crash names the call
    try:
        call()
        print("RESULT", label, "no error", sep="\t", flush=True)
    except BaseException as error:
        print("RESULT", label, type(error).__name__, str(error).replace("\n", " "), sep="\t", flush=True)
"""


@pytest.mark.parametrize("name", WELL_CLASSES + ("arguments",))
def test_an_unconstructed_instance_is_refused_however_it_is_reached(name):
    # Before: bool() of the empty pickle read a garbage size and its repr() segfaulted, Survey.__new__ then
    # len() gave OverflowError, Survey.tvd.fget(s) "cannot create std::vector larger than max_size()", and an
    # unconstructed HydraulicOscillator given to SoftString.oscillators returned a zero result.
    done = _child(WALK, name)
    assert done.returncode == 0, f"crashed (return code {done.returncode}) at: {done.stdout.splitlines()[-1:]}"
    results = [line.split("\t") for line in done.stdout.splitlines() if line.startswith("RESULT")]
    assert len(results) >= (3 if name == "arguments" else 4), done.stdout
    wrong = [r[1:] for r in results if r[2] != "TypeError" or "never constructed" not in r[3]]
    assert not wrong, wrong


def test_the_walk_covers_every_attribute_of_the_well_classes():
    # every function-like entry of each class's __dict__ is one the walk calls (it reads vars(cls) itself): here,
    # that those entries exist, so a class that lost its methods would not pass the walk vacuously
    for name in WELL_CLASSES:
        entries = [a for a, v in vars(getattr(_core, name)).items()
                   if isinstance(v, (property, staticmethod)) or callable(v)]
        assert {"__init__", "__reduce__", "__repr__"} <= set(entries), (name, entries)


# ------------------------------------------------------------------------------------------------ 2. Ctrl-C
LONG = r"""
import math, sys, time
import frictionsim as fs
from frictionsim import wells
survey = wells.read_survey("examples/surveys/horizontal_3km.csv")
string = fs.DrillString([fs.PipeSection(length=4700.0),
                         fs.PipeSection(outer_diameter=0.1651, inner_diameter=0.0714, length=150.0)])
model = wells.soft_string(survey, string)
MU = dict(open_hole_friction=0.2, cased_hole_friction=0.2)
# never settles (a tolerance of 1e-12) and may run 600 s: each routine would take minutes
SLOW = dict(MU, max_time=600.0, steady_tolerance=1e-12)
tool = fs.HydraulicOscillator(measured_depth=4000.0, force_amplitude=60e3, frequency=18.0)
hook_load = model.run("sliding_drilling", weight_on_bit=20e3, **MU).hook_load
routines = {
    "oscillator_response": lambda: model.oscillator_response("sliding_drilling", tool, **SLOW),
    "oscillators": lambda: model.oscillators("sliding_drilling", tool, vibration="dynamic", **SLOW),
    "sliding_weight_on_bit": lambda: model.sliding_weight_on_bit(hook_load, tool, vibration="dynamic", **SLOW),
    "place_oscillators": lambda: wells.place_oscillators(model, hook_load, scan_points=3, vibration="dynamic", **SLOW),
    "frequency_scan": lambda: wells.frequency_scan(model, tool, [16.0, 18.0, 20.0], hook_load=hook_load, **SLOW),
}
print("started", flush=True)
try:
    routines[sys.argv[1]]()
    print("finished", flush=True)
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
"""

#: measured seconds from SIGINT to the child's exit, per routine (printed at the end of the module's run)
STOP_TIMES: dict = {}


@pytest.mark.parametrize("routine", ["oscillator_response", "oscillators", "sliding_weight_on_bit",
                                     "place_oscillators", "frequency_scan"])
def test_ctrl_c_stops_a_dynamic_vibration_run_promptly(routine):
    # Before: still running 30 s after SIGINT (the dynamic run never polled the interrupt).
    child = subprocess.Popen([sys.executable, "-c", LONG, routine], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, cwd=ROOT)
    try:
        assert child.stdout.readline().strip() == "started"
        time.sleep(1.0)  # well inside the run
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=60.0)
        stopped = time.monotonic() - sent
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    STOP_TIMES[routine] = stopped
    print(f"{routine}: stopped {stopped:.3f} s after SIGINT")
    assert "KeyboardInterrupt" in out, (out, err)
    assert stopped < 3.0  # the spec is 0.5 s; a loaded 2-core machine adds its start-up and scheduling


# ------------------------------------------------------------------------------------- 3. unbounded work
UNBOUNDED = SETUP + r"""
import itertools, time
from frictionsim.errors import InvalidParameterError
fast = fs.HydraulicOscillator(measured_depth=700.0, force_amplitude=10e3, frequency=1e4)
faster = fs.HydraulicOscillator(measured_depth=700.0, force_amplitude=10e3, frequency=1e6)
cases = {
    "oscillators 1e4 Hz": lambda: MODEL.oscillators("sliding_drilling", fast, vibration="dynamic"),
    "oscillators 1e6 Hz": lambda: MODEL.oscillators("sliding_drilling", faster, vibration="dynamic"),
    "oscillator_response 1e4 Hz": lambda: MODEL.oscillator_response("sliding_drilling", fast),
    "sliding_weight_on_bit 1e6 Hz": lambda: MODEL.sliding_weight_on_bit(1e5, faster, vibration="dynamic"),
    "two tools within one run's limit each": lambda: MODEL.oscillators(
        "sliding_drilling", [fs.HydraulicOscillator(measured_depth=700.0, frequency=f) for f in (48.0, 48.0)],
        vibration="dynamic", max_time=600.0),
    "broomstick depth_step 1 mm": lambda: wells.broomstick(SURVEY, STRING, depth_step=0.001),
    "broomstick depth_step 1e-300": lambda: wells.broomstick(SURVEY, STRING, depth_step=1e-300),
    "broomstick endless depths": lambda: wells.broomstick(SURVEY, STRING, depths=itertools.count(1.0)),
    "broomstick endless friction factors": lambda: wells.broomstick(SURVEY, STRING, itertools.repeat(0.2)),
    "oscillators endless tools": lambda: MODEL.oscillators("trip_out", itertools.repeat(TOOL)),
    "frequency_scan endless frequencies": lambda: wells.frequency_scan(MODEL, TOOL, itertools.count(1.0)),
}
for label, call in cases.items():
    start = time.perf_counter()
    try:
        call()
        print("RESULT", label, "no error", "", sep="\t", flush=True)
    except InvalidParameterError as error:
        print("RESULT", label, "refused", error.parameter, f"{time.perf_counter() - start:.4f}",
              str(error).replace("\n", " "), sep="\t", flush=True)
    except BaseException as error:
        print("RESULT", label, type(error).__name__, str(error), sep="\t", flush=True)
"""

EXPECTED_REFUSALS = {"oscillators 1e4 Hz": "frequency", "oscillators 1e6 Hz": "frequency",
                     "oscillator_response 1e4 Hz": "frequency", "sliding_weight_on_bit 1e6 Hz": "frequency",
                     "two tools within one run's limit each": "tools",
                     "broomstick depth_step 1 mm": "depth_step", "broomstick depth_step 1e-300": "depth_step",
                     "broomstick endless depths": "depths", "broomstick endless friction factors": "friction_factors",
                     "oscillators endless tools": "tools", "frequency_scan endless frequencies": "frequencies"}


def test_work_beyond_its_limit_is_refused_before_it_starts_naming_the_parameter():
    # Before: 1e4 Hz ran past 60 s, 1e6 Hz allocated until std::bad_alloc, depth_step=0.001 ran past 60 s, and an
    # endless iterator hung. The child's timeout turns a regression into a failure instead of a hang.
    done = _child(UNBOUNDED, timeout=300.0)
    results = {line.split("\t")[1]: line.split("\t")[2:] for line in done.stdout.splitlines()
               if line.startswith("RESULT")}
    assert set(results) == set(EXPECTED_REFUSALS), (done.stdout, done.stderr)
    for label, parameter in EXPECTED_REFUSALS.items():
        outcome = results[label]
        assert outcome[:2] == ["refused", parameter], (label, outcome)
        print(f"{label}: refused in {float(outcome[2]) * 1e3:.1f} ms: {outcome[3][:160]}")
    assert "1e+07" in results["oscillators 1e4 Hz"][3]  # the limit is stated
    assert "2e+08" in results["broomstick depth_step 1 mm"][3]


def test_the_limits_leave_field_work_alone():
    # the dynamic runs of the test suites (a 4.85 km string at 18 Hz, 600 s at most; 100 elements per wavelength
    # over 300 s) and a broomstick of a 10 km well every 5 m are inside the limits: estimated, not run
    survey = wells.read_survey(HORIZONTAL)
    string = fs.DrillString([fs.PipeSection(length=4700.0),
                             fs.PipeSection(outer_diameter=0.1651, inner_diameter=0.0714, length=150.0)])
    response = _core.SoftString(survey, string, 485)
    tool = fs.HydraulicOscillator(measured_depth=4000.0, force_amplitude=60e3, frequency=18.0)
    with pytest.raises(fs.InvalidParameterError) as info:  # a wrong operation: refused after the work estimate
        response.oscillator_response("rotary_drilling", tool, max_time=600.0)
    assert info.value.parameter == "vibration"
    count = 10000.0 / 5.0 + 1.0
    assert count * (0.5 * 10000.0 / 10.0 + 1.0) * 4 * 3 < wells.MAX_BROOMSTICK_WORK


def test_torque_drag_refuses_a_millimetre_depth_step(tmp_path, monkeypatch, capsys):
    # the CLI inherits broomstick's rule: exit 2 with the message, in milliseconds (before: past 60 s)
    monkeypatch.chdir(tmp_path)
    start = time.perf_counter()
    assert main(["torque-drag", str(S_WELL), "--mu", "0.3", "--depth-step", "0.001"]) == 2
    took = time.perf_counter() - start
    err = capsys.readouterr().err
    assert "depth_step = 0.001" in err and "2e+08" in err, err
    print(f"torque-drag --depth-step 0.001: exit 2 after {took:.2f} s")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_a_survey_path_that_is_a_fifo_is_refused_without_waiting(tmp_path):
    fifo = tmp_path / "survey.csv"
    os.mkfifo(fifo)
    code = ("import sys\nfrom frictionsim import wells, InvalidParameterError\n"
            "try:\n    wells.read_survey(sys.argv[1])\nexcept InvalidParameterError as e:\n"
            "    print(e.parameter, e, sep='|')\n")
    done = _child(code, str(fifo), timeout=60.0)  # before: hung (open() waits for a writer)
    parameter, message = done.stdout.strip().split("|", 1)
    assert parameter == "path" and "FIFO" in message and str(fifo) in message


# ---------------------------------------------------------------------------------------------- 4. read_survey
def _same_survey(a, b):
    for field in ("measured_depth", "inclination", "azimuth"):
        np.testing.assert_array_equal(getattr(a, field), getattr(b, field))


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-le", "utf-16-be", "utf-32", "utf-8-sig"])
def test_a_survey_with_a_byte_order_mark_reads_as_the_utf8_one(encoding, tmp_path):
    text = S_WELL.read_text(encoding="utf-8")
    path = tmp_path / "s_well.csv"
    bom = {"utf-16-le": b"\xff\xfe", "utf-16-be": b"\xfe\xff"}.get(encoding, b"")
    path.write_bytes(bom + text.encode(encoding))  # before: UnicodeDecodeError
    _same_survey(wells.read_survey(path), wells.read_survey(S_WELL))


def test_a_latin1_survey_with_degree_signs_reads(tmp_path):
    text = S_WELL.read_text(encoding="utf-8").replace("inc [deg]", "inc [\u00b0]").replace("azi [deg]", "azi (\u00b0)")
    path = tmp_path / "latin1.csv"
    path.write_bytes(text.encode("latin-1"))  # the degree sign is byte 0xB0: UnicodeDecodeError before
    _same_survey(wells.read_survey(path), wells.read_survey(S_WELL))


@pytest.mark.parametrize("content, says", [
    (bytes(range(256)) * 8, "not a text survey file"),  # UnicodeDecodeError before
    (bytes(range(128, 256)) * 8, "not a text survey file"),
    (b"md,inc,azi\n0,0,0\n\x00\x01\x02\x03", "control character"),
    (("md,inc,azi\n0,0,0\n" + "9" * 200000 + ",0,0\n").encode(), "line 3"),  # the csv module's error before
    (b"\xff\xfe" + b"m\x00d\x00,", "not a text survey file"),  # a UTF-16 mark over an odd number of bytes
])
def test_a_file_that_is_no_survey_is_refused_naming_it(content, says, tmp_path):
    path = tmp_path / "odd.csv"
    path.write_bytes(content)
    with pytest.raises(fs.InvalidParameterError, match=says) as info:
        wells.read_survey(path)
    assert info.value.parameter == "path" and str(path) in str(info.value)


@pytest.mark.parametrize("path, says", [("/dev/zero", "a device"), ("examples/surveys", "a directory"),
                                        ("s_well\0.csv", "NUL|null"), ("/no/such/survey.csv", "cannot read")])
def test_a_path_that_is_no_file_is_refused_naming_it(path, says, monkeypatch):
    # /dev/zero: MemoryError before; a NUL in the path: a bare ValueError
    monkeypatch.chdir(ROOT)
    with pytest.raises(fs.InvalidParameterError, match=says) as info:
        wells.read_survey(path)
    assert info.value.parameter == "path"


def test_a_survey_file_larger_than_the_limit_is_refused_before_it_is_read(tmp_path, monkeypatch):
    path = tmp_path / "big.csv"
    path.write_bytes(b"md,inc,azi\n" + b"0,0,0\n" * 20)
    monkeypatch.setattr(wells, "MAX_SURVEY_BYTES", 64)
    with pytest.raises(fs.InvalidParameterError, match="larger than") as info:
        wells.read_survey(path)
    assert info.value.parameter == "path"


# ---------------------------------------------------------------------------- 5. the parameter named, its kind
@pytest.mark.parametrize("operation, keyword", [("sliding_drilling", "weight_on_bit"),
                                                ("rotary_drilling", "weight_on_bit"),
                                                ("rotary_drilling", "bit_torque")])
@pytest.mark.parametrize("value", [1e300, 1e10, math.inf])
def test_a_huge_bit_load_is_named_not_the_friction(operation, keyword, value):
    # before: weight_on_bit=1e300 overflowed the side force and blamed open_hole_friction (a lock-up)
    with pytest.raises(fs.InvalidParameterError, match=keyword) as info:
        MODEL.run(operation, **{keyword: value})
    assert info.value.parameter == keyword
    assert MODEL.run(operation, **{keyword: 1e9}).hook_load < 0.0 if keyword == "weight_on_bit" else True


@pytest.mark.parametrize("hook_load", [-1e300, -1e12])
def test_a_hook_load_no_weight_on_bit_reaches_is_named(hook_load):
    # before: -1e300 blamed open_hole_friction (the search's weight on bit overflowed)
    with pytest.raises(fs.InvalidParameterError, match="hook_load") as info:
        MODEL.sliding_weight_on_bit(hook_load, [])
    assert info.value.parameter == "hook_load"
    # the search itself: a hook load the plain string reaches inverts to its weight on bit
    reached = MODEL.run("sliding_drilling", weight_on_bit=5e4).hook_load
    assert MODEL.sliding_weight_on_bit(reached, []) == pytest.approx(5e4, rel=1e-9)


@pytest.mark.parametrize("call, keyword, value", [
    (lambda v: MODEL.run("trip_out", mud_density=v), "mud_density", 1200.0),  # numpy's TypeError before
    (lambda v: MODEL.oscillators("trip_out", TOOL, zone_threshold=v), "zone_threshold", 0.1),
    (lambda v: MODEL.oscillators("trip_out", TOOL, vibration="dynamic", cycles=v, transient=0.05), "cycles", 1.0),
    (lambda v: fs.HydraulicOscillator(measured_depth=v), "measured_depth", 700.0),
])
def test_a_one_element_array_is_refused_by_name(call, keyword, value):
    with pytest.raises(TypeError, match=f"{keyword} must be a number, not an array of shape \\(1,\\)"):
        call(np.array([value]))
    assert repr(call(np.float64(value))) == repr(call(value))  # a NumPy scalar and a 0-d array are numbers
    assert repr(call(np.array(value))) == repr(call(value))


@pytest.mark.parametrize("field", ["measured_depth", "inclination", "azimuth"])
@pytest.mark.parametrize("bad, says", [([0.0, 0.5 + 1j], "complex"), (np.array([0.0, 0.5 + 0j]), "complex"),
                                       (np.array([0.0, 1.0], dtype=np.float16).astype(np.complex64), "complex"),
                                       (np.array([False, True]), "booleans"), (np.array(["0", "1"]), "text"),
                                       ([0.0, __import__("fractions").Fraction(1, 2)], "Fraction")])
@pytest.mark.parametrize("build", [fs.Survey, fs.Survey.from_degrees], ids=["radians", "degrees"])
def test_a_survey_refuses_what_is_not_a_real_number(field, bad, says, build):
    # before: complex numbers lost their imaginary part silently (and text in an array became numbers)
    stations = {"measured_depth": [0.0, 1000.0], "inclination": [0.0, 0.1], "azimuth": [0.0, 0.0]}
    stations[field] = bad
    with pytest.raises(TypeError, match=f"{field} must hold real numbers.*{says}"):
        build(**stations)
    ok = build([0, 1000], np.array([0.0, 0.1], dtype=np.float32), [np.int64(0), 0.0])
    assert len(ok) == 2 and ok.inclination[1] == pytest.approx(0.1 if build is fs.Survey else 0.1 * math.pi / 180,
                                                               rel=1e-7)


# ------------------------------------------------------------------------------------------------- 6. pickling
def _fields(obj):
    """Every property of a result, nested results as their own fields."""
    out = {}
    for name, value in vars(type(obj)).items():
        if isinstance(value, property):
            got = getattr(obj, name)
            if isinstance(got, (wells.TorqueDragResult, wells.OscillatorResponse)):
                got = _fields(got)
            elif isinstance(got, list):
                got = [_fields(g) for g in got]
            out[name] = got
    return out


def _assert_same(a, b, where=""):
    assert type(a) is type(b), where
    if isinstance(a, dict):
        assert a.keys() == b.keys(), where
        for k in a:
            _assert_same(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            _assert_same(x, y, f"{where}[{i}]")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b), where
    else:
        assert a == b, where


def _results():
    dynamic = MODEL.oscillators("trip_out", [TOOL], vibration="dynamic", transient=0.05, cycles=1)
    assert dynamic.responses
    return {"TorqueDragResult": MODEL.run("rotary_drilling", weight_on_bit=5e4, bit_torque=2e3),
            "OscillatorDragResult wave": MODEL.oscillators("trip_out", TOOL),
            "OscillatorDragResult dynamic": dynamic,
            "OscillatorResponse": dynamic.responses[0]}


def _run_in_worker(_):
    exec(SETUP, globals())
    return MODEL.oscillators("trip_out", TOOL)


def test_results_pickle_field_for_field():
    # before: "cannot pickle 'frictionsim._core.TorqueDragResult' object" (no constructor, no __reduce__)
    for label, result in _results().items():
        fields = _fields(result)
        assert len(fields) >= 9, label
        for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
            again = pickle.loads(pickle.dumps(result, protocol))
            assert type(again) is type(result)
            _assert_same(_fields(again), fields, label)
        assert repr(again) == repr(result)


def test_a_result_crosses_a_process_pool():
    with cf.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork")) as pool:
        back = pool.submit(_run_in_worker, None).result(timeout=120)
    _assert_same(_fields(back), _fields(MODEL.oscillators("trip_out", TOOL)))


def test_tampered_result_pickles_are_refused_by_name():
    good = MODEL.run("trip_out")
    rebuild, (cls, args, kwargs, factory) = good.__reduce__()
    assert rebuild is _core._rebuild and cls is wells.TorqueDragResult and args == ()
    # the constructors' rules; their TypeErrors become the package's error in _rebuild (bindings/module.cpp)
    for change, says in [({"tension": kwargs["tension"][:-1]}, "tension must hold 21 values"),
                         ({"operation": "levitate"}, "operation must be one of"),
                         ({"side_force": [1j] * 20}, "side_force must hold real numbers"),
                         ({"extra": 1}, "unexpected keyword argument 'extra'")]:
        with pytest.raises(fs.InvalidParameterError, match=says):
            rebuild(cls, args, {**kwargs, **change}, factory)
    with pytest.raises(fs.InvalidParameterError, match="missing the keyword argument 'torque'"):
        rebuild(cls, args, {k: v for k, v in kwargs.items() if k != "torque"}, factory)
    response = _results()["OscillatorResponse"]
    _, (cls, args, kwargs, factory) = response.__reduce__()
    with pytest.raises(fs.InvalidParameterError, match="settled must be a bool"):
        rebuild(cls, args, {**kwargs, "settled": "yes"}, factory)
    with pytest.raises(fs.InvalidParameterError, match="excitation_node") as info:
        rebuild(cls, args, {**kwargs, "excitation_node": 10**6}, factory)
    assert info.value.parameter == "excitation_node"
