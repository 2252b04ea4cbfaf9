#include "pivoting/iterate.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ode_bpp::pivoting {

namespace {

/// Rows i with take(i) of w = (A + shift I) x - b and of the scale |A + shift I||x| + |b|.
template <typename Take>
void refresh_rows(const BoxedLcp& lcp, const std::vector<double>& x, Iterate& it, Take take) {
    const int n = lcp.n();
    it.w.resize(static_cast<std::size_t>(n));
    it.scale.resize(static_cast<std::size_t>(n));
    const linalg::SymmetricRows& A = *lcp.A;
    const double* xs = x.data();
    double* w = it.w.data();
    double* scale = it.scale.data();
    for (int i = 0; i < n; ++i) {
        if (!take(i)) continue;
        A.row_with_scale(i, xs, lcp.shift, w[i], scale[i]);
        w[i] -= lcp.b[i];
        scale[i] += std::abs(lcp.b[i]);
    }
}

}  // namespace

void refresh_residual(const BoxedLcp& lcp, const std::vector<double>& x, Iterate& it) {
    refresh_rows(lcp, x, it, [](int) { return true; });
    it.complete = true;
}

void refresh_bounded_residual(const BoxedLcp& lcp, const std::vector<double>& x, Iterate& it) {
    const char* unbounded = lcp.always_free.data();
    refresh_rows(lcp, x, it, [unbounded](int i) { return !unbounded[i]; });
    it.complete = std::find(lcp.always_free.begin(), lcp.always_free.end(), 1) == lcp.always_free.end();
}

void complete_residual(const BoxedLcp& lcp, const std::vector<double>& x, Iterate& it) {
    if (it.complete) return;
    const char* unbounded = lcp.always_free.data();
    refresh_rows(lcp, x, it, [unbounded](int i) { return unbounded[i] != 0; });
    it.complete = true;
}

void refresh_tight_residual(const BoxedLcp& lcp, const std::vector<double>& x, const std::vector<RowState>& states,
                            Iterate& it) {
    const RowState* s = states.data();
    refresh_rows(lcp, x, it, [s](int i) { return s[i] != RowState::Free; });
    it.complete = false;
}

void refresh_free_residual(const BoxedLcp& lcp, const std::vector<double>& x, const std::vector<RowState>& states,
                           Iterate& it) {
    const RowState* s = states.data();
    refresh_rows(lcp, x, it, [s](int i) { return s[i] == RowState::Free; });
    it.complete = false;
}

namespace {

/// y = A x without the diagonal over the columns j with take(j) and x_j != 0, in built-row order
/// (tight_columns_product's summation order, iterate.h).
template <typename Take>
void columns_product(const linalg::SymmetricRows& A, const std::vector<double>& x, Take take, std::vector<int>& columns,
                     std::vector<double>& y) {
    const int n = A.n();
    columns.clear();
    for (int j = 0; j < n; ++j)
        if (take(j) && x[j] != 0) columns.push_back(j);
    if (!A.order().empty())  // rows list their columns by built row, not by stored index
        std::sort(columns.begin(), columns.end(), [&A](int a, int b) { return A.built_row(a) < A.built_row(b); });
    y.assign(static_cast<std::size_t>(n), 0.0);
    for (int j : columns) {
        const double xj = x[j];
        for (int k = A.row_begin(j); k < A.row_end(j); ++k) y[A.col(k)] += A.val(k) * xj;
    }
}

}  // namespace

void tight_columns_product(const linalg::SymmetricRows& A, const std::vector<char>& tight, const std::vector<double>& x,
                           std::vector<int>& columns, std::vector<double>& y) {
    const char* t = tight.data();
    columns_product(A, x, [t](int j) { return t[j] != 0; }, columns, y);
}

void off_diagonal_product(const linalg::SymmetricRows& A, const std::vector<double>& x, std::vector<int>& columns,
                          std::vector<double>& y) {
    columns_product(A, x, [](int) { return true; }, columns, y);
}

double free_residual(const Iterate& it, const std::vector<char>& tight) {
    double worst = 0;
    for (std::size_t i = 0; i < tight.size(); ++i)
        if (!tight[i] && it.w[i] != 0) worst = std::max(worst, std::abs(it.w[i]) / it.scale[i]);
    return worst;
}

void classify_iterate(const BoxedLcp& lcp, const Iterate& it, const std::vector<RowState>& states,
                      const std::vector<double>& x, double tolerance, Infeasibility& inf) {
    const auto diag = [&lcp](int i) { return lcp.A->diag(i) + lcp.shift; };
    classify_rows(lcp.n(), states, x, it.w, it.lo, it.hi, diag, it.scale, tolerance, inf);
}

void orient_pinned_rows(const Iterate& it, std::vector<RowState>& states) {
    for (std::size_t i = 0; i < states.size(); ++i)
        if (it.lo[i] == it.hi[i]) states[i] = it.w[i] >= 0 ? RowState::AtLo : RowState::AtHi;
}

double accuracy_limit(double tolerance, int n) {
    return std::max(0.1 * tolerance, 100.0 * n * std::numeric_limits<double>::epsilon());
}

}  // namespace ode_bpp::pivoting
