// The fuzz target's seed corpus (tests/fuzz/corpus) replayed through its entry point (simulate.fuzz.cpp) in the
// suite built with FRICTIONSIM_BUILD_FUZZERS (scripts/check's sanitized build): every seed must end in a named
// rejection, a stop with its time, or a finite completed result. A defect aborts the process ("fuzz defect: ..."),
// and Catch2 names the seed; a sanitizer report fails the case.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "catch.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

TEST_CASE("fuzz target: every seed of its corpus replays to a named rejection or a finite result", "[fuzz]") {
    std::vector<std::filesystem::path> seeds;  // ctest runs the suite in tests/
    for (const auto& entry : std::filesystem::directory_iterator("fuzz/corpus"))
        if (entry.is_regular_file()) seeds.push_back(entry.path());
    std::sort(seeds.begin(), seeds.end());
    REQUIRE(seeds.size() >= 60);  // the committed seeds: a missing folder or a wrong working directory fails here
    for (const auto& seed : seeds) {
        INFO("seed " << seed.filename().string());
        std::ifstream file(seed, std::ios::binary);
        REQUIRE(file);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
        CHECK(LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()) == 0);
    }
}
