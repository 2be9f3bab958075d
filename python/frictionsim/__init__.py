"""frictionsim: friction-driven dynamics in drilling.

A C++17 engine (stick-slip located as events, exact restarts, Dormand-Prince 5(4) and SUNDIALS CVODE) with the
friction laws and rigs of paper 000 (axial vibrating-sliding rig, shale on 45 steel), paper 001 (torsional rig),
field-scale drill strings (StringRig on a DrillString of PipeSections, frictionsim.drillstring) and torque and drag
along a well survey (Survey, SoftString, frictionsim.wells); Python adds
fitting, signal processing, plots, sweeps and a command line. SI units throughout (values with units at the
boundary: frictionsim.units).

    >>> import frictionsim as fs
    >>> rig = fs.AxialVibrationRig(friction=fs.Dahl(mu=0.41, tangential_stiffness=4e4))
    >>> result = fs.simulate(rig, 2.0)
    >>> result.mean_over_cycles(transient=1.0)   # mean friction force F_df [N]
"""

from ._core import (
    FRICTION_LAWS,
    RIGS,
    HAS_EIGEN,
    HAS_SUNDIALS,
    AxialVibrationRig,
    DetournayBit,
    DrillString,
    HydraulicOscillator,
    HystereticFriction,
    KinematicRig,
    NavarroLopez2Dof,
    NavarroLopez4Dof,
    NavarroLopezBit,
    OscillatorResponse,
    Parameter,
    PipeSection,
    PowerLawCoefficient,
    SoftString,
    StopCondition,
    StringRig,
    Survey,
    TorqueDragResult,
    TorsionalRig,
    table5,
    vibration_velocity_amplitude,
)
from ._core import CallableLaw  # a friction law written in Python (not in FRICTION_LAWS)
if HAS_EIGEN:  # the Moreau-Jean string needs an extension built with Eigen
    from ._core import TorsionalString, aarsnes_shor_well_b
from .errors import AccuracyWarning, BudgetExceededError, ChatteringError, InvalidParameterError, SimulationError
from .result import Event, Result
from .simulation import METHODS, SOLVER_DEFAULTS, simulate
from .sweeps import SweepResult, sweep
from . import units

#: Values with units at the boundary ("55 rpm", "25 klbf", pint quantities; pint from frictionsim[units]): every
#: engine routine that takes a parameter table's keywords converts them to the table's SI unit.
units.install()

from ._core import __version__  # the CMake project version (CMakeLists.txt), compiled into the extension

#: Friction laws a rig can run with: the engine's list (include/frictionsim/friction/laws.hpp), each class named
#: as in C++ (fs.Coulomb, fs.LuGre, ...), with its parameter table in ``Law.parameters``.
globals().update({_law.__name__: _law for _law in FRICTION_LAWS})
#: Rigs simulate() runs: the engine's list (include/frictionsim/rigs/rigs.hpp) and the string models, each class
#: named as bound, so a rig added to the list needs no line here.
globals().update({_rig.__name__: _rig for _rig in RIGS})

__all__ = [
    "AccuracyWarning",
    "AxialVibrationRig",
    "BudgetExceededError",
    "CallableLaw",
    "ChatteringError",
    "DetournayBit",
    "DrillString",
    "HydraulicOscillator",
    "HystereticFriction",
    "Event",
    "FRICTION_LAWS",
    "HAS_EIGEN",
    "HAS_SUNDIALS",
    "InvalidParameterError",
    "KinematicRig",
    "METHODS",
    "NavarroLopez2Dof",
    "NavarroLopez4Dof",
    "NavarroLopezBit",
    "OscillatorResponse",
    "Parameter",
    "PipeSection",
    "SOLVER_DEFAULTS",
    "PowerLawCoefficient",
    "Result",
    "SimulationError",
    "SoftString",
    "StopCondition",
    "StringRig",
    "Survey",
    "TorqueDragResult",
    "TorsionalRig",
    "simulate",
    "sweep",
    "SweepResult",
    "table5",
    "units",
    "vibration_velocity_amplitude",
] + [_law.__name__ for _law in FRICTION_LAWS] + (["TorsionalString", "aarsnes_shor_well_b"] if HAS_EIGEN else [])
__all__ += [_rig.__name__ for _rig in RIGS if _rig.__name__ not in __all__]


def __getattr__(name: str):
    # Submodules with heavier imports (pandas, scipy, matplotlib, PyEMD, dask) load on first use: fs.fit, ...
    import importlib

    if name in ("axial", "cli", "contact", "data", "demo", "drillstring", "fit", "io", "plots", "provenance",
                "scenario", "signal", "torsional", "wells"):
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'frictionsim' has no attribute {name!r}")
