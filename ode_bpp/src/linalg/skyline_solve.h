// Forward and backward substitution inside the skyline (paper Alg. 3 CHOLSOLVE).
#pragma once

#include "linalg/skyline.h"

namespace ode_bpp::linalg {

/// Solves L Lᵀ x = rhs in place (x holds rhs on entry, the solution on exit; n entries, L's
/// index space). Only stored entries of L are read. Removed indices are identity rows/columns
/// of L, so a caller that zeroes their rhs entries gets x = 0 there and the solution of
/// A_FF x_F = rhs_F on the kept indices.
void skyline_solve(const SkylineMatrix& L, double* x);

}  // namespace ode_bpp::linalg
