from .power_law import PowerLawFit, fit_power_law
from .identify import IdentificationResult, identify, identify_dahl, identify_lugre, identify_stribeck
from .rig import identify_axial_rig
