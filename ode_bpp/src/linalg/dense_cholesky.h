// Dense Cholesky of a small symmetric matrix in place (paper Alg. 1 line 5: L_FF <- chol(A_FF)),
// and the two triangular solves of Eq. 6. For the small islands that bpp factors densely
// (Tuning::dense_island_rows), where a general-purpose factorization's set-up per call costs
// more than the O(n^3 / 6) flops themselves.
#pragma once

namespace ode_bpp::linalg {

/// Factors L Lᵀ = A in place, row by row (Cholesky–Banachiewicz).
///
/// a: input, the lower triangle of the n x n symmetric matrix A, row-major with row stride lda
///    (a[i * lda + j], j <= i; the strict upper triangle is neither read nor written);
///    output, L in the same positions.
/// diagonal: input, n entries, A's diagonal before factoring (the breakdown test's scale;
///    it may alias nothing in a).
/// Returns -1 on success, else the first column k whose pivot d_k = A(k,k) - sum_j L(k,j)²
/// breaks down (pivot_breaks_down of cholesky_pivot.h: d_k <= eps A(k,k), or NaN), with
/// columns 0 .. k-1 factored.
int dense_cholesky(double* a, int n, int lda, const double* diagonal);

/// x <- L^-T L^-1 x with the factor of dense_cholesky; x: n entries.
void dense_cholesky_solve(const double* l, int n, int lda, double* x);

}  // namespace ode_bpp::linalg
