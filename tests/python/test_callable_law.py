"""fs.CallableLaw (issue 12, item 7): a friction law whose force and state rate are Python callables.

Dahl's equations written in Python match fs.Dahl on the kinematic, axial and torsional rigs; a stateless smooth
Coulomb law runs on every integrator; a callable's exception reaches the caller unchanged with the partial result;
a callable returning a non-number stops the run naming it; the law pickles by reference.
"""

from __future__ import annotations

import _thread
import concurrent.futures as cf
import math
import pickle
import threading
import traceback

import numpy as np
import pytest

import frictionsim as fs

MU, K_T, N = 0.41, 4e4, 90.0
EPS = 1e-2  # m/s, velocity scale of the smooth Coulomb law
METHODS = ["dormand_prince", "cvode_bdf"]


# Module-level callables: they pickle by reference.
def dahl_force(v_r, normal_force, z):
    """Dahl (paper 000 eq 9): F = k_t z."""
    return K_T * z


def dahl_rate(v_r, normal_force, z):
    """Dahl: dz/dt = v_r (1 - k_t z sgn(v_r) / (mu N))."""
    sign = (v_r > 0) - (v_r < 0)
    return v_r * (1.0 - K_T * z * sign / (MU * normal_force))


def smooth_coulomb(v_r, normal_force, z):
    """F = mu N tanh(v_r / eps): Coulomb friction without a stick phase."""
    return MU * normal_force * math.tanh(v_r / EPS)


def python_dahl(**kwargs):
    return fs.CallableLaw(dahl_force, dahl_rate, name="dahl_py", **kwargs)


def harmonic(law):
    return fs.KinematicRig.harmonic(law, sliding_velocity=1e-3, velocity_amplitude=0.5, frequency=17.0,
                                    normal_force=N)


def failing(after_calls, exception, function=dahl_force):
    """A force callable that behaves as `function` and raises `exception` from its call number `after_calls`."""
    calls = [0]

    def force(v_r, normal_force, z):
        calls[0] += 1
        if calls[0] >= after_calls:
            raise exception
        return function(v_r, normal_force, z)

    return force


# ---------------------------------------------------------------------------------------------- the class
def test_the_class_is_exported_but_not_one_of_the_tabled_laws():
    assert fs.CallableLaw is fs._core.CallableLaw and "CallableLaw" in fs.__all__
    assert fs.CallableLaw not in fs.FRICTION_LAWS  # scenarios and fits enumerate the tabled laws only
    law = python_dahl()
    assert law.force is dahl_force and law.state_derivative is dahl_rate
    assert law.state_count == 1 and law.name == "dahl_py" and law.stiff is False
    assert fs.CallableLaw.has_stick is False and fs.CallableLaw.state_names == ("law_state",)
    assert repr(law).startswith("CallableLaw(force=<function dahl_force") and "name='dahl_py'" in repr(law)
    stateless = fs.CallableLaw(smooth_coulomb)
    assert stateless.state_count == 0 and stateless.state_derivative is None and stateless.name == "CallableLaw"


def test_construction_is_checked():
    with pytest.raises(TypeError, match="force must be a callable"):
        fs.CallableLaw(1.0)
    with pytest.raises(TypeError, match="state_derivative must be a callable"):
        fs.CallableLaw(dahl_force, "dahl_rate")
    with pytest.raises(fs.InvalidParameterError, match="needs a state_derivative") as info:
        fs.CallableLaw(dahl_force, state_count=1)
    assert info.value.parameter == "state_derivative"
    with pytest.raises(fs.InvalidParameterError, match="must be 1 with a state_derivative"):
        fs.CallableLaw(dahl_force, dahl_rate, state_count=0)
    assert fs.CallableLaw(dahl_force, dahl_rate, state_count=np.int64(1)).state_count == 1
    for bad in (2, -1, 10**30, True, 1.0, "1", np.float64(1.0)):
        with pytest.raises(fs.InvalidParameterError, match="state_count must be 0 or 1"):
            fs.CallableLaw(dahl_force, dahl_rate, state_count=bad)
    with pytest.raises(fs.InvalidParameterError, match="stiff must be True or False"):
        fs.CallableLaw(dahl_force, stiff=1)
    with pytest.raises(TypeError, match="name must be a str"):
        fs.CallableLaw(dahl_force, name=None)
    with pytest.raises(TypeError):
        fs.CallableLaw(dahl_force, dahl_rate, 1)  # state_count is keyword-only
    with pytest.raises(TypeError, match="never constructed"):
        fs.KinematicRig(fs.CallableLaw.__new__(fs.CallableLaw), relative_velocity=0.1, normal_force=N)


def test_a_wrong_friction_argument_names_the_callable_law_among_the_choices():
    with pytest.raises(TypeError, match="CallableLaw"):
        fs.AxialVibrationRig(friction=dahl_force)


# ---------------------------------------------------------------------------------------------- (a) Dahl in Python
@pytest.mark.parametrize("method", METHODS)
def test_dahl_in_python_matches_fs_dahl_on_the_kinematic_rig(method):
    times = np.linspace(0.0, 0.5, 51)  # output times: fs.Dahl locates its kink at v_r = 0, the callable does not
    options = dict(method=method, rtol=1e-11, atol=1e-15, output_times=times)
    mine = fs.simulate(harmonic(python_dahl()), 0.5, **options)
    reference = fs.simulate(harmonic(fs.Dahl(MU, K_T)), 0.5, **options)
    assert mine.completed and mine.state_names == ["law_state", "friction_impulse", "friction_work"]
    z_scale = MU * N / K_T
    np.testing.assert_allclose(mine.law_state, reference.dahl_deflection, rtol=0, atol=1e-7 * z_scale)
    np.testing.assert_allclose(mine.friction_force, reference.friction_force, rtol=0, atol=1e-7 * MU * N)
    np.testing.assert_allclose(mine.friction_work, reference.friction_work, rtol=1e-7,
                               atol=1e-7 * np.max(np.abs(reference.friction_work)))
    assert np.max(np.abs(reference.dahl_deflection)) > 0.9 * z_scale  # the run saturates: a real test


@pytest.mark.parametrize("method", METHODS)
def test_dahl_in_python_matches_fs_dahl_on_the_axial_rig(method):
    times = np.linspace(0.0, 0.5, 51)
    options = dict(method=method, rtol=1e-11, atol=1e-15, output_times=times)
    mine = fs.simulate(fs.AxialVibrationRig(friction=python_dahl()), 0.5, **options)
    reference = fs.simulate(fs.AxialVibrationRig(friction=fs.Dahl(MU, K_T)), 0.5, **options)
    assert mine.completed and reference.stats["events"] > 10 and mine.stats["events"] == 0
    for name, other in [("law_state", "dahl_deflection"), ("position", "position"), ("velocity", "velocity"),
                        ("friction_impulse", "friction_impulse"), ("drive_work", "drive_work")]:
        scale = np.max(np.abs(reference[other]))
        np.testing.assert_allclose(mine[name], reference[other], rtol=0, atol=1e-7 * scale, err_msg=name)
    np.testing.assert_allclose(mine.friction_force, reference.friction_force, rtol=0, atol=1e-7 * MU * N)


@pytest.mark.parametrize("method", METHODS)
def test_dahl_in_python_runs_on_the_torsional_rig(method):
    times = np.linspace(0.0, 1.0, 11)
    mine = fs.simulate(fs.TorsionalRig(python_dahl()), 1.0, method=method, rtol=1e-10, output_times=times)
    reference = fs.simulate(fs.TorsionalRig(fs.Dahl(MU, K_T)), 1.0, method=method, rtol=1e-10, output_times=times)
    scale = np.max(np.abs(reference.dahl_deflection))
    np.testing.assert_allclose(mine.law_state, reference.dahl_deflection, rtol=0, atol=1e-4 * scale)
    np.testing.assert_allclose(mine.disc_speed, reference.disc_speed, rtol=0,
                               atol=1e-4 * np.max(np.abs(reference.disc_speed)))


# ---------------------------------------------------------------------------------------------- (b) stateless law
@pytest.mark.parametrize("method", ["dormand_prince", "cvode_bdf", "cvode_adams"])
def test_a_stateless_smooth_coulomb_law_runs_on_every_integrator(method):
    law = fs.CallableLaw(smooth_coulomb, name="smooth_coulomb")
    times = np.linspace(0.0, 0.2, 41)
    result = fs.simulate(harmonic(law), 0.2, method=method, rtol=1e-10, atol=1e-12, output_times=times)
    v_r = 1e-3 - 0.5 * np.cos(2 * np.pi * 17.0 * times)
    exact = MU * N * np.tanh(v_r / EPS)
    np.testing.assert_allclose(result.friction_force, exact, rtol=1e-12, atol=1e-12 * MU * N)
    assert np.all(result.law_state == 0.0)  # state_count 0: z never changes
    fine = np.linspace(0.0, 0.2, 400_001)
    force = MU * N * np.tanh((1e-3 - 0.5 * np.cos(2 * np.pi * 17.0 * fine)) / EPS)
    impulse = float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(fine)))  # trapezoidal rule
    assert result.friction_impulse[-1] == pytest.approx(impulse, rel=1e-6)


def test_a_stateless_law_keeps_the_initial_state_it_is_given():
    law = fs.CallableLaw(lambda v_r, normal_force, z: z, name="constant_z")
    result = fs.simulate(fs.KinematicRig(law, relative_velocity=0.1, normal_force=N, initial_state=[2.5]), 1.0)
    assert np.all(result.law_state == 2.5) and np.all(result.friction_force == 2.5)
    assert result.friction_impulse[-1] == pytest.approx(2.5, rel=1e-12)


def test_the_smooth_coulomb_law_on_the_axial_rig_agrees_across_integrators():
    law = fs.CallableLaw(smooth_coulomb)
    means = [fs.simulate(fs.AxialVibrationRig(friction=law), 0.5, method=method, rtol=1e-9)
             .mean_over_cycles(transient=0.2) for method in ["dormand_prince", "cvode_bdf", "cvode_adams"]]
    # the mean is a small difference of forces of +-mu N: compare on that scale
    assert means[1] == pytest.approx(means[0], abs=1e-6 * MU * N)
    assert means[2] == pytest.approx(means[0], abs=1e-6 * MU * N)
    assert 0.0 < means[0] < MU * N  # the vibration reduces the mean friction force


def test_stiff_makes_automatic_pick_cvode_bdf():
    rig = fs.AxialVibrationRig(friction=fs.CallableLaw(smooth_coulomb, stiff=True))
    automatic = fs.simulate(rig, 0.2, rtol=1e-8)
    assert automatic.stats == fs.simulate(rig, 0.2, rtol=1e-8, method="cvode_bdf").stats
    assert automatic.stats["jacobian_evaluations"] > 0  # difference-quotient Jacobians: CVODE BDF ran
    explicit = fs.simulate(fs.AxialVibrationRig(friction=fs.CallableLaw(smooth_coulomb)), 0.2, rtol=1e-8)
    assert explicit.stats["jacobian_evaluations"] == 0  # not stiff: Dormand-Prince


def test_threads_run_callable_law_rigs_side_by_side():
    rigs = [harmonic(python_dahl()), fs.AxialVibrationRig(friction=python_dahl())] * 2
    serial = [fs.simulate(r, 0.2, output_times=[0.1, 0.2]).states for r in rigs]
    with cf.ThreadPoolExecutor(2) as pool:
        threaded = list(pool.map(lambda r: fs.simulate(r, 0.2, output_times=[0.1, 0.2]).states, rigs))
    for a, b in zip(serial, threaded):
        np.testing.assert_array_equal(a, b)


# ---------------------------------------------------------------------------------------------- (c) exceptions
@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("rig_kind", ["kinematic", "axial"])
@pytest.mark.parametrize("role", ["force", "state_derivative"])
def test_an_exception_in_a_callable_propagates_with_the_partial_result(method, rig_kind, role):
    error = ZeroDivisionError("the model divided by zero")
    broken = failing(3000, error, dahl_force if role == "force" else dahl_rate)
    law = (fs.CallableLaw(broken, dahl_rate, name="broken") if role == "force"
           else fs.CallableLaw(dahl_force, broken, name="broken"))
    rig = harmonic(law) if rig_kind == "kinematic" else fs.AxialVibrationRig(friction=law)
    with pytest.raises(ZeroDivisionError, match="the model divided by zero") as info:
        fs.simulate(rig, 1.0, method=method)
    assert info.value is error  # the callable's own exception object, not a copy or a wrapper
    frames = [frame.name for frame in traceback.extract_tb(info.value.__traceback__)]
    assert frames[0] == "test_an_exception_in_a_callable_propagates_with_the_partial_result"
    assert frames[-1] == "force"  # the callable's frame: the traceback goes down to the raise
    # the report, as fs.SimulationError carries it
    partial = info.value.partial
    assert isinstance(partial, fs.Result) and not partial.completed and len(partial) > 10
    assert 0.0 < info.value.time_reached < 1.0 and partial.t_reached == info.value.time_reached
    assert partial.t[-1] == pytest.approx(info.value.time_reached)
    if hasattr(info.value, "__notes__"):  # Python 3.11+
        assert any(f"broken': {role} (failing.<locals>.force) raised ZeroDivisionError" in note
                   for note in info.value.__notes__)
    # the partial trajectory is the trajectory: it matches an unbroken run up to the failure
    t_check = partial.t[len(partial) // 2]
    whole_rig = harmonic(python_dahl()) if rig_kind == "kinematic" else fs.AxialVibrationRig(friction=python_dahl())
    whole = fs.simulate(whole_rig, t_check, method=method, output_times=[t_check])
    assert partial.law_state[len(partial) // 2] == pytest.approx(whole.law_state[-1], rel=1e-5, abs=1e-9)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("exception", [KeyboardInterrupt, SystemExit])
def test_keyboard_interrupt_and_system_exit_propagate_unchanged(method, exception):
    raised = exception("from the law")
    law = fs.CallableLaw(failing(500, raised), dahl_rate)
    with pytest.raises(exception, match="from the law") as info:
        fs.simulate(fs.AxialVibrationRig(friction=law), 1.0, method=method)
    assert info.value is raised and not hasattr(info.value, "partial")


def test_ctrl_c_stops_a_callable_law_run_as_keyboard_interrupt():
    # interrupt_main trips SIGINT's handler as Ctrl-C does: Python runs it inside the law's callable
    timer = threading.Timer(0.2, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            fs.simulate(fs.AxialVibrationRig(friction=python_dahl()), 1e6, output_times=[1e6], timeout=60.0)
    finally:
        timer.cancel()


def test_after_a_callable_raised_other_failures_are_simulation_errors_again():
    with pytest.raises(ValueError):
        fs.simulate(harmonic(fs.CallableLaw(failing(100, ValueError("bad")), dahl_rate)), 1.0)
    # nothing of the failure stays behind: the next run completes, the next failure is the engine's own
    assert fs.simulate(harmonic(python_dahl()), 0.1).completed
    with pytest.raises(fs.BudgetExceededError):
        fs.simulate(harmonic(python_dahl()), 1.0, max_output_rows=5)
    def velocity(t):
        if t > 0.3:
            raise RuntimeError("sensor lost")
        return math.sin(40 * t)

    with pytest.raises(fs.SimulationError, match="sensor lost"):  # a callable signal's error is reported as before
        fs.simulate(fs.KinematicRig(python_dahl(), relative_velocity=velocity, normal_force=N), 1.0)


def test_an_exception_in_a_thread_stays_in_its_thread():
    def run(law):
        return fs.simulate(fs.AxialVibrationRig(friction=law), 0.3, output_times=[0.3]).states

    laws = [python_dahl(), fs.CallableLaw(failing(2000, LookupError("thread 1")), dahl_rate), python_dahl()]
    with cf.ThreadPoolExecutor(2) as pool:
        futures = [pool.submit(run, law) for law in laws]
        with pytest.raises(LookupError, match="thread 1"):
            futures[1].result()
        np.testing.assert_array_equal(futures[0].result(), futures[2].result())


# ---------------------------------------------------------------------------------------------- (d) bad values
@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("value, message", [
    (math.nan, r"force \(.*nan_force\) must return a finite number \[N\], got nan at v_r = "),
    (math.inf, r"force \(.*nan_force\) must return a finite number \[N\], got inf at v_r = "),
    ("12.0", r"force \(.*nan_force\) must return a real number \[N\], got str '12.0' at v_r = "),
    (None, r"force \(.*nan_force\) must return a real number \[N\], got NoneType None"),
    (True, r"force \(.*nan_force\) must return a real number \[N\], got bool True"),
    (np.array([1.0]), r"force \(.*nan_force\) must return a real number \[N\], got numpy.ndarray"),
])
def test_a_callable_returning_a_non_number_stops_the_run_naming_it(method, value, message):
    def nan_force(v_r, normal_force, z):
        return value if z > 1e-4 else K_T * z

    law = fs.CallableLaw(nan_force, dahl_rate, name="my_law")
    with pytest.raises(fs.SimulationError, match="CallableLaw 'my_law': " + message) as info:
        fs.simulate(harmonic(law), 1.0, method=method)
    assert 0.0 < info.value.time_reached < 1.0 and not info.value.partial.completed


@pytest.mark.parametrize("method", METHODS)
def test_a_non_finite_state_rate_stops_the_run_naming_it(method):
    def runaway(v_r, normal_force, z):
        return math.inf if z > 1e-4 else dahl_rate(v_r, normal_force, z)

    with pytest.raises(fs.SimulationError, match=r"CallableLaw 'CallableLaw': state_derivative \(.*runaway\) must "
                                                 r"return a finite number"):
        fs.simulate(harmonic(fs.CallableLaw(dahl_force, runaway)), 1.0, method=method)


def test_numpy_scalars_and_ints_are_numbers():
    law = fs.CallableLaw(lambda v_r, normal_force, z: np.float32(3.0), lambda v_r, normal_force, z: np.int64(2))
    result = fs.simulate(fs.KinematicRig(law, relative_velocity=0.1, normal_force=N), 1.0, output_times=[1.0])
    assert result.friction_force[-1] == 3.0 and result.law_state[-1] == pytest.approx(2.0, rel=1e-12)


# ---------------------------------------------------------------------------------------------- (e) pickling
def test_pickling_round_trip_with_module_level_functions():
    law = fs.CallableLaw(dahl_force, dahl_rate, name="dahl_py", stiff=True)
    restored = pickle.loads(pickle.dumps(law))
    assert type(restored) is fs.CallableLaw and restored is not law
    assert restored.force is dahl_force and restored.state_derivative is dahl_rate  # by reference
    assert (restored.name, restored.stiff, restored.state_count) == ("dahl_py", True, 1)
    stateless = pickle.loads(pickle.dumps(fs.CallableLaw(smooth_coulomb)))
    assert stateless.state_count == 0 and stateless.state_derivative is None
    # a rig carrying the law pickles too, and the copy runs the same
    rig = fs.AxialVibrationRig(friction=python_dahl(), amplitude=2e-3)
    copy = pickle.loads(pickle.dumps(rig))
    assert copy.friction.force is dahl_force and copy.amplitude == 2e-3
    np.testing.assert_array_equal(fs.simulate(copy, 0.1, output_times=[0.1]).states,
                                  fs.simulate(rig, 0.1, output_times=[0.1]).states)


def test_a_lambda_fails_with_pickles_own_error():
    law = fs.CallableLaw(lambda v_r, normal_force, z: 0.0)
    with pytest.raises((pickle.PicklingError, AttributeError), match="lambda"):
        pickle.dumps(law)


def test_a_run_that_fails_at_its_first_evaluation_has_a_printable_empty_partial():
    def broken(v_r, normal_force, z):
        raise RuntimeError("no force model yet")

    rig = fs.KinematicRig.harmonic(fs.CallableLaw(broken), sliding_velocity=1e-3, velocity_amplitude=0.1,
                                   frequency=17.0, normal_force=90.0)
    with pytest.raises(RuntimeError, match="no force model yet") as info:
        fs.simulate(rig, 0.1)
    partial = info.value.partial
    assert len(partial.t) == 0 and not partial.completed
    assert "0 rows, no rows" in repr(partial)
