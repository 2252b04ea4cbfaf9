// bench/world/assembly_time.cpp
#include "assembly_time.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
#include <vector>

#include "linalg/symmetric_rows.h"
#include "ode/assemble.h"

namespace ode_bpp::bench {

namespace {

// Stored entries written per timed round, summed over the assemblies: as physical_limit.cpp
// sizes its rounds, far above the clock's resolution even for a 1-row island.
constexpr std::int64_t kEntriesPerRound = 1 << 18;
constexpr int kMaxAssemblies = 2000;

}  // namespace

double assembly_time_us(const dMLCP& island, int repeat) {
    if (!ode::has_sparse_form(island)) return std::numeric_limits<double>::quiet_NaN();
    linalg::SymmetricRows rows;
    ode::AssemblyBuffers buffers;
    ode::assemble_rows(island, rows, buffers);  // finds the pattern; the timed calls reuse it
    const std::int64_t entries = std::max<std::int64_t>(std::int64_t{rows.n()} + rows.off_diagonal_entries(), 1);
    const auto assemblies = static_cast<int>(std::clamp<std::int64_t>(kEntriesPerRound / entries, 1, kMaxAssemblies));
    std::vector<double> times;
    for (int round = 0; round < std::max(1, repeat); ++round) {
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < assemblies; ++k) ode::assemble_rows(island, rows, buffers);
        times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() /
                        assemblies);
    }
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

}  // namespace ode_bpp::bench
