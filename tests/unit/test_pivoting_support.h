// Shared set-up of the test_pivoting_* suites.
#pragma once

#include <cmath>
#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::pivoting::test {

/// The driver's BoxedLcp of a problem in its own order (no permutation, fixed bounds as given),
/// with its friction rows, their normals and mu listed for the friction LCP.
struct DriverLcp {
    linalg::SymmetricRows A;
    BoxedLcp lcp;
    std::vector<int> rows, normals;
    std::vector<double> mu;
    explicit DriverLcp(const Problem& p) : A(p, {}) {
        lcp.A = &A;
        for (int i = 0; i < p.n; ++i) {
            const bool unbounded = i < p.nub || (p.lo[i] == -INFINITY && p.hi[i] == INFINITY);
            lcp.b.push_back(p.b[i]);
            lcp.lo.push_back(unbounded ? -INFINITY : p.lo[i]);
            lcp.hi.push_back(unbounded ? INFINITY : p.hi[i]);
            lcp.always_free.push_back(unbounded);
            if (p.findex != nullptr && p.findex[i] >= 0) {
                rows.push_back(i);
                normals.push_back(p.findex[i]);
                mu.push_back(p.hi[i]);
                lcp.always_free.back() = 0;
            }
        }
    }
};

}  // namespace ode_bpp::pivoting::test
