#include "residuals.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "row_bounds.h"
#include "unbounded_friction.h"

namespace ode_bpp {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double clamp_to(double v, std::pair<double, double> bounds) {
    return std::min(std::max(v, bounds.first), bounds.second);
}

double inf_norm(ConstStrided v, int n) {
    double m = 0;
    for (int i = 0; i < n; ++i) m = std::max(m, std::abs(v[i]));
    return m;
}

/// s_i = scale_i / A_ii in units of x; for a friction row at least |mu_i| s_n of its normal n,
/// since its bound mu_i |x_n| is known only to that scale (the solver's certificate,
/// FrictionSet::consistent in pivoting/friction_set.h, uses the same). Without it a friction row whose own
/// scale is rounding (x ~ 1e-13 beside a resting normal) read 0.5 on answers accurate to 1e-12.
template <typename Diagonal>
[[gnu::always_inline]] inline double row_scale(const Problem& p, Diagonal diag, const std::vector<double>& scale, int i) {
    double s = scale[i] / diag(i);
    if (i >= p.nub && p.findex != nullptr && p.findex[i] >= 0 && std::isfinite(p.hi[i])) {
        const int n = p.findex[i];
        s = std::max(s, std::abs(p.hi[i]) * scale[n] / diag(n));
    }
    return s;
}

/// Row i's effective bounds (bounds_at) and the bounds of the fixed-bound problem x implies
/// (Residuals::fixed_bound: +-|x_i| for a bounded friction row, the effective bounds for any other
/// row), from one look at its kind: unbounded, boxed, or a friction row.
struct RowBounds {
    std::pair<double, double> effective, implied;
    bool friction = false;  ///< findex[i] >= 0
};

// always_inline: summarize's three instantiations call it once per row, and GCC's -O2 left it
// out of line (a call per row, its result through memory: a tenth of a small island's summary)
[[gnu::always_inline]] inline RowBounds row_bounds(const Problem& p, ConstStrided x, int i) {
    const int normal = p.findex != nullptr ? p.findex[i] : -1;
    const std::pair<double, double> unbounded{-kInf, kInf};
    if (i < p.nub) return {unbounded, unbounded, normal >= 0};
    if (normal < 0) {
        const std::pair<double, double> box{p.lo[i], p.hi[i]};
        return {box, box, false};
    }
    const double mu = p.hi[i];
    if (mu == kInf) return {unbounded, unbounded, true};
    const double n = x[normal];
    const double bound = n == 0 ? 0.0 : std::abs(mu * n);
    const double xi = std::abs(x[i]);
    return {{-bound, bound}, {-xi, xi}, true};
}

/// Residuals from w = A x - b and scale = |A||x| + |b|; diag(i) = A_ii.
template <typename Diagonal>
Residuals summarize(const Problem& p, Diagonal diag, ConstStrided x, const std::vector<double>& w,
                    const std::vector<double>& scale, const std::vector<RowState>* states) {
    double natural = 0, fixed_bound = 0, scaled_natural = 0, scaled_fixed_bound = 0, free_rows = 0, friction = 0;
    for (int i = 0; i < p.n; ++i) {  // (local sums: w, x and the maxima could alias in memory)
        const RowBounds rb = row_bounds(p, x, i);
        const double xi = x[i], wi = w[i], di = diag(i);
        const double step = xi - wi, scaled_step = xi - wi / di;
        const double natural_i = std::abs(xi - clamp_to(step, rb.effective));
        const double scaled = std::abs(xi - clamp_to(scaled_step, rb.effective));
        // only a friction row's implied bounds differ from its effective ones (row_bounds)
        const double fixed_i = rb.friction ? std::abs(xi - clamp_to(step, rb.implied)) : natural_i;
        const double scaled_fixed = rb.friction ? std::abs(xi - clamp_to(scaled_step, rb.implied)) : scaled;
        natural = std::max(natural, natural_i);
        fixed_bound = std::max(fixed_bound, fixed_i);
        if (scaled > 0 || scaled_fixed > 0) {
            const double s_i = row_scale(p, diag, scale, i);
            if (scaled > 0) scaled_natural = std::max(scaled_natural, scaled / s_i);
            if (scaled_fixed > 0) scaled_fixed_bound = std::max(scaled_fixed_bound, scaled_fixed / s_i);
        }
        const bool free = states != nullptr ? (*states)[i] == RowState::Free
                                            : rb.effective.first < xi && xi < rb.effective.second;
        if (free) free_rows = std::max(free_rows, std::abs(wi));
        if (rb.friction) friction = std::max(friction, std::abs(xi) - rb.effective.second);
    }
    Residuals r;
    r.natural = natural;
    r.scaled_natural = scaled_natural;
    r.scaled_fixed_bound = scaled_fixed_bound;
    r.free = free_rows;
    r.friction = friction;
    const double b_scale = std::max(1.0, inf_norm(p.b, p.n));
    r.relative_natural = natural / b_scale;
    r.fixed_bound = fixed_bound / b_scale;
    return r;
}

/// A_ii of the dense form.
struct DenseDiagonal {
    const Problem& p;
    double operator()(int i) const { return p.A[static_cast<std::ptrdiff_t>(i) * p.lda + i]; }
};

/// All rows: row k is row k.
struct EveryRow {
    int operator[](int k) const { return k; }
};

/// dense_residual_vectors on the rows row[0 .. count) (ascending) alone.
template <typename Rows>
void dense_residual_pass(const Problem& p, ConstStrided x, Rows row, int count, double* w, double* scale) {
    for (int k = 0; k < count; ++k) {
        const int i = row[k];
        w[i] = DenseDiagonal{p}(i) * x[i];
        scale[i] = std::abs(w[i]);
    }
    // Row i's own terms are summed in registers: no earlier row adds to w_i, so each w_i still
    // sums A(i,i) x_i, then A(i,j) x_j for j < i, then A(k,i) x_k for k > i (the same bits as
    // one running sum in memory, which the compiler must reload after every store to w_j).
    for (int k = 1; k < count; ++k) {
        const int i = row[k];
        const double* a_i = p.A + static_cast<std::ptrdiff_t>(i) * p.lda;
        const double xi = x[i];
        double wi = w[i], si = scale[i];
        for (int l = 0; l < k; ++l) {
            const int j = row[l];
            const double to_i = a_i[j] * x[j], to_j = a_i[j] * xi;
            wi += to_i;
            si += std::abs(to_i);
            w[j] += to_j;
            scale[j] += std::abs(to_j);
        }
        w[i] = wi;
        scale[i] = si;
    }
    for (int k = 0; k < count; ++k) {
        const int i = row[k];
        w[i] -= p.b[i];
        scale[i] += std::abs(p.b[i]);
    }
}

}  // namespace

void dense_residual_vectors(const Problem& p, ConstStrided x, double* w, double* scale) {
    dense_residual_pass(p, x, EveryRow{}, p.n, w, scale);
}

void dense_residual_vectors_on(const Problem& p, ConstStrided x, const int* rows, int count, double* w, double* scale) {
    dense_residual_pass(p, x, rows, count, w, scale);
}

namespace {

void dense_residual_vectors(const Problem& p, ConstStrided x, std::vector<double>& w, std::vector<double>& scale) {
    w.resize(static_cast<std::size_t>(p.n));
    scale.resize(static_cast<std::size_t>(p.n));
    dense_residual_vectors(p, x, w.data(), scale.data());
}

}  // namespace

bool is_unbounded_friction_row(const Problem& p, int i) { return unbounded_friction_row(p, i); }

std::pair<double, double> effective_bounds(const Problem& p, ConstStrided x, int i) { return bounds_at(p, x, i); }

void residual_vectors(const Problem& p, const linalg::SymmetricRows& A, ConstStrided x, std::vector<double>& w,
                      std::vector<double>& scale) {
    w.assign(static_cast<std::size_t>(p.n), 0.0);
    scale.assign(static_cast<std::size_t>(p.n), 0.0);
    for (int i = 0; i < p.n; ++i) {  // (A x)_r - b_r, summed as the pivoting loop sums its w
        const int r = A.built_row(i);
        double wi = A.diag(i) * x[r];
        double si = std::abs(wi);
        for (int k = A.row_begin(i); k < A.row_end(i); ++k) {
            const double term = A.val(k) * x[A.built_row(A.col(k))];
            wi += term;
            si += std::abs(term);
        }
        w[r] = wi - p.b[r];
        scale[r] = si + std::abs(p.b[r]);
    }
}

void residual_vectors(const Problem& p, ConstStrided x, std::vector<double>& w, std::vector<double>& scale) {
    if (p.sparse != nullptr) return residual_vectors(p, *p.sparse, x, w, scale);
    dense_residual_vectors(p, x, w, scale);
}

Residuals compute_residuals(const Problem& p, ConstStrided x, const std::vector<RowState>* states) {
    ResidualBuffers buffers;
    if (p.sparse != nullptr) return compute_residuals(p, *p.sparse, x, states, buffers);
    dense_residual_vectors(p, x, buffers.w, buffers.scale);
    return summarize(p, DenseDiagonal{p}, x, buffers.w, buffers.scale, states);
}

Residuals compute_residuals(const Problem& p, const linalg::SymmetricRows& A, ConstStrided x,
                            const std::vector<RowState>* states, ResidualBuffers& buffers) {
    residual_vectors(p, A, x, buffers.w, buffers.scale);
    return residuals_from(p, A, x, states, buffers);
}

Residuals residuals_from(const Problem& p, const linalg::SymmetricRows& A, ConstStrided x,
                         const std::vector<RowState>* states, ResidualBuffers& vectors) {
    if (A.order().empty()) return summarize(p, [&A](int i) { return A.diag(i); }, x, vectors.w, vectors.scale, states);
    vectors.diagonal.resize(static_cast<std::size_t>(p.n));
    for (int i = 0; i < p.n; ++i) vectors.diagonal[A.built_row(i)] = A.diag(i);
    const std::vector<double>& diagonal = vectors.diagonal;
    return summarize(p, [&diagonal](int i) { return diagonal[i]; }, x, vectors.w, vectors.scale, states);
}

Residuals dense_residuals_from(const Problem& p, ConstStrided x, const std::vector<double>& w,
                               const std::vector<double>& scale, const std::vector<RowState>* states) {
    return summarize(p, DenseDiagonal{p}, x, w, scale, states);
}

std::vector<RowState> states_of(const Problem& p, const std::vector<double>& x) {
    std::vector<RowState> states(static_cast<std::size_t>(p.n), RowState::Free);
    const ConstStrided xs{x.data(), 1};
    for (int i = 0; i < p.n; ++i) {
        const auto [lo, hi] = effective_bounds(p, xs, i);
        if (x[i] <= lo) states[i] = RowState::AtLo;
        else if (x[i] >= hi) states[i] = RowState::AtHi;
    }
    return states;
}

int count_tight(const std::vector<RowState>& states) {
    return static_cast<int>(std::count_if(states.begin(), states.end(), [](RowState s) { return s != RowState::Free; }));
}

Residuals residuals_from_vectors(const Problem& p, ConstStrided x, const ResidualBuffers& vectors,
                                 const std::vector<RowState>* states) {
    const std::vector<double>& diagonal = vectors.diagonal;
    return summarize(p, [&diagonal](int i) { return diagonal[i]; }, x, vectors.w, vectors.scale, states);
}

}  // namespace ode_bpp
