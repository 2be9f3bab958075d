// Friction laws for Python: every law of EngineLaws (include/frictionsim/friction/laws.hpp) through bind_law, its
// law-specific methods, fs.Parameter (what Law.parameters holds), and the cycle-averaged power-law coefficient of
// paper 000 (eq 17, Table 5). Every law pickles, so rigs can go to process pools and dask workers.
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "law_binding.hpp"

namespace frictionsim::python {

std::string format_double(double v) {
    // The shortest text that reads back to the same double: a repr rebuilds its object bit for bit (12 digits
    // turned a rig made from "55 rpm" into another rig, 7532 steps instead of 7535).
    if (v == 0.0 && std::signbit(v)) return "-0.0";  // "-0" would read back as the integer 0
    // Python's repr layout: positional from 1e-4 to 1e16, else scientific; the shortest digits either way
    const double size = std::abs(v);
    const bool positional = v == 0.0 || (size >= 1e-4 && size < 1e16);
    char text[400];
    const std::to_chars_result end = std::to_chars(
        text, text + sizeof text, v, positional ? std::chars_format::fixed : std::chars_format::scientific);
    return std::string(text, end.ptr);
}

namespace {

/// The elasto-plastic law's deflections scale with F_N: Python callers pass it directly, so it is checked here.
double require_normal_force(double normal_force) {
    return detail::require_positive(ElastoPlastic::name, "normal_force", normal_force);
}

/// Methods beyond what bind_law gives every law: only where a law has more to say (its curve, its deflections).
template <class Law>
void def_law_methods(py::class_<Law>&) {}

void def_law_methods(py::class_<Stribeck>& c) {
    c.def("slip_force", &Stribeck::slip_force, py::arg("v_r"), py::arg("normal_force"), py::arg("direction"),
          "Slip force [N] at relative velocity v_r [m/s] on branch direction (+1 or -1).");
}
void def_law_methods(py::class_<LuGre>& c) {
    c.def("stribeck_level", &LuGre::stribeck_level, py::arg("v_r"), py::arg("normal_force"),
          "Steady sliding level g(v_r) [N] at normal force F_N [N].");
}
void def_law_methods(py::class_<ElastoPlastic>& c) {
    c.def("stribeck_level", &ElastoPlastic::stribeck_level, py::arg("v_r"), py::arg("normal_force"),
          "Steady sliding level g(v_r) [N] at normal force F_N [N].")
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
             "alpha(z) [-] at deflection z [m] and normal force F_N [N], on branch sgn(v_r) (+1 or -1).");
}

}  // namespace

std::string engine_law_names(const char* extra) {
    std::vector<std::string> names;
    for_each_type(PythonLaws{}, [&](auto tag) { names.emplace_back(decltype(tag)::type::name); });
    if (extra) names.emplace_back(extra);
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return out;
}

bool is_engine_law(py::handle law) {
    bool found = false;
    for_each_type(PythonLaws{}, [&](auto tag) { found = found || py::isinstance<typename decltype(tag)::type>(law); });
    return found;
}

FrictionLaw friction_law_from_python(py::handle law, const char* parameter) {
    require_constructed(law);
    std::optional<FrictionLaw> out;
    for_each_type(PythonLaws{}, [&](auto tag) {
        using Law = typename decltype(tag)::type;
        if (!out && py::isinstance<Law>(law)) out = law.cast<Law>();
    });
    if (out) return *out;
    std::string message = std::string(parameter) + " must be a friction law (" + engine_law_names() + "), got " +
                          std::string(py::str(py::type::of(law).attr("__name__")));
    if (py::isinstance<PowerLawCoefficient>(law))
        message += ": a PowerLawCoefficient is a cycle-averaged coefficient, not an instantaneous law; use "
                   "Coulomb(mu=law.coefficient(v_a, v_d)) for a rig at one velocity ratio";
    throw py::type_error(message);
}

py::object friction_law_to_python(const FrictionLaw& law) {
    return std::visit([](const auto& l) { return py::cast(l); }, law);
}

namespace {

/// Every field of a Parameter, in declaration order: its pickled state, equality and hash.
py::tuple parameter_state(const ParameterInfo& p) {
    return py::make_tuple(p.name, p.field, p.symbol, p.unit, p.rule, p.doc, p.lower, p.upper, p.lower_open,
                          p.upper_open, p.unset_allowed, p.required, p.at_least, p.default_value, p.example);
}

/// The state as equality and hashing see it: an unset example (NaN, which equals nothing) as None.
py::tuple compared(const ParameterInfo& p) {
    py::list fields(parameter_state(p));
    if (std::isnan(p.example)) fields[fields.size() - 1] = py::none();
    return py::tuple(fields);
}

ParameterInfo parameter_from_state(const py::tuple& state) {
    constexpr std::size_t fields = 15;
    if (state.size() != fields)
        throw InvalidParameter("state", "Parameter.__setstate__: state must be the " + std::to_string(fields) +
                                            " fields a pickled Parameter holds, got " + std::to_string(state.size()));
    try {
        return ParameterInfo{state[0].cast<std::string>(), state[1].cast<std::string>(), state[2].cast<std::string>(),
                             state[3].cast<std::string>(), state[4].cast<std::string>(), state[5].cast<std::string>(),
                             state[6].cast<double>(), state[7].cast<double>(), state[8].cast<bool>(),
                             state[9].cast<bool>(), state[10].cast<bool>(), state[11].cast<bool>(),
                             state[12].cast<std::optional<std::string>>(), state[13].cast<std::optional<double>>(),
                             state[14].cast<double>()};
    } catch (const py::cast_error&) {
        throw InvalidParameter("state", "Parameter.__setstate__: state must hold a pickled Parameter's fields (str, "
                                        "float and bool in their order); a field has another type");
    }
}

}  // namespace

void register_laws(py::module_& m) {
    py::class_<ParameterInfo>(m, "Parameter", R"doc(
One parameter of a law or rig, as its C++ parameter table describes it (Law.parameters holds one per keyword).

name is the constructor keyword (and scenario key), field the C++ member; the rule is lower/upper with open or
closed ends, or at least another parameter (at_least); unset_allowed: None means "not given"; default is None
for a required keyword.
)doc")
        .def_readonly("name", &ParameterInfo::name)
        .def_readonly("field", &ParameterInfo::field)
        .def_readonly("symbol", &ParameterInfo::symbol)
        .def_readonly("unit", &ParameterInfo::unit)
        .def_readonly("rule", &ParameterInfo::rule, "The rule in words, as errors print it.")
        .def_readonly("doc", &ParameterInfo::doc)
        .def_readonly("lower", &ParameterInfo::lower)
        .def_readonly("upper", &ParameterInfo::upper)
        .def_readonly("lower_open", &ParameterInfo::lower_open)
        .def_readonly("upper_open", &ParameterInfo::upper_open)
        .def_readonly("at_least", &ParameterInfo::at_least)
        .def_readonly("unset_allowed", &ParameterInfo::unset_allowed)
        .def_readonly("required", &ParameterInfo::required)
        .def_readonly("default", &ParameterInfo::default_value)
        .def_readonly("example", &ParameterInfo::example,
                      "A typical value (the C++ default), also for a required keyword; NaN where unset.")
        .def("__repr__", [](const ParameterInfo& p) {
            return "Parameter(name='" + p.name + "', symbol='" + p.symbol + "', unit='" + p.unit + "', rule='" +
                   p.rule + "', default=" + (p.default_value ? format_double(*p.default_value) : "None") + ")";
        })
        .def("__eq__", [](const ParameterInfo& a, const py::object& other) -> py::object {
            if (!py::isinstance<ParameterInfo>(other)) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
            return py::bool_(compared(a).equal(compared(other.cast<const ParameterInfo&>())));
        })
        .def("__hash__", [](const ParameterInfo& p) { return py::hash(compared(p)); })
        // A law's parameters cross a process pool with it: pickled as their fields, rebuilt by __setstate__ (no
        // constructor: a Parameter comes from a parameter table).
        .def(py::pickle([](const ParameterInfo& p) { return parameter_state(p); }, &parameter_from_state));

    py::list laws;
    for_each_type(EngineLaws{}, [&](auto tag) {
        using Law = typename decltype(tag)::type;
        auto cls = bind_law<Law>(m);
        def_law_methods(cls);
        laws.append(cls);
    });
    m.attr("FRICTION_LAWS") = py::tuple(laws);

    py::class_<PowerLawCoefficient> power_law(m, "PowerLawCoefficient", R"doc(
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
)doc");
    def_field_properties(power_law, PowerLawCoefficient::fields, [](const PowerLawCoefficient& p) { return p.params(); });
    power_law
        .def(py::init([](double eta, double exponent) {
                 return PowerLawCoefficient(PowerLawCoefficient::Params{eta, exponent});
             }),
             py::arg("eta"), py::arg("exponent"))
        .def_static("from_table5", py::overload_cast<std::string_view>(&PowerLawCoefficient::from_table5),
                    py::arg("lubricant"),
                    "Table 5's eta' and c for 'dry', 'water', 'wbm', 'obm' or 'sbm' (case-insensitive).")
        .def_static("from_eq15", &PowerLawCoefficient::from_eq15, py::arg("eta"), py::arg("exponent"),
                    "From eq 15's mu_df = eta (u0 f / v_d)^c: eta' = eta / (2 pi)^c (eq 17).")
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
