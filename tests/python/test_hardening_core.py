"""Issue 23 on the engine's core surface: the construction guard of every class of the extension (a walk over
_core), tampered pickles through `_rebuild`, fs.Parameter pickling, and the recorded output bounded by bytes with a
consistent partial result when the memory runs out. Each test fails on the code before its fix.
"""

from __future__ import annotations

import json
import pickle
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import _core

def _classes_of(namespace) -> set:
    """The extension's classes in a namespace and, recursively, the classes nested in them (enums included)."""
    found = set()
    for value in list(vars(namespace).values()):
        if isinstance(value, type) and getattr(value, "__module__", "") == "frictionsim._core" \
                and not issubclass(value, BaseException) and value is not namespace:
            found.add(value)
            found |= _classes_of(value)
    return found


#: every class of the extension, nested ones too
CLASSES = sorted(_classes_of(_core), key=lambda c: c.__qualname__)


def _run_python(code: str, timeout: float = 300.0) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)


# ---------------------------------------------------------------------------------------------- construction guard
#: Run in one child process (a crash is a negative return code; the last line printed names what crashed): for every
#: class, a bare instance (cls.__new__(cls), what an incomplete pickle leaves) reached every way Python reaches an
#: instance's C++ value: its repr, every property's getter, the dunder slots the interpreter calls without
#: __getattribute__ (len, bool, iter, getitem, hash, eq), pickling, and every method and property reached through the
#: class with the bare instance as self. One JSON line per use: the exception's type and whether it says "never
#: constructed" (or "ok" when the use returned).
WALK = textwrap.dedent("""
    import json, operator, pickle, sys
    from frictionsim import _core

    def out(cls, use, kind, text=""):
        print(json.dumps({"cls": cls, "use": use, "kind": kind, "guarded": "never constructed" in text}), flush=True)

    def attempt(cls, use, f):
        print(json.dumps({"trying": cls + "." + use}), flush=True)
        try:
            f()
        except BaseException as e:
            out(cls, use, type(e).__name__, str(e))
        else:
            out(cls, use, "ok")

    for name in sys.argv[1:]:
        cls = _core
        for part in name.split("."):
            cls = getattr(cls, part)
        try:
            bare = cls.__new__(cls)
        except TypeError as e:  # a class that cannot be made without construction is guarded by that
            out(name, "__new__", "TypeError", "never constructed: " + str(e))
            continue
        attempt(name, "repr", lambda: repr(bare))
        attempt(name, "pickle", lambda: pickle.dumps(bare))
        for slot, use in (("__len__", len), ("__bool__", bool), ("__iter__", iter),
                          ("__getitem__", lambda o: o[0]), ("__hash__", hash), ("__eq__", lambda o: o == o)):
            if slot in vars(cls):
                attempt(name, slot, lambda use=use: use(bare))
        for attr, value in sorted(vars(cls).items()):
            if attr == "_pybind11_conduit_v1_":
                continue  # pybind11's cross-module hook: no access to the value
            if type(value) is property:  # not pybind11's static properties: they read no instance
                attempt(name, attr + ".fget", lambda value=value: value.fget(bare))
            elif callable(value) and not attr.startswith("__") and not isinstance(value, (staticmethod, type)) \\
                    and type(value).__name__ == "instancemethod":
                attempt(name, attr + "(bare)", lambda attr=attr: getattr(cls, attr)(bare))
""")


def test_the_walk_covers_every_class_of_the_extension():
    names = {cls.__name__ for cls in CLASSES}
    # the classes the reproducers named, and one of each family: laws, rigs, options, results, wells
    assert {"Survey", "DrillString", "HydraulicOscillator", "StopCondition", "TorqueDragResult", "Coulomb",
            "StringRig", "SolverOptions", "RawResult", "Parameter", "Method"} <= names
    assert len(CLASSES) >= 35


def _walk(names) -> tuple[list[dict], subprocess.CompletedProcess]:
    done = subprocess.run([sys.executable, "-c", WALK, *names], capture_output=True, text=True, timeout=600)
    lines = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    return lines, done


def test_no_use_of_an_unconstructed_instance_crashes_or_runs_on_garbage():
    lines, done = _walk([cls.__qualname__ for cls in CLASSES])
    trying = [line["trying"] for line in lines if "trying" in line]
    assert done.returncode == 0, f"crashed ({done.returncode}) at {trying[-1] if trying else '?'}: {done.stderr[-2000:]}"
    uses = [line for line in lines if "use" in line]
    assert len(uses) > 300  # every class's repr, pickling, properties and methods
    enums = {cls.__qualname__ for cls in CLASSES if hasattr(cls, "__members__")}
    wrong = []
    for use in uses:
        if use["cls"] in enums and use["use"] in ("pickle", "__hash__", "__eq__"):
            continue  # an enum's __new__ makes a value pickle and copy can rebuild (test_hardening_fields)
        # a property or a method given the bare instance as self: refused as never constructed, whatever the call
        if not (use["kind"] == "TypeError" and use["guarded"]):
            wrong.append(use)
    assert not wrong, f"{len(wrong)} uses not refused as never constructed, e.g. {wrong[:8]}"


# ------------------------------------------------------------------------------------------------ tampered pickles
def test_a_tampered_pickle_raises_the_packages_error_naming_what_is_wrong():
    rebuild = _core._rebuild
    coulomb = fs.Coulomb(0.4)
    cases = [
        ((int, (), {}, ""), "cls"),  # not a class of the extension
        (("Coulomb", (), {}, ""), "cls"),
        ((type(coulomb), [0.4], {}, ""), "args"),  # a list, not a tuple
        ((type(coulomb), (), [("mu", 0.4)], ""), "kwargs"),
        ((type(coulomb), (), {1: 0.4}, ""), "kwargs"),
        ((type(coulomb), (0.4,), {}, 7), "factory"),
        ((type(coulomb), (0.4,), {}, "no_such_factory"), "factory"),
        ((type(coulomb), (0.4,), {}, "__class__"), "factory"),  # an attribute, not a static constructor
        ((type(coulomb), ("a lot",), {}, ""), "args"),  # arguments the constructor's overloads do not take
        ((type(coulomb), (), {"mu": 0.4, "nonsense": 1.0}, ""), "args"),
    ]
    for arguments, parameter in cases:
        with pytest.raises(fs.InvalidParameterError, match="unpickling") as caught:
            rebuild(*arguments)
        assert caught.value.parameter == parameter, arguments
    # the constructor's own rule keeps its error and its parameter
    with pytest.raises(fs.InvalidParameterError) as caught:
        rebuild(type(coulomb), (-1.0,), {}, "")
    assert caught.value.parameter == "mu"
    # and a good pickle still rebuilds through it
    assert repr(pickle.loads(pickle.dumps(coulomb))) == repr(coulomb)
    harmonic = fs.KinematicRig.harmonic(fs.Coulomb(0.3), sliding_velocity=1e-3, velocity_amplitude=0.2,
                                        frequency=17.0, normal_force=90.0)
    assert repr(pickle.loads(pickle.dumps(harmonic))) == repr(harmonic)


def test_a_pickle_stream_naming_a_missing_factory_raises_the_packages_error():
    function, (cls, args, kwargs, _) = fs.Coulomb(0.4).__reduce__()
    assert function is _core._rebuild
    stream = pickle.dumps(_Reduce(function, (cls, args, kwargs, "gone")))  # what a tampered stream holds
    with pytest.raises(fs.InvalidParameterError, match="factory"):
        pickle.loads(stream)


class _Reduce:
    """An object that pickles as `function(*args)`: the shape of a tampered pickle stream."""

    def __init__(self, function, args):
        self.function, self.args = function, args

    def __reduce__(self):
        return self.function, self.args


# ------------------------------------------------------------------------------------------------ fs.Parameter
def test_a_parameter_pickles_with_every_field():
    for law in (fs.Coulomb(0.4), fs.LuGre(0.3, 0.4, 0.01, 1e5, 300.0, 1.0)):
        for p in law.parameters:
            for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
                back = pickle.loads(pickle.dumps(p, protocol=protocol))
                assert back == p and hash(back) == hash(p)
                for field in ("name", "field", "symbol", "unit", "rule", "doc", "lower", "upper", "lower_open",
                              "upper_open", "at_least", "unset_allowed", "required", "default"):
                    assert getattr(back, field) == getattr(p, field)
                assert np.isnan(back.example) == np.isnan(p.example)
                assert repr(back) == repr(p)
    a, b = fs.Coulomb(0.4).parameters[:2]
    assert a != b and a != "mu"
    with pytest.raises(fs.InvalidParameterError, match="state"):
        _setstate_of(("mu",))  # what unpickling does: __setstate__ on a bare Parameter


def test_a_tampered_parameter_state_is_refused():
    p = fs.Coulomb(0.4).parameters[0]
    state = p.__getstate__()
    bad = list(state)
    bad[6] = "not a number"
    with pytest.raises(fs.InvalidParameterError, match="state"):
        pickle.loads(pickle.dumps(_Reduce(_setstate_of, (tuple(bad),))))


def _setstate_of(state):
    obj = _core.Parameter.__new__(_core.Parameter)
    obj.__setstate__(state)
    return obj


# ------------------------------------------------------------------------------------------------ memory by bytes
def _string(elements: int = 40) -> "fs.TorsionalString":
    return fs.TorsionalString(fs.drillstring.field_string(), elements=elements)


def test_a_run_too_big_for_the_byte_budget_is_refused_before_it_starts():
    rig = _string(40)
    row = (len(rig.state_names) + 2) * 8 + 4
    start = time.perf_counter()
    with pytest.raises(fs.InvalidParameterError, match="max_output_bytes") as caught:
        fs.simulate(rig, 10.0, step=1e-3, max_output_bytes=10_000 * row)  # every step recorded: 10001 rows
    assert caught.value.parameter == "max_output_bytes"
    assert time.perf_counter() - start < 2.0  # refused before a step is taken (measured: milliseconds)
    assert "at least 10001 rows" in str(caught.value) and "an eighth" in str(caught.value)
    # room for the rows and the run's few events (a located switch's record, its states not kept on a string)
    assert len(fs.simulate(rig, 10.0, step=1e-3, max_output_bytes=10_001 * row + 10_000).t) == 10001
    # the default: an eighth of the memory the process may use
    budget = _core.SolverOptions().output_byte_budget
    with open("/proc/meminfo") as meminfo:
        total = next(int(line.split()[1]) * 1024 for line in meminfo if line.startswith("MemTotal"))
    assert budget <= total / 8 * 1.02


def test_the_byte_budget_stops_a_run_with_a_consistent_partial_result():
    rig = fs.TorsionalRig(fs.Coulomb(0.3), reference_speed=4.0, normal_force=30.0)
    row = (len(rig.state_names) + 2) * 8 + 4  # t, states, friction force (doubles), mode (int)
    with pytest.raises(fs.BudgetExceededError) as caught:
        fs.simulate(rig, 50.0, max_output_bytes=100 * row)  # every step recorded: thousands of rows
    err = caught.value
    assert err.budget == "max_output_bytes" and "max_output_bytes = " + str(100 * row) in str(err)
    p = err.partial
    assert len(p.t) == p.states.shape[0] == len(p.friction_force) == len(p.mode) <= 100
    assert err.time_reached == p.t[-1]


def test_running_out_of_memory_keeps_the_partial_result_consistent():
    # the child limits its address space past its imports; the engine's reserve then fails with bad_alloc while
    # recording every step of a string with no byte budget in the way (measured: at t = 136 s, 65536 rows, 106 MiB;
    # copying the partial result into NumPy then runs out too, so it comes without one: never a torn one). Before,
    # pybind11's unchecked copy gave reshape a null array: a segfault.
    code = textwrap.dedent("""
        import resource, numpy as np, frictionsim as fs
        rig = fs.StringRig(fs.drillstring.field_string(), fs.Coulomb(0.3), elements=100)
        with open('/proc/self/status') as f:
            vm = [int(line.split()[1]) * 1024 for line in f if line.startswith('VmSize')][0]
        resource.setrlimit(resource.RLIMIT_AS, (vm + (200 << 20), vm + (200 << 20)))
        try:  # every step recorded (209 states a row), neither budget in the way: the memory runs out first
            fs.simulate(rig, 2000.0, max_output_bytes=1 << 50, max_output_rows=1 << 40)
        except fs.BudgetExceededError as e:
            p = e.partial
            print('budget', e.budget, 'partial', None if p is None else
                  (len(p.t), p.states.shape[0], len(p.friction_force), len(p.mode)))
        except MemoryError:
            print('MemoryError')
    """)
    done = _run_python(code)
    assert done.returncode == 0, done.stderr[-2000:]
    words = done.stdout.split()
    assert words[:2] == ["budget", "max_output_bytes"], done.stdout + done.stderr[-2000:]
    if words[3] != "None":
        sizes = [int(w) for w in done.stdout.split("(")[1].rstrip(")\n").split(",")]
        assert len(set(sizes)) == 1 and sizes[0] > 0  # every column the same length
