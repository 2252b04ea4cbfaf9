// ode_bpp/residuals.h: the quality measures of an MLCP answer, shared by the solver, the CLI and
// the benchmarks so that every method (ours, Dantzig, PGS, peers) is judged by the same numbers.
//
// Index space: the caller's original row order throughout.
#pragma once

#include "ode_bpp/export.h"

#include <utility>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp {

/// (Residuals, the measures themselves, is declared in ode_bpp/solver.h as part of Result.)

/// Row i's bounds at x: (-inf, +inf) for rows < nub and for a friction row whose mu_i = hi_i is
/// +inf (ODE's "never slips": such a row is unbounded whatever its normal, docs/modelling.md);
/// +-|mu_i x[findex[i]]| for any other friction row (0 when the normal impulse is 0, as ODE's
/// Dantzig does); (lo_i, hi_i) otherwise. x: n entries.
ODE_BPP_API std::pair<double, double> effective_bounds(const Problem& problem, ConstStrided x, int i);

/// w = A x - b and scale = |A||x| + |b| (n entries each, outputs), with the full symmetric A read
/// from its lower triangle. O(n^2).
ODE_BPP_API void residual_vectors(const Problem& problem, ConstStrided x, std::vector<double>& w, std::vector<double>& scale);

/// True for a friction row whose coefficient mu_i = hi_i is +inf: an unbounded row (effective_bounds).
ODE_BPP_API bool is_unbounded_friction_row(const Problem& problem, int i);

/// All of Residuals at x (n entries). states (n entries) defines the free set of the free
/// residual; null means the rows strictly inside their effective bounds. The problem must have
/// passed validate(). O(n^2).
ODE_BPP_API Residuals compute_residuals(const Problem& problem, ConstStrided x, const std::vector<RowState>* states = nullptr);

}  // namespace ode_bpp
