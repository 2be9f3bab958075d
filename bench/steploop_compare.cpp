// Issue 22 item 4 (the step loop written once): runs a set of rigs, laws, methods and options through simulate()
// and writes every field of each Result (times, states, friction, modes, events with their states, stop events,
// stats, status, message, t_reached) as hexadecimal floats, one line per field. Built twice, once against the
// headers before a change and once after (-I picks the tree), the two outputs compared byte for byte are the
// runs compared with == . Not in the default build:
//   c++ -O2 -std=c++17 -DFRICTIONSIM_EIGEN=1 -I<include tree> -isystem /usr/include/eigen3
//       bench/steploop_compare.cpp -lsundials_cvode -lsundials_nvecserial ... -o compare
#include <cstdio>
#include <string>
#include <vector>

#include <frictionsim/simulate.hpp>
#include <frictionsim/string/string_rig.hpp>
#include <frictionsim/string/string_rig_params.hpp>

using namespace frictionsim;

namespace {

void put(const char* what, const std::vector<double>& v) {
    std::printf("%s %zu", what, v.size());
    for (double x : v) std::printf(" %a", x);
    std::printf("\n");
}

void put_events(const char* what, const std::vector<Event>& events) {
    std::printf("%s %zu\n", what, events.size());
    for (const Event& e : events) {
        std::printf(" %a %d %s %d %d %s %s %d %d\n", e.time, e.switching_function, e.name.c_str(), e.mode_before,
                    e.mode_after, e.mode_before_name.c_str(), e.mode_after_name.c_str(), e.stop_condition,
                    e.direction);
        put("  before", e.state_before);
        put("  after", e.state_after);
    }
}

void dump(const Result& r) {
    put("t", r.t);
    put("states", r.states);
    put("friction", r.friction_force);
    std::printf("mode %zu", r.mode.size());
    for (int m : r.mode) std::printf(" %d", m);
    std::printf("\n");
    put_events("events", r.events);
    put_events("stop_events", r.stop_events);
    const SolverStats& s = r.stats;
    std::printf("stats %ld %ld %ld %ld %ld %ld %ld\n", s.steps, s.rhs_evaluations, s.jacobian_evaluations,
                s.guard_evaluations, s.error_test_failures, s.restarts, s.events);
    std::printf("status %d %d %a %s\n", r.completed ? 1 : 0, r.status, r.t_reached, r.message.c_str());
    for (const std::string& w : r.warnings) std::printf("warning %s\n", w.c_str());
}

template <class Model>
void run(const char* label, const Model& model, double t_end, SolverOptions o, Method method) {
    o.method = method;
    std::printf("== %s %s\n", label, method == Method::rosenbrock ? "rosenbrock" : "dormand_prince");
    try {
        dump(simulate(model, t_end, o));
    } catch (const SimulationError& e) {  // a failed run keeps its partial result
        std::printf("threw %s\n", e.what());
        if (e.partial()) dump(*e.partial());
    } catch (const std::exception& e) {
        std::printf("threw %s\n", e.what());
    }
}

template <class Model>
void both(const char* label, const Model& model, double t_end, const SolverOptions& o) {
    run(label, model, t_end, o, Method::dormand_prince);
    run(label, model, t_end, o, Method::rosenbrock);
}

SolverOptions tolerance(double rtol) {
    SolverOptions o;
    o.rtol = rtol;
    o.atol = 1e-4 * rtol;
    return o;
}

std::vector<double> grid(double t_end, int n) {
    std::vector<double> t;
    for (int i = 0; i <= n; ++i) t.push_back(t_end * i / n);
    return t;
}

DrillString pipe_string(double length) {
    PipeSection s;
    s.length = length;
    return DrillString({s});
}

/// tests/string_rig.test.cpp's stick-slip string: 1000 m at 60 degrees, PI top drive, velocity-weakening bit.
StringRig<Coulomb, VelocityWeakeningBit> string_rig(std::size_t n) {
    StringRigParams p;
    p.inclination = pi / 3.0;
    p.damping_time = 2e-3;
    p.end_inertia = 40.0;
    p.end_mass = 20e3;
    p.surface_speed = 4.0;
    p.top_drive_inertia = 300.0;
    p.proportional_gain = 3e3;
    p.integral_gain = 1e3;
    StringRigSetup s;
    s.elements = n;
    NavarroLopezBit::Params b;
    b.viscous_damping = 0.0;
    return StringRig<Coulomb, VelocityWeakeningBit>(pipe_string(1000.0), p, s, Coulomb(0.2, 0.3),
                                                    VelocityWeakeningBit(NavarroLopezBit(b), 6e4));
}

}  // namespace

int main() {
    const AxialRig<Coulomb> block(spring_block_params(0.5, 200.0, 0.05), Coulomb(0.4, 0.6));
    {
        SolverOptions o = tolerance(1e-8);
        o.output_times = grid(20.0, 400);
        o.record_event_states = true;
        both("axial coulomb stick-slip", block, 20.0, o);
        both("axial coulomb stick-slip, loose", block, 20.0, tolerance(1e-4));
    }
    {
        const AxialRig<Dahl> rig(AxialRigParams{}, Dahl(0.41, 4e4));
        SolverOptions o = tolerance(1e-8);
        o.output_times = grid(2.0, 2000);
        both("axial dahl", rig, 2.0, o);
        SolverOptions every = tolerance(1e-6);
        every.record_steps = true;
        both("axial dahl, every step", rig, 0.3, every);
    }
    {
        const AxialRig<LuGre> rig(canudas_de_wit_1995_params(), LuGre(canudas_de_wit_1995_lugre()));
        SolverOptions o = tolerance(1e-8);
        o.output_times = grid(20.0, 200);
        both("axial lugre", rig, 20.0, o);
    }
    {
        const TorsionalRig<decltype(paper001_fig7_friction())> rig(TorsionalRigParams{}, paper001_fig7_friction());
        SolverOptions o;
        o.rtol = 1e-8;
        o.atol = 1e-10;
        o.output_times = grid(30.0, 3000);
        both("torsional hysteretic stick-slip", rig, 30.0, o);
        const TorsionalRig<Stribeck> stribeck(TorsionalRigParams{},
                                              Stribeck(Stribeck::Params{0.22, 0.3566, 0.3, 1.0, 0.0, 0.0}));
        both("torsional stribeck stick-slip", stribeck, 30.0, o);
    }
    {
        SolverOptions o = tolerance(1e-6);
        o.output_times = grid(10.0, 100);
        both("string rig, 50 elements", string_rig(50), 10.0, o);
    }
    {
        SolverOptions o = tolerance(1e-8);
        StopCondition level;
        level.state = block.state_names()[0];
        level.level = 0.1;
        level.direction = 1;
        level.terminal = false;
        StopCondition stick;
        stick.mode = "stick";
        o.stop_conditions = {level, stick};
        o.output_times = grid(20.0, 200);
        both("stop conditions: a level (logged), a switch into stick (terminal)", block, 20.0, o);
        SolverOptions few = tolerance(1e-8);
        few.max_steps = 300;
        both("max_steps exceeded: the partial result", block, 20.0, few);
        both("a span of ulps", block, 1e-300, tolerance(1e-8));
    }
    return 0;
}
