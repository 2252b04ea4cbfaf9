// The residuals of ode_bpp/residuals.h from A's compressed rows, for callers that already hold
// them (solve(), PGS): O(nnz) instead of another O(n^2) pass over the dense A.
#pragma once

#include <vector>

#include "ode_bpp/residuals.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp {

/// As compute_residuals(problem, x, states); A: linalg::SymmetricRows(problem, {}) (original order).
Residuals compute_residuals(const Problem& problem, const linalg::SymmetricRows& A, ConstStrided x,
                            const std::vector<RowState>* states);

/// As residual_vectors(problem, x, w, scale), from A = linalg::SymmetricRows(problem, {}).
void residual_vectors(const Problem& problem, const linalg::SymmetricRows& A, ConstStrided x, std::vector<double>& w,
                      std::vector<double>& scale);

}  // namespace ode_bpp
