#include "linalg/factor_error.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace ode_bpp::linalg {

double factor_error(const SkylineMatrix& La, const SkylineMatrix& Lb, const std::vector<char>& removed) {
    assert(La.n() == Lb.n());
    auto kept = [&removed](int k) { return removed.empty() || removed[k] == 0; };
    double sum_squares = 0.0;
    for (int k = 0; k < La.n(); ++k) {
        if (!kept(k)) continue;
        const int last = std::max(La.sky(k), Lb.sky(k));
        for (int r = k; r <= last; ++r) {
            if (!kept(r)) continue;
            const double difference = La.get(r, k) - Lb.get(r, k);
            sum_squares += difference * difference;
        }
    }
    return std::sqrt(sum_squares);
}

}  // namespace ode_bpp::linalg
