// Shared set-up of the test_pivoting_* suites.
#pragma once

#include <cmath>
#include <numeric>
#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/friction_set.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::pivoting::test {

/// The driver's BoxedLcp of a problem in its own order (build_boxed_lcp with the identity),
/// with its friction rows, their normals and mu.
struct DriverLcp {
    linalg::SymmetricRows A;
    BoxedLcp lcp;
    FrictionSet friction;
    explicit DriverLcp(const Problem& p) : A(p, {}) {
        std::vector<int> identity(static_cast<std::size_t>(p.n));
        std::iota(identity.begin(), identity.end(), 0);
        build_boxed_lcp(p, A, identity, lcp, friction);
    }
};

}  // namespace ode_bpp::pivoting::test
