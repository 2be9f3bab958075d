// The lumped drill strings of Navarro-Lopez & Cortes (2007) for Python: fs.NavarroLopez2Dof and fs.NavarroLopez4Dof
// (include/frictionsim/rigs/navarro_lopez.hpp). Their bit law is part of their parameter table (no friction
// argument): bind_rig binds them as BoundTableRig (keywords, properties, outputs, help(), repr, pickling and
// _simulate from NavarroLopez*Params::fields()); this file adds their docstrings and their own methods.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>
#include <variant>
#include <vector>

#include <frictionsim/rigs/navarro_lopez.hpp>

#include "rig_binding.hpp"

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

template <class P>
py::object bind_navarro_lopez(py::module_& m, const char* name, const std::string& description) {
    using Bound = BoundTableRig<NavarroLopezRig<P>, P>;
    constexpr std::array<ExtraKeyword<P>, 0> no_extra_keywords{};
    auto cls = bind_rig<Bound>(m, name, description, P::fields(), NoLaw{}, no_extras<Bound>);
    def_table_init(cls, name, P::fields(), no_extra_keywords, [](const P& p) { return Bound(p); });
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
    return std::move(cls);
}

constexpr const char* common_doc = R"doc(
A constant motor torque u drives the rotary table (viscous loss c_r); springs k and dampers d join the inertias;
the bit (last inertia) carries the velocity-weakening friction of NavarroLopezBit with stick, under weight on bit W:

    J_i w_i' = [i = 0] (u - c_r w_0) + S_{i-1} - S_i - T_i,   S_i = k_i (phi_i - phi_{i+1}) + d_i (w_i - w_{i+1})
    T_b = c_b w_b + R_b W mu_b(w_b) sign(w_b),  mu_b = mu_cb + (mu_sb - mu_cb) exp(-gamma_b |w_b| / v_f)   (slip)
    |T_b| <= R_b W mu_sb                                                                           (stick)

Steady states (closed forms): while the bit turns every inertia runs at the root w of steady_balance(w) = 0,
u - (c_r + c_b) w - R_b W mu_b(w) = 0; at rest the bit holds while W >= stuck_weight_threshold = u / (R_b mu_sb).
Switches are located as events (exact stick, or a Karnopp band D_v). States: each inertia's speed [rad/s], each
spring's twist [rad], and motor_work = stored energy change + damping_work + friction_work [J]. The Result's
friction_force is the bit's torque T_b [N m]; the mode is 0 while everything turns forwards, 1 while the bit sticks.
)doc";

}  // namespace

template <>
py::object register_rig<table_rig<NavarroLopez2Dof, NavarroLopez2DofParams>>(py::module_& m) {
    return bind_navarro_lopez<NavarroLopez2DofParams>(
        m, "NavarroLopez2Dof",
        std::string("\nThe 2-DOF drill string of Navarro-Lopez & Suarez (2004), reused by Navarro-Lopez & Cortes "
                    "(2007): rotary table and bit.\n") +
            common_doc + "\nDefaults: the papers' parameter set at u = 6 kN m, W = 30 kN (illustrative).\n\n"
                         "Keywords\n--------\n");
}

template <>
py::object register_rig<table_rig<NavarroLopez4Dof, NavarroLopez4DofParams>>(py::module_& m) {
    return bind_navarro_lopez<NavarroLopez4DofParams>(
        m, "NavarroLopez4Dof",
        std::string("\nThe 4-DOF drill string of Navarro-Lopez & Cortes (2007): rotary table, two pipe inertias, "
                    "bit. With pipe_wall_torque > 0 each pipe inertia also rubs the wellbore (Coulomb, with stick): "
                    "the balance subtracts 2 T_p.\n") +
            common_doc + "\nDefaults: the parameter set of the public code of Navarro-Lopez & Cortes' model.\n\n"
                         "Keywords\n--------\n");
}

}  // namespace frictionsim::python
