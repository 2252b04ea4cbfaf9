// solve_bpp: the problem in the factor strategy's order, the friction policy over fixed-bound
// solves (friction_policy.h, fixed_bound_solve.h), and the Result in the caller's order.
#include "pivoting/bpp_driver.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "ordering/order_rows.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/kept_buffers_impl.h"
#include "pivoting/fixed_bound_solve.h"
#include "pivoting/free_solver.h"
#include "pivoting/friction_policy.h"
#include "pivoting/friction_set.h"
#include "ordering/ordering_choice.h"
#include "pivoting/tuning.h"
#include "pivoting/strategies.h"
#include "linalg/skyline.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::pivoting {

namespace {

bool is_identity(const std::vector<int>& perm) {
    for (std::size_t i = 0; i < perm.size(); ++i)
        if (perm[i] != static_cast<int>(i)) return false;
    return true;
}

/// One BPP solve's problem in the permuted space (perm[new] = old), kept in the caller's
/// BppWorkspace so that its vectors' capacity outlives the solve.
struct PermutedProblem {
    std::vector<int> perm;
    linalg::SymmetricRows permuted_A;  ///< A in the solver's order, unless that is the caller's
    linalg::SymmetricRows original_A;  ///< A in the problem's order, where the caller's is another
    const linalg::SymmetricRows* A = nullptr;
    BoxedLcp lcp;
    FrictionSet friction;
    std::unique_ptr<FreeSolver> solver;
};

/// ordering::choose_ordering for this solve, hinted by the warm start where
/// Tuning::order_tight_last asks. A: in the problem's order.
std::vector<int> chosen_ordering(const Problem& p, const linalg::SymmetricRows& A, const Options& o, const Start& start,
                                 Method strategy) {
    static const std::vector<RowState> kNoHint;
    const bool hint = o.tuning.order_tight_last;
    const auto first = hint && o.friction == FrictionMode::Frozen ? ordering::FirstSolve::FrictionRowsTight
                                                                   : ordering::FirstSolve::AsWarmStart;
    return ordering::choose_ordering(strategy, p, A, hint ? start.states : kNoHint, first,
                                     o.tuning.price_tight_last_orderings);
}

/// True when A is stored in the permutation perm already: its order() (a permutation), or the
/// identity for A stored as built.
bool stored_in(const linalg::SymmetricRows& A, const std::vector<int>& perm, int n) {
    if (!A.order().empty()) return A.order() == perm;
    return static_cast<int>(perm.size()) == n && is_identity(perm);
}

/// The symmetric permutation to factor in: the given one where the strategy orders and it is
/// valid (the hook passes the previous step's), else ordering/ordering_choice.h's. A stored in
/// that permutation already (ode/island_view.h assembles it so) is taken as it is.
void order(const Problem& p, const linalg::SymmetricRows& stored_A, const Options& o, const Start& start,
           Method strategy, PermutedProblem& q) {
    const bool orders = strategy_orders(strategy);
    if (orders && stored_in(stored_A, start.ordering, p.n)) {
        q.perm = start.ordering;
        q.A = &stored_A;
        return;
    }
    const bool given = orders && ordering::is_permutation(start.ordering, p.n);
    const linalg::SymmetricRows& A = stored_A.in_built_order(q.original_A);
    q.perm = given ? start.ordering : chosen_ordering(p, A, o, start, strategy);
    q.A = &A;
    if (!is_identity(q.perm)) {
        A.permute_into(q.perm, q.permuted_A);
        q.A = &q.permuted_A;
    }
}

std::vector<RowState> permuted_start(const Problem& p, const Start& start, const std::vector<int>& perm) {
    std::vector<RowState> states(static_cast<std::size_t>(p.n), RowState::Free);
    if (!start.states.empty())
        for (int i = 0; i < p.n; ++i) states[i] = start.states[perm[i]];
    return states;
}

Status status_of(PolicyOutcome outcome, double shift) {
    switch (outcome) {
        case PolicyOutcome::BudgetSpent: return Status::MaxIterations;
        case PolicyOutcome::FrictionInconsistent: return Status::FrictionNotConsistent;
        case PolicyOutcome::NotSpd: return Status::NotSpd;
        case PolicyOutcome::Converged: break;
    }
    return shift > 0 ? Status::FallbackUsed : Status::Converged;
}

/// What the policy's outcome means, for Result::message; empty on a plain convergence.
std::string message_of(PolicyOutcome outcome, double shift, const Options& o, int rounds, const std::string& note) {
    // nothing to say, so no stream: building one costs about as much as a 6-row island's pivoting
    if (outcome == PolicyOutcome::Converged && !(shift > 0)) return {};
    std::ostringstream m;
    if (outcome == PolicyOutcome::NotSpd) {
        m << "Cholesky breaks down even on A + " << tuning::kLastShift
          << " * max diag * I: A is not positive definite";
        return m.str();
    }
    if (outcome == PolicyOutcome::BudgetSpent)
        m << "pivot budget of " << std::max(1, o.max_pivots) << " steps ran out; x is the least infeasible iterate. ";
    if (outcome == PolicyOutcome::FrictionInconsistent) m << "friction bounds still moving after " << rounds << " rounds. ";
    if (outcome != PolicyOutcome::Converged && !note.empty()) m << note << ". ";
    if (shift > 0) m << "Cholesky broke down; solved with A + " << shift << " I. ";
    std::string s = m.str();
    if (!s.empty()) s.pop_back();
    return s;
}

/// The answer in the caller's order, with the counters, status and message.
Result finish(PolicyOutcome outcome, const FixedBoundSolver& fixed, const PivotCounters& counters,
              const PermutedProblem& q, const std::vector<RowState>& states, const std::vector<double>& x,
              std::vector<double>& x_out) {
    const int n = static_cast<int>(x.size());
    Result r;
    r.pivoting = counters;
    r.regularization = fixed.shift();
    x_out.assign(static_cast<std::size_t>(n), 0.0);
    if (outcome == PolicyOutcome::NotSpd) return r;
    r.ordering = q.perm;
    r.states.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        x_out[q.perm[i]] = x[i];
        r.states[q.perm[i]] = states[i];
        r.tight += states[i] != RowState::Free;
    }
    if (fixed.shift() > 0) r.fallback = Fallback::Regularized;
    return r;
}

/// The loop's w and scales at the answer xp (permuted space), in the caller's order; empty when
/// the loop did not end at xp (pivot_loop.h, converged_iterate).
void vectors_at_answer(LoopWorkspace& loop, const std::vector<int>& perm, const std::vector<double>& xp,
                       ResidualBuffers& out) {
    const Iterate* it = converged_iterate(loop, xp);
    if (it == nullptr) return;
    out.w.resize(xp.size());
    out.scale.resize(xp.size());
    for (std::size_t i = 0; i < xp.size(); ++i) {
        out.w[perm[i]] = it->w[i];
        out.scale[perm[i]] = it->scale[i];
    }
}

std::vector<char> tight_set(const std::vector<RowState>& states) {
    std::vector<char> tight(states.size());
    for (std::size_t i = 0; i < states.size(); ++i) tight[i] = states[i] != RowState::Free;
    return tight;
}

}  // namespace

struct BppBuffers {
    PermutedProblem problem;
    FixedBoundBuffers fixed_bound;
    StrategyBuffers strategies;
};

template class KeptBuffers<BppBuffers>;

Result solve_bpp(const Problem& problem, const linalg::SymmetricRows& A, const Options& options, const Start& start,
                 std::vector<double>& x, BppWorkspace& workspace, ResidualBuffers& at_answer) {
    at_answer.w.clear();
    at_answer.scale.clear();
    const Method strategy = strategy_of(problem, options);
    PermutedProblem& q = workspace.contents().problem;
    order(problem, A, options, start, strategy, q);
    q.solver.reset();  // the previous solve's strategy works in the buffers the next one takes
    q.solver = make_free_solver(strategy, *q.A, workspace.contents().strategies);
    if (!q.solver) {
        x.assign(static_cast<std::size_t>(problem.n), 0.0);
        Result r;
        r.status = Status::InvalidInput;
        r.message = std::string("method ") + to_string(options.method) + " is not a BPP method or is not available";
        return r;
    }
    build_boxed_lcp(problem, *q.A, q.perm, q.lcp, q.friction);
    std::vector<RowState> states = permuted_start(problem, start, q.perm);
    std::vector<double> xp;
    PivotCounters counters;
    const bool warm = !start.states.empty();
    FixedBoundSolver fixed(q.lcp, *q.solver, options, q.A->max_diag(), counters, workspace.contents().fixed_bound, warm);
    PolicyOutcome outcome;
    std::string note;
    if (options.friction == FrictionMode::Consistent) {
        ConsistentFriction policy(fixed, q.lcp, q.friction, options, warm, counters);
        outcome = policy.solve(states, xp);
        note = policy.note();
    } else {
        outcome = solve_frozen(fixed, q.lcp, q.friction, std::max(1, options.max_pivots), second_start(options, warm),
                               states, xp);
    }
    xp.resize(static_cast<std::size_t>(problem.n), 0.0);
    Result r = finish(outcome, fixed, counters, q, states, xp, x);
    if (outcome != PolicyOutcome::NotSpd) vectors_at_answer(workspace.contents().fixed_bound.loop, q.perm, xp, at_answer);
    r.status = status_of(outcome, fixed.shift());
    r.message = message_of(outcome, fixed.shift(), options, r.pivoting.friction_rounds, note);
    if (options.compute_factor_error && outcome != PolicyOutcome::NotSpd) r.factor_error = q.solver->factor_error(tight_set(states));
    return r;
}

Method strategy_of(const Problem& p, const Options& o) {
    return o.method == Method::Bpp && p.n <= o.tuning.dense_island_rows ? Method::BppChol : o.method;
}

bool strategy_orders(Method strategy) { return strategy == Method::Bpp || strategy == Method::BppSky; }

bool is_bpp(Method m) { return m == Method::BppChol || m == Method::BppDown || m == Method::BppSky || m == Method::Bpp; }

std::int64_t dense_triangle_entries(int n) {
    const auto rows = static_cast<std::int64_t>(n);
    return rows * (rows + 1) / 2;
}

bool factor_may_be_too_large(int n, const Options& o) {
    return is_bpp(o.method) && o.max_factor_entries > 0 && dense_triangle_entries(n) > o.max_factor_entries;
}

std::int64_t planned_factor_entries(const Problem& problem, const linalg::SymmetricRows& A, const Options& options,
                                    const Start& start, linalg::SymmetricRows& scratch, std::vector<int>& chosen) {
    chosen.clear();
    const Method strategy = strategy_of(problem, options);
    if (!strategy_orders(strategy)) return dense_triangle_entries(problem.n);
    const auto envelope = [](const std::vector<int>& first) {
        return static_cast<std::int64_t>(linalg::SkylineShape::size_of_row_profile(first));
    };
    const auto envelope_under = [&envelope](const linalg::SymmetricRows& built, const std::vector<int>& perm) {
        return envelope(is_identity(perm) ? built.row_profile() : built.row_profile_under(perm));
    };
    // the same three cases as order()
    if (stored_in(A, start.ordering, problem.n)) return envelope(A.row_profile());
    const linalg::SymmetricRows& built = A.in_built_order(scratch);
    if (ordering::is_permutation(start.ordering, problem.n)) return envelope_under(built, start.ordering);
    chosen = chosen_ordering(problem, built, options, start, strategy);
    return envelope_under(built, chosen);
}

}  // namespace ode_bpp::pivoting
