#include "unbounded_friction.h"

#include <limits>

#include "ode_bpp/residuals.h"

namespace ode_bpp {

bool has_unbounded_friction(const Problem& problem) {
    if (problem.findex == nullptr) return false;
    for (int i = problem.nub; i < problem.n; ++i)
        if (unbounded_friction_row(problem, i)) return true;
    return false;
}

Problem UnboundedFriction::view(const Problem& problem) {
    const auto n = static_cast<std::size_t>(problem.n);
    findex_.assign(problem.findex, problem.findex + n);
    lo_.resize(n);
    hi_.resize(n);
    for (int i = 0; i < problem.n; ++i) {
        const bool unbounded = unbounded_friction_row(problem, i);
        lo_[i] = unbounded ? -std::numeric_limits<double>::infinity() : problem.lo[i];
        hi_[i] = problem.hi[i];  // +inf for the rows turned unbounded
        if (unbounded) findex_[i] = -1;
    }
    Problem q = problem;
    q.findex = findex_.data();
    q.lo = ConstStrided{lo_.data(), 1};
    q.hi = ConstStrided{hi_.data(), 1};
    return q;
}

}  // namespace ode_bpp
