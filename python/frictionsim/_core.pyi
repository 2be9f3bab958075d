# Type information for the compiled engine (bindings/*.cpp), generated from the built module by a pybind11 .pyi generator;
# numeric parameter types simplified to float / int, docstrings left to the module itself (help(fs.Dahl)).
# Regenerate when the bindings change.
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['AxialVibrationRig', 'Coulomb', 'Dahl', 'ElastoPlastic', 'Event', 'EventLog', 'HydraulicOscillatorParams', 'HystereticFriction', 'KinematicRig', 'LuGre', 'Method', 'PowerLawCoefficient', 'RawResult', 'SolverOptions', 'Stribeck', 'TorsionalRig', 'equivalent_rig_normal_force', 'hot_contact_stress', 'hot_relative_curvature', 'hot_weight_per_length_in_mud', 'limit_cycle', 'mean_from_integral', 'mean_over_cycles', 'mean_over_window', 'paper001_fig7_friction', 'rig_contact_stress', 'rock_steel_contact_compliance', 'table5', 'vibration_velocity_amplitude', 'whole_cycle_window']

class Coulomb:

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
        ...

    def __init__(self, mu: float, mu_static: float | None=None) -> None:
        ...

    def __repr__(self) -> str:
        ...


    @property
    def mu(self) -> float:
        ...

    @property
    def mu_static(self) -> float:
        ...

class Stribeck:

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
        ...

    def __init__(self, mu: float, mu_static: float, stribeck_velocity: float, shape_exponent: float=2.0, viscous_coefficient: float=0.0, karnopp_band: float=0.0) -> None:
        ...

    def __repr__(self) -> str:
        ...


    def slip_force(self, v_r: float, normal_force: float, direction: int) -> float:
        ...

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

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
        ...

    def __init__(self, mu: float, tangential_stiffness: float, exponent: float=1.0) -> None:
        ...

    def __repr__(self) -> str:
        ...


    @property
    def exponent(self) -> float:
        ...

    @property
    def mu(self) -> float:
        ...

    @property
    def tangential_stiffness(self) -> float:
        ...

class LuGre:

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
        ...

    def __init__(self, mu: float, mu_static: float, stribeck_velocity: float, bristle_stiffness: float, bristle_damping: float, viscous_damping: float=0.0) -> None:
        ...

    def __repr__(self) -> str:
        ...


    def stribeck_level(self, v_r: float, normal_force: float) -> float:
        ...

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

class ElastoPlastic:

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
        ...

    def __init__(self, mu: float, mu_static: float, stribeck_velocity: float, bristle_stiffness: float, bristle_damping: float, viscous_damping: float=0.0, breakaway_fraction: float=0.5) -> None:
        ...

    def __repr__(self) -> str:
        ...


    def breakaway_deflection(self, normal_force: float) -> float:
        ...

    def plastic_deflection(self, normal_force: float) -> float:
        ...

    def plasticity_factor(self, normal_force: float, z: float, branch: int) -> float:
        ...

    def stribeck_level(self, v_r: float, normal_force: float) -> float:
        ...

    @property
    def breakaway_fraction(self) -> float:
        ...

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
    fitted_velocity_ratio_max: typing.ClassVar[float] = 2564.0
    fitted_velocity_ratio_min: typing.ClassVar[float] = 160.0

    @staticmethod
    def from_eq15(eta: float, exponent: float) -> PowerLawCoefficient:
        ...

    @staticmethod
    def from_table5(lubricant: str) -> PowerLawCoefficient:
        ...

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
        ...

    def __init__(self, eta: float, exponent: float) -> None:
        ...

    def __repr__(self) -> str:
        ...


    def coefficient(self, vibration_velocity_amplitude: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], sliding_velocity: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        ...

    def friction_force(self, normal_force: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], vibration_velocity_amplitude: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], sliding_velocity: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        ...

    @property
    def eta(self) -> float:
        ...

    @property
    def exponent(self) -> float:
        ...

class Method:
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

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
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

    max_rtol: typing.ClassVar[float]
    reliable_rtol: typing.ClassVar[float]
    min_atol: typing.ClassVar[float]

    @property
    def timeout(self) -> float:
        ...

    @timeout.setter
    def timeout(self, arg0: float) -> None:
        ...

    @property
    def max_output_rows(self) -> int:
        ...

    @max_output_rows.setter
    def max_output_rows(self, arg0: int) -> None:
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
        ...

    @property
    def switching_function(self) -> int:
        ...

    @property
    def time(self) -> float:
        ...

class RawResult:

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

    @property
    def warnings(self) -> list[str]:
        ...

    def take_event_log(self) -> EventLog:
        ...

class EventLog:

    def __len__(self) -> int:
        ...

    @property
    def rows(self) -> list[tuple]:
        ...

class AxialVibrationRig:

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
        ...

    def __init__(self, friction: typing.Any, *, mass: float=0.2, drive_stiffness: float=20000.0, sliding_velocity: float=0.001, amplitude: float=0.005, frequency: float=17.0, normal_force: float=90.0, gravity: bool=False, gravitational_acceleration: float=9.81, initial_position: float | None=None, initial_velocity: float=0.0) -> None:
        ...

    def __repr__(self) -> str:
        ...


    def _simulate(self, arg0: float, arg1: SolverOptions, arg2: float) -> RawResult:
        ...

    def drive_force(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], position: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        ...

    def surface_velocity(self, t: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        ...

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
        ...

    @property
    def sliding_velocity(self) -> float:
        ...

    @property
    def state_names(self) -> list[str]:
        ...

    @property
    def vibration_velocity_amplitude(self) -> float:
        ...

class KinematicRig:

    @staticmethod
    def harmonic(friction: typing.Any, *, sliding_velocity: float, velocity_amplitude: float, frequency: float, normal_force: typing.Any, initial_state: collections.abc.Sequence[float] | None=None) -> KinematicRig:
        ...

    def __reduce__(self) -> tuple:
        """Unpickling calls the constructor through _rebuild (the same checks and errors)."""
        ...

    def __init__(self, friction: typing.Any, *, relative_velocity: typing.Any, normal_force: typing.Any, initial_state: collections.abc.Sequence[float] | None=None) -> None:
        ...

    def __repr__(self) -> str:
        ...


    def _simulate(self, arg0: float, arg1: SolverOptions, arg2: float) -> RawResult:
        ...

    @property
    def frequency(self) -> float | None:
        ...

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
        ...

    @property
    def relative_velocity(self) -> typing.Any:
        ...

    @property
    def state_names(self) -> list[str]:
        ...

class HydraulicOscillatorParams:

    def __init__(self, *, tool_outer_radius: float, tool_inner_radius: float, wellbore_radius: float, steel_density: float, mud_density: float, rock_youngs_modulus: float, rock_poisson_ratio: float, steel_youngs_modulus: float, steel_poisson_ratio: float, rock_wear_width: float, specimen_width: float, gravity: float=9.81) -> None:
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

def _rebuild(cls: type, args: tuple, kwargs: dict, factory: str) -> typing.Any:
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
    ...

def mean_over_cycles(t: collections.abc.Sequence[float], y: collections.abc.Sequence[float], period: float, transient: float=0.0, cycles: int=0) -> float:
    ...

def mean_over_window(t: collections.abc.Sequence[float], y: collections.abc.Sequence[float], t_a: float, t_b: float) -> float:
    ...

def rig_contact_stress(normal_force: float, rock_wear_width: float, specimen_width: float) -> float:
    ...

def rock_steel_contact_compliance(params: HydraulicOscillatorParams) -> float:
    ...

def table5() -> list:
    ...

def vibration_velocity_amplitude(amplitude: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], frequency: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
    ...

def whole_cycle_window(t_first: float, t_last: float, period: float, transient: float=0.0, cycles: int=0) -> tuple[float, float, int]:
    ...

class HystereticFriction:

    def __reduce__(self) -> tuple: ...
    def __init__(self, stick_slope: float, accelerating: collections.abc.Sequence[float], decelerating: collections.abc.Sequence[float], stick_speed: float=0.001, reference_normal_force: float=35.0, branch_gap: str='hold') -> None: ...
    def __repr__(self) -> str: ...
    def torque(self, w: numpy.typing.ArrayLike, al: numpy.typing.ArrayLike, normal_force: numpy.typing.ArrayLike | None=None) -> typing.Any: ...
    def branch_torque(self, accelerating: numpy.typing.ArrayLike, w: numpy.typing.ArrayLike, al: numpy.typing.ArrayLike, normal_force: numpy.typing.ArrayLike | None=None) -> typing.Any: ...
    @property
    def stick_slope(self) -> float: ...
    @property
    def stick_speed(self) -> float: ...
    @property
    def accelerating(self) -> tuple[float, float, float, float, float, float]: ...
    @property
    def decelerating(self) -> tuple[float, float, float, float, float, float]: ...
    @property
    def reference_normal_force(self) -> float: ...
    @property
    def branch_gap(self) -> str: ...

class TorsionalRig:

    def __reduce__(self) -> tuple: ...
    def __init__(self, friction: typing.Any, **kwargs: float) -> None: ...
    def __repr__(self) -> str: ...
    def _simulate(self, arg0: float, arg1: SolverOptions, arg2: float) -> RawResult: ...
    def shaft_torque(self, states: numpy.typing.ArrayLike) -> numpy.ndarray: ...
    def voltage(self, states: numpy.typing.ArrayLike) -> numpy.ndarray: ...
    def stored_mechanical_energy(self, states: numpy.typing.ArrayLike) -> numpy.ndarray: ...
    def disc_acceleration(self, states: numpy.typing.ArrayLike, mode: typing.Any) -> numpy.ndarray: ...
    @property
    def friction(self) -> typing.Any: ...
    @property
    def period(self) -> None: ...
    @property
    def natural_frequency(self) -> float: ...
    @property
    def state_names(self) -> list[str]: ...
    disc_inertia: float
    shaft_stiffness: float
    shaft_damping: float
    motor_inertia: float
    gear_ratio: float
    inductance: float
    resistance: float
    torque_constant: float
    back_emf_constant: float
    motor_friction_torque: float
    motor_viscous_coefficient: float
    proportional_gain: float
    integral_gain: float
    reference_speed: float
    normal_force: float
    contact_radius: float
    initial_disc_speed: float
    initial_drive_speed: float

def paper001_fig7_friction(branch_gap: str='hold') -> HystereticFriction: ...

def limit_cycle(t: numpy.typing.ArrayLike, w: numpy.typing.ArrayLike, transient: float=0.0, level: float | None=None, stick_speed: float=0.01, hysteresis: float=0.05, min_amplitude: float=0.0) -> dict: ...
