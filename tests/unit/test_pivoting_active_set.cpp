// The active-set stage of a fixed-bound solve (pivoting/active_set.h): directly, its answers
// satisfy the boxed LCP's conditions from any start and it gives back what it was handed when it
// stops early; through solve(), the captured islands of the slow tail (tests/data/captured), on
// which block pivoting and the regularization rescue ran out of their 100-step budget, converge
// and certify without the rescue and without ODE's Dantzig.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"
#include "pivoting/active_set.h"
#include "pivoting/fixed_bound_solve.h"
#include "pivoting/free_solver.h"
#include "pivoting/friction_policy.h"
#include "pivoting/strategies.h"
#include "problems/generators.h"
#include "problems/vectors.h"
#include "test_io_support.h"
#include "test_pivoting_support.h"

namespace ode_bpp {
namespace {

// The three islands single pivots with Murty's rule finished, and one they did not (the leading
// 250 rows of a 481-row bin island; its README line).
const char* const kOverBudget[] = {"bin-frozen-over-budget-93.mlcp", "bin-frozen-over-budget-114.mlcp",
                                   "forwarder-frozen-over-budget-226.mlcp", "bin-frozen-over-budget-250.mlcp"};

Result solve_captured(const std::string& name, bool active_set, int rescue_after = Tuning{}.rescue_after,
                      int release_at_most = Tuning{}.active_set_release_at_most) {
    const ReadResult read = read_mlcp((io_test::data_dir() / "captured" / name).string());
    EXPECT_TRUE(read.ok) << read.error;
    Options o;  // Bpp, Frozen friction, a budget of 100
    o.dantzig_fallback = false;
    o.tuning.active_set = active_set;
    o.tuning.rescue_after = rescue_after;
    o.tuning.active_set_release_at_most = release_at_most;
    o.tuning.rescue_after_moved_bounds_cold = std::min(o.tuning.rescue_after_moved_bounds_cold, rescue_after);
    std::vector<double> x(static_cast<std::size_t>(read.file.n));
    return solve(read.file.view(), o, x.data());
}

TEST(PivotingActiveSet, FinishesTheCapturedIslandsThatRanOutOfBudget) {
    for (const char* name : kOverBudget) {
        const Result r = solve_captured(name, true);
        EXPECT_EQ(r.status, Status::Converged) << name << ": " << r.message;
        EXPECT_EQ(r.fallback, Fallback::None) << name;
        EXPECT_EQ(r.pivoting.rescues, 0) << name;
        EXPECT_GT(r.pivoting.murty_pivots, 0) << name;
        EXPECT_LE(r.residuals.scaled_fixed_bound, certification_level(Options{}.tolerance)) << name;
    }
}

// The active set reads the free rows' w only to check its updated factor, and checks it where
// its answer would be accepted: on this winch island (CFM 1e-10, from the warm start it was
// solved from inside ODE) the updates leave the factor short of Eq. 6's accuracy there, it is
// rebuilt, and the answer is the fresh factor's.
TEST(PivotingActiveSet, ChecksItsUpdatedFactorWhereItsAnswerWouldBeAccepted) {
    const ReadResult read = read_mlcp((io_test::data_dir() / "captured" / "winch-worn-active-set-factor-336.mlcp").string());
    ASSERT_TRUE(read.ok) << read.error;
    std::string error;
    const std::optional<Start> start = start_from_metadata(read.file.meta, read.file.n, &error);
    ASSERT_TRUE(start.has_value()) << error;
    Options o;
    o.dantzig_fallback = false;
    std::vector<double> x(static_cast<std::size_t>(read.file.n));
    const Result r = solve(read.file.view(), o, x.data(), *start);
    ASSERT_EQ(r.status, Status::Converged) << r.message;
    EXPECT_GT(r.pivoting.update_steps, 0) << "the active set did not run";
    EXPECT_GE(r.pivoting.accuracy_refactors, 1) << "the worn factor's answer was accepted unchecked";
    EXPECT_LE(r.residuals.scaled_fixed_bound, certification_level(o.tolerance));
}

TEST(PivotingActiveSet, WithoutItTheSameIslandsRunOutOfBudget) {
    for (const char* name : kOverBudget) EXPECT_EQ(solve_captured(name, false).status, Status::MaxIterations) << name;
}

// Islands of thousands of rows have the stage too (its factor is kept on the envelope): a chain
// of over 1,600 rows with contacts, one plain step from a start with every bounded row at its
// upper bound, then the active set, which converges to the answer the plain loop reaches alone.
TEST(PivotingActiveSet, TakesIslandsOfThousandsOfRows) {
    const auto owned = problems::chain_mlcp(600, 200);
    const Problem p = owned.view();
    ASSERT_GT(p.n, 1600) << "above the stage's former 1,500-row limit";
    Options o;
    o.dantzig_fallback = false;
    o.max_pivots = 1000;
    std::vector<double> reference(static_cast<std::size_t>(p.n)), x(static_cast<std::size_t>(p.n));
    const Result plain = solve(p, o, reference.data());
    ASSERT_EQ(plain.status, Status::Converged) << plain.message;
    o.tuning.rescue_after = o.tuning.rescue_after_moved_bounds = 1;
    Start wrong;  // every bounded row at its upper bound: one plain step does not finish from there
    wrong.states.assign(static_cast<std::size_t>(p.n), RowState::AtHi);
    std::fill(wrong.states.begin(), wrong.states.begin() + p.nub, RowState::Free);
    const Result r = solve(p, o, x.data(), wrong);
    ASSERT_EQ(r.status, Status::Converged) << r.message;
    EXPECT_GT(r.pivoting.update_steps, 0) << "the active set did not run";
    EXPECT_EQ(r.fallback, Fallback::None);
    EXPECT_LT(problems::max_abs_diff(x, reference), 1e-6 * (1 + problems::inf_norm(reference)));
}

// Frozen friction's second fixed-bound solve from a warm start whose friction states miss the
// bounds the frictionless normals give (the state of every friction row flipped): the active set
// takes over after Tuning::rescue_after_moved_bounds plain steps, where with rescue_after's the
// block steps alone finish; both reach the cold answer, the only one of this SPD problem.
TEST(PivotingActiveSet, TakesFrozenFrictionsMovedBoundsAfterFewerPlainSteps) {
    const auto owned = problems::chain_mlcp(30, 20);
    const Problem p = owned.view();
    Options o;
    o.dantzig_fallback = false;
    std::vector<double> reference(static_cast<std::size_t>(p.n)), x(static_cast<std::size_t>(p.n));
    const Result cold = solve(p, o, reference.data());
    ASSERT_EQ(cold.status, Status::Converged) << cold.message;
    Start flipped{cold.states, {}};
    int friction_rows = 0;
    for (int i = 0; i < p.n; ++i) {
        if (p.findex == nullptr || p.findex[i] < 0) continue;
        RowState& s = flipped.states[static_cast<std::size_t>(i)];
        s = s == RowState::Free ? RowState::AtHi : RowState::Free;
        ++friction_rows;
    }
    ASSERT_GT(friction_rows, 0);
    const auto solve_flipped = [&](int moved_bounds_steps) {
        o.tuning.rescue_after_moved_bounds = moved_bounds_steps;
        const Result r = solve(p, o, x.data(), flipped);
        EXPECT_EQ(r.status, Status::Converged) << r.message;
        EXPECT_LT(problems::max_abs_diff(x, reference), 1e-6 * (1 + problems::inf_norm(reference)));
        return r;
    };
    EXPECT_EQ(solve_flipped(o.tuning.rescue_after).pivoting.update_steps, 0) << "block steps alone finish";
    EXPECT_GT(solve_flipped(1).pivoting.update_steps, 0) << "the active set did not take over";
}

// Without a warm start Frozen friction's second solve has rescue_after_moved_bounds_cold plain
// steps, and only those: the warm start's setting leaves a cold solve alone, and with one plain
// step the active set takes over and reaches the answer block steps reach alone.
TEST(PivotingActiveSet, TakesAColdSolvesMovedBoundsAfterItsOwnPlainSteps) {
    const auto owned = problems::chain_mlcp(30, 20);
    const Problem p = owned.view();
    Options o;
    o.dantzig_fallback = false;
    // block steps alone finish this chain's solves within 8 plain steps each
    o.tuning.rescue_after = o.tuning.rescue_after_moved_bounds_cold = 8;
    o.tuning.rescue_after_moved_bounds = 1;  // a warm start's: not this solve's
    std::vector<double> reference(static_cast<std::size_t>(p.n)), x(static_cast<std::size_t>(p.n));
    const Result block = solve(p, o, reference.data());
    ASSERT_EQ(block.status, Status::Converged) << block.message;
    EXPECT_EQ(block.pivoting.update_steps, 0) << "block steps alone finish";
    o.tuning.rescue_after_moved_bounds_cold = 1;
    const Result r = solve(p, o, x.data());
    ASSERT_EQ(r.status, Status::Converged) << r.message;
    EXPECT_GT(r.pivoting.update_steps, 0) << "the active set did not take over";
    EXPECT_LT(problems::max_abs_diff(x, reference), 1e-6 * (1 + problems::inf_norm(reference)));
}

// With one plain step before it, the active set answers most of the problem on random boxed
// MLCPs: the answer is Dantzig's (both solve the same frozen-friction problem exactly).
TEST(PivotingActiveSet, AgreesWithDantzigWhenItDoesMostOfTheWork) {
    int used = 0;
    for (double cond : {1e2, 1e6})
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            const auto p = problems::random_boxed_mlcp(40, 4, 8, cond, seed);
            Options o;
            o.dantzig_fallback = false;
            o.method = Method::Dantzig;
            std::vector<double> reference(static_cast<std::size_t>(p.n)), x(static_cast<std::size_t>(p.n));
            ASSERT_EQ(solve(p, o, reference.data()).status, Status::Converged);
            for (Method m : {Method::Bpp, Method::BppSky, Method::BppChol}) {
                o.method = m;
                o.tuning.rescue_after = 1;
                o.tuning.dense_island_rows = 0;  // the skyline path, not the small-island one
                const Result r = solve(p, o, x.data());
                ASSERT_EQ(r.status, Status::Converged) << to_string(m) << " seed " << seed << ": " << r.message;
                used += r.pivoting.update_steps > 0;
                EXPECT_EQ(r.pivoting.downdate_steps + r.pivoting.refactor_steps + r.pivoting.update_steps, r.pivoting.pivots);
                const double tol = 1e3 * cond * std::numeric_limits<double>::epsilon() * (1 + problems::inf_norm(reference));
                EXPECT_LT(problems::max_abs_diff(x, reference), tol) << to_string(m) << " cond " << cond << " seed " << seed;
            }
        }
    EXPECT_GT(used, 0);  // the path under test was taken
}

// The captured tail islands: projecting the plain attempt's iterate onto the bounds pushes many
// rows that belong free onto a bound; they leave T together (active_set.h), not one per step
// (main before that took 41 and 36 active-set steps on these two). Released all at once they
// take at most 20 and 24; at most 8 at once (the default, which halves a pile's steps at rest),
// 25 and 21.
TEST(PivotingActiveSet, FreesTheRowsTheProjectionTightenedTogether) {
    const struct {
        const char* name;
        int max_steps_all, max_steps_default;
    } islands[] = {{"forwarder-frozen-over-budget-226.mlcp", 20, 25}, {"bin-frozen-over-budget-93.mlcp", 24, 24}};
    for (const auto& island : islands) {
        const Result all = solve_captured(island.name, true, Tuning{}.rescue_after, 0);
        EXPECT_EQ(all.status, Status::Converged) << island.name << ": " << all.message;
        EXPECT_GT(all.pivoting.murty_pivots, 0) << island.name;
        EXPECT_LE(all.pivoting.murty_pivots, island.max_steps_all) << island.name;
        const Result capped = solve_captured(island.name, true);
        EXPECT_EQ(capped.status, Status::Converged) << island.name << ": " << capped.message;
        EXPECT_LE(capped.pivoting.murty_pivots, island.max_steps_default) << island.name;
    }
}

// The active set classifies its answer on w = Ax - b and polishes it itself: no plain step
// re-solves it. With one plain step per fixed-bound solve, Frozen friction's two solves (the
// frictionless one, then the frozen one) take two plain steps in all, the active set the rest.
TEST(PivotingActiveSet, ItsAnswerIsNotSolvedAgainByAPlainStep) {
    for (const char* name : kOverBudget) {
        const Result r = solve_captured(name, true, 1);
        ASSERT_EQ(r.status, Status::Converged) << name << ": " << r.message;
        EXPECT_GT(r.pivoting.update_steps, 0) << name;
        EXPECT_EQ(r.pivoting.downdate_steps + r.pivoting.refactor_steps, 2) << name;
        EXPECT_LE(r.residuals.scaled_fixed_bound, certification_level(Options{}.tolerance)) << name;
    }
}

// A plain step that leaves more than Tuning::hand_over_above rows infeasible hands the solve to
// the active set at once, where block steps alone would go on; both reach the answer, the only
// one of this SPD problem.
TEST(PivotingActiveSet, HandsOverAfterAPlainStepThatLeavesSeveralRowsInfeasible) {
    const auto owned = problems::random_boxed_mlcp(60, 10, 0, 1e3, 7);
    const Problem p = owned.view();
    Options o;
    o.dantzig_fallback = false;
    o.tuning.hand_over_above = 0;
    std::vector<double> reference(static_cast<std::size_t>(p.n)), x(static_cast<std::size_t>(p.n));
    ASSERT_EQ(solve(p, o, reference.data()).status, Status::Converged);
    Start wrong;  // every bounded row at its upper bound: the first step leaves many infeasible
    wrong.states.assign(static_cast<std::size_t>(p.n), RowState::AtHi);
    std::fill(wrong.states.begin(), wrong.states.begin() + p.nub, RowState::Free);
    for (const int hand_over_above : {0, 1}) {
        o.tuning.hand_over_above = hand_over_above;
        const Result r = solve(p, o, x.data(), wrong);
        ASSERT_EQ(r.status, Status::Converged) << r.message;
        EXPECT_LT(problems::max_abs_diff(x, reference), 1e-8 * (1 + problems::inf_norm(reference)));
        const int plain_steps = r.pivoting.pivots - r.pivoting.update_steps;
        if (hand_over_above == 0) {
            EXPECT_GT(plain_steps, 1);
            EXPECT_EQ(r.pivoting.update_steps, 0) << "block steps alone finish";
        } else {
            EXPECT_EQ(plain_steps, 1) << "one plain step before the active set";
            EXPECT_GT(r.pivoting.update_steps, 0) << "the active set did not take over";
        }
    }
}

// Where the first plain step leaves exactly hand_over_above rows infeasible, block steps go on
// (one infeasible row: the next block step is its single pivot); one more such row hands over.
// Box rows, weakly coupled: x_i = b_i / 2 roughly, so the even rows end at their upper bound and
// flipping one of them to free leaves that row alone infeasible.
TEST(PivotingActiveSet, ASingleInfeasibleRowIsPivotedByTheNextBlockStep) {
    auto owned = problems::OwnedProblem::zeros("weakly coupled box", 40);
    for (int i = 0; i < owned.n; ++i) {
        owned.a(i, i) = 2;
        if (i > 0) owned.a(i, i - 1) = owned.a(i - 1, i) = 0.01;
        owned.b[static_cast<std::size_t>(i)] = i % 2 == 0 ? 3.0 : 0.5;
        owned.lo[static_cast<std::size_t>(i)] = -1;
        owned.hi[static_cast<std::size_t>(i)] = 1;
    }
    const Problem p = owned.view();
    Options o;
    o.dantzig_fallback = false;
    std::vector<double> reference(static_cast<std::size_t>(p.n)), x(static_cast<std::size_t>(p.n));
    const Result cold = solve(p, o, reference.data());
    ASSERT_EQ(cold.status, Status::Converged) << cold.message;
    ASSERT_EQ(cold.states[0], RowState::AtHi);
    const auto with_even_rows_freed = [&](int rows) {
        Start start{cold.states, {}};
        for (int k = 0; k < rows; ++k) start.states[static_cast<std::size_t>(2 * k)] = RowState::Free;
        const Result r = solve(p, o, x.data(), start);
        EXPECT_EQ(r.status, Status::Converged) << r.message;
        EXPECT_LT(problems::max_abs_diff(x, reference), 1e-12);
        return r;
    };
    o.tuning.hand_over_above = 1;
    const Result one = with_even_rows_freed(1);
    EXPECT_EQ(one.pivoting.pivots, 2);
    EXPECT_EQ(one.pivoting.update_steps, 0) << "one infeasible row went to the active set";
    const Result two = with_even_rows_freed(2);
    EXPECT_EQ(two.pivoting.pivots - two.pivoting.update_steps, 1);
    EXPECT_GT(two.pivoting.update_steps, 0) << "two infeasible rows stayed with block steps";
    o.tuning.hand_over_above = 2;
    EXPECT_EQ(with_even_rows_freed(2).pivoting.update_steps, 0) << "the threshold is not hand_over_above";
}

namespace direct {

using pivoting::LoopOutcome;
using pivoting::test::DriverLcp;

struct ActiveSetRun {
    LoopOutcome outcome;
    std::vector<RowState> states;
    std::vector<double> x;
    PivotStats counters;
};

/// The buffers a fixed-bound solve keeps for the stage from one run to the next.
struct KeptActiveSetBuffers {
    pivoting::ActiveSetWorkspace workspace;
    pivoting::FreeRowsFactor factor;
};

ActiveSetRun run_active_set_in(KeptActiveSetBuffers& kept, const pivoting::BoxedLcp& lcp, std::vector<double> start,
                               int max_steps, int release_at_most = Tuning{}.active_set_release_at_most) {
    pivoting::PivotSettings settings;
    settings.max_pivots = max_steps;
    settings.release_at_most = release_at_most;
    ActiveSetRun run{LoopOutcome::Breakdown, std::vector<RowState>(start.size(), RowState::Free), std::move(start), {}};
    run.outcome = pivoting::active_set(lcp, settings, run.states, run.x, run.counters, kept.workspace, kept.factor);
    return run;
}

ActiveSetRun run_active_set(const pivoting::BoxedLcp& lcp, std::vector<double> start, int max_steps,
                            int release_at_most = Tuning{}.active_set_release_at_most) {
    KeptActiveSetBuffers fresh;
    return run_active_set_in(fresh, lcp, std::move(start), max_steps, release_at_most);
}

/// The largest violation of the boxed LCP's conditions at x, relative to (|A||x| + |b|)_i:
/// x outside [lo, hi], w = Ax - b nonzero strictly inside, or of the wrong sign at a bound.
double kkt_violation(const pivoting::BoxedLcp& lcp, const std::vector<double>& x) {
    std::vector<double> w, scale;
    lcp.A->multiply(x, 0, w);
    lcp.A->abs_multiply(x, 0, scale);
    double worst = 0;
    for (int i = 0; i < lcp.n(); ++i) {
        const double s = scale[i] + std::abs(lcp.b[i]);
        const double wi = w[i] - lcp.b[i];
        if (x[i] < lcp.lo[i] || x[i] > lcp.hi[i]) return std::numeric_limits<double>::infinity();
        double v = std::abs(wi);
        if (x[i] == lcp.lo[i]) v = std::max(0.0, -wi);
        if (x[i] == lcp.hi[i]) v = std::max(0.0, wi);
        if (lcp.lo[i] == lcp.hi[i]) v = 0;
        worst = std::max(worst, v / s);
    }
    return worst;
}

// The box QP has one minimizer, so every start ends at the same x, and it satisfies the
// conditions to the classification tolerance.
TEST(PivotingActiveSet, EveryStartEndsAtTheOneSolution) {
    std::mt19937_64 rng(7);
    for (double cond : {1e2, 1e6})
        for (std::uint64_t seed = 1; seed <= 5; ++seed) {
            const auto p = problems::random_boxed_mlcp(40, 4, 8, cond, seed);
            const DriverLcp d(p);
            std::vector<double> first;
            for (int start = 0; start < 4; ++start) {
                std::vector<double> x0(static_cast<std::size_t>(p.n), 0.0);
                if (start > 0) {
                    std::normal_distribution<double> g(0, start == 3 ? 100 : 1);
                    for (double& v : x0) v = g(rng);
                }
                const ActiveSetRun r = run_active_set(d.lcp, x0, 20 * p.n);
                ASSERT_EQ(r.outcome, LoopOutcome::Converged) << "cond " << cond << " seed " << seed << " start " << start;
                EXPECT_LE(kkt_violation(d.lcp, r.x), 10 * Options{}.tolerance) << "seed " << seed << " start " << start;
                EXPECT_EQ(r.counters.pivots, r.counters.update_steps);
                if (first.empty()) first = r.x;
                const double tol = 1e4 * cond * std::numeric_limits<double>::epsilon() * (1 + problems::inf_norm(first));
                EXPECT_LT(problems::max_abs_diff(r.x, first), tol) << "cond " << cond << " seed " << seed << " start " << start;
            }
        }
}

// The most rows that left T in one step: the largest fall of |T| from one step to the next
// (tight_per_step holds |T| as each step begins; a release ends its step).
int largest_release(const PivotStats& counters) {
    int largest = 0;
    for (std::size_t k = 1; k < counters.tight_per_step.size(); ++k)
        largest = std::max(largest, counters.tight_per_step[k - 1] - counters.tight_per_step[k]);
    return largest;
}

// From a start that projection pushes onto wrong bounds, a release frees at most
// release_at_most rows (0: every wrong-sign row at once); each cap ends at the one minimizer.
TEST(PivotingActiveSet, ReleasesAtMostItsCapOfRowsAtOnce) {
    const auto p = problems::random_boxed_mlcp(40, 4, 8, 1e2, 3);
    const DriverLcp d(p);
    const std::vector<double> x0(static_cast<std::size_t>(p.n), 1e3);
    const ActiveSetRun all = run_active_set(d.lcp, x0, 20 * p.n, 0);
    ASSERT_EQ(all.outcome, LoopOutcome::Converged);
    ASSERT_GT(largest_release(all.counters), 3) << "the start must leave several wrong-sign rows at once";
    for (int cap : {1, 3}) {
        const ActiveSetRun r = run_active_set(d.lcp, x0, 20 * p.n, cap);
        ASSERT_EQ(r.outcome, LoopOutcome::Converged) << "cap " << cap;
        EXPECT_LE(largest_release(r.counters), cap);
        EXPECT_LE(kkt_violation(d.lcp, r.x), 10 * Options{}.tolerance) << "cap " << cap;
        EXPECT_LT(problems::max_abs_diff(r.x, all.x), 1e-9 * (1 + problems::inf_norm(all.x))) << "cap " << cap;
    }
}

// A run whose budget ends right after it freed several rows leaves nothing behind in the kept
// buffers: the next run, on its own start, does what it does with fresh buffers (fuzz_solve
// found the next run's first step retightening those rows out of a factor that never held them).
TEST(PivotingActiveSet, KeptBuffersCarryNothingFromOneRunToTheNext) {
    const auto p = problems::random_boxed_mlcp(40, 4, 8, 1e2, 3);
    const DriverLcp d(p);
    const std::vector<double> wrong(static_cast<std::size_t>(p.n), 1e3), zero(static_cast<std::size_t>(p.n), 0.0);
    const ActiveSetRun alone = run_active_set(d.lcp, zero, 20 * p.n);
    ASSERT_EQ(alone.outcome, LoopOutcome::Converged);
    const ActiveSetRun full = run_active_set(d.lcp, wrong, 20 * p.n, 0);
    ASSERT_EQ(full.outcome, LoopOutcome::Converged);
    int cut_after_release = 0;
    for (int budget = 1; budget < full.counters.pivots; ++budget) {
        KeptActiveSetBuffers kept;
        const ActiveSetRun cut = run_active_set_in(kept, d.lcp, wrong, budget, 0);
        ASSERT_EQ(cut.outcome, LoopOutcome::MaxIterations) << "budget " << budget;
        cut_after_release += budget < static_cast<int>(full.counters.tight_per_step.size()) &&
                             full.counters.tight_per_step[budget] + 1 < full.counters.tight_per_step[budget - 1];
        const ActiveSetRun next = run_active_set_in(kept, d.lcp, zero, 20 * p.n);
        EXPECT_EQ(next.outcome, alone.outcome) << "budget " << budget;
        EXPECT_EQ(next.states, alone.states) << "budget " << budget;
        EXPECT_EQ(next.x, alone.x) << "budget " << budget;
        EXPECT_EQ(next.counters.pivots, alone.counters.pivots) << "budget " << budget;
    }
    EXPECT_GT(cut_after_release, 0) << "no budget ended right after a release of several rows";
}

// A fixed-bound solve keeps the active set's factor storage for the stage's next run up to
// Tuning::active_set_kept_factor_bytes (fresh pages cost a fault each on first touch), and gives
// a larger one back to the system (0: every one).
TEST(PivotingActiveSet, KeepsItsFactorsStorageUpToItsBoundForTheNextRun) {
    const auto owned = problems::chain_mlcp(30, 20);
    const Problem p = owned.view();
    for (const std::size_t kept : {Tuning{}.active_set_kept_factor_bytes, std::size_t{0}}) {
        Options o;
        o.tuning.rescue_after_moved_bounds_cold = 1;  // the active set takes the second solve over
        o.tuning.active_set_kept_factor_bytes = kept;
        DriverLcp d(p);
        pivoting::StrategyBuffers strategy;
        const auto solver = pivoting::make_free_solver(Method::Bpp, d.A, strategy);
        ASSERT_NE(solver, nullptr);
        PivotStats counters;
        pivoting::FixedBoundBuffers buffers;
        pivoting::FixedBoundSolver fixed(d.lcp, *solver, o, d.A.max_diag(), counters, buffers, /*warm=*/false);
        std::vector<RowState> states(static_cast<std::size_t>(p.n), RowState::Free);
        std::vector<double> x;
        ASSERT_EQ(pivoting::solve_frozen(fixed, d.lcp, d.friction, o.max_pivots, pivoting::SecondStart::Requested,
                                         states, x),
                  pivoting::PolicyOutcome::Converged);
        ASSERT_GT(counters.update_steps, 0) << "the active set did not run";
        if (kept > 0) {
            EXPECT_GT(buffers.free_rows.storage_bytes(), 0u) << "given back";
            EXPECT_LE(buffers.free_rows.storage_bytes(), kept);
        } else {
            EXPECT_EQ(buffers.free_rows.storage_bytes(), 0u) << "kept above its bound";
        }
    }
}

// Cut short, it hands back the index set and x it was given.
TEST(PivotingActiveSet, GivesBackItsStartWhenItStopsEarly) {
    const auto p = problems::random_boxed_mlcp(40, 4, 8, 1e2, 3);
    const DriverLcp d(p);
    std::vector<double> x0(static_cast<std::size_t>(p.n), 1e3);
    const ActiveSetRun r = run_active_set(d.lcp, x0, 1);
    ASSERT_EQ(r.outcome, LoopOutcome::MaxIterations);
    EXPECT_EQ(r.x, x0);
    EXPECT_EQ(r.states, std::vector<RowState>(static_cast<std::size_t>(p.n), RowState::Free));
    EXPECT_EQ(r.counters.pivots, 1);
}

}  // namespace direct

}  // namespace
}  // namespace ode_bpp
