#include "linalg/dense_cholesky.h"

namespace ode_bpp::linalg {

int dense_cholesky(double* a, int n, int lda, const double* diagonal, double* inverse_diagonal) {
    for (int k = 0; k < n; ++k)
        if (!dense_cholesky_row(a, k, lda, diagonal[k], inverse_diagonal)) return k;
    return -1;
}

void dense_cholesky_solve(const double* l, const double* inverse_diagonal, int n, int lda, double* x) {
    for (int k = 0; k < n; ++k) dense_forward_entry(l, inverse_diagonal, k, lda, x);
    dense_backward_solve(l, inverse_diagonal, n, lda, x);
}

}  // namespace ode_bpp::linalg
