#include "peer_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ode_bpp::peers {

bool DenseMlcp::has_friction() const {
    return std::any_of(findex.begin(), findex.end(), [](int f) { return f >= 0; });
}

int ode_padded_stride(int n) { return n > 1 ? ((n - 1) | 3) + 1 : n; }

DenseMlcp dense_copy(const Problem& problem, int stride) {
    const int n = problem.n;
    DenseMlcp d;
    d.n = n;
    d.nub = problem.nub;
    d.stride = stride > 0 ? stride : n;
    d.A.assign(static_cast<std::size_t>(n) * d.stride, 0.0);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j <= i; ++j) {
            const double a = problem.A[static_cast<std::ptrdiff_t>(i) * problem.lda + j];
            d.A[static_cast<std::size_t>(i) * d.stride + j] = a;
            d.A[static_cast<std::size_t>(j) * d.stride + i] = a;
        }
    }
    const double inf = std::numeric_limits<double>::infinity();
    d.b.resize(n);
    d.lo.resize(n);
    d.hi.resize(n);
    d.findex.assign(n, -1);
    for (int i = 0; i < n; ++i) {
        d.b[i] = problem.b[i];
        d.findex[i] = problem.findex ? problem.findex[i] : -1;
        const bool unbounded = i < problem.nub;
        d.hi[i] = unbounded ? inf : problem.hi[i];
        d.lo[i] = unbounded ? -inf : d.findex[i] >= 0 ? -problem.hi[i] : problem.lo[i];
    }
    return d;
}

namespace {

/// Solves `fixed` with the rows whose box is a single point (lo_i == hi_i, x_i = lo_i whatever
/// w_i) taken out: b_R -= A_Ri lo_i for the remaining rows R. Lemke's reformulation of a box
/// degenerates on a zero-width box (Bullet's then returns a wrong answer as a success); the
/// reduced problem has the same solution. x: n entries, start on entry, answer on return.
bool solve_without_pinned_rows(const DenseMlcp& fixed, const FixedBoundSolver& solver, double* x) {
    std::vector<int> kept;
    for (int i = 0; i < fixed.n; ++i) {
        if (fixed.lo[i] == fixed.hi[i]) x[i] = fixed.lo[i];
        else kept.push_back(i);
    }
    if (static_cast<int>(kept.size()) == fixed.n) return solver(fixed, x);
    DenseMlcp reduced;
    reduced.n = reduced.stride = static_cast<int>(kept.size());
    reduced.nub = 0;  // the unbounded rows keep their infinite bounds, which is what nub says
    reduced.A.resize(static_cast<std::size_t>(reduced.n) * reduced.n);
    reduced.findex.assign(reduced.n, -1);
    std::vector<double> y(reduced.n);
    for (int r = 0; r < reduced.n; ++r) {
        const int i = kept[r];
        const double* row = fixed.A.data() + static_cast<std::size_t>(i) * fixed.stride;
        double rhs = fixed.b[i];
        for (int j = 0; j < fixed.n; ++j) {
            if (fixed.lo[j] == fixed.hi[j]) rhs -= row[j] * fixed.lo[j];
        }
        for (int c = 0; c < reduced.n; ++c) reduced.A[static_cast<std::size_t>(r) * reduced.n + c] = row[kept[c]];
        reduced.b.push_back(rhs);
        reduced.lo.push_back(fixed.lo[i]);
        reduced.hi.push_back(fixed.hi[i]);
        y[r] = x[i];
    }
    const bool ok = solver(reduced, y.data());
    for (int r = 0; r < reduced.n; ++r) x[kept[r]] = y[r];
    return ok;
}

}  // namespace

bench::PeerStatus solve_frozen(const Problem& problem, const FixedBoundSolver& solver, double* x) {
    DenseMlcp fixed = dense_copy(problem);
    std::fill(x, x + problem.n, 0.0);
    if (!fixed.has_friction())
        return solve_without_pinned_rows(fixed, solver, x) ? bench::PeerStatus::Solved : bench::PeerStatus::Failed;
    const std::vector<int> findex = fixed.findex;
    const std::vector<double> mu = fixed.hi;
    std::fill(fixed.findex.begin(), fixed.findex.end(), -1);
    for (int i = 0; i < fixed.n; ++i) {
        if (findex[i] >= 0) fixed.lo[i] = fixed.hi[i] = 0.0;  // ODE lcp.cpp: friction waits for its normal
    }
    if (!solve_without_pinned_rows(fixed, solver, x)) return bench::PeerStatus::Failed;
    // The answer projected onto its box: a normal of -1e-15 (rounding) must give the friction rows
    // the point box [0, 0], not a box of width 1e-15 that Lemke-type peers cannot pivot in.
    for (int i = 0; i < fixed.n; ++i) x[i] = std::clamp(x[i], fixed.lo[i], fixed.hi[i]);
    for (int i = 0; i < fixed.n; ++i) {
        if (findex[i] < 0) continue;
        fixed.hi[i] = std::fabs(mu[i] * x[findex[i]]);
        fixed.lo[i] = -fixed.hi[i];
    }
    return solve_without_pinned_rows(fixed, solver, x) ? bench::PeerStatus::Solved : bench::PeerStatus::Failed;
}

void make_bounds_finite(DenseMlcp& problem) {
    double scale = 0.0;
    for (int i = 0; i < problem.n; ++i) {
        const double diagonal = problem.A[static_cast<std::size_t>(i) * problem.stride + i];
        if (diagonal > 0) scale = std::max(scale, std::fabs(problem.b[i]) / diagonal);
    }
    const double big = 1e6 * std::max(scale, std::numeric_limits<double>::min());
    for (int i = 0; i < problem.n; ++i) {
        problem.lo[i] = std::max(problem.lo[i], -big);
        problem.hi[i] = std::min(problem.hi[i], big);
    }
}

bool all_finite(const double* x, int n) {
    return std::all_of(x, x + n, [](double v) { return std::isfinite(v); });
}

}  // namespace ode_bpp::peers
