// Dense Cholesky of a small symmetric matrix in place (paper Alg. 1 line 5: L_FF <- chol(A_FF)),
// and the two triangular solves of Eq. 6. For the small islands that bpp factors densely
// (Tuning::dense_island_rows), where a general-purpose factorization's set-up per call costs
// more than the O(n^3 / 6) flops themselves.
//
// The factorization goes row by row (Cholesky–Banachiewicz): row k of L needs only A's row k and
// rows 0..k-1 of L, so a caller may gather A one row at a time and factor it as it goes
// (dense_cholesky_row), with the forward solve's entry k in the same pass. Inline: on a few rows
// a call per row costs as much as the row.
#pragma once

#include <cmath>

#include "linalg/cholesky_pivot.h"

namespace ode_bpp::linalg {

/// sum_{j<k} x_j y_j, summed by increasing j.
inline double dense_dot(const double* x, const double* y, int k) {
    double sum = 0;
    for (int j = 0; j < k; ++j) sum += x[j] * y[j];
    return sum;
}

/// Factors row k of L Lᵀ = A in place, rows 0 .. k-1 of L already in a (row stride lda):
/// L(k,j) = (A(k,j) - L(k,0:j) . L(j,0:j)) / L(j,j) for j < k, then L(k,k) = sqrt(d_k) with
/// d_k = A(k,k) - |L(k,0:k)|². diagonal: A(k,k) before factoring (the breakdown test's scale).
/// inverse_diagonal: input, 1 / L(j,j) for j < k; output, entry k = 1 / L(k,k). The divisions
/// by L(j,j) are multiplications by it: each L(k,j) waits for L(k,j-1), so on a few rows the
/// divisions' latency, one after the other, was a sixth of a small island's pivoting time (perf).
/// Returns false when d_k breaks down (pivot_breaks_down of cholesky_pivot.h; L(k,k) then unset).
inline bool dense_cholesky_row(double* a, int k, int lda, double diagonal, double* inverse_diagonal) {
    double* row_k = a + static_cast<long>(k) * lda;
    for (int j = 0; j < k; ++j) {
        const double* row_j = a + static_cast<long>(j) * lda;
        row_k[j] = (row_k[j] - dense_dot(row_k, row_j, j)) * inverse_diagonal[j];
    }
    const double pivot = row_k[k] - dense_dot(row_k, row_k, k);
    if (pivot_breaks_down(pivot, diagonal)) return false;
    row_k[k] = std::sqrt(pivot);
    inverse_diagonal[k] = 1.0 / row_k[k];
    return true;
}

/// Entry k of the forward solve L y = x, entries 0 .. k-1 of y already in x and row k of L
/// factored: x_k <- (x_k - L(k,0:k) . y(0:k)) / L(k,k), with inverse_diagonal[k] = 1 / L(k,k).
inline void dense_forward_entry(const double* l, const double* inverse_diagonal, int k, int lda, double* x) {
    const double* row_k = l + static_cast<long>(k) * lda;
    x[k] = (x[k] - dense_dot(row_k, x, k)) * inverse_diagonal[k];
}

/// Lᵀ x = y in place, by columns of L (rows of Lᵀ); x: n entries, y on entry;
/// inverse_diagonal: n entries, 1 / L(i,i).
inline void dense_backward_solve(const double* l, const double* inverse_diagonal, int n, int lda, double* x) {
    for (int i = n - 1; i >= 0; --i) {
        const double* row_i = l + static_cast<long>(i) * lda;
        x[i] *= inverse_diagonal[i];
        for (int j = 0; j < i; ++j) x[j] -= row_i[j] * x[i];
    }
}

/// Factors L Lᵀ = A in place, row by row (dense_cholesky_row for k = 0 .. n-1).
///
/// a: input, the lower triangle of the n x n symmetric matrix A, row-major with row stride lda
///    (a[i * lda + j], j <= i; the strict upper triangle is neither read nor written);
///    output, L in the same positions.
/// diagonal: input, n entries, A's diagonal before factoring (the breakdown test's scale;
///    it may alias nothing in a).
/// inverse_diagonal: output, n entries, 1 / L(k,k) (for dense_cholesky_solve).
/// Returns -1 on success, else the first column k whose pivot d_k = A(k,k) - sum_j L(k,j)²
/// breaks down (pivot_breaks_down of cholesky_pivot.h: d_k <= eps A(k,k), or NaN), with
/// columns 0 .. k-1 factored.
int dense_cholesky(double* a, int n, int lda, const double* diagonal, double* inverse_diagonal);

/// x <- L^-T L^-1 x with the factor of dense_cholesky and its inverse_diagonal; x: n entries
/// (dense_forward_entry for k = 0 .. n-1, then dense_backward_solve).
void dense_cholesky_solve(const double* l, const double* inverse_diagonal, int n, int lda, double* x);

}  // namespace ode_bpp::linalg
