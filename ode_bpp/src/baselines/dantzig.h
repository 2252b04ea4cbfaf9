// ODE's stock Dantzig solver (dSolveMLCPDantzig from the ode-bpp patch) on our Problem.
#pragma once

#include <vector>

#include "linalg/symmetric_rows.h"
#include "ode_bpp/solver.h"

namespace ode_bpp::baselines {

/// Copies the problem into ODE's layout (A, the problem's matrix in original order, expanded into
/// a full n x dPAD(n) buffer, which ODE destroys: O(n^2); contiguous b, lo, hi, findex) and runs
/// ODE's Dantzig. Problem validated; x: out,
/// n entries, original space, possibly non-finite (ODE does not check). False when ODE refused
/// the call (no memory); x is then zero.
bool solve_dantzig(const Problem& problem, const linalg::SymmetricRows& A, std::vector<double>& x);

}  // namespace ode_bpp::baselines
