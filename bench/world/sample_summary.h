// bench/world/sample_summary.h: the statistics every timing of the world-step benchmarks reports.
#pragma once

#include <vector>

namespace ode_bpp::bench {

/// Median, mean and the slowest 1 % of a sample (NaN for an empty one).
struct SampleSummary {
    double median = 0;
    double mean = 0;
    /// Mean of the slowest ceil(1 % of n) values: the tail a frame budget must absorb.
    double slowest_percent = 0;
    double max = 0;
};

SampleSummary summarize(std::vector<double> values);

}  // namespace ode_bpp::bench
