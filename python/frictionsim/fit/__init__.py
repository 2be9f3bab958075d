from .power_law import PowerLawFit, fit_power_law
