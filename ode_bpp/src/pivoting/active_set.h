// A primal-feasible active-set method for the fixed-bound problem: the stage of a fixed-bound
// solve that terminates finitely, where block pivots run out of steps.
//
// The maths. With A + shift I SPD (ODE's CFM > 0, or a shift of the breakdown ladder), the boxed
// LCP of boxed_lcp.h is exactly the KKT system of the strictly convex box QP
//     min q(x) = 1/2 x'(A + shift I)x - b'x   subject to   lo <= x <= hi,
// with w = (A + shift I)x - b = grad q the multipliers of the active bounds (w >= 0 at lo,
// w <= 0 at hi, w = 0 strictly inside), so its unique minimizer is the LCP's unique solution.
// The method (Nocedal & Wright, Numerical Optimization, Alg. 16.3, on bound constraints) keeps x
// feasible, the tight rows T at their bounds and every free row strictly inside its bounds:
//  - x* = the minimizer of q over the face {x_T fixed}: Eq. 6 with the free set's factor;
//  - if x* is within the bounds, x = x*; if every tight row's multiplier has the right sign
//    (Eq. 4, classify_row.h) x solves the problem, otherwise the tight rows with wrong-sign
//    multipliers leave T (appended to the factor), the most violated first and at most
//    PivotSettings::release_at_most of them, the next most violated (released all at once, most
//    of a pile's rows came back one step each: Tuning::active_set_release_at_most);
//  - otherwise the ratio test: x moves along x* - x until the first free row reaches a bound,
//    and that row joins T (one row removed from the factor).
// The first step after several rows left T may bend: the released rows that the new x* does not
// move strictly inwards rejoin T, and x moves along d = x* - x on the rest of F (d_i = 0 on the
// re-tightened rows) to the minimum of q along d (its curvature d'(A + shift I)d = |Lᵀ d|² from
// the free set's factor L), or to the first bound on the way. d is a descent direction: x*
// minimizes q on the larger face, so g'(x* - x) < 0 at x (not that face's minimizer), and each
// dropped term g_i d_i is > 0 (g_i = w_i has the wrong sign, d_i points outwards), so g'd < 0
// too. x minimizes the face before the release, so g is zero on that face's free rows (Eq. 6, to
// the factor's accuracy) and g'd sums the released rows' terms alone, each < 0. (Should rounding
// make g'd >= 0, only the most violated row stays released, as in the single-row method.) On the
// captured tail islands this frees the rows that projecting the start pushed onto a bound in a
// few steps instead of one each (docs/tuning.md).
// Why it terminates: q is convex along each segment and the step stops at or before the minimum
// along it, so q never rises. After a release, the next step falls strictly: the face step moves
// every released row strictly inwards (else it bends) and every other free row is strictly inside,
// so it is not zero (ibid., Thm. 16.5 for one row), and the bent step is a descent step of
// positive length. So the face minimizers where rows leave T have strictly falling q, hence no
// face (T with its bounds) repeats there, and between two of them each step reaches the face's
// minimizer, bends once, or moves at least one row into T: at most n + 2 steps. There are
// finitely many faces. Rows that may not be tight (BoxedLcp::always_free, infinite bounds) never
// join T; pinned rows (lo = hi) never leave it.
// Each step costs one solve with the free set's factor and one row update per row that changes
// set, at most O(|F|²) each (free_rows_factor.h), like one of ODE's Dantzig pivots; at a face's
// minimizer, w on the tight rows (the rows of A that Eq. 4 reads there), and on the free rows
// only where the updated factor's accuracy is checked: where its x* would be the answer, and
// every few minima on the way (tuning::kActiveSetUncheckedMinima; a factor that fails is
// rebuilt and the face's minimizer solved again from x*, which is feasible); a bent step adds a
// product with the factor. It starts from a given iterate projected onto the bounds, so a good
// start (the pivoting loop's least infeasible iterate) leaves only the rows whose state is wrong
// there.
//
// Index space: the permuted space of the BoxedLcp.
#pragma once

#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/free_rows_factor.h"
#include "pivoting/kept_buffers.h"
#include "pivoting/pivot_loop.h"

namespace ode_bpp::pivoting {

/// True when active_set can take this problem on: fixed bounds only (no moving friction bounds).
/// Any size: its factor is kept on the envelope (linalg/incremental_cholesky.h), at most about
/// twice that of A_FF in the island's order (free_rows_factor.h), the memory the loop's skyline
/// factors take anyway.
bool active_set_applies(const BoxedLcp& lcp);

/// The buffers of active_set (active_set.cpp), kept by the caller so that their capacity
/// outlives one run. One run per workspace at a time.
struct ActiveSetBuffers;
using ActiveSetWorkspace = KeptBuffers<ActiveSetBuffers>;
extern template class KeptBuffers<ActiveSetBuffers>;  // instantiated where ActiveSetBuffers is defined

/// Runs the active-set method on (A + lcp.shift I, b, lo, hi) (fixed bounds only) from x (n
/// entries, projected onto the bounds here; the rows at a bound after that start tight) for at
/// most settings.max_pivots steps, to settings.tolerance (classify_row.h) on w = (A + shift I)x - b
/// itself. Converged: states and x solve it, polished as the pivoting loop polishes its answers
/// (PivotSettings::polish: at most tuning::kPolishRounds releases of the tight rows wrong beyond
/// the factor's accuracy, on the unshifted problem), pinned rows at the bound their multiplier
/// supports. MaxIterations or Breakdown (a row dependent on the free set to machine
/// precision): states and x as they came in. Each step counts in counters.pivots, murty_pivots
/// (a single pivot) and update_steps. factor: the free set's factor (its state on return
/// unspecified). seed: a factor of the same A + shift I to build the free set's factor from
/// (FreeRowsFactor::reset), or none.
LoopOutcome active_set(const BoxedLcp& lcp, const PivotSettings& settings, std::vector<RowState>& states,
                       std::vector<double>& x, PivotCounters& counters, ActiveSetWorkspace& workspace,
                       FreeRowsFactor& factor, const EnvelopeFactor& seed = {});

}  // namespace ode_bpp::pivoting
