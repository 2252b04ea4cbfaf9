#include "baselines/pgs.h"

#include <algorithm>

#include "ode_bpp/residuals.h"
#include "row_bounds.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::baselines {

void solve_pgs(const Problem& p, const linalg::SymmetricRows& A, int sweeps, std::vector<double>& x) {
    x.assign(static_cast<std::size_t>(p.n), 0.0);
    const ConstStrided xs{x.data(), 1};
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        for (int i = 0; i < p.n; ++i) {
            double w = A.diag(i) * x[i] - p.b[i];
            for (int k = A.row_begin(i); k < A.row_end(i); ++k) w += A.val(k) * x[A.col(k)];
            const auto [lo, hi] = bounds_at(p, xs, i);
            x[i] = std::clamp(x[i] - w / A.diag(i), lo, hi);
        }
    }
}

}  // namespace ode_bpp::baselines
