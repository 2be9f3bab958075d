"""Rig-level identification: the friction law of paper 000's axial vibrating-sliding rig from its drive force.

Paper 000 (sec 4.2) finds the Dahl tangential contact stiffness k_t "one of the most complicated parameters
that need to be determined" and points to genetic / particle-swarm searches. The quantity its rig measures is
the drive force of eq 7, F_d = k_d (v_d t - x), not the friction force itself. :func:`identify_axial_rig`
therefore fits the law inside the full rig model (eqs 5-9, ``fs.AxialVibrationRig``): every residual
evaluation simulates the rig with ``output_times=t`` and compares ``rig.drive_force(t, x(t))`` with the
measured drive force. The search (:mod:`frictionsim.fit.solver`), the uncertainty (covariance s^2 (J^T J)^-1
with the log-transform chain rule) and the identifiability flags (:mod:`frictionsim.fit.uncertainty`) are
those of the kinematic identification (:mod:`frictionsim.fit.kinematic`): one shared core.
"""

from __future__ import annotations

import math
import time
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from .._core import AxialVibrationRig, Dahl
from ..validation import reject
from .forward_model import default_force_atol, simulate_at_samples, simulate_kwargs, with_state_atol
from .parameters import canonical_name
from .result import identification_result, IdentificationResult
from .search_space import Bounds, build_search_space, resolve_excess, user_bounds, user_values
from .solver import fit_model, fit_setup
from .validation import checked_record, residual_weights, sample_times, summable, varying

__all__ = ["identify_axial_rig"]


def identify_axial_rig(t: Any, drive_force: Any, *, law: Any = "dahl",
                       fit: Sequence[str] = ("mu", "tangential_stiffness"),
                       mass: float = 0.2, drive_stiffness: float = 2e4, sliding_velocity: float = 1e-3,
                       amplitude: float = 5e-3, frequency: float = 17.0, normal_force: float = 90.0,
                       gravity: bool = False, gravitational_acceleration: float = 9.81,
                       initial_position: Optional[float] = None, initial_velocity: float = 0.0,
                       method: str = "least_squares", bounds: Optional[Bounds] = None,
                       initial_guess: Optional[Mapping[str, float]] = None, transient: float = 0.0,
                       weights: Any = None, rtol: float = 1e-7, atol: Optional[float] = None,
                       simulate_options: Optional[Mapping[str, Any]] = None,
                       **solver_options: Any) -> IdentificationResult:
    """Fit friction-law parameters (default the Dahl mu and k_t) of the axial vibrating-sliding rig to a
    measured drive-force record F_d(t) = k_d (v_d t - x) [N] (paper 000, eqs 5-9).

    Parameters
    ----------
    t : array, s
        Sample times, strictly increasing, from t[0] = 0: the rig starts there with ``initial_position`` and
        ``initial_velocity`` and the drive spring's end at v_d t (record from the start of the run, transient
        included; subtract a logger's start time).
    drive_force : array, N
        Measured drive force at ``t``.
    law : str or class
        The friction law inside the rig: any law :func:`frictionsim.fit.identify` accepts (a key of
        ``LAW_PARAMETERS``, e.g. "dahl", "lugre", "elasto_plastic", "stribeck", or the class).
    fit : sequence of str
        Parameters to estimate (e.g. ("mu", "tangential_stiffness") or with "exponent"); the others are held
        at ``initial_guess`` values or the law's defaults (Dahl exponent 1).
    mass, drive_stiffness, sliding_velocity, amplitude, frequency, normal_force, gravity,
    gravitational_acceleration, initial_position, initial_velocity
        The rig (``fs.AxialVibrationRig``): m [kg], k_d [N/m], v_d [m/s], u0 [m], f [Hz], F_N [N], ...
    method : {"least_squares", "differential_evolution"}
        Local least squares (after a coarse scan of the fitted parameters that have no initial guess), or the
        global differential-evolution search (deterministic for ``seed``) polished by least squares.
    bounds : dict, optional
        {name: (lower, upper)}, physical units (default ``LAW_PARAMETERS``); a positive lower bound makes the
        search logarithmic.
    initial_guess : dict, optional
        Starting values of fitted parameters and values of held ones.
    transient : float, s
        Samples before t[0] + transient are simulated but not fitted.
    weights : array, optional
        Residual weights (1/sigma_i) at ``t``.
    rtol : float
        Relative tolerance of each run.
    atol : float, N, optional
        Absolute tolerance on forces (default 1e-6 of the largest measured drive force); the position,
        velocity and law-state tolerances are scaled from it (atol / k_d, atol / k_t, ...).
    simulate_options : dict, optional
        Further keywords for :func:`frictionsim.simulate`.
    **solver_options
        As for :func:`frictionsim.fit.identify_dahl` (seed, polish, maxiter, popsize, tol, workers, ...).

    Returns
    -------
    IdentificationResult
        ``signal_name`` "drive_force"; ``rig`` is the AxialVibrationRig at the solution.

    Raises
    ------
    InvalidParameterError (a ValueError)
        Bad input; ``.parameter`` names it.
    """
    started = time.perf_counter()
    lawdef, method, opts = fit_setup(law, method, solver_options)
    t, measured_all = checked_record(t, drive_force, "drive_force")
    summable("drive_force", measured_all)
    if t[0] != 0.0:  # F_d = k_d (v_d t - x) depends on absolute t: a shifted clock is a different experiment
        reject(f"t must start at 0, when the rig starts from rest and the drive end at v_d t = 0 (got "
               f"t[0] = {t[0]!r} s; subtract the logger's start time)", "t")
    w_all = residual_weights(weights, t.size)
    rig_kwargs: Dict[str, Any] = dict(mass=mass, drive_stiffness=drive_stiffness, sliding_velocity=sliding_velocity,
                                      amplitude=amplitude, frequency=frequency, normal_force=normal_force,
                                      gravity=bool(gravity), gravitational_acceleration=gravitational_acceleration,
                                      initial_position=initial_position, initial_velocity=initial_velocity)
    probe = AxialVibrationRig(Dahl(0.4, 4e4), **rig_kwargs)  # the engine checks the rig (names the parameter)
    if not (isinstance(transient, (int, float)) and math.isfinite(transient) and transient >= 0):
        reject(f"transient must be a non-negative number of seconds (got {transient!r})", "transient")
    window = t >= t[0] + transient
    if np.count_nonzero(window) < 3:
        reject(f"transient = {transient} s leaves fewer than 3 samples to fit", "transient")
    sim_kwargs = simulate_kwargs(simulate_options, rtol, atol)

    # what is fitted, what is held
    if isinstance(fit, str):
        fit = (fit,)
    fitted_names: List[str] = []
    for key in fit:
        name = canonical_name(lawdef, str(key), "fit")
        if name in lawdef.excess:
            variable, other = lawdef.excess[name]
            reject(f"fit: {name} is fitted as {variable} = {name} - {other}; name that", "fit")
        if name in fitted_names:
            reject(f"fit names {name} twice", "fit")
        lawdef.refuse_fitting_tied(name, "fit")
        fitted_names.append(name)
    if not fitted_names:
        reject("fit must name at least one parameter", "fit")
    n_fit_samples = int(np.count_nonzero(window if w_all is None else window & (w_all > 0)))
    if len(fitted_names) >= n_fit_samples:
        reject(f"t: {n_fit_samples} fitted samples cannot determine {len(fitted_names)} parameters", "t")
    speed = max(probe.vibration_velocity_amplitude, probe.sliding_velocity, 1e-3)
    all_bounds = user_bounds(lawdef, bounds, {}, float(np.max(np.abs(measured_all))) or 1.0, speed)
    values = user_values(lawdef, initial_guess, "initial_guess")
    resolve_excess(lawdef, values, "initial_guess")
    user_guess = {k: v for k, v in values.items() if k in fitted_names}
    fixed: Dict[str, float] = {}
    for p in lawdef.params:
        if p.name in fitted_names:
            continue
        if p.name in values:
            fixed[p.name] = values[p.name]
        elif p.default is not None:
            fixed[p.name] = p.default
        else:
            reject(f"initial_guess[{p.name!r}]: {lawdef.name} needs a value for {p.name} when it is not fitted",
                   f"initial_guess[{p.name!r}]")

    weight_force = probe.mass * probe.gravitational_acceleration if probe.gravity else 0.0
    level = float(np.quantile(np.abs(measured_all - weight_force), 0.95))
    mu = max(level / probe.normal_force, 1e-3)  # while the rig slides, F_d balances mu N (plus inertia)
    guess = lawdef.starting_values()
    guess.update(mu=mu, mu_static_excess=0.1 * mu)
    guess.update(user_guess)
    spec = build_search_space(lawdef, fitted_names, guess, fixed, all_bounds, {}, {}, user_guess)
    # mu is scanned too: the drive-force level is a rough guess of mu N, since F_d also carries m x''
    scan_names = lawdef.scan_order([name for name in fitted_names if name not in user_guess and
                                    (lawdef.param(name).scan or name == "mu")])

    after = f" after transient = {transient} s" if transient else ""
    measured = varying("drive_force", measured_all[window], where=after)
    w = None if w_all is None else w_all[window]
    force_atol = default_force_atol(atol, measured_all)
    duration = float(t[-1] - t[0])

    def rig_for(q: Mapping[str, float]) -> AxialVibrationRig:
        return AxialVibrationRig(lawdef.build(lawdef.physical(q)), **rig_kwargs)

    def model(q: Mapping[str, float]) -> np.ndarray:
        rig = rig_for(q)
        kwargs = with_state_atol(sim_kwargs, rig.state_names, force_atol, duration=duration, speed=speed,
                                 law_stiffness=lawdef.state_stiffness(lawdef.physical(q)),
                                 drive_stiffness=probe.drive_stiffness, omega=2.0 * math.pi * probe.frequency)
        result = simulate_at_samples(rig, t, kwargs)
        if result.t.size != t.size:
            raise IndexError("the run did not record every requested time")
        return np.asarray(rig.drive_force(result.t, result["position"]))[window]

    result_fit = fit_model(model, measured, w, spec, method=method, opts=opts, scan_names=scan_names,
                           x0_given=bool(user_guess))
    q_fit = dict(result_fit.q)

    def forward(t_new: Any, v_new: Any, n_new: Any, state_new: Any) -> np.ndarray:
        """The rig at the solution recorded at new times, run as every residual of the fit was."""
        for name, value in (("relative_velocity", v_new), ("normal_force", n_new), ("initial_state", state_new)):
            if value is not None:
                reject(f"eval on the axial vibration rig takes only t: the rig sets its own {name}", name)
        t_new = sample_times(t_new)
        if t_new[0] < 0.0:
            reject(f"t must not start before 0, when the rig starts (got t[0] = {t_new[0]!r} s)", "t")
        late = t_new[0] > 0.0  # the run still starts at 0: the drive end is at v_d t
        times = np.concatenate(([0.0], t_new)) if late else t_new
        rig = rig_for(q_fit)
        kwargs = with_state_atol(sim_kwargs, rig.state_names, force_atol, duration=duration, speed=speed,
                                 law_stiffness=lawdef.state_stiffness(lawdef.physical(q_fit)),
                                 drive_stiffness=probe.drive_stiffness, omega=2.0 * math.pi * probe.frequency)
        result = simulate_at_samples(rig, times, kwargs)
        force = np.asarray(rig.drive_force(result.t, result["position"]))
        return force[1:] if late else force

    return identification_result(result_fit, lawdef, method=method, experiment="axial vibration rig",
                                 signal_name="drive_force", t=t[window], measured=measured,
                                 rig=rig_for(result_fit.q), initial_state=None, started=started, weights=w,
                                 forward=forward)

