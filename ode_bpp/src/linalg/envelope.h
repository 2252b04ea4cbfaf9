// The envelope (row profile) of a symmetrically permuted matrix, and loading it into skyline
// storage (paper Sec. 3.4: the skyline of L is the envelope of A, since Cholesky fill stays
// inside the envelope).
#pragma once

#include <cstddef>
#include <vector>

#include "linalg/skyline.h"

namespace ode_bpp::linalg {

/// Row profile of Ap = P A Pᵀ, Ap(i,j) = A(perm[i], perm[j]).
/// A: n x n, row-major with row stride lda; only its lower triangle is read (an entry
/// A(p,q) with p < q is read as A(q,p)). perm: n entries, perm[new] = old, or null for identity.
/// Returns first (n entries, permuted space): first[i] = smallest j <= i with Ap(i,j) != 0,
/// or i when row i of Ap's lower triangle is entirely zero.
std::vector<int> row_profile(const double* A, int lda, int n, const int* perm);

/// Ap = P A Pᵀ (same arguments as row_profile) in skyline storage shaped by its row profile.
/// Every stored entry is written, zeros included, so the result is ready for
/// skyline_cholesky(L, 0, {}).
SkylineMatrix load_skyline(const double* A, int lda, int n, const int* perm);

/// Envelope size sum_i (i - first[i]): the number of strictly-lower entries inside the row
/// envelope (George & Liu's |Env(A)|; the diagonal is not counted).
std::ptrdiff_t envelope_size(const std::vector<int>& first);

}  // namespace ode_bpp::linalg
