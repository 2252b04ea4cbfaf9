// Single principal pivots on an incrementally updated dense factor of A_FF: where block steps
// cycle (nearly redundant contact rows, box friction flipping between its bounds), each pivot
// moves one row between F and T and so changes L_FF by one appended row or one removed row
// (free_rows_factor.h), O(|F|²), instead of a deletion from L0 or a refactorization per step.
// The most violated row flips, and Murty's rule (murty_rule.h) takes over where that
// cycles, so that the method terminates finitely on A + shift I SPD (single_pivots.cpp).
//
// Index space: the permuted space of the BoxedLcp.
#pragma once

#include <memory>
#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/free_rows_factor.h"
#include "pivoting/pivot_loop.h"

namespace ode_bpp::pivoting {

/// True when single_pivots can take this problem on: fixed bounds only (no moving friction
/// bounds), and small enough for a dense factor (tuning::kSinglePivotMaxRows).
bool single_pivots_apply(const BoxedLcp& lcp);

/// The buffers of single_pivots (single_pivots.cpp), kept by the caller so that their capacity
/// outlives one run: a warm run allocates nothing. One run per workspace at a time.
struct SinglePivotBuffers;
using SinglePivotsWorkspace = KeptBuffers<SinglePivotBuffers>;
extern template class KeptBuffers<SinglePivotBuffers>;  // instantiated where SinglePivotBuffers is defined

/// Runs single pivots from `states` (a normalized index set, e.g. the pivoting loop's least
/// infeasible one) on (A + lcp.shift I, b, lo, hi) for at most settings.max_pivots pivots, to
/// settings.tolerance (classify_row.h). Converged: states and x (n entries) solve it.
/// MaxIterations (budget, or tuning::kSinglePivotPatience pivots without progress) or Breakdown
/// (an appended row dependent on the free set to machine precision): states as they came in,
/// x unspecified. Each pivot counts in counters.pivots, murty_pivots and update_steps.
/// workspace: the run's buffers; factor: the free set's factor (its state on return unspecified).
LoopOutcome single_pivots(const BoxedLcp& lcp, const PivotSettings& settings, std::vector<RowState>& states,
                          std::vector<double>& x, PivotCounters& counters, SinglePivotsWorkspace& workspace,
                          FreeRowsFactor& factor);

}  // namespace ode_bpp::pivoting
