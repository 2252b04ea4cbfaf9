// The Júdice-Pires loop (pivoting/pivot_loop.h) through solve(), against exhaustive enumeration
// of all 3^n index sets (problems/oracle.h), for every BPP strategy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "pivoting/pivot_loop.h"
#include "pivoting/strategies.h"
#include "problems/generators.h"
#include "problems/named.h"
#include "problems/vectors.h"
#include "problems/oracle.h"
#include "test_pivoting_support.h"

namespace ode_bpp {
namespace {

using problems::inf_norm;
using problems::max_abs_diff;

const Method kBppMethods[] = {Method::BppChol, Method::BppDown, Method::BppSky, Method::Bpp};

Result run(const problems::OwnedProblem& p, Method m, std::vector<double>& x, Options o = {}, const Start& start = {}) {
    o.method = m;
    x.assign(p.n, 0.0);
    return solve(p, o, x.data(), start);
}

class PivotingEnumeration : public ::testing::TestWithParam<Method> {};

TEST_P(PivotingEnumeration, MatchesAllIndexSetsWithoutFriction) {
    int checked = 0;
    for (int n = 2; n <= 9; ++n)
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            auto p = problems::random_boxed_mlcp(n, static_cast<int>(seed % 3 == 0), 0, 1e3, 100 * n + seed);
            p.findex.clear();
            const auto expected = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
            ASSERT_TRUE(expected.has_value()) << "n " << n << " seed " << seed;
            std::vector<double> x;
            const Result r = run(p, GetParam(), x);
            ASSERT_EQ(r.status, Status::Converged) << r.message << " n " << n << " seed " << seed;
            // cond 1e3: x is determined to ~cond * tol relative
            EXPECT_LT(max_abs_diff(x, *expected), 1e-6 * (1 + inf_norm(*expected))) << "n " << n << " seed " << seed;
            ++checked;
        }
    EXPECT_EQ(checked, 48);
}

TEST_P(PivotingEnumeration, FrozenFrictionMatchesTwoStageEnumeration) {
    for (int contacts = 1; contacts <= 3; ++contacts)
        for (std::uint64_t seed = 1; seed <= 5; ++seed) {
            const int n = 3 * contacts + 1 + static_cast<int>(seed % 2);
            const auto p = problems::random_boxed_mlcp(n, 1, contacts, 1e2, 7 * seed + contacts);
            const auto expected = problems::enumerate_frozen_friction(p);
            ASSERT_TRUE(expected.has_value());
            std::vector<double> x;
            const Result r = run(p, GetParam(), x);
            ASSERT_EQ(r.status, Status::Converged) << r.message;
            EXPECT_LT(max_abs_diff(x, *expected), 1e-6 * (1 + inf_norm(*expected)))
                << "contacts " << contacts << " seed " << seed;
        }
}

TEST_P(PivotingEnumeration, WarmStartFromTheAnswerNeedsOnePivot) {
    const auto p = problems::random_boxed_mlcp(9, 2, 0, 1e3, 77);
    std::vector<double> x;
    const Result first = run(p, GetParam(), x);
    ASSERT_EQ(first.status, Status::Converged);
    ASSERT_GT(first.pivoting.pivots, 1);
    Start start;
    start.states = first.states;
    std::vector<double> x2;
    const Result second = run(p, GetParam(), x2, {}, start);
    EXPECT_EQ(second.status, Status::Converged);
    EXPECT_EQ(second.pivoting.pivots, 1);
    EXPECT_LT(max_abs_diff(x, x2), 1e-12 * (1 + inf_norm(x)));
}

INSTANTIATE_TEST_SUITE_P(AllStrategies, PivotingEnumeration, ::testing::ValuesIn(kBppMethods),
                         [](const auto& info) { return std::string(to_string(info.param)) == "bpp-chol" ? "chol"
                                                       : std::string(to_string(info.param)) == "bpp-down" ? "down"
                                                       : std::string(to_string(info.param)) == "bpp-sky"  ? "sky"
                                                                                                          : "bpp"; });

TEST(PivotingMurty, PureBlockPivotingCyclesOnTheNamedProblem) {
    const auto p = problems::block_pivoting_cycle();
    Options o;
    o.tuning.murty_after = 1 << 30;
    o.tuning.rescue_after = 0;  // no regularization rescue either: block steps alone
    o.max_pivots = 200;
    std::vector<double> x;
    const Result r = run(p, Method::BppChol, x, o);
    EXPECT_EQ(r.status, Status::MaxIterations);
    EXPECT_EQ(r.pivoting.murty_pivots, 0);
    // 200 block steps among at most 27 index sets: a deterministic rule that never stops revisits
    // a set, i.e. cycles
    ASSERT_EQ(r.pivoting.tight_per_step.size(), 200u);
}

TEST(PivotingMurty, SafeguardEngagesAndConvergesToTheEnumeratedAnswer) {
    const auto p = problems::block_pivoting_cycle();
    const auto expected = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
    ASSERT_TRUE(expected.has_value());
    for (Method m : kBppMethods)
        for (int murty_after : {0, 1, 3, 10}) {
            Options o;
            o.tuning.murty_after = murty_after;
            o.tuning.rescue_after = 0;  // the safeguard alone, without the regularization rescue
            std::vector<double> x;
            const Result r = run(p, m, x, o);
            ASSERT_EQ(r.status, Status::Converged) << to_string(m) << " murty_after " << murty_after;
            EXPECT_GT(r.pivoting.murty_pivots, 0) << to_string(m) << " murty_after " << murty_after;
            EXPECT_LT(max_abs_diff(x, *expected), 1e-9);
        }
}

TEST(PivotingBudget, ExhaustedBudgetReturnsTheLeastInfeasibleIterateWithinBounds) {
    const auto p = problems::random_boxed_mlcp(40, 0, 0, 1e6, 5);
    std::vector<double> x;
    Options o;
    o.max_pivots = 1;
    const Result r = run(p, Method::Bpp, x, o);
    ASSERT_EQ(r.status, Status::MaxIterations);
    EXPECT_FALSE(r.message.empty());
    EXPECT_TRUE(is_usable(r.status));
    EXPECT_EQ(r.pivoting.pivots, 1);
    for (int i = 0; i < p.n; ++i) {
        ASSERT_TRUE(std::isfinite(x[i]));
        EXPECT_GE(x[i], p.lo[i]);
        EXPECT_LE(x[i], p.hi[i]);
        if (r.states[i] == RowState::AtLo) { EXPECT_EQ(x[i], p.lo[i]); }
        if (r.states[i] == RowState::AtHi) { EXPECT_EQ(x[i], p.hi[i]); }
    }
}

TEST(PivotingLoop, PinnedRowsStayAtTheirValueAndRowsWithInfiniteBoundsStayFree) {
    auto p = problems::random_boxed_mlcp(8, 0, 0, 1e2, 9);
    p.findex.clear();
    p.lo[3] = p.hi[3] = 0;  // pinned (lo = hi = 0, as a friction row with no normal)
    p.lo[5] = -std::numeric_limits<double>::infinity();
    p.hi[5] = std::numeric_limits<double>::infinity();
    const auto expected = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
    ASSERT_TRUE(expected.has_value());
    for (Method m : kBppMethods) {
        Start start;
        start.states.assign(p.n, RowState::AtHi);  // impossible for row 5: must start free
        std::vector<double> x;
        const Result r = run(p, m, x, {}, start);
        ASSERT_EQ(r.status, Status::Converged) << to_string(m);
        EXPECT_EQ(x[3], 0.0);
        EXPECT_EQ(r.states[5], RowState::Free);
        EXPECT_LT(max_abs_diff(x, *expected), 1e-8);
    }
}

TEST(PivotingLoop, ARunThatMayStallStopsAtTheFirstRevisitedIndexSet) {
    const auto owned = problems::block_pivoting_cycle();
    const pivoting::test::DriverLcp driver(owned.view());
    const pivoting::BoxedLcp& lcp = driver.lcp;
    pivoting::DenseRefactorBuffers buffers;  // outlives the strategy
    auto solver = pivoting::make_dense_refactor_solver(driver.A, buffers);
    ASSERT_TRUE(solver->prepare(0));
    pivoting::PivotSettings settings;
    settings.max_pivots = 200;
    settings.murty_after = 1 << 20;  // block steps only: this problem cycles among them
    settings.stall_after = 1 << 20;  // far beyond the budget: only the cycle can stop the run
    std::vector<RowState> states;
    std::vector<double> x;
    pivoting::PivotCounters counters;
    const auto outcome = pivoting::pivot_fixed_bounds(lcp, *solver, settings, states, x, counters);
    EXPECT_EQ(outcome, pivoting::LoopOutcome::Stalled);
    // 3 rows give at most 27 index sets: a cycle shows within 27 steps
    EXPECT_LE(counters.pivots, 27);
    EXPECT_EQ(counters.murty_pivots, 0);
    for (int i = 0; i < owned.n; ++i) {
        EXPECT_GE(x[i], lcp.lo[i]);
        EXPECT_LE(x[i], lcp.hi[i]);
    }
    // a run that may not stall (the plain attempt) keeps going: Murty's rule breaks the cycle
    settings.stall_after = 0;
    settings.murty_after = 3;
    states.clear();
    EXPECT_EQ(pivoting::pivot_fixed_bounds(lcp, *solver, settings, states, x, counters), pivoting::LoopOutcome::Converged);
}

TEST(PivotingLoop, DirectCallLeavesTheFinalIndexSetAndCountsSteps) {
    const auto owned = problems::random_boxed_mlcp(10, 0, 0, 1e2, 21);
    const Problem p = owned.view();
    const pivoting::test::DriverLcp driver(p);
    const pivoting::BoxedLcp& lcp = driver.lcp;
    pivoting::DenseRefactorBuffers buffers;  // outlives the strategy
    auto solver = pivoting::make_dense_refactor_solver(driver.A, buffers);
    ASSERT_TRUE(solver->prepare(0));
    std::vector<RowState> states;
    std::vector<double> x;
    pivoting::PivotCounters counters;
    const auto outcome = pivoting::pivot_fixed_bounds(lcp, *solver, pivoting::PivotSettings{}, states, x, counters);
    ASSERT_EQ(outcome, pivoting::LoopOutcome::Converged);
    EXPECT_EQ(counters.pivots, static_cast<int>(counters.tight_per_step.size()));
    EXPECT_EQ(counters.refactor_steps, counters.pivots);
    for (int i = 0; i < p.n; ++i) {
        if (states[i] == RowState::AtLo) { EXPECT_EQ(x[i], lcp.lo[i]); }
        if (states[i] == RowState::AtHi) { EXPECT_EQ(x[i], lcp.hi[i]); }
    }
    const auto expected = problems::enumerate_boxed_lcp(owned, owned.lo, owned.hi);
    ASSERT_TRUE(expected.has_value());
    EXPECT_LT(max_abs_diff(x, *expected), 1e-8);
}


// A run whose answer only feeds a later solve (Frozen friction's frictionless solve) refreshes w
// on the rows Eq. 4 reads only, from its first step on: the same steps, index set and x to the
// bit, and no answer kept for the residuals (they would read rows it never computed).
TEST(PivotingLoop, ARunWithoutACompleteAnswerTakesTheSameStepsAndKeepsNothing) {
    const auto owned = problems::random_boxed_mlcp(24, 8, 3, 1e2, 17);  // 8 rows never tight
    const Problem p = owned.view();
    pivoting::test::DriverLcp driver(p);
    pivoting::BoxedLcp& lcp = driver.lcp;
    for (int i : driver.friction.rows) lcp.lo[i] = lcp.hi[i] = 0;  // the frictionless solve
    ASSERT_TRUE(std::count(lcp.always_free.begin(), lcp.always_free.end(), 1) > 0);
    std::vector<RowState> states[2];
    std::vector<double> x[2];
    pivoting::PivotCounters counters[2];
    pivoting::LoopWorkspace workspace[2];
    for (int k : {0, 1}) {
        pivoting::DenseRefactorBuffers buffers;
        auto solver = pivoting::make_dense_refactor_solver(driver.A, buffers);
        ASSERT_TRUE(solver->prepare(0));
        pivoting::PivotSettings settings;
        settings.answer = k == 0 ? pivoting::AnswerUse::Final : pivoting::AnswerUse::Intermediate;
        ASSERT_EQ(pivoting::pivot_fixed_bounds(lcp, *solver, settings, states[k], x[k], counters[k], workspace[k]),
                  pivoting::LoopOutcome::Converged);
    }
    EXPECT_GT(counters[0].pivots, 1);
    EXPECT_EQ(counters[1].tight_per_step, counters[0].tight_per_step);
    EXPECT_EQ(states[1], states[0]);
    for (int i = 0; i < p.n; ++i) EXPECT_TRUE(std::memcmp(&x[1][i], &x[0][i], sizeof(double)) == 0) << "row " << i;
    EXPECT_NE(pivoting::converged_iterate(workspace[0], x[0]), nullptr);
    EXPECT_EQ(pivoting::converged_iterate(workspace[1], x[1]), nullptr);
}

// The polish (pivot_loop.cpp): a tight set whose multipliers have the wrong sign within the
// classification tolerance is not kept when freeing those rows converges as well.
TEST(PivotingPolish, TheToleranceAloneKeepsOpposedFrictionAtItsBoundsAndThePolishFreesIt) {
    const auto owned = problems::opposed_friction_pair();
    const pivoting::test::DriverLcp driver(owned.view());  // friction bounds fixed at +-mu
    const pivoting::BoxedLcp& lcp = driver.lcp;
    pivoting::DenseRefactorBuffers buffers;  // outlives the strategy
    auto solver = pivoting::make_dense_refactor_solver(driver.A, buffers);
    ASSERT_TRUE(solver->prepare(0));
    const std::vector<RowState> opposed = {RowState::Free, RowState::AtHi, RowState::Free, RowState::AtLo};
    for (bool polish : {false, true}) {
        pivoting::PivotSettings settings;
        settings.polish = polish;
        std::vector<RowState> states = opposed;
        std::vector<double> x;
        pivoting::PivotCounters counters;
        ASSERT_EQ(pivoting::pivot_fixed_bounds(lcp, *solver, settings, states, x, counters),
                  pivoting::LoopOutcome::Converged)
            << "polish " << polish;
        if (!polish) {
            // the premise: 1e-9 relative tolerance accepts the internal force +-mu
            EXPECT_EQ(states, opposed);
            EXPECT_EQ(counters.pivots, 1);
        } else {
            EXPECT_EQ(states[1], RowState::Free);
            EXPECT_EQ(states[3], RowState::Free);
            EXPECT_LT(std::abs(x[1]) + std::abs(x[3]), 1e-6 * lcp.hi[1]);
            EXPECT_EQ(counters.pivots, 2);
        }
    }
}

TEST_P(PivotingEnumeration, AWarmStartWithOpposedFrictionAtItsBoundsEndsWithTheColdAnswer) {
    const auto owned = problems::opposed_friction_pair();
    std::vector<double> cold, warm;
    const Result c = run(owned, GetParam(), cold);
    ASSERT_EQ(c.status, Status::Converged) << c.message;
    Start start;
    start.states = {RowState::Free, RowState::AtHi, RowState::Free, RowState::AtLo};
    const Result r = run(owned, GetParam(), warm, {}, start);
    ASSERT_EQ(r.status, Status::Converged) << r.message;
    const double bound = 0.5 * cold[0];  // mu x_normal
    ASSERT_GT(bound, 0.01);
    EXPECT_LT(std::abs(cold[1]) + std::abs(cold[3]), 1e-6 * bound);  // 0 up to rounding / cfm
    // without the polish the friction stays at -+mu x_normal
    EXPECT_LT(std::abs(warm[1]) + std::abs(warm[3]), 1e-6 * bound);
    EXPECT_LT(max_abs_diff(warm, cold), 1e-6 * inf_norm(cold));
    EXPECT_EQ(r.states[1], RowState::Free);
    EXPECT_EQ(r.states[3], RowState::Free);
}

}  // namespace
}  // namespace ode_bpp
