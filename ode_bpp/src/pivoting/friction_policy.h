// How friction bounds follow the normal impulses (Options::friction), as ordered stages of
// fixed-bound solves (fixed_bound_solve.h), each returning what it achieved.
//
// Index space: the permuted space of the solve.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/fixed_bound_solve.h"
#include "pivoting/friction_lcp.h"
#include "pivoting/friction_set.h"
#include "pivoting/lemke.h"

namespace ode_bpp::pivoting {

/// What a friction policy made of the problem; the answer is in its states and x either way.
enum class PolicyOutcome {
    Converged,             ///< every row satisfies Eq. 4 (Consistent: with bounds from its own normals)
    BudgetSpent,           ///< a fixed-bound solve of the answer ran out of pivot steps
    FrictionInconsistent,  ///< Consistent: the bounds still moved after Tuning::max_friction_rounds
    NotSpd,                ///< a Cholesky breakdown even on the largest regularization
};

/// Where Frozen friction's second solve starts: every row as requested (a warm start,
/// Tuning::frozen_second_solve_from_warm_start), or the friction rows as requested and the others
/// where the frictionless solve left them.
enum class SecondStart { Requested, FrictionRowsRequested };

/// Dantzig's semantics (ODE lcp.cpp): every friction row held at 0 while the others are solved,
/// then bounds +-|mu x_normal| from those normals, kept fixed for a second solve that starts from
/// `second` (StartBounds::Moved: from a warm start, the active set takes it over sooner). Without
/// friction rows, one solve. states: in, the requested start; out, the final index set.
PolicyOutcome solve_frozen(FixedBoundSolver& fixed, BoxedLcp& lcp, const FrictionSet& friction, int budget,
                           SecondStart second, std::vector<RowState>& states, std::vector<double>& x);

/// The second start Options ask for, given whether the solve started from a warm start.
SecondStart second_start(const Options& options, bool warm);

/// Consistent friction: every friction impulse within mu times its *own* normal. Stages, in order:
///  1. with a warm start, a linked solve straight from it (friction bounds moving with the
///     normals inside every pivot step, friction_link.h), then Lemke's method on the friction LCP
///     (friction_lcp.h) certified by a linked solve;
///  2. the Frozen answer, a linked solve from it, then the Lemke stage if it has not run;
///  3. damped, Anderson-accelerated outer rounds of fixed-bound solves (friction_update.h) from
///     the best iterate, until every friction row is consistent with its own normal.
/// The outer rounds converge only while the map from bounds to normals contracts, which the
/// capstan effect of a chain on a drum breaks; the linked solve and Lemke are what finish those
/// (docs/tuning.md has the measurements behind the order).
class ConsistentFriction {
public:
    /// warm: the solve starts from an earlier index set (Start::states), which stage 1 needs.
    ConsistentFriction(FixedBoundSolver& fixed, BoxedLcp& lcp, const FrictionSet& friction, const Options& options,
                       bool warm, PivotCounters& counters)
        : fixed_(fixed), lcp_(lcp), friction_(friction), options_(options), warm_(warm), counters_(counters) {}

    PolicyOutcome solve(std::vector<RowState>& states, std::vector<double>& x);

    /// Why the Lemke stage did not finish, if it ran. The outer bound updates and Lemke's pivots
    /// are counted in counters.friction_rounds and counters.lemke_pivots.
    const std::string& note() const { return note_; }

private:
    /// A stage either finished the problem (a certified consistent answer in states and x),
    /// left it unfinished (states and x: its least infeasible iterate, or as they came in), or
    /// met a breakdown even on the largest regularization.
    enum class Stage { Finished, Unfinished, NotSpd };

    Stage linked_solve(std::vector<RowState>& states, std::vector<double>& x, bool from_answer);
    Stage lemke(std::vector<RowState>& states, std::vector<double>& x);
    /// Lemke's path on the dense friction LCP, and on the sparse one (guess: its starting basis).
    LemkeSolution dense_lemke(const FrictionLcp& lcp);
    LemkeSolution sparse_lemke(const FrictionLcp& lcp, const std::vector<char>& guess);
    PolicyOutcome outer_rounds(std::vector<RowState>& states, std::vector<double>& x, bool budget_spent);
    /// A linked solve from the outer rounds' consistent answer, kept where it finishes.
    void certify_rounds(std::vector<RowState>& states, std::vector<double>& x);
    /// Options::max_pivots, at least 1: the budget of each fixed-bound solve.
    int budget() const { return std::max(1, options_.max_pivots); }
    /// An upper bound of the friction LCP's size (friction_lcp.h).
    int lemke_variables_at_most() const;

    FixedBoundSolver& fixed_;
    BoxedLcp& lcp_;
    const FrictionSet& friction_;
    const Options& options_;
    bool warm_;
    PivotCounters& counters_;
    bool lemke_tried_ = false;
    std::string note_;
};

}  // namespace ode_bpp::pivoting
