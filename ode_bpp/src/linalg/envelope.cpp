#include "linalg/envelope.h"

#include <algorithm>

namespace ode_bpp::linalg {

namespace {

/// Ap(i,j) for j <= i, read from the lower triangle of row-major A.
double permuted_lower(const double* A, int lda, const int* perm, int i, int j) {
    const int p = perm ? perm[i] : i;
    const int q = perm ? perm[j] : j;
    const int row = std::max(p, q);
    const int col = std::min(p, q);
    return A[static_cast<std::ptrdiff_t>(row) * lda + col];
}

}  // namespace

std::vector<int> row_profile(const double* A, int lda, int n, const int* perm) {
    std::vector<int> first(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        int j = 0;
        while (j < i && permuted_lower(A, lda, perm, i, j) == 0.0) ++j;
        first[i] = j;
    }
    return first;
}

SkylineMatrix load_skyline(const double* A, int lda, int n, const int* perm) {
    SkylineMatrix L(SkylineShape::from_row_profile(row_profile(A, lda, n, perm)));
    for (int k = 0; k < n; ++k) {
        double* column = L.column(k);
        for (int r = k; r <= L.sky(k); ++r) column[r - k] = permuted_lower(A, lda, perm, r, k);
    }
    return L;
}

std::ptrdiff_t envelope_size(const std::vector<int>& first) {
    std::ptrdiff_t size = 0;
    for (std::size_t i = 0; i < first.size(); ++i) size += static_cast<std::ptrdiff_t>(i) - first[i];
    return size;
}

}  // namespace ode_bpp::linalg
