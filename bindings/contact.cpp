// Contact mechanics of paper 000 (eqs 1-4) for Python: the hydraulic oscillator tool's normal force downhole
// and the equivalent normal force on the friction rig. Wrapped by frictionsim.contact.
#include <pybind11/stl.h>

#include "common.hpp"

namespace frictionsim::python {

void register_contact(py::module_& m) {
    using P = HydraulicOscillatorParams;
    py::class_<P>(m, "HydraulicOscillatorParams", "Geometry and materials of paper 000 eqs 1-4, SI units.")
        .def(py::init([](double r_co, double r_ci, double r_w, double rho_s, double rho_m, double e_r, double nu_r,
                         double e_s, double nu_s, double a, double l, double g) {
                 P p{r_co, r_ci, r_w, rho_s, rho_m, e_r, nu_r, e_s, nu_s, a, l, g};
                 p.validate();
                 return p;
             }),
             py::kw_only(), py::arg("tool_outer_radius"), py::arg("tool_inner_radius"), py::arg("wellbore_radius"),
             py::arg("steel_density"), py::arg("mud_density"), py::arg("rock_youngs_modulus"),
             py::arg("rock_poisson_ratio"), py::arg("steel_youngs_modulus"), py::arg("steel_poisson_ratio"),
             py::arg("rock_wear_width"), py::arg("specimen_width"), py::arg("gravity") = 9.81)
        .def_readonly("tool_outer_radius", &P::tool_outer_radius)
        .def_readonly("tool_inner_radius", &P::tool_inner_radius)
        .def_readonly("wellbore_radius", &P::wellbore_radius)
        .def_readonly("steel_density", &P::steel_density)
        .def_readonly("mud_density", &P::mud_density)
        .def_readonly("rock_youngs_modulus", &P::rock_youngs_modulus)
        .def_readonly("rock_poisson_ratio", &P::rock_poisson_ratio)
        .def_readonly("steel_youngs_modulus", &P::steel_youngs_modulus)
        .def_readonly("steel_poisson_ratio", &P::steel_poisson_ratio)
        .def_readonly("rock_wear_width", &P::rock_wear_width)
        .def_readonly("specimen_width", &P::specimen_width)
        .def_readonly("gravity", &P::gravity);
    m.def("hot_weight_per_length_in_mud", &hot_weight_per_length_in_mud, py::arg("params"));
    m.def("hot_relative_curvature", &hot_relative_curvature, py::arg("params"));
    m.def("rock_steel_contact_compliance", &rock_steel_contact_compliance, py::arg("params"));
    m.def("hot_contact_stress", &hot_contact_stress, py::arg("params"));
    m.def("rig_contact_stress", &rig_contact_stress, py::arg("normal_force"), py::arg("rock_wear_width"),
          py::arg("specimen_width"));
    m.def("equivalent_rig_normal_force", &equivalent_rig_normal_force, py::arg("params"));
}

}  // namespace frictionsim::python
