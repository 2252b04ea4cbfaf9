// Norms the tests compare answers with.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace ode_bpp::problems {

/// max_i |a_i - b_i| over the common length.
inline double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
    double d = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) d = std::max(d, std::abs(a[i] - b[i]));
    return d;
}

/// max_i |a_i|.
inline double inf_norm(const std::vector<double>& a) {
    double m = 0;
    for (double v : a) m = std::max(m, std::abs(v));
    return m;
}

}  // namespace ode_bpp::problems
