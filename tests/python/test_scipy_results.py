"""SciPy-style results (issue 15, item 2) on paper 001's torsional rig: stop conditions evaluated in the engine
(a state crossing a level, a switch into a named mode; direction and terminal flags), t_events / y_events, the state
before and after each switch, rows at both sides of a switch, and OdeResult's names (y, success, status, message,
nfev, njev)."""

import pickle

import numpy as np
import pytest

import frictionsim as fs

StopCondition = fs.StopCondition


def rig():
    return fs.TorsionalRig(fs.torsional.fig7_laws()["Stribeck"], initial_drive_speed=5.76, initial_disc_speed=0.0)


@pytest.fixture(scope="module")
def free_run():
    """10 s of stick-slip, every internal step recorded, no stop condition."""
    return fs.simulate(rig(), 10.0, rtol=1e-10, atol=1e-12)


def test_scipy_names(free_run):
    r = free_run
    assert r.status == 0 and r.success and r.message == "the run reached t_end"
    assert r.y.shape == (len(r.state_names), len(r.t))
    np.testing.assert_array_equal(r.y[r.state_names.index("disc_speed")], r["disc_speed"])
    assert r.nfev == r.stats["rhs_evaluations"] > 0
    assert r.njev == r.stats["jacobian_evaluations"]
    assert r.t_events == [] and r.y_events == [] and r.stop_events == []


def test_each_switch_carries_the_state_before_and_after(free_run):
    sticks = [e for e in free_run.events if e.mode_after_name.startswith("stick")]
    assert len(sticks) >= 3
    w = free_run.state_names.index("disc_speed")
    for e in sticks:
        assert e.state_before.shape == e.state_after.shape == (len(free_run.state_names),)
        assert abs(e.state_before[w]) < 1e-6  # the root: the disc speed has reached zero
        assert e.state_after[w] == 0.0  # entering stick sets it to zero exactly
        others = [i for i in range(len(free_run.state_names)) if i != w]
        np.testing.assert_allclose(e.state_after[others], e.state_before[others], rtol=0, atol=1e-12)
    frame = free_run.events_frame()
    assert len(frame) == len(free_run.events)
    assert list(frame["disc_speed_after"][frame["mode_after"] == sticks[0].mode_after_name])[0] == 0.0


def test_terminal_mode_condition_stops_at_the_first_stick_of_the_disc(free_run):
    first_stick = next(e for e in free_run.events if e.mode_after_name.startswith("stick"))
    r = fs.simulate(rig(), 10.0, rtol=1e-10, atol=1e-12, events=[StopCondition(mode=first_stick.mode_after_name)])
    assert r.status == 1 and r.success and "mode" in r.message
    assert r.t[-1] == r.t_reached == pytest.approx(first_stick.time, abs=1e-9)
    assert r["disc_speed"][-1] == 0.0
    assert len(r.t_events) == 1 and r.t_events[0] == pytest.approx([first_stick.time], abs=1e-9)


def test_level_crossings_match_the_trajectory_and_respect_direction(free_run):
    level = 3.0
    conditions = [StopCondition(state="disc_speed", level=level, direction=+1, terminal=False),
                  StopCondition(state="disc_speed", level=level, direction=-1, terminal=False)]
    r = fs.simulate(rig(), 10.0, rtol=1e-10, atol=1e-12, events=conditions)
    assert r.status == 0
    # the crossings of the recorded trajectory (every internal step), located by linear interpolation
    w, t = free_run["disc_speed"] - level, free_run.t
    k = np.nonzero(np.sign(w[:-1]) != np.sign(w[1:]))[0]
    crossings = t[k] - w[k] * (t[k + 1] - t[k]) / (w[k + 1] - w[k])
    rising = crossings[w[k + 1] > w[k]]
    falling = crossings[w[k + 1] < w[k]]
    assert len(rising) >= 3 and len(r.t_events[0]) == len(rising)
    assert len(r.t_events[1]) == len(falling)
    np.testing.assert_allclose(r.t_events[0], rising, atol=2e-4)  # linear interpolation between steps
    np.testing.assert_allclose(r.t_events[1], falling, atol=2e-4)
    for ys in r.y_events:
        np.testing.assert_allclose(ys[:, r.state_names.index("disc_speed")], level, atol=1e-9)


def test_terminal_level_condition_ends_the_run_on_the_level():
    r = fs.simulate(rig(), 10.0, output_times=np.linspace(0.0, 10.0, 101),
                    events=[StopCondition(state="disc_speed", level=4.0, direction=+1)])
    assert r.status == 1
    assert r["disc_speed"][-1] == pytest.approx(4.0, abs=1e-9)
    assert r.t[-1] == r.t_events[0][0]
    assert np.all(np.diff(r.t) > 0)  # the output grid up to the stop, then the stop's row


def test_record_events_puts_rows_at_both_sides_of_each_switch():
    grid = np.linspace(0.0, 5.0, 51)
    r = fs.simulate(rig(), 5.0, output_times=grid, record_events=True)
    plain = fs.simulate(rig(), 5.0, output_times=grid)
    times = sorted({e.time for e in r.events})
    assert len(times) >= 3
    assert len(r.t) >= len(plain.t) + 2 * len(times)
    assert np.all(np.diff(r.t) >= 0)
    for time in times:
        at = [e for e in r.events if e.time == time]
        rows = np.nonzero(r.t == time)[0]
        assert len(rows) >= 2
        assert r.mode[rows[0]] == at[0].mode_before  # the state and mode just before the switch
        np.testing.assert_array_equal(r.states[rows[0]], at[0].state_before)
        assert r.mode[rows[-1]] == at[-1].mode_after  # and just after it
        np.testing.assert_array_equal(r.states[rows[-1]], at[-1].state_after)


def test_stop_conditions_are_checked():
    with pytest.raises(ValueError, match="stop_conditions.state"):
        fs.simulate(rig(), 1.0, events=[StopCondition(state="no_such_state", level=1.0)])
    with pytest.raises(ValueError, match="direction"):
        fs.simulate(rig(), 1.0, events=[StopCondition(state="disc_speed", level=1.0, direction=2)])
    with pytest.raises(ValueError, match="events"):
        fs.simulate(rig(), 1.0, events=["disc_speed"])
    with pytest.raises(ValueError, match="record_events"):
        fs.simulate(rig(), 1.0, record_events="yes")


def test_a_result_with_stop_events_pickles():
    r = fs.simulate(rig(), 3.0, events=[StopCondition(state="disc_speed", level=2.0, terminal=False)])
    back = pickle.loads(pickle.dumps(r))
    assert back.t_events[0] == pytest.approx(r.t_events[0])
    assert back.events[0].state_after == pytest.approx(r.events[0].state_after)


def test_conditions_read_back_from_solver_options_are_usable():
    # The list attribute hands out references into the C++ vector: they are constructed objects (repr, fields,
    # pickling), not the never-constructed instances that __new__ alone makes.
    from frictionsim import _core

    options = _core.SolverOptions()
    condition = fs.StopCondition(state="disc_speed", level=0.5, direction=-1, terminal=True)
    options.stop_conditions = [condition]
    (back,) = options.stop_conditions
    assert repr(back) == repr(condition) and back.level == 0.5 and back.direction == -1
    assert repr(pickle.loads(pickle.dumps(back))) == repr(condition)
    with pytest.raises(TypeError, match="never constructed"):
        repr(fs.StopCondition.__new__(fs.StopCondition))

