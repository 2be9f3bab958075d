// Field-scale drill strings for Python (issue 13, item 3): fs.PipeSection and fs.DrillString (geometry and its
// lumped model), fs.NavarroLopezBit (the velocity-weakening bit law, through bind_law), DetournayBit (the drag bit's
// depth-of-cut law, a table like PipeSection's) and fs.StringRig, the event-driven string of
// drillstring/string_rig.hpp. The rig is held as one instantiation per wall law of PythonLaws, off bottom or on
// bottom (the velocity-weakening bit or the Detournay bit under a weight on bit, chosen at run time: OnRockBit),
// 2 x 8 alternatives, no virtual call in the right-hand side. Keywords, properties, repr, pickling and the docstring come from the tables
// (PipeSection::fields, StringRigParams::fields, NavarroLopezBit::fields, DetournayBit::fields).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <frictionsim/string/string_rig.hpp>
#include <frictionsim/string/treatment.hpp>

#include "law_binding.hpp"
#include "rig_binding.hpp"
#include "simulation.hpp"
#include "string_binding.hpp"

namespace frictionsim::python {

namespace {

constexpr const char* rig_name = event_string_rig::name;
constexpr auto section_fields = PipeSection::fields();
constexpr auto rig_fields = StringRigParams::fields();
constexpr auto detournay_fields = DetournayBit::fields;
/// More elements than any string needs (a 6 km string at 1 m): a guard against a typo allocating gigabytes.
constexpr long max_elements = 100000;

/// The bit laws a Python StringRig takes.
using BitLaw = std::variant<NavarroLopezBit, DetournayBit>;

/// The on-bottom bit of a Python StringRig, either bit law under its weight on bit, picked at run time: the bit is
/// one contact evaluated once per right-hand side, so the dispatch costs nothing measurable, and the extension
/// compiles one on-bottom rig per wall law instead of one per wall law and bit (a third less of its largest unit).
/// Both laws are set-valued and stateless with slip slopes (the Bit interface of bits/bit.hpp), so the rig runs
/// exactly as on either one alone.
class OnRockBit {
public:
    static constexpr const char* name = "OnRockBit";
    static constexpr bool touches_rock = true;
    static constexpr bool has_stick = true;
    static constexpr std::size_t state_count = 0;
    static_assert(VelocityWeakeningBit::has_stick && VelocityWeakeningBit::state_count == 0 &&
                      DetournayBitOnRock::has_stick && DetournayBitOnRock::state_count == 0,
                  "OnRockBit forwards set-valued, stateless bits only");

    OnRockBit() = default;
    OnRockBit(const BitLaw& law, double weight_on_bit)
        : bit_(std::holds_alternative<NavarroLopezBit>(law)
                   ? Either(VelocityWeakeningBit(std::get<NavarroLopezBit>(law), weight_on_bit))
                   : Either(DetournayBitOnRock(std::get<DetournayBit>(law), weight_on_bit))) {}

    double weight_on_bit() const { return visit([](const auto& b) { return b.weight_on_bit(); }); }
    double static_limit(double w) const { return visit([w](const auto& b) { return b.static_limit(w); }); }
    double slip_force(double speed, double w, int direction) const {
        return visit([&](const auto& b) { return b.slip_force(speed, w, direction); });
    }
    double slip_slope(double speed, double w, int direction) const {
        return visit([&](const auto& b) { return b.slip_slope(speed, w, direction); });
    }
    double karnopp_band() const { return visit([](const auto& b) { return b.karnopp_band(); }); }

private:
    using Either = std::variant<VelocityWeakeningBit, DetournayBitOnRock>;
    template <class F>
    double visit(F&& f) const { return std::visit(std::forward<F>(f), bit_); }
    Either bit_;
};

template <class Law> using OffBottomRig = StringRig<Law, OffBottom>;
template <class Law> using OnBottomRig = StringRig<Law, OnRockBit>;

/// std::variant<StringRig<L, OffBottom>..., StringRig<L, OnRockBit>...> over the laws of a list.
template <class Laws>
struct string_rig_variant;
template <class... L>
struct string_rig_variant<TypeList<L...>> {
    using type = std::variant<OffBottomRig<L>..., OnBottomRig<L>...>;
};
using StringRigVariant = string_rig_variant<PythonLaws>::type;

const char* hoisting_name(Hoisting h) { return h == Hoisting::hook_speed ? "hook_speed" : "hook_load"; }

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")); }

/// A real number (not a bool or a string), or a TypeError naming the keyword.
double real_from(py::handle value, const char* keyword) {
    if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) || !py::hasattr(value, "__float__"))
        throw py::type_error(std::string(rig_name) + ": " + keyword + " must be a number (got " + type_name(value) +
                             ")");
    return value.attr("__float__")().cast<double>();
}

/// A whole number in [low, high] (Python int or NumPy integer, not a bool), or an InvalidParameter naming it.
std::size_t count_from(py::handle value, const char* keyword, long low, long high, const char* owner = rig_name) {
    return static_cast<std::size_t>(whole_number_from(value, keyword, owner, low, high));
}

bool flag_from(py::handle value, const char* keyword) {
    if (!py::isinstance<py::bool_>(value) && !is_numpy_bool(value))
        throw py::type_error(std::string(rig_name) + ": " + keyword + " must be True or False (got " +
                             type_name(value) + ")");
    return py::bool_(py::reinterpret_borrow<py::object>(value));
}

std::string choice_from(py::handle value, const char* keyword, const char* a, const char* b) {
    const std::string s = py::isinstance<py::str>(value) ? value.cast<std::string>() : std::string();
    if (s != a && s != b)
        throw InvalidParameter(keyword, std::string(rig_name) + ": " + keyword + " must be '" + a + "' or '" + b +
                                            "' (got " + std::string(py::repr(value)) + ")");
    return s;
}

/// The table's keywords of `P` from kwargs (unknown keywords left to the caller), validated with the owner's name.
template <class P, std::size_t N>
P table_from_kwargs(const py::kwargs& kwargs, const std::array<Field<P>, N>& fields, const char* owner,
                    std::size_t& used) {
    P p{};
    used = read_field_keywords(p, kwargs, fields, owner);
    return p;
}

/// "__init__(self, <positional>, *, <table keywords>, <extras>) -> None": the signature help() and the stub show.
template <class P, std::size_t N>
std::string table_signature(const std::string& positional, const std::array<Field<P>, N>& fields,
                            const std::string& extras) {
    const P defaults{};
    std::string s = "__init__(self" + positional + ", *";
    for (const Field<P>& f : fields)
        s += ", " + std::string(f.public_name()) + ": float = " + format_double(defaults.*(f.member));
    return s + extras + ") -> None\n";
}

template <class P, std::size_t N>
[[noreturn]] void refuse_unknown_keyword(const py::kwargs& kwargs, const std::array<Field<P>, N>& fields,
                                         const std::vector<const char*>& extras, const char* owner) {
    for (auto item : kwargs) {
        const std::string key = py::str(item.first);
        bool known = false;
        for (const Field<P>& f : fields) known = known || key == f.public_name();
        for (const char* x : extras) known = known || key == x;
        if (!known) throw py::type_error(std::string(owner) + "() got an unexpected keyword argument '" + key + "'");
    }
    throw py::type_error(std::string(owner) + "(): an unexpected keyword argument");
}

/// How open codes write the drag bit's torque, T = c_c eps a^2 d + c_f gamma mu a W_f: their constants on the
/// cutting and the wear-flat terms (DetournayBit's law has one constant c on both: c_c = c_f = c).
struct TorqueConvention {
    const char* name;
    double cutting, friction;
    const char* form;
};
constexpr TorqueConvention torque_conventions[] = {
    {"detournay_defourny", DetournayBit::detournay_defourny_constant, DetournayBit::detournay_defourny_constant,
     "T = eps a^2 d / 2 + gamma mu a W_f / 2 (Detournay & Defourny 1992; Richard, Germay & Detournay 2007; the "
     "open Simulator4nDOF's Detournay.cs, whose own speed factors - (w^2 / (w^2 + (0.4 pi)^2)) on the cutting "
     "torque, (1 + exp(-mu w / 2 pi)) / 2 on the wear flats' - this law does not carry)"},
    {"unit", DetournayBit::unit_constant, DetournayBit::unit_constant,
     "T = eps a^2 d + gamma mu a W_f (codes that drop the half)"},
    {"half_cutting", DetournayBit::detournay_defourny_constant, DetournayBit::unit_constant,
     "T = eps a^2 d / 2 + gamma mu a W_f (the wear flats' half absorbed into gamma: here c = 1/2, gamma = 2 gamma')"},
};

const TorqueConvention& torque_convention(const std::string& name) {
    std::string names;
    for (const TorqueConvention& c : torque_conventions) {
        if (name == c.name) return c;
        names += std::string(names.empty() ? "'" : ", '") + c.name + "'";
    }
    throw InvalidParameter("convention", "DetournayBit: convention must be one of " + names + " (got '" + name + "')");
}

// ---- PipeSection, DrillString ------------------------------------------------------------------------------------

PipeSection checked_section(const PipeSection& s, const char* owner) {
    validate_fields(owner, s, section_fields);
    if (!(s.inner_diameter < s.outer_diameter))
        detail::reject(owner, "inner_diameter", "< outer_diameter (a tube has a wall)", s.inner_diameter);
    check_section_scale(owner, s);
    return s;
}

std::string section_repr(const PipeSection& s) {
    std::string out = "PipeSection(";
    bool first = true;
    for (const Field<PipeSection>& f : section_fields) {
        out += (first ? "" : ", ") + std::string(f.public_name()) + "=" + format_double(s.*(f.member));
        first = false;
    }
    return out + ")";
}

DrillString string_from(py::handle sections) {
    if (py::isinstance<py::str>(sections) || !py::isinstance<py::sequence>(sections))
        throw py::type_error("DrillString: sections must be a sequence of PipeSection (got " + type_name(sections) +
                             ")");
    std::vector<PipeSection> out;
    for (py::handle s : sections) {
        require_constructed(s);
        if (!py::isinstance<PipeSection>(s))
            throw py::type_error("DrillString: sections must hold PipeSection objects (got " + type_name(s) + ")");
        out.push_back(s.cast<PipeSection>());
    }
    return DrillString(std::move(out));
}

template <class T>
py::array_t<T> to_array(const std::vector<T>& v) {
    return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

// ---- StringRig ---------------------------------------------------------------------------------------------------

/// The Python StringRig: what it was built from (for properties, repr and pickling) and the rig itself.
struct BoundStringRig {
    DrillString string;
    FrictionLaw friction;
    std::optional<BitLaw> bit;
    double weight_on_bit = 0.0;
    StringRigParams params;
    /// as given: empty contact_nodes / normal_forces / node_inclinations mean "the rig's defaults"
    StringRigSetup setup;
    bool contact_nodes_given = false, normal_forces_given = false, inclinations_given = false;
    bool start_hanging = false;  ///< start from the rig's hanging_state() (axial positions at rest)
    StringRigVariant rig;

    BoundStringRig(DrillString s, FrictionLaw law, std::optional<BitLaw> b, double wob, const StringRigParams& p,
                   StringRigSetup setup_in, bool nodes_given, bool forces_given, bool incline_given, bool hanging)
        : string(std::move(s)), friction(std::move(law)), bit(std::move(b)), weight_on_bit(wob), params(p),
          setup(std::move(setup_in)), contact_nodes_given(nodes_given), normal_forces_given(forces_given),
          inclinations_given(incline_given), start_hanging(hanging), rig(build()) {
        if (start_hanging) std::visit([](auto& r) { r.set_initial_state(r.hanging_state()); }, rig);
    }

    template <class F>
    decltype(auto) visit(F&& f) const { return std::visit(std::forward<F>(f), rig); }

private:
    StringRigVariant build() const {
        return std::visit(
            [&](auto law) -> StringRigVariant {
                using Law = decltype(law);
                if (!bit) return OffBottomRig<Law>(string, params, setup, std::move(law));
                return OnBottomRig<Law>(string, params, setup, std::move(law), OnRockBit(*bit, weight_on_bit));
            },
            friction);
    }
};

const std::vector<const char*> rig_extras{"bit",           "weight_on_bit", "elements",      "top_drive",
                                          "axial",         "hoisting",      "wall_contacts", "contact_nodes",
                                          "normal_forces", "excitation_node", "node_inclinations",
                                          "start_hanging"};

/// The items of a per-node sequence, each read by `read`, refused past one per node of the longest string (an
/// endless iterator must end in an error, not hang).
template <class Read>
auto per_node_items(py::handle values, const char* keyword, const char* what, Read read) {
    if (py::isinstance<py::str>(values) || py::isinstance<py::bytes>(values) || !py::hasattr(values, "__iter__"))
        throw py::type_error(std::string(rig_name) + ": " + keyword + " must be a sequence of " + what + " (got " +
                             type_name(values) + ")");
    std::vector<decltype(read(values))> items;
    for (py::handle item : values) {
        if (items.size() > static_cast<std::size_t>(max_elements))
            throw InvalidParameter(keyword, std::string(rig_name) + ": " + keyword + " holds more than one item per " +
                                                "node of a string of at most " + std::to_string(max_elements) +
                                                " elements");
        items.push_back(read(item));
    }
    return items;
}

BoundStringRig make_string_rig(py::handle string, py::handle friction, const py::kwargs& kwargs) {
    if (!py::isinstance<DrillString>(string))
        throw py::type_error(std::string(rig_name) + ": string must be a DrillString (got " + type_name(string) + ")");
    std::size_t used = 0;
    StringRigParams p = table_from_kwargs(kwargs, rig_fields, rig_name, used);
    StringRigSetup setup;
    std::optional<BitLaw> bit;
    std::optional<double> wob;
    bool nodes_given = false, forces_given = false, inclinations_given = false, hanging = false;
    const auto given = [&](const char* key) {
        if (!kwargs.contains(key)) return false;
        ++used;
        return !kwargs[key].is_none();
    };
    if (given("bit")) {
        const py::handle b = kwargs["bit"];
        if (py::isinstance<NavarroLopezBit>(b)) bit = b.cast<NavarroLopezBit>();
        else if (py::isinstance<DetournayBit>(b)) bit = b.cast<DetournayBit>();
        else
            throw py::type_error(std::string(rig_name) +
                                 ": bit must be a NavarroLopezBit, a DetournayBit or None (off bottom), got " +
                                 type_name(b));
    }
    if (given("weight_on_bit")) wob = real_from(kwargs["weight_on_bit"], "weight_on_bit");
    if (given("elements"))
        setup.elements = count_from(kwargs["elements"], "elements", 1, max_elements);
    if (given("top_drive"))
        setup.top_drive = top_drive_from(kwargs["top_drive"], rig_name);
    if (given("axial")) setup.axial = flag_from(kwargs["axial"], "axial");
    if (given("hoisting"))
        setup.hoisting = choice_from(kwargs["hoisting"], "hoisting", "hook_speed", "hook_load") == "hook_speed"
                             ? Hoisting::hook_speed
                             : Hoisting::hook_load;
    if (given("wall_contacts")) setup.wall_contacts = flag_from(kwargs["wall_contacts"], "wall_contacts");
    if (given("contact_nodes")) {
        nodes_given = true;
        setup.contact_nodes = per_node_items(kwargs["contact_nodes"], "contact_nodes", "node numbers", [](py::handle n) {
            return count_from(n, "contact_nodes", 0, max_elements);
        });
        if (setup.contact_nodes.empty())
            throw InvalidParameter("contact_nodes", std::string(rig_name) +
                                                        ": contact_nodes must name at least one node (None: every "
                                                        "node; wall_contacts=False: none)");
    }
    if (given("normal_forces")) {
        forces_given = true;
        setup.normal_forces = per_node_items(kwargs["normal_forces"], "normal_forces", "forces in N",
                                             [](py::handle f) { return real_from(f, "normal_forces"); });
        if (setup.normal_forces.empty())
            throw InvalidParameter("normal_forces", std::string(rig_name) +
                                                        ": normal_forces must hold one force per contact node (None: "
                                                        "the inclined hole's buoyed weight)");
    }
    if (given("excitation_node"))
        setup.excitation_node = count_from(kwargs["excitation_node"], "excitation_node", 0, max_elements);
    if (given("start_hanging")) hanging = flag_from(kwargs["start_hanging"], "start_hanging");
    if (given("node_inclinations")) {
        inclinations_given = true;
        setup.node_inclinations = per_node_items(kwargs["node_inclinations"], "node_inclinations", "angles in rad",
                                                 [](py::handle a) { return real_from(a, "node_inclinations"); });
        if (setup.node_inclinations.empty())
            throw InvalidParameter("node_inclinations", std::string(rig_name) +
                                                            ": node_inclinations must hold one angle per node (None: "
                                                            "the straight hole's inclination)");
    }
    if (used != kwargs.size()) refuse_unknown_keyword(kwargs, rig_fields, rig_extras, rig_name);
    if (bit && !wob)
        throw InvalidParameter("weight_on_bit", std::string(rig_name) +
                                                    ": weight_on_bit must be given (N) with a bit on bottom");
    if (!bit && wob)
        throw InvalidParameter("weight_on_bit", std::string(rig_name) +
                                                    ": weight_on_bit needs a bit (bit=None: the bit is off bottom)");
    return BoundStringRig(string.cast<DrillString>(), friction_law_from_python(friction, "friction"), bit,
                          wob.value_or(0.0), p, setup, nodes_given, forces_given, inclinations_given, hanging);
}

py::dict rig_extras_of(const BoundStringRig& r) {
    py::dict d;
    d["bit"] = r.bit ? std::visit([](const auto& b) { return py::cast(b); }, *r.bit) : py::object(py::none());
    d["weight_on_bit"] = r.bit ? py::cast(r.weight_on_bit) : py::none();
    d["elements"] = r.setup.elements;
    d["top_drive"] = top_drive_name(r.setup.top_drive);
    d["axial"] = r.setup.axial;
    d["hoisting"] = hoisting_name(r.setup.hoisting);
    d["wall_contacts"] = r.setup.wall_contacts;
    d["contact_nodes"] = r.contact_nodes_given ? py::cast(r.setup.contact_nodes) : py::none();
    d["normal_forces"] = r.normal_forces_given ? py::cast(r.setup.normal_forces) : py::none();
    d["excitation_node"] = r.setup.excitation_node;
    d["node_inclinations"] = r.inclinations_given ? py::cast(r.setup.node_inclinations) : py::none();
    d["start_hanging"] = r.start_hanging;
    return d;
}

/// A node number in 0..N, or an InvalidParameter naming `keyword`.
std::size_t node_of(const BoundStringRig& r, long node, const char* keyword) {
    return count_from(py::int_(node), keyword, 0, static_cast<long>(r.setup.elements));
}

/// simulate_variant's run with the string's stop flag polled beside Ctrl-C, the work estimated first
/// (check_string_rig_work).
std::shared_ptr<Result> run_string_rig(const BoundStringRig& r, double t_end, const SolverOptions& options,
                                       double t_start) {
    SolverOptions polled = options;
    polled.interrupt = string_run_interrupt();
    r.visit([&](const auto& system) {
        SolverOptions resolved = polled;
        if (has_sundials) resolve_callable_law_method(system, resolved);
        check_string_rig_work(rig_name, system, t_end, t_start, resolved);
    });
    try {
        py::gil_scoped_release release;
        return r.visit([&](const auto& system) {
            SolverOptions o = polled;
            if (has_sundials) resolve_callable_law_method(system, o);
            return std::make_shared<Result>(simulate_built_in(system, t_end, o, t_start));
        });
    } catch (const Interrupted&) {
        raise_pending_python_error();
    }
}

using StatesArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// f(rig, t, x, mode) for every row of a (rows, states) array at times t, with the mode each row's state implies
/// (the rig's initial_mode: exact stick shows as zero speed, the drive's limit as the PI torque beyond it).
template <class F>
py::array_t<double> per_row(const BoundStringRig& r, StatesArray t, StatesArray states, F&& f) {
    const std::size_t n = r.visit([](const auto& s) { return s.state_size(); });
    if (states.ndim() != 2 || static_cast<std::size_t>(states.shape(1)) != n)
        throw InvalidParameter("states", "states must be an array of shape (rows, " + std::to_string(n) + ")");
    const auto rows = static_cast<std::size_t>(states.shape(0));
    if (t.ndim() != 1 || static_cast<std::size_t>(t.shape(0)) != rows)
        throw InvalidParameter("t", "t must hold one time per row of states");
    py::array_t<double> out(static_cast<py::ssize_t>(rows));
    auto o = out.mutable_unchecked<1>();
    const double* x = states.data();
    const double* time = t.data();
    r.visit([&](const auto& s) {
        for (std::size_t k = 0; k < rows; ++k) {
            const double* row = x + k * n;
            o(static_cast<py::ssize_t>(k)) = f(s, time[k], row, s.initial_mode(time[k], row));
        }
    });
    return out;
}

const char* const rig_description = R"doc(
A drill string on the event-driven engine (drillstring/string_rig.hpp): the lumped string of a DrillString (N
elements of equal length, node 0 at the top, node N at the bit), in torsion and optionally axially:

    J_i w_i' = tau_i - tau_{i-1} - k_t J_s,i w_i [+ T_m at node 0] - T_wall,i [- T_bit at node N]
    m_i v_i' = F_i - F_{i-1} + w_b,i cos I [- H at node 0] [+ F_x sin(2 pi f_x t) at excitation_node] - F_wall,i [- W]
    tau_e = k_e (th_{e+1} - th_e) + beta k_e (w_{e+1} - w_e)   (and the same for F_e with E A / dx)

(k_t, damping_rate: Aarsnes & Shor's viscous damping against absolute rotation, J_s,i node i's string inertia.)
Top drive: PI speed control of a motor of inertia J_td, T_m = clamp(k_p (w_set - w_0) + k_i int (w_set - w_0) dt,
+-T_max) with anti-windup, or a prescribed surface speed; either ramps w_set from rest as w_set (1 - exp(-t / T_SP))
with setpoint_time_constant T_SP > 0. With control_period T_c > 0 the PI is sampled at t = k T_c and its torque held
between samples (Aarsnes & Shor's MAIN.m, as TorsionalString's sampled PI: the set-point filtered by forward Euler,
sp += (w_set - sp) T_c / T_SP, the demand k_p (sp - w_0) + k_i I held within +-T_max, I += T_c (sp - w_0) unless
limited); each sample is an event top_drive.sample. A wall contact at each chosen node with `friction` (any
law of fs.FRICTION_LAWS or a CallableLaw) at the pipe's outer radius; its normal force given or the straight
inclined hole's buoyed weight w_b sin I (per node with node_inclinations). Torsion-only: exact per-contact stick;
axial=True: friction against the resultant of axial and circumferential sliding (paper 000's friction vector),
stick caught at stick_speed, slow slip below it where a node cannot hold. The bit: None (off bottom), a
NavarroLopezBit (velocity weakening, exact stick) or a DetournayBit (depth of cut d at W, torque
c eps a^2 d + c gamma mu a (a l sigma) turning forwards, sticking within it; no delayed depth of cut) under
weight_on_bit W [N] on node N.

Parameters
----------
string : DrillString
friction : a friction law (any class of fs.FRICTION_LAWS, or fs.CallableLaw) of the wall contacts
bit : NavarroLopezBit, DetournayBit or None
    None: the bit hangs off bottom (node N may carry a wall contact).
weight_on_bit : float or None
    W [N], required with a bit.
elements : int = 20
    N.
top_drive : {"pi_motor", "prescribed_speed"}
axial : bool = False
    Also the axial motion (u_i, v_i per node).
hoisting : {"hook_speed", "hook_load"}
    The axial top boundary (with axial=True).
wall_contacts : bool = True
    False: no wall contact at all.
contact_nodes : sequence of int or None
    Nodes with a wall contact, increasing, in 1..N (below N with the bit on bottom). None: every such node.
normal_forces : sequence of float or None
    One normal force [N] per contact node. None: w_b sin(I_i) per node. In a curved well: the soft-string side
    forces lumped to the nodes (e.g. SoftString.node_side_forces of the string hanging at rest).
excitation_node : int = 0
    Node of the axial excitation F_x sin(2 pi f_x t).
node_inclinations : sequence of float or None
    One hole inclination I_i [rad, 0..pi] per node 0..N (axial gravity w_b,i cos I_i; e.g. from a Survey at the
    nodes' measured depths). None: `inclination` at every node.
start_hanging : bool = False
    Start (axial runs) with the string hanging at rest from the top node without wall friction: each element
    stretched by the buoyed weight along the hole below it (less W on bottom), so no axial transient.

States, node by node: speed_error_integral (a sampled PI's also held_motor_torque [N m], sampled_setpoint [rad/s]
and next_sample, the index k of the next sample at k T_c), then theta_i [rad], omega_i [rad/s], [u_i [m], v_i [m/s]],
[the wall law's states]_i, the bit law's states, and the work integrals [J] drive_work, hoist_work, excitation_work,
wall_friction_work, damping_work, bit_work (drive + hoist + excitation = energy change + friction + damping + bit).
The Result's friction_force is the total wall friction torque [N m]; its mode counts the stuck wall contacts.
frictionsim.drillstring reads bit and surface speed, surface torque and stuck contacts out of a Result.

Keywords
--------
)doc";

}  // namespace

/// This thread's stop flag (string_binding.hpp): a strong reference, or null.
PyObject*& string_run_stop() {
    thread_local PyObject* flag = nullptr;
    return flag;
}

TopDrive top_drive_from(py::handle value, const char* owner) {
    const std::string s = py::isinstance<py::str>(value) ? value.cast<std::string>() : std::string();
    for (TopDrive d : {TopDrive::pi_motor, TopDrive::prescribed_speed})
        if (s == top_drive_name(d)) return d;
    throw InvalidParameter("top_drive", std::string(owner) + ": top_drive must be 'pi_motor' or 'prescribed_speed' "
                                                             "(got " + std::string(py::repr(value)) + ")");
}

template <>
py::object register_rig<event_string_rig>(py::module_& m) {
    // the constructors read their keywords off the tables: their signatures are written from the tables too
    py::options options;

    // ---- PipeSection
    py::class_<PipeSection> section(m, "PipeSection", kept(R"doc(
One section of a drill string: a steel tube (drill pipe, heavy-weight pipe, collars). All keywords optional;
defaults: 5" drill pipe (OD 127 mm, ID 108.6 mm), 100 m, steel. SI units; ID < OD.

Keywords
--------
)doc" + keywords_doc(section_fields)));
    def_field_properties(section, section_fields, [](const PipeSection& s) -> const PipeSection& { return s; });
    options.disable_function_signatures();
    section
        .def(py::init([](const py::kwargs& kwargs) {
                 std::size_t used = 0;
                 const PipeSection s = table_from_kwargs(kwargs, section_fields, "PipeSection", used);
                 if (used != kwargs.size()) refuse_unknown_keyword(kwargs, section_fields, {}, "PipeSection");
                 return checked_section(s, "PipeSection");
             }),
             kept(table_signature("", section_fields, "") +
                  "\nThe section's geometry and steel by keyword (see the class docstring).\n"));
    options.enable_function_signatures();
    section
        .def_property_readonly("area", &PipeSection::area, "A = pi (OD^2 - ID^2) / 4 [m^2].")
        .def_property_readonly("polar_moment", &PipeSection::polar_moment, "I_p = pi (OD^4 - ID^4) / 32 [m^4].")
        .def_property_readonly("torsional_rigidity", &PipeSection::torsional_rigidity, "G I_p [N m^2/rad].")
        .def_property_readonly("axial_rigidity", &PipeSection::axial_rigidity, "E A [N].")
        .def_property_readonly("inertia_per_length", &PipeSection::inertia_per_length, "rho I_p [kg m].")
        .def_property_readonly("mass_per_length", &PipeSection::mass_per_length, "rho A [kg/m].")
        .def("__repr__", &section_repr)
        .def("__reduce__", [](py::handle self) {
            return reduce_by_construction(self, py::tuple(), field_keywords(self.cast<const PipeSection&>(),
                                                                            section_fields));
        });

    // ---- DrillString
    py::class_<DrillString> string(m, "DrillString", R"doc(
A drill string as its sections, top to bottom (a sequence of PipeSection), and its lumped model.

lump(elements) gives N elements of equal length dx = L / N, each a torsional spring G I_p / dx and an axial spring
E A / dx between two nodes, each element's inertia rho I_p dx and mass rho A dx split half to each node; an element
across a section boundary takes each section's share (compliances in series).
)doc");
    options.disable_function_signatures();
    string.def(py::init([](py::handle sections) { return string_from(sections); }),
               "__init__(self, sections: collections.abc.Sequence[PipeSection]) -> None\n\nSections top to bottom.\n",
               py::arg("sections"));
    options.enable_function_signatures();
    string
        .def_property_readonly("sections", [](const DrillString& s) { return s.sections(); },
                               "The sections, top to bottom (copies).")
        .def_property_readonly("length", &DrillString::length, "Total length L [m].");
    options.disable_function_signatures();
    string.def("lump", [](const DrillString& s, py::handle elements) {
                 const LumpedString l = s.lump(count_from(elements, "elements", 1, max_elements, "DrillString"));
                 py::dict d;
                 d["element_length"] = l.element_length;
                 d["node_inertia"] = to_array(l.node_inertia);
                 d["node_mass"] = to_array(l.node_mass);
                 d["torsional_stiffness"] = to_array(l.torsional_stiffness);
                 d["axial_stiffness"] = to_array(l.axial_stiffness);
                 return d;
             },
             // the signature pybind11 writes for a long: elements is read as a handle so that 2**63 is refused
             // by its value (InvalidParameter), not by pybind11's overload resolution
             "lump(self, elements: typing.SupportsInt | typing.SupportsIndex) -> dict\n\n"
             "The lumped string of N = elements: "
             "element_length dx [m], node_inertia J_i [kg m^2] and node_mass m_i [kg] (N + 1 nodes), "
             "torsional_stiffness [N m/rad] and axial_stiffness [N/m] (N springs).\n",
             py::arg("elements"));
    options.enable_function_signatures();
    string
        .def("__len__", [](const DrillString& s) { return s.sections().size(); })
        .def("__repr__", [](const DrillString& s) {
            std::string out = "DrillString([";
            for (std::size_t i = 0; i < s.sections().size(); ++i)
                out += (i ? ", " : "") + section_repr(s.sections()[i]);
            return out + "])";
        })
        .def("__reduce__", [](py::handle self) {
            return reduce_by_construction(self, py::make_tuple(py::cast(self.cast<const DrillString&>().sections())));
        });

    // ---- NavarroLopezBit: a law table like the wall laws', bound by the same template
    auto bit = bind_law<NavarroLopezBit>(m);
    bit.attr("__doc__") = kept(R"doc(Velocity-weakening bit friction of Navarro-Lopez & Cortes (2007, Sec. 2):

    T_b(w) = c_b w + R_b W mu_b(w) sign(w),  mu_b(w) = mu_cb + (mu_sb - mu_cb) exp(-gamma_b |w| / v_f)   (slip)
    |T_b| <= R_b W mu_sb                                                                              (stick)

with bit speed w [rad/s] and weight on bit W [N]. Defaults: the paper's parameter set.
)doc" + std::string(py::str(bit.attr("__doc__"))));
    bit.def("coefficient", py::vectorize([](NavarroLopezBit& b, double w) { return b.coefficient(w); }),
            py::arg("angular_speed"), "mu_b(w) [-] at bit speed w [rad/s] (arrays broadcast).")
        .def("torque", py::vectorize([](NavarroLopezBit& b, double w, double weight) {
                 if (!(std::isfinite(weight) && weight >= 0.0))
                     throw InvalidParameter("weight_on_bit", "NavarroLopezBit: weight_on_bit must be >= 0 and finite");
                 return b.torque(w, weight, w > 0.0 ? 1 : w < 0.0 ? -1 : 0);
             }),
             py::arg("angular_speed"), py::arg("weight_on_bit"),
             "Slip torque T_b [N m] at bit speed w [rad/s] under weight on bit W [N] (0 at w = 0: the stuck bit's "
             "torque is whatever holds it, within static_limit).")
        .def("static_limit", py::vectorize([](NavarroLopezBit& b, double weight) { return b.static_limit(weight); }),
             py::arg("weight_on_bit"), "R_b W mu_sb [N m]: the largest torque the stuck bit holds.");

    // ---- DetournayBit: the drag bit's depth-of-cut law, a table like PipeSection's
    py::class_<DetournayBit> drag(m, "DetournayBit", kept(R"doc(
Drag bit of Detournay & Defourny (1992), as in Richard, Germay & Detournay (2007, Sec. 2): weight and torque on bit
are a cutting part proportional to the depth of cut per revolution d plus a frictional contact part (wear flats):

    W = zeta eps a d + a l sigma,   T = c eps a^2 d + c gamma mu a (a l sigma)

c = torque_constant: 1/2 in Detournay & Defourny's convention, 1 in codes that drop the half; codes also differ
in where the half sits (some put it on the cutting term only and absorb the wear flats' into their gamma).
DetournayBit.CONVENTIONS names the forms (cutting constant, wear-flat constant, formula), from_convention builds the
bit of a code from that code's parameters, and convention names this bit's. As a StringRig's bit
under weight_on_bit W: d = depth_at_weight(W), T turning forwards whatever the speed, the stuck bit held within
|T| (turning backwards only the wear flats rub). The delayed depth of cut of Richard-Germay-Detournay (axial-
torsional coupling through a state-dependent delay) is not modelled. Defaults: an illustrative 8.5" PDC bit.

Keywords
--------
)doc" + keywords_doc(detournay_fields)));
    def_field_properties(drag, detournay_fields, [](const DetournayBit& b) -> const DetournayBit::Params& {
        return b.params();
    });
    py::dict conventions;
    for (const TorqueConvention& c : torque_conventions)
        conventions[c.name] = py::make_tuple(c.cutting, c.friction, c.form);
    drag.attr("CONVENTIONS") = conventions;
    options.disable_function_signatures();
    drag.def(py::init([](const py::kwargs& kwargs) {
                 std::size_t used = 0;
                 const DetournayBit::Params p = table_from_kwargs(kwargs, detournay_fields, "DetournayBit", used);
                 if (used != kwargs.size()) refuse_unknown_keyword(kwargs, detournay_fields, {}, "DetournayBit");
                 return DetournayBit(p);
             }),
             kept(table_signature("", detournay_fields, "") + "\nThe bit's parameters by keyword.\n"));
    options.enable_function_signatures();
    drag.def_property_readonly("contact_force", &DetournayBit::contact_force, "W_f = a l sigma [N].")
        .def_property_readonly("contact_torque", &DetournayBit::contact_torque,
                               "T_f = c gamma mu a W_f [N m]: the wear flats' torque.")
        .def("depth_at_weight", py::vectorize([](DetournayBit& b, double weight) {
                 return b.depth_at_weight(weight);
             }),
             py::arg("weight_on_bit"),
             "Steady depth of cut per revolution d = (W - a l sigma) / (zeta eps a) [m] at weight on bit W [N] "
             "(0 below the contact force).")
        .def_static("depth_of_cut", py::vectorize(&DetournayBit::depth_of_cut), py::arg("rate_of_penetration"),
                    py::arg("angular_speed"),
                    "d = 2 pi V / Omega [m per revolution] from the rate of penetration V [m/s] and the angular speed "
                    "Omega [rad/s] (> 0: the bit cuts only while it turns forwards); arrays broadcast.")
        .def_static("from_convention", [](const std::string& convention, const py::kwargs& kwargs) {
                const TorqueConvention& c = torque_convention(convention);
                std::size_t used = 0;
                DetournayBit::Params p = table_from_kwargs(kwargs, detournay_fields, "DetournayBit", used);
                if (used != kwargs.size()) refuse_unknown_keyword(kwargs, detournay_fields, {}, "DetournayBit");
                if (kwargs.contains("torque_constant"))
                    throw InvalidParameter("torque_constant", "DetournayBit.from_convention: the convention sets "
                                                              "torque_constant; give one or the other");
                // T = c_c eps a^2 d + c_f gamma' mu a W_f  ==  c eps a^2 d + c gamma mu a W_f
                p.torque_constant = c.cutting;
                p.contact_orientation *= c.friction / c.cutting;
                return DetournayBit(p);
            },
            py::arg("convention"),
            "The bit of a code that writes its torque in `convention` (a key of DetournayBit.CONVENTIONS), with "
            "that code's parameters by keyword (contact_orientation is the code's gamma): T = c_c eps a^2 d + c_f "
            "gamma' mu a W_f becomes this law's T = c eps a^2 d + c gamma mu a W_f with c = c_c, gamma = gamma' "
            "c_f / c_c. The weight on bit has no such constant.")
        .def_property_readonly("convention", [](const DetournayBit& b) -> py::object {
                for (const TorqueConvention& c : torque_conventions)
                    if (c.cutting == c.friction && b.params().torque_constant == c.cutting) return py::str(c.name);
                return py::none();
            },
            "The name of the convention whose torque this bit writes with its own gamma (torque_constant 1/2: "
            "'detournay_defourny', 1: 'unit'), or None for another constant.")
        .def("weight_on_bit", py::vectorize([](DetournayBit& b, double depth) { return b.weight_on_bit(depth); }),
             py::arg("depth_of_cut"), "W = zeta eps a d + a l sigma [N] at depth of cut d [m].")
        .def("torque_on_bit", py::vectorize([](DetournayBit& b, double depth) { return b.torque_on_bit(depth); }),
             py::arg("depth_of_cut"), "T = c eps a^2 d + c gamma mu a (a l sigma) [N m] at depth of cut d [m].")
        .def("__repr__", [](const DetournayBit& b) {
            const std::string changed = changed_fields_repr(b.params(), detournay_fields);  // ", key=value..."
            return "DetournayBit(" + (changed.empty() ? changed : changed.substr(2)) + ")";
        })
        .def("__reduce__", [](py::handle self) {
            return reduce_by_construction(self, py::tuple(),
                                          field_keywords(self.cast<const DetournayBit&>().params(), detournay_fields));
        });

    // ---- StringRig
    py::class_<BoundStringRig> cls(m, rig_name, kept(rig_description + keywords_doc(rig_fields)));
    def_field_properties(cls, rig_fields, [](const BoundStringRig& r) -> const StringRigParams& { return r.params; });
    def_outputs(cls, event_string_rig::outputs());
    const std::string extras_signature =
        ", bit: NavarroLopezBit | None = None, weight_on_bit: float | None = None, elements: int = 20, "
        "top_drive: str = 'pi_motor', axial: bool = False, hoisting: str = 'hook_speed', wall_contacts: bool = True, "
        "contact_nodes: collections.abc.Sequence[int] | None = None, "
        "normal_forces: collections.abc.Sequence[float] | None = None, excitation_node: int = 0, "
        "node_inclinations: collections.abc.Sequence[float] | None = None, start_hanging: bool = False";
    options.disable_function_signatures();
    cls.def(py::init([](py::handle s, py::handle friction, const py::kwargs& kwargs) {
                return make_string_rig(s, friction, kwargs);
            }),
            kept(table_signature(", string: DrillString, friction: object", rig_fields, extras_signature) +
                 "\nThe string, the wall law, then the rig's set-up and parameters by keyword (see the class "
                 "docstring).\n"),
            py::arg("string"), py::arg("friction"));
    options.enable_function_signatures();
    cls.def_property_readonly("string", [](const BoundStringRig& r) { return r.string; }, "The DrillString.")
        .def_property_readonly("friction", [](const BoundStringRig& r) { return friction_law_to_python(r.friction); },
                               "The wall contacts' friction law.")
        .def_property_readonly("bit",
                               [](const BoundStringRig& r) {
                                   return r.bit ? std::visit([](const auto& b) { return py::cast(b); }, *r.bit)
                                                : py::object(py::none());
                               },
                               "The bit law (NavarroLopezBit or DetournayBit), or None off bottom.")
        .def_property_readonly("node_inclinations",
                               [](const BoundStringRig& r) {
                                   return to_array(r.visit([](const auto& s) { return s.node_inclinations(); }));
                               },
                               "The hole inclination at each node [rad] (as the rig placed them).")
        .def_property_readonly("weight_on_bit",
                               [](const BoundStringRig& r) { return r.bit ? py::cast(r.weight_on_bit) : py::none(); },
                               "W [N], or None off bottom.")
        .def_property_readonly("on_bottom", [](const BoundStringRig& r) { return r.bit.has_value(); })
        .def_property_readonly("elements", [](const BoundStringRig& r) { return r.setup.elements; }, "N.")
        .def_property_readonly("top_drive", [](const BoundStringRig& r) { return top_drive_name(r.setup.top_drive); })
        .def_property_readonly("axial", [](const BoundStringRig& r) { return r.setup.axial; })
        .def_property_readonly("hoisting", [](const BoundStringRig& r) { return hoisting_name(r.setup.hoisting); })
        .def_property_readonly("wall_contacts", [](const BoundStringRig& r) { return r.setup.wall_contacts; })
        .def_property_readonly("excitation_node", [](const BoundStringRig& r) { return r.setup.excitation_node; })
        .def_property_readonly("contact_nodes",
                               [](const BoundStringRig& r) {
                                   return r.visit([](const auto& s) { return s.contact_nodes(); });
                               },
                               "The nodes with a wall contact (as the rig placed them).")
        .def_property_readonly("normal_forces",
                               [](const BoundStringRig& r) {
                                   return to_array(r.visit([](const auto& s) { return s.normal_forces(); }));
                               },
                               "The normal force of each contact [N], in contact_nodes order.")
        .def_property_readonly("node_radius",
                               [](const BoundStringRig& r) {
                                   return to_array(r.visit([](const auto& s) { return s.node_radius(); }));
                               },
                               "Contact radius of each node [m] (the larger OD on a section boundary).")
        .def_property_readonly("node_inertia",
                               [](const BoundStringRig& r) {
                                   return to_array(r.visit([](const auto& s) { return s.node_inertia(); }));
                               },
                               "J_i [kg m^2] of each node (with J_td at node 0 under PI control, J_end at node N).")
        .def_property_readonly("node_mass",
                               [](const BoundStringRig& r) {
                                   return to_array(r.visit([](const auto& s) { return s.node_mass(); }));
                               },
                               "m_i [kg] of each node (with m_end at node N).")
        .def_property_readonly("period", [](const BoundStringRig&) { return py::none(); },
                               "None: a string has no imposed period (its stick-slip period is an outcome).")
        .def_property_readonly("state_names", [](const BoundStringRig& r) {
            return r.visit([](const auto& s) { return s.state_names(); });
        })
        .def("theta_index", [](const BoundStringRig& r, long node) {
                 return r.visit([&](const auto& s) { return s.theta(node_of(r, node, "node")); });
             },
             "Column of theta_node [rad] in the states.", py::arg("node"))
        .def("omega_index", [](const BoundStringRig& r, long node) {
                 return r.visit([&](const auto& s) { return s.omega(node_of(r, node, "node")); });
             },
             "Column of omega_node [rad/s] in the states.", py::arg("node"))
        .def("work_index", [](const BoundStringRig& r) { return r.visit([](const auto& s) { return s.work_offset(); }); },
             "Column of drive_work, the first of the six work integrals.")
        .def("surface_torque", [](const BoundStringRig& r, StatesArray t, StatesArray states) {
                 return per_row(r, t, states, [](const auto& s, double time, const double* x, const ContactModes& md) {
                     return s.surface_torque(time, x, md);
                 });
             },
             "The torque the "
             "surface applies [N m] at each row (t [s], states (rows, states)): the motor's under PI control, what "
             "holds the prescribed speed otherwise.",
             py::arg("t"), py::arg("states"))
        .def("hook_force", [](const BoundStringRig& r, StatesArray t, StatesArray states) {
                 return per_row(r, t, states, [](const auto& s, double time, const double* x, const ContactModes& md) {
                     return s.hook_force(time, x, md);
                 });
             },
             "The hook's force on the string [N], positive up, at each row (t [s], states (rows, states)): the hook "
             "load, or what holds the prescribed hook speed (axial runs; 0 in torsion-only runs).",
             py::arg("t"), py::arg("states"))
        .def("bit_torque", [](const BoundStringRig& r, StatesArray t, StatesArray states) {
                 return per_row(r, t, states, [](const auto& s, double time, const double* x, const ContactModes& md) {
                     return s.bit_torque(time, x, md);
                 });
             },
             "The torque on bit "
             "[N m] at each row (0 off bottom; the holding torque while the bit sticks).",
             py::arg("t"), py::arg("states"))
        .def("_simulate", &run_string_rig, py::arg("t_end"), py::arg("options"), py::arg("t_start"))
        .def("__reduce__", [](py::handle self) {
            const auto& r = self.cast<const BoundStringRig&>();
            py::dict kwargs = field_keywords(r.params, rig_fields);
            for (auto item : rig_extras_of(r)) kwargs[item.first] = item.second;
            return reduce_by_construction(self, py::make_tuple(py::cast(r.string), friction_law_to_python(r.friction)),
                                          kwargs);
        })
        .def("__repr__", [](const BoundStringRig& r) {
            std::string out = std::string(rig_name) + "(" + std::string(py::repr(py::cast(r.string))) +
                              ", friction=" + std::string(py::repr(friction_law_to_python(r.friction)));
            const StringRigSetup defaults;
            for (auto item : rig_extras_of(r)) {
                const std::string key = py::str(item.first);
                const py::handle v = item.second;
                if (v.is_none()) continue;
                if (key == "elements" && r.setup.elements == defaults.elements) continue;
                if (key == "top_drive" && r.setup.top_drive == defaults.top_drive) continue;
                if (key == "axial" && r.setup.axial == defaults.axial) continue;
                if (key == "hoisting" && r.setup.hoisting == defaults.hoisting) continue;
                if (key == "wall_contacts" && r.setup.wall_contacts == defaults.wall_contacts) continue;
                if (key == "excitation_node" && r.setup.excitation_node == defaults.excitation_node) continue;
                if (key == "start_hanging" && !r.start_hanging) continue;
                out += ", " + key + "=" + std::string(py::repr(v));
            }
            return out + changed_fields_repr(r.params, rig_fields) + ")";
        });

    // ---- the treatment of a string's contacts, chosen by the measured rule (string/treatment.hpp)
    m.def(
        "automatic_treatment",
        [](long wall_contacts, bool bit_on_bottom) {
            if (wall_contacts < 0) detail::reject("automatic_treatment", "wall_contacts", ">= 0",
                                                  static_cast<double>(wall_contacts));
            return std::string(
                treatment_name(automatic_treatment(static_cast<std::size_t>(wall_contacts), bit_on_bottom)));
        },
        py::arg("wall_contacts"), py::arg("bit_on_bottom"), R"doc(
The contact treatment a drill string of `wall_contacts` wall contacts runs cheapest in: "exact" (fs.StringRig,
every switch located), "mixed" (fs.TorsionalString with the bit's switches located, the walls captured) or
"captured" (fs.TorsionalString, Moreau-Jean over every contact).

The rule, measured (bench/mixed.bench.cpp: the cost to reach 1e-4 s in the bit's switch times, ratios within one
run): exact up to 30 contacts (at 10 the mixed costs 3.1x and the captured 8.7x the exact), mixed up to 300 with
the bit on bottom (at 100 the exact costs 1.25x and the captured 1.7x the mixed), captured beyond (at 1000 the
mixed costs 1.07x and the exact 1.43x the captured). Off bottom the mixed treatment is the captured one.
)doc");
    // this thread's stop flag of the string runs (drillstring.stick_slip_map's workers: string_binding.hpp)
    m.def("_string_run_stop", [](py::object flag) -> py::object {
        PyObject*& slot = string_run_stop();
        const py::object previous = slot ? py::reinterpret_steal<py::object>(slot) : py::object(py::none());
        slot = flag.is_none() ? nullptr : flag.release().ptr();
        return previous;
    }, py::arg("flag"), "Sets the object whose is_set() this thread's string runs poll beside Ctrl-C (None: none); "
                        "returns the previous one.");
    return std::move(cls);
}

}  // namespace frictionsim::python
