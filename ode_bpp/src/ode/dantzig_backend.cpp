// The ODE glue's Dantzig: ODE's stock dSolveMLCPDantzig (from the ode-bpp patch) behind the core's
// slot (baselines/dantzig.h), installed when libode_bpp loads.
#include <ode/ode.h>

#include <vector>

#include "baselines/dantzig.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::ode {

namespace {

/// Copies the problem into ODE's layout (A expanded into a full n x dPAD(n) buffer, which ODE
/// destroys: O(n^2); contiguous b, lo, hi, findex) and runs ODE's Dantzig.
bool solve_with_ode_dantzig(const Problem& p, const linalg::SymmetricRows& As, std::vector<double>& x) {
    static_assert(sizeof(dReal) == sizeof(double), "the patched ODE must be double precision");
    const int n = p.n;
    const int stride = dPAD(n);
    std::vector<double> A(static_cast<std::size_t>(n) * stride, 0.0);
    for (int i = 0; i < n; ++i) {
        double* row = A.data() + static_cast<std::size_t>(i) * stride;
        row[i] = As.diag(i);
        for (int k = As.row_begin(i); k < As.row_end(i); ++k) row[As.col(k)] = As.val(k);
    }
    std::vector<double> b(n), lo(n), hi(n);
    std::vector<int> findex(n, -1);
    for (int i = 0; i < n; ++i) {
        b[i] = p.b[i];
        lo[i] = p.lo[i];
        hi[i] = p.hi[i];
        if (p.findex != nullptr) findex[i] = p.findex[i];
        // ODE's Dantzig asserts lo <= 0 <= hi on every row (an abort() in its checked build).
        // Validation leaves two kinds of rows to their meaning rather than their values:
        // the first nub rows are unbounded, and a friction row's lo is -|mu x_f| (hi holds mu).
        if (i < p.nub) {
            lo[i] = -dInfinity;
            hi[i] = dInfinity;
        } else if (findex[i] >= 0) {
            lo[i] = -hi[i];
        }
    }
    x.assign(static_cast<std::size_t>(n), 0.0);
    const int ok = dSolveMLCPDantzig(n, A.data(), x.data(), b.data(), p.nub, lo.data(), hi.data(), findex.data());
    if (ok == 0) x.assign(static_cast<std::size_t>(n), 0.0);
    return ok != 0;
}

int install_at_load() {
    baselines::install_dantzig(&solve_with_ode_dantzig);
    return 1;
}

[[maybe_unused]] const int g_installed_at_load = install_at_load();

}  // namespace

}  // namespace ode_bpp::ode
