// What goes with an iterate x of the pivoting loops (pivot_loop.cpp, active_set.cpp):
// w = (A + shift I) x - b, the row scales (|A||x| + |b|)_i that classify_row.h measures against,
// and Eq. 6's backward error on the free rows.
//
// Index space: the BoxedLcp's (the permuted space of the solve); tight_columns_product's is the
// stored order of the SymmetricRows it is given.
#pragma once

#include <vector>

#include "pivoting/boxed_lcp.h"
#include "pivoting/classify_row.h"

namespace ode_bpp::pivoting {

/// w, the row scales and the bounds in force (moving friction bounds change them), n entries each.
struct Iterate {
    std::vector<double> w, scale, lo, hi;
    /// w and scale hold x's values on every row; else only on the rows that can be tight
    /// (refresh_bounded_residual), and the always-free rows hold whatever they held before.
    bool complete = false;
};

/// w = (A + shift I) x - b and scale = |A + shift I||x| + |b|, from x (n entries).
void refresh_residual(const BoxedLcp& lcp, const std::vector<double>& x, Iterate& it);

/// The same on the rows that can be tight only (not BoxedLcp::always_free): an always-free row
/// keeps its infinite bounds, so Eq. 4 never reads its w or scale (classify_row.h), nor does the
/// polish, which reads tight rows. On ODE's islands these are the joints' rows, with 43-95 % of
/// A's entries on the paper's scenes (docs/benchmarks.md), so a later pivot step skips most of
/// the product. Each row is summed as refresh_residual sums it (SymmetricRows::row_with_scale):
/// complete_residual then gives the same vectors bit for bit.
void refresh_bounded_residual(const BoxedLcp& lcp, const std::vector<double>& x, Iterate& it);

/// Fills in the always-free rows refresh_bounded_residual left, at the same x; nothing
/// when it is complete already. For what reads every row: Eq. 6's backward error (the accuracy
/// guard) and the residuals of the answer.
void complete_residual(const BoxedLcp& lcp, const std::vector<double>& x, Iterate& it);

/// The same on the rows that `states` holds tight (at a bound) only, and on the free rows only:
/// each row summed as refresh_residual sums it, so that both at one x give its vectors bit for
/// bit. The active set (active_set.cpp) classifies Eq. 4 on its tight rows at every face
/// minimizer, where its free rows lie strictly inside their bounds, and reads the free rows' w
/// only to check its factor. Neither sets `complete`.
void refresh_tight_residual(const BoxedLcp& lcp, const std::vector<double>& x, const std::vector<RowState>& states,
                            Iterate& it);
void refresh_free_residual(const BoxedLcp& lcp, const std::vector<double>& x, const std::vector<RowState>& states,
                           Iterate& it);

/// y_i = (A_FT x_T)_i on the free rows (tight[i] == 0; on a tight row, the same sum over the
/// other tight columns: A x_T without the diagonal), Eq. 6's right-hand side without b: a pass
/// over the rows of the tight columns with x_j != 0 only (A symmetric), O(n + their entries)
/// instead of O(nnz). Each y_i adds its terms in the order row i of A lists
/// them when every row lists its columns by increasing built_row (symmetric_rows.h; assign from a
/// dense A with the identity, both assign_lower and permute_into of such a matrix keep this), so
/// that y_i is bit for bit lcp.A->multiply's at x with x_F = 0: the terms skipped are exact zeros.
/// x: n entries; columns: scratch.
void tight_columns_product(const linalg::SymmetricRows& A, const std::vector<char>& tight, const std::vector<double>& x,
                           std::vector<int>& columns, std::vector<double>& y);

/// y = (A - diag(A)) x, over x's non-zero columns only, summed as tight_columns_product sums (it
/// is that product with every column tight): O(n + their entries). For an x that is zero on
/// most rows (FreeRowsFactor's x_T). x: n entries; columns: scratch.
void off_diagonal_product(const linalg::SymmetricRows& A, const std::vector<double>& x, std::vector<int>& columns,
                          std::vector<double>& y);

/// max over free rows (tight[i] == 0) of |w_i| / scale_i: Eq. 6's backward error, row by row.
double free_residual(const Iterate& it, const std::vector<char>& tight);

/// Eq. 4 row by row on (A + shift I, b) at x and the index set `states` (classify_row.h), with the
/// bounds and scales of `it`; the infeasible rows go to `inf`.
void classify_iterate(const BoxedLcp& lcp, const Iterate& it, const std::vector<RowState>& states,
                      const std::vector<double>& x, double tolerance, Infeasibility& inf);

/// A pinned row (lo = hi) is at both bounds; report it at the one its w supports (w >= 0: at lo).
void orient_pinned_rows(const Iterate& it, std::vector<RowState>& states);

/// A fresh Cholesky solve misses Eq. 6 by about n eps relative to |A||x| + |b|; a tenth of the
/// classification tolerance keeps the pivoting decisions unaffected by the factor. A factor
/// that misses by more (after deletions or updates) is replaced by a fresh one.
double accuracy_limit(double tolerance, int n);

}  // namespace ode_bpp::pivoting
