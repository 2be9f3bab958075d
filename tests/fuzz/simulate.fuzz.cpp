// Fuzz target (issue 11): bytes -> a friction law, a rig and solver options -> construct and run a short
// simulation. Every input must end in one of: InvalidParameter (bad input, named), SimulationError (a stop with
// its time and partial result), or a completed Result whose every value is finite. Anything else (a crash, a
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

#include <frictionsim/simulate.hpp>

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

template <class Law>
void run_rigs(const Law& law, Bytes& in) {
    const SolverOptions o = options(in);
    const double t_end = in.byte() & 1 ? in.number() : 0.05;
    const std::size_t which = in.byte() % (TabledRigs::size + 1);
    if (which == TabledRigs::size) {  // the kinematic rig, built from signals
        if constexpr (Law::has_stick) {
            if (law.karnopp_band() > 0.0) return;  // rejected by the kinematic rig; checked elsewhere
        }
        const HarmonicSlidingVelocity v(in.number(), in.number(), in.number());
        require_finite(simulate(KinematicRig<Law, HarmonicSlidingVelocity>(law, v, ConstantSignal(in.number())),
                                t_end, o));
        return;
    }
    std::size_t i = 0;
    for_each_rig(TabledRigs{}, [&](auto tag) {
        using Rig = typename decltype(tag)::template of<Law>;
        if (i++ != which) return;
        const auto p = params_from<typename Rig::Params>(Rig::Params::fields(), in);
        require_finite(simulate(Rig(p, law), t_end, o));
    });
}

/// A law of the engine's list from the bytes: each field of its table either keeps its default or takes a number.
template <class Law>
Law law_from(Bytes& in) {
    return Law(params_from<typename Law::Params>(Law::fields, in));
}

void run(Bytes& in) {
    const std::size_t which = in.byte() % EngineLaws::size;
    std::size_t i = 0;
    for_each_type(EngineLaws{}, [&](auto tag) {
        if (i++ == which) run_rigs(law_from<typename decltype(tag)::type>(in), in);
    });
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
