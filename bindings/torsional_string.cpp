// The Aarsnes-Shor torsional string for Python (include/frictionsim/string/torsional_string.hpp): fs.TorsionalString,
// the one string model (string/string_model.hpp's StringModel): a lumped string whose wall contacts are captured by
// Moreau-Jean time-stepping (no event per switch), the bit on bottom captured with them or its switches located
// exactly ("mixed"), or every switch located on the event-driven StringRig ("exact"); "auto" by the measured rule;
// the same Result columns under every treatment; the closed forms of A&S sec. 4;
// the Well B preset fs.aarsnes_shor_well_b. Its entry of EngineRigs (time_stepping_rig) and this binding need Eigen
// (FRICTIONSIM_EIGEN): without it the list has no such entry and nothing is registered.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rig_binding.hpp"

#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN
#include <frictionsim/solve/time_stepping.hpp>
#include <frictionsim/string/string_model.hpp>
#include <frictionsim/string/torsional_string.hpp>

#include "simulation.hpp"
#include "string_binding.hpp"
#endif

namespace frictionsim::python {

#if defined(FRICTIONSIM_EIGEN) && FRICTIONSIM_EIGEN

namespace {

constexpr const char* name = "TorsionalString";
constexpr auto fields = TorsionalStringParams::fields();
/// More elements than any string needs (a 6 km string at 1 m): a guard against a typo allocating gigabytes.
constexpr long max_elements = 100000;
constexpr long default_elements = 200;
constexpr double default_switch_tolerance = 1e-10;

/// The treatment as given: one of StringTreatment's, or none for "auto" (the measured rule, resolved once the
/// string is lumped).
using GivenTreatment = std::optional<StringTreatment>;

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")); }

GivenTreatment treatment_from(py::handle value) {
    const std::string s = py::isinstance<py::str>(value) ? value.cast<std::string>() : std::string();
    if (s == "auto") return std::nullopt;
    for (StringTreatment t : {StringTreatment::captured, StringTreatment::mixed, StringTreatment::exact})
        if (s == treatment_name(t)) return t;
    throw InvalidParameter("treatment", std::string(name) + ": treatment must be 'captured', 'mixed', 'exact' or "
                                            "'auto' (got " + std::string(py::repr(value)) + ")");
}

double real_from(py::handle value, const char* keyword) {
    if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) || !py::hasattr(value, "__float__"))
        throw py::type_error(std::string(name) + ": " + keyword + " must be a number (got " + type_name(value) + ")");
    return value.attr("__float__")().cast<double>();
}

std::vector<double> reals_from(py::handle value, const char* keyword) {
    if (py::isinstance<py::str>(value) || !py::hasattr(value, "__iter__"))
        throw py::type_error(std::string(name) + ": " + keyword + " must be a sequence of numbers (got " +
                             type_name(value) + ")");
    std::vector<double> out;
    for (py::handle x : value) {
        if (py::isinstance<py::bool_>(x) || py::isinstance<py::str>(x) || !py::hasattr(x, "__float__"))
            throw py::type_error(std::string(name) + ": " + keyword + " must hold numbers (got " + type_name(x) + ")");
        out.push_back(x.attr("__float__")().cast<double>());
    }
    return out;
}

/// The survey as given: an fs.Survey (the one survey type; its azimuths count), or (measured_depth, inclination)
/// [m, rad] (or anything with those attributes), a well in one vertical plane. Kept as given for repr and pickling.
struct GivenSurvey {
    std::optional<Survey> survey;           ///< none: the straight well of params.inclination
    bool as_pair = false;
    std::vector<double> measured_depth, inclination;  ///< the pair as given

    /// The pair as a Survey (azimuth 0): one station is the straight well of that inclination.
    static GivenSurvey from_pair(std::vector<double> md, std::vector<double> inc) {
        GivenSurvey g;
        g.as_pair = true;
        if (inc.size() != md.size())
            detail::reject(name, "survey.inclination", "one per survey.measured_depth (count given)",
                           static_cast<double>(inc.size()));
        g.measured_depth = md;
        g.inclination = inc;
        if (md.empty()) return g;
        std::vector<SurveyStation> stations;
        for (std::size_t i = 0; i < md.size(); ++i) {
            if (!(inc[i] >= 0.0 && inc[i] <= pi)) detail::reject(name, "survey.inclination", "in [0, pi] rad", inc[i]);
            stations.push_back(SurveyStation{md[i], inc[i], 0.0});
        }
        if (stations.size() == 1) stations.push_back(SurveyStation{md[0] + 1.0, inc[0], 0.0});
        try {
            g.survey = Survey(std::move(stations));
        } catch (const InvalidParameter& e) {  // name the keyword as the user wrote it
            throw InvalidParameter("survey." + e.parameter(), std::string(name) + ": survey: " + e.what());
        }
        return g;
    }
};

GivenSurvey survey_from(py::handle value) {
    require_constructed(value);  // a bare Survey would be cast to an uninitialised one
    if (py::isinstance<Survey>(value)) {
        GivenSurvey g;
        g.survey = value.cast<Survey>();
        return g;
    }
    if (py::hasattr(value, "measured_depth") && py::hasattr(value, "inclination"))
        return GivenSurvey::from_pair(reals_from(value.attr("measured_depth"), "survey.measured_depth"),
                                      reals_from(value.attr("inclination"), "survey.inclination"));
    if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value) || py::len(value) != 2)
        throw py::type_error(std::string(name) + ": survey must be (measured_depth, inclination) [m, rad] or an "
                                                 "fs.Survey (got " + type_name(value) + ")");
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(value);
    return GivenSurvey::from_pair(reals_from(pair[0], "survey.measured_depth"),
                                  reals_from(pair[1], "survey.inclination"));
}

template <class T>
py::array_t<T> to_array(const std::vector<T>& v) {
    return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

/// The Python TorsionalString: what it was built from (properties, repr, pickling) and the C++ string.
struct BoundTorsionalString {
    DrillString string;
    TorsionalStringParams params;
    std::size_t elements;
    GivenSurvey survey;
    std::optional<std::vector<double>> radius;  ///< as given; none: each section's OD / 2
    std::optional<NavarroLopezBit> bit;         ///< as given; none: the default NavarroLopezBit
    StringTreatment treatment;                  ///< "auto" resolved by the measured rule
    TopDrive drive;
    double slow_speed, switch_tolerance;
    TorsionalString model;              ///< the description (its properties and closed forms)
    std::optional<StringModel> treated;  ///< what a run runs: the description under its treatment

    BoundTorsionalString(DrillString s, const TorsionalStringParams& p, std::size_t n, GivenSurvey sv,
                         std::optional<std::vector<double>> r, std::optional<NavarroLopezBit> b, GivenTreatment t,
                         TopDrive d, double slow, double tolerance)
        : string(std::move(s)), params(p), elements(n), survey(std::move(sv)), radius(std::move(r)), bit(std::move(b)),
          treatment(t.value_or(StringTreatment::captured)), drive(d), slow_speed(slow), switch_tolerance(tolerance),
          model(checked(string, survey.survey, t, params, elements), params, elements, survey.survey,
                radius.value_or(std::vector<double>{}), bit.value_or(NavarroLopezBit{})) {
        model.set_slow_speed(slow);
        model.set_top_drive(d);
        if (!t) treatment = automatic_treatment(model.contact_count(), model.bit_on_bottom());
        treated.emplace(model, treatment, tolerance);  // refuses what the treatment cannot carry, naming it
        model.set_bit_treatment(treatment == StringTreatment::mixed ? BitTreatment::exact : BitTreatment::captured,
                                tolerance);
    }

private:
    /// What the C++ constructor does not check: a survey that ends above the bit, a treatment without a bit.
    static const DrillString& checked(const DrillString& s, const std::optional<Survey>& survey, GivenTreatment t,
                                      const TorsionalStringParams& p, std::size_t) {
        if (survey && survey->last_depth() < s.length()) {
            const std::string rule = "reaching the bit (its last measured depth >= the string's length, " +
                                     format_double(s.length()) + " m; last given)";
            detail::reject(name, "survey", rule.c_str(), survey->last_depth());
        }
        if (t == StringTreatment::mixed && !(p.weight_on_bit > 0.0))
            throw InvalidParameter("treatment", std::string(name) + ": treatment 'mixed' locates the bit's stick "
                                                "and slip, and this string's bit is off bottom (weight_on_bit = 0): "
                                                "use 'captured', or put the bit on bottom");
        return s;
    }
};

py::object survey_to_python(const GivenSurvey& s) {
    if (!s.as_pair) return s.survey ? py::cast(*s.survey) : py::object(py::none());
    if (s.measured_depth.empty()) return py::none();
    return py::make_tuple(py::cast(s.measured_depth), py::cast(s.inclination));
}

/// The keywords outside the table, as the constructor takes them back (pickling, repr).
py::dict extras_of(const BoundTorsionalString& r) {
    py::dict d;
    d["elements"] = r.elements;
    d["survey"] = survey_to_python(r.survey);
    d["contact_radius"] = r.radius ? py::cast(*r.radius) : py::object(py::none());
    d["bit"] = r.bit ? py::cast(*r.bit) : py::object(py::none());
    d["treatment"] = treatment_name(r.treatment);
    d["top_drive"] = top_drive_name(r.drive);
    d["slow_speed"] = r.slow_speed;
    d["switch_tolerance"] = r.switch_tolerance;
    return d;
}

BoundTorsionalString make(py::handle string, const py::kwargs& kwargs) {
    if (!py::isinstance<DrillString>(string))
        throw py::type_error(std::string(name) + ": string must be a DrillString (got " + type_name(string) + ")");
    TorsionalStringParams p{};
    std::size_t used = read_field_keywords(p, kwargs, fields, name);
    long elements = default_elements;
    GivenSurvey survey;
    std::optional<std::vector<double>> radius;
    std::optional<NavarroLopezBit> bit;
    GivenTreatment treatment = StringTreatment::captured;
    TopDrive drive = TopDrive::pi_motor;
    double slow_speed = 0.0, switch_tolerance = default_switch_tolerance;
    const auto given = [&](const char* key) {
        const bool present = kwargs.contains(key) && !kwargs[key].is_none();
        used += kwargs.contains(key) ? 1 : 0;
        return present;
    };
    if (given("elements"))
        elements = static_cast<long>(whole_number_from(kwargs["elements"], "elements", name, 1, max_elements));
    if (given("survey")) survey = survey_from(kwargs["survey"]);
    if (given("contact_radius")) radius = reals_from(kwargs["contact_radius"], "contact_radius");
    if (given("bit")) {
        const py::handle b = kwargs["bit"];
        if (!py::isinstance<NavarroLopezBit>(b))
            throw py::type_error(std::string(name) + ": bit must be a NavarroLopezBit or None (got " + type_name(b) +
                                 ")");
        bit = b.cast<NavarroLopezBit>();
    }
    if (given("treatment")) treatment = treatment_from(kwargs["treatment"]);
    if (given("top_drive")) drive = top_drive_from(kwargs["top_drive"], name);
    if (given("slow_speed")) slow_speed = real_from(kwargs["slow_speed"], "slow_speed");
    if (given("switch_tolerance")) switch_tolerance = real_from(kwargs["switch_tolerance"], "switch_tolerance");
    if (used != kwargs.size())
        for (auto item : kwargs) {
            const std::string key = py::str(item.first);
            bool known = key == "elements" || key == "survey" || key == "contact_radius" || key == "bit" ||
                         key == "treatment" || key == "top_drive" || key == "slow_speed" ||
                         key == "switch_tolerance";
            for (const Field<TorsionalStringParams>& f : fields) known = known || key == f.public_name();
            if (!known)
                throw py::type_error(std::string(name) + "() got an unexpected keyword argument '" + key + "'");
        }
    return BoundTorsionalString(string.cast<DrillString>(), p, static_cast<std::size_t>(elements), std::move(survey),
                                std::move(radius), std::move(bit), treatment, drive, slow_speed, switch_tolerance);
}

/// simulate_variant's run for the string model: the GIL released, Ctrl-C polled between steps; the exact treatment
/// on the integrators this extension has (simulate_built_in).
/// The work is estimated first (string_binding.hpp): the time-stepping treatments' fixed steps over the nodes, the
/// exact treatment's StringRig by its explicit methods' stability bound. This thread's stop flag is polled beside
/// Ctrl-C.
std::shared_ptr<Result> run_string(const BoundTorsionalString& r, double t_end, const SolverOptions& options, double t_start) {
    SolverOptions polled = options;
    polled.interrupt = string_run_interrupt();
    const double span = t_end - t_start;
    const bool time_stepping = is_time_stepping_method(options.method) ||
                               (options.method == Method::automatic && r.treatment != StringTreatment::exact);
    if (time_stepping && span > 0.0 && std::isfinite(span) && options.step > 0.0)
        check_run_work(name, span / options.step, 2.0 * static_cast<double>(r.model.nodes()), span,
                       "the fixed steps (t_end - t_start) / step over the nodes' angles and speeds");
    try {
        py::gil_scoped_release release;
        return std::make_shared<Result>(r.treated->run(
            t_end, polled, t_start, [](const auto& rig, double end, const SolverOptions& o, double start) {
                check_string_rig_work(name, rig, end, start, o);  // the exact treatment's StringRig
                return simulate_built_in(rig, end, o, start);
            }));
    } catch (const Interrupted&) {
        raise_pending_python_error();
    }
}

const char* description = R"doc(
The torsional drill string of Aarsnes & Shor (2018, J. Pet. Sci. Eng. 163, 712-721; "A&S") with hundreds of wall
contacts, stepped by Moreau-Jean time-stepping: the contacts' stick and slip are captured by each step's inclusion
(no event per switch), which is what a field-resolution string needs (fs.StringRig locates every switch as an
event and drowns in them at a thousand contacts).

    string:    N elements of the DrillString (lump(N)); viscous damping k_t J omega per node (A&S eq 3)
    wall:      at each node a Coulomb contact of static bound int F_c dx over its half elements,
               F_c(x) = mu sin(inc(x)) g rho A (1 - rho_mud / rho) r_o (A&S eq 6), kinetic f_rat times it; below
               omega_c a slipping node keeps the static level (A&S eq 4)
    top drive: I_TD at node 0 under the PI tau_m = k_p e + k_i int e, e = omega_SP - omega_TD (A&S eqs 7-10),
               continuous or sampled every control_period (zero-order hold, as A&S's code); with torque_limit
               T_max > 0 clamped to +-T_max, the integral frozen while limited (StringRig's PI drive; implicit:
               each step taken linear or at the limit and checked at its end, no step restriction); or
               top_drive="prescribed_speed": node 0 turns at omega_SP(t), motor_torque what that takes
    bit:       off bottom (weight_on_bit = 0): the bit torque T_b; on bottom: the velocity-weakening bit (a
               NavarroLopezBit under weight_on_bit) merged with node N's wall contact

Closed forms of A&S sec. 4 (properties): breakoff_torque (eq 27), minimum_torque (eq 30), top_drive_twist (eq 29
at x = 0), build_up_time (eq 34), fundamental_period (the continuous string's lowest mode, top held) and
period_estimate (eq 40). fs.aarsnes_shor_well_b builds A&S's Well B.

Parameters
----------
string : DrillString
elements : int = 200
    N >= 1: N + 1 nodes.
survey : (measured_depth, inclination) or Survey, optional
    The well's inclination at each measured depth (Survey.inclination_at): an fs.Survey (minimum curvature, its
    azimuths count), or (measured_depth [m], inclination [rad]), a well in one vertical plane, linear in between.
    It must reach the bit. Default: a straight well of `inclination`.
contact_radius : sequence of float, optional
    r_o per section [m]; default each section's OD / 2.
bit : NavarroLopezBit, optional
    The on-bottom bit's law (used when weight_on_bit > 0); default NavarroLopezBit().
treatment : {"captured", "mixed", "exact", "auto"}
    "captured": every contact, the bit's too, captured by the time-stepping (method "moreau_jean" or
    "explicit_projection", its "automatic"); "mixed": the bit's stick and slip located exactly (a lumped switch of
    the run, restarted there), the walls captured; needs the bit on bottom and no torque_limit; "exact": every
    contact's stick and slip located as an event on the event-driven StringRig of the same string (any
    event-driven method; no stick band, bit_torque off bottom, or wall at node 0: vertical at the top); "auto":
    the measured rule (fs.automatic_treatment: exact up to 30 wall contacts, mixed up to 300 on bottom, captured
    beyond). The Result has the same columns under every treatment; under "exact" its events are every located
    switch (the time-stepping logs the bit's), and a stop condition reads bit_speed or top_drive_speed.
top_drive : {"pi_motor", "prescribed_speed"}
    As fs.StringRig's: the PI motor (torque_limit: its limit, 0 none), or node 0 held at the set-point speed
    (no controller: control_period and torque_limit must be 0).

Keywords
--------
)doc";

}  // namespace

template <>
py::object register_rig<time_stepping_rig<TorsionalString, TorsionalStringParams>>(py::module_& m) {
    py::class_<BoundTorsionalString> cls(m, name, kept(std::string(description) + keywords_doc(fields)));
    def_field_properties(cls, fields, [](const BoundTorsionalString& r) -> const TorsionalStringParams& {
        return r.params;
    });
    def_outputs(cls, TorsionalStringParams::outputs());
    const TorsionalStringParams defaults{};
    std::string signature = "__init__(self, string: DrillString, *";
    for (const Field<TorsionalStringParams>& f : fields)
        signature += ", " + std::string(f.public_name()) + ": float = " + format_double(defaults.*(f.member));
    signature += ", elements: int = " + std::to_string(default_elements) +
                 ", survey: object | None = None, contact_radius: collections.abc.Sequence[float] | None = None, "
                 "bit: NavarroLopezBit | None = None, treatment: str = 'captured', top_drive: str = 'pi_motor', "
                 "slow_speed: float = 0.0, "
                 "switch_tolerance: float = " + format_double(default_switch_tolerance) + ") -> None\n\n"
                 "The string, then the set-up and the parameters by keyword (see the class docstring).\n";
    py::options options;
    options.disable_function_signatures();
    cls.def(py::init([](py::handle string, const py::kwargs& kwargs) { return make(string, kwargs); }),
            kept(std::move(signature)), py::arg("string"));
    options.enable_function_signatures();
    cls.def_property_readonly("string", [](const BoundTorsionalString& r) { return r.string; }, "The DrillString.")
        .def_property_readonly("elements", [](const BoundTorsionalString& r) { return r.elements; }, "N.")
        .def_property_readonly("nodes", [](const BoundTorsionalString& r) { return r.model.nodes(); }, "N + 1.")
        .def_property_readonly("contact_count", [](const BoundTorsionalString& r) { return r.model.contact_count(); },
                               "Wall contacts (nodes with a static bound > 0; on bottom node N's is the bit's): what "
                               "a run's Result.mode counts at rest, as a StringRig's does.")
        .def_property_readonly("contact_nodes",
                               [](const BoundTorsionalString& r) { return r.model.wall_contact_nodes(); },
                               "The nodes of the wall contacts, top down (a StringRig's contact_nodes).")
        .def_property_readonly("survey", [](const BoundTorsionalString& r) { return survey_to_python(r.survey); },
                               "(measured_depth [m], inclination [rad]) as given, or None (a straight well).")
        .def_property_readonly("contact_radius",
                               [](const BoundTorsionalString& r) {
                                   if (r.radius) return to_array(*r.radius);
                                   std::vector<double> out;
                                   for (const PipeSection& s : r.string.sections()) out.push_back(s.outer_diameter / 2.0);
                                   return to_array(out);
                               },
                               "r_o of each section [m].")
        .def_property_readonly("bit", [](const BoundTorsionalString& r) { return r.model.bit_law(); },
                               "The on-bottom bit's law (NavarroLopezBit).")
        .def_property_readonly("treatment", [](const BoundTorsionalString& r) { return treatment_name(r.treatment); })
        .def_property_readonly("top_drive", [](const BoundTorsionalString& r) { return top_drive_name(r.drive); },
                               "'pi_motor' or 'prescribed_speed' (StringRig's top_drive).")
        .def_property_readonly("bit_on_bottom", [](const BoundTorsionalString& r) { return r.model.bit_on_bottom(); })
        .def_property_readonly("period", [](const BoundTorsionalString&) { return py::none(); },
                               "None: the string has no imposed period (its stick-slip period is an outcome).")
        .def_property_readonly("element_length", [](const BoundTorsionalString& r) { return r.model.lumped().element_length; },
                               "dx = L / N [m].")
        .def_property_readonly("node_inertia",
                               [](const BoundTorsionalString& r) { return to_array(r.model.lumped().node_inertia); },
                               "The string's inertia at each node [kg m^2] (without I_TD and J_BHA).")
        .def_property_readonly("static_friction_torque",
                               [](const BoundTorsionalString& r) { return to_array(r.model.static_friction_torque()); },
                               "Static bound of each node's wall contact [N m] (they add up to breakoff_torque).")
        .def_property_readonly("bit_static_torque", [](const BoundTorsionalString& r) { return r.model.bit_static_torque(); },
                               "Node N's static bound with the bit on bottom [N m]: its wall's plus R_b W mu_sb.")
        .def("wall_friction_per_length",
             py::vectorize([](BoundTorsionalString& r, double x) { return r.model.wall_friction_per_length(x); }),
             py::arg("measured_depth"), "F_c(x) of A&S eq 6 [N m/m] at measured depth x [m] (arrays broadcast).")
        .def_property_readonly("breakoff_torque", [](const BoundTorsionalString& r) { return r.model.breakoff_torque(); },
                               "A&S eq 27: int_0^L F_c dx [N m], the torque the top drive must reach to free the bit.")
        .def_property_readonly("minimum_torque", [](const BoundTorsionalString& r) { return r.model.minimum_torque(); },
                               "A&S eq 30: breakoff_torque (1 - 2 (1 - f_rat)) [N m], the cycle's minimum motor torque.")
        .def_property_readonly("top_drive_twist", [](const BoundTorsionalString& r) { return r.model.top_drive_twist(); },
                               "A&S eq 29 at x = 0: int_0^L tau(x) / (J G)(x) dx [rad], tau(x) = int_x^L F_c: the "
                               "twist of the string holding the break-off torque profile.")
        .def_property_readonly("build_up_time", [](const BoundTorsionalString& r) { return r.model.build_up_time(); },
                               "A&S eq 34: 2 (1 - f_rat) top_drive_twist / omega_SP [s].")
        .def_property_readonly("fundamental_period",
                               [](const BoundTorsionalString& r) { return r.model.fundamental_period(); },
                               "The continuous string's lowest torsional period [s], top held, the bit free with J_BHA.")
        .def_property_readonly("period_estimate", [](const BoundTorsionalString& r) { return r.model.period_estimate(); },
                               "A&S eq 40: build_up_time + fundamental_period [s] (an upper estimate of the stick-slip "
                               "period).")
        .def_property_readonly("slow_speed", [](const BoundTorsionalString& r) { return r.slow_speed; })
        .def_property_readonly("switch_tolerance", [](const BoundTorsionalString& r) { return r.switch_tolerance; })
        .def_property_readonly("state_names", [](const BoundTorsionalString& r) { return r.model.state_names(); })
        .def("_simulate", &run_string, py::arg("t_end"), py::arg("options"), py::arg("t_start"))
        .def("__reduce__", [](py::handle self) {
            const auto& r = self.cast<const BoundTorsionalString&>();
            py::dict kwargs = field_keywords(r.params, fields);
            for (auto item : extras_of(r)) kwargs[item.first] = item.second;
            return reduce_by_construction(self, py::make_tuple(py::cast(r.string)), kwargs);
        })
        .def("__repr__", [](const BoundTorsionalString& r) {
            std::string out = std::string(name) + "(" + std::string(py::repr(py::cast(r.string)));
            for (auto item : extras_of(r)) {
                const std::string key = py::str(item.first);
                if (item.second.is_none()) continue;
                if (key == "treatment" && r.treatment == StringTreatment::captured) continue;
                if (key == "top_drive" && r.drive == TopDrive::pi_motor) continue;
                if (key == "slow_speed" && r.slow_speed == 0.0) continue;
                if (key == "switch_tolerance" && r.switch_tolerance == default_switch_tolerance) continue;
                out += ", " + key + "=" + std::string(py::repr(item.second));
            }
            return out + changed_fields_repr(r.params, fields) + ")";
        });

    m.def("aarsnes_shor_well_b", [](const std::string& collar, const std::string& wave_speed, double measured_depth,
                                    const py::kwargs& kwargs) {
        if (collar != "as_published" && collar != "corrected")
            throw InvalidParameter("collar", "aarsnes_shor_well_b: collar must be 'as_published' or 'corrected' (got '" +
                                                 collar + "')");
        if (wave_speed != "as_code" && wave_speed != "physical")
            throw InvalidParameter("wave_speed", "aarsnes_shor_well_b: wave_speed must be 'as_code' or 'physical' "
                                                 "(got '" + wave_speed + "')");
        // the BHA is 230 m long and the survey ends at 4000 m
        if (!(measured_depth > 230.0 && measured_depth <= 4000.0))
            detail::reject("aarsnes_shor_well_b", "measured_depth", "in (230, 4000] m (the BHA's length, the survey's end)",
                           measured_depth);
        const WellBCase c = aarsnes_shor_well_b(
            collar == "as_published" ? CollarPolarMoment::as_published : CollarPolarMoment::corrected,
            wave_speed == "as_code" ? CollarWaveSpeed::as_code : CollarWaveSpeed::physical, measured_depth);
        py::dict all;
        for (const auto& item : field_keywords(c.params, fields)) all[item.first] = item.second;
        all["elements"] = 1000;
        std::vector<double> md, inc;  // Well B's survey as (measured_depth, inclination), as it has always been given
        for (const SurveyStation& st : c.survey.stations()) {
            md.push_back(st.measured_depth);
            inc.push_back(st.inclination);
        }
        all["survey"] = py::make_tuple(py::cast(md), py::cast(inc));
        all["contact_radius"] = py::cast(c.contact_radius);
        all["slow_speed"] = 1.5;  // the stuck fraction as A&S's code counts it
        for (auto item : kwargs) all[item.first] = item.second;  // the caller's overrides
        return make(py::cast(c.string), py::reinterpret_borrow<py::kwargs>(all));
    },
          py::arg("collar") = "as_published", py::arg("wave_speed") = "as_code", py::arg("measured_depth") = 2500.0,
          R"doc(Well B of Aarsnes & Shor (2018) as a TorsionalString (parameters_WellB.m, MAIN.m: mu 0.3, f_rat 0.65,
40 rpm), at measured_depth [m] (230 < md <= 4000): 5.77" pipe above a 230 m BHA averaged over its four sections,
G 61 / 67 GPa, rho 7850, I_TD 2900, k_p 38e3, k_i 100e3, the survey 0 / 0 / 60 / 60 deg at 0 / 500 / 1600 /
4000 m, omega_c 1.5 rad/s, the PI sampled every 0.01 s, the code's damping at its grid; elements 1000 (the
published grid), the stuck fraction counted below 1.5 rad/s (slow_speed) as the code counts it. Further keywords (elements=, treatment=, any table keyword) override the preset's.

collar : {"as_published", "corrected"}
    The collar's polar moment: parameters_WellB.m's line carries an extra factor pi ("as_published", what the
    published results were computed with), or the length-averaged pi (OD^4 - ID^4) / 32 ("corrected").
wave_speed : {"as_code", "physical"}
    torsionalWaveStep.m updates the collar with the pipe's wave speed sqrt(G_p / rho) while its torque is J_c G_c
    times the strain: a collar of density rho G_c / G_p, 67/61 = 1.098 times the steel's ("as_code"), or steel
    ("physical").

The break-off torque (eq 27) depends on the wave-speed variant only: the collar variants share the collar's
area, hence its weight, and the polar moment does not enter the wall friction. "physical" gives the paper's
analytic 19.531 kN m; "as_code" weighs the collar 67/61 times heavier, hence more wall friction: 20.536 kN m.
)doc");
    return std::move(cls);
}

#endif

}  // namespace frictionsim::python
