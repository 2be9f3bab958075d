// The default memory budget of a run's recorded output: a share of the memory this process may use, so that a long
// field-scale run stops with its partial result before it takes the machine (SolverOptions::max_output_bytes).
#pragma once

#include <cstddef>
#include <cstdio>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace frictionsim::detail {

/// The machine's physical memory [bytes], 0 when it cannot be read.
inline std::size_t physical_memory_bytes() {
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page);
#endif
    return 0;
}

/// A container's memory limit [bytes] (cgroup v2 memory.max, else v1 memory.limit_in_bytes), 0 when there is none.
inline std::size_t container_memory_limit() {
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::FILE* f = std::fopen(path, "r");
        if (f == nullptr) continue;
        unsigned long long limit = 0;
        const bool read = std::fscanf(f, "%llu", &limit) == 1;  // "max" (no limit) does not read as a number
        std::fclose(f);
        if (read && limit > 0) return static_cast<std::size_t>(limit);
    }
    return 0;
}

/// The memory this process may use: the physical memory, or a container's limit where that is lower.
inline std::size_t usable_memory_bytes() {
    const std::size_t physical = physical_memory_bytes(), limit = container_memory_limit();
    return limit > 0 && (physical == 0 || limit < physical) ? limit : physical;
}

/// An eighth of the usable memory (2 GiB where it cannot be read): the Python package copies the rows once more into
/// NumPy arrays, and a sweep runs one simulation per core.
inline std::size_t default_output_bytes() {
    const std::size_t memory = usable_memory_bytes();
    return memory > 0 ? memory / 8 : std::size_t{2} << 30;
}

}  // namespace frictionsim::detail
