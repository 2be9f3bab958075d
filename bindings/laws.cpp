// Friction laws for Python: Coulomb, Stribeck (Karnopp band optional), Dahl, LuGre, elasto-plastic, and the
// cycle-averaged power-law coefficient of paper 000 (eq 17, Table 5). Keyword names follow the papers' symbols
// where Python users read them (mu, mu_static); every law pickles, so rigs can go to process pools and dask workers.
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "common.hpp"

namespace frictionsim::python {

namespace {

constexpr double unset = std::numeric_limits<double>::quiet_NaN();

/// None -> unset (NaN, "equal to mu"); a NaN the caller passed is bad input, not "unset".
double or_unset(const std::optional<double>& v, const char* name) {
    if (!v) return unset;
    if (std::isnan(*v)) throw InvalidParameter(name, std::string("Coulomb: ") + name + " must be finite or None (got nan)");
    return *v;
}

template <class Make>
auto constructing(Make&& make) -> decltype(make()) {
    try {
        return make();
    } catch (const InvalidParameter& e) {
        rethrow_with_python_names(e);
    }
}

std::string format_double(double v) {
    std::ostringstream s;
    s.precision(12);
    s << v;
    return s.str();
}

/// The elasto-plastic law's deflections scale with F_N: Python callers pass it directly, so it is checked here.
double require_normal_force(double normal_force) {
    return detail::require_positive(ElastoPlastic::name, "normal_force", normal_force);
}

/// What LuGre and ElastoPlastic share in Python: the six bristle parameters (properties, repr, pickle) and g(v).
template <class Law>
void def_bristle_parameters(py::class_<Law>& c) {
    c.def_property_readonly("mu", [](const Law& l) { return l.params().coulomb_coefficient; })
        .def_property_readonly("mu_static", [](const Law& l) { return l.params().static_coefficient; })
        .def_property_readonly("stribeck_velocity", [](const Law& l) { return l.params().stribeck_velocity; })
        .def_property_readonly("bristle_stiffness", [](const Law& l) { return l.params().bristle_stiffness; })
        .def_property_readonly("bristle_damping", [](const Law& l) { return l.params().bristle_damping; })
        .def_property_readonly("viscous_damping", [](const Law& l) { return l.params().viscous_damping; })
        .def("stribeck_level", &Law::stribeck_level, py::arg("v_r"), py::arg("normal_force"),
             "Steady sliding level g(v_r) [N] at normal force F_N [N].");
}
template <class Params>
std::string bristle_arguments(const Params& p) {
    return "mu=" + format_double(p.coulomb_coefficient) + ", mu_static=" + format_double(p.static_coefficient) +
           ", stribeck_velocity=" + format_double(p.stribeck_velocity) + ", bristle_stiffness=" +
           format_double(p.bristle_stiffness) + ", bristle_damping=" + format_double(p.bristle_damping) +
           ", viscous_damping=" + format_double(p.viscous_damping);
}
template <class Params>
py::tuple bristle_state(const Params& p) {
    return py::make_tuple(p.coulomb_coefficient, p.static_coefficient, p.stribeck_velocity, p.bristle_stiffness,
                          p.bristle_damping, p.viscous_damping);
}

}  // namespace

void rethrow_with_python_names(const InvalidParameter& e) {
    struct Alias {
        const char* cpp;
        const char* python;
    };
    static constexpr Alias aliases[] = {{"friction_coefficient", "mu"},
                                        {"coulomb_coefficient", "mu"},
                                        {"static_coefficient", "mu_static"}};
    for (const Alias& a : aliases) {
        if (e.parameter() != a.cpp) continue;
        std::string message = e.what();
        const std::string needle = std::string(": ") + a.cpp + " must";
        if (const auto at = message.find(needle); at != std::string::npos)
            message.replace(at, needle.size(), std::string(": ") + a.python + " (" + a.cpp + ") must");
        throw InvalidParameter(a.python, message);
    }
    throw e;
}

FrictionLaw friction_law_from_python(py::handle law, const char* parameter) {
    require_constructed(law);
    if (py::isinstance<Coulomb>(law)) return law.cast<Coulomb>();
    if (py::isinstance<Stribeck>(law)) return law.cast<Stribeck>();
    if (py::isinstance<Dahl>(law)) return law.cast<Dahl>();
    if (py::isinstance<LuGre>(law)) return law.cast<LuGre>();
    if (py::isinstance<ElastoPlastic>(law)) return law.cast<ElastoPlastic>();
    std::string message = std::string(parameter) +
                          " must be a friction law (Coulomb, Stribeck, Dahl, LuGre or ElastoPlastic), got " +
                          std::string(py::str(py::type::of(law).attr("__name__")));
    if (py::isinstance<PowerLawCoefficient>(law))
        message += ": a PowerLawCoefficient is a cycle-averaged coefficient, not an instantaneous law; use "
                   "Coulomb(mu=law.coefficient(v_a, v_d)) for a rig at one velocity ratio";
    throw py::type_error(message);
}

py::object friction_law_to_python(const FrictionLaw& law) {
    return std::visit([](const auto& l) { return py::cast(l); }, law);
}

void register_laws(py::module_& m) {
    py::class_<Coulomb>(m, "Coulomb", R"doc(
Coulomb friction with static and kinetic coefficients (paper 000, eq 8).

Slip: F = mu F_N sgn(v_r). Stick (in rigs with a mass): the contact holds v_r = 0 while the force needed
stays within mu_static F_N (Leine's switch model), located exactly as events.

Parameters
----------
mu : float
    Kinetic (sliding) friction coefficient mu [-], > 0.
mu_static : float, optional
    Static (breakaway) coefficient mu_s [-], >= mu. Default: equal to mu.
)doc")
        .def(py::init([](double mu, std::optional<double> mu_static) {
                 return constructing([&] { return Coulomb(mu, or_unset(mu_static, "mu_static")); });
             }),
             py::arg("mu"), py::arg("mu_static") = py::none())
        .def_property_readonly("mu", &Coulomb::friction_coefficient, "Kinetic coefficient mu [-].")
        .def_property_readonly("mu_static", &Coulomb::static_coefficient, "Static coefficient mu_s [-].")
        .def("__repr__", [](const Coulomb& c) {
            return "Coulomb(mu=" + format_double(c.friction_coefficient()) +
                   ", mu_static=" + format_double(c.static_coefficient()) + ")";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& c = self.cast<const Coulomb&>();
            return reduce_by_construction(self, py::make_tuple(c.friction_coefficient(), c.static_coefficient()));
        });

    py::class_<Stribeck>(m, "Stribeck", R"doc(
Stribeck friction with exact stick, or a Karnopp band (Karnopp 1985).

Slip: F = [mu + (mu_static - mu) exp(-(|v_r|/v_s)^delta)] F_N sgn(v_r) + sigma_v v_r.
Stick holds while the force needed stays within mu_static F_N. With karnopp_band > 0, |v_r| below the band
counts as stick (the band is a located mode of its own).

Parameters
----------
mu : float
    Coulomb (high-speed) coefficient mu_c [-], > 0.
mu_static : float
    Static coefficient mu_s [-], >= mu.
stribeck_velocity : float
    Stribeck velocity v_s [m/s], > 0.
shape_exponent : float
    delta [-], > 0 (2: Gaussian decay, 1: exponential).
viscous_coefficient : float
    Viscous friction sigma_v [N s/m], >= 0.
karnopp_band : float
    Half-width of the Karnopp stick band [m/s], >= 0; 0 means exact stick.
)doc")
        .def(py::init([](double mu, double mu_static, double stribeck_velocity, double shape_exponent,
                         double viscous_coefficient, double karnopp_band) {
                 return constructing([&] {
                     return Stribeck(Stribeck::Params{mu, mu_static, stribeck_velocity, shape_exponent,
                                                      viscous_coefficient, karnopp_band});
                 });
             }),
             py::arg("mu"), py::arg("mu_static"), py::arg("stribeck_velocity"), py::arg("shape_exponent") = 2.0,
             py::arg("viscous_coefficient") = 0.0, py::arg("karnopp_band") = 0.0)
        .def_property_readonly("mu", [](const Stribeck& s) { return s.params().coulomb_coefficient; })
        .def_property_readonly("mu_static", [](const Stribeck& s) { return s.params().static_coefficient; })
        .def_property_readonly("stribeck_velocity", [](const Stribeck& s) { return s.params().stribeck_velocity; })
        .def_property_readonly("shape_exponent", [](const Stribeck& s) { return s.params().shape_exponent; })
        .def_property_readonly("viscous_coefficient",
                               [](const Stribeck& s) { return s.params().viscous_coefficient; })
        .def_property_readonly("karnopp_band", [](const Stribeck& s) { return s.params().karnopp_band; })
        .def("slip_force", &Stribeck::slip_force, py::arg("v_r"), py::arg("normal_force"), py::arg("direction"),
             "Slip force [N] at relative velocity v_r [m/s] on branch direction (+1 or -1).")
        .def("__repr__", [](const Stribeck& s) {
            const auto& p = s.params();
            return "Stribeck(mu=" + format_double(p.coulomb_coefficient) + ", mu_static=" +
                   format_double(p.static_coefficient) + ", stribeck_velocity=" + format_double(p.stribeck_velocity) +
                   ", shape_exponent=" + format_double(p.shape_exponent) + ", viscous_coefficient=" +
                   format_double(p.viscous_coefficient) + ", karnopp_band=" + format_double(p.karnopp_band) + ")";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& p = self.cast<const Stribeck&>().params();
            return reduce_by_construction(self, py::make_tuple(p.coulomb_coefficient, p.static_coefficient,
                                                               p.stribeck_velocity, p.shape_exponent,
                                                               p.viscous_coefficient, p.karnopp_band));
        });

    py::class_<Dahl>(m, "Dahl", R"doc(
Dahl friction (paper 000, eq 9; Dahl 1968): a bristle deflection z with

    dz/dt = v_r sgn(b) |b|^alpha,   b = 1 - k_t z sgn(v_r) / (mu F_N),   F = k_t z.

The force rises with slope k_t from a reversal and saturates at mu F_N. The kink of dz/dt at v_r = 0 is
located as an event. State: dahl_deflection z [m].

Parameters
----------
mu : float
    Friction coefficient mu [-], > 0 (saturation force mu F_N).
tangential_stiffness : float
    Tangential contact stiffness k_t [N/m], > 0 (paper 000 fits 30-40 N/mm for shale on 45 steel, Fig. 10).
exponent : float
    alpha [-], in [0.5, 50] (1 in the paper). Below 0.5 the saturation is reached with an unbounded slope that no
    step-size control resolves in reasonable time.
)doc")
        .def(py::init([](double mu, double k_t, double alpha) {
                 return constructing([&] { return Dahl(mu, k_t, alpha); });
             }),
             py::arg("mu"), py::arg("tangential_stiffness"), py::arg("exponent") = 1.0)
        .def_property_readonly("mu", &Dahl::friction_coefficient, "Friction coefficient mu [-].")
        .def_property_readonly("tangential_stiffness", &Dahl::tangential_stiffness, "k_t [N/m].")
        .def_property_readonly("exponent", &Dahl::exponent, "alpha [-].")
        .def("__repr__", [](const Dahl& d) {
            return "Dahl(mu=" + format_double(d.friction_coefficient()) + ", tangential_stiffness=" +
                   format_double(d.tangential_stiffness()) + ", exponent=" + format_double(d.exponent()) + ")";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& d = self.cast<const Dahl&>();
            return reduce_by_construction(
                self, py::make_tuple(d.friction_coefficient(), d.tangential_stiffness(), d.exponent()));
        });

    py::class_<LuGre> lugre(m, "LuGre", R"doc(
LuGre friction (Canudas de Wit, Olsson, Astrom & Lischinsky 1995):

    dz/dt = v_r - sigma0 |v_r| z / g(v_r),  g(v) = F_N [mu + (mu_static - mu) exp(-(v/v_s)^2)],
    F = sigma0 z + sigma1 dz/dt + sigma2 v_r.

Stiff (bristle dynamics): simulate() picks CVODE BDF for it. State: bristle_deflection z [m].

Parameters
----------
mu, mu_static : float
    Coulomb and static coefficients [-], 0 < mu <= mu_static (Fc = mu F_N, Fs = mu_static F_N).
stribeck_velocity : float
    v_s [m/s], > 0.
bristle_stiffness : float
    sigma0 [N/m], > 0.
bristle_damping : float
    sigma1 [N s/m], >= 0.
viscous_damping : float
    sigma2 [N s/m], >= 0.
)doc");
    lugre
        .def(py::init([](double mu, double mu_static, double v_s, double sigma0, double sigma1, double sigma2) {
                 return constructing([&] { return LuGre(LuGre::Params{mu, mu_static, v_s, sigma0, sigma1, sigma2}); });
             }),
             py::arg("mu"), py::arg("mu_static"), py::arg("stribeck_velocity"), py::arg("bristle_stiffness"),
             py::arg("bristle_damping"), py::arg("viscous_damping") = 0.0)
        .def("__repr__", [](const LuGre& l) { return "LuGre(" + bristle_arguments(l.params()) + ")"; })
        .def("__reduce__", [](py::handle self) {
            return reduce_by_construction(self, bristle_state(self.cast<const LuGre&>().params()));
        });
    def_bristle_parameters(lugre);

    py::class_<ElastoPlastic> elasto_plastic(m, "ElastoPlastic", R"doc(
Elasto-plastic friction (Dupont, Hayward, Armstrong & Altpeter 2002): LuGre with a purely elastic presliding
regime, so that small oscillations below break-away do not drift (LuGre creeps under them):

    dz/dt = v_r (1 - alpha(z, v_r) z / z_ss(v_r)),   z_ss(v) = sgn(v) g(v) / sigma0,
    g(v)  = F_N [mu + (mu_static - mu) exp(-(v/v_s)^2)],
    F     = sigma0 z + sigma1 dz/dt + sigma2 v_r,

    alpha = 0                                            |z| <= z_ba, or sgn(z) != sgn(v_r) (elastic)
          = 1/2 + 1/2 sin(pi (|z| - z_m) / (z_max - z_ba))   z_ba < |z| < z_max,  z_m = (z_max + z_ba) / 2
          = 1                                            |z| >= z_max (LuGre)

with the paper's constants 0 <= z_ba < z_max <= |z_ss(v)|: z_max = mu F_N / sigma0 (the largest that rule allows)
and z_ba = breakaway_fraction z_max. The kink of dz/dt at v_r = 0 is located as an event. Stiff (bristle
dynamics): simulate() picks CVODE BDF for it. State: bristle_deflection z [m].

Parameters
----------
mu, mu_static : float
    Coulomb and static coefficients [-], 0 < mu <= mu_static (Fc = mu F_N, Fs = mu_static F_N).
stribeck_velocity : float
    v_s [m/s], > 0.
bristle_stiffness : float
    sigma0 [N/m], > 0.
bristle_damping : float
    sigma1 [N s/m], >= 0.
viscous_damping : float
    sigma2 [N s/m], >= 0.
breakaway_fraction : float
    z_ba / z_max [-], in [0, 1). 0 starts the plastic ramp at z = 0 (LuGre-like when loading; unloading stays
    elastic).
)doc");
    elasto_plastic
        .def(py::init([](double mu, double mu_static, double v_s, double sigma0, double sigma1, double sigma2,
                         double breakaway_fraction) {
                 return constructing([&] {
                     return ElastoPlastic(
                         ElastoPlastic::Params{{mu, mu_static, v_s, sigma0, sigma1, sigma2}, breakaway_fraction});
                 });
             }),
             py::arg("mu"), py::arg("mu_static"), py::arg("stribeck_velocity"), py::arg("bristle_stiffness"),
             py::arg("bristle_damping"), py::arg("viscous_damping") = 0.0, py::arg("breakaway_fraction") = 0.5)
        .def_property_readonly("breakaway_fraction",
                               [](const ElastoPlastic& l) { return l.params().breakaway_fraction; })
        .def("plastic_deflection", [](const ElastoPlastic& l, double normal_force) {
            return l.plastic_deflection(require_normal_force(normal_force));
        }, py::arg("normal_force"), "z_max = mu F_N / sigma0 [m]: from it on the contact slides as LuGre's.")
        .def("breakaway_deflection", [](const ElastoPlastic& l, double normal_force) {
            return l.breakaway_deflection(require_normal_force(normal_force));
        }, py::arg("normal_force"), "Break-away deflection z_ba [m] at normal force F_N [N]: below it the contact is "
                                    "purely elastic.")
        .def("plasticity_factor", [](const ElastoPlastic& l, double normal_force, double z, int branch) {
            if (branch != 1 && branch != -1)
                throw InvalidParameter("branch", "ElastoPlastic: branch must be +1 or -1 (the sign of v_r), got " +
                                                     std::to_string(branch));
            detail::require_finite(ElastoPlastic::name, "z", z);
            return l.plasticity_factor(require_normal_force(normal_force), z, branch);
        }, py::arg("normal_force"), py::arg("z"), py::arg("branch"),
             "alpha(z) [-] at deflection z [m] and normal force F_N [N], on branch sgn(v_r) (+1 or -1).")
        .def("__repr__", [](const ElastoPlastic& l) {
            return "ElastoPlastic(" + bristle_arguments(l.params()) +
                   ", breakaway_fraction=" + format_double(l.params().breakaway_fraction) + ")";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& p = self.cast<const ElastoPlastic&>().params();
            return reduce_by_construction(self, py::tuple(bristle_state(p) + py::make_tuple(p.breakaway_fraction)));
        });
    def_bristle_parameters(elasto_plastic);

    py::class_<PowerLawCoefficient>(m, "PowerLawCoefficient", R"doc(
Cycle-averaged dynamic friction coefficient of paper 000 (eq 17, Table 5):

    mu_df = eta' (v_a / v_d)^c,   v_a = 2 pi f u0 (eq 16).

Not an instantaneous law: it gives the mean friction force mu_df F_N over whole vibration cycles. Table 5 was
fitted over v_a/v_d of about 160-2564 (Table 4); outside that it extrapolates.

Parameters
----------
eta : float
    eta' [-], in (0, 10] (Table 5: 0.12-1.07).
exponent : float
    c [-], in [-2, 2] (negative: more vibration, less friction; Table 5: -0.09 to -0.37).
)doc")
        .def(py::init([](double eta, double exponent) {
                 return PowerLawCoefficient(PowerLawCoefficient::Params{eta, exponent});
             }),
             py::arg("eta"), py::arg("exponent"))
        .def_static("from_table5", py::overload_cast<std::string_view>(&PowerLawCoefficient::from_table5),
                    py::arg("lubricant"),
                    "Table 5's eta' and c for 'dry', 'water', 'wbm', 'obm' or 'sbm' (case-insensitive).")
        .def_static("from_eq15", &PowerLawCoefficient::from_eq15, py::arg("eta"), py::arg("exponent"),
                    "From eq 15's mu_df = eta (u0 f / v_d)^c: eta' = eta / (2 pi)^c (eq 17).")
        .def_property_readonly("eta", [](const PowerLawCoefficient& p) { return p.params().eta; }, "eta' [-].")
        .def_property_readonly("exponent", [](const PowerLawCoefficient& p) { return p.params().exponent; }, "c [-].")
        .def_readonly_static("fitted_velocity_ratio_min", &PowerLawCoefficient::fitted_velocity_ratio_min)
        .def_readonly_static("fitted_velocity_ratio_max", &PowerLawCoefficient::fitted_velocity_ratio_max)
        .def("coefficient", py::vectorize(&PowerLawCoefficient::coefficient),
             py::arg("vibration_velocity_amplitude"), py::arg("sliding_velocity"),
             "mu_df [-] for v_a [m/s] and v_d [m/s] (arrays broadcast).")
        .def("friction_force", py::vectorize(&PowerLawCoefficient::friction_force), py::arg("normal_force"),
             py::arg("vibration_velocity_amplitude"), py::arg("sliding_velocity"),
             "Mean friction force F_df = mu_df F_N [N] over whole cycles (eq 14).")
        .def("__repr__", [](const PowerLawCoefficient& p) {
            return "PowerLawCoefficient(eta=" + format_double(p.params().eta) +
                   ", exponent=" + format_double(p.params().exponent) + ")";
        })
        .def("__reduce__", [](py::handle self) {
            const auto& p = self.cast<const PowerLawCoefficient&>().params();
            return reduce_by_construction(self, py::make_tuple(p.eta, p.exponent));
        });

    m.def("vibration_velocity_amplitude", py::vectorize(&frictionsim::vibration_velocity_amplitude),
          py::arg("amplitude"), py::arg("frequency"), "v_a = 2 pi f u0 [m/s] (paper 000, eq 16).");
    m.def("table5", [] {
        py::list rows;
        for (const Table5Row& r : table5())
            rows.append(py::dict(py::arg("lubricant") = lubricant_name(r.lubricant), py::arg("eta") = r.eta_prime,
                                 py::arg("exponent") = r.exponent, py::arg("slope") = r.fit_slope,
                                 py::arg("intercept") = r.fit_intercept, py::arg("r_squared") = r.fit_r_squared));
        return rows;
    }, "Paper 000's Table 5 as printed: one dict per lubricant.");
}

}  // namespace frictionsim::python
