// The fuzz target's reading of its input (tests/fuzz/simulate.fuzz.cpp says what it draws): the byte reader, the
// defect report, the solver options, parameter tables and strings from bytes, and the cases' split over translation
// units. The cases (a law on the lab rigs, a law on the event-driven string, the field models) are compiled in
// FRICTIONSIM_FUZZ_PARTS objects of cases.fuzz.cpp, case c in part c % parts, so the target's instantiations (every
// law on every rig, each on three ODE methods) compile on every core instead of in one translation unit.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <frictionsim/rigs/rigs.hpp>
#include <frictionsim/simulate.hpp>

#ifndef FRICTIONSIM_FUZZ_PARTS
#error "FRICTIONSIM_FUZZ_PARTS (the number of objects of cases.fuzz.cpp) is set by tests/CMakeLists.txt and scripts/fuzz"
#endif

namespace frictionsim::fuzz {

inline constexpr std::size_t parts = FRICTIONSIM_FUZZ_PARTS;

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

[[noreturn]] inline void defect(const char* what) {
    std::fprintf(stderr, "fuzz defect: %s\n", what);
    std::abort();
}

inline void require_finite(const Result& r) {
    if (!r.completed) defect("a returned Result is not completed");
    for (double v : r.states)
        if (!std::isfinite(v)) defect("NaN or inf state in a completed Result");
    for (double v : r.friction_force)
        if (!std::isfinite(v)) defect("NaN or inf friction force in a completed Result");
}

inline SolverOptions options(Bytes& in) {
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

/// 1-2 pipe sections from their table.
inline DrillString string_from(Bytes& in) {
    std::vector<PipeSection> sections(1 + in.byte() % 2);
    for (PipeSection& s : sections) s = params_from<PipeSection>(PipeSection::fields(), in);
    return DrillString(sections);
}

/// The cases, in the byte layout's order: 0 the field models (first byte 0xFF), 1 + l the law l of EngineLaws on the
/// lab rigs (first byte l mod the laws), 1 + laws + l the law l on the event-driven string (first byte 0xFE, then l).
inline constexpr std::size_t field_case = 0;
inline constexpr std::size_t lab_case = 1;
inline constexpr std::size_t string_case = 1 + EngineLaws::size;
inline constexpr std::size_t cases = 1 + 2 * EngineLaws::size;

/// Runs case `c` (c % parts == Part) on the rest of the input; defined in cases.fuzz.cpp, one object per part.
template <std::size_t Part>
void run_case(std::size_t c, Bytes& in);

}  // namespace frictionsim::fuzz
