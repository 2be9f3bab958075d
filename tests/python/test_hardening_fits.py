"""Issue 11's items on fits, sweeps and the power law: NaN is never success, empty tables are named, extreme
exponents are refused, unpicklable sweep functions fail before the pool is used."""

import concurrent.futures as cf
import math
import threading

import numpy as np
import pandas as pd
import pytest

import frictionsim as fs
from frictionsim.fit import fit_power_law, identify_dahl

MU, K_T, N = 0.41, 4e4, 90.0


def _record(scale=1.0):
    t = np.linspace(0.0, 0.5, 201)
    v = 0.05 * np.sin(2 * np.pi * 4 * t)
    rig = fs.KinematicRig(fs.Dahl(MU, K_T), relative_velocity=(t, v), normal_force=N)
    force = fs.simulate(rig, t[-1], output_times=t).friction_force
    return t, v, scale * force


def test_a_constant_force_record_is_refused_not_fitted_with_r_squared_nan():
    t, v, _ = _record()
    with pytest.raises(fs.InvalidParameterError, match="constant") as info:
        identify_dahl(t, v, np.full_like(t, 10.0), N, fit_exponent=False)  # R^2 = nan, success=True before
    assert info.value.parameter == "friction_force"


def test_a_fit_that_overflows_is_never_reported_as_success():
    t, v, force = _record(scale=1e300)  # residual sums overflow to inf: refused up front, or never success
    try:
        result = identify_dahl(t, v, force, N, fit_exponent=False)
    except fs.InvalidParameterError as error:
        assert error.parameter == "friction_force"
    else:
        assert not result.success and "non-finite" in result.message
    good = identify_dahl(t, v, force / 1e300, N, fit_exponent=False)
    assert good.success and math.isfinite(good.r_squared) and good.r_squared > 0.999


@pytest.mark.parametrize("table, parameter", [
    (pd.DataFrame(columns=["lubricant", "velocity_ratio", "mu_df"]), "table"),  # pandas KeyError before
    (pd.DataFrame({"velocity_ratio": [100.0, 200.0]}), "table"),
    (pd.DataFrame({"lubricant": ["dry"], "velocity_ratio": [100.0], "mu_df": [0.2]}), "table"),
    (pd.DataFrame({"lubricant": ["dry"] * 2, "velocity_ratio": [100.0, -1.0], "mu_df": [0.2, 0.1]}), "table"),
    ("not a table", "table"),
])
def test_fit_power_law_names_what_is_wrong_with_the_table(table, parameter):
    with pytest.raises(fs.InvalidParameterError) as info:
        fit_power_law(table)
    assert info.value.parameter == parameter


def test_fit_power_law_of_equal_coefficients_is_never_nan():
    # a flat line with R^2 = 1 by convention, or refused as having nothing to fit: never NaN as success
    try:
        fit = fit_power_law(pd.DataFrame({"velocity_ratio": [100.0, 200.0, 400.0], "mu_df": [0.2, 0.2, 0.2]}))
    except fs.InvalidParameterError as error:
        assert error.parameter in ("table", "mu_df")
    else:
        assert fit.slope == 0.0 and math.isfinite(fit.r_squared)


@pytest.mark.parametrize("exponent", [1e300, -1e300, 2.5, math.inf])
def test_power_law_exponent_outside_any_friction_law_is_refused(exponent):
    with pytest.raises(fs.InvalidParameterError) as info:  # coefficient() returned inf before
        fs.PowerLawCoefficient(eta=0.2, exponent=exponent)
    assert info.value.parameter == "exponent"


def test_power_law_coefficient_that_would_overflow_is_named():
    law = fs.PowerLawCoefficient(eta=1.0, exponent=2.0)
    with pytest.raises(fs.InvalidParameterError) as info:
        law.coefficient(1e300, 1e-300)
    assert info.value.parameter == "vibration_velocity_amplitude"
    assert math.isfinite(fs.PowerLawCoefficient.from_table5("dry").coefficient(0.5, 1e-3))


def _top_level_point(x):
    return x * 2.0


def test_an_unpicklable_function_fails_before_the_process_pool_is_used():
    finished = threading.Event()
    errors = []

    def run():
        try:
            with cf.ProcessPoolExecutor(max_workers=1) as pool:
                try:
                    fs.sweep(lambda x: x, {"x": [1.0, 2.0]}, executor=pool, progress=False)
                except fs.sweeps.SweepError as error:
                    errors.append(error)
                # the pool still works afterwards: nothing broken was sent to it
                errors.append(fs.sweep(_top_level_point, {"x": [1.0]}, executor=pool, progress=False).values)
        finally:
            finished.set()

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    assert finished.wait(120), "the sweep or the pool's shutdown hung"
    assert isinstance(errors[0], fs.sweeps.SweepError) and "top-level function" in str(errors[0])
    assert errors[1] == [2.0]
