// The residuals of ode_bpp/residuals.h from A's compressed rows, for callers that already hold
// them (solve(), PGS): O(nnz) instead of another O(n^2) pass over the dense A.
#pragma once

#include <vector>

#include "ode_bpp/residuals.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp {

/// w = A x - b and the row scales |A||x| + |b| of one answer (ode_bpp/residuals.h), n entries
/// each; kept by the caller so that their capacity outlives a solve.
struct ResidualBuffers {
    std::vector<double> w, scale;
    std::vector<double> diagonal;  ///< A_ii in the problem's order, where A is stored in another
};

/// As compute_residuals(problem, x, states); A: linalg::SymmetricRows(problem, {}) or
/// problem.sparse, stored in any order (SymmetricRows::order).
/// buffers: scratch, left holding w and scale of x.
Residuals compute_residuals(const Problem& problem, const linalg::SymmetricRows& A, ConstStrided x,
                            const std::vector<RowState>* states, ResidualBuffers& buffers);

/// As compute_residuals(problem, A, x, states, buffers) when vectors already hold w and scale of
/// x as residual_vectors sums them (a pivoting loop's at its answer, bpp_driver.h): the same
/// values, without the pass over A. O(n).
Residuals residuals_from(const Problem& problem, const linalg::SymmetricRows& A, ConstStrided x,
                         const std::vector<RowState>* states, ResidualBuffers& vectors);

/// The residuals of x on a problem in the dense form (Problem::A) from its w = A x - b and row
/// scales as residual_vectors computes them (e.g. kept by a pivoting loop at its answer): the
/// same values as compute_residuals(problem, x, states), without its O(n^2) pass.
Residuals dense_residuals_from(const Problem& problem, ConstStrided x, const std::vector<double>& w,
                               const std::vector<double>& scale, const std::vector<RowState>* states);

/// The index set an answer x (n entries) describes: a row at its effective bound is tight (rows
/// pinned at lo = hi count as at lo). For methods without one of their own (PGS, Dantzig).
std::vector<RowState> states_of(const Problem& problem, const std::vector<double>& x);

/// The rows of an index set that are not free (Result::tight).
int count_tight(const std::vector<RowState>& states);

/// The residuals of x from vectors alone: w = A x - b, the row scales and A's diagonal (n entries
/// each, the problem's order), for a caller that holds A in neither form (ode/jacobian_pgs.h).
/// With scale = |A||x| + |b| these are compute_residuals' values; a larger scale lowers only the
/// scaled residual (Residuals::scaled_natural). O(n).
Residuals residuals_from_vectors(const Problem& problem, ConstStrided x, const ResidualBuffers& vectors,
                                 const std::vector<RowState>* states);

/// As residual_vectors(problem, x, w, scale) on a problem in the dense form (Problem::A), into
/// w and scale of at least n entries each (entries from n on untouched): w = A x - b and
/// scale = |A||x| + |b| from the lower triangle, each entry used for both of its rows, each row
/// summed as the compressed rows' residual_vectors sums it (diagonal, off-diagonal terms by
/// increasing column, then b). O(n^2), no allocation.
void dense_residual_vectors(const Problem& problem, ConstStrided x, double* w, double* scale);

/// dense_residual_vectors on the rows rows[0 .. count) alone (ascending, original order), where
/// x is 0 on every other row: w and scale of those rows, each summed in the same order as
/// dense_residual_vectors sums it, without the exact zeros the other rows add (a sum of 0 may
/// come out -0 instead of +0). The entries of the other rows are not written. O(count^2).
void dense_residual_vectors_on(const Problem& problem, ConstStrided x, const int* rows, int count, double* w,
                               double* scale);

/// As residual_vectors(problem, x, w, scale), from A = linalg::SymmetricRows(problem, {}) or
/// problem.sparse (stored in any order; w and scale come in the problem's); each
/// row summed as SymmetricRows::multiply_with_scale sums it, then b: the pivoting loop's w and
/// scales (pivoting/iterate.h) at the same x, bit for bit, in any symmetric permutation of A.
void residual_vectors(const Problem& problem, const linalg::SymmetricRows& A, ConstStrided x, std::vector<double>& w,
                      std::vector<double>& scale);

}  // namespace ode_bpp
