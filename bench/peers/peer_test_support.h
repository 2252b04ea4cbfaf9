// Shared checks of the peer adapters' gtests: an adapter's answer against a reference answer.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "ode_bpp/solver.h"

namespace ode_bpp::peers::testing {

/// ||x - reference||_inf <= rel_tol * max(1, ||reference||_inf): the answers agree to a tolerance
/// that scales with the answer.
inline ::testing::AssertionResult agrees(const std::vector<double>& x, const std::vector<double>& reference,
                                         double rel_tol) {
    double scale = 1.0, gap = 0.0;
    for (std::size_t i = 0; i < reference.size(); ++i) {
        scale = std::max(scale, std::fabs(reference[i]));
        gap = std::max(gap, std::fabs(x[i] - reference[i]));
    }
    if (gap <= rel_tol * scale) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "||x - reference||_inf = " << gap << " > " << rel_tol << " * " << scale;
}

/// ODE's own Dantzig on the problem (the reference the peers' Dantzig ports must reproduce);
/// its status in *status.
inline std::vector<double> odes_dantzig_answer(const ode_bpp::Problem& p, ode_bpp::Status* status) {
    ode_bpp::Options options;
    options.method = ode_bpp::Method::Dantzig;
    std::vector<double> x(static_cast<std::size_t>(p.n));
    *status = ode_bpp::solve(p, options, x.data()).status;
    return x;
}

}  // namespace ode_bpp::peers::testing
