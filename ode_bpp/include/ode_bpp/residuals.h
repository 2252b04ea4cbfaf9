// ode_bpp/residuals.h: the quality measures of an MLCP answer, shared by the solver, the CLI and
// the benchmarks so that every method (ours, Dantzig, PGS, peers) is judged by the same numbers.
//
// Index space: the caller's original row order throughout.
#pragma once

#include <utility>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp {

struct Residuals {
    /// ||x - clamp(x - w, lo(x), hi(x))||_inf with w = A x - b and the friction bounds taken
    /// from x's own normal impulses (Result::natural_residual).
    double natural = 0;
    /// natural / max(1, ||b||_inf) (Result::relative_natural_residual).
    double relative_natural = 0;
    /// Scale-free version: max_i |x_i - clamp(x_i - w_i / A_ii, lo_i(x), hi_i(x))| / s_i with the
    /// row's own scale s_i = ((|A||x|)_i + |b_i|) / A_ii (0 where the numerator is 0), for a
    /// friction row at least |mu_i| s_findex[i], as its bound is known only to its normal's scale.
    /// The diagonal scaling keeps the same solution set and makes both terms units of x; this is
    /// the quantity the per-row tolerance Options::tolerance bounds (Result::scaled_natural_residual).
    double scaled_natural = 0;
    /// ||A_FF x_F - (b_F - A_FT x_T)||_inf = max over free rows of |w_i| (Result::free_residual).
    double free = 0;
    /// max over friction rows of max(0, |x_i| - mu_i |x_findex[i]|) (Result::friction_error).
    double friction = 0;
    /// relative_natural of the fixed-bound problem the answer implies: each friction row with a
    /// finite mu bounded by +-|x_i|, its own magnitude, instead of +-mu_i |x_findex[i]|. Frozen
    /// friction and ODE's Dantzig fix friction bounds that the answer does not carry; whatever
    /// they were, an exact answer of that fixed-bound problem has this residual at rounding level
    /// (a friction row strictly inside its bounds has w_i = 0, one at a bound has w_i of the sign
    /// that keeps it there), so a larger value refutes it. It cannot certify one: a row stopped
    /// short of its bound passes (Result::fixed_bound_residual).
    double fixed_bound = 0;
    /// scaled_natural of the same fixed-bound problem (Result::scaled_fixed_bound_residual).
    double scaled_fixed_bound = 0;
};

/// Row i's bounds at x: (-inf, +inf) for rows < nub and for a friction row whose mu_i = hi_i is
/// +inf (ODE's "never slips": such a row is unbounded whatever its normal, docs/modelling.md);
/// +-|mu_i x[findex[i]]| for any other friction row (0 when the normal impulse is 0, as ODE's
/// Dantzig does); (lo_i, hi_i) otherwise. x: n entries.
std::pair<double, double> effective_bounds(const Problem& problem, ConstStrided x, int i);

/// w = A x - b and scale = |A||x| + |b| (n entries each, outputs), with the full symmetric A read
/// from its lower triangle. O(n^2).
void residual_vectors(const Problem& problem, ConstStrided x, std::vector<double>& w, std::vector<double>& scale);

/// True for a friction row whose coefficient mu_i = hi_i is +inf: an unbounded row (effective_bounds).
bool is_unbounded_friction_row(const Problem& problem, int i);

/// All of Residuals at x (n entries). states (n entries) defines the free set of the free
/// residual; null means the rows strictly inside their effective bounds. The problem must have
/// passed validate(). O(n^2).
Residuals compute_residuals(const Problem& problem, ConstStrided x, const std::vector<RowState>* states = nullptr);

}  // namespace ode_bpp
