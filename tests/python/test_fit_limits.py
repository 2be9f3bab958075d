"""Issue 11, item 11: no fit reports success with a NaN or inf in its result, and a record no fit can use (constant,
too large for double precision's sums of squares, too short, non-finite) is refused naming the argument.

Every public fit: identify_dahl / lugre / elasto_plastic / stribeck / identify, identify_axial_rig,
estimate_friction_torque, fit_hysteretic_friction, fit_power_law."""

import dataclasses
import functools
import math

import numpy as np
import pytest

import frictionsim as fs
from frictionsim import fit
from frictionsim.fit import kinematic, rig

MU, K_T, N = 0.41, 4e4, 90.0
T = np.linspace(0.0, 0.5, 201)
V = 0.05 * np.sin(2 * np.pi * 4 * T)


@pytest.fixture(scope="module")
def force():
    record = fs.KinematicRig(fs.Dahl(MU, K_T), relative_velocity=(T, V), normal_force=N)
    return fs.simulate(record, T[-1], output_times=T).friction_force


KINEMATIC = {
    "identify_dahl": functools.partial(fit.identify_dahl, fit_exponent=False),
    "identify_lugre": fit.identify_lugre,
    "identify_elasto_plastic": fit.identify_elasto_plastic,
    "identify_stribeck": fit.identify_stribeck,
    "identify": functools.partial(fit.identify, "dahl"),
}


def _no_simulation(monkeypatch):
    """Refusals come before any simulation: a run now fails the test."""
    def refuse(*args, **kwargs):
        raise AssertionError("a simulation ran before the record was checked")
    monkeypatch.setattr("frictionsim.fit.forward_model.simulate", refuse)


# ------------------------------------------------------------------------------------- constant records: R^2 undefined
@pytest.mark.parametrize("level", [10.0, 0.3, -0.1])  # 0.3 and -0.1: the mean is off by an ulp, R^2 was -1e28
@pytest.mark.parametrize("name", sorted(KINEMATIC))
def test_a_constant_friction_force_is_refused_before_fitting(name, level, monkeypatch):
    _no_simulation(monkeypatch)
    with pytest.raises(fs.InvalidParameterError, match="must vary.*R\\^2 is undefined") as info:
        KINEMATIC[name](T, V, np.full_like(T, level), N)
    assert info.value.parameter == "friction_force"


def test_a_force_constant_to_within_rounding_is_constant(monkeypatch):
    _no_simulation(monkeypatch)
    wobble = 0.3 + np.where(np.arange(T.size) % 2, 0.0, np.spacing(0.3))  # one ulp: a CSV round trip, not a signal
    with pytest.raises(fs.InvalidParameterError, match="to within rounding") as info:
        fit.identify_dahl(T, V, wobble, N)
    assert info.value.parameter == "friction_force"


def test_a_constant_drive_force_is_refused_also_after_the_transient(monkeypatch):
    _no_simulation(monkeypatch)
    with pytest.raises(fs.InvalidParameterError, match="must vary") as info:
        fit.identify_axial_rig(T, np.full_like(T, 0.3))
    assert info.value.parameter == "drive_force"
    varying_then_flat = np.where(T < 0.1, np.sin(40 * T), 0.3)
    with pytest.raises(fs.InvalidParameterError, match="after transient = 0.2 s") as info:
        fit.identify_axial_rig(T, varying_then_flat, transient=0.2)
    assert info.value.parameter == "drive_force"


# ------------------------------------------------------------------------------------------------- magnitudes
@pytest.mark.parametrize("scale", [1e300, 1e160])
@pytest.mark.parametrize("name", sorted(KINEMATIC))
def test_a_record_whose_squares_overflow_is_refused(force, name, scale, monkeypatch):
    _no_simulation(monkeypatch)  # 1e300 ran the whole search on inf costs before
    with pytest.raises(fs.InvalidParameterError, match="rescale") as info:
        KINEMATIC[name](T, V, force * scale, N)
    assert info.value.parameter == "friction_force"


def test_a_drive_force_whose_squares_overflow_is_refused(monkeypatch):
    _no_simulation(monkeypatch)
    with pytest.raises(fs.InvalidParameterError, match="rescale") as info:
        fit.identify_axial_rig(T, 1e300 * np.sin(40 * T))
    assert info.value.parameter == "drive_force"


def test_a_record_the_model_cannot_approach_fails_instead_of_returning_inf_r_squared(force):
    # 1e-300 N: every model force is ~1e297 records away; SS_res / SS_tot overflows. success=True, R^2 = -inf
    # before (and every run failed on the derived atol of 1e-310).
    result = fit.identify_dahl(T, V, force * 1e-300, N, fit_exponent=False)
    assert not result.success
    assert "not finite" in result.message and "r_squared" in result.message
    assert result.n_failed == 0
    good = fit.identify_dahl(T, V, force, N, fit_exponent=False)
    assert good.success and good.r_squared > 0.999 and math.isfinite(good.rms_residual)


# ---------------------------------------------------------------------------------- non-finite input, short records
@pytest.mark.parametrize("argument", ["t", "relative_velocity", "friction_force", "normal_force"])
@pytest.mark.parametrize("bad", [math.nan, math.inf])
def test_non_finite_input_is_named(force, argument, bad, monkeypatch):
    _no_simulation(monkeypatch)
    args = dict(t=T.copy(), relative_velocity=V.copy(), friction_force=force.copy(), normal_force=np.full_like(T, N))
    args[argument][7] = bad
    with pytest.raises(fs.InvalidParameterError, match="finite") as info:
        fit.identify_dahl(**args)
    assert info.value.parameter == argument


@pytest.mark.parametrize("samples", [0, 1, 2])
def test_too_few_samples_are_named(force, samples, monkeypatch):
    _no_simulation(monkeypatch)
    with pytest.raises(fs.InvalidParameterError, match="at least 3") as info:
        fit.identify_dahl(T[:samples], V[:samples], force[:samples], N)
    assert info.value.parameter == "t"
    with pytest.raises(fs.InvalidParameterError, match="cannot determine") as info:  # 3 samples, 3 parameters
        fit.identify_dahl(T[:3], V[:3], force[:3], N)
    assert info.value.parameter == "t"


# ----------------------------------------------------------------- the one check every identification result passes
def _inject(field, value):
    """Wrap the fitting core so that its answer carries ``value`` in ``field`` (the first fitted parameter's)."""
    from frictionsim.fit.solver import fit_model

    def wrapped(*args, **kwargs):
        answer = fit_model(*args, **kwargs)
        name = answer.fitted[0]
        if field == "params":
            return dataclasses.replace(answer, params={**answer.params, name: value})
        if field == "stderr":  # an identifiable parameter's standard error
            return dataclasses.replace(answer, stderr={**answer.stderr, name: value},
                                       identifiable={**answer.identifiable, name: True})
        signal = answer.signal.copy()
        signal[3] = value
        return dataclasses.replace(answer, signal=signal)
    return wrapped


@pytest.mark.parametrize("field, value", [("params", math.nan), ("params", math.inf), ("stderr", math.nan),
                                          ("stderr", math.inf), ("signal", math.nan)])
@pytest.mark.parametrize("module", [kinematic, rig])
def test_no_identification_reports_success_with_a_non_finite_field(force, module, field, value, monkeypatch):
    monkeypatch.setattr(module, "fit_model", _inject(field, value))
    if module is kinematic:
        result = fit.identify_dahl(T, V, force, N, fit_exponent=False)
    else:
        drive = fs.simulate(fs.AxialVibrationRig(friction=fs.Dahl(MU, K_T)), 0.3,
                            output_times=np.linspace(0.0, 0.3, 151))
        result = fit.identify_axial_rig(drive.t, fs.AxialVibrationRig(friction=fs.Dahl(MU, K_T)).drive_force(
            drive.t, drive["position"]), fit=("mu",), initial_guess={"tangential_stiffness": K_T})
    assert not result.success
    assert result.message.startswith("not finite")


def test_an_undetermined_parameter_keeps_its_infinite_standard_error_and_the_success(force, monkeypatch):
    # inf is the answer "the data do not determine it" (flagged not identifiable), not a failure: as scipy's
    # curve_fit reports an undetermined covariance as inf
    from frictionsim.fit.solver import fit_model

    def undetermined(*args, **kwargs):
        answer = fit_model(*args, **kwargs)
        name = answer.fitted[0]
        return dataclasses.replace(answer, stderr={**answer.stderr, name: math.inf},
                                   identifiable={**answer.identifiable, name: False})

    monkeypatch.setattr(kinematic, "fit_model", undetermined)
    result = fit.identify_dahl(T, V, force, N, fit_exponent=False)
    assert result.success and math.isinf(result.stderr["mu"]) and not result.identifiable["mu"]
