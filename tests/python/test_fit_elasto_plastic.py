"""Identification of the elasto-plastic law (frictionsim.fit.identify_elasto_plastic): synthetic round trips.

As for LuGre (test_identify.py): the record is simulated by the engine at tight tolerance from known parameters,
Gaussian noise is added (fixed seed), and the fit must recover the parameters, breakaway_fraction included,
within the stated tolerance and within 3 standard errors. A record without force reversals cannot show the
elastic band, and the fit must say so.
"""

import numpy as np
import pytest

import frictionsim as fs
from frictionsim.fit import LAW_PARAMETERS, identify, identify_elasto_plastic
from test_identify import check_recovered  # the same acceptance as LuGre's round trip

N = 90.0  # F_N [N]
TRUTH = dict(mu=0.3, mu_static=0.45, stribeck_velocity=0.01, bristle_stiffness=1e5, bristle_damping=300.0,
             viscous_damping=20.0, breakaway_fraction=0.6)
GUESS = dict(mu=0.25, mu_static=0.5, stribeck_velocity=0.02, bristle_stiffness=5e4, bristle_damping=150.0,
             viscous_damping=10.0, breakaway_fraction=0.3)
SIGMA = 0.01 * TRUTH["mu"] * N  # noise: 1 % of mu N
# errors over 30 noise seeds (0..29), initial_state="zero": at most 0.19 %, 3.3 %, 3.9 %, 0.97 %, 5.9 %, 3.0 %,
# 3.8 % (unbiased; spread within 1.1 times the reported standard errors, none beyond 2.8 of them)
RTOL = dict(mu=0.01, mu_static=0.05, stribeck_velocity=0.05, bristle_stiffness=0.02, bristle_damping=0.10,
            viscous_damping=0.06, breakaway_fraction=0.06)


def simulate(law, t, v, initial_state=None):
    rig = fs.KinematicRig(law, relative_velocity=(t, v), normal_force=N, initial_state=initial_state)
    return fs.simulate(rig, t[-1], output_times=t, t_start=t[0], rtol=1e-10, atol=1e-12)


@pytest.fixture(scope="module")
def record():
    """2 s of v_r = 0.1 sin(2 pi t) m/s at 1 kHz from rest (LuGre's sweep): four reversals, each followed by
    elastic unloading, the ramp from z_ba to z_max = mu N / sigma_0 and gross sliding through the Stribeck region
    (where z_ss = g / sigma_0 lies above z_max)."""
    t = np.linspace(0.0, 2.0, 2001)
    v = 0.1 * np.sin(2.0 * np.pi * t)
    run = simulate(fs.ElastoPlastic(**TRUTH), t, v)
    noisy = run.friction_force + np.random.default_rng(3).normal(0.0, SIGMA, t.size)
    return t, v, run, noisy


@pytest.fixture(scope="module")
def fit(record):
    t, v, _, noisy = record
    # The record starts from rest, z = 0. The default initial_state="measured" would take z0 from the first noisy
    # sample, an error the covariance does not count: over 30 seeds sigma_0 and sigma_1 then scatter twice their
    # reported standard errors (as LuGre's do).
    return identify_elasto_plastic(t, v, noisy, N, initial_guess=GUESS, initial_state="zero")


def test_the_record_passes_through_every_regime(record):
    t, v, run, _ = record
    law = fs.ElastoPlastic(**TRUTH)
    alpha = np.array([law.plasticity_factor(N, zi, 1 if vi >= 0 else -1)
                      for vi, zi in zip(v, run.bristle_deflection)])
    # measured 137 elastic, 380 on the ramp, 1484 sliding samples. Of the ramp's, 53 have alpha < 0.99; most of the
    # rest approach z_max from below in fast sliding, where z_ss = g / sigma_0 = z_max to within exp(-(v/v_s)^2).
    ramp = (alpha > 0.0) & (alpha < 1.0)
    assert np.sum(alpha == 0.0) > 100 and np.sum(ramp) > 300 and np.sum(alpha == 1.0) > 1000
    assert np.sum(ramp & (alpha < 0.99)) > 40
    # the elastic band shows: LuGre with the same parameters is up to 33 sigma away (39 while z_max rose with
    # g(v) / sigma_0, a wider ramp; 25 still puts the band far above the noise)
    lugre = fs.LuGre(**{k: value for k, value in TRUTH.items() if k != "breakaway_fraction"})
    assert np.max(np.abs(simulate(lugre, t, v).friction_force - run.friction_force)) > 25 * SIGMA


def test_round_trip_recovers_every_parameter(record, fit):
    t, v, run, noisy = record
    result = fit
    assert result.success, result.message
    # measured errors: -0.11 %, +3.3 %, -2.6 %, +0.01 %, +0.7 %, +2.5 %, -0.59 % (0.02 to 1.8 standard errors)
    check_recovered(result, TRUTH, RTOL)
    assert result.fitted == tuple(TRUTH)
    assert all(result.identifiable.values()), result.reasons
    assert result.law_name == "ElastoPlastic" and isinstance(result.law, fs.ElastoPlastic)
    assert result.law.breakaway_fraction == result.params["breakaway_fraction"]
    assert result.law.mu_static == result.params["mu_static"] >= result.params["mu"]
    assert result.initial_state == [0.0]
    # the refit force reproduces the data: the residual is the noise, the model the noise-free force
    assert result.rms_residual == pytest.approx(SIGMA, rel=0.05)  # measured 0.990 sigma
    assert result.r_squared > 0.9999  # measured 0.99991
    assert np.max(np.abs(result.model - run.friction_force)) < 0.5 * SIGMA  # measured 0.30 sigma
    rerun = fs.simulate(result.rig, t[-1], t_start=t[0], output_times=t, rtol=1e-10, atol=1e-12)
    assert np.max(np.abs(rerun.friction_force - result.model)) < 1e-2 * SIGMA  # the fit's tolerances: 1.2e-3 sigma
    # reported with its symbol and unit
    frame = result.to_pandas()
    assert tuple(frame.loc["breakaway_fraction", ["symbol", "unit"]]) == ("beta", "-")
    assert "breakaway_fraction" in result.summary()


def test_breakaway_fraction_held_fixed(record):
    t, v, _, noisy = record
    guess = {k: value for k, value in GUESS.items() if k != "breakaway_fraction"}
    held = identify_elasto_plastic(t, v, noisy, N, initial_guess=guess, initial_state="zero",
                                   fixed=dict(beta=TRUTH["breakaway_fraction"]))
    assert "breakaway_fraction" not in held.fitted and len(held.fitted) == 6
    assert held.params["breakaway_fraction"] == TRUTH["breakaway_fraction"] and held.stderr["breakaway_fraction"] == 0
    assert "fixed" in held.reasons["breakaway_fraction"]
    check_recovered(held, {k: value for k, value in TRUTH.items() if k != "breakaway_fraction"}, RTOL)
    assert held.rms_residual == pytest.approx(SIGMA, rel=0.05)
    # held at a wrong value the other six cannot make up for it: the record determines beta
    wrong = identify_elasto_plastic(t, v, noisy, N, initial_guess=guess, initial_state="zero",
                                    fixed=dict(breakaway_fraction=0.2))
    assert wrong.rms_residual > 1.2 * SIGMA  # measured 1.34 sigma (1.10 at 0.4, 1.11 at 0.8)


@pytest.mark.parametrize("start", [520, 700])
def test_measured_initial_state_is_exact_unloading_and_sliding(record, start):
    """initial_state="measured" from the noise-free record cut where each closed-form inverse of F is exact:
    at t = 0.52 s the contact unloads after a reversal, elastic though |z| = 1.05 z_ba (LuGre's inverse would be
    14 % off); at t = 0.7 s it slides at 0.095 m/s, where sigma_1 |v_r| = 1.06 g and the elastic inverse gives a
    state that also matches F (z = +1.5e-5 m; the contact is at -z_max = -2.7e-4 m).

    There LuGre's inverse divides by 1 - sigma_1 |v_r| / g = -0.057, which multiplies the relative error of the
    fitted mu (through g) by 18.6 in z_0. The fits therefore resolve the force to atol = 1e-6 N: at the default,
    1e-6 of max|F| (3e-5 N), the fitted mu is off by 5.8e-7 and z_0 by 1.1e-5."""
    t, v, run, _ = record
    law = fs.ElastoPlastic(**TRUTH)
    z = run.bristle_deflection[start]
    expected_alpha = 0.0 if start == 520 else 1.0
    assert law.plasticity_factor(N, z, -1) == pytest.approx(expected_alpha, abs=1e-6)
    cut = slice(start, None)
    fixed = {k: value for k, value in TRUTH.items() if k not in ("mu", "mu_static")}
    fixed["mu_static_excess"] = TRUTH["mu_static"] - TRUTH["mu"]
    result = identify_elasto_plastic(t[cut], v[cut], run.friction_force[cut], N, fixed=fixed,
                                     initial_guess=dict(mu=TRUTH["mu"]), atol=1e-6)
    assert result.initial_state[0] == pytest.approx(z, rel=1e-5)  # measured 0 and 1.2e-7
    assert result.params["mu"] == pytest.approx(TRUTH["mu"], rel=1e-6)  # measured 2e-12 and 6e-9
    assert result.rms_residual < 1e-3 * SIGMA  # measured 2.3e-5 and 2.0e-5 sigma: the fit's tolerances


def test_without_reversal_breakaway_fraction_is_flagged():
    """Sliding one way at 0.03..0.07 m/s from the steady state: z stays at z_ss = g / sigma_0 >= z_max, alpha = 1,
    and the elastic band never shows; nor do the Stribeck curve and the bristle (the force is g + sigma_2 v_r),
    while mu and sigma_2 do."""
    t = np.linspace(0.0, 0.5, 501)
    v = 0.05 + 0.02 * np.cos(2.0 * np.pi * 4.0 * t)
    law = fs.ElastoPlastic(**TRUTH)
    steady = [law.stribeck_level(v[0], N) / TRUTH["bristle_stiffness"]]
    force = simulate(law, t, v, initial_state=steady).friction_force
    force = force + np.random.default_rng(0).normal(0.0, SIGMA, t.size)
    result = identify_elasto_plastic(t, v, force, N)
    assert not result.identifiable["breakaway_fraction"], result.reasons["breakaway_fraction"]
    assert not result.reasons["breakaway_fraction"].startswith("identified")
    flagged = {name for name, ok in result.identifiable.items() if not ok}
    assert flagged == {"mu_static", "stribeck_velocity", "bristle_stiffness", "bristle_damping",
                       "breakaway_fraction"}, result.reasons
    assert result.params["mu"] == pytest.approx(TRUTH["mu"], rel=0.01)
    assert not result.all_identifiable and "NO:" in result.summary()


@pytest.mark.parametrize("law", ["elasto_plastic", "ElastoPlastic", "elastoplastic", "Elasto-Plastic",
                                 fs.ElastoPlastic], ids=str)
def test_identify_dispatches(record, fit, law):
    t, v, _, noisy = record
    result = identify(law, t, v, noisy, N, initial_guess=GUESS, initial_state="zero")
    assert result.law_name == "ElastoPlastic" and result.params == fit.params


def test_identify_passes_fit_viscous(record):
    t, v, _, noisy = record
    result = identify("elasto_plastic", t, v, noisy, N, fit_viscous=False, initial_guess=GUESS,
                      initial_state="zero", max_nfev=2)
    assert "viscous_damping" not in result.fitted and result.params["viscous_damping"] == GUESS["viscous_damping"]


def parameter_of(excinfo):
    assert isinstance(excinfo.value, ValueError) and isinstance(excinfo.value, fs.InvalidParameterError)
    return excinfo.value.parameter


@pytest.mark.parametrize("change, parameter, rule", [
    (dict(bounds={"breakaway_fraction": (0.0, 1.0)}), "bounds['breakaway_fraction']", "upper bound must be < 1"),
    (dict(bounds={"beta": (0.2, 1.5)}), "bounds['beta']", "upper bound must be < 1"),
    (dict(bounds={"breakaway_fraction": (-0.1, 0.5)}), "bounds['breakaway_fraction']", "lower bound must be >= 0"),
    (dict(fixed={"breakaway_fraction": 1.0}), "fixed['breakaway_fraction']", "not a valid breakaway_fraction"),
    (dict(initial_guess={"breakaway_fraction": 0.97}), "initial_guess['breakaway_fraction']", "outside its bounds"),
])
def test_bad_breakaway_fraction_names_the_parameter(change, parameter, rule):
    t = np.linspace(0.0, 1.0, 50)
    with pytest.raises(ValueError, match=rule) as excinfo:
        identify_elasto_plastic(t, np.sin(t), np.cos(t), N, **change)
    assert parameter_of(excinfo) == parameter


def test_public_names_and_default_bounds():
    assert fs.fit.identify_elasto_plastic is identify_elasto_plastic
    assert "identify_elasto_plastic" in fs.fit.__all__
    table = LAW_PARAMETERS["elasto_plastic"]
    assert table["breakaway_fraction"] == ("beta", "-", (0.0, 0.95))
    assert {k: value for k, value in table.items() if k != "breakaway_fraction"} == LAW_PARAMETERS["lugre"]
    assert "breakaway_fraction" in identify_elasto_plastic.__doc__ and "fit_viscous" in identify_elasto_plastic.__doc__
    assert "initial_state" in identify_elasto_plastic.__doc__  # the common parameters
