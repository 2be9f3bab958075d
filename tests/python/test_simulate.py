"""fs.simulate and the bound engine: results against closed forms and an independent SciPy implementation of the
same equations, conservation of energy, threads and pickling, and errors that name the parameter."""

import math
import pickle
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import frictionsim as fs

MU, K_T, N = 0.41, 4e4, 90.0  # paper 000: dry mu of Table 4, k_t of Fig. 10, F_N of Fig. 7(a)


# ------------------------------------------------------------------------------------------------ laws
def test_laws_keep_their_parameters_and_pickle():
    laws = [fs.Coulomb(0.3, mu_static=0.4), fs.Stribeck(0.3, 0.5, 1e-3, shape_exponent=1.5, viscous_coefficient=2.0),
            fs.Dahl(MU, K_T, exponent=2.0), fs.LuGre(1.0, 1.5, 1e-3, 1e5, 316.0, 0.4)]
    for law in laws:
        copy = pickle.loads(pickle.dumps(law))
        assert type(copy) is type(law) and repr(copy) == repr(law)
    assert fs.Coulomb(0.3).mu_static == 0.3  # default: static = kinetic
    assert (laws[2].mu, laws[2].tangential_stiffness, laws[2].exponent) == (MU, K_T, 2.0)
    assert laws[3].stribeck_level(0.0, 10.0) == pytest.approx(15.0)  # g(0) = mu_s N
    # slip force mu_c N + (mu_s - mu_c) N e^-(v/vs)^delta + sigma_v v
    v = 2e-3
    expected = (0.3 + 0.2 * math.exp(-(2.0 ** 1.5))) * 10.0 + 2.0 * v
    assert laws[1].slip_force(v, 10.0, 1) == pytest.approx(expected, rel=1e-14)


@pytest.mark.parametrize("make, parameter", [
    (lambda: fs.Coulomb(-0.1), "mu"),
    (lambda: fs.Coulomb(0.4, mu_static=0.3), "mu_static"),
    (lambda: fs.Coulomb(0.4, mu_static=float("nan")), "mu_static"),  # NaN is not "unset"
    (lambda: fs.Stribeck(0.3, 0.4, 0.0), "stribeck_velocity"),
    (lambda: fs.Stribeck(0.3, 0.4, 1e-3, karnopp_band=-1.0), "karnopp_band"),
    (lambda: fs.Dahl(MU, float("nan")), "tangential_stiffness"),
    (lambda: fs.Dahl(MU, K_T, exponent=-1.0), "exponent"),
    (lambda: fs.LuGre(1.0, 1.5, 1e-3, -1.0, 1.0), "bristle_stiffness"),
    (lambda: fs.PowerLawCoefficient(0.0, -0.2), "eta"),
])
def test_bad_law_parameters_are_value_errors_naming_the_parameter(make, parameter):
    with pytest.raises(ValueError, match=parameter) as info:
        make()
    assert isinstance(info.value, fs.InvalidParameterError) and info.value.parameter == parameter


def test_power_law_coefficient_is_table5_and_eq17():
    obm = fs.PowerLawCoefficient.from_table5("OBM")
    assert (obm.eta, obm.exponent) == (0.1332, -0.20306)
    rows = {r["lubricant"]: r for r in fs.table5()}
    assert rows["dry"]["intercept"] == 0.0284 and rows["sbm"]["r_squared"] == 0.87
    v_a = fs.vibration_velocity_amplitude(5e-3, 17.0)  # eq 16
    assert v_a == pytest.approx(2 * math.pi * 17 * 5e-3)
    ratios = np.array([200.0, 800.0, 2000.0])
    np.testing.assert_allclose(obm.coefficient(ratios * 1e-3, 1e-3), 0.1332 * ratios ** -0.20306, rtol=1e-14)
    # eq 15's eta in (u0 f / v_d)^c equals eta' (2 pi)^c (eq 17)
    eq15 = fs.PowerLawCoefficient.from_eq15(obm.eta * (2 * math.pi) ** obm.exponent, obm.exponent)
    assert eq15.eta == pytest.approx(obm.eta, rel=1e-14)
    with pytest.raises(ValueError, match="lubricant"):
        fs.PowerLawCoefficient.from_table5("mud")
    with pytest.raises(TypeError, match="cycle-averaged"):
        fs.AxialVibrationRig(friction=obm)


# ------------------------------------------------------------------------------------------------ results
def test_axial_rig_defaults_are_paper_fig7a_and_result_is_numpy():
    rig = fs.AxialVibrationRig(friction=fs.Dahl(MU, K_T))
    assert (rig.amplitude, rig.frequency, rig.sliding_velocity, rig.normal_force) == (5e-3, 17.0, 1e-3, 90.0)
    assert rig.vibration_velocity_amplitude == pytest.approx(2 * math.pi * 17 * 5e-3)
    times = np.linspace(0.0, 0.5, 501)
    result = fs.simulate(rig, 0.5, output_times=times)
    assert result.completed and result.t_reached == 0.5
    np.testing.assert_array_equal(result.t, times)
    assert result.state_names == ["position", "velocity", "dahl_deflection", "friction_impulse", "friction_work",
                                  "drive_work"] == rig.state_names
    assert result.states.shape == (501, 6) and isinstance(result.friction_force, np.ndarray)
    np.testing.assert_array_equal(result["velocity"], result.velocity)
    np.testing.assert_allclose(result.friction_force, K_T * result.dahl_deflection, rtol=1e-15)  # F = k_t z
    assert all(e.name == "relative_velocity" for e in result.events) and len(result.events) > 10
    assert result.stats["events"] == len(result.events) and result.stats["steps"] > 0
    frame = result.to_pandas()
    assert list(frame.columns) == result.state_names + ["friction_force", "mode"] and len(frame) == 501
    with pytest.raises(KeyError, match="no state 'speed'"):
        result["speed"]
    with pytest.raises(ValueError):  # results are read-only views
        result.t[0] = 1.0


def test_kinematic_coulomb_mean_force_is_the_closed_form():
    # v_r = v_d - v_a cos(wt): F = mu N sgn(v_r) averages to (2/pi) asin(v_d/v_a) mu N over a cycle.
    for ratio in (0.1, 0.5, 0.9):
        rig = fs.KinematicRig.harmonic(fs.Coulomb(MU), sliding_velocity=ratio * 0.5, velocity_amplitude=0.5,
                                       frequency=17.0, normal_force=N)
        mean = fs.simulate(rig, 10 / 17).mean_over_cycles()
        assert mean == pytest.approx(2 / math.pi * math.asin(ratio) * MU * N, rel=1e-7)


def test_relative_velocity_as_callable_samples_or_harmonic_agree():
    law, v_d, v_a, f = fs.Dahl(MU, K_T), 0.1, 0.5, 17.0
    harmonic = fs.KinematicRig.harmonic(law, sliding_velocity=v_d, velocity_amplitude=v_a, frequency=f,
                                        normal_force=N)
    callable_ = fs.KinematicRig(law, relative_velocity=lambda t: v_d - v_a * math.cos(2 * math.pi * f * t),
                                normal_force=lambda t: N)
    t = np.linspace(0.0, 0.3, 30001)
    sampled = fs.KinematicRig(law, relative_velocity=(t, v_d - v_a * np.cos(2 * np.pi * f * t)),
                              normal_force=(t, np.full_like(t, N)))
    means = [fs.simulate(r, 0.29, rtol=1e-10).mean_over_cycles(period=1 / f, transient=0.1)
             for r in (harmonic, callable_, sampled)]
    assert means[1] == pytest.approx(means[0], rel=1e-8)
    assert means[2] == pytest.approx(means[0], rel=1e-4)  # linear interpolation between 1e-5 s samples


# --------------------------------------------------------------------------------- independent SciPy model
def scipy_axial_dahl(t_end, t_eval, m=0.2, k_d=2e4, v_d=1e-3, u0=5e-3, f=17.0):
    """Paper 000 eqs 5-9 with Dahl friction (alpha = 1), written out again for solve_ivp."""
    w = 2 * math.pi * f

    def rhs(t, y):
        x, v, z, impulse = y
        v_r = v - u0 * w * math.cos(w * t)
        force = K_T * z
        return [v, (k_d * (v_d * t - x) - force) / m, v_r * (1 - K_T / (MU * N) * np.sign(v_r) * z), force]

    return solve_ivp(rhs, (0.0, t_end), [0, 0, 0, 0], method="DOP853", rtol=1e-12, atol=1e-14, t_eval=t_eval)


def test_axial_dahl_agrees_with_an_independent_scipy_implementation():
    t_end, times = 0.5, np.linspace(0.0, 0.5, 201)
    reference = scipy_axial_dahl(t_end, times)
    assert reference.success
    for method in ("dormand_prince", "cvode_bdf"):
        result = fs.simulate(fs.AxialVibrationRig(friction=fs.Dahl(MU, K_T)), t_end, output_times=times,
                             method=method, rtol=1e-10, atol=1e-13)
        scale = np.abs(reference.y).max(axis=1)
        for i, name in enumerate(["position", "velocity", "dahl_deflection", "friction_impulse"]):
            assert np.max(np.abs(result[name] - reference.y[i])) < 1e-6 * scale[i], (method, name)
        t_a, t_b = 0.5 - 4 / 17, 0.5
        ref_mean = (np.interp(t_b, times, reference.y[3]) - np.interp(t_a, times, reference.y[3])) / (t_b - t_a)
        assert result.mean_over_cycles(transient=t_a) == pytest.approx(ref_mean, abs=1e-6 * MU * N)


@pytest.mark.parametrize("law", [fs.Coulomb(MU, mu_static=0.5), fs.Dahl(MU, K_T), fs.LuGre(MU, 0.5, 1e-3, 1e5, 300.0, 0.4)])
@pytest.mark.parametrize("gravity", [False, True])
def test_axial_rig_energy_balance(law, gravity):
    # drive work = change of kinetic + spring + potential energy + friction work (+ energy stored in the law)
    rig = fs.AxialVibrationRig(friction=law, gravity=gravity, amplitude=1e-3, frequency=10.0, sliding_velocity=2e-3)
    r = fs.simulate(rig, 0.5, rtol=1e-10, atol=1e-12)
    stretch = rig.sliding_velocity * r.t - r.position
    weight = rig.mass * 9.81 if gravity else 0.0
    energy = 0.5 * rig.mass * r.velocity ** 2 + 0.5 * rig.drive_stiffness * stretch ** 2 + weight * r.position
    balance = r.drive_work - (energy - energy[0]) - r.friction_work
    assert np.max(np.abs(balance)) < 1e-7 * max(np.max(np.abs(r.drive_work)), 1e-6)
    np.testing.assert_allclose(rig.drive_force(r.t, r.position), rig.drive_stiffness * stretch, rtol=1e-15)


# ------------------------------------------------------------------------------------- threads and pickle
def test_threads_and_pickled_rigs_give_identical_results():
    rigs = [fs.AxialVibrationRig(friction=law, amplitude=a) for law in (fs.Coulomb(MU), fs.Dahl(MU, K_T))
            for a in (1e-3, 5e-3)]
    serial = [fs.simulate(r, 0.3) for r in rigs]
    with ThreadPoolExecutor(max_workers=2) as pool:
        threaded = list(pool.map(lambda r: fs.simulate(r, 0.3), rigs))
    unpickled = [fs.simulate(pickle.loads(pickle.dumps(r)), 0.3) for r in rigs]
    for a, b, c in zip(serial, threaded, unpickled):
        np.testing.assert_array_equal(a.states, b.states)
        np.testing.assert_array_equal(a.states, c.states)
    result = pickle.loads(pickle.dumps(serial[0]))  # before its event log was read: that is read out lazily
    np.testing.assert_array_equal(result.friction_force, serial[0].friction_force)
    assert len(result.events) == serial[0].stats["events"] > 0
    assert result.events == serial[0].events


# ---------------------------------------------------------------------------------------------- errors
@pytest.mark.parametrize("parameter, kwargs", [
    ("mass", dict(mass=0.0)), ("drive_stiffness", dict(drive_stiffness=-1.0)),
    ("sliding_velocity", dict(sliding_velocity=float("nan"))), ("amplitude", dict(amplitude=-1e-3)),
    ("frequency", dict(frequency=0.0)), ("normal_force", dict(normal_force=-90.0)),
    ("initial_position", dict(initial_position=float("inf"))),
])
def test_bad_rig_parameters_name_the_parameter(parameter, kwargs):
    with pytest.raises(ValueError, match=parameter) as info:
        fs.AxialVibrationRig(friction=fs.Coulomb(MU), **kwargs)
    assert info.value.parameter == parameter


@pytest.mark.parametrize("parameter, kwargs", [
    ("rtol", dict(rtol=0.0)), ("atol", dict(atol=-1.0)), ("output_times", dict(output_times=[0.2, 0.1])),
    ("output_times", dict(output_times=[0.0, 2.0])), ("max_steps", dict(max_steps=0)),
    ("atol_per_state", dict(atol_per_state=[1e-9])), ("method", dict(method="euler")), ("rtol", dict(rtol=1.0)),
    ("max_steps", dict(max_steps=1.5)),
])
def test_bad_solver_options_name_the_option(parameter, kwargs):
    with pytest.raises(ValueError, match=parameter):
        fs.simulate(fs.AxialVibrationRig(friction=fs.Coulomb(MU)), 1.0, **kwargs)


def test_bad_kinematic_inputs():
    with pytest.raises(ValueError, match="normal_force"):
        fs.KinematicRig(fs.Coulomb(MU), relative_velocity=1.0, normal_force=0.0)
    with pytest.raises(ValueError, match="relative_velocity"):
        fs.KinematicRig(fs.Coulomb(MU), relative_velocity=([0.0, 1.0], [1.0]), normal_force=N)
    with pytest.raises(ValueError, match="karnopp_band"):
        fs.KinematicRig(fs.Stribeck(0.3, 0.4, 1e-3, karnopp_band=1e-4), relative_velocity=1.0, normal_force=N)
    with pytest.raises(ValueError, match="initial_state"):
        fs.KinematicRig(fs.Coulomb(MU), relative_velocity=1.0, normal_force=N, initial_state=[0.0])
    with pytest.raises(TypeError, match="relative_velocity"):
        fs.KinematicRig(fs.Coulomb(MU), relative_velocity="fast", normal_force=N)
    sampled = fs.KinematicRig(fs.Dahl(MU, K_T), relative_velocity=([0.0, 1.0], [1.0, -1.0]), normal_force=N)
    with pytest.raises(ValueError, match="t_end"):  # past the data: said up front, not at the edge of the data
        fs.simulate(sampled, 1.5)


def test_numpy_scalars_and_cycle_counts():
    rig = fs.KinematicRig(fs.Coulomb(MU), relative_velocity=np.float32(0.5), normal_force=np.int64(90))
    assert rig.normal_force == 90.0
    result = fs.simulate(rig, 1.0)
    assert result.mean_over_cycles(period=0.1, cycles=np.int64(3)) == pytest.approx(MU * N, rel=1e-12)
    for cycles in (0, -1, 2.5, True):
        with pytest.raises(ValueError, match="cycles"):
            result.mean_over_cycles(period=0.1, cycles=cycles)


def test_failed_run_reports_time_reached_and_keeps_the_partial_result():
    def velocity(t):
        if t > 0.3:
            raise RuntimeError("sensor lost")
        return math.sin(40 * t)

    rig = fs.KinematicRig(fs.Dahl(MU, K_T), relative_velocity=velocity, normal_force=N)
    with pytest.raises(fs.SimulationError, match="sensor lost") as info:
        fs.simulate(rig, 1.0)
    error = info.value
    assert 0.25 < error.time_reached <= 0.3
    partial = error.partial
    assert partial.period is None  # a callable v_r has no period; an axial rig's partial keeps its 1/f
    assert not partial.completed and partial.t[-1] == pytest.approx(error.time_reached)
    assert partial.t_reached == error.time_reached and len(partial) > 10
    # the partial trajectory is the trajectory: it matches an unbroken run up to the failure
    whole = fs.simulate(fs.KinematicRig(fs.Dahl(MU, K_T), relative_velocity=lambda t: math.sin(40 * t),
                                        normal_force=N), 0.25, output_times=[0.25])
    assert np.interp(0.25, partial.t, partial.dahl_deflection) == pytest.approx(whole.dahl_deflection[-1], rel=1e-3)


def test_chattering_is_reported_with_the_switching_function():
    rig = fs.KinematicRig(fs.Coulomb(MU), relative_velocity=lambda t: math.sin(2 * math.pi * 2000 * t),
                          normal_force=N)
    with pytest.raises(fs.ChatteringError) as info:
        fs.simulate(rig, 0.1, max_events_in_window=3, event_window=1e-3)  # 4 reversals per ms
    assert info.value.switching_function == "relative_velocity"
    assert info.value.time_reached < 0.01 and len(info.value.partial.events) >= 3


# ---------------------------------------------------------------------------------------------- contact
def test_hydraulic_oscillator_normal_force_is_eqs_1_to_4():
    tool = dict(tool_outer_radius=0.0855, tool_inner_radius=0.035, wellbore_radius=0.108, steel_density=7850.0,
                mud_density=1200.0, rock_youngs_modulus=20e9, rock_poisson_ratio=0.25, steel_youngs_modulus=210e9,
                steel_poisson_ratio=0.3, rock_wear_width=0.01, specimen_width=0.03)
    hot = fs.contact.HydraulicOscillatorTool(**tool)
    q = 9.81 * math.pi * (0.0855 ** 2 - 0.035 ** 2) * (7850.0 - 1200.0)  # eq 1
    compliance = (1 - 0.25 ** 2) / 20e9 + (1 - 0.3 ** 2) / 210e9
    sigma = math.sqrt(q * (1 / 0.0855 - 1 / 0.108) / (math.pi * compliance))  # eq 2
    assert hot.weight_per_length_in_mud() == pytest.approx(q, rel=1e-14)
    assert hot.contact_stress() == pytest.approx(sigma, rel=1e-14)
    assert hot.equivalent_rig_normal_force() == pytest.approx(0.01 * 0.03 * sigma, rel=1e-14)  # eq 4
    assert fs.contact.rig_contact_stress(90.0, 0.01, 0.03) == pytest.approx(90.0 / 3e-4)  # eq 3
    with pytest.raises(ValueError, match="tool_outer_radius"):
        fs.contact.HydraulicOscillatorTool(**{**tool, "tool_outer_radius": 0.2})
    with pytest.raises(ValueError, match="rock_poisson_ratio"):
        fs.contact.HydraulicOscillatorTool(**{**tool, "rock_poisson_ratio": 0.5})


def test_partial_result_of_an_axial_rig_keeps_its_period():
    rig = fs.AxialVibrationRig(friction=fs.Dahl(MU, K_T))
    with pytest.raises(fs.SimulationError, match="max_steps") as info:
        fs.simulate(rig, 2.0, max_steps=3000)
    partial = info.value.partial
    assert partial.period == rig.period and 0.0 < partial.t_reached < 2.0
    assert partial.mean_over_cycles(cycles=1) > 0.0  # usable as is: no period to pass


def test_event_log_is_read_out_lazily_and_survives_copies_and_pickles():
    """A Result moves the engine's event log out of its raw result (so the raw columns are not kept alive) and makes
    Event objects only when asked; pickles, copies and a failed run's partial result carry it intact."""
    import copy

    rig = fs.AxialVibrationRig(friction=fs.Dahl(MU, K_T))
    options = fs._core.SolverOptions()
    options.output_times = [0.0, 0.3]
    raw = rig._simulate(0.3, options, 0.0)
    result = fs.Result(raw)
    assert len(raw.events) == 0  # moved out, not copied
    reference = fs.simulate(rig, 0.3, output_times=[0.0, 0.3]).events
    assert len(reference) == result.stats["events"] > 10
    for duplicate in (copy.copy(result), copy.deepcopy(result), pickle.loads(pickle.dumps(result))):
        assert duplicate.events == reference
    assert result.events == reference
    # a failed run: the partial result's events pickle before they were ever read
    with pytest.raises(fs.SimulationError) as info:
        fs.simulate(rig, 2.0, max_steps=3000)
    error = pickle.loads(pickle.dumps(info.value))
    assert len(error.partial.events) == error.partial.stats["events"] > 0
    assert error.partial.events == info.value.partial.events
