"""Friction-law identification (frictionsim.fit.identify_* and identify_axial_rig): synthetic round trips.

Every record is simulated by the engine at tight tolerance (rtol 1e-10) from known parameters, Gaussian noise
is added (fixed seeds), and the fit must recover the parameters within the stated tolerance and within
3 standard errors. The identifiability tests use records that cannot determine some parameters and check
that exactly those are flagged.
"""

import numpy as np
import pytest

import frictionsim as fs
from frictionsim.fit import (
    LAW_PARAMETERS,
    IdentificationResult,
    identify,
    identify_axial_rig,
    identify_dahl,
    identify_lugre,
    identify_stribeck,
)

N = 90.0  # F_N [N], paper 000 Fig 7(a)
F_HZ, V_D, V_A = 17.0, 1e-3, 0.534  # f [Hz], v_d [m/s], v_a [m/s] of paper 000 Fig 10 (u0 = 5 mm)
DAHL_TRUE = dict(mu=0.41, tangential_stiffness=4e4, exponent=1.0)  # k_t = 40 N/mm (Fig 10)


def simulate_force(law, t, v, normal_force=N, initial_state=None):
    rig = fs.KinematicRig(law, relative_velocity=(t, v), normal_force=normal_force, initial_state=initial_state)
    return fs.simulate(rig, t[-1], output_times=t, t_start=t[0], rtol=1e-10, atol=1e-12).friction_force


def check_recovered(result, truth, rtol):
    """Each parameter within its relative tolerance and within 3 standard errors of the truth."""
    for name, true in truth.items():
        value, se = result.params[name], result.stderr[name]
        assert value == pytest.approx(true, rel=rtol[name]), (name, value, true)
        assert abs(value - true) <= 3.0 * se, (name, value, true, se)


# ------------------------------------------------------------------------------------------------ Dahl
@pytest.fixture(scope="module")
def dahl_record():
    """0.2 s (3.4 cycles) of v_r = v_d - v_a cos(2 pi f t) at 5 kHz: the force reverses every half cycle."""
    t = np.arange(0.0, 0.2, 1.0 / 5000.0)
    v = V_D - V_A * np.cos(2.0 * np.pi * F_HZ * t)
    force = simulate_force(fs.Dahl(**DAHL_TRUE), t, v)
    sigma = 0.01 * DAHL_TRUE["mu"] * N  # 1 % of mu N
    noisy = force + np.random.default_rng(1).normal(0.0, sigma, t.size)
    return t, v, noisy, sigma


@pytest.fixture(scope="module")
def dahl_fit(dahl_record):
    t, v, force, _ = dahl_record
    return identify_dahl(t, v, force, N, initial_guess=dict(mu=0.3, tangential_stiffness=1e4, exponent=1.5))


def test_dahl_round_trip_from_perturbed_guess(dahl_record, dahl_fit):
    _, _, _, sigma = dahl_record
    result = dahl_fit
    assert isinstance(result, IdentificationResult)
    assert result.success, result.message
    # mu within 1 %, k_t within 2 %, alpha within 3 % (measured: 0.03 %, 0.07 %, 0.3 %), and within 3 s.e.
    check_recovered(result, DAHL_TRUE, dict(mu=0.01, tangential_stiffness=0.02, exponent=0.03))
    assert result.fitted == ("mu", "tangential_stiffness", "exponent")
    assert all(result.identifiable.values()), result.reasons
    assert result.rms_residual == pytest.approx(sigma, rel=0.1)  # the residual is the noise
    assert result.r_squared > 0.999
    assert result.n_failed == 0 and result.n_evaluations > 10
    assert isinstance(result.law, fs.Dahl)
    assert result.law.tangential_stiffness == result.params["tangential_stiffness"]
    assert result.law.exponent == result.params["exponent"]
    assert result.model.shape == result.measured.shape == result.t.shape
    corr = result.correlation
    assert corr.shape == (3, 3) and np.allclose(np.diag(corr), 1.0) and np.allclose(corr, corr.T)


def test_dahl_without_initial_guess_reaches_the_same_fit(dahl_record, dahl_fit):
    t, v, force, _ = dahl_record
    result = identify_dahl(t, v, force, N)  # data-based mu, coarse k_t scan, then least squares
    for name, value in dahl_fit.params.items():
        assert result.params[name] == pytest.approx(value, rel=1e-3), name


def test_dahl_standard_errors_follow_the_chain_rule(dahl_record, dahl_fit):
    """s^2 (J^T J)^-1 recomputed here with J in the physical parameters (no log transform)."""
    t, v, force, _ = dahl_record
    names = ["mu", "tangential_stiffness", "exponent"]
    p = np.array([dahl_fit.params[n] for n in names])

    def model(values):
        return simulate_force(fs.Dahl(*values), t, v, initial_state=[force[0] / values[1]])

    jac = np.empty((t.size, 3))
    for i in range(3):
        h = 1e-3 * p[i]
        up, down = p.copy(), p.copy()
        up[i] += h
        down[i] -= h
        jac[:, i] = (model(up) - model(down)) / (2.0 * h)
    residual = model(p) - force
    s2 = residual @ residual / (t.size - 3)
    stderr = np.sqrt(np.diag(s2 * np.linalg.inv(jac.T @ jac)))
    for name, se in zip(names, stderr):
        assert dahl_fit.stderr[name] == pytest.approx(se, rel=0.05), name


def test_dahl_fit_exponent_false_and_generic_identify(dahl_record, dahl_fit):
    t, v, force, _ = dahl_record
    result = identify("Dahl", t, v, force, N, fit_exponent=False,
                      initial_guess=dict(mu=0.3, tangential_stiffness=1e4))
    assert result.fitted == ("mu", "tangential_stiffness")
    assert result.params["exponent"] == 1.0 and result.stderr["exponent"] == 0.0
    assert "fixed" in result.reasons["exponent"]
    check_recovered(result, dict(mu=0.41, tangential_stiffness=4e4), dict(mu=0.01, tangential_stiffness=0.02))


def test_dahl_fitted_initial_state(dahl_record):
    t, v, force, sigma = dahl_record
    result = identify_dahl(t, v, force, N, fit_exponent=False, initial_state="fit")
    assert "initial_force" in result.fitted
    # the record starts from rest (F0 = 0): the fitted F_0 must agree within 3 s.e. and within 2 sigma_noise
    assert abs(result.params["initial_force"]) <= 3.0 * result.stderr["initial_force"]
    assert abs(result.params["initial_force"]) < 2.0 * sigma
    assert result.initial_state == [pytest.approx(result.params["initial_force"] /
                                                  result.params["tangential_stiffness"])]


def test_summary_and_dataframe(dahl_fit):
    text = dahl_fit.summary()
    for word in ("Dahl", "tangential_stiffness", "std. error", "identifiable", "R^2", "correlation"):
        assert word in text
    frame = dahl_fit.to_pandas()
    assert list(frame.index) == ["mu", "tangential_stiffness", "exponent"]
    for column in ("value", "stderr", "relative_stderr", "unit", "fitted", "identifiable", "reason"):
        assert column in frame.columns
    assert frame.loc["tangential_stiffness", "unit"] == "N/m"
    assert frame.loc["mu", "value"] == dahl_fit.params["mu"]
    assert dahl_fit.correlation_frame().shape == (3, 3)


# ------------------------------------------------------------------------------------------------ identifiability
def test_dahl_without_reversal_flags_stiffness_and_exponent():
    """v_r never reverses and the force sits at mu N throughout: k_t and alpha are not identifiable, mu is."""
    t = np.arange(0.0, 0.2, 1.0 / 5000.0)
    v = 0.05 + 0.02 * np.cos(2.0 * np.pi * F_HZ * t)  # 0.03 .. 0.07 m/s, far from zero
    saturated = [DAHL_TRUE["mu"] * N / DAHL_TRUE["tangential_stiffness"]]
    force = simulate_force(fs.Dahl(**DAHL_TRUE), t, v, initial_state=saturated)
    force = force + np.random.default_rng(0).normal(0.0, 0.01 * DAHL_TRUE["mu"] * N, t.size)
    result = identify_dahl(t, v, force, N)
    assert result.identifiable["mu"], result.reasons["mu"]
    assert result.params["mu"] == pytest.approx(0.41, rel=0.005)
    assert result.reasons["mu"].startswith("identified")
    for name in ("tangential_stiffness", "exponent"):
        assert not result.identifiable[name], (name, result.reasons[name])
        assert result.reasons[name] and not result.reasons[name].startswith("identified")
    assert "NO:" in result.summary()
    assert not result.all_identifiable


def test_lugre_quasi_static_flags_bristle_damping():
    """Quasi-static sliding (|v_r| <= 2 mm/s): sigma_1 dz/dt is below the noise, sigma_0 and mu still show."""
    t = np.linspace(0.0, 10.0, 2001)
    v = 2e-3 * np.sin(2.0 * np.pi * 0.1 * t)
    law = fs.LuGre(0.3, 0.45, 5e-4, 1e5, 300.0, 20.0)
    force = simulate_force(law, t, v) + np.random.default_rng(3).normal(0.0, 0.01 * 0.3 * N, t.size)
    result = identify_lugre(t, v, force, N)
    assert not result.identifiable["bristle_damping"], result.reasons["bristle_damping"]
    for name in ("mu", "bristle_stiffness", "stribeck_velocity"):
        assert result.identifiable[name], (name, result.reasons[name])
    assert result.params["bristle_stiffness"] == pytest.approx(1e5, rel=0.02)


# ------------------------------------------------------------------------------------------------ LuGre, Stribeck
@pytest.fixture(scope="module")
def sweep():
    """2 s of v_r = 0.1 sin(2 pi t) m/s at 1 kHz: four reversals, |v_r| sweeps through the Stribeck region."""
    t = np.linspace(0.0, 2.0, 2001)
    return t, 0.1 * np.sin(2.0 * np.pi * t)


def test_lugre_round_trip(sweep):
    t, v = sweep
    truth = dict(mu=0.3, mu_static=0.45, stribeck_velocity=0.01, bristle_stiffness=1e5, bristle_damping=300.0,
                 viscous_damping=20.0)
    force = simulate_force(fs.LuGre(**truth), t, v)
    force = force + np.random.default_rng(3).normal(0.0, 0.01 * 0.3 * N, t.size)
    guess = dict(mu=0.25, mu_static=0.5, stribeck_velocity=0.02, bristle_stiffness=5e4, bristle_damping=150.0,
                 viscous_damping=10.0)
    result = identify_lugre(t, v, force, N, initial_guess=guess)
    assert result.success, result.message
    # measured errors: 0.07 %, 0.4 %, 0.4 %, 0.7 %, 4.3 %, 1.7 %
    check_recovered(result, truth, dict(mu=0.01, mu_static=0.05, stribeck_velocity=0.05, bristle_stiffness=0.03,
                                        bristle_damping=0.10, viscous_damping=0.05))
    assert all(result.identifiable.values()), result.reasons
    assert isinstance(result.law, fs.LuGre) and result.law.mu_static == result.params["mu_static"]
    assert result.params["mu_static"] >= result.params["mu"]


def test_stribeck_round_trip_with_sampled_normal_force(sweep):
    t, v = sweep
    normal = N + 5.0 * np.sin(2.0 * np.pi * 0.7 * t)  # N(t) samples
    truth = dict(mu=0.3, mu_static=0.45, stribeck_velocity=0.01, shape_exponent=2.0, viscous_coefficient=20.0)
    force = simulate_force(fs.Stribeck(**truth), t, v, normal_force=(t, normal))
    force = force + np.random.default_rng(2).normal(0.0, 0.01 * 0.3 * N, t.size)
    result = identify_stribeck(t, v, force, normal)  # no initial guess
    assert result.success, result.message
    check_recovered(result, truth, dict(mu=0.01, mu_static=0.01, stribeck_velocity=0.02, shape_exponent=0.05,
                                        viscous_coefficient=0.05))
    assert all(result.identifiable.values()), result.reasons
    assert isinstance(result.law, fs.Stribeck) and result.law.karnopp_band == 0.0


# ------------------------------------------------------------------------------------------------ any engine law
@pytest.mark.skipif(not hasattr(fs, "GeneralizedMaxwellSlip"), reason="engine built without GeneralizedMaxwellSlip")
def test_gms_is_identified_by_key_from_its_parameter_table():
    """identify() fits any engine law with something to fit from the law's own parameter table: the generalized
    Maxwell-slip law has no identify_* function and no entry in the fit's search hints for its attraction and
    block parameters. One cycle of its own friction force (+-0.8 mm, past every block's break-away, 5-160 um at
    10 N) gives back its Stribeck curve and the four block stiffnesses; attraction, shape and damping are held by
    fixed=, the block weights (tied: they sum to 1) at their defaults."""
    t = np.linspace(0.0, 1.0, 401)
    v = 5e-3 * np.sin(2.0 * np.pi * t)
    normal = 10.0
    truth = dict(mu=0.3, mu_static=0.4, stribeck_velocity=1e-3, block_stiffness_1=8e4, block_stiffness_2=4e4,
                 block_stiffness_3=2e4, block_stiffness_4=1e4)
    sigma = 0.01  # N, 0.3 % of mu N
    force = simulate_force(fs.GeneralizedMaxwellSlip(**truth), t, v, normal_force=normal)
    force = force + np.random.default_rng(5).normal(0.0, sigma, t.size)
    fixed = dict(shape_exponent=2.0, attraction=4000.0, block_damping=0.0, viscous_damping=0.0)
    result = identify("gms", t, v, force, normal, fixed=fixed)  # no initial guess: the record's and the table's
    assert result.success, result.message
    assert result.law_name == "GeneralizedMaxwellSlip" and isinstance(result.law, fs.GeneralizedMaxwellSlip)
    assert set(result.fitted) == set(truth)
    # measured errors: 0.001 %, 0.03 %, 0.2 %, 0.2 %, 0.1 %, 0.02 %, 0.02 % (all within 0.5 s.e.)
    check_recovered(result, truth, dict(mu=0.01, mu_static=0.01, stribeck_velocity=0.02, block_stiffness_1=0.03,
                                        block_stiffness_2=0.02, block_stiffness_3=0.02, block_stiffness_4=0.02))
    assert all(result.identifiable.values()), result.reasons
    assert result.rms_residual == pytest.approx(sigma, rel=0.1)
    assert [result.params[f"block_weight_{i}"] for i in range(1, 5)] == [0.1, 0.2, 0.3, 0.4]
    assert "fixed" in result.reasons["block_weight_1"]
    assert result.to_pandas().loc["block_stiffness_1", "symbol"] == "k_1"  # from the engine's table
    # by class, with the weights given: the same fit; a weight cannot be fitted on its own
    weights = {f"block_weight_{i}": w for i, w in zip(range(1, 5), (0.1, 0.2, 0.3, 0.4))}
    again = identify(fs.GeneralizedMaxwellSlip, t, v, force, normal, fixed=dict(fixed, **weights))
    assert again.params == result.params
    with pytest.raises(ValueError) as excinfo:
        identify("gms", t, v, force, normal, initial_guess=dict(block_weight_1=0.2))
    assert parameter_of(excinfo) == "initial_guess['block_weight_1']"


# ------------------------------------------------------------------------------------------------ global search
def test_differential_evolution_without_initial_guess_is_deterministic():
    """Default bounds (mu 1e-4..10, k_t 10..1e10 N/m, alpha 0.5..4), no starting point: the paper's
    genetic / PSO role. 0.12 s record, popsize 8, 30 generations, then a least-squares polish."""
    t = np.arange(0.0, 0.12, 1.0 / 5000.0)
    v = V_D - V_A * np.cos(2.0 * np.pi * F_HZ * t)
    force = simulate_force(fs.Dahl(**DAHL_TRUE), t, v)
    force = force + np.random.default_rng(5).normal(0.0, 0.01 * DAHL_TRUE["mu"] * N, t.size)
    kwargs = dict(method="differential_evolution", popsize=8, maxiter=30, seed=3)
    result = identify_dahl(t, v, force, N, **kwargs)
    check_recovered(result, DAHL_TRUE, dict(mu=0.01, tangential_stiffness=0.02, exponent=0.03))
    assert "differential_evolution" in result.message and result.method == "differential_evolution"
    again = identify_dahl(t, v, force, N, **kwargs)
    assert again.params == result.params


# ------------------------------------------------------------------------------------------------ rig level
@pytest.fixture(scope="module")
def rig_record():
    """0.5 s of the paper-000 rig (Fig 7(a) setup) from rest, transient included, drive force at 2 kHz."""
    t = np.linspace(0.0, 0.5, 1001)
    rig = fs.AxialVibrationRig(friction=fs.Dahl(0.41, 4e4))
    run = fs.simulate(rig, t[-1], output_times=t, rtol=1e-10, atol=1e-12)
    drive = rig.drive_force(run.t, run.position)
    sigma = 0.02 * float(np.std(drive))  # 2 % of the signal's spread (~0.6 N)
    return t, drive + np.random.default_rng(0).normal(0.0, sigma, t.size), sigma


def test_axial_rig_recovers_tangential_stiffness(rig_record):
    t, drive, sigma = rig_record
    result = identify_axial_rig(t, drive, initial_guess=dict(mu=0.3, tangential_stiffness=2e4))
    assert result.success, result.message
    assert result.signal_name == "drive_force" and isinstance(result.rig, fs.AxialVibrationRig)
    # k_t within 1 %, mu within 0.5 % (measured: 0.09 %, 0.01 %), and within 3 s.e.
    check_recovered(result, dict(mu=0.41, tangential_stiffness=4e4), dict(mu=0.005, tangential_stiffness=0.01))
    assert result.fitted == ("mu", "tangential_stiffness") and result.params["exponent"] == 1.0
    assert all(result.identifiable.values())
    assert result.rms_residual == pytest.approx(sigma, rel=0.1)
    auto = identify_axial_rig(t, drive)  # no guess: scan, then least squares
    for name in ("mu", "tangential_stiffness"):
        assert auto.params[name] == pytest.approx(result.params[name], rel=1e-3)


def test_axial_rig_differential_evolution_and_transient(rig_record):
    t, drive, _ = rig_record
    result = identify_axial_rig(t, drive, method="differential_evolution", popsize=6, maxiter=15, seed=1,
                                bounds=dict(mu=(0.1, 1.0), tangential_stiffness=(1e3, 1e6)), transient=0.1)
    assert result.n_samples == int(np.count_nonzero(t >= 0.1)) and result.t[0] >= 0.1
    check_recovered(result, dict(mu=0.41, tangential_stiffness=4e4), dict(mu=0.005, tangential_stiffness=0.01))


# ------------------------------------------------------------------------------------------------ failures, bad input
def test_failed_simulations_give_a_finite_residual_not_a_crash(dahl_record):
    t, v, force, _ = dahl_record
    result = identify_dahl(t, v, force, N, simulate_options=dict(max_steps=5), max_nfev=3)
    assert not result.success
    assert result.n_failed == result.n_evaluations > 0
    assert "failed" in result.message


def parameter_of(excinfo):
    assert isinstance(excinfo.value, ValueError) and isinstance(excinfo.value, fs.InvalidParameterError)
    return excinfo.value.parameter


@pytest.mark.parametrize("change, parameter", [
    (dict(relative_velocity=np.zeros(5)), "relative_velocity"),
    (dict(friction_force=np.full(50, np.nan)), "friction_force"),
    (dict(t=np.r_[0.0, np.linspace(0.0, 1.0, 49)]), "t"),
    (dict(t=np.linspace(0.0, 1.0, 50)[::-1]), "t"),
    (dict(normal_force=-90.0), "normal_force"),
    (dict(normal_force=np.r_[np.full(49, 90.0), 0.0]), "normal_force"),
    (dict(normal_force=np.full(7, 90.0)), "normal_force"),
    (dict(bounds={"mu": (0.5, 0.1)}), "bounds['mu']"),
    (dict(bounds={"tangential_stiffness": (0.0, 1e6)}), "bounds['tangential_stiffness']"),
    (dict(bounds={"friction": (0.0, 1.0)}), "bounds['friction']"),
    (dict(initial_guess={"k_t": 1e12}), "initial_guess['tangential_stiffness']"),
    (dict(method="genetic"), "method"),
    (dict(initial_state="relaxed"), "initial_state"),
    (dict(weights=-np.ones(50)), "weights"),
])
def test_bad_kinematic_input_names_the_parameter(change, parameter):
    t = np.linspace(0.0, 1.0, 50)
    args = dict(t=t, relative_velocity=np.sin(t), friction_force=np.cos(t), normal_force=N)
    options = {k: v for k, v in change.items() if k not in args}
    args.update({k: v for k, v in change.items() if k in args})
    with pytest.raises(ValueError) as excinfo:
        identify_dahl(args["t"], args["relative_velocity"], args["friction_force"], args["normal_force"], **options)
    assert parameter_of(excinfo) == parameter


@pytest.mark.parametrize("change, parameter", [
    (dict(drive_force=np.zeros(3)), "drive_force"),
    (dict(mass=-0.2), "mass"),
    (dict(fit=("mu", "stiffness")), "fit['stiffness']"),
    (dict(transient=-1.0), "transient"),
    (dict(bounds={"mu": (1.0, 1.0)}), "bounds['mu']"),
    (dict(t=np.linspace(5.0, 5.1, 50)), "t"),  # a logger's clock: the drive end moves with absolute t
])
def test_bad_rig_input_names_the_parameter(change, parameter):
    t = change.pop("t", np.linspace(0.0, 0.1, 50))
    args = dict(drive_force=np.zeros(50))
    args.update(change)
    drive = args.pop("drive_force")
    with pytest.raises(ValueError) as excinfo:
        identify_axial_rig(t, drive, **args)
    assert parameter_of(excinfo) == parameter


def test_public_names():
    """fs.fit.identify is the dispatching function (no module of that name shadows it)."""
    assert fs.fit.identify is identify and callable(identify)
    # every engine law with something to fit (Coulomb: mu N sgn(v_r) on the kinematic rig, nothing to identify)
    assert set(LAW_PARAMETERS) == {law.key for law in fs.FRICTION_LAWS} - {"coulomb"}
    assert {"dahl", "lugre", "elasto_plastic", "stribeck"} <= set(LAW_PARAMETERS)
    assert LAW_PARAMETERS["dahl"]["tangential_stiffness"] == ("k_t", "N/m", (10.0, 1e10))
    assert fs.fit.IdentificationResult is IdentificationResult


def test_unknown_law_and_mu_static_bounds():
    t = np.linspace(0.0, 1.0, 50)
    with pytest.raises(ValueError) as excinfo:
        identify("coulomb-ish", t, np.sin(t), np.cos(t), N)
    assert parameter_of(excinfo) == "law"
    with pytest.raises(ValueError) as excinfo:
        identify_lugre(t, np.sin(t), np.cos(t), N, bounds={"mu_static": (0.1, 1.0)})
    assert parameter_of(excinfo) == "bounds['mu_static']"
    with pytest.raises(TypeError):
        identify_dahl(t, np.sin(t), np.cos(t), N, popsze=3)
