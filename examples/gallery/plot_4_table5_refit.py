"""
Refitting Table 5: the power-law friction coefficient (paper 000, eq 17)
========================================================================

Paper 000 condenses its vibrated runs (Table 4) into one law per lubricant: the dynamic friction coefficient
falls as a power of the velocity ratio,

    mu_df = eta' (v_a / v_d)^c        (eq 17, Table 5),

with v_a = 2 pi f u0 the vibration's velocity amplitude (eq 16) and v_d the sliding velocity.
:func:`frictionsim.fit.fit_power_law` refits it the way the paper did: an ordinary least-squares line through
log10(mu_df) against log10(v_a / v_d), five runs per lubricant. The slopes, intercepts and eta' come out as
printed; the printed R^2 do not (see the module's notes: every printed value is 0.04-0.09 lower).
"""

import matplotlib.pyplot as plt
import numpy as np

import frictionsim as fs
from frictionsim.data import table4, table5

# %%
# The refit beside the printed table
# ----------------------------------
refit = fs.demo.table5_refit()
columns = ["lubricant", "slope_printed", "slope_refit", "eta_prime_printed", "eta_prime_refit",
           "r_squared_printed", "r_squared_refit", "adjusted_r_squared_refit"]
print(refit[columns].to_string(index=False, float_format=lambda x: f"{x:.5g}"))

# %%
# The same line, independently: numpy's polyfit on the logarithms of Table 4's runs gives the same slope
# and intercept to rounding, so the refit is exactly the paper's regression.
runs = table4()
fits = fs.fit.fit_power_law(runs)
for lubricant, rows in runs.groupby("lubricant", sort=False):
    slope, intercept = np.polyfit(np.log10(rows["velocity_ratio"]), np.log10(rows["mu_df"]), 1)
    assert np.isclose(slope, fits.loc[lubricant, "slope"], rtol=1e-9, atol=1e-12)
    assert np.isclose(intercept, fits.loc[lubricant, "intercept"], rtol=1e-9, atol=1e-12)
    print(f"{lubricant:6s} polyfit c = {slope:+.5f}, log10 eta' = {intercept:+.5f}")

# %%
# How well do five runs determine each law?
# ------------------------------------------
# The paper prints no uncertainty. The refit's standard errors (``scipy.stats.linregress``: the residual variance
# over m - 2 = 3 degrees of freedom) are large: with five runs per lubricant over about a decade of v_a / v_d or
# less, the exponents are known to 16-36 % of their value, and the dry eta' (10 to the intercept, its error by the
# delta method) only to 70 %.
print(fits[["exponent", "slope_stderr", "eta_prime", "eta_prime_stderr", "r_squared"]]
      .to_string(float_format=lambda x: f"{x:.4g}"))

# %%
# The log-log plot (cf. the paper's Fig. 11)
# ------------------------------------------
# :func:`frictionsim.plots.power_law_figure` draws each lubricant's five runs, its refit over the range of
# v_a / v_d it was fitted on (outside it the law extrapolates) and, dashed, Table 5 as printed, which lies on the
# refit.
fig, ax = plt.subplots(figsize=(8, 5.5), layout="constrained")
fs.plots.power_law_figure(runs, fits, printed=table5(), ax=ax)
plt.show()
