"""Fitting: the Table 5 power-law refit, and friction-law identification through the C++ engine.

Identification by output-error least squares, one module a job:

* :mod:`.kinematic`: identify_dahl / identify_lugre / identify_elasto_plastic / identify_stribeck on the kinematic
  rig, and identify for any law of ``fs.FRICTION_LAWS`` with something to fit (the keys of LAW_PARAMETERS);
* :mod:`.rig`: identify_axial_rig, the law inside paper 000's axial vibrating-sliding rig;
* :mod:`.torsional`: paper 001's identification of the hysteretic law (eq 6) on the torsional rig, by linear least
  squares: estimate_friction_torque (eq 1a from the encoder angles, FrictionTorqueEstimate) and
  fit_hysteretic_friction (stick slope and poly22 branches; HystereticFit, BranchFit);
* :mod:`.parameters` (each law's fit variables: the engine's parameter table plus search hints),
  :mod:`.search_space` (log / linear search variables, bounds), :mod:`.validation` (the record),
  :mod:`.forward_model` (one simulation per residual), :mod:`.residuals`, :mod:`.solver` (scan, least_squares,
  differential_evolution), :mod:`.uncertainty` (covariance, identifiability), :mod:`.result`
  (IdentificationResult: AIC / BIC, eval, plot), :mod:`.profile` (profile-likelihood conf_interval),
  :mod:`.progress` (verbose= / callback= of the searches, FitProgress), :mod:`.records` (decimate: a long record
  shortened by block means, within the searches' work limit, solver.MAX_FIT_WORK);
* :mod:`.compare`: compare_laws, several laws fitted to one record and ranked by AIC.

Everything logs to ``logging.getLogger("frictionsim")``; nothing prints.
"""

from .compare import compare_laws
from .power_law import PowerLawFit, fit_power_law
from .progress import FitProgress
from .kinematic import identify, identify_dahl, identify_elasto_plastic, identify_lugre, identify_stribeck
from .parameters import LAW_PARAMETERS
from .result import IdentificationResult
from .records import decimate
from .rig import identify_axial_rig
from .torsional import (BranchFit, FrictionTorqueEstimate, HystereticFit, estimate_friction_torque,
                        fit_hysteretic_friction)

__all__ = ["PowerLawFit", "fit_power_law", "IdentificationResult", "LAW_PARAMETERS", "identify", "identify_dahl",
           "identify_lugre", "identify_elasto_plastic", "identify_stribeck", "identify_axial_rig",
           "FrictionTorqueEstimate", "estimate_friction_torque", "BranchFit", "HystereticFit",
           "fit_hysteretic_friction", "compare_laws", "FitProgress", "decimate"]
