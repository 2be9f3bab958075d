"""Standard errors of every fit against the closed-form least-squares covariance sigma^2 (X^T X)^-1,
sigma^2 = RSS / (m - n), on small problems linear in their parameters.

With few samples the divisor shows: m = 6 samples and n = 2 parameters make RSS / m two thirds of RSS / (m - n)
(standard errors 18 % smaller), and every test asserts both the match and that the wrong divisor misses.
"""

import math

import numpy as np
import pandas as pd
import pytest

from frictionsim.fit import fit_hysteretic_friction, fit_power_law, identify_stribeck

N = 90.0  # F_N [N]
MU, V_S, DELTA = 0.3, 0.01, 2.0  # Stribeck: held, so F is linear in (mu_s - mu, sigma_v)


def closed_form(X, y, weights=None):
    """-> (estimate, covariance) of weighted linear least squares, written out: sigma^2 (X^T W X)^-1."""
    w = np.ones(len(y)) if weights is None else np.asarray(weights)
    A, b = X * w[:, None], y * w
    estimate = np.linalg.solve(A.T @ A, A.T @ b)
    r = b - A @ estimate
    m, n = X.shape
    return estimate, (r @ r) / (m - n) * np.linalg.inv(A.T @ A)


def stribeck_record(m=6, seed=4, sigma=0.4):
    """m samples of sliding at v_r in [2, 50] mm/s (one sign: the rig's slip branch); F = mu N + X theta + noise,
    X = [N exp(-(v/v_s)^delta), v] the sensitivities to theta = (mu_s - mu, sigma_v)."""
    t = np.arange(float(m))
    v = np.linspace(0.002, 0.05, m)
    X = np.column_stack([N * np.exp(-(v / V_S) ** DELTA), v])
    force = MU * N + X @ np.array([0.15, 40.0]) + np.random.default_rng(seed).normal(0.0, sigma, m)
    return t, v, force, X


def fit_linear_stribeck(t, v, force, **kwargs):
    return identify_stribeck(t, v, force, N, fixed=dict(mu=MU, stribeck_velocity=V_S, shape_exponent=DELTA),
                             **kwargs)


@pytest.mark.parametrize("weighted", [False, True])
def test_identification_stderr_is_the_least_squares_covariance(weighted):
    t, v, force, X = stribeck_record()
    weights = np.array([1.0, 2.0, 0.5, 1.0, 1.5, 0.8]) if weighted else None
    result = fit_linear_stribeck(t, v, force, weights=weights)
    estimate, cov = closed_form(X, force - MU * N, weights)
    assert result.success, result.message
    assert result.fitted == ("mu_static", "viscous_coefficient")  # mu_static = mu + fitted excess, mu held
    # the fit reaches the linear least-squares solution and reports its covariance
    assert result.params["mu_static"] - MU == pytest.approx(estimate[0], rel=1e-7)
    assert result.params["viscous_coefficient"] == pytest.approx(estimate[1], rel=1e-7)
    np.testing.assert_allclose(result.covariance, cov, rtol=1e-6)
    se = np.sqrt(np.diag(cov))
    assert result.stderr["mu_static"] == pytest.approx(se[0], rel=1e-6)
    assert result.stderr["viscous_coefficient"] == pytest.approx(se[1], rel=1e-6)
    # dividing the residual variance by m = 6 instead of m - n = 4 would give sqrt(4/6) of these
    assert result.stderr["mu_static"] / se[0] != pytest.approx(math.sqrt(4.0 / 6.0), rel=0.05)
    assert result.stderr["mu"] == 0.0  # held


def test_power_law_stderr_is_the_least_squares_covariance():
    """Six runs of a noisy power law: linregress's slope and intercept errors, and the delta method for eta' and
    eta (eq 15) with the slope-intercept covariance, against sigma^2 (X^T X)^-1, X = [1, log10(v_a/v_d)]."""
    ratio = np.geomspace(20.0, 400.0, 6)
    mu = 0.2 * ratio ** -0.15 * 10.0 ** np.random.default_rng(5).normal(0.0, 0.03, ratio.size)
    fit = fit_power_law(pd.DataFrame(dict(velocity_ratio=ratio, mu_df=mu)))
    X = np.column_stack([np.ones(ratio.size), np.log10(ratio)])
    (intercept, slope), cov = closed_form(X, np.log10(mu))
    assert (fit.slope, fit.intercept) == (pytest.approx(slope, rel=1e-12), pytest.approx(intercept, rel=1e-12))
    assert fit.intercept_stderr == pytest.approx(math.sqrt(cov[0, 0]), rel=1e-9)
    assert fit.slope_stderr == pytest.approx(math.sqrt(cov[1, 1]), rel=1e-9)
    assert fit.exponent_stderr == fit.slope_stderr
    assert fit.slope_intercept_covariance == pytest.approx(cov[0, 1], rel=1e-9)
    assert fit.slope_stderr / math.sqrt(cov[1, 1]) != pytest.approx(math.sqrt(4.0 / 6.0), rel=0.05)
    # delta method: eta' = 10^b; eta = 10^(b + c log10 2 pi)
    ln10, lever = math.log(10.0), math.log10(2.0 * math.pi)
    assert fit.eta_prime_stderr == pytest.approx(ln10 * fit.eta_prime * math.sqrt(cov[0, 0]), rel=1e-9)
    gradient = ln10 * fit.eta_eq15 * np.array([1.0, lever])
    assert fit.eta_eq15_stderr == pytest.approx(math.sqrt(gradient @ cov @ gradient), rel=1e-9)
    row = fit.to_dict()
    assert row["eta_prime_stderr"] == fit.eta_prime_stderr and row["eta_eq15_stderr"] == fit.eta_eq15_stderr


def test_table5_refit_stderr_on_table4():
    """The refit of paper 000's Table 5 carries standard errors (the paper prints none): five runs per lubricant,
    so three degrees of freedom; checked against the closed form on Table 4's own columns."""
    from frictionsim.data import table4

    table = table4()
    fits = fit_power_law(table)
    for lubricant, rows in table.groupby(table["lubricant"].str.lower(), sort=False):
        X = np.column_stack([np.ones(len(rows)), np.log10(rows["velocity_ratio"].to_numpy(float))])
        _, cov = closed_form(X, np.log10(rows["mu_df"].to_numpy(float)))
        assert fits.loc[lubricant, "slope_stderr"] == pytest.approx(math.sqrt(cov[1, 1]), rel=1e-9)
        assert fits.loc[lubricant, "intercept_stderr"] == pytest.approx(math.sqrt(cov[0, 0]), rel=1e-9)
    # dry: c = -0.365 +- 0.107, eta' = 1.068 +- 0.729 (one standard error)
    assert fits.loc["dry", "slope_stderr"] == pytest.approx(0.1074, abs=5e-4)
    assert fits.loc["dry", "eta_prime_stderr"] == pytest.approx(0.729, abs=5e-3)


def branch_record(m=9, seed=6, sigma=0.02):
    """A stick phase (w = 0, torque ramping to 1.3 N m), then m accelerating and m decelerating slip samples at
    scattered (w, al), T = poly22 + noise."""
    rng = np.random.default_rng(seed)
    coefficients = {+1: np.array([0.9, -0.03, 0.004, 0.002, -1e-4, 5e-5]),
                    -1: np.array([1.1, -0.05, 0.006, 0.003, 2e-4, -6e-5])}
    w, al, torque = [np.zeros(5)], [np.zeros(5)], [np.linspace(0.2, 1.3, 5)]
    for sign in (+1, -1):
        ws, als = rng.uniform(0.5, 10.0, m), sign * rng.uniform(1.0, 40.0, m)
        design = np.column_stack([np.ones(m), ws, als, ws ** 2, ws * als, als ** 2])
        w.append(ws)
        al.append(als)
        torque.append(design @ coefficients[sign] + rng.normal(0.0, sigma, m))
    return np.concatenate(w), np.concatenate(al), np.concatenate(torque)


def test_hysteretic_branch_stderr_is_the_least_squares_covariance():
    """Eq 6's poly22 branches, m = 9 samples each for 6 coefficients: RSS / m would be a third of RSS / (m - 6)."""
    w, al, torque = branch_record()
    fit = fit_hysteretic_friction(w, al, torque, guard=0, acceleration_threshold=0.0)
    for branch, keep in ((fit.accelerating, (w > 0) & (al > 0)), (fit.decelerating, (w > 0) & (al < 0))):
        X = np.column_stack([np.ones(keep.sum()), w[keep], al[keep], w[keep] ** 2, w[keep] * al[keep],
                             al[keep] ** 2])
        estimate, cov = closed_form(X, torque[keep])
        assert branch.samples == 9
        np.testing.assert_allclose(branch.coefficients, estimate, rtol=1e-8)
        np.testing.assert_allclose(branch.stderr, np.sqrt(np.diag(cov)), rtol=1e-6)
        assert branch.stderr[0] / math.sqrt(cov[0, 0]) != pytest.approx(math.sqrt(3.0 / 9.0), rel=0.05)
    assert "s.e. p" in fit.summary()


def test_hysteretic_branch_with_six_samples_has_undetermined_stderr():
    w, al, torque = branch_record(m=6)
    fit = fit_hysteretic_friction(w, al, torque, guard=0, acceleration_threshold=0.0)
    assert fit.accelerating.samples == 6
    assert all(math.isinf(se) for se in fit.accelerating.stderr)  # an exact fit: no residual to judge it, not NaN

