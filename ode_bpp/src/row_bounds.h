// A row's bounds at an iterate, inline for the loops that visit every row (the residual summary,
// projected Gauss-Seidel's sweeps). ode_bpp/residuals.h's effective_bounds is this function.
//
// Index space: the caller's original row order.
#pragma once

#include <cmath>
#include <limits>
#include <utility>

#include "ode_bpp/solver.h"
#include "unbounded_friction.h"

namespace ode_bpp {

/// (-inf, +inf) for rows < nub and friction rows of mu = +inf; +-|mu_i x[findex[i]]| for any
/// other friction row (0 when the normal impulse is 0, as ODE's Dantzig does); (lo_i, hi_i)
/// otherwise. x: n entries.
inline std::pair<double, double> bounds_at(const Problem& p, ConstStrided x, int i) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    if (i < p.nub || unbounded_friction_row(p, i)) return {-kInf, kInf};
    if (p.findex != nullptr && p.findex[i] >= 0) {
        const double normal = x[p.findex[i]];
        const double bound = normal == 0 ? 0.0 : std::abs(p.hi[i] * normal);
        return {-bound, bound};
    }
    return {p.lo[i], p.hi[i]};
}

}  // namespace ode_bpp
