"""Friction-law identification on the kinematic rig: any engine law with something to fit (Dahl, LuGre,
ElastoPlastic, Stribeck, ...: :func:`identify` lists them) fitted to a measured friction force through the C++ engine.

Paper 000 (sec 4.2) stresses that the Dahl tangential contact stiffness k_t "is one of the most complicated
parameters that need to be determined" and that genetic / particle-swarm searches are commonly used for it.
This module does that identification by output-error least squares: every residual evaluation is one
simulation ``fs.simulate(fs.KinematicRig(law, relative_velocity=(t, v_r), normal_force=N), t[-1],
output_times=t, t_start=t[0])`` whose ``friction_force`` is compared with the measured friction force F(t) [N].
The search and the uncertainty are the shared core's (:mod:`frictionsim.fit.solver`,
:mod:`frictionsim.fit.uncertainty`), as for the rig-level fit (:mod:`frictionsim.fit.rig`).

The friction force follows the engine's sign convention: positive opposing positive relative velocity v_r.
A kinematic rig has no mass, so set-valued laws (Stribeck) give their slip force on the branch sgn(v_r) (no
stick); the fitted Stribeck curve is the sliding branch.
"""

from __future__ import annotations

import math
import time
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from .._core import KinematicRig
from ..validation import reject
from .forward_model import default_force_atol, simulate_at_samples, simulate_kwargs, with_state_atol
from .parameters import INITIAL_FORCE, law_def, LawDef, Param
from .result import identification_result, IdentificationResult
from .search_space import Bounds, build_search_space, resolve_excess, user_bounds, user_values
from .solver import fit_model, fit_setup
from .validation import checked_normal_force, checked_record, finite_vector, residual_weights, summable, varying

__all__ = ["identify", "identify_dahl", "identify_lugre", "identify_elasto_plastic", "identify_stribeck"]


def _data_guess(lawdef: LawDef, v: np.ndarray, force: np.ndarray, n_abs: np.ndarray) -> Dict[str, float]:
    """Starting values from the record (refined by a coarse scan and least_squares).

    Dahl: mu from the saturated plateau of |F| / N. Laws with a Stribeck curve (a static coefficient: Stribeck,
    LuGre, ElastoPlastic, ...): the sliding branch at the faster half of the samples, sgn(v_r) F = mu N + sigma v_r,
    fitted as a line (mu from the intercept, sigma_2 / sigma_v from the slope); mu_static from the top 1 % of
    |F| / N.
    """
    ratio = np.abs(force) / n_abs
    speed = np.abs(v)
    top = float(np.quantile(ratio, 0.95))
    mu = float(np.median(ratio[ratio >= 0.9 * top]))  # the saturated plateau, unbiased by the noise
    viscous = 0.0
    if lawdef.excess:
        fast = speed >= np.quantile(speed, 0.5)
        if np.count_nonzero(fast) >= 3 and np.ptp(speed[fast]) > 0:
            slope, intercept = np.polyfit(speed[fast], np.sign(v[fast]) * force[fast] / n_abs[fast], 1)
            if slope > 0 and intercept > 0:
                mu = float(intercept)
                viscous = float(slope * np.median(n_abs))
            else:
                mu = float(np.median(ratio[fast]))
    guess = lawdef.starting_values()
    guess["mu"] = max(mu, 1e-3)
    peak = float(np.quantile(ratio, 0.99))
    guess["mu_static_excess"] = max(peak - guess["mu"], 0.1 * guess["mu"])
    moving = speed[speed > 0]
    typical_speed = float(np.quantile(moving, 0.9)) if moving.size else 1e-3
    guess["stribeck_velocity"] = max(0.1 * typical_speed, 1e-6)
    guess["viscous_damping"] = viscous
    guess["viscous_coefficient"] = viscous
    return guess


def _initial_state_choice(lawdef: LawDef, initial_state: Union[str, float, Sequence[float]],
                          force_scale: float) -> Tuple[Dict[str, Param], Optional[List[float]]]:
    """-> (extra fit variables, fixed law state): "fit" adds F_0 [N] as a fit variable (a force, not the law
    state, so its scale does not depend on the stiffness being fitted); "zero" or a given state fixes it;
    "measured" (None, None) derives it from the first sample at each run."""
    extra: Dict[str, Param] = {}
    fixed_state: Optional[List[float]] = None
    if isinstance(initial_state, str):
        if initial_state not in ("measured", "fit", "zero"):
            reject(f"initial_state must be 'measured', 'fit', 'zero' or the law state (got {initial_state!r})",
                   "initial_state")
        if lawdef.state_count == 0 and initial_state == "fit":
            reject(f"initial_state='fit': {lawdef.name} has no internal state", "initial_state")
        if initial_state == "fit" and not lawdef.inverts_force:
            reject(f"initial_state='fit': the friction force does not determine {lawdef.name}'s state; give "
                   f"'zero' or the state", "initial_state")
        if initial_state == "fit":
            extra[INITIAL_FORCE] = Param(INITIAL_FORCE, "F_0", "N", (-2.0 * force_scale, 2.0 * force_scale),
                                         minimum=-math.inf, strict=False)
        elif initial_state == "zero" and lawdef.state_count:
            fixed_state = [0.0] * lawdef.state_count
    else:
        if lawdef.state_count == 0:
            reject(f"initial_state: {lawdef.name} has no internal state", "initial_state")
        fixed_state = list(finite_vector("initial_state", np.atleast_1d(initial_state), lawdef.state_count))
    return extra, fixed_state


def _identify_kinematic(law: Any, t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                        method: str = "least_squares", bounds: Optional[Bounds] = None,
                        initial_guess: Optional[Mapping[str, float]] = None,
                        fixed: Optional[Mapping[str, float]] = None,
                        initial_state: Union[str, float, Sequence[float]] = "measured",
                        weights: Any = None, rtol: float = 1e-7, atol: Optional[float] = None,
                        simulate_options: Optional[Mapping[str, Any]] = None,
                        **solver_options: Any) -> IdentificationResult:
    started = time.perf_counter()
    lawdef, method, opts = fit_setup(law, method, solver_options)
    t, v = checked_record(t, relative_velocity, "relative_velocity")
    force = finite_vector("friction_force", friction_force, t.size)
    summable("friction_force", varying("friction_force", force))
    n_arg, n0 = checked_normal_force(normal_force, t)
    n_samples = np.full(t.size, n_arg) if isinstance(n_arg, float) else np.interp(t, n_arg[0], n_arg[1])
    w = residual_weights(weights, t.size)
    sim_kwargs = simulate_kwargs(simulate_options, rtol, atol)
    force_scale = float(np.max(np.abs(force))) or 1.0
    extra, fixed_state = _initial_state_choice(lawdef, initial_state, force_scale)

    all_bounds = user_bounds(lawdef, bounds, extra, force_scale, float(np.max(np.abs(v))) or 1.0)
    user_guess = user_values(lawdef, initial_guess, "initial_guess", tuple(extra))
    user_fixed = user_values(lawdef, fixed, "fixed")
    resolve_excess(lawdef, user_guess, "initial_guess", user_fixed)
    resolve_excess(lawdef, user_fixed, "fixed")
    for name in user_fixed:
        if name in user_guess:
            reject(f"{name} is both fixed and given an initial guess", f"fixed[{name!r}]")

    guess = _data_guess(lawdef, v, force, n_samples)
    if INITIAL_FORCE in extra:
        guess[INITIAL_FORCE] = float(force[0])
    guess.update(user_guess)
    fitted_names: List[str] = []
    fixed_values: Dict[str, float] = {}
    for p in list(lawdef.params) + list(extra.values()):
        if p.name in user_fixed:
            fixed_values[p.name] = user_fixed[p.name]
        elif p.tied:
            if p.name in user_guess:
                lawdef.refuse_fitting_tied(p.name, f"initial_guess[{p.name!r}]")
            fixed_values[p.name] = p.default if p.default is not None else p.start
        else:
            fitted_names.append(p.name)
    if len(fitted_names) >= t.size:
        reject(f"t: {t.size} samples cannot determine {len(fitted_names)} parameters", "t")
    floors = {INITIAL_FORCE: force_scale}  # F_0 may be ~0: its relative error is taken against max|F|
    spec = build_search_space(lawdef, fitted_names, guess, fixed_values, all_bounds, extra, floors, user_guess)
    scan_names = lawdef.scan_order([p.name for p in lawdef.params
                                    if p.scan and p.name in fitted_names and p.name not in user_guess])

    def rig_for(q: Mapping[str, float]):
        physical = lawdef.physical(q)
        law_obj = lawdef.build(physical)
        state = None
        if lawdef.state_count:
            if fixed_state is not None:
                state = fixed_state
            else:
                f0 = q[INITIAL_FORCE] if INITIAL_FORCE in q else float(force[0])
                state = lawdef.state_from_force(physical, f0, float(v[0]), n0)
        return KinematicRig(law_obj, relative_velocity=(t, v), normal_force=n_arg, initial_state=state), state

    force_atol = default_force_atol(atol, force)
    duration, v_max = float(t[-1] - t[0]), float(np.max(np.abs(v))) or 1.0

    def model(q: Mapping[str, float]) -> np.ndarray:
        rig, _ = rig_for(q)
        kwargs = with_state_atol(sim_kwargs, rig.state_names, force_atol, duration=duration, speed=v_max,
                                 law_stiffness=lawdef.state_stiffness(lawdef.physical(q)))
        return simulate_at_samples(rig, t, kwargs).friction_force

    fit = fit_model(model, force, w, spec, method=method, opts=opts, scan_names=scan_names,
                    x0_given=bool(user_guess))
    rig, state = rig_for(fit.q)
    physical = lawdef.physical(fit.q)

    def forward(t_new: Any, v_new: Any, n_new: Any, state_new: Any) -> np.ndarray:
        """The fitted law on the kinematic rig for new inputs, run as every residual of the fit was."""
        if v_new is None:
            reject("eval on the kinematic rig needs relative_velocity at t", "relative_velocity")
        t_new, v_new = checked_record(t_new, v_new, "relative_velocity")
        n_new, _ = checked_normal_force(n_arg if n_new is None else n_new, t_new)
        if isinstance(state_new, str) and state_new == "zero":
            state_new = [0.0] * lawdef.state_count if lawdef.state_count else None
        elif state_new is None:
            state_new = state
        elif lawdef.state_count == 0:
            reject(f"initial_state: {lawdef.name} has no internal state", "initial_state")
        else:
            state_new = list(finite_vector("initial_state", np.atleast_1d(state_new), lawdef.state_count))
        rig_new = KinematicRig(lawdef.build(physical), relative_velocity=(t_new, v_new), normal_force=n_new,
                               initial_state=state_new)
        kwargs = with_state_atol(sim_kwargs, rig_new.state_names, force_atol, duration=duration, speed=v_max,
                                 law_stiffness=lawdef.state_stiffness(physical))
        return np.asarray(simulate_at_samples(rig_new, t_new, kwargs).friction_force)

    return identification_result(fit, lawdef, method=method, experiment="kinematic rig",
                                 signal_name="friction_force", t=t, measured=force, rig=rig, initial_state=state,
                                 started=started, weights=w, forward=forward)


_COMMON_DOC = """
    Parameters
    ----------
    t : array, s
        Sample times, strictly increasing.
    relative_velocity : array, m/s
        Measured relative velocity v_r(t) at ``t`` (interpolated linearly between samples).
    friction_force : array, N
        Measured friction force F(t) (positive opposing positive v_r).
    normal_force : float or array or (t_N, N) pair, N
        Constant normal force, samples at ``t``, or its own samples covering ``t``; positive.
    method : {"least_squares", "differential_evolution"}
        Local trust-region least squares (after a coarse scan of the stiffness-like parameters that have no
        initial guess), or a global differential-evolution search over the bounds (the paper's genetic /
        particle-swarm role), deterministic for a given ``seed`` and polished by least_squares.
    bounds : dict, optional
        {name: (lower, upper)} in physical units, overriding the defaults (``LAW_PARAMETERS``). A lower bound
        > 0 makes the search logarithmic. mu_static is bounded through ``mu_static_excess`` = mu_static - mu.
    initial_guess : dict, optional
        Starting values (default: estimated from the record plus a coarse scan); with differential_evolution
        they seed the population. Names as the law's keywords or their symbols (k_t, alpha, v_s, sigma0, ...);
        mu_static needs mu given too.
    fixed : dict, optional
        Parameters held at the given values instead of fitted. Parameters tied by a rule across them that the
        law's table does not state (GeneralizedMaxwellSlip's block weights, which sum to 1) are never fitted:
        they take the value given here or their default.
    initial_state : "measured" | "fit" | "zero" | float
        Law state at t[0]: from the first measured force (Dahl z0 = F0 / k_t; LuGre from F0 and v_r(t0);
        ElastoPlastic as LuGre when sliding, z0 = (F0 - (sigma_1 + sigma_2) v_r(t0)) / sigma_0 in its elastic
        band; a law whose state the force does not determine, such as GeneralizedMaxwellSlip's blocks, starts at
        rest, z = 0), fitted (reported as ``initial_force`` F_0 [N]; laws with such an inverse only), zero, or
        the law state itself (m).
    weights : array, optional
        Residual weights (1/sigma_i).
    rtol : float
        Relative tolerance of each run (a fit needs only moderate accuracy).
    atol : float, N, optional
        Absolute tolerance on the friction force (default 1e-6 of the largest measured force); the law state's
        tolerance is atol / k_t (or / sigma_0), so a stiff contact is resolved as accurately as a soft one.
    simulate_options : dict, optional
        Further keywords for :func:`frictionsim.simulate` (method, max_step, ...).
    **solver_options
        seed (0), polish (True), maxiter (100), popsize (15), tol (0.01), workers (1: threads for
        differential_evolution), max_nfev, diff_step (1e-3: forward-difference step in the search
        variables), ftol/xtol/gtol (1e-10), loss ("linear"; the covariance assumes it), max_relative_stderr
        (0.3: above it a parameter is flagged not identifiable), rcond (1e-4: singular-value ratio of the scaled
        Jacobian below which a direction counts as unidentifiable), jacobian_step (1e-2, central differences for
        the covariance, in the search variables), scan (True), verbose (False: True logs every generation and
        iteration at INFO to ``logging.getLogger("frictionsim")`` and shows it on stderr when no logging is
        configured), callback (None: ``callback(progress)`` with a :class:`frictionsim.fit.FitProgress` after
        every differential-evolution generation and least-squares iteration; a true return value (True,
        ``np.True_``; None goes on) stops the search at the best point found, and the result is then not a success).

    Returns
    -------
    IdentificationResult

    Raises
    ------
    InvalidParameterError (a ValueError)
        Bad input; ``.parameter`` names it. A record whose work, samples x the simulations the search needs at
        the least, is beyond ``frictionsim.fit.solver.MAX_FIT_WORK`` is refused before anything runs
        (``FitWorkError``, naming ``t``, with the ``factor`` that brings it within: :func:`frictionsim.fit.decimate`).
    KeyboardInterrupt
        Ctrl-C: every simulation polls it (a fraction of a second); ``verbose`` / ``callback`` report progress.
"""


def identify_dahl(t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                  fit_exponent: bool = True, method: str = "least_squares", bounds: Optional[Bounds] = None,
                  initial_guess: Optional[Mapping[str, float]] = None, fixed: Optional[Mapping[str, float]] = None,
                  **options: Any) -> IdentificationResult:
    """Fit the Dahl law (paper 000, eq 9): mu [-], tangential_stiffness k_t [N/m], exponent alpha [-].

    ``fit_exponent=False`` holds alpha at ``initial_guess['exponent']`` or 1 (the paper's choice). k_t is
    only identifiable when the record contains force reversals (pre-sliding); with v_r of one sign and the
    force saturated at mu N, k_t and alpha are flagged not identifiable.
    """
    fixed = dict(fixed or {})
    if not fit_exponent and not any(k in fixed for k in ("exponent", "alpha")):
        guess = dict(initial_guess or {})
        fixed["exponent"] = guess.pop("exponent", guess.pop("alpha", 1.0))
        initial_guess = guess
    return _identify_kinematic("dahl", t, relative_velocity, friction_force, normal_force, method=method,
                               bounds=bounds, initial_guess=initial_guess, fixed=fixed, **options)


def _identify_bristle_law(key: str, t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                          fit_viscous: bool, initial_guess: Optional[Mapping[str, float]],
                          fixed: Optional[Mapping[str, float]], **options: Any) -> IdentificationResult:
    """LuGre, ElastoPlastic: ``fit_viscous=False`` holds sigma_2 at ``initial_guess['viscous_damping']`` or 0."""
    fixed = dict(fixed or {})
    if not fit_viscous and not any(k in fixed for k in ("viscous_damping", "sigma2", "sigma_2")):
        guess = dict(initial_guess or {})
        fixed["viscous_damping"] = guess.pop("viscous_damping", 0.0)
        initial_guess = guess
    return _identify_kinematic(key, t, relative_velocity, friction_force, normal_force,
                               initial_guess=initial_guess, fixed=fixed, **options)


def identify_lugre(t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                   fit_viscous: bool = True, method: str = "least_squares", bounds: Optional[Bounds] = None,
                   initial_guess: Optional[Mapping[str, float]] = None, fixed: Optional[Mapping[str, float]] = None,
                   **options: Any) -> IdentificationResult:
    """Fit the LuGre law: mu, mu_static [-], stribeck_velocity v_s [m/s], bristle_stiffness sigma_0 [N/m],
    bristle_damping sigma_1 [N s/m], viscous_damping sigma_2 [N s/m].

    ``fit_viscous=False`` holds sigma_2 at ``initial_guess['viscous_damping']`` or 0. sigma_1 only shows in
    fast pre-sliding transients: quasi-static data leave it flagged not identifiable.
    """
    return _identify_bristle_law("lugre", t, relative_velocity, friction_force, normal_force,
                                 fit_viscous=fit_viscous, method=method, bounds=bounds, initial_guess=initial_guess,
                                 fixed=fixed, **options)


def identify_elasto_plastic(t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                            fit_viscous: bool = True, method: str = "least_squares", bounds: Optional[Bounds] = None,
                            initial_guess: Optional[Mapping[str, float]] = None,
                            fixed: Optional[Mapping[str, float]] = None, **options: Any) -> IdentificationResult:
    """Fit the elasto-plastic law (Dupont et al. 2002): LuGre's parameters (see :func:`identify_lugre`) and
    breakaway_fraction beta [-] = z_ba / (mu F_N / sigma_0), the elastic band's share of the Coulomb deflection.

    ``fit_viscous=False`` holds sigma_2 at ``initial_guess['viscous_damping']`` or 0. beta only shows where
    the bristle is loaded from a force reversal towards sliding (the knee between the elastic band and the
    sliding level): a record that never reverses leaves it flagged not identifiable. Its bounds must stay
    below 1 (default [0, 0.95]).
    """
    return _identify_bristle_law("elasto_plastic", t, relative_velocity, friction_force, normal_force,
                                 fit_viscous=fit_viscous, method=method, bounds=bounds, initial_guess=initial_guess,
                                 fixed=fixed, **options)


def identify_stribeck(t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any, *,
                      fit_shape_exponent: bool = True, fit_viscous: bool = True, method: str = "least_squares",
                      bounds: Optional[Bounds] = None, initial_guess: Optional[Mapping[str, float]] = None,
                      fixed: Optional[Mapping[str, float]] = None, **options: Any) -> IdentificationResult:
    """Fit the Stribeck sliding curve: mu, mu_static [-], stribeck_velocity v_s [m/s], shape_exponent delta [-],
    viscous_coefficient sigma_v [N s/m].

    In the kinematic rig the law gives its slip force on the branch sgn(v_r) (no stick, karnopp_band 0), so
    the data should sweep |v_r| through the Stribeck region (|v_r| ~ v_s) to identify v_s and delta.
    ``fit_shape_exponent=False`` / ``fit_viscous=False`` hold delta (default 2) / sigma_v (default 0).
    """
    fixed = dict(fixed or {})
    guess = dict(initial_guess or {})
    if not fit_shape_exponent and not any(k in fixed for k in ("shape_exponent", "delta")):
        fixed["shape_exponent"] = guess.pop("shape_exponent", guess.pop("delta", 2.0))
    if not fit_viscous and not any(k in fixed for k in ("viscous_coefficient", "sigma_v")):
        fixed["viscous_coefficient"] = guess.pop("viscous_coefficient", guess.pop("sigma_v", 0.0))
    return _identify_kinematic("stribeck", t, relative_velocity, friction_force, normal_force, method=method,
                               bounds=bounds, initial_guess=guess, fixed=fixed, **options)


#: The laws with their own identify_* function (extra keywords such as fit_exponent); any other law of
#: LAW_PARAMETERS is fitted by the common core with the common keywords.
_FUNCTIONS = {"dahl": identify_dahl, "lugre": identify_lugre, "elasto_plastic": identify_elasto_plastic,
              "stribeck": identify_stribeck}


def identify(law: Any, t: Any, relative_velocity: Any, friction_force: Any, normal_force: Any,
             **kwargs: Any) -> IdentificationResult:
    """Identify ``law`` from the record: any engine law of ``fs.FRICTION_LAWS`` with something to fit (the keys
    of ``LAW_PARAMETERS``), by its key ("dahl", "lugre", "elasto_plastic" or "elastoplastic", "stribeck", "gms",
    ..., case-insensitive), its class name, or its class (fs.Dahl, fs.LuGre, ...).

    Dispatches to :func:`identify_dahl`, :func:`identify_lugre`, :func:`identify_elasto_plastic` or
    :func:`identify_stribeck` where the law has one; any other law takes the common keywords below.
    """
    lawdef = law_def(law)
    function = _FUNCTIONS.get(lawdef.key)
    if function is None:
        return _identify_kinematic(lawdef.key, t, relative_velocity, friction_force, normal_force, **kwargs)
    return function(t, relative_velocity, friction_force, normal_force, **kwargs)


for _f in (identify_dahl, identify_lugre, identify_elasto_plastic, identify_stribeck, identify):
    _f.__doc__ = (_f.__doc__ or "") + _COMMON_DOC
del _f
