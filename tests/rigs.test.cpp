// The rig list (rigs/rigs.hpp): every entry declares the units of its outputs, matching the states its rig names;
// and a toy rig written as a new rig would be (tests/rigs/belt_rig.hpp) runs through simulate() and through the
// same generic code the fuzz target and the benchmarks use for EngineRigs, against its closed-form stick-slip period.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include <frictionsim/frictionsim.hpp>
#include <frictionsim/rigs/rigs.hpp>
#include <frictionsim/simulate.hpp>

#include "rigs/belt_rig.hpp"

using namespace frictionsim;

namespace {

/// The states a rig of `Entry` names (with Coulomb, which has none, for the law-built ones).
template <class Entry>
std::vector<std::string> state_names_of() {
    std::vector<std::string> out;
    const auto add = [&](const auto& rig) {
        for (const char* n : rig.state_names()) out.emplace_back(n);
    };
    if constexpr (Entry::construction == RigConstruction::law)
        add(typename Entry::template of<Coulomb>(typename Entry::Params{}, Coulomb(0.3, 0.4)));
    else if constexpr (Entry::construction == RigConstruction::table)
        add(typename Entry::type(typename Entry::Params{}));
    else
        add(typename Entry::template of<Coulomb, ConstantSignal>(Coulomb(0.3), ConstantSignal(0.1),
                                                                 ConstantSignal(1.0)));
    return out;
}

/// The outputs table of `Entry` covers exactly its states plus friction_force, each once, each with a unit.
template <class Entry>
void check_outputs() {
    INFO(Entry::name);
    std::set<std::string> declared;
    for (const RigOutput& o : Entry::outputs()) {
        CHECK(std::string(o.unit) != "");
        CHECK(std::string(o.what) != "");
        CHECK(declared.insert(o.name).second);
    }
    std::set<std::string> expected{"friction_force"};
    for (const std::string& n : state_names_of<Entry>()) expected.insert(n);
    CHECK(declared == expected);
    // friction is a force on the lab's sliding rigs, a torque on the rotating ones
    const std::string unit = Entry::outputs()[0].unit;
    CHECK(std::string(Entry::outputs()[0].name) == "friction_force");
    CHECK((unit == "N" || unit == "N m"));
}

/// Whether `outputs` declares the column `name`: by its name, or as a state per node (a row stem_* for stem_<i>).
template <class Outputs>
bool declares(const Outputs& outputs, const std::string& name) {
    for (const RigOutput& o : outputs) {
        const std::string row = o.name;
        if (row == name) return true;
        if (row.size() > 2 && row.compare(row.size() - 2, 2, "_*") == 0) {
            const std::string stem = row.substr(0, row.size() - 1);  // "theta_"
            if (name.size() > stem.size() && name.compare(0, stem.size(), stem) == 0 &&
                name.find_first_not_of("0123456789", stem.size()) == std::string::npos)
                return true;
        }
    }
    return false;
}

/// A string model's outputs: friction_force first (a torque), each row once with a unit and a meaning, and a mode
/// row of unit "1" (the mode column counts contacts at rest); every state of `runs` (set-ups of the model that
/// name all its states between them) declared, and every row but friction_force and mode some state's.
template <class Entry>
void check_string_outputs(const std::vector<std::vector<std::string>>& runs) {
    INFO(Entry::name);
    const auto outputs = Entry::outputs();
    CHECK(std::string(outputs[0].name) == "friction_force");
    CHECK(std::string(outputs[0].unit) == "N m");
    std::set<std::string> rows, used;
    for (const RigOutput& o : outputs) {
        CHECK(std::string(o.unit) != "");
        CHECK(std::string(o.what) != "");
        CHECK(rows.insert(o.name).second);
        if (std::string(o.name) == "mode") CHECK(std::string(o.unit) == "1");
    }
    CHECK(rows.count("mode") == 1);
    for (const std::vector<std::string>& names : runs)
        for (const std::string& n : names) {
            INFO(n);
            CHECK(declares(outputs, n));
            for (const RigOutput& o : outputs)
                if (declares(std::array<RigOutput, 1>{o}, n)) used.insert(o.name);
        }
    used.insert("friction_force");
    used.insert("mode");
    CHECK(used == rows);
}

DrillString one_pipe(double length) {
    PipeSection s;
    s.length = length;
    return DrillString({s});
}

template <class Names>
std::vector<std::string> strings_of(const Names& names) {
    return std::vector<std::string>(names.begin(), names.end());
}

/// The closed-form stick-slip period of a block on a belt with Coulomb friction (mu_k < mu_s, no damping): it
/// sticks from x = 2 x_k - x_s to x_s = mu_s N / k at the belt's speed, then slips as a harmonic oscillator about
/// x_k = mu_k N / k (w = sqrt(k / m)) until x' = v_b again: T = 2 (x_s - x_k) / v_b + (2 pi - 2 phi) / w,
/// phi = atan2((x_s - x_k) w, v_b).
double belt_period(const test::BeltRigParams& p, double mu_k, double mu_s) {
    const double x_s = mu_s * p.normal_force / p.stiffness, x_k = mu_k * p.normal_force / p.stiffness;
    const double w = std::sqrt(p.stiffness / p.mass);
    const double phi = std::atan2((x_s - x_k) * w, p.belt_speed);
    return 2.0 * (x_s - x_k) / p.belt_speed + (2.0 * pi - 2.0 * phi) / w;
}

}  // namespace

TEST_CASE("every rig of EngineRigs declares its outputs' units, one per state and friction_force", "[rigs]") {
    STATIC_REQUIRE(EngineRigs::size == 7);
    STATIC_REQUIRE(count_rigs<RigConstruction::law>(EngineRigs{}) == 2);
    STATIC_REQUIRE(count_rigs<RigConstruction::table>(EngineRigs{}) == 2);
    STATIC_REQUIRE(count_rigs<RigConstruction::string>(EngineRigs{}) == 1);
    STATIC_REQUIRE(count_rigs<RigConstruction::time_stepping>(EngineRigs{}) == 1);
    std::vector<std::string> names;
    for_each_type(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        if constexpr (Entry::construction != RigConstruction::string &&
                      Entry::construction != RigConstruction::time_stepping)
            check_outputs<Entry>();  // the string models: the next case
        names.emplace_back(Entry::name);
    });
    CHECK(names == std::vector<std::string>{"AxialVibrationRig", "KinematicRig", "TorsionalRig", "StringRig",
                                            "NavarroLopez2Dof", "NavarroLopez4Dof", "TorsionalString"});
    CHECK(std::string(AxialRigParams::outputs()[0].unit) == "N");
    CHECK(std::string(NavarroLopez4DofParams::outputs()[0].unit) == "N m");
}

TEST_CASE("the string models of EngineRigs declare their outputs: per node, work integrals, counted mode", "[rigs]") {
    const DrillString string = one_pipe(300.0);
    // StringRig: torsion under the PI drive off bottom, and axial under a prescribed speed with the bit on bottom:
    // between them every state a Coulomb-walled string has (a wall law's own states come from the law)
    for_each_rig<RigConstruction::string>(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        StringRigSetup torsion;
        torsion.elements = 3;
        StringRigSetup axial = torsion;
        axial.axial = true;
        axial.top_drive = TopDrive::prescribed_speed;
        const typename Entry::template of<Coulomb> off_bottom(string, StringRigParams{}, torsion, Coulomb(0.3));
        const typename Entry::template of<Coulomb, VelocityWeakeningBit> on_bottom(
            string, StringRigParams{}, axial, Coulomb(0.3), VelocityWeakeningBit(NavarroLopezBit(), 2e4));
        const std::vector<std::string> a = off_bottom.state_names(), b = on_bottom.state_names();
        CHECK(std::find(a.begin(), a.end(), "speed_error_integral") != a.end());
        CHECK(std::find(b.begin(), b.end(), "u_3") != b.end());
        // a law that remembers reversals (Leuven) adds the planar contact's reference axis per node in axial runs;
        // the law's own states are the law's to declare (Law::state_units), so only the axis is kept here
        Leuven::Params leuven;
        leuven.presliding_stiffness = 1e7;
        const typename Entry::template of<Leuven> remembering(string, StringRigParams{}, axial, Leuven(leuven));
        std::vector<std::string> c;
        for (const std::string& n : remembering.state_names())
            if (n.rfind("slip_axis_", 0) == 0) c.push_back(n);
        CHECK(!c.empty());
        StringRigParams sampling;  // the sampled PI's states
        sampling.control_period = 0.01;
        const typename Entry::template of<Coulomb> sampled(string, sampling, torsion, Coulomb(0.3));
        check_string_outputs<Entry>({a, b, c, sampled.state_names()});
    });
    // TorsionalString: its four columns
    for_each_rig<RigConstruction::time_stepping>(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        const typename Entry::type model(string, typename Entry::Params{}, 5);
        check_string_outputs<Entry>({strings_of(model.state_names())});
    });
}

TEST_CASE("a toy rig added to a list of rigs runs through the list's generic code at its closed-form period",
          "[rigs]") {
    using Rigs = append<EngineRigs, law_rig<test::BeltRig, test::BeltRigParams>>::type;
    STATIC_REQUIRE(count_rigs<RigConstruction::law>(Rigs{}) == 3);
    check_outputs<law_rig<test::BeltRig, test::BeltRigParams>>();

    // The fuzz target's and the benchmark's way to build a law rig from an entry: Entry::of<Law>(Params, law).
    const test::BeltRigParams p{};
    const double mu_k = 0.3, mu_s = 0.4;
    std::vector<double> starts;  // times the block starts sticking
    Result run;
    std::size_t i = 0;
    for_each_rig<RigConstruction::law>(Rigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        if (i++ != 2) return;
        if constexpr (std::is_same_v<typename Entry::Params, test::BeltRigParams>) {
            SolverOptions o;
            o.rtol = 1e-10;
            o.atol = 1e-12;
            run = simulate(typename Entry::template of<Coulomb>(p, Coulomb(mu_k, mu_s)), 5.0, o);
        }
    });
    REQUIRE(run.completed);
    for (const Event& e : run.events)
        if (e.mode_after_name == "stick" && e.time > 0.0) starts.push_back(e.time);
    REQUIRE(starts.size() >= 5);
    const double period = belt_period(p, mu_k, mu_s);  // 0.2 + 3 pi / 20 s = 0.6712 s here
    // the first stick comes from rest (x = 0), the later ones from 2 x_k - x_s: a cycle from the second on
    for (std::size_t k = 2; k < starts.size(); ++k) CHECK(starts[k] - starts[k - 1] == Approx(period).epsilon(1e-6));
    // after breaking away at x_s with the belt's speed, the block swings about x_k with amplitude
    // sqrt((x_s - x_k)^2 + (v_b / w)^2): its largest extension
    const double x_s = mu_s * p.normal_force / p.stiffness, x_k = mu_k * p.normal_force / p.stiffness;
    const double reach = std::hypot(x_s - x_k, p.belt_speed / std::sqrt(p.stiffness / p.mass));
    SolverOptions dense;
    dense.rtol = 1e-10;
    dense.atol = 1e-12;
    for (int k = 0; k <= 5000; ++k) dense.output_times.push_back(5.0 * k / 5000);
    const Result sampled = simulate(test::BeltRig<Coulomb>(p, Coulomb(mu_k, mu_s)), 5.0, dense);
    double x_max = 0.0;
    for (double x : sampled.column_values("position")) x_max = std::max(x_max, x);
    CHECK(x_max == Approx(x_k + reach).epsilon(1e-5));
    // energy: belt work = mechanical energy change + friction work
    const std::size_t last = run.rows() - 1;
    const double x = run.state(last, 0), v = run.state(last, 1);
    const double energy = 0.5 * p.mass * v * v + 0.5 * p.stiffness * x * x;
    CHECK(run.state(last, run.column("belt_work")) ==
          Approx(energy + run.state(last, run.column("friction_work"))).epsilon(1e-6));
}
