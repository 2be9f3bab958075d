# Type information for the compiled engine (bindings/*.cpp), generated from the built module by a pybind11 .pyi generator;
# numeric parameter types simplified to float / int. Regenerate when the bindings change.
"""
frictionsim C++ engine: friction laws, rigs and the hybrid (stick-slip) integrator.
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['AxialVibrationRig', 'Coulomb', 'Dahl', 'Event', 'HydraulicOscillatorParams', 'KinematicRig', 'LuGre', 'Method', 'PowerLawCoefficient', 'RawResult', 'SolverOptions', 'Stribeck', 'equivalent_rig_normal_force', 'hot_contact_stress', 'hot_relative_curvature', 'hot_weight_per_length_in_mud', 'mean_from_integral', 'mean_over_cycles', 'mean_over_window', 'rig_contact_stress', 'rock_steel_contact_compliance', 'table5', 'vibration_velocity_amplitude', 'whole_cycle_window']
class Coulomb:
    """
    Coulomb friction with static and kinetic coefficients (paper 000, eq 8).
    
    Slip: F = mu F_N sgn(v_r). Stick (in rigs with a mass): the contact holds v_r = 0 while the force needed
    stays within mu_static F_N (Leine's switch model), located exactly as events.
    
    Parameters
    ----------
    mu : float
        Kinetic (sliding) friction coefficient mu [-], > 0.
    mu_static : float, optional
        Static (breakaway) coefficient mu_s [-], >= mu. Default: equal to mu.
    """
    def __getstate__(self) -> tuple[float, float]:
        ...
    def __init__(self, mu: float, mu_static: float | None = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def mu(self) -> float:
        """
        Kinetic coefficient mu [-].
        """
    @property
    def mu_static(self) -> float:
        """
        Static coefficient mu_s [-].
        """
class Stribeck:
    """
    Stribeck friction with exact stick, or a Karnopp band (Karnopp 1985).
    
    Slip: F = [mu + (mu_static - mu) exp(-(|v_r|/v_s)^delta)] F_N sgn(v_r) + sigma_v v_r.
    Stick holds while the force needed stays within mu_static F_N. With karnopp_band > 0, |v_r| below the band
    counts as stick (the band is a located mode of its own).
    
    Parameters
    ----------
    mu : float
        Coulomb (high-speed) coefficient mu_c [-], > 0.
    mu_static : float
        Static coefficient mu_s [-], >= mu.
    stribeck_velocity : float
        Stribeck velocity v_s [m/s], > 0.
    shape_exponent : float
        delta [-], > 0 (2: Gaussian decay, 1: exponential).
    viscous_coefficient : float
        Viscous friction sigma_v [N s/m], >= 0.
    karnopp_band : float
        Half-width of the Karnopp stick band [m/s], >= 0; 0 means exact stick.
    """
    def __getstate__(self) -> tuple[float, float, float, float, float, float]:
        ...
    def __init__(self, mu: float, mu_static: float, stribeck_velocity: float, shape_exponent: float = 2.0, viscous_coefficient: float = 0.0, karnopp_band: float = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def slip_force(self, v_r: float, normal_force: float, direction: int) -> float:
        """
        Slip force [N] at relative velocity v_r [m/s] on branch direction (+1 or -1).
        """
    @property
    def karnopp_band(self) -> float:
        ...
    @property
    def mu(self) -> float:
        ...
    @property
    def mu_static(self) -> float:
        ...
    @property
    def shape_exponent(self) -> float:
        ...
    @property
    def stribeck_velocity(self) -> float:
        ...
    @property
    def viscous_coefficient(self) -> float:
        ...
class Dahl:
    """
    Dahl friction (paper 000, eq 9; Dahl 1968): a bristle deflection z with
    
        dz/dt = v_r sgn(b) |b|^alpha,   b = 1 - k_t z sgn(v_r) / (mu F_N),   F = k_t z.
    
    The force rises with slope k_t from a reversal and saturates at mu F_N. The kink of dz/dt at v_r = 0 is
    located as an event. State: dahl_deflection z [m].
    
    Parameters
    ----------
    mu : float
        Friction coefficient mu [-], > 0 (saturation force mu F_N).
    tangential_stiffness : float
        Tangential contact stiffness k_t [N/m], > 0 (paper 000 fits 30-40 N/mm for shale on 45 steel, Fig. 10).
    exponent : float
        alpha [-], >= 0 (1 in the paper).
    """
    def __getstate__(self) -> tuple[float, float, float]:
        ...
    def __init__(self, mu: float, tangential_stiffness: float, exponent: float = 1.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def exponent(self) -> float:
        """
        alpha [-].
        """
    @property
    def mu(self) -> float:
        """
        Friction coefficient mu [-].
        """
    @property
    def tangential_stiffness(self) -> float:
        """
        k_t [N/m].
        """
class LuGre:
    """
    LuGre friction (Canudas de Wit, Olsson, Astrom & Lischinsky 1995):
    
        dz/dt = v_r - sigma0 |v_r| z / g(v_r),  g(v) = F_N [mu + (mu_static - mu) exp(-(v/v_s)^2)],
        F = sigma0 z + sigma1 dz/dt + sigma2 v_r.
    
    Stiff (bristle dynamics): simulate() picks CVODE BDF for it. State: bristle_deflection z [m].
    
    Parameters
    ----------
    mu, mu_static : float
        Coulomb and static coefficients [-], 0 < mu <= mu_static (Fc = mu F_N, Fs = mu_static F_N).
    stribeck_velocity : float
        v_s [m/s], > 0.
    bristle_stiffness : float
        sigma0 [N/m], > 0.
    bristle_damping : float
        sigma1 [N s/m], >= 0.
    viscous_damping : float
        sigma2 [N s/m], >= 0.
    """
    def __getstate__(self) -> tuple[float, float, float, float, float, float]:
        ...
    def __init__(self, mu: float, mu_static: float, stribeck_velocity: float, bristle_stiffness: float, bristle_damping: float, viscous_damping: float = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def stribeck_level(self, v_r: float, normal_force: float) -> float:
        """
        Steady sliding level g(v_r) [N] at normal force F_N [N].
        """
    @property
    def bristle_damping(self) -> float:
        ...
    @property
    def bristle_stiffness(self) -> float:
        ...
    @property
    def mu(self) -> float:
        ...
    @property
    def mu_static(self) -> float:
        ...
    @property
    def stribeck_velocity(self) -> float:
        ...
    @property
    def viscous_damping(self) -> float:
        ...
class PowerLawCoefficient:
    """
    Cycle-averaged dynamic friction coefficient of paper 000 (eq 17, Table 5):
    
        mu_df = eta' (v_a / v_d)^c,   v_a = 2 pi f u0 (eq 16).
    
    Not an instantaneous law: it gives the mean friction force mu_df F_N over whole vibration cycles. Table 5 was
    fitted over v_a/v_d of about 160-2564 (Table 4); outside that it extrapolates.
    
    Parameters
    ----------
    eta : float
        eta' [-], > 0.
    exponent : float
        c [-] (negative: more vibration, less friction).
    """
    fitted_velocity_ratio_max: typing.ClassVar[float] = 2564.0
    fitted_velocity_ratio_min: typing.ClassVar[float] = 160.0
    @staticmethod
    def from_eq15(eta: float, exponent: float) -> PowerLawCoefficient:
        """
        From eq 15's mu_df = eta (u0 f / v_d)^c: eta' = eta / (2 pi)^c (eq 17).
        """
    @staticmethod
    def from_table5(lubricant: str) -> PowerLawCoefficient:
        """
        Table 5's eta' and c for 'dry', 'water', 'wbm', 'obm' or 'sbm' (case-insensitive).
        """
    def __getstate__(self) -> tuple[float, float]:
        ...
    def __init__(self, eta: float, exponent: float) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def coefficient(self, vibration_velocity_amplitude: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], sliding_velocity: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        mu_df [-] for v_a [m/s] and v_d [m/s] (arrays broadcast).
        """
    def friction_force(self, normal_force: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], vibration_velocity_amplitude: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], sliding_velocity: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        Mean friction force F_df = mu_df F_N [N] over whole cycles (eq 14).
        """
    @property
    def eta(self) -> float:
        """
        eta' [-].
        """
    @property
    def exponent(self) -> float:
        """
        c [-].
        """
class Method:
    """
    Integrator of the hybrid event loop.
    
    Members:
    
      automatic : cvode_bdf for stiff laws (LuGre), dormand_prince otherwise
    
      dormand_prince : explicit RK5(4), dense output, root location
    
      cvode_bdf : SUNDIALS CVODE BDF + Newton, dense linear solver
    
      cvode_adams : SUNDIALS CVODE Adams-Moulton + fixed point
    """
    __members__: typing.ClassVar[dict[str, Method]]
    automatic: typing.ClassVar[Method]
    cvode_adams: typing.ClassVar[Method]
    cvode_bdf: typing.ClassVar[Method]
    dormand_prince: typing.ClassVar[Method]
    @typing.overload
    def __eq__(self, other: Method) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: int) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: Method) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: int) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class SolverOptions:
    """
    Options of simulate(); validated when the run starts.
    """
    method: Method
    record_steps: bool
    def __init__(self) -> None:
        ...
    @property
    def atol(self) -> float:
        ...
    @atol.setter
    def atol(self, arg0: float) -> None:
        ...
    @property
    def atol_per_state(self) -> list[float]:
        ...
    @atol_per_state.setter
    def atol_per_state(self, arg0: collections.abc.Sequence[float]) -> None:
        ...
    @property
    def event_window(self) -> float:
        ...
    @event_window.setter
    def event_window(self, arg0: float) -> None:
        ...
    @property
    def initial_step(self) -> float:
        ...
    @initial_step.setter
    def initial_step(self, arg0: float) -> None:
        ...
    @property
    def max_events_in_window(self) -> int:
        ...
    @max_events_in_window.setter
    def max_events_in_window(self, arg0: int) -> None:
        ...
    @property
    def max_step(self) -> float:
        ...
    @max_step.setter
    def max_step(self, arg0: float) -> None:
        ...
    @property
    def max_steps(self) -> int:
        ...
    @max_steps.setter
    def max_steps(self, arg0: int) -> None:
        ...
    @property
    def output_times(self) -> list[float]:
        ...
    @output_times.setter
    def output_times(self, arg0: collections.abc.Sequence[float]) -> None:
        ...
    @property
    def rtol(self) -> float:
        ...
    @rtol.setter
    def rtol(self, arg0: float) -> None:
        ...
class Event:
    """
    One switch of the hybrid system (a stick-slip transition, a velocity reversal).
    """
    def __repr__(self) -> str:
        ...
    @property
    def mode_after(self) -> int:
        ...
    @property
    def mode_after_name(self) -> str:
        ...
    @property
    def mode_before(self) -> int:
        ...
    @property
    def mode_before_name(self) -> str:
        ...
    @property
    def name(self) -> str:
        """
        name of the guard, e.g. 'relative_velocity'
        """
    @property
    def switching_function(self) -> int:
        """
        index of the guard that fired
        """
    @property
    def time(self) -> float:
        """
        t [s]
        """
class RawResult:
    """
    What the C++ engine recorded (see frictionsim.Result).
    """
    @property
    def completed(self) -> bool:
        ...
    @property
    def events(self) -> list[Event]:
        ...
    @property
    def friction_force(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def mode(self) -> numpy.typing.NDArray[numpy.int32]:
        ...
    @property
    def state_names(self) -> list[str]:
        ...
    @property
    def states(self) -> numpy.ndarray[typing.Any, numpy.dtype[typing.Any]]:
        ...
    @property
    def stats(self) -> dict:
        ...
    @property
    def t(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def t_reached(self) -> float:
        ...
class AxialVibrationRig:
    """
    The axial vibrating-sliding rig of paper 000 (eqs 5-9): a specimen of mass m pulled through a drive spring
    k_d whose end moves at v_d, on a surface vibrating as u = u0 sin(2 pi f t), with friction under normal force F_N:
    
        m x'' = F_d - F_F - F_g,   F_d = k_d (v_d t - x),   v_r = x' - u0 w cos(w t).
    
    Defaults are the paper's Fig. 7(a) dry case (u0 = 5 mm, f = 17 Hz, v_d = 1 mm/s, F_N = 90 N; m = 0.2 kg,
    k_d = 2e4 N/m chosen, the paper gives no drive stiffness). SI units.
    
    States: position x [m], velocity x' [m/s], the law's state (dahl_deflection / bristle_deflection [m]),
    friction_impulse [N s], friction_work [J], drive_work [J] (drive work = energy change + friction work).
    
    Parameters
    ----------
    friction : Coulomb | Stribeck | Dahl | LuGre
    mass : float            m [kg], > 0
    drive_stiffness : float k_d [N/m], > 0
    sliding_velocity : float v_d [m/s], >= 0
    amplitude : float       u0 [m], >= 0
    frequency : float       f [Hz], > 0
    normal_force : float    F_N [N], > 0
    gravity : bool          vertical rig: F_g = m g opposes the sliding
    gravitational_acceleration : float  g [m/s^2]
    initial_position : float, optional  x(0) [m]; default 0, or -m g / k_d with gravity (spring carries the weight)
    initial_velocity : float            x'(0) [m/s]
    """
    def __getstate__(self) -> tuple[typing.Any, float, float, float, float, float, float, bool, float, float | None, float]:
        ...
    def __init__(self, friction: typing.Any, *, mass: float = 0.2, drive_stiffness: float = 20000.0, sliding_velocity: float = 0.001, amplitude: float = 0.005, frequency: float = 17.0, normal_force: float = 90.0, gravity: bool = False, gravitational_acceleration: float = 9.81, initial_position: float | None = None, initial_velocity: float = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def _simulate(self, arg0: float, arg1: SolverOptions, arg2: float) -> RawResult:
        ...
    def drive_force(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], position: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        F_d = k_d (v_d t - x) [N] (eq 7).
        """
    def surface_velocity(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        Velocity of the vibrating surface u0 w cos(w t) [m/s].
        """
    @property
    def amplitude(self) -> float:
        ...
    @property
    def drive_stiffness(self) -> float:
        ...
    @property
    def frequency(self) -> float:
        ...
    @property
    def friction(self) -> typing.Any:
        ...
    @property
    def gravitational_acceleration(self) -> float:
        ...
    @property
    def gravity(self) -> bool:
        ...
    @property
    def initial_position(self) -> float | None:
        ...
    @property
    def initial_velocity(self) -> float:
        ...
    @property
    def mass(self) -> float:
        ...
    @property
    def normal_force(self) -> float:
        ...
    @property
    def period(self) -> float:
        """
        Vibration period 1/f [s].
        """
    @property
    def sliding_velocity(self) -> float:
        ...
    @property
    def state_names(self) -> list[str]:
        ...
    @property
    def vibration_velocity_amplitude(self) -> float:
        """
        v_a = 2 pi f u0 [m/s] (eq 16).
        """
class KinematicRig:
    """
    A friction law driven by a prescribed relative velocity v_r(t) [m/s] and normal force N(t) [N]: no mass, so
    set-valued laws (Coulomb, Stribeck) give their slip force on the branch sgn(v_r); reversals of v_r are located
    as events. This is the model that identification from measured signals fits (frictionsim.fit).
    
    States: the law's state (dahl_deflection / bristle_deflection [m]), friction_impulse int F dt [N s] and
    friction_work int F v_r dt [J].
    
    Parameters
    ----------
    friction : Coulomb | Stribeck (no Karnopp band) | Dahl | LuGre
    relative_velocity : float | callable t -> v_r | (t, v_r) pair of arrays (piecewise linear)
    normal_force : float | callable t -> N | (t, N) pair of arrays, > 0 at every time
    initial_state : sequence of float, optional
        The law's initial state (z0 [m] for Dahl and LuGre); default zero.
    """
    @staticmethod
    def harmonic(friction: typing.Any, *, sliding_velocity: float, velocity_amplitude: float, frequency: float, normal_force: typing.Any, initial_state: collections.abc.Sequence[float] | None = None) -> KinematicRig:
        """
        The paper's relative velocity v_r = v_d - v_a cos(2 pi f t) (eqs 8-9, 16), v_a [m/s], f [Hz].
        """
    def __getstate__(self) -> tuple[typing.Any, bool, typing.Any, typing.Any, list[float] | None]:
        ...
    def __init__(self, friction: typing.Any, *, relative_velocity: typing.Any, normal_force: typing.Any, initial_state: collections.abc.Sequence[float] | None = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def _simulate(self, arg0: float, arg1: SolverOptions, arg2: float) -> RawResult:
        ...
    @property
    def frequency(self) -> float | None:
        """
        f [Hz] of a harmonic relative velocity, else None.
        """
    @property
    def friction(self) -> typing.Any:
        ...
    @property
    def initial_state(self) -> list[float] | None:
        ...
    @property
    def normal_force(self) -> typing.Any:
        ...
    @property
    def period(self) -> float | None:
        """
        Period 1/f [s] of a harmonic relative velocity, else None.
        """
    @property
    def relative_velocity(self) -> typing.Any:
        ...
    @property
    def state_names(self) -> list[str]:
        ...
class HydraulicOscillatorParams:
    """
    Geometry and materials of paper 000 eqs 1-4, SI units.
    """
    def __init__(self, *, tool_outer_radius: float, tool_inner_radius: float, wellbore_radius: float, steel_density: float, mud_density: float, rock_youngs_modulus: float, rock_poisson_ratio: float, steel_youngs_modulus: float, steel_poisson_ratio: float, rock_wear_width: float, specimen_width: float, gravity: float = 9.81) -> None:
        ...
    @property
    def gravity(self) -> float:
        ...
    @property
    def mud_density(self) -> float:
        ...
    @property
    def rock_poisson_ratio(self) -> float:
        ...
    @property
    def rock_wear_width(self) -> float:
        ...
    @property
    def rock_youngs_modulus(self) -> float:
        ...
    @property
    def specimen_width(self) -> float:
        ...
    @property
    def steel_density(self) -> float:
        ...
    @property
    def steel_poisson_ratio(self) -> float:
        ...
    @property
    def steel_youngs_modulus(self) -> float:
        ...
    @property
    def tool_inner_radius(self) -> float:
        ...
    @property
    def tool_outer_radius(self) -> float:
        ...
    @property
    def wellbore_radius(self) -> float:
        ...
def equivalent_rig_normal_force(params: HydraulicOscillatorParams) -> float:
    ...
def hot_contact_stress(params: HydraulicOscillatorParams) -> float:
    ...
def hot_relative_curvature(params: HydraulicOscillatorParams) -> float:
    ...
def hot_weight_per_length_in_mud(params: HydraulicOscillatorParams) -> float:
    ...
def mean_from_integral(t: collections.abc.Sequence[float], running_integral: collections.abc.Sequence[float], t_a: float, t_b: float) -> float:
    """
    (Y(t_b) - Y(t_a)) / (t_b - t_a): the mean of dY/dt from its running integral Y (linear between samples).
    """
def mean_over_cycles(t: collections.abc.Sequence[float], y: collections.abc.Sequence[float], period: float, transient: float = 0.0, cycles: int = 0) -> float:
    """
    Mean of sampled y(t) over whole cycles after a transient (trapezoid rule on the samples).
    """
def mean_over_window(t: collections.abc.Sequence[float], y: collections.abc.Sequence[float], t_a: float, t_b: float) -> float:
    """
    Mean of sampled y(t) over [t_a, t_b] (trapezoid rule, interpolated window ends).
    """
def rig_contact_stress(normal_force: float, rock_wear_width: float, specimen_width: float) -> float:
    ...
def rock_steel_contact_compliance(params: HydraulicOscillatorParams) -> float:
    ...
def table5() -> list:
    """
    Paper 000's Table 5 as printed: one dict per lubricant.
    """
def vibration_velocity_amplitude(amplitude: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], frequency: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    """
    v_a = 2 pi f u0 [m/s] (paper 000, eq 16).
    """
def whole_cycle_window(t_first: float, t_last: float, period: float, transient: float = 0.0, cycles: int = 0) -> tuple[float, float, int]:
    """
    (t_a, t_b, cycles): whole cycles of `period` [s] after `transient` [s]; cycles <= 0 takes all that fit.
    """
