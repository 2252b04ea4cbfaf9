#include "linalg/skyline_solve.h"
#include "linalg/kernel_clones.h"

#include <Eigen/Core>

namespace ode_bpp::linalg {

namespace {

using ConstSegment = Eigen::Map<const Eigen::VectorXd>;

/// L y = rhs, column by column: y_k = rhs_k / L(k,k), rhs(k+1:sky[k]) -= y_k L(k+1:sky[k], k).
/// On x86-64 also compiled for AVX2 and chosen by the CPU at load time (kernel_clones.h): the
/// same operations per entry, the same bits.
KERNEL_FOR_AVX2_TOO
void forward_substitution(const SkylineMatrix& L, double* x) {
    for (int k = 0; k < L.n(); ++k) {
        const double* column = L.column(k);
        const double y_k = x[k] / column[0];
        x[k] = y_k;
        const int below = L.sky(k) - k;
        if (y_k == 0.0) continue;
        double* rhs = x + k + 1;
        for (int r = 0; r < below; ++r) rhs[r] -= y_k * column[1 + r];
    }
}

/// Lᵀ x = y, from the last row up: x_k = (y_k - L(k+1:sky[k], k)ᵀ x(k+1:sky[k])) / L(k,k).
void backward_substitution(const SkylineMatrix& L, double* x) {
    for (int k = L.n() - 1; k >= 0; --k) {
        const double* column = L.column(k);
        const int below = L.sky(k) - k;
        double sum = x[k];
        if (below > 0) sum -= ConstSegment(column + 1, below).dot(ConstSegment(x + k + 1, below));
        x[k] = sum / column[0];
    }
}

}  // namespace

void skyline_solve(const SkylineMatrix& L, double* x) {
    forward_substitution(L, x);
    backward_substitution(L, x);
}

}  // namespace ode_bpp::linalg
