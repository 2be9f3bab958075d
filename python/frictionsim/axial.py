"""The axial vibrating-sliding rig of paper 000 (shale on 45 steel): the mean friction F_df of one run, the friction
reduction that axial vibration brings, Table 4's runs beside the simulation, the reduction against the velocity
ratio, the Fig. 7(a) presets, and the identification of the law inside the rig (:func:`identify_axial_rig`, kept in
:mod:`frictionsim.fit.rig`).

The rig is eqs 5-7 (:class:`frictionsim.AxialVibrationRig`; its defaults are the Fig. 7(a) dry case), with Coulomb
(eq 8) or Dahl (eq 9) friction; v_a = 2 pi f u0 (eq 16) and Table 5's mu_df = eta' (v_a/v_d)^c (eq 17). Under the
prescribed v_r = v_d - v_a cos(2 pi f t) Coulomb friction averages (2/pi) asin(v_d/v_a) mu N over a cycle
(v_d < v_a), so it is reduced by 1 - (2/pi) asin(v_d/v_a); on the rig, inertia and drive spring change that. A
reduction is 1 - F_df / (mu F_N), mu F_N being the sliding friction without vibration (Table 4's F_sf).

    >>> import frictionsim as fs
    >>> fs.axial.axial_mean_friction(friction=fs.Dahl(0.41, 4e4))      # F_df [N] of the Fig. 7(a) rig
    >>> fs.axial.coulomb_reduction(0.4), fs.axial.kinematic_coulomb_reduction(0.4)    # 0.738 both
    >>> fs.axial.reduction_sweep([0.1, 0.4, 0.8])                        # pandas DataFrame, one row per v_d/v_a
"""

from __future__ import annotations

import math
from typing import Any, Dict, Mapping, Optional, Sequence

# frictionsim.sweeps imports this module (the old home of the mean-friction functions): nothing here imports it.
from ._core import AxialVibrationRig, Coulomb, Dahl, KinematicRig, PowerLawCoefficient, whole_cycle_window
from .errors import InvalidParameterError
from .simulation import SOLVER_DEFAULTS, simulate

__all__ = ["FIG7A_MU", "FIG7A_TANGENTIAL_STIFFNESS", "NO_VIBRATION_T_END", "SWEEP_SETTLE", "axial_mean_friction",
           "axial_reduction", "coulomb_reduction", "fig7a_laws", "fig7a_rig_parameters", "identify_axial_rig",
           "kinematic_coulomb_reduction", "kinematic_mean_friction", "reduction_sweep", "table4_comparison",
           "table4_run"]

#: Fig. 7(a)'s friction, the scenario choices of examples/axial_rig_demo.cpp: mu = 0.41 (Table 4, dry:
#: F_sf / F_N = 0.4097) and the Dahl k_t = 40 N/mm of Fig. 10 [N/m].
FIG7A_MU, FIG7A_TANGENTIAL_STIFFNESS = 0.41, 4e4
SWEEP_SETTLE = 8.0  #: s before the averaged cycles of a swept axial run (Dahl loads over ~1 mm at 1 mm/s)
NO_VIBRATION_T_END = 12.0  #: s; without vibration the Dahl force approaches mu F_N with a ~1 s time constant


def __getattr__(name: str):
    # identify_axial_rig stays in fit.rig; imported on first use (fit loads SciPy).
    if name == "identify_axial_rig":
        from .fit.rig import identify_axial_rig

        return identify_axial_rig
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# ------------------------------------------------------------------------------------------------ presets
def fig7a_rig_parameters() -> Dict[str, float]:
    """The Fig. 7(a) rig, dry, Table 4 run VS3 (u0 = 5 mm, f = 17 Hz, v_d = 60 mm/min, F_N = 90 N; m = 0.2 kg and
    k_d = 2e4 N/m chosen): the engine's defaults, ``AxialVibrationRig.parameters``, as a new dict of keywords."""
    return {p.name: p.default for p in AxialVibrationRig.parameters}


def fig7a_laws(mu: float = FIG7A_MU) -> Dict[str, Any]:
    """Fig. 7(a)'s two laws by key: Coulomb (eq 8) and Dahl (eq 9, k_t = 40 N/mm, alpha = 1) with coefficient ``mu``."""
    return {"coulomb": Coulomb(mu), "dahl": Dahl(mu, FIG7A_TANGENTIAL_STIFFNESS)}


# ------------------------------------------------------------------------------------------------ one run
def axial_mean_friction(*, friction: Any, t_end: float = 2.0, transient: float = 1.0, method: str = "automatic",
                        rtol: float = SOLVER_DEFAULTS.rtol, atol: float = SOLVER_DEFAULTS.atol, **rig_params: Any) -> float:
    """Mean friction force F_df [N] of one :class:`frictionsim.AxialVibrationRig` run (paper 000, Table 4).

    Builds ``AxialVibrationRig(friction=friction, **rig_params)`` (``mass`` [kg], ``drive_stiffness`` [N/m],
    ``sliding_velocity`` v_d [m/s], ``amplitude`` A [m], ``frequency`` f [Hz], ``normal_force`` N [N], ...),
    simulates it to ``t_end`` [s] and returns the mean friction force over the whole vibration cycles after
    ``transient`` [s]. Top-level and picklable: pass it to :func:`frictionsim.sweep`, e.g. over amplitude and
    frequency for a friction-reduction map (reduction 1 - F_df / (mu N) for a Coulomb law).
    """
    rig = AxialVibrationRig(friction=friction, **rig_params)
    if not (math.isfinite(float(t_end)) and t_end > 0):
        raise InvalidParameterError(f"axial_mean_friction: t_end must be positive and finite (got {t_end!r})",
                                    "t_end")
    # Only the window's ends are recorded (dense output): the mean comes from the friction impulse there, and a
    # sweep point copies two rows instead of every step's (half the time of a 2-s point, all of it GIL-free).
    t_a, t_b, _ = whole_cycle_window(0.0, float(t_end), rig.period, float(transient))
    result = simulate(rig, t_end, method=method, rtol=rtol, atol=atol, output_times=[t_a, t_b])
    return result.mean_over_cycles()  # the record is exactly those whole cycles


def kinematic_mean_friction(*, friction: Any, sliding_velocity: float, velocity_amplitude: float, frequency: float,
                            normal_force: float, t_end: Optional[float] = None, transient: float = 0.0,
                            method: str = "automatic", rtol: float = SOLVER_DEFAULTS.rtol, atol: float = SOLVER_DEFAULTS.atol) -> float:
    """Mean friction force [N] of a prescribed-motion contact, v_r = v_d - v_a cos(2 pi f t) (paper 000, eqs 8-9).

    Builds :meth:`frictionsim.KinematicRig.harmonic` with ``sliding_velocity`` v_d [m/s],
    ``velocity_amplitude`` v_a [m/s], ``frequency`` f [Hz] and ``normal_force`` N [N], simulates it to
    ``t_end`` [s] (default: ``transient`` plus 10 periods) and returns the mean friction force over the whole
    cycles after ``transient`` [s]. For Coulomb friction and v_d < v_a this is (2/pi) asin(v_d/v_a) mu N.
    """
    rig = KinematicRig.harmonic(friction, sliding_velocity=sliding_velocity, velocity_amplitude=velocity_amplitude,
                                frequency=frequency, normal_force=normal_force)
    if t_end is None:
        t_end = transient + 10.0 * rig.period
    result = simulate(rig, t_end, method=method, rtol=rtol, atol=atol)
    return result.mean_over_cycles(transient=transient)


def _mean_over_last_cycles(friction: Any, t_end: float, cycles: int, rtol: float, atol: float, method: str,
                           rig_params: Mapping[str, Any]) -> float:
    """F_df [N] over the last ``cycles`` whole cycles before ``t_end`` (as a scenario's ``cycles`` measures)."""
    frequency = float(rig_params.get("frequency", fig7a_rig_parameters()["frequency"]))
    return axial_mean_friction(friction=friction, t_end=t_end, transient=t_end - cycles / frequency, method=method,
                               rtol=rtol, atol=atol, **rig_params)


# ------------------------------------------------------------------------------------------------ friction reduction
def _check_ratio(ratio: Any) -> float:
    if isinstance(ratio, (str, bytes)) or not (math.isfinite(float(ratio)) and float(ratio) > 0):
        raise InvalidParameterError(f"ratio: v_d/v_a must be positive and finite (got {ratio!r})", "ratio")
    return float(ratio)


def coulomb_reduction(ratio: float) -> float:
    """Closed-form friction reduction 1 - (2/pi) asin(v_d/v_a) of Coulomb friction (eq 8) under the prescribed
    v_r = v_d - v_a cos(2 pi f t), ``ratio`` = v_d/v_a; 0 for v_d >= v_a (v_r never reverses)."""
    ratio = _check_ratio(ratio)
    return 1.0 - 2.0 / math.pi * math.asin(ratio) if ratio < 1.0 else 0.0


def kinematic_coulomb_reduction(ratio: float, *, cycles: int = 5, sliding_velocity: Optional[float] = None,
                                frequency: Optional[float] = None, normal_force: Optional[float] = None,
                                rtol: float = 1e-10, atol: float = 1e-12) -> float:
    """The reduction of :func:`coulomb_reduction`, simulated: 1 - F_df / (mu N) of the kinematic rig
    (:func:`kinematic_mean_friction`, Coulomb mu = 0.41) over ``cycles`` cycles at v_a = v_d / ``ratio``.
    v_d [m/s], f [Hz] and N [N] default to Fig. 7(a)'s; mu and N cancel."""
    ratio, rig = _check_ratio(ratio), fig7a_rig_parameters()
    v_d = float(rig["sliding_velocity"] if sliding_velocity is None else sliding_velocity)
    f = float(rig["frequency"] if frequency is None else frequency)
    normal = float(rig["normal_force"] if normal_force is None else normal_force)
    mean = kinematic_mean_friction(friction=Coulomb(FIG7A_MU), sliding_velocity=v_d, velocity_amplitude=v_d / ratio,
                                   frequency=f, normal_force=normal, t_end=cycles / f, rtol=rtol, atol=atol)
    return 1.0 - mean / (FIG7A_MU * normal)


def axial_reduction(friction: Any, ratio: float, *, mu: Optional[float] = None, settle: float = SWEEP_SETTLE,
                    cycles: int = 10, method: str = "automatic", rtol: float = 1e-8, atol: float = 1e-12,
                    **rig_params: Any) -> float:
    """Friction reduction 1 - F_df / (mu F_N) of the axial rig (eqs 5-7) with ``friction``, vibrated at
    u0 = v_d / (2 pi f ``ratio``) (eq 16; so no ``amplitude`` in ``rig_params``, the rest default to Fig. 7(a));
    F_df over ``cycles`` cycles after ``settle`` [s], ``mu`` defaults to the law's."""
    ratio = _check_ratio(ratio)
    if "amplitude" in rig_params:
        raise InvalidParameterError("axial_reduction: the amplitude follows from ratio; do not pass it", "amplitude")
    params = {**fig7a_rig_parameters(), **rig_params}
    params["amplitude"] = params["sliding_velocity"] / ratio / (2.0 * math.pi * params["frequency"])
    mean = axial_mean_friction(friction=friction, t_end=settle + cycles / params["frequency"], transient=settle,
                               method=method, rtol=rtol, atol=atol, **params)
    return 1.0 - mean / ((friction.mu if mu is None else mu) * params["normal_force"])


def _table5_reduction(lubricant: str, ratio: float, mu: float) -> float:
    """1 - mu_df / mu of Table 5 (eq 17) at v_d/v_a = ``ratio``; NaN outside the v_a/v_d its Table 4 runs span."""
    from .data import table4

    t4 = table4()
    runs = t4[t4["lubricant"] == lubricant]["velocity_ratio"]
    if not runs.min() <= 1.0 / ratio <= runs.max():
        return math.nan
    return 1.0 - float(PowerLawCoefficient.from_table5(lubricant).coefficient(1.0 / ratio, 1.0)) / mu


def _table4_reduction(lubricant: str, ratio: float) -> float:
    """Measured 1 - F_df / F_sf of the Table 4 run of ``lubricant`` at v_d/v_a = ``ratio``, NaN if none."""
    import numpy as np

    from .data import table4

    t4 = table4()
    runs = t4[(t4["lubricant"] == lubricant) & np.isclose(t4["velocity_ratio"], 1.0 / ratio, rtol=1e-9)]
    return float(1.0 - runs["F_df_N"].iloc[0] / runs["F_sf_N"].iloc[0]) if len(runs) else math.nan


def reduction_sweep(ratios: Sequence[float], *, mu: float = FIG7A_MU, laws: Optional[Mapping[str, Any]] = None,
                    lubricant: str = "dry", settle: float = SWEEP_SETTLE, cycles: int = 10, kinematic_cycles: int = 5,
                    method: str = "automatic", rtol: float = 1e-8, atol: float = 1e-12, **rig_params: Any):
    """Friction reduction 1 - F_df / (mu F_N) against v_d/v_a on the axial rig (``rig_params``, default Fig. 7(a)):
    a pandas DataFrame, one row per ratio of ``ratios`` plus the rig's own (its ``amplitude``: Table 4 VS3 for
    Fig. 7(a)), sorted.

    Columns: velocity_ratio (v_d/v_a), velocity_amplitude_m_per_s, amplitude_mm, coulomb_closed_form
    (:func:`coulomb_reduction`), kinematic_coulomb (:func:`kinematic_coulomb_reduction`), axial_<name> per law of
    ``laws`` (default :func:`fig7a_laws` of ``mu``; :func:`axial_reduction` against ``mu``), table5_<lubricant>
    (1 - mu_df / mu of eq 17, inside the v_a/v_d range of its Table 4 runs) and table4_<lubricant> (the measured
    1 - F_df / F_sf of a Table 4 run at that ratio). Serial: each ratio takes milliseconds.
    """
    import pandas as pd

    params = {**fig7a_rig_parameters(), **rig_params}
    own = params.pop("amplitude")
    v_d, f = float(params["sliding_velocity"]), float(params["frequency"])
    omega = 2.0 * math.pi * f
    laws = fig7a_laws(mu) if laws is None else laws
    rows = []
    for ratio in sorted({_check_ratio(r) for r in ratios} | ({v_d / (omega * own)} if own > 0 else set())):
        v_a = v_d / ratio
        rows.append({
            "velocity_ratio": ratio, "velocity_amplitude_m_per_s": v_a, "amplitude_mm": 1e3 * v_a / omega,
            "coulomb_closed_form": coulomb_reduction(ratio),
            "kinematic_coulomb": kinematic_coulomb_reduction(ratio, cycles=kinematic_cycles, sliding_velocity=v_d,
                                                             frequency=f, normal_force=params["normal_force"]),
            **{f"axial_{name}": axial_reduction(law, ratio, mu=mu, settle=settle, cycles=cycles, method=method,
                                                rtol=rtol, atol=atol, **params) for name, law in laws.items()},
            f"table5_{lubricant}": _table5_reduction(lubricant, ratio, mu),
            f"table4_{lubricant}": _table4_reduction(lubricant, ratio),
        })
    return pd.DataFrame(rows)


# ------------------------------------------------------------------------------------------------ Table 4
def table4_run(lubricant: str, *, amplitude: float, frequency: float, sliding_velocity: float, normal_force: float):
    """Table 4's run (a pandas Series, :func:`frictionsim.data.table4`'s columns) of ``lubricant`` at u0 [m],
    f [Hz], v_d [m/s] and F_N [N], or None."""
    import numpy as np

    from .data import table4

    t4 = table4()
    match = t4[(t4["lubricant"] == lubricant) & np.isclose(t4["amplitude_m"], float(amplitude))
               & np.isclose(t4["frequency_hz"], float(frequency))
               & np.isclose(t4["sliding_velocity_m_per_s"], float(sliding_velocity))
               & np.isclose(t4["normal_force_n"], float(normal_force))]
    return match.iloc[0] if len(match) else None


def table4_comparison(friction: Any, *, lubricant: Optional[str] = None, t_end: float = 2.0, cycles: int = 10,
                      no_vibration_t_end: float = NO_VIBRATION_T_END, method: str = "automatic", rtol: float = 1e-8,
                      atol: float = 1e-12, **rig_params: Any) -> Dict[str, Any]:
    """One law on the axial rig (``rig_params``, default Fig. 7(a)) beside Table 4's run and Table 5 (eq 17).

    F_df: mean friction over the last ``cycles`` cycles before ``t_end`` [s]; F_sf: the same without vibration
    (u0 = 0) to ``no_vibration_t_end`` [s]. A dict: table4_run, F_N_N, mu, velocity_ratio (v_a/v_d), F_df_sim_N,
    F_sf_sim_N, reduction_sim_percent (1 - F_df/F_sf), mu_df_sim, F_df_table4_N, F_sf_table4_N,
    reduction_table4_percent, mu_df_table4, F_df_table5_N, mu_df_table5 (NaN / "" where ``lubricant`` or its run is
    missing).
    """
    params = {**fig7a_rig_parameters(), **rig_params}
    rig = AxialVibrationRig(friction=friction, **params)
    normal, ratio = float(rig.normal_force), rig.vibration_velocity_amplitude / rig.sliding_velocity
    moving = _mean_over_last_cycles(friction, t_end, cycles, rtol, atol, method, params)
    still = _mean_over_last_cycles(friction, no_vibration_t_end, cycles, rtol, atol, method,
                                   {**params, "amplitude": 0.0})
    t4 = None if lubricant is None else table4_run(lubricant, amplitude=rig.amplitude, frequency=rig.frequency,
                                                   sliding_velocity=rig.sliding_velocity, normal_force=normal)
    mu_t5 = float(PowerLawCoefficient.from_table5(lubricant).coefficient(ratio, 1.0)) if lubricant else math.nan

    def measured(column: str) -> float:
        return float(t4[column]) if t4 is not None else math.nan

    return {
        "table4_run": t4["number"] if t4 is not None else "", "F_N_N": normal, "mu": friction.mu,
        "velocity_ratio": ratio, "F_df_sim_N": moving, "F_sf_sim_N": still,
        "reduction_sim_percent": 100.0 * (1.0 - moving / still), "mu_df_sim": moving / normal,
        "F_df_table4_N": measured("F_df_N"), "F_sf_table4_N": measured("F_sf_N"),
        "reduction_table4_percent": 100.0 * (1.0 - measured("F_df_N") / measured("F_sf_N")),
        "mu_df_table4": measured("mu_df"), "F_df_table5_N": mu_t5 * normal, "mu_df_table5": mu_t5,
    }
