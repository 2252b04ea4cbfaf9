// solve() across methods: the BPP variants agree with each other, with ODE's Dantzig and with
// the residual certificate over a range of condition numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "problems/generators.h"
#include "problems/named.h"
#include "problems/vectors.h"
#include "problems/oracle.h"

namespace ode_bpp {
namespace {

using problems::inf_norm;
using problems::max_abs_diff;

const Method kBppMethods[] = {Method::BppChol, Method::BppDown, Method::BppSky, Method::Bpp};

Result run(const problems::OwnedProblem& p, Method m, std::vector<double>& x, Options o = {}, const Start& start = {}) {
    o.method = m;
    x.assign(p.n, std::numeric_limits<double>::quiet_NaN());
    return solve(p, o, x.data(), start);
}

bool all_finite(const std::vector<double>& x) {
    return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

TEST(SolverNames, RoundTrip) {
    const auto names = method_names();
    ASSERT_EQ(names.size(), 6u);
    for (const auto& name : names) EXPECT_EQ(to_string(*method_from_string(name)), name);
    EXPECT_FALSE(method_from_string("lemke").has_value());
    EXPECT_EQ(*friction_from_string(to_string(FrictionMode::Consistent)), FrictionMode::Consistent);
    EXPECT_EQ(*friction_from_string(to_string(FrictionMode::Frozen)), FrictionMode::Frozen);
    EXPECT_STREQ(to_string(Status::NotSpd), "not-spd");
}

TEST(SolverAgreement, BppVariantsAgreeWithEachOtherAndWithDantzig) {
    for (double cond : {1e2, 1e4, 1e6, 1e8})
        for (std::uint64_t seed = 1; seed <= 3; ++seed)
            for (bool friction : {false, true}) {
                auto p = problems::random_boxed_mlcp(36, 5, 4, cond, seed);
                if (!friction) p.findex.clear();
                std::vector<double> reference;
                const Result rd = run(p, Method::Dantzig, reference);
                ASSERT_EQ(rd.status, Status::Converged);
                // Dantzig and BPP solve the same (frozen-friction) problem exactly; both are
                // backward stable, so they differ by ~ cond * eps relative
                const double tol = 1e3 * cond * std::numeric_limits<double>::epsilon() * (1 + inf_norm(reference));
                for (Method m : kBppMethods) {
                    std::vector<double> x;
                    Options o;
                    o.max_pivots = 1000;
                    const Result r = run(p, m, x, o);
                    ASSERT_EQ(r.status, Status::Converged) << to_string(m) << " cond " << cond << " seed " << seed;
                    EXPECT_LT(max_abs_diff(x, reference), tol)
                        << to_string(m) << " cond " << cond << " seed " << seed << " friction " << friction;
                    EXPECT_EQ(r.pivoting.downdate_steps + r.pivoting.refactor_steps + r.pivoting.update_steps, r.pivoting.pivots) << to_string(m);
                    EXPECT_EQ(static_cast<int>(r.pivoting.tight_per_step.size()), r.pivoting.pivots);
                }
            }
}

TEST(SolverAgreement, ChainIslandWithStructureMatchesDantzig) {
    const auto p = problems::chain_mlcp(30, 12, 100, 1e-6);
    std::vector<double> reference;
    ASSERT_EQ(run(p, Method::Dantzig, reference).status, Status::Converged);
    for (Method m : kBppMethods) {
        std::vector<double> x;
        const Result r = run(p, m, x);
        ASSERT_EQ(r.status, Status::Converged) << to_string(m) << ": " << r.message;
        EXPECT_LT(max_abs_diff(x, reference), 1e-9 * inf_norm(reference)) << to_string(m);
        EXPECT_GT(r.tight, 0);
    }
}

/// Tuning::order_tight_last off: a warm start no longer changes the ordering (Cuthill-McKee or
/// its reverse only); on, the ordering differs here (the warm start's tight rows last price
/// lower on this chain) but the answer does not.
TEST(SolverOrdering, TightLastCanBeTurnedOff) {
    const auto p = problems::chain_mlcp(8, 8, 100, 1e-6);
    std::vector<double> cold_x, warm_x, plain_x;
    const Result cold = run(p, Method::Bpp, cold_x);
    ASSERT_EQ(cold.status, Status::Converged);
    ASSERT_GT(cold.tight, 0);
    Options o;
    Start start;
    start.states = cold.states;
    o.tuning.order_tight_last = true;
    const Result warm = run(p, Method::Bpp, warm_x, o, start);
    ASSERT_EQ(warm.status, Status::Converged);
    ASSERT_NE(warm.ordering, cold.ordering) << "the switch has nothing to turn off on this problem";
    EXPECT_LT(max_abs_diff(warm_x, cold_x), 1e-9 * inf_norm(cold_x));
    o.tuning.order_tight_last = false;
    const Result plain = run(p, Method::Bpp, plain_x, o, start);
    EXPECT_EQ(plain.ordering, cold.ordering);
}

/// Bpp refactors small islands densely (Tuning::dense_island_rows); with the threshold at 0 the
/// same islands go through the skyline strategy, and both answers pass the same certificate.
TEST(SolverSmallIslands, DenseAndSkylinePathsOfBppAgree) {
    for (int n : {6, 20, 32}) {
        const auto p = problems::random_boxed_mlcp(n, 2, 0, 1e6, 40 + n);  // fixed bounds: certificate applies
        std::vector<double> dense, skyline;
        const Result a = run(p, Method::Bpp, dense);
        Options o;
        o.tuning.dense_island_rows = 0;
        const Result b = run(p, Method::Bpp, skyline, o);
        ASSERT_EQ(a.status, Status::Converged) << n;
        ASSERT_EQ(b.status, Status::Converged) << n;
        EXPECT_EQ(a.pivoting.downdate_steps, 0) << n;  // the dense path never deletes rows
        EXPECT_LT(max_abs_diff(dense, skyline), 1e-8 * (1 + inf_norm(dense))) << n;
        EXPECT_LT(b.residuals.scaled_natural, o.tolerance) << n;
    }
}

/// A given ordering (the hook passes the previous step's) is the one factored in, whatever it is,
/// and any valid permutation gives the same answer; an invalid one is ignored.
TEST(SolverOrdering, GivenOrderingIsUsedAndInvalidOnesAreRecomputed) {
    const auto p = problems::chain_mlcp(30, 12, 100, 1e-6);
    for (Method m : {Method::Bpp, Method::BppSky}) {
        std::vector<double> computed, given;
        const Result first = run(p, m, computed);
        ASSERT_EQ(first.status, Status::Converged);
        ASSERT_EQ(static_cast<int>(first.ordering.size()), p.n);
        Start start;
        start.ordering = first.ordering;
        std::reverse(start.ordering.begin(), start.ordering.end());  // valid, but not what it would choose
        const Result again = run(p, m, given, {}, start);
        ASSERT_EQ(again.status, Status::Converged) << to_string(m);
        EXPECT_EQ(again.ordering, start.ordering) << to_string(m);
        EXPECT_LT(max_abs_diff(given, computed), 1e-9 * inf_norm(computed)) << to_string(m);
        start.ordering.assign(p.n, 0);  // not a permutation
        const Result recomputed = run(p, m, given, {}, start);
        EXPECT_EQ(recomputed.ordering, first.ordering) << to_string(m);
    }
}

/// Consistent friction: the answer satisfies the MLCP with bounds from its own normals, so the
/// natural residual certifies it. Certified to the per-row tolerance, over cond 1e2 .. 1e14.
TEST(SolverCertificate, NaturalResidualCertifiesAnswersFromCond1e2To1e14) {
    int converged = 0, total = 0;
    for (double cond = 1e2; cond <= 1e14; cond *= 100)
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            const auto p = problems::random_boxed_mlcp(24, 4, 3, cond, seed);
            Options o;
            o.friction = FrictionMode::Consistent;
            o.max_pivots = 3000;
            o.tuning.max_friction_rounds = 200;
            std::vector<double> x;
            const Result r = run(p, Method::Bpp, x, o);
            ++total;
            ASSERT_TRUE(all_finite(x));
            ASSERT_TRUE(r.status == Status::Converged || r.status == Status::FallbackUsed)
                << to_string(r.status) << " cond " << cond << " seed " << seed << ": " << r.message;
            converged += r.status == Status::Converged;
            // an exact solve of a perturbation of size eps * cond in x: scaled residual ~ tol
            EXPECT_LT(r.residuals.scaled_natural, 10 * o.tolerance) << "cond " << cond << " seed " << seed;
            EXPECT_LT(r.residuals.friction, 10 * o.tolerance * (1 + inf_norm(x))) << "cond " << cond << " seed " << seed;
            const Residuals check = compute_residuals(p, ConstStrided{x.data(), 1}, &r.states);
            EXPECT_EQ(check.scaled_natural, r.residuals.scaled_natural);
        }
    EXPECT_EQ(total, 21);
    EXPECT_GE(converged, 15);
}

TEST(SolverCertificate, FactorErrorIsReportedForDeletionVariantsOnly) {
    const auto p = problems::chain_mlcp(20, 8, 100, 1e-6);
    for (const std::string& name : method_names()) {
        Options o;
        o.compute_factor_error = true;
        std::vector<double> x;
        const Result r = run(p, *method_from_string(name), x, o);
        const bool deletes = name == "bpp-down" || name == "bpp-sky" || name == "bpp";
        if (deletes) {
            EXPECT_GE(r.factor_error, 0) << name;
            EXPECT_LT(r.factor_error, 1e-8) << name;
        } else {
            EXPECT_TRUE(std::isnan(r.factor_error)) << name;
        }
    }
}

TEST(SolverInterface, StridedPairsLikeOdeAreReadAndWrittenInPlace) {
    const auto p = problems::chain_mlcp(10, 4);
    std::vector<double> pairs(2 * p.n);
    for (int i = 0; i < p.n; ++i) pairs[2 * i] = p.b[i];
    Problem view = p.view();
    view.b = ConstStrided{pairs.data(), 2};
    std::vector<double> x;
    const Result contiguous = run(p, Method::Bpp, x);
    const Result strided = solve(view, Options{}, Strided{pairs.data() + 1, 2});
    EXPECT_EQ(strided.status, contiguous.status);
    for (int i = 0; i < p.n; ++i) {
        EXPECT_EQ(pairs[2 * i], p.b[i]);
        EXPECT_EQ(pairs[2 * i + 1], x[i]);
    }
}

TEST(SolverInterface, RecordStepsCanBeTurnedOff) {
    const auto p = problems::random_boxed_mlcp(20, 2, 2, 1e3, 3);
    Options o;
    o.record_steps = false;
    std::vector<double> x;
    const Result r = run(p, Method::Bpp, x, o);
    EXPECT_GT(r.pivoting.pivots, 0);
    EXPECT_TRUE(r.pivoting.tight_per_step.empty());
}

TEST(SolverWarmStart, WarmStartOfAPerturbedProblemConvergesFasterToTheSameAnswer) {
    for (Method m : kBppMethods) {
        auto p = problems::chain_mlcp(30, 12, 100, 1e-6);
        std::vector<double> x;
        const Result cold = run(p, m, x);
        ASSERT_EQ(cold.status, Status::Converged);
        for (double& b : p.b) b *= 1.01;  // the next time step, roughly
        std::vector<double> x_cold, x_warm;
        const Result again = run(p, m, x_cold);
        Start start;
        start.states = cold.states;
        const Result warm = run(p, m, x_warm, {}, start);
        ASSERT_EQ(warm.status, Status::Converged);
        EXPECT_LT(warm.pivoting.pivots, again.pivoting.pivots) << to_string(m);
        EXPECT_LT(max_abs_diff(x_warm, x_cold), 1e-9 * inf_norm(x_cold)) << to_string(m);
    }
}

TEST(SolverContinuation, StagesReachTheSameAnswer) {
    const auto p = problems::chain_mlcp(25, 10, 1000, 1e-10);
    std::vector<double> x0, x1;
    const Result plain = run(p, Method::Bpp, x0);
    Options o;
    o.tuning.continuation_stages = 4;
    const Result staged = run(p, Method::Bpp, x1, o);
    ASSERT_TRUE(plain.status == Status::Converged || plain.status == Status::FallbackUsed) << plain.message;
    ASSERT_EQ(staged.status, plain.status) << staged.message;
    EXPECT_GT(staged.pivoting.pivots, plain.pivoting.pivots);  // the stages cost pivots of their own
    EXPECT_LT(max_abs_diff(x0, x1), 1e-8 * inf_norm(x0));
}

TEST(SolverPgs, ConvergesOnAWellConditionedProblemAndReportsMaxIterationsOtherwise) {
    auto p = problems::random_boxed_mlcp(15, 0, 0, 3, 4);
    p.findex.clear();
    const auto expected = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
    ASSERT_TRUE(expected.has_value());
    Options o;
    o.pgs_iterations = 2000;
    std::vector<double> x;
    const Result r = run(p, Method::Pgs, x, o);
    EXPECT_EQ(r.status, Status::Converged);
    EXPECT_LE(r.residuals.scaled_natural, o.tolerance);
    EXPECT_LT(max_abs_diff(x, *expected), 1e-7);
    o.pgs_iterations = 1;
    const Result short_run = run(p, Method::Pgs, x, o);
    EXPECT_EQ(short_run.status, Status::MaxIterations);
    EXPECT_FALSE(short_run.message.empty());
    EXPECT_TRUE(all_finite(x));
}

}  // namespace
}  // namespace ode_bpp
