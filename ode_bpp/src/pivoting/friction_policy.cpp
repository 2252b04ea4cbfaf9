#include "pivoting/friction_policy.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "pivoting/friction_lcp.h"
#include "pivoting/friction_update.h"
#include "pivoting/lemke.h"
#include "pivoting/sparse_lemke.h"
#include "pivoting/tuning.h"

namespace ode_bpp::pivoting {

SecondStart second_start(const Options& options, bool warm) {
    return warm && options.tuning.frozen_second_solve_from_warm_start ? SecondStart::Requested
                                                                      : SecondStart::FrictionRowsRequested;
}

PolicyOutcome solve_frozen(FixedBoundSolver& fixed, BoxedLcp& lcp, const FrictionSet& friction, int budget,
                           SecondStart second, std::vector<RowState>& states, std::vector<double>& x) {
    const auto outcome = [](FixedOutcome o) {
        return o == FixedOutcome::NotSpd ? PolicyOutcome::NotSpd
               : o == FixedOutcome::BudgetSpent ? PolicyOutcome::BudgetSpent
                                                : PolicyOutcome::Converged;
    };
    if (friction.empty()) return outcome(fixed.solve(states, x, budget));
    const std::vector<RowState> requested = states;
    friction.set_bounds(lcp, std::vector<double>(friction.size(), 0.0));
    const FixedOutcome frictionless = fixed.solve(states, x, budget, AnswerUse::Intermediate);
    if (frictionless == FixedOutcome::NotSpd) return PolicyOutcome::NotSpd;
    friction.set_bounds(lcp, friction.targets(x));
    if (second == SecondStart::Requested) states = requested;
    else
        for (int i : friction.rows) states[i] = requested[i];
    const FixedOutcome frozen = fixed.solve(states, x, budget, AnswerUse::Final, StartBounds::Moved);
    if (frozen == FixedOutcome::NotSpd) return PolicyOutcome::NotSpd;
    return frictionless == FixedOutcome::BudgetSpent ? PolicyOutcome::BudgetSpent : outcome(frozen);
}

PolicyOutcome ConsistentFriction::solve(std::vector<RowState>& states, std::vector<double>& x) {
    if (options_.tuning.link_friction && warm_ && !friction_.empty()) {
        const std::vector<RowState> warm = states;
        friction_.set_bounds(lcp_, friction_.mu);  // placeholders: every step sets them from the normals first
        Stage stage = linked_solve(states, x, /*from_answer=*/false);
        if (stage != Stage::Unfinished) return stage == Stage::Finished ? PolicyOutcome::Converged : PolicyOutcome::NotSpd;
        states = warm;
        stage = lemke(states, x);
        if (stage != Stage::Unfinished) return stage == Stage::Finished ? PolicyOutcome::Converged : PolicyOutcome::NotSpd;
    }
    // here the states are what the linked stages left where they ran, no longer the warm start
    const PolicyOutcome frozen =
        solve_frozen(fixed_, lcp_, friction_, budget(), SecondStart::FrictionRowsRequested, states, x);
    if (frozen == PolicyOutcome::NotSpd || friction_.empty()) return frozen;
    bool budget_spent = frozen == PolicyOutcome::BudgetSpent;
    if (options_.tuning.link_friction) {
        for (const bool from_lemke : {false, true}) {
            const Stage stage = from_lemke ? lemke(states, x) : linked_solve(states, x, /*from_answer=*/true);
            if (stage != Stage::Unfinished) return stage == Stage::Finished ? PolicyOutcome::Converged : PolicyOutcome::NotSpd;
        }
        // the outer rounds go on from the linked solve's least infeasible iterate (96.3 % against
        // 92 % from the Frozen answer) and re-solve with its bounds fixed first: that iterate may
        // be consistent in its friction but not yet a solution of the other rows
        friction_.set_bounds(lcp_, friction_.targets(x));
        ++counters_.friction_rounds;
        const FixedOutcome o = fixed_.solve(states, x, budget());
        if (o == FixedOutcome::NotSpd) return PolicyOutcome::NotSpd;
        budget_spent = budget_spent || o == FixedOutcome::BudgetSpent;
    }
    return outer_rounds(states, x, budget_spent);
}

/// Outer rounds until every friction row is consistent with the bound its own normal implies,
/// or Tuning::max_friction_rounds. budget_spent: an earlier fixed-bound solve of this answer ran
/// out of steps (its status then says so).
PolicyOutcome ConsistentFriction::outer_rounds(std::vector<RowState>& states, std::vector<double>& x, bool budget_spent) {
    FrictionBoundUpdate update(options_.tuning.friction_damping);  // in (0, 1]: solve()'s validate_call
    for (;;) {
        if (friction_.consistent(lcp_, options_.tolerance, states, x)) {
            if (!budget_spent) certify_rounds(states, x);
            return budget_spent ? PolicyOutcome::BudgetSpent : PolicyOutcome::Converged;
        }
        if (counters_.friction_rounds >= options_.tuning.max_friction_rounds)
            return budget_spent ? PolicyOutcome::BudgetSpent : PolicyOutcome::FrictionInconsistent;
        friction_.set_bounds(lcp_, update.next(friction_.bounds(lcp_), friction_.targets(x)));
        ++counters_.friction_rounds;
        const FixedOutcome o = fixed_.solve(states, x, budget());
        if (o == FixedOutcome::NotSpd) return PolicyOutcome::NotSpd;
        budget_spent = budget_spent || o == FixedOutcome::BudgetSpent;
    }
}

/// The rounds stop where each friction impulse is within the consistency test's per-row
/// tolerance of mu times its normal, which leaves it off by up to tol * scale (a rock pile island:
/// 5.2e-7, relative residual 2.4e-8). A linked solve from that answer holds each friction row at
/// a bound to its own normal exactly (friction_link.h), usually in one step; its answer replaces
/// the rounds' where it finishes, else theirs stands.
void ConsistentFriction::certify_rounds(std::vector<RowState>& states, std::vector<double>& x) {
    if (!options_.tuning.link_friction) return;
    std::vector<RowState> linked_states = states;
    std::vector<double> linked_x = x;
    const std::vector<double> bounds = friction_.bounds(lcp_);
    if (linked_solve(linked_states, linked_x, /*from_answer=*/true) == Stage::Finished) {
        states.swap(linked_states);
        x.swap(linked_x);
    } else {
        friction_.set_bounds(lcp_, bounds);
    }
}

/// A solve with moving friction bounds (friction_link.h) from states, with kLinkedBudgetFactor
/// times the pivot budget. from_answer: start from the bounds mu |x_n| of the answer in x (else
/// from the bounds already set). Finished when it converged to a consistent answer.
ConsistentFriction::Stage ConsistentFriction::linked_solve(std::vector<RowState>& states, std::vector<double>& x,
                                                           bool from_answer) {
    if (from_answer) friction_.set_bounds(lcp_, friction_.targets(x));
    friction_.link(lcp_);
    ++counters_.linked_solves;
    const FixedOutcome o = fixed_.solve(states, x, tuning::kLinkedBudgetFactor * budget());
    lcp_.friction_normal.clear();
    lcp_.friction_mu.clear();
    if (o == FixedOutcome::NotSpd) return Stage::NotSpd;
    return o == FixedOutcome::Converged && friction_.consistent(lcp_, options_.tolerance, states, x) ? Stage::Finished
                                                                                                   : Stage::Unfinished;
}

/// Lemke's method on the friction LCP (a copositive LCP, which Lemke solves where block pivoting
/// with moving bounds cycles), then a linked solve from the index set of its answer, which
/// certifies it to the loop's own tolerance (usually in one step). Runs once per solve;
/// Unfinished leaves states and x as they came in.
ConsistentFriction::Stage ConsistentFriction::lemke(std::vector<RowState>& states, std::vector<double>& x) {
    if (lemke_tried_ || !options_.tuning.lemke_friction) return Stage::Unfinished;
    lemke_tried_ = true;
    const int variables = lemke_variables_at_most();
    const bool fits_dense = lcp_.n() <= tuning::kLemkeMaxRows && variables <= tuning::kLemkeMaxVariables;
    if (!fits_dense && variables > tuning::kSparseLemkeMaxVariables) {
        note_ = "Lemke stage skipped: the island is too large even for the sparse Lemke stage";
        return Stage::Unfinished;
    }
    // the sparse stage wherever it applies from kSparseLemkeFromVariables on: it forms no dense M
    // and pays one sparse solve per pivot (docs/tuning.md)
    const bool dense = fits_dense && (variables < tuning::kSparseLemkeFromVariables ||
                                      !FrictionLcp::has_sparse_form(lcp_, friction_.view()));
    std::string why;
    const std::optional<FrictionLcp> lcp =
        dense ? FrictionLcp::build(lcp_, friction_.view(), why) : FrictionLcp::build_sparse(lcp_, friction_.view(), why);
    if (!lcp) {
        note_ = "Lemke stage skipped: " + why;
        return Stage::Unfinished;
    }
    const LemkeSolution s = dense ? dense_lemke(*lcp) : sparse_lemke(*lcp, lcp->basis_guess(states, x));
    // An inaccurate answer (its path passed a nearly singular basis, sparse_lemke.h) still goes
    // to the linked solve below, which certifies it by its own test or hands the island on: a
    // 291-row cannon island finished there at a relative residual of 1e-10, where the outer
    // rounds stalled at 1.5e-8 (docs/benchmarks.md, "Certified answers on the piles").
    const bool inaccurate = s.outcome == LemkeOutcome::Inaccurate;
    if (s.outcome != LemkeOutcome::Solved && !inaccurate) {
        note_ = s.outcome == LemkeOutcome::RayTermination  ? "Lemke stage ended on a ray"
                : s.outcome == LemkeOutcome::SingularBasis ? "Lemke stage's basis factor broke down"
                                                           : "Lemke stage ran out of pivots";
        return Stage::Unfinished;
    }
    std::vector<RowState> lemke_states;
    std::vector<double> lemke_x;
    lcp->recover(s, lemke_x, lemke_states);
    if (!std::all_of(lemke_x.begin(), lemke_x.end(), [](double v) { return std::isfinite(v); })) {
        note_ = "Lemke's answer was not finite";
        return Stage::Unfinished;
    }
    const Stage certified = linked_solve(lemke_states, lemke_x, /*from_answer=*/true);
    if (certified == Stage::Unfinished)
        note_ = inaccurate ? "Lemke stage's answer was inaccurate and did not pass the linked solve"
                           : "Lemke's answer did not pass the linked solve";
    if (certified != Stage::Finished) return certified;
    states = lemke_states;
    x = lemke_x;
    return Stage::Finished;
}

/// Up to tuning::kLemkeAttempts covering vectors, each with kLemkePivotsPerVariable pivots per
/// variable.
LemkeSolution ConsistentFriction::dense_lemke(const FrictionLcp& lcp) {
    const int size = static_cast<int>(lcp.q().size());
    LemkeSolution s;
    for (int attempt = 0; attempt < tuning::kLemkeAttempts && s.outcome != LemkeOutcome::Solved; ++attempt) {
        s = solve_lemke(lcp.M(), lcp.q(), spread_covering_vector(size, attempt), tuning::kLemkePivotsPerVariable * size + 10);
        counters_.lemke_pivots += s.pivots;
    }
    return s;
}

/// First from the guessed basis, then from the slack basis with one spread covering vector after
/// another while a path ends on a ray or an inaccurate answer (at most
/// tuning::kSparseLemkeAttempts paths), all within one budget (the piles'
/// paths are long, and how long depends on the covering vector: docs/tuning.md).
LemkeSolution ConsistentFriction::sparse_lemke(const FrictionLcp& lcp, const std::vector<char>& guess) {
    const int size = static_cast<int>(lcp.q().size());
    int budget = static_cast<int>(
        std::min<long long>(static_cast<long long>(tuning::kSparseLemkePivotsPerVariable) * size + 10, tuning::kSparseLemkeMaxPivots));
    LemkeSolution s;
    for (int attempt = 0; attempt < tuning::kSparseLemkeAttempts && budget > 0; ++attempt) {
        s = solve_sparse_lemke(lcp.sparse_M(), lcp.q(), attempt == 0 ? guess : std::vector<char>{},
                               spread_covering_vector(size, attempt), budget);
        counters_.lemke_pivots += s.pivots;
        budget -= s.pivots;
        if (s.outcome == LemkeOutcome::Solved || s.outcome == LemkeOutcome::MaxPivots) break;
    }
    return s;
}

/// 3 variables per friction row, 2 per other row bounded on both sides, 1 per one-sided row.
int ConsistentFriction::lemke_variables_at_most() const {
    int count = static_cast<int>(friction_.size());  // + 2 each below: their bounds are finite
    for (int i = 0; i < lcp_.n(); ++i)
        if (!lcp_.always_free[i]) count += std::isfinite(lcp_.lo[i]) && std::isfinite(lcp_.hi[i]) ? 2 : 1;
    return count;
}

}  // namespace ode_bpp::pivoting
