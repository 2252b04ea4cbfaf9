// bench/report/physical_limit.h: the least work of a direct method that knows the answer's index
// set (the "physical limit"): one Cholesky factorization of the final A_FF in envelope
// (skyline) storage plus one solve with it, timed alone.
#pragma once

#include <cstdint>
#include <vector>

#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"

namespace ode_bpp::bench {

/// Median over `repeat` rounds of the time [us] of skyline_cholesky + skyline_solve on A_FF,
/// F = the rows whose state is Free, in the file's Cuthill-McKee order (its constraint graph, as
/// bench_fig5 draws it) restricted to F. Everything else (extracting A_FF, the order, loading the
/// envelope) is done beforehand and not timed. Each round factors enough prepared copies of the
/// envelope to last well above the clock's resolution and reports the time per copy.
/// Returns 0 when F is empty and NaN when A_FF is not positive definite in floating point.
double physical_limit_us(const MlcpFile& file, const std::vector<RowState>& states, int repeat);

/// Calls per timed round of a kernel that touches `entries_per_call` stored entries: enough for
/// about 2^18 entries per round (far above the clock's resolution even for a 1-row island, within
/// the second-level cache of most machines), at least 1 and at most 2000.
int calls_per_round(std::int64_t entries_per_call);

/// The median of the rounds' times (the upper one of an even count); times: non-empty.
double median_round(std::vector<double> times);

}  // namespace ode_bpp::bench
