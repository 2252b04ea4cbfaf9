#include "linalg/dense_cholesky.h"

#include <cmath>

#include "linalg/cholesky_pivot.h"

namespace ode_bpp::linalg {

namespace {

/// sum_{j<k} x_j y_j.
double dot(const double* x, const double* y, int k) {
    double sum = 0;
    for (int j = 0; j < k; ++j) sum += x[j] * y[j];
    return sum;
}

}  // namespace

int dense_cholesky(double* a, int n, int lda, const double* diagonal) {
    for (int i = 0; i < n; ++i) {
        double* row_i = a + static_cast<long>(i) * lda;
        // L(i,j) = (A(i,j) - L(i,0:j) . L(j,0:j)) / L(j,j), j < i
        for (int j = 0; j < i; ++j) {
            const double* row_j = a + static_cast<long>(j) * lda;
            row_i[j] = (row_i[j] - dot(row_i, row_j, j)) / row_j[j];
        }
        // d_i = A(i,i) - |L(i,0:i)|²
        const double pivot = row_i[i] - dot(row_i, row_i, i);
        if (pivot_breaks_down(pivot, diagonal[i])) return i;
        row_i[i] = std::sqrt(pivot);
    }
    return -1;
}

void dense_cholesky_solve(const double* l, int n, int lda, double* x) {
    // L y = x, forward by rows
    for (int i = 0; i < n; ++i) {
        const double* row_i = l + static_cast<long>(i) * lda;
        x[i] = (x[i] - dot(row_i, x, i)) / row_i[i];
    }
    // Lᵀ x = y, backward by columns of L (rows of Lᵀ)
    for (int i = n - 1; i >= 0; --i) {
        const double* row_i = l + static_cast<long>(i) * lda;
        x[i] /= row_i[i];
        for (int j = 0; j < i; ++j) x[j] -= row_i[j] * x[i];
    }
}

}  // namespace ode_bpp::linalg
