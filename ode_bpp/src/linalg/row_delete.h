// Deleting one row/column from a Cholesky factor in place (paper Alg. 3 DOWNDATE, rebuilt from
// the maths; Davis & Hager 2005, CHOLMOD rowdel).
#pragma once

#include <vector>

#include "linalg/skyline.h"

namespace ode_bpp::linalg {

/// Takes index i out of L Lᵀ = M, leaving L Lᵀ = M with row/column i replaced by the identity.
///
/// Maths: with sigma = L(i+1:n, i), the trailing block L33 becomes chol(L33 L33ᵀ + sigma sigmaᵀ),
/// a rank-1 *update* (nothing cancels, hence stable), computed by Givens rotations of each column
/// k = i+1 .. n-1 against sigma, touching only rows k .. sky[k] of column k (sigma's support stays
/// inside sky[k] because sky is non-decreasing). Then L(i,i) = 1, L(i+1:, i) = 0 and
/// L(i, j) = 0 for j < i, so that skyline_solve needs no skipping.
/// Index space: L's. L: a factor in skyline (or dense) storage; i: 0 <= i < n.
/// work: scratch, resized to n as needed (no allocation once it is large enough).
/// Writes: columns i .. n-1, and row i in the earlier columns L.shape().first_column_holding(i)
/// .. i-1. To get L0 back after deleting a set D: L.copy_tail_from(L0, min D) and
/// L.copy_rows_from(L0, D, min D).
/// Order: any order of deletions gives the same result. An index j deleted earlier is an
/// identity row/column, so sigma_j = L(j,i) = 0 and stays exactly 0 through every rotation
/// (L(j,k) = 0 for k < j), and column j is left untouched. Ascending order is the natural one
/// (each sweep ends at n-1 either way); deleting an index twice is a no-op.
void skyline_delete_row(SkylineMatrix& L, int i, std::vector<double>& work);

}  // namespace ode_bpp::linalg
