#include "linalg/dense_cholesky.h"

namespace ode_bpp::linalg {

int dense_cholesky(double* a, int n, int lda, const double* diagonal) {
    for (int k = 0; k < n; ++k)
        if (!dense_cholesky_row(a, k, lda, diagonal[k])) return k;
    return -1;
}

void dense_cholesky_solve(const double* l, int n, int lda, double* x) {
    for (int k = 0; k < n; ++k) dense_forward_entry(l, k, lda, x);
    dense_backward_solve(l, n, lda, x);
}

}  // namespace ode_bpp::linalg
