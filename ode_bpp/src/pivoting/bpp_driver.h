// The BPP methods end to end: ordering, factor strategy, friction policy, the rescue
// continuation of a fixed-bound solve that does not converge plainly (Tuning::rescue_after), the
// optional up-front continuation and the regularize-on-breakdown retry around the pivoting loop.
#pragma once

#include <vector>

#include "ode_bpp/solver.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::pivoting {

/// Solves a validated problem with options.method in {BppChol, BppDown, BppSky, Bpp}.
/// A: linalg::SymmetricRows(problem, {}), the problem's matrix in original order.
/// x: out, n entries, original space (zero when the status is NotSpd).
/// Fills status, message, fallback ("regularized" or empty), the counters, tight, states
/// (original space) and factor_error; leaves the residual fields to the caller.
Result solve_bpp(const Problem& problem, const linalg::SymmetricRows& A, const Options& options, const Start& start,
                 std::vector<double>& x);

}  // namespace ode_bpp::pivoting
