#include "linalg/row_delete.h"
#include "linalg/kernel_clones.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace ode_bpp::linalg {

namespace {

/// work(i+1 : sky[i]) = sigma = L(i+1 : sky[i], i); returns the last row of sigma's support.
int load_sigma(const SkylineMatrix& L, int i, std::vector<double>& work) {
    const double* column = L.column(i);
    const int last = L.sky(i);
    std::copy(column + 1, column + (last - i + 1), work.begin() + (i + 1));
    return last;
}

/// One rotation's two vector passes, fused: sigma -= a l, then l = b l + c sigma, entry by entry
/// (always_inline: it is the loop the AVX2 copy below exists for).
[[gnu::always_inline]] inline void rotate_entries(double* l, double* sigma, int count, double a, double b, double c) {
    for (int r = 0; r < count; ++r) {
        sigma[r] -= a * l[r];
        l[r] = b * l[r] + c * sigma[r];
    }
}

/// L33 L33ᵀ + sigma sigmaᵀ by one Givens rotation per column. sigma is held as scale * work
/// so that each column costs two vector operations (one pass: rotate_entries):
///   x = sigma_k, y = L(k,k), r = sqrt(y² + x²), c = y / r, s = x / r;
///   sigma'' = sigma - (x/y) L(k+1:, k)                 (Alg. 3 line 13)
///   L(k+1:, k) <- (r/y) L(k+1:, k) + s sigma''          (Alg. 3 line 14; = c L + s sigma)
///   sigma <- c sigma''                                  (= c sigma - s L, folded into scale)
/// The product of the c's equals 1 / sqrt(1 + |L33⁻¹ sigma|²), so scale cannot underflow for
/// any factor with finite entries. On x86-64 also compiled for AVX2 and chosen by the CPU at load
/// time (kernel_clones.h): the same operations per entry, the same bits.
KERNEL_FOR_AVX2_TOO
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
        // x / (y scale), then c and s of the rotation with sigma's scale folded in
        rotate_entries(column + 1, work + k + 1, last - k, work[k] * inverse_y, r * inverse_y, x * scale * inverse_r);
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
