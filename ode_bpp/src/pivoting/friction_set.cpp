#include "pivoting/friction_set.h"

#include <algorithm>
#include <cmath>

namespace ode_bpp::pivoting {

namespace {

/// Row k's distance from consistency with its target (FrictionSet::consistent).
double inconsistency(int i, double target, const std::vector<RowState>& states, const std::vector<double>& x) {
    if (states[i] == RowState::Free) return std::max(0.0, std::abs(x[i]) - target);
    return std::abs(std::abs(x[i]) - target);  // x_i sits at its bound: that bound must be the target
}

}  // namespace

void FrictionSet::clear() {
    rows.clear();
    normal_of.clear();
    mu.clear();
}

std::vector<double> FrictionSet::targets(const std::vector<double>& x) const {
    std::vector<double> target(rows.size());
    for (std::size_t k = 0; k < target.size(); ++k) {
        const double normal = x[normal_of[k]];
        target[k] = normal == 0 ? 0.0 : std::abs(mu[k] * normal);
    }
    return target;
}

void FrictionSet::set_bounds(BoxedLcp& lcp, const std::vector<double>& bound) const {
    for (std::size_t k = 0; k < bound.size(); ++k) {
        lcp.hi[rows[k]] = bound[k];
        lcp.lo[rows[k]] = -bound[k];
    }
}

std::vector<double> FrictionSet::bounds(const BoxedLcp& lcp) const {
    std::vector<double> bound(rows.size());
    for (std::size_t k = 0; k < bound.size(); ++k) bound[k] = lcp.hi[rows[k]];
    return bound;
}

void FrictionSet::link(BoxedLcp& lcp) const {
    const auto n = static_cast<std::size_t>(lcp.n());
    lcp.friction_normal.assign(n, -1);
    lcp.friction_mu.assign(n, 0.0);
    for (std::size_t k = 0; k < rows.size(); ++k)
        if (std::isfinite(mu[k])) {
            lcp.friction_normal[rows[k]] = normal_of[k];
            lcp.friction_mu[rows[k]] = std::abs(mu[k]);
        }
}

bool FrictionSet::consistent(const BoxedLcp& lcp, double tolerance, const std::vector<RowState>& states,
                             const std::vector<double>& x) const {
    std::vector<double> scale;
    lcp.A->abs_multiply(x, lcp.shift, scale);
    const auto x_tolerance = [&](int i) {
        return tolerance * (scale[i] + std::abs(lcp.b[i])) / (lcp.A->diag(i) + lcp.shift);
    };
    const std::vector<double> target = targets(x);
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const int i = rows[k];
        const double normal_tolerance = std::isfinite(mu[k]) ? std::abs(mu[k]) * x_tolerance(normal_of[k]) : 0.0;
        if (inconsistency(i, target[k], states, x) > std::max(x_tolerance(i), normal_tolerance)) return false;
    }
    return true;
}

}  // namespace ode_bpp::pivoting
