#include "linalg/row_delete.h"

#include <Eigen/Core>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace ode_bpp::linalg {

namespace {

using Segment = Eigen::Map<Eigen::VectorXd>;

/// work(i+1 : sky[i]) = sigma = L(i+1 : sky[i], i); returns the last row of sigma's support.
int load_sigma(const SkylineMatrix& L, int i, std::vector<double>& work) {
    const double* column = L.column(i);
    const int last = L.sky(i);
    std::copy(column + 1, column + (last - i + 1), work.begin() + (i + 1));
    return last;
}

/// L33 L33ᵀ + sigma sigmaᵀ by one Givens rotation per column. sigma is held as scale * work
/// so that each column costs two vector passes:
///   x = sigma_k, y = L(k,k), r = sqrt(y² + x²), c = y / r, s = x / r;
///   sigma'' = sigma - (x/y) L(k+1:, k)                 (Alg. 3 line 13)
///   L(k+1:, k) <- (r/y) L(k+1:, k) + s sigma''          (Alg. 3 line 14; = c L + s sigma)
///   sigma <- c sigma''                                  (= c sigma - s L, folded into scale)
/// The product of the c's equals 1 / sqrt(1 + |L33⁻¹ sigma|²), so scale cannot underflow for
/// any factor with finite entries.
void rank_one_update_trailing(SkylineMatrix& L, int i, int support_end, double* work) {
    double scale = 1.0;
    for (int k = i + 1; k < L.n(); ++k) {
        const int last = L.sky(k);
        if (last > support_end) {
            std::fill(work + support_end + 1, work + last + 1, 0.0);
            support_end = last;
        }
        const double x = scale * work[k];
        if (x == 0.0) continue;  // the rotation is the identity (e.g. an index deleted earlier)
        double* column = L.column(k);
        const double y = column[0];
        const double r = std::sqrt(y * y + x * x);
        const double inverse_y = 1.0 / y, inverse_r = 1.0 / r;
        const int below = last - k;
        Segment l_below(column + 1, below);
        Segment sigma_below(work + k + 1, below);
        sigma_below.noalias() -= (work[k] * inverse_y) * l_below;  // x / (y scale)
        l_below = (r * inverse_y) * l_below + (x * scale * inverse_r) * sigma_below;
        column[0] = r;
        scale *= y * inverse_r;
    }
}

void make_identity_row_column(SkylineMatrix& L, int i) {
    double* column = L.column(i);
    column[0] = 1.0;
    std::fill(column + 1, column + L.shape().height(i), 0.0);
    for (int j = L.shape().first_column_holding(i); j < i; ++j) L.at(i, j) = 0.0;
}

}  // namespace

void skyline_delete_row(SkylineMatrix& L, int i, std::vector<double>& work) {
    assert(0 <= i && i < L.n());
    if (static_cast<int>(work.size()) < L.n()) work.resize(static_cast<std::size_t>(L.n()));
    const int support_end = load_sigma(L, i, work);
    rank_one_update_trailing(L, i, support_end, work.data());
    make_identity_row_column(L, i);
}

}  // namespace ode_bpp::linalg
