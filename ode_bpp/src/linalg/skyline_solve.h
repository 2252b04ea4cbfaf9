// Forward and backward substitution inside the skyline (paper Alg. 3 CHOLSOLVE).
#pragma once

#include "linalg/skyline.h"

namespace ode_bpp::linalg {

/// Solves L Lᵀ x = rhs in place (x holds rhs on entry, the solution on exit; n entries, L's
/// index space). Only stored entries of L are read. Removed indices are identity rows/columns
/// of L, so a caller that zeroes their rhs entries gets x = 0 there and the solution of
/// A_FF x_F = rhs_F on the kept indices.
void skyline_solve(const SkylineMatrix& L, double* x);

/// The same with L's leading k1 x k1 block alone (rows and columns < k1; 0 <= k1 <= n): x[0 .. k1)
/// in place, x[k1 ..) neither read nor written. Columns >= k1 of L need not be factored, so a
/// factor computed only through column k1 (skyline_cholesky's partial form) serves the free rows
/// 0 .. k1-1 of a solve whose tight rows are all of k1 .. n-1. With k1 = n: skyline_solve.
void skyline_solve_leading(const SkylineMatrix& L, int k1, double* x);

}  // namespace ode_bpp::linalg
