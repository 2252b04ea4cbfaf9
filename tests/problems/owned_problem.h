// An MLCP that owns its storage, for tests and benchmarks; view() gives the ode_bpp::Problem.
#pragma once

#include <string>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp::problems {

struct OwnedProblem {
    std::string name;
    int n = 0;
    int lda = 0;               ///< row stride of A (>= n; generators pad like ODE's dPAD)
    int nub = 0;
    std::vector<double> A;     ///< n x lda row-major, both triangles filled (solvers read the lower)
    std::vector<double> b, lo, hi;
    std::vector<int> findex;   ///< n entries or empty (no friction)
    std::vector<int> block_row, block_body;  ///< constraint-graph blocks or empty

    /// A view onto this object's storage (valid while it lives and is not resized).
    Problem view() const;
    operator Problem() const { return view(); }  // NOLINT: deliberate, tests pass problems as views
    double a(int i, int j) const { return A[static_cast<std::size_t>(i) * lda + j]; }
    double& a(int i, int j) { return A[static_cast<std::size_t>(i) * lda + j]; }
    /// Allocates an n x n problem with lda = n rounded up to a multiple of 4 (as dPAD does),
    /// zero A and b, and unbounded rows.
    static OwnedProblem zeros(std::string name, int n);
};

}  // namespace ode_bpp::problems
