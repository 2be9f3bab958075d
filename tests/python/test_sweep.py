"""fs.sweep: grid expansion, identical results on every executor, physics through a sweep, errors, validation."""

from __future__ import annotations

import functools
import logging
import math
import multiprocessing
import re
import signal
import threading
import time
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

import frictionsim as fs
from frictionsim.sweeps import SweepError, SweepResult, axial_mean_friction, grid_points, kinematic_mean_friction

MU, NORMAL_FORCE = 0.41, 90.0  # paper 000: shale on 45 steel, N = 90 N
# Fresh worker interpreters, as on macOS and Windows (and no fork() of a process running dask's threads).
SPAWN = multiprocessing.get_context("spawn")
DAHL = dict(friction=fs.Dahl(MU, 4e4), t_end=0.5, transient=0.2)  # ~2 ms per run
AXIAL_GRID = {"amplitude": [1e-3, 5e-3], "frequency": [10.0, 17.0, 25.0]}  # m, Hz: 6 points


@pytest.fixture(scope="module")
def serial():
    return fs.sweep(axial_mean_friction, AXIAL_GRID, fixed=DAHL, progress=False)


@pytest.fixture(scope="module")
def dask_client():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=logging.ERROR) as cluster, distributed.Client(cluster) as client:
        yield client


@pytest.fixture(params=["threads", "processes", "processes_chunked", "dask"])
def executor(request):
    """Each executor kind; the dask one is a Client passed as is (sweep calls client.get_executor())."""
    if request.param == "dask":
        yield request.getfixturevalue("dask_client")
    elif request.param == "threads":
        with ThreadPoolExecutor(2) as pool:
            yield pool
    else:
        with ProcessPoolExecutor(2, mp_context=SPAWN) as pool:
            yield pool


# ------------------------------------------------------------------------------------------------ grid
def test_cartesian_grid_is_c_order_with_shape_and_axes(serial):
    points, names, shape = grid_points({"a": [1, 2], "b": np.array([10.0, 20.0, 30.0])})
    assert names == ["a", "b"] and shape == (2, 3)
    assert points == [{"a": a, "b": b} for a in (1, 2) for b in (10.0, 20.0, 30.0)]
    assert all(type(p["b"]) is float for p in points)  # NumPy scalars become plain floats

    assert serial.parameters == ["amplitude", "frequency"] and serial.grid_shape == (2, 3) and len(serial) == 6
    assert serial.axes == AXIAL_GRID
    assert serial.points[1] == {"amplitude": 1e-3, "frequency": 17.0}
    values = serial.as_array()
    assert values.shape == (2, 3)
    for (i, j), value in np.ndenumerate(values):  # as_array[i, j] is the point (amplitude[i], frequency[j])
        point = {"amplitude": AXIAL_GRID["amplitude"][i], "frequency": AXIAL_GRID["frequency"][j]}
        assert value == axial_mean_friction(**DAHL, **point)


def test_axial_point_equals_the_mean_over_a_full_record():
    """axial_mean_friction records only its window's ends (dense output). A run recording every step gets its
    window ends by linear interpolation of the impulse, off by ~1e-4 relative at default steps; with steps of
    5 us it agrees to 1e-7."""
    point = {"amplitude": 3e-3, "frequency": 17.0}
    full = fs.simulate(fs.AxialVibrationRig(friction=DAHL["friction"], **point), DAHL["t_end"], max_step=5e-6)
    expected = full.mean_over_cycles(transient=DAHL["transient"])
    assert axial_mean_friction(**DAHL, **point) == pytest.approx(expected, rel=3e-7)
    for bad, parameter in ((-1.0, "t_end"), (float("nan"), "t_end")):
        with pytest.raises(fs.InvalidParameterError) as info:
            axial_mean_friction(friction=DAHL["friction"], t_end=bad)
        assert info.value.parameter == parameter
    with pytest.raises(fs.InvalidParameterError) as info:
        axial_mean_friction(friction=DAHL["friction"], t_end=0.5, transient=0.6)
    assert info.value.parameter == "transient"


def test_axial_sweep_shows_friction_reduction(serial):
    """Vibration lowers the mean friction F_df below mu N, more at larger amplitude and frequency (paper 000)."""
    f_df = serial.as_array()
    assert np.all(f_df > 0) and np.all(f_df < 0.1 * MU * NORMAL_FORCE)
    assert np.all(f_df[1] < f_df[0])  # larger amplitude, lower friction
    assert np.all(np.diff(f_df, axis=1) < 0)  # higher frequency, lower friction (Dahl law)


def test_explicit_points_keep_their_order_and_dict_values_expand():
    points = [{"v": 3.0}, {"v": 1.0}, {"v": 2.0, "w": 5.0}]
    result = fs.sweep(_moments, points, progress=False)
    assert result.points == points and result.grid_shape is None and result.axes is None
    assert result.parameters == ["v", "w"]
    assert result.values == [{"square": 9.0, "v": 3.0}, {"square": 1.0, "v": 1.0}, {"square": 4.0, "v": 2.0}]
    frame = result.to_pandas()
    assert list(frame.columns) == ["v", "w", "square", "value.v"]  # a value key equal to a parameter is renamed
    assert frame["square"].tolist() == [9.0, 1.0, 4.0] and math.isnan(frame["w"][0]) and frame["w"][2] == 5.0
    with pytest.raises(ValueError, match="explicit points"):
        result.as_array()


def test_as_array_picks_a_key_of_dict_values():
    result = fs.sweep(_moments, {"v": [1.0, 2.0]}, progress=False)
    assert result.as_array("square").tolist() == [1.0, 4.0]
    with pytest.raises(ValueError, match="square"):
        result.as_array()


# ------------------------------------------------------------------------------------------------ executors
def test_every_executor_gives_bit_identical_values_in_grid_order(serial, executor, request):
    chunksize = 2 if "chunked" in request.node.callspec.params["executor"] else 1
    result = fs.sweep(axial_mean_friction, AXIAL_GRID, fixed=DAHL, executor=executor, progress=False,
                      chunksize=chunksize)
    assert result.points == serial.points
    assert result.values == serial.values  # ==, bit for bit, in grid order
    assert result.failed == []


def test_values_are_stored_in_grid_order_not_completion_order():
    with ThreadPoolExecutor(4) as pool:  # point i sleeps (4 - i) * 20 ms: they complete in reverse order
        result = fs.sweep(_sleep_then_echo, {"i": range(4)}, fixed={"n": 4}, executor=pool, progress=False)
    assert result.values == [0, 1, 2, 3]


def test_progress_bar_does_not_change_results(serial, capsys):
    shown = fs.sweep(axial_mean_friction, AXIAL_GRID, fixed=DAHL, progress=True, description="F_df map")
    err = capsys.readouterr().err
    assert "F_df map" in err and "6/6" in err
    hidden = fs.sweep(axial_mean_friction, AXIAL_GRID, fixed=DAHL, progress=False)
    assert capsys.readouterr().err == ""
    assert shown.values == hidden.values == serial.values


def test_fs_sweep_is_the_function_after_importing_its_module():
    import frictionsim.sweeps  # noqa: F401 - the module is `sweeps`, so nothing rebinds fs.sweep

    assert fs.sweep is frictionsim.sweeps.sweep
    for _ in range(2):
        assert fs.sweep(_moments, {"v": [2.0]}, progress=False).values == [{"square": 4.0, "v": 2.0}]


# ------------------------------------------------------------------------------------------------ physics
def test_kinematic_coulomb_mean_force_matches_the_analytic_law():
    """v_r = v_d - v_a cos(2 pi f t): F_df = (2/pi) asin(v_d/v_a) mu N for v_d < v_a, and mu N for v_d >= v_a."""
    mu, normal_force, v_d = 0.3, 50.0, 0.01
    ratios = [0.1, 0.3, 0.5, 0.7, 0.9, 1.5]
    with ThreadPoolExecutor(2) as pool:
        result = fs.sweep(kinematic_mean_friction, {"velocity_amplitude": [v_d / r for r in ratios]},
                          fixed=dict(friction=fs.Coulomb(mu), sliding_velocity=v_d, frequency=17.0,
                                     normal_force=normal_force), executor=pool, progress=False)
    for ratio, value in zip(ratios, result.values):
        expected = (2 / math.pi) * math.asin(min(ratio, 1.0)) * mu * normal_force
        assert value == pytest.approx(expected, rel=1e-6), ratio


# ------------------------------------------------------------------------------------------------ errors
BAD_GRID = {"amplitude": [1e-3, -1e-3, 5e-3], "frequency": [17.0]}  # a negative amplitude is rejected by the rig


@pytest.mark.parametrize("kind", ["serial", "threads", "dask"])
def test_errors_raise_names_the_failing_point(kind, request):
    pool = ThreadPoolExecutor(2) if kind == "threads" else None
    executor = request.getfixturevalue("dask_client") if kind == "dask" else pool
    try:
        with pytest.raises(SweepError, match=r"point 1 \(amplitude=-0.001, frequency=17.0\)") as caught:
            fs.sweep(axial_mean_friction, BAD_GRID, fixed=DAHL, executor=executor, progress=False)
    finally:
        if pool:
            pool.shutdown()
    error = caught.value
    assert error.index == 1 and error.point == {"amplitude": -1e-3, "frequency": 17.0}
    assert isinstance(error.error, fs.InvalidParameterError) and error.error.parameter == "amplitude"
    assert error.__cause__ is error.error and "amplitude must be" in str(error)


def test_errors_raise_cancels_outstanding_points():
    _CALLS.clear()
    with ThreadPoolExecutor(1) as pool:
        with pytest.raises(SweepError, match=r"point 0 \(i=0\)"):
            fs.sweep(_slow_unless_first, {"i": range(50)}, executor=pool, progress=False)
    assert 1 <= len(_CALLS) < 10  # the rest were cancelled before they started


def test_errors_collect_keeps_the_other_points(serial):
    with ProcessPoolExecutor(2, mp_context=SPAWN) as pool:
        result = fs.sweep(axial_mean_friction, BAD_GRID, fixed=DAHL, executor=pool, progress=False, errors="collect")
    assert result.failed == [1]
    error = result.values[1]
    assert isinstance(error, fs.InvalidParameterError) and error.parameter == "amplitude"  # pickled intact
    assert result.values[0] == serial.values[1] and result.values[2] == serial.values[4]  # same points, f = 17 Hz
    assert np.isnan(result.as_array()[1, 0])
    frame = result.to_pandas()
    assert frame["error"].tolist()[0] is None and frame["error"][1].startswith("InvalidParameterError: ")
    assert math.isnan(frame["value"][1]) and frame["value"][2] == serial.values[4]


# ----------------------------------------------------------------------- what pickles, interrupts (issue 11, item 13)
@pytest.fixture
def deadline():
    """SIGALRM after 60 s: a sweep or a pool shutdown that deadlocks fails the test instead of hanging CI."""
    def hung(signum, frame):
        raise TimeoutError("the sweep or the executor's shutdown hung for 60 s")

    previous = signal.signal(signal.SIGALRM, hung)
    signal.alarm(60)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, previous)


class _CountingPool(ProcessPoolExecutor):
    """A process pool that counts the tasks handed to it."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.submitted = 0

    def submit(self, *args, **kwargs):
        self.submitted += 1
        return super().submit(*args, **kwargs)


def _closure():
    factor = 2.0
    return lambda x, scale=1.0: factor * scale * x


@pytest.mark.parametrize("function, name", [(lambda x: x, "<lambda>"), (_closure(), "_closure.<locals>.<lambda>"),
                                            (functools.partial(_closure(), scale=3.0), "_closure.<locals>.<lambda>")])
def test_an_unpicklable_function_fails_before_the_process_pool_is_used(deadline, function, name):
    with _CountingPool(1, mp_context=SPAWN) as pool:
        with pytest.raises(SweepError, match=f"function '.*{re.escape(name)}' must pickle") as caught:
            fs.sweep(function, {"x": [1.0, 2.0]}, executor=pool, progress=False)
        assert pool.submitted == 0  # before: submitted, failed in the pool's feeder, and shutdown could deadlock
        assert caught.value.index == -1 and caught.value.point == {}
        assert fs.sweep(_moments, {"v": [3.0]}, executor=pool, progress=False).values == [{"square": 9.0, "v": 3.0}]


@pytest.mark.parametrize("fixed, grid, what", [({"w": threading.Lock()}, {"v": [1.0]}, "fixed"),
                                               ({}, [{"v": 1.0}, {"v": threading.Lock()}], "grid")])
def test_unpicklable_fixed_or_grid_values_fail_before_the_process_pool_is_used(deadline, fixed, grid, what):
    with _CountingPool(1, mp_context=SPAWN) as pool:
        with pytest.raises(SweepError, match=f"the {what} must pickle"):
            fs.sweep(_moments, grid, fixed=fixed, executor=pool, progress=False)
        assert pool.submitted == 0


def test_a_lambda_runs_on_dask_which_pickles_with_cloudpickle(dask_client):
    # only a ProcessPoolExecutor is known to use pickle: any other executor serialises as it likes
    assert fs.sweep(lambda v: 2.0 * v, {"v": [1.0, 2.0]}, executor=dask_client, progress=False).values == [2.0, 4.0]


@pytest.mark.parametrize("interrupt", [KeyboardInterrupt, SystemExit])
@pytest.mark.parametrize("errors", ["raise", "collect"])
@pytest.mark.parametrize("chunksize, at", [(1, 0), (5, 2)])
def test_an_interrupt_in_a_point_propagates_and_no_further_point_starts(interrupt, errors, chunksize, at):
    for _ in range(5):  # before the fix, a run now and then got away with it
        started, returned = [], threading.Event()

        def point(i):
            started.append(i)
            if i == at:
                raise interrupt()
            if i > at:  # a later point holds its worker until the sweep has returned: none can start meanwhile
                returned.wait(10.0)
            return i

        with ThreadPoolExecutor(2) as pool:
            try:
                with pytest.raises(interrupt):
                    fs.sweep(point, {"i": range(40)}, executor=pool, progress=False, errors=errors,
                             chunksize=chunksize)
            finally:
                returned.set()
        # before: the interrupted worker went on to the next point in the queue before the caller could cancel it
        assert set(range(at + 1)) <= set(started) <= set(range(at + 1)) | {chunksize}  # + the other worker's first


# ------------------------------------------------------------------------------------------------ validation
@pytest.mark.parametrize("grid, kwargs, parameter", [
    ({}, {}, "grid"),
    ([], {}, "grid"),
    (42, {}, "grid"),
    ([{"v": 1.0}, 2.0], {}, "grid[1]"),
    ({"v": 0.5}, {}, "grid['v']"),
    ({"v": []}, {}, "grid['v']"),
    ({"v": "abc"}, {}, "grid['v']"),
    ({"v": {1.0, 2.0}}, {}, "grid['v']"),  # a set has no deterministic order
    ({"v": np.zeros((2, 2))}, {}, "grid['v']"),
    ({"v": [1.0]}, {"errors": "ignore"}, "errors"),
    ({"v": [1.0]}, {"chunksize": 0}, "chunksize"),
    ({"v": [1.0]}, {"fixed": {"v": 2.0}}, "fixed"),
])
def test_bad_arguments_raise_value_error_naming_the_parameter(grid, kwargs, parameter):
    with pytest.raises(ValueError, match=r"^sweep: " + parameter.replace("[", r"\[")) as caught:
        fs.sweep(_moments, grid, progress=False, **kwargs)
    assert isinstance(caught.value, fs.InvalidParameterError) and caught.value.parameter == parameter


def test_bad_function_or_executor_raise_type_error():
    with pytest.raises(TypeError, match="function"):
        fs.sweep(3.0, {"v": [1.0]})
    with pytest.raises(TypeError, match="executor"):
        fs.sweep(_moments, {"v": [1.0]}, executor="threads")


def test_sweep_result_repr_and_iteration(serial):
    assert isinstance(serial, SweepResult)
    assert repr(serial).startswith("SweepResult(6 points over ['amplitude', 'frequency'] (2x3), 0 failed")
    assert list(serial) == list(zip(serial.points, serial.values))


# ------------------------------------------------------------------------------------------------ helpers
def _moments(v: float, w: float = 0.0) -> dict:
    return {"square": v * v, "v": v}


_CALLS: list = []
_LOCK = threading.Lock()


def _slow_unless_first(i: int) -> int:
    with _LOCK:
        _CALLS.append(i)
    if i == 0:
        raise RuntimeError("first point fails")
    time.sleep(0.02)
    return i


def _sleep_then_echo(i: int, n: int) -> int:
    time.sleep((n - i) * 0.02)
    return i
