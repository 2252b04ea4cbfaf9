// One fixed-bound solve of a BPP method: the boxed LCP with its bounds as they stand (paper
// Eq. 3-6) solved by the pivoting loop (pivot_loop.h) on the shifts that regularization.h
// decides: the plain attempt from the warm start; where that does not converge within
// Tuning::rescue_after steps (rescue_after_moved_bounds, or rescue_after_moved_bounds_cold without
// a warm start, for a solve whose bounds have just moved, StartBounds), or whose step leaves more
// than Tuning::hand_over_above rows infeasible (other solves), the active-set method on an
// incremental factor kept on its envelope (active_set.h, which terminates finitely), then the
// rescue continuation, then the plain loop again where the rescue gives up; and all of it again
// one rung up the breakdown ladder after a Cholesky breakdown.
//
// Index space: the permuted space of the BoxedLcp and its FreeSolver.
#pragma once

#include <optional>
#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/active_set.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/free_rows_factor.h"
#include "pivoting/free_solver.h"
#include "pivoting/pivot_loop.h"
#include "pivoting/regularization.h"

namespace ode_bpp::pivoting {

/// How a fixed-bound solve ended.
enum class FixedOutcome {
    Converged,    ///< x solves (A + shift() I, b, lo, hi) to the tolerance
    BudgetSpent,  ///< the pivot budget ran out; x is the least infeasible iterate, within bounds
    NotSpd,       ///< a Cholesky breakdown even on the last rung of the ladder
};

/// The buffers of a fixed-bound solve's stages, kept by the caller (BppWorkspace) so that their
/// capacity outlives one solve.
struct FixedBoundBuffers {
    LoopWorkspace loop;
    FreeRowsFactor free_rows;  ///< the active set's factor (on the envelope, free_rows_factor.h)
    ActiveSetWorkspace active_set;
};

/// What the index set a fixed-bound solve starts from answered: the bounds as they stand, or
/// bounds that have moved since (Frozen friction's second solve: friction rows bounded anew by
/// mu times the frictionless normals, while the warm start holds the previous step's states).
enum class StartBounds { Same, Moved };

class FixedBoundSolver {
public:
    /// lcp: the problem (its shift is set here); solver: a factor strategy on lcp.A; options:
    /// murty_after, tolerance, record_steps, rescue_after, rescue_after_moved_bounds(_cold),
    /// continuation_stages; max_diag: max_i A_ii; counters: accumulated over every solve;
    /// buffers: the stages' buffers; warm: the caller's solve started from Start::states.
    FixedBoundSolver(BoxedLcp& lcp, FreeSolver& solver, const Options& options, double max_diag,
                     PivotCounters& counters, FixedBoundBuffers& buffers, bool warm);

    /// Solves from `states` (in: the warm start; out: the final index set) within `budget` pivot
    /// steps of the target problem. x: out, n entries. bounds: what `states` answered.
    FixedOutcome solve(std::vector<RowState>& states, std::vector<double>& x, int budget,
                       AnswerUse use = AnswerUse::Final, StartBounds bounds = StartBounds::Same);

    /// delta of the problem every answer solves: 0 unless a breakdown raised it.
    double shift() const { return regularization_.target(); }

private:
    LoopOutcome at_target(std::vector<RowState>& states, std::vector<double>& x, int budget);
    LoopOutcome by_active_set(std::vector<RowState>& states, std::vector<double>& x);
    LoopOutcome rescue(std::vector<RowState>& states, std::vector<double>& x, int budget);
    void run_continuation(std::vector<RowState>& states, std::vector<double>& x, int budget);
    /// Factors A + shift I unless the solver already holds that factor; false on breakdown.
    bool prepare(double shift);
    PivotSettings settings(int budget) const;
    /// Steps of the plain attempt before the active set and the rescue; 0: neither.
    int plain_steps() const;

    BoxedLcp& lcp_;
    FreeSolver& solver_;
    const Options& options_;
    PivotCounters& counters_;
    FixedBoundBuffers& buffers_;
    Regularization regularization_;
    std::optional<double> prepared_;       ///< the shift the solver holds a factor of
    AnswerUse use_ = AnswerUse::Final;     ///< of the solve in progress
    StartBounds start_bounds_ = StartBounds::Same;  ///< of the solve in progress
    const bool warm_;                      ///< the caller's solve started from Start::states
    bool continuation_done_ = false;       ///< the up-front continuation runs before the first solve only
    std::vector<RowState> start_, entry_states_;  ///< warm start of a solve; states entering a rescue
    std::vector<double> entry_x_;
};

}  // namespace ode_bpp::pivoting
