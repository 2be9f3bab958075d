// Friction laws, measured call by call: for every law the same operations on the same stream of inputs, so that
// the rows compare. Every law of the engine's list (EngineLaws, friction/laws.hpp) is registered at its parameter
// table's defaults, plus a Karnopp band and Dahl at alpha = 0.5. One function template (`register_law`) registers,
// per law:
//   <Law>/force             the friction force as a rig computes it: ContactSwitching<Law>::force (set-valued
//                           laws take their stick or slip branch, the stick branch clamping the force needed to
//                           stick), and for paper 001's eq 6 DiscContact<HystereticFriction>::respond (the
//                           per-branch implicit solve, branch_equation(...).root());
//   <Law>/state_derivative  dz/dt of the law's internal states. Registered only for laws with a state: a law
//                           without state has no such call, and no row is better than a row that times a no-op;
//   <Law>/guards            the switching functions the event loop evaluates after every step. Registered only for
//                           laws with guards: LuGre is smooth and has none.
// plus Hysteretic/torque, eq 6 evaluated explicitly at a given (w, dw/dt, N): what identification evaluates, not
// the rig (the rig cannot, dw/dt being unknown until the branch equation is solved).
//
// The stream (1024 points, one stick-slip cycle): a stick window with the force needed to stick ramping past the
// break-away level, a positive slip hump v ~ sin^2 (dense at low speed, so the Stribeck region and a Karnopp band
// are crossed), a second stick window, a negative hump; normal force +-10 %, internal states within the law's
// steady deflection. Each point's mode is the one the rig would pick there (initial_mode), so modes come in runs
// as in a simulation. Items are calls: items_per_second is calls per second and the `per_call` counter is the
// time of one call (independent calls, so this is throughput, not latency).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <frictionsim/friction/hysteretic.hpp>
#include <frictionsim/friction/laws.hpp>
#include <frictionsim/contact/switching.hpp>
#include <frictionsim/contact/disc_contact.hpp>
#include <frictionsim/papers.hpp>
#include <frictionsim/rigs/reference_setups.hpp>

using namespace frictionsim;

namespace {

constexpr std::size_t stream_length = 1024;
constexpr double pi = 3.14159265358979323846;

/// One point of the stream, dimensionless: velocity in [-1, 1] (0 in the stick windows), normal-force factor
/// around 1, load = (force or torque needed to stick) / scale, state in [-0.9, 0.9] of the steady deflection.
struct StreamPoint {
    double velocity, normal, load, state;
};

std::vector<StreamPoint> make_stream() {
    constexpr std::size_t stick_length = stream_length / 8, slip_length = stream_length * 3 / 8;
    std::vector<StreamPoint> stream;
    stream.reserve(stream_length);
    for (int side : {+1, -1}) {
        for (std::size_t j = 0; j < stick_length; ++j) {  // stick: load ramps to 0.75 (past every static level)
            const double x = (static_cast<double>(j) + 0.5) / stick_length;
            stream.push_back({0.0, 1.0, side * 0.75 * x, side * 0.9 * (2.0 * x - 1.0)});
        }
        for (std::size_t j = 0; j < slip_length; ++j) {  // slip hump; the load falls from 0.75 to 0.15
            const double x = (static_cast<double>(j) + 0.5) / slip_length, hump = std::sin(pi * x);
            stream.push_back({side * hump * hump, 1.0, side * (0.45 + 0.3 * std::cos(pi * x)),
                              side * (0.7 + 0.2 * hump)});
        }
    }
    for (std::size_t k = 0; k < stream.size(); ++k)
        stream[k].normal = 1.0 + 0.1 * std::sin(2.0 * pi * 3.0 * static_cast<double>(k) / stream_length);
    return stream;
}

/// One call's inputs in a law's units. `load` is the force needed to stick (N) for the engine's laws and the
/// shaft torque S (N m) for eq 6; `acceleration` is used by eq 6 only.
constexpr std::size_t max_states = 16;  // GMS 4 blocks; Leuven 12 (its turning-point memory)
struct Sample {
    double velocity, normal_force, load;
    std::array<double, max_states> z;
    double acceleration;
    int mode;
};

/// The law's steady sliding state at v_r = 0.05 m/s and normal force N (the scale of its internal states), found by
/// integrating its own state equation (explicit Euler, 1e-6 s steps, 0.5 s): one rule for every law of the list.
template <class Law>
std::array<double, max_states> steady_state(const Law& law, double normal_force) {
    std::array<double, max_states> z{}, dz{};
    if constexpr (Law::state_count > 0)
        for (int i = 0; i < 500000; ++i) {
            law.state_derivative(0.05, normal_force, z.data(), +1, dz.data());
            for (std::size_t j = 0; j < Law::state_count; ++j) z[j] += 1e-6 * dz[j];
        }
    return z;
}

/// An engine law on the path the axial and torsional rigs share (ContactSwitching), sliding at up to 0.05 m/s
/// under 90 N (paper 000's normal force).
template <class Law>
class SwitchingContact {
    using Switching = ContactSwitching<Law>;

public:
    static_assert(Law::state_count <= max_states, "Sample holds max_states internal states");
    static constexpr std::size_t state_count = Law::state_count;
    static constexpr std::size_t guard_count = Switching::guard_count;
    static constexpr bool has_stick_mode = Law::has_stick;

    explicit SwitchingContact(Law law) : law_(std::move(law)), steady_(steady_state(law_, 90.0)) {}

    Sample sample(const StreamPoint& p) const {
        Sample s{};
        s.velocity = 0.05 * p.velocity;
        s.normal_force = 90.0 * p.normal;
        s.load = p.load * s.normal_force;
        for (std::size_t j = 0; j < max_states; ++j) s.z[j] = p.state * p.normal * steady_[j];
        s.mode = Switching::initial_mode(law_, s.velocity, s.normal_force, s.z.data(), s.load);
        return s;
    }
    double force(const Sample& s) const {
        return Switching::force(law_, s.velocity, s.normal_force, s.z.data(), s.mode, s.load);
    }
    void state_derivative(const Sample& s, double* dz) const {
        law_.state_derivative(s.velocity, s.normal_force, s.z.data(), s.mode, dz);
    }
    void guards(const Sample& s, double* g) const {
        Switching::guards(law_, s.velocity, s.normal_force, s.mode, s.load, g);
    }

private:
    Law law_;
    std::array<double, max_states> steady_;
};

/// Paper 001's eq 6 on the torsional rig's disc (Fig. 7 set, J2 = 0.0149 kg m^2, N2 = 35 N): up to 14 rad/s,
/// shaft torque up to 1.5 N m, so that both slip branches and the stick band occur.
class HystereticContact {
public:
    static constexpr std::size_t state_count = 0;
    static constexpr std::size_t guard_count = DiscContact<HystereticFriction>::guard_count;
    static constexpr bool has_stick_mode = true;

    HystereticContact() : disc_(paper001_fig7_friction(), 0.1, normal_force) {}

    Sample sample(const StreamPoint& p) const {
        Sample s{};
        s.velocity = 14.0 * p.velocity;
        s.normal_force = normal_force;  // DiscContact holds N fixed: the explicit torque uses the same one
        s.load = 2.0 * p.load;
        s.mode = disc_.initial_mode(s.velocity, s.load, nullptr, inertia);
        s.acceleration = disc_.respond(s.velocity, s.load, nullptr, s.mode, inertia).acceleration;
        return s;
    }
    DiscResponse force(const Sample& s) const { return disc_.respond(s.velocity, s.load, nullptr, s.mode, inertia); }
    void guards(const Sample& s, double* g) const { disc_.guards(s.velocity, s.load, nullptr, s.mode, inertia, g); }
    double torque(const Sample& s) const {
        return disc_.law().torque(s.velocity, s.acceleration, s.normal_force);
    }

private:
    static constexpr double inertia = 0.0149, normal_force = 35.0;
    DiscContact<HystereticFriction> disc_;
};

/// Times `op(contact, sample)` over the whole stream per iteration.
template <class Contact, class Op>
void run(benchmark::State& state, const Contact& contact, const std::vector<Sample>& samples, Op op) {
    Contact c = contact;
    benchmark::DoNotOptimize(c);  // the law's parameters stay unknown to the optimiser
    for (auto _ : state)
        for (const Sample& s : samples) op(c, s);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(samples.size()));
    state.counters["per_call"] = benchmark::Counter(static_cast<double>(samples.size()),
                                                    benchmark::Counter::kIsIterationInvariantRate |
                                                        benchmark::Counter::kInvert);
}

/// The same operations for every law: force, state derivative (laws with a state), guards (laws with guards).
template <class Contact>
std::vector<Sample> register_law(const std::string& name, const Contact& contact) {
    std::vector<Sample> samples;
    for (const StreamPoint& p : make_stream()) samples.push_back(contact.sample(p));
    double stick_fraction = 0.0;
    for (const Sample& s : samples) stick_fraction += s.mode == 0 ? 1.0 : 0.0;
    stick_fraction /= static_cast<double>(samples.size());

    benchmark::RegisterBenchmark((name + "/force").c_str(), [=](benchmark::State& state) {
        run(state, contact, samples, [](const Contact& c, const Sample& s) {
            auto f = c.force(s);
            benchmark::DoNotOptimize(f);
        });
        if constexpr (Contact::has_stick_mode) state.counters["stick_fraction"] = stick_fraction;
    });
    if constexpr (Contact::state_count > 0) {
        benchmark::RegisterBenchmark((name + "/state_derivative").c_str(), [=](benchmark::State& state) {
            run(state, contact, samples, [](const Contact& c, const Sample& s) {
                double dz[Contact::state_count];
                c.state_derivative(s, dz);
                for (double& d : dz) benchmark::DoNotOptimize(d);
            });
        });
    }
    if constexpr (Contact::guard_count > 0) {
        benchmark::RegisterBenchmark((name + "/guards").c_str(), [=](benchmark::State& state) {
            run(state, contact, samples, [](const Contact& c, const Sample& s) {
                double g[Contact::guard_count];
                c.guards(s, g);
                for (double& v : g) benchmark::DoNotOptimize(v);
            });
        });
    }
    return samples;
}

int register_all() {
    // every law of the engine's list at its table's defaults, then variants worth their own row
    for_each_type(EngineLaws{}, [](auto tag) {
        using Law = typename decltype(tag)::type;
        register_law(Law::name, SwitchingContact<Law>(Law(typename Law::Params{})));
    });
    Stribeck::Params karnopp{};
    karnopp.karnopp_band = 1e-4;
    register_law("Karnopp", SwitchingContact<Stribeck>(Stribeck(karnopp)));
    register_law("Dahl_alpha0.5", SwitchingContact<Dahl>(Dahl(0.41, 4e4, 0.5)));
    const HystereticContact hysteretic;
    const std::vector<Sample> samples = register_law("Hysteretic", hysteretic);
    benchmark::RegisterBenchmark("Hysteretic/torque", [=](benchmark::State& state) {
        run(state, hysteretic, samples, [](const HystereticContact& c, const Sample& s) {
            double t = c.torque(s);
            benchmark::DoNotOptimize(t);
        });
    });
    return 0;
}

[[maybe_unused]] const int registered = register_all();

}  // namespace
