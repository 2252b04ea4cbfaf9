#include "linalg/skyline_solve.h"
#include "linalg/kernel_clones.h"
#include "linalg/short_update.h"

#include <Eigen/Core>

#include <algorithm>

namespace ode_bpp::linalg {

namespace {

using ConstSegment = Eigen::Map<const Eigen::VectorXd>;

/// Rows of column k below the diagonal inside the leading k1 x k1 block (kLeading), or all of
/// them (k1 = n, no clipping: the whole solve keeps its instructions).
template <bool kLeading>
[[gnu::always_inline]] inline int rows_below(const SkylineMatrix& L, int k, int k1) {
    return (kLeading ? std::min(L.sky(k), k1 - 1) : L.sky(k)) - k;
}

/// L y = rhs on the leading k1 rows, column by column: y_k = rhs_k / L(k,k),
/// rhs(k+1:s) -= y_k L(k+1:s, k) with s = min(sky[k], k1 - 1).
/// Both substitutions multiply by 1 / L(k,k): that division reads L alone, so the CPU computes
/// it ahead, off the chain of x's entries, where x_k / L(k,k) waited for x_k (on short columns,
/// the crane's, the divisions' latency set the pace: its solver call -5 % in wall time).
template <bool kLeading>
[[gnu::always_inline]] inline void forward_columns(const SkylineMatrix& L, int k1, double* x) {
    for (int k = 0; k < k1; ++k) {
        const double* column = L.column(k);
        const double y_k = x[k] * (1.0 / column[0]);
        x[k] = y_k;
        const int below = rows_below<kLeading>(L, k, k1);
        if (y_k == 0.0) continue;
        double* rhs = x + k + 1;
        if (below <= kShortRun) {
            subtract_multiple_short(rhs, column + 1, y_k, below);  // short_update.h
            continue;
        }
        for (int r = 0; r < below; ++r) rhs[r] -= y_k * column[1 + r];
    }
}

/// forward_columns, whole and leading. On x86-64 each is also compiled for AVX2 and chosen by the
/// CPU at load time (kernel_clones.h): the same operations per entry, the same bits.
KERNEL_FOR_AVX2_TOO
void forward_substitution(const SkylineMatrix& L, double* x) { forward_columns<false>(L, L.n(), x); }
KERNEL_FOR_AVX2_TOO
void forward_substitution_leading(const SkylineMatrix& L, int k1, double* x) { forward_columns<true>(L, k1, x); }

/// Lᵀ x = y on the leading k1 rows, from row k1 - 1 up: x_k = (y_k - L(k+1:s, k)ᵀ x(k+1:s)) / L(k,k).
template <bool kLeading>
void backward_substitution(const SkylineMatrix& L, int k1, double* x) {
    for (int k = k1 - 1; k >= 0; --k) {
        const double* column = L.column(k);
        const int below = rows_below<kLeading>(L, k, k1);
        double sum = x[k];
        if (below > 0) sum -= ConstSegment(column + 1, below).dot(ConstSegment(x + k + 1, below));
        x[k] = sum * (1.0 / column[0]);
    }
}

}  // namespace

void skyline_solve(const SkylineMatrix& L, double* x) {
    forward_substitution(L, x);
    backward_substitution<false>(L, L.n(), x);
}

void skyline_solve_leading(const SkylineMatrix& L, int k1, double* x) {
    if (k1 == L.n()) return skyline_solve(L, x);
    forward_substitution_leading(L, k1, x);
    backward_substitution<true>(L, k1, x);
}

}  // namespace ode_bpp::linalg
