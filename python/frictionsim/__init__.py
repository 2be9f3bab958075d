"""frictionsim: friction-driven dynamics in drilling.

A C++17 engine (stick-slip located as events, exact restarts, Dormand-Prince 5(4) and SUNDIALS CVODE) with the
friction laws and rigs of paper 000 (axial vibrating-sliding rig, shale on 45 steel); Python adds fitting, signal
processing, plots, sweeps and a command line. SI units throughout.

    >>> import frictionsim as fs
    >>> rig = fs.AxialVibrationRig(friction=fs.Dahl(mu=0.41, tangential_stiffness=4e4))
    >>> result = fs.simulate(rig, 2.0)
    >>> result.mean_over_cycles(transient=1.0)   # mean friction force F_df [N]
"""

from ._core import (
    AxialVibrationRig,
    Coulomb,
    Dahl,
    ElastoPlastic,
    HystereticFriction,
    KinematicRig,
    LuGre,
    PowerLawCoefficient,
    Stribeck,
    TorsionalRig,
    table5,
    vibration_velocity_amplitude,
)
from .errors import AccuracyWarning, BudgetExceededError, ChatteringError, InvalidParameterError, SimulationError
from .result import Event, Result
from .simulation import METHODS, simulate
from .sweeps import SweepResult, sweep

__version__ = "0.1.0"

#: Friction laws a rig can run with.
FRICTION_LAWS = (Coulomb, Stribeck, Dahl, LuGre, ElastoPlastic)

__all__ = [
    "AccuracyWarning",
    "AxialVibrationRig",
    "BudgetExceededError",
    "ChatteringError",
    "Coulomb",
    "Dahl",
    "ElastoPlastic",
    "HystereticFriction",
    "Event",
    "FRICTION_LAWS",
    "InvalidParameterError",
    "KinematicRig",
    "LuGre",
    "METHODS",
    "PowerLawCoefficient",
    "Result",
    "SimulationError",
    "Stribeck",
    "TorsionalRig",
    "simulate",
    "sweep",
    "SweepResult",
    "table5",
    "vibration_velocity_amplitude",
]


def __getattr__(name: str):
    # Submodules with heavier imports (pandas, scipy, matplotlib, PyEMD, dask) load on first use: fs.fit, ...
    import importlib

    if name in ("cli", "contact", "data", "demo", "fit", "plots", "scenario", "signal", "torsional"):
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'frictionsim' has no attribute {name!r}")
