// Júdice-Pires block principal pivoting with Murty's single-pivot safeguard, for the boxed LCP
// with fixed bounds (paper Sec. 3.1, Eq. 4-6, Alg. 1/2 outer loop), in the permuted space.
#pragma once

#include <memory>
#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/free_solver.h"
#include "pivoting/iterate.h"
#include "pivoting/kept_buffers.h"

namespace ode_bpp::pivoting {

/// What a run's (or a fixed-bound solve's) answer is for.
enum class AnswerUse {
    Final,         ///< reported: its w and row scales end complete on every row (its residuals
                   ///< read them, solver.cpp), and the workspace keeps it (converged_iterate)
    Intermediate,  ///< read by a later solve through x and the index set only (Frozen friction's
                   ///< frictionless solve): every step refreshes the rows Eq. 4 reads only, and
                   ///< nothing is kept
};

/// What one run of the loop may do; the defaults are Options' and Tuning's (fixed_bound_solve.cpp
/// derives every run's settings from them).
struct PivotSettings {
    int max_pivots = Options{}.max_pivots;       ///< solves of Eq. 6 allowed in this run
    int murty_after = Tuning{}.murty_after;      ///< block steps without a new minimum of infeasible rows before Murty
    double tolerance = Options{}.tolerance;      ///< relative, scaled per row (classify_row.h)
    bool record_steps = true;                    ///< |T| of every step into tight_per_step
    /// Steps without a new least count of infeasible rows after which the run gives up with
    /// LoopOutcome::Stalled (in the block and in Murty's phase alike); 0: never. A run that may
    /// stall also stalls as soon as a block step returns to an index set it has already visited:
    /// a block step is a function of the index set, so the run has entered a cycle and waiting
    /// only repeats it.
    int stall_after = 0;
    /// A step that leaves more rows infeasible than this ends the run at once with
    /// LoopOutcome::MaxIterations, x and states as for that outcome (Tuning::hand_over_above);
    /// 0 or less: never.
    int hand_over_above = 0;
    /// After convergence on the unshifted problem, free the tight rows whose multiplier has the
    /// wrong sign beyond the factor's accuracy and pivot on from there (pivot_loop.cpp, polish);
    /// the new answer replaces the first only if it converges too.
    bool polish = true;
    /// The active set's release: most tight rows with wrong-sign multipliers freed at once
    /// (Tuning::active_set_release_at_most); 0 or less: all.
    int release_at_most = Tuning{}.active_set_release_at_most;
    AnswerUse answer = AnswerUse::Final;         ///< what the run's answer is for
};

/// Counters accumulated over every run of the loop that a solve makes.
/// The loop's counts are the public PivotStats (ode_bpp/solver.h), summed over every fixed-bound
/// solve of one answer.
using PivotCounters = PivotStats;


/// How a run of the loop ended.
enum class LoopOutcome {
    Converged,      ///< no row infeasible: x solves the boxed LCP to the scaled tolerance
    MaxIterations,  ///< budget spent: x is the least infeasible iterate, projected onto the bounds
    Stalled,        ///< settings.stall_after steps without progress, or a cycle of block steps;
                    ///< x and states as for MaxIterations
    Breakdown,      ///< the strategy met a non-positive pivot; x and states are not meaningful
};

/// The loop's buffers (pivot_loop.cpp), kept by the caller so that their capacity outlives one
/// run: a warm run allocates nothing. One run per workspace at a time.
struct LoopBuffers;
using LoopWorkspace = KeptBuffers<LoopBuffers>;
extern template class KeptBuffers<LoopBuffers>;  // instantiated where LoopBuffers is defined

/// Runs the loop from the index set `states` (n entries, permuted space; rows that must be free
/// or are pinned are corrected first) and leaves the final index set there. x: out, n entries,
/// permuted space; always within [lo, hi] unless the outcome is Breakdown.
/// The solver must have been prepared with lcp.shift.
/// workspace: the loop's buffers.
LoopOutcome pivot_fixed_bounds(const BoxedLcp& lcp, FreeSolver& solver, const PivotSettings& settings,
                               std::vector<RowState>& states, std::vector<double>& x, PivotCounters& counters,
                               LoopWorkspace& workspace);
/// The same with buffers of its own (allocated for this run).
LoopOutcome pivot_fixed_bounds(const BoxedLcp& lcp, FreeSolver& solver, const PivotSettings& settings,
                               std::vector<RowState>& states, std::vector<double>& x, PivotCounters& counters);

/// w = A x - b and the row scales |A||x| + |b| (refresh_residual) at x, when x is bit for bit
/// the answer of the workspace's latest run and that run converged on the unshifted problem
/// (lcp.shift == 0); null otherwise. Valid until the workspace's next run. The answer of a solve
/// need not come from the loop's latest run (single pivots, a projected iterate), hence the test.
const Iterate* converged_iterate(LoopWorkspace& workspace, const std::vector<double>& x);

}  // namespace ode_bpp::pivoting
