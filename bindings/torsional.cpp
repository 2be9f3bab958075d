// The torsional drill-string rig of paper 001 (eqs 1-6) for Python: the hysteretic velocity-acceleration
// friction law (eq 6), the rig with any law on the disc, pickling, and simulate().
#include <pybind11/numpy.h>
#include <pybind11/stl.h>


#include "rig_binding.hpp"

namespace frictionsim::python {

namespace {

using Polynomial = std::array<double, 6>;

BranchPolynomial to_branch(const Polynomial& c) { return BranchPolynomial{c[0], c[1], c[2], c[3], c[4], c[5]}; }
Polynomial to_tuple(const BranchPolynomial& b) { return {b.c00, b.c10, b.c01, b.c20, b.c11, b.c02}; }

BranchGap branch_gap_from(const std::string& name) {
    if (name == "hold") return BranchGap::hold;
    if (name == "error") return BranchGap::error;
    throw InvalidParameter("branch_gap", "HystereticFriction: branch_gap must be 'hold' or 'error' (got '" + name + "')");
}
const char* branch_gap_name(BranchGap g) { return g == BranchGap::hold ? "hold" : "error"; }

HystereticFriction make_hysteretic(double stick_slope, const Polynomial& accelerating, const Polynomial& decelerating,
                                   double stick_speed, double reference_normal_force, const std::string& branch_gap) {
    HystereticFriction::Params p;
    p.stick_slope = stick_slope;
    p.accelerating = to_branch(accelerating);
    p.decelerating = to_branch(decelerating);
    p.stick_speed = stick_speed;
    p.reference_normal_force = reference_normal_force;
    p.branch_gap = branch_gap_from(branch_gap);
    return HystereticFriction(p);
}


}  // namespace

LawOrHysteretic law_or_hysteretic_from_python(py::handle law, const char* parameter) {
    require_constructed(law);
    if (py::isinstance<HystereticFriction>(law)) return law.cast<HystereticFriction>();
    if (!py::isinstance<PowerLawCoefficient>(law) && is_engine_law(law))
        return std::visit([](auto l) -> LawOrHysteretic { return l; }, friction_law_from_python(law, parameter));
    throw py::type_error(std::string(parameter) + " must be a friction law (" + engine_law_names("HystereticFriction") +
                         "), got " + std::string(py::str(py::type::of(law).attr("__name__"))));
}

py::object law_or_hysteretic_to_python(const LawOrHysteretic& law) {
    return std::visit([](const auto& l) { return py::cast(l); }, law);
}

namespace {

constexpr auto fields = TorsionalRigParams::fields();

using TorsionalDrillStringRig = BoundRig<TorsionalRig, LawsAndHysteretic, TorsionalRigParams>;
constexpr std::array<ExtraKeyword<TorsionalRigParams>, 0> no_extra_keywords{};

/// Applies a rig method to every row of a (rows, states) array, e.g. the shaft torque of a whole Result.
template <class F>
py::array_t<double> per_row(const TorsionalDrillStringRig& r, py::array_t<double, py::array::c_style | py::array::forcecast> states,
                            const py::object& modes, F&& f) {
    const std::size_t n = r.visit([](const auto& s) { return std::decay_t<decltype(s)>::state_size; });
    if (states.ndim() != 2 || static_cast<std::size_t>(states.shape(1)) != n)
        throw InvalidParameter("states", "states must be an array of shape (rows, " + std::to_string(n) + ")");
    const auto rows = static_cast<std::size_t>(states.shape(0));
    std::vector<int> mode(rows, 1);
    if (!modes.is_none()) {
        auto m = modes.cast<py::array_t<int, py::array::c_style | py::array::forcecast>>();
        if (m.ndim() != 1 || static_cast<std::size_t>(m.shape(0)) != rows)
            throw InvalidParameter("mode", "mode must have one entry per row of states");
        for (std::size_t k = 0; k < rows; ++k) mode[k] = m.at(k);
        r.visit([&](const auto& s) {
            for (int md : mode)
                if (std::string(s.mode_name(md)) == "unknown")
                    throw InvalidParameter("mode", "mode must hold the rig's recorded mode codes (got " +
                                                       std::to_string(md) + ")");
        });
    }
    py::array_t<double> out(rows);
    auto o = out.mutable_unchecked<1>();
    const double* x = states.data();
    r.visit([&](const auto& s) {
        for (std::size_t k = 0; k < rows; ++k) o(k) = f(s, x + k * n, mode[k]);
    });
    return out;
}

}  // namespace

template <>
py::object register_rig<law_rig<TorsionalRig, TorsionalRigParams>>(py::module_& m) {
    const HystereticFriction::Params hd;
    py::class_<HystereticFriction> hysteretic(m, "HystereticFriction", R"doc(
Hysteretic velocity-acceleration friction torque of paper 001 (eq 6), in N m on a disc turning at w [rad/s]
with acceleration al [rad/s^2]:

    T = a w                                                      |w| <= w_s  (stick band)
    T = p00 + p10 w + p01 al + p20 w^2 + p11 w al + p02 al^2       |w| >  w_s, al > 0  (accelerating)
    T = n00 + n10 w + n01 al + n20 w^2 + n11 w al + n02 al^2       |w| >  w_s, al < 0  (decelerating)

For w < -w_s the law is extended oddly, T(w, al) = -T(-w, -al). The coefficients hold at
reference_normal_force; a rig's normal force N scales T by N / reference_normal_force. Only the torsional rig
runs it: the torque depends on the acceleration, and the rig solves J al = S - T(w, al) exactly on each branch.

Parameters
----------
stick_slope : float
    a [N m s/rad], > 0; the break-away torque is a w_s.
accelerating, decelerating : sequence of 6 floats
    (p00, p10, p01, p20, p11, p02) and (n00, ..., n02) in SI units (N m, N m s/rad, kg m^2, ...).
stick_speed : float
    w_s [rad/s], > 0 (1e-3 in the paper).
reference_normal_force : float
    N_ref [N], > 0 (35 N in the paper).
branch_gap : {"hold", "error"}
    Where neither branch is consistent (the shaft torque between the decelerating level N0(w) and the
    accelerating level P0(w) at al = 0; eq 6 has no case for it): "hold" keeps al = 0 with the set-valued
    torque in [N0, P0] (Filippov) until the shaft torque leaves the gap; "error" stops the run with a
    SimulationError that names the time, speed and torques.
)doc");
    def_field_properties(hysteretic, HystereticFriction::fields, [](const HystereticFriction& h) { return h.params(); });
    hysteretic
        .def(py::init(&make_hysteretic), py::arg("stick_slope"), py::arg("accelerating"), py::arg("decelerating"),
             py::arg("stick_speed") = hd.stick_speed, py::arg("reference_normal_force") = hd.reference_normal_force,
             py::arg("branch_gap") = "hold")
        .def_property_readonly("accelerating", [](const HystereticFriction& h) { return to_tuple(h.params().accelerating); },
                               "(p00, p10, p01, p20, p11, p02)")
        .def_property_readonly("decelerating", [](const HystereticFriction& h) { return to_tuple(h.params().decelerating); },
                               "(n00, n10, n01, n20, n11, n02)")
        .def_property_readonly("branch_gap", [](const HystereticFriction& h) { return branch_gap_name(h.params().branch_gap); })
        .def("_torque", py::vectorize([](HystereticFriction& h, double w, double al, double normal_force) {
                 return h.torque(w, al, normal_force);
             }))
        .def("_branch_torque", py::vectorize([](HystereticFriction& h, bool accelerating, double w, double al,
                                                double normal_force) { return h.slip_torque(accelerating, w, al, normal_force); }))
        .def("torque", [](py::object self, py::object w, py::object al, py::object normal_force) {
                 if (normal_force.is_none()) normal_force = self.attr("reference_normal_force");
                 return self.attr("_torque")(w, al, normal_force);
             },
             py::arg("w"), py::arg("al"), py::arg("normal_force") = py::none(),
             "Eq 6 [N m] at speed w [rad/s] and acceleration al [rad/s^2], the branch picked by the sign of w al "
             "(al = 0 counts as decelerating), at normal_force [N] (default: the reference normal force, where the "
             "coefficients hold); arrays broadcast.")
        .def("branch_torque", [](py::object self, py::object accelerating, py::object w, py::object al, py::object normal_force) {
                 if (normal_force.is_none()) normal_force = self.attr("reference_normal_force");
                 return self.attr("_branch_torque")(accelerating, w, al, normal_force);
             },
             py::arg("accelerating"), py::arg("w"), py::arg("al"), py::arg("normal_force") = py::none(),
             "One slip branch of eq 6 [N m], whatever the signs (normal_force as in torque()).")
        .def("__repr__", [](const HystereticFriction& h) {
            const auto& p = h.params();
            const auto tuple = [](const BranchPolynomial& b) {
                const Polynomial c = to_tuple(b);
                std::string s = "(";
                for (std::size_t i = 0; i < 6; ++i) s += format_double(c[i]) + (i < 5 ? ", " : ")");
                return s;
            };
            return "HystereticFriction(stick_slope=" + format_double(p.stick_slope) + ", accelerating=" + tuple(p.accelerating) +
                   ", decelerating=" + tuple(p.decelerating) + ", stick_speed=" + format_double(p.stick_speed) +
                   ", reference_normal_force=" + format_double(p.reference_normal_force) + ", branch_gap='" +
                   branch_gap_name(p.branch_gap) + "')";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& p = self.cast<const HystereticFriction&>().params();
            return reduce_by_construction(self, py::make_tuple(p.stick_slope, to_tuple(p.accelerating),
                                                               to_tuple(p.decelerating), p.stick_speed,
                                                               p.reference_normal_force, branch_gap_name(p.branch_gap)));
        });

    m.def("paper001_fig7_friction", [](const std::string& branch_gap) {
        return paper001_fig7_friction(branch_gap_from(branch_gap));
    }, py::arg("branch_gap") = "hold",
          "The eq 6 law chosen to reproduce paper 001's Fig. 7 (0.835 Hz, peak 13.8 rad/s at w_ref = 5.76 rad/s, N2 = 35 N).");

    const std::string description = R"doc(
The torsional drill-string rig of paper 001 (eqs 1-5): disc D2 on a shaft (k2, d2), driven through a gear
eta:1 by a DC motor (L, R, K_T, K_E, T_f, C_m, J_m) under PI speed control of the load-side speed w3, with
friction torque T_f2 on the disc:

    J2 w2'        = S - T_f2,        S = k2 (th3 - th2) + d2 (w3 - w2)
    eta^2 J_m w3' = eta K_T i - eta^2 C_m w3 - eta T_f sgn(w3) - S        (motor friction sticks at w3 = 0)
    L i'          = V - R i - eta K_E w3,    V = k_p (w_ref - w3) + k_i int (w_ref - w3) dt

Defaults: Tables 1-2 at the Fig. 7 operating point (w_ref = 5.76 rad/s, N2 = 35 N). J_m = J3 / eta^2 (Table 1's
J3 read as referred to the load side), k_i = 3.5 (Table 2 misprints its label). SI units; all keywords optional.

friction : a friction law (any class of fs.FRICTION_LAWS) or HystereticFriction
    The engine's laws act at contact_radius r with normal force N2 (v_r = r w2, T_f2 = r F); the
    HystereticFriction of eq 6 acts on w2 and dw2/dt directly, scaled by N2 / its reference normal force.

States: disc_angle th2 [rad], disc_speed w2 [rad/s], shaft_twist th3 - th2 [rad], drive_speed w3 [rad/s],
current i [A], speed_error_integral [rad], the law's states, and the energy integrals [J] motor_work
(int eta K_T i w3 dt), friction_work (int T_f2 w2 dt), damping_work, electrical_work (int V i dt), ohmic_work:
motor_work = stored mechanical energy change + friction_work + damping_work. The Result's friction_force is
T_f2 [N m]; its mode is the disc's (minus 16 while the motor sticks, minus 32 while it turns backwards).

Keywords
--------
)doc";
    auto cls = bind_rig<TorsionalDrillStringRig>(m, "TorsionalRig", description, fields, law_or_hysteretic_to_python,
                                                 [](const TorsionalDrillStringRig&) { return py::dict(); });
    def_table_init(cls, "TorsionalRig", fields, no_extra_keywords, [](py::handle friction, const TorsionalRigParams& p) {
        return TorsionalDrillStringRig(law_or_hysteretic_from_python(friction, "friction"), p);
    });
    cls.def_property_readonly("period", [](const TorsionalDrillStringRig&) { return py::none(); },
                               "None: the rig has no imposed period (its stick-slip period is an outcome).")
        .def_property_readonly("natural_frequency",
                               [](const TorsionalDrillStringRig& r) { return r.visit([](const auto& s) { return s.natural_frequency(); }); },
                               "sqrt(k2 / J2) / 2 pi [Hz]: the disc on a rigidly held shaft end.")
        .def("shaft_torque", [](const TorsionalDrillStringRig& r, py::array_t<double, py::array::c_style | py::array::forcecast> states) {
                 return per_row(r, states, py::none(), [](const auto& s, const double* x, int) { return s.shaft_torque(x); });
             },
             py::arg("states"), "S = k2 (th3 - th2) + d2 (w3 - w2) [N m] for each row of a (rows, states) array.")
        .def("voltage", [](const TorsionalDrillStringRig& r, py::array_t<double, py::array::c_style | py::array::forcecast> states) {
                 return per_row(r, states, py::none(), [](const auto& s, const double* x, int) { return s.voltage(x); });
             },
             py::arg("states"), "PI output V [V] (eq 3) for each row.")
        .def("stored_mechanical_energy", [](const TorsionalDrillStringRig& r, py::array_t<double, py::array::c_style | py::array::forcecast> states) {
                 return per_row(r, states, py::none(), [](const auto& s, const double* x, int) { return s.stored_mechanical_energy(x); });
             },
             py::arg("states"), "J2 w2^2 / 2 + eta^2 J_m w3^2 / 2 + k2 (th3 - th2)^2 / 2 [J] for each row.")
        .def("disc_acceleration", [](const TorsionalDrillStringRig& r, py::array_t<double, py::array::c_style | py::array::forcecast> states,
                                     py::object mode) {
                 return per_row(r, states, mode, [](const auto& s, const double* x, int md) { return s.disc_acceleration(x, md); });
             },
             py::arg("states"), py::arg("mode"), "dw2/dt [rad/s^2] for each row in its recorded mode.");
    return std::move(cls);
}

}  // namespace frictionsim::python
