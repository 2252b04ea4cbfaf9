#include "pivoting/fixed_bound_solve.h"

#include <algorithm>
#include <limits>

#include "pivoting/active_set.h"
#include "pivoting/tuning.h"

namespace ode_bpp::pivoting {

FixedBoundSolver::FixedBoundSolver(BoxedLcp& lcp, FreeSolver& solver, const Options& options, double max_diag,
                                   PivotCounters& counters, FixedBoundBuffers& buffers, bool warm)
    : lcp_(lcp), solver_(solver), options_(options), counters_(counters), buffers_(buffers), regularization_(max_diag),
      warm_(warm) {}

FixedOutcome FixedBoundSolver::solve(std::vector<RowState>& states, std::vector<double>& x, int budget,
                                     AnswerUse use, StartBounds bounds) {
    use_ = use;
    start_bounds_ = bounds;
    start_ = states;
    if (!continuation_done_) run_continuation(states, x, budget);
    for (;;) {
        if (prepare(shift())) {
            const LoopOutcome outcome = at_target(states, x, budget);
            if (outcome == LoopOutcome::Converged) return FixedOutcome::Converged;
            if (outcome != LoopOutcome::Breakdown) return FixedOutcome::BudgetSpent;
        }
        if (!regularization_.raise_target()) return FixedOutcome::NotSpd;
        states = start_;
    }
}

/// The plain loop gets plain_steps() steps, fewer where a step leaves more than
/// Tuning::hand_over_above rows infeasible; if it has not converged by then, the
/// active-set method on an incremental factor (active_set.h) goes on from its least infeasible
/// iterate, with a budget of its own; where it does not finish, the rescue starts afresh
/// from the warm start with the rest of the budget, and should it give up, the plain loop
/// resumes from its least infeasible index set. Converged, MaxIterations or Breakdown.
LoopOutcome FixedBoundSolver::at_target(std::vector<RowState>& states, std::vector<double>& x, int budget) {
    int first = counters_.pivots;
    const auto left = [&] { return budget - (counters_.pivots - first); };
    const int plain = plain_steps();
    const bool rescue_allowed = plain > 0;
    const bool active_set_next = rescue_allowed && options_.tuning.active_set && active_set_applies(lcp_);
    PivotSettings plain_settings = settings(rescue_allowed ? std::min(budget, plain) : budget);
    if (active_set_next && start_bounds_ != StartBounds::Moved)
        plain_settings.hand_over_above = options_.tuning.hand_over_above;  // <= 0: never (pivot_loop.h)
    LoopOutcome outcome = pivot_fixed_bounds(lcp_, solver_, plain_settings, states, x, counters_, buffers_.loop);
    if (outcome != LoopOutcome::MaxIterations || !rescue_allowed || left() <= 0) return outcome;
    if (active_set_next) {
        const int before = counters_.pivots;
        outcome = by_active_set(states, x);
        if (outcome == LoopOutcome::Converged) return outcome;
        first += counters_.pivots - before;  // the active set had a budget of its own
    }
    outcome = rescue(states, x, left());
    if (outcome != LoopOutcome::Stalled) return outcome;
    if (!prepare(shift())) return LoopOutcome::Breakdown;
    if (left() <= 0) return LoopOutcome::MaxIterations;
    return pivot_fixed_bounds(lcp_, solver_, settings(left()), states, x, counters_, buffers_.loop);
}

/// The active-set method from x, the plain loop's least infeasible iterate (active_set.h), which
/// classifies its answer on w = (A + shift I)x - b itself and polishes it as the plain loop would.
/// Converged, MaxIterations or Breakdown; states and x as they came in unless Converged. The
/// factor keeps its storage for the next run unless it holds more than
/// Tuning::active_set_kept_factor_bytes.
LoopOutcome FixedBoundSolver::by_active_set(std::vector<RowState>& states, std::vector<double>& x) {
    const int max_steps = tuning::kActiveSetStepsPerRow * lcp_.n() + tuning::kActiveSetStepsExtra;
    const LoopOutcome outcome = active_set(lcp_, settings(max_steps), states, x, counters_, buffers_.active_set,
                                           buffers_.free_rows, solver_.latest_factor());
    if (buffers_.free_rows.storage_bytes() > options_.tuning.active_set_kept_factor_bytes) buffers_.free_rows.release();
    return outcome;
}

/// The rescue continuation (regularization.h): stages on A + delta I, the first from the warm
/// start, each later one from the last converged stage's index set, at most `budget` steps.
/// Converged (states, x: the answer on the target), Breakdown, or Stalled when it gives up,
/// leaving states and x as they came in and the solver prepared for another delta.
LoopOutcome FixedBoundSolver::rescue(std::vector<RowState>& states, std::vector<double>& x, int budget) {
    entry_states_ = states;
    entry_x_ = x;
    const int first = counters_.pivots;
    PivotSettings stage = settings(budget);
    const int murty_after = std::max(0, options_.tuning.murty_after);
    stage.stall_after = murty_after > std::numeric_limits<int>::max() - tuning::kMurtyPatience
                            ? 0  // no stall count: revisits alone end a stage
                            : murty_after + tuning::kMurtyPatience;
    std::vector<RowState> accepted = start_, trial;
    RescueSchedule schedule(regularization_);
    while (counters_.pivots - first < budget) {
        if (!prepare(schedule.delta())) return LoopOutcome::Breakdown;
        stage.max_pivots = budget - (counters_.pivots - first);
        trial = accepted;
        const int before = counters_.pivots;
        const LoopOutcome outcome = pivot_fixed_bounds(lcp_, solver_, stage, trial, x, counters_, buffers_.loop);
        if (outcome == LoopOutcome::Breakdown) return outcome;
        if (outcome == LoopOutcome::Converged) {
            accepted.swap(trial);
            if (schedule.at_target()) {
                states = accepted;
                ++counters_.rescues;
                return outcome;
            }
            schedule.converged(counters_.pivots - before);
        } else if (!schedule.stalled()) {
            break;
        }
    }
    states = entry_states_;
    x = entry_x_;
    return LoopOutcome::Stalled;
}

/// Tuning::continuation_stages solves on A + delta_k I before the first fixed-bound solve,
/// each from the last one's index set; later solves start warm anyway.
void FixedBoundSolver::run_continuation(std::vector<RowState>& states, std::vector<double>& x, int budget) {
    continuation_done_ = true;
    const int stages = options_.tuning.continuation_stages;
    for (int k = 0; k < stages; ++k) {
        const double delta = regularization_.continuation(k, stages);
        if (delta <= shift() || !prepare(delta)) break;
        std::vector<RowState> trial = states;
        if (pivot_fixed_bounds(lcp_, solver_, settings(budget), trial, x, counters_, buffers_.loop) == LoopOutcome::Breakdown) break;
        states.swap(trial);
    }
}

bool FixedBoundSolver::prepare(double shift) {
    lcp_.shift = shift;
    if (prepared_ == shift) return true;
    prepared_.reset();
    if (!solver_.prepare(shift)) return false;
    prepared_ = shift;
    return true;
}

int FixedBoundSolver::plain_steps() const {
    const Tuning& t = options_.tuning;
    if (t.rescue_after <= 0) return 0;
    if (start_bounds_ != StartBounds::Moved) return t.rescue_after;
    return std::max(1, warm_ ? t.rescue_after_moved_bounds : t.rescue_after_moved_bounds_cold);
}

PivotSettings FixedBoundSolver::settings(int budget) const {
    PivotSettings s;
    s.max_pivots = budget;
    s.murty_after = std::max(0, options_.tuning.murty_after);
    s.tolerance = options_.tolerance;
    s.record_steps = options_.record_steps;
    s.release_at_most = options_.tuning.active_set_release_at_most;
    s.answer = use_;
    return s;
}

}  // namespace ode_bpp::pivoting
