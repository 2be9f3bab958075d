// Fuzz target (issue 11): bytes -> a friction law, a rig and solver options -> construct and run a short
// simulation; a first byte 0xFF draws a field model instead (issue 22): the time-stepping string of EngineRigs (the
// Aarsnes-Shor TorsionalString) with its treatment (captured / exact bit, on or off bottom) and a time-stepping
// method, or a rig of EngineRigs built from its table alone (the Navarro-Lopez strings); a first byte 0xFE the
// event-driven string of EngineRigs (StringRig: a wall law, its set-up, off bottom or a bit on bottom). Every rig
// drawn is an entry of EngineRigs (rigs/rigs.hpp), by kind, so a rig added there is fuzzed; the byte layout of the
// committed seeds (tests/fuzz/corpus) is kept (no seed before 0xFE's branch began with 0xFE). Every input must end in one of: InvalidParameter (bad input, named), SimulationError (a
// stop with its time and partial result), or a completed Result whose every value is finite. Anything else (a crash, a
// sanitizer report, another exception, a "completed" run with NaN) aborts, so libFuzzer reports it.
//
// Built two ways: with clang's libFuzzer (scripts/fuzz), and as a plain program that replays files given on the
// command line (FRICTIONSIM_FUZZ_REPLAY; scripts/check runs the seed corpus under ASan + UBSan).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <vector>

#include <frictionsim/rigs/rigs.hpp>
#include <frictionsim/simulate.hpp>
#include <frictionsim/string/string_model.hpp>
#include <frictionsim/string/torsional_string.hpp>

using namespace frictionsim;

namespace {

/// Reads the input front to back; past its end every value is 0 (so short inputs still run).
class Bytes {
public:
    Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    double number() {  // raw IEEE doubles: NaN, inf, denormals and huge values all reachable
        double v = 0.0;
        std::uint8_t raw[8] = {};
        for (auto& b : raw) b = byte();
        std::memcpy(&v, raw, sizeof v);
        return v;
    }

private:
    const std::uint8_t* data_;
    std::size_t size_, at_ = 0;
};

[[noreturn]] void defect(const char* what) {
    std::fprintf(stderr, "fuzz defect: %s\n", what);
    std::abort();
}

void require_finite(const Result& r) {
    if (!r.completed) defect("a returned Result is not completed");
    for (double v : r.states)
        if (!std::isfinite(v)) defect("NaN or inf state in a completed Result");
    for (double v : r.friction_force)
        if (!std::isfinite(v)) defect("NaN or inf friction force in a completed Result");
}

SolverOptions options(Bytes& in) {
    SolverOptions o;
    const std::uint8_t m = in.byte() % 3;
    o.method = m == 0 ? Method::dormand_prince : m == 1 ? Method::cvode_bdf : Method::cvode_adams;
    if (in.byte() & 1) o.rtol = in.number();
    if (in.byte() & 1) o.atol = in.number();
    o.max_steps = 20000;  // bounded: a fuzz input may not take long
    o.max_output_rows = 5000;
    o.timeout = 2.0;
    return o;
}

/// A parameter struct from the bytes: each field of its table either keeps its default or takes a number.
template <class Params, class Fields>
Params params_from(const Fields& fields, Bytes& in) {
    Params p{};
    for (const auto& f : fields)
        if (in.byte() & 1) p.*(f.member) = in.number();
    return p;
}

/// A rig of EngineRigs built with `law`: the law rigs in the list's order, then the kinematic rig (the byte layout
/// of the seed corpus: its index comes after the law rigs').
template <class Law>
void run_rigs(const Law& law, Bytes& in) {
    constexpr std::size_t law_rigs = count_rigs<RigConstruction::law>(EngineRigs{});
    const SolverOptions o = options(in);
    const double t_end = in.byte() & 1 ? in.number() : 0.05;
    const std::size_t which = in.byte() % (law_rigs + 1);
    if (which == law_rigs) {  // the kinematic rig, built from signals
        if constexpr (Law::has_stick) {
            if (law.karnopp_band() > 0.0) return;  // rejected by the kinematic rig; checked elsewhere
        }
        const HarmonicSlidingVelocity v(in.number(), in.number(), in.number());
        using Kinematic = signal_rig::of<Law, HarmonicSlidingVelocity>;
        require_finite(simulate(Kinematic(law, v, ConstantSignal(in.number())), t_end, o));
        return;
    }
    std::size_t i = 0;
    for_each_rig<RigConstruction::law>(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        using Rig = typename Entry::template of<Law>;
        if (i++ != which) return;
        const auto p = params_from<typename Entry::Params>(Entry::Params::fields(), in);
        require_finite(simulate(Rig(p, law), t_end, o));
    });
}

/// A law of the engine's list from the bytes: each field of its table either keeps its default or takes a number.
template <class Law>
Law law_from(Bytes& in) {
    return Law(params_from<typename Law::Params>(Law::fields, in));
}

/// 1-2 pipe sections from their table.
DrillString string_from(Bytes& in) {
    std::vector<PipeSection> sections(1 + in.byte() % 2);
    for (PipeSection& s : sections) s = params_from<PipeSection>(PipeSection::fields(), in);
    return DrillString(sections);
}

/// The event-driven string of EngineRigs with `law` on its walls: 1-2 sections, its table, a small set-up (1-8
/// elements, PI or prescribed drive, torsion or also axial with either hoisting, wall contacts or none), off bottom
/// or on bottom with the velocity-weakening or the Detournay bit (tables and weight drawn), on an ODE method.
template <class Law>
void run_string(const Law& law, Bytes& in) {
    static_assert(count_rigs<RigConstruction::string>(EngineRigs{}) == 1,
                  "the byte layout draws one event-driven string: give a second its own byte");
    for_each_rig<RigConstruction::string>(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        const DrillString string = string_from(in);
        const auto p = params_from<typename Entry::Params>(Entry::Params::fields(), in);
        StringRigSetup setup;
        setup.elements = 1 + in.byte() % 8;
        const std::uint8_t flags = in.byte();
        setup.top_drive = flags & 1 ? TopDrive::prescribed_speed : TopDrive::pi_motor;
        setup.axial = (flags & 2) != 0;
        setup.hoisting = flags & 4 ? Hoisting::hook_load : Hoisting::hook_speed;
        setup.wall_contacts = (flags & 8) == 0;
        const SolverOptions o = options(in);
        const double t_end = in.byte() & 1 ? in.number() : 0.05;
        const std::uint8_t bit = in.byte() % 3;
        if (bit == 0) {
            require_finite(simulate(typename Entry::template of<Law>(string, p, setup, law), t_end, o));
        } else if (bit == 1) {
            const NavarroLopezBit b(params_from<NavarroLopezBit::Params>(NavarroLopezBit::fields, in));
            using Rig = typename Entry::template of<Law, VelocityWeakeningBit>;
            require_finite(simulate(Rig(string, p, setup, law, VelocityWeakeningBit(b, in.number())), t_end, o));
        } else {
            const DetournayBit b(params_from<DetournayBit::Params>(DetournayBit::fields, in));
            using Rig = typename Entry::template of<Law, DetournayBitOnRock>;
            require_finite(simulate(Rig(string, p, setup, law, DetournayBitOnRock(b, in.number())), t_end, o));
        }
    });
}

/// A time-stepping model of EngineRigs: a small TorsionalString (1-16 elements, sections and parameters from their
/// tables), the bit's treatment, Moreau-Jean or the explicit projection with a drawn step, the PI or a prescribed
/// speed, the active set or projected Gauss-Seidel, or the string model's exact treatment; or a rig of EngineRigs
/// built from its table alone (a Navarro-Lopez string) on an ODE method.
void run_field(Bytes& in) {
    static_assert(count_rigs<RigConstruction::time_stepping>(EngineRigs{}) == 1,
                  "the byte layout draws one time-stepping model: give a second its own byte");
    constexpr std::size_t table_rigs = count_rigs<RigConstruction::table>(EngineRigs{});
    const std::size_t which = in.byte() % (table_rigs + 1);
    if (which > 0) {  // a rig of EngineRigs built from its table alone (the Navarro-Lopez strings)
        const SolverOptions o = options(in);
        const double t_end = in.byte() & 1 ? in.number() : 0.5;
        std::size_t i = 0;
        for_each_rig<RigConstruction::table>(EngineRigs{}, [&](auto tag) {
            using Entry = typename decltype(tag)::type;
            if (++i != which) return;
            const auto p = params_from<typename Entry::Params>(Entry::Params::fields(), in);
            require_finite(simulate(typename Entry::type(p), t_end, o));
        });
        return;
    }
    for_each_rig<RigConstruction::time_stepping>(EngineRigs{}, [&](auto tag) {
        using Entry = typename decltype(tag)::type;
        const DrillString string = string_from(in);
        const auto p = params_from<typename Entry::Params>(Entry::Params::fields(), in);
        const std::size_t elements = 1 + in.byte() % 16;
        typename Entry::type model(string, p, elements);
        model.set_bit_treatment(in.byte() & 1 ? BitTreatment::exact : BitTreatment::captured);
        SolverOptions o;
        o.method = in.byte() & 1 ? Method::explicit_projection : Method::moreau_jean;
        o.step = in.byte() & 1 ? in.number() : 1e-3;
        if (in.byte() & 1) o.theta = in.number();
        o.max_steps = 20000;
        o.max_output_rows = 5000;
        o.timeout = 2.0;
        const double t_end = in.byte() & 1 ? in.number() : 0.05;
        // read last, so the seeds made before keep their meaning (past the end a byte reads 0: the defaults)
        const std::uint8_t drive = in.byte();
        if (drive & 1) model.set_top_drive(TopDrive::prescribed_speed);
        if (drive & 2) o.contact_solver = ContactSolverChoice::projected_gauss_seidel;
        // then the string model's exact treatment (string/string_model.hpp: the StringRig of the same string on an
        // ODE method, its rows in the string's columns)
        if (in.byte() & 1) {
            const StringModel exact(model, StringTreatment::exact);
            SolverOptions e;
            e.max_steps = o.max_steps;
            e.max_output_rows = o.max_output_rows;
            e.timeout = o.timeout;
            return require_finite(simulate(exact, t_end, e));
        }
        require_finite(simulate(model, t_end, o));
    });
}

/// A law of the engine's list from the bytes, then `f(law)`.
template <class F>
void with_law(Bytes& in, std::size_t which, F&& f) {
    std::size_t i = 0;
    for_each_type(EngineLaws{}, [&](auto tag) {
        if (i++ == which) f(law_from<typename decltype(tag)::type>(in));
    });
}

void run(Bytes& in) {
    const std::uint8_t first = in.byte();
    if (first == 0xFF) return run_field(in);
    if (first == 0xFE) return with_law(in, in.byte() % EngineLaws::size, [&](const auto& law) { run_string(law, in); });
    with_law(in, first % EngineLaws::size, [&](const auto& law) { run_rigs(law, in); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Bytes in(data, size);
    try {
        run(in);
    } catch (const InvalidParameter&) {  // bad input, named: fine
    } catch (const SimulationError&) {   // a stop with its time: fine
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz defect: unexpected exception: %s\n", e.what());
        std::abort();
    }
    return 0;
}

#ifdef FRICTIONSIM_FUZZ_REPLAY
int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        std::ifstream file(argv[i], std::ios::binary);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    }
    std::printf("replayed %d input(s): no defect\n", argc - 1);
    return 0;
}
#endif
