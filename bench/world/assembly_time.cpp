// bench/world/assembly_time.cpp
#include "assembly_time.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "linalg/symmetric_rows.h"
#include "ode/assemble.h"
#include "physical_limit.h"

namespace ode_bpp::bench {

double assembly_time_us(const dMLCP& island, int repeat) {
    if (!ode::has_sparse_form(island)) return std::numeric_limits<double>::quiet_NaN();
    linalg::SymmetricRows rows;
    ode::AssemblyBuffers buffers;
    ode::assemble_rows(island, rows, buffers);  // finds the pattern; the timed calls reuse it
    // rounds sized as the physical limit's: entries written per assembly
    const int assemblies = calls_per_round(std::int64_t{rows.n()} + rows.off_diagonal_entries());
    std::vector<double> times;
    for (int round = 0; round < std::max(1, repeat); ++round) {
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < assemblies; ++k) ode::assemble_rows(island, rows, buffers);
        times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() /
                        assemblies);
    }
    return median_round(std::move(times));
}

}  // namespace ode_bpp::bench
