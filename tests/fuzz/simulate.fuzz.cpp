// Fuzz target (issue 11): bytes -> a friction law, a rig and solver options -> construct and run a short
// simulation; a first byte 0xFF draws a field model instead (issue 22): the time-stepping string of EngineRigs (the
// Aarsnes-Shor TorsionalString) with its treatment (captured / exact bit, on or off bottom) and a time-stepping
// method, or a rig of EngineRigs built from its table alone (the Navarro-Lopez strings); a first byte 0xFE the
// event-driven string of EngineRigs (StringRig: a wall law, its set-up, off bottom or a bit on bottom; issue 23: in
// a surveyed well, 2-4 stations of drawn inclinations, its node inclinations and soft-string wall forces). Every rig
// drawn is an entry of EngineRigs (rigs/rigs.hpp), by kind, so a rig added there is fuzzed; the byte layout of the
// committed seeds (tests/fuzz/corpus) is kept (no seed before 0xFE's branch began with 0xFE). Every input must end
// in one of: InvalidParameter (bad input, named), SimulationError (a stop with its time and partial result), or a
// completed Result whose every value is finite. Anything else (a crash, a sanitizer report, another exception, a
// "completed" run with NaN) aborts, so libFuzzer reports it.
//
// This file reads the first byte and hands the input to its case (fuzz_input.hpp); the cases are compiled in
// parts (cases.fuzz.cpp, one object per part). Built two ways: with clang's libFuzzer (scripts/fuzz), and into the
// Catch2 suite (FRICTIONSIM_BUILD_FUZZERS), where corpus.test.cpp replays the seed corpus through the entry point
// (scripts/check runs it under ASan + UBSan).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <utility>

#include "fuzz_input.hpp"

using namespace frictionsim;
using namespace frictionsim::fuzz;

namespace {

template <std::size_t... P>
void run_case_in_part(std::size_t c, Bytes& in, std::index_sequence<P...>) {
    ((c % parts == P ? run_case<P>(c, in) : void()), ...);
}

void run(Bytes& in) {
    const std::uint8_t first = in.byte();
    std::size_t c = 0;
    if (first == 0xFF) c = field_case;
    else if (first == 0xFE) c = string_case + in.byte() % EngineLaws::size;
    else c = lab_case + first % EngineLaws::size;
    run_case_in_part(c, in, std::make_index_sequence<parts>{});
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
