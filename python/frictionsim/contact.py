"""Contact mechanics of paper 000 (eqs 1-4): the normal force of a hydraulic oscillator tool (HOT) lying on the low
side of a horizontal wellbore, and the normal force that reproduces its contact stress on the friction rig.

    q_c     = g pi (r_co^2 - r_ci^2) (rho_s - rho_m)                                   (eq 1)
    sigma_d = sqrt(q_c (1/r_co - 1/r_w) / (pi [(1 - mu_r^2)/E_r + (1 - mu_s^2)/E_s]))  (eq 2)
    sigma_e = F_e / (a l)                                                              (eq 3)
    F_e     = a l sigma_d                                                              (eq 4)

All inputs and outputs are SI (the paper prints stresses in MPa and moduli in GPa). The paper calls r_co, r_ci, r_w
"diameters" but eq 1 is an annulus area written with radii: they are radii here. Eq 2 prints (1/r_w - 1/r_co),
negative for a tool inside a larger hole; the positive difference of eq 4 is used.
"""

from __future__ import annotations

from dataclasses import dataclass

from . import _core

__all__ = ["HydraulicOscillatorTool", "rig_contact_stress"]


@dataclass(frozen=True)
class HydraulicOscillatorTool:
    """A HOT in a horizontal wellbore and the rig specimen it is compared with. SI units.

    Invalid combinations (inner radius >= outer radius, a tool that does not fit the hole, a tool lighter than the
    mud, Poisson ratios outside [0, 0.5)) raise ValueError naming the field.
    """

    tool_outer_radius: float  #: r_co [m]
    tool_inner_radius: float  #: r_ci [m], the flow bore
    wellbore_radius: float  #: r_w [m]
    steel_density: float  #: rho_s [kg/m^3]
    mud_density: float  #: rho_m [kg/m^3]
    rock_youngs_modulus: float  #: E_r [Pa]
    rock_poisson_ratio: float  #: mu_r [-]
    steel_youngs_modulus: float  #: E_s [Pa]
    steel_poisson_ratio: float  #: mu_s [-]
    rock_wear_width: float  #: a [m], width of the flat worn on the rock sample (eq 3)
    specimen_width: float  #: l [m], width of the steel specimen (eq 3)
    gravity: float = 9.81  #: g [m/s^2]

    def __post_init__(self) -> None:
        self._params()  # validate now, not at first use

    def _params(self) -> "_core.HydraulicOscillatorParams":
        return _core.HydraulicOscillatorParams(**{f: float(getattr(self, f)) for f in self.__dataclass_fields__})

    def weight_per_length_in_mud(self) -> float:
        """q_c [N/m]: buoyed weight per unit length of the tool (eq 1)."""
        return _core.hot_weight_per_length_in_mud(self._params())

    def contact_stress(self) -> float:
        """sigma_d [Pa]: peak Hertz line-contact stress between the tool and the wellbore rock (eq 2)."""
        return _core.hot_contact_stress(self._params())

    def equivalent_rig_normal_force(self) -> float:
        """F_e [N]: rig normal force with the same contact stress on the worn flat (eq 4)."""
        return _core.equivalent_rig_normal_force(self._params())


def rig_contact_stress(normal_force: float, rock_wear_width: float, specimen_width: float) -> float:
    """sigma_e = F_e / (a l) [Pa]: mean stress on the rig's worn flat (eq 3). F_e [N], a and l [m]."""
    return _core.rig_contact_stress(normal_force, rock_wear_width, specimen_width)
