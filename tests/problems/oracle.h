// Brute-force reference answers for small problems, independent of the solver's code.
#pragma once

#include <optional>
#include <vector>

#include "problems/owned_problem.h"

namespace ode_bpp::problems {

/// The solution of the boxed LCP with the given fixed bounds (n entries each; rows < nub are
/// free whatever they say), found by trying all 3^n index sets with a dense Eigen LDL^T solve of
/// A_FF and keeping the one that satisfies the conditions of ode_bpp/solver.h to a relative
/// tolerance rel_tol * ((|A||x|)_i + |b_i|). For SPD A the solution is unique. n <= 12.
/// Empty when no index set qualifies.
std::optional<std::vector<double>> enumerate_boxed_lcp(const OwnedProblem& problem, const std::vector<double>& lo,
                                                       const std::vector<double>& hi, double rel_tol = 1e-9);

/// ODE Dantzig's friction semantics by enumeration: every friction row pinned at 0 for a first
/// solve, then bounds +-|mu x_normal| from its normals for a second (bounds from the problem's
/// lo/hi otherwise).
std::optional<std::vector<double>> enumerate_frozen_friction(const OwnedProblem& problem, double rel_tol = 1e-9);

}  // namespace ode_bpp::problems
