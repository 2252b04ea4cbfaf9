// bench/world/sample_summary.cpp
#include "sample_summary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace ode_bpp::bench {

SampleSummary summarize(std::vector<double> values) {
    SampleSummary s;
    if (values.empty()) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        return {nan, nan, nan, nan};
    }
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size(), mid = n / 2;
    s.median = n % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
    s.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(n);
    const std::size_t tail = std::max<std::size_t>(1, (n + 99) / 100);
    s.slowest_percent = std::accumulate(values.end() - static_cast<std::ptrdiff_t>(tail), values.end(), 0.0) /
                        static_cast<double>(tail);
    s.max = values.back();
    return s;
}

}  // namespace ode_bpp::bench
