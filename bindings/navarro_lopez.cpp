// The lumped drill strings of Navarro-Lopez & Cortes (2007) for Python: fs.NavarroLopez2Dof and fs.NavarroLopez4Dof
// (include/frictionsim/rigs/navarro_lopez.hpp). Their bit law is part of their parameter table (no friction
// argument): register_rig binds them from their tables alone, as any rig built from its table (keywords,
// properties, outputs, help() from Params::description, repr, pickling and _simulate from NavarroLopez*Params);
// this file adds only their own methods (def_rig_methods: the bit, the inertias, the steady-state closed forms).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>
#include <variant>
#include <vector>

#include <frictionsim/rigs/navarro_lopez.hpp>

#include "rig_binding.hpp"
#include "string_binding.hpp"

namespace frictionsim::python {

namespace {

/// u - (c_r + c_b) w - R_b W mu_b(w) - (sum of the pipe wall torques) [N m]: the steady balance with every inertia
/// at speed w > 0 (the sum of all equations); its root is the steady bit speed.
template <class P>
double steady_balance(const NavarroLopezRig<P>& rig, double w) {
    const P& p = rig.params();
    double walls = 0.0;
    for (std::size_t i = 0; i + 1 < P::dof; ++i)
        if (rig.has_contact(i)) walls += rig.static_limit(i);
    return p.motor_torque - p.table_damping * w - rig.bit_law().torque(w, p.weight_on_bit, +1) - walls;
}

/// The strings' own members beside what register_rig binds from their tables.
template <class P, class Class>
void def_navarro_lopez_methods(Class& cls) {
    using Bound = BoundTableRig<NavarroLopezRig<P>, P>;
    cls.def_property_readonly("period", [](const Bound&) { return py::none(); },
                              "None: the string has no imposed period (its stick-slip period is an outcome).")
        .def_property_readonly("bit", [](const Bound& r) { return r.model().bit_law(); },
                               "The bit's law (NavarroLopezBit) built from this table's bit fields.")
        .def_property_readonly("inertias", [](const Bound& r) {
            const auto& J = r.model().inertias();
            return std::vector<double>(J.begin(), J.end());
        }, "J of each inertia, rotary table first, bit last [kg m^2].")
        .def_property_readonly("stuck_weight_threshold", [](const Bound& r) {
            const P& p = r.params;
            return p.motor_torque / (p.bit_radius * p.static_coefficient);
        }, "u / (R_b mu_sb) [N]: at or above this weight on bit a stuck string stays stuck (the bit holds u).")
        .def("steady_balance", py::vectorize([](Bound& r, double w) { return steady_balance(r.model(), w); }),
             py::arg("speed"),
             "u - (c_r + c_b) w - R_b W mu_b(w) - sum T_p [N m] at a common speed w > 0 [rad/s] (arrays broadcast): "
             "the sum of all equations with every inertia at w; its root is the steady speed while the bit turns.");
}

}  // namespace

template <>
void def_rig_methods<table_rig<NavarroLopez2Dof, NavarroLopez2DofParams>>(
    TableRigClass<table_rig<NavarroLopez2Dof, NavarroLopez2DofParams>>& cls) {
    def_navarro_lopez_methods<NavarroLopez2DofParams>(cls);
}

template <>
void def_rig_methods<table_rig<NavarroLopez4Dof, NavarroLopez4DofParams>>(
    TableRigClass<table_rig<NavarroLopez4Dof, NavarroLopez4DofParams>>& cls) {
    def_navarro_lopez_methods<NavarroLopez4DofParams>(cls);
}

}  // namespace frictionsim::python
