// Projected Gauss-Seidel, as ODE's quickstep applies it to the same MLCP (the baseline that
// games use instead of pivoting).
#pragma once

#include <vector>

#include "ode_bpp/solver.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::baselines {

/// `sweeps` Gauss-Seidel sweeps from x = 0 in row order: x_i <- clamp(x_i - w_i / A_ii,
/// lo_i(x), hi_i(x)), w = A x - b with the current x, a friction row's bounds taken from the
/// current value of its normal (quickstep's rule). Problem validated; A: linalg::SymmetricRows(problem,
/// {}); x: out, n entries, original space.
void solve_pgs(const Problem& problem, const linalg::SymmetricRows& A, int sweeps, std::vector<double>& x);

}  // namespace ode_bpp::baselines
