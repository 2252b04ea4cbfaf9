// Left-looking Cholesky inside the skyline (paper Alg. 2 line 2 and Sec. 3.4), with optional
// removed indices embedded as identity rows/columns (the factor of A_FF, paper Eq. 6).
#pragma once

#include <vector>

#include "linalg/skyline.h"

namespace ode_bpp::linalg {

/// Factors in place, from column k0 on, L Lᵀ = Ap with the removed indices taken out.
///
/// Index space: L's (the permuted space of the caller).
/// On entry: columns 0 .. k0-1 of L hold the factor (of Ap restricted to the kept indices,
/// with every removed index < k0 already an identity row/column); columns k0 .. n-1 hold Ap's
/// lower triangle inside the skyline. Rows of removed indices >= k0 may hold anything in
/// columns < k0 (they are zeroed here).
/// removed: n flags (removed[k] != 0: index k is taken out), or empty for none.
/// On exit (success): L Lᵀ = Ap restricted to the kept rows/columns, and each removed k is an
/// identity row/column: L(k,k) = 1, L(r,k) = 0 (r > k), L(k,j) = 0 (j < k). The writes to row k
/// reach back to column L.shape().first_column_holding(k), possibly below k0.
/// Returns -1 on success, else the first kept column k whose pivot d_k failed the relative test
///     d_k > (w_k + 1) * eps * Ap(k,k),   w_k = number of earlier columns reaching row k,
/// i.e. d_k is not distinguishable from the rounding error of its own inner product (or is not
/// finite). On failure, columns k0 .. k-1 are factored and the rest is unspecified.
int skyline_cholesky(SkylineMatrix& L, int k0, const std::vector<char>& removed);

/// The same for columns k0 .. k1-1 only (k0 <= k1 <= n); columns k1 .. n-1 keep Ap. A
/// left-looking column k reads only columns < k and Ap's column k, so finishing later with
/// skyline_cholesky(L, k1, ...) gives the factor of one whole call, bit for bit: a factor can
/// be computed as far as its use needs (pivoting/skyline_solver.cpp's L0).
int skyline_cholesky(SkylineMatrix& L, int k0, int k1, const std::vector<char>& removed);

}  // namespace ode_bpp::linalg
