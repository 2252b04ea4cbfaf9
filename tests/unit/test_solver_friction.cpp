// Friction semantics: Frozen reproduces ODE's Dantzig; Consistent keeps every friction impulse
// inside mu times its normal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "ode_bpp/io.h"
#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "problems/generators.h"
#include "problems/named.h"
#include "problems/vectors.h"
#include "problems/oracle.h"
#include "test_io_support.h"

namespace ode_bpp {
namespace {

using problems::max_abs_diff;

const Method kBppMethods[] = {Method::BppChol, Method::BppDown, Method::BppSky, Method::Bpp};

Result run(const problems::OwnedProblem& p, Method m, FrictionMode f, std::vector<double>& x, Options o = {}) {
    o.method = m;
    o.friction = f;
    x.assign(p.n, 0.0);
    return solve(p, o, x.data());
}

TEST(SolverFriction, DantzigBreaksTheConeOnTheNotesExampleAndFrozenBppMatchesIt) {
    const auto p = problems::dantzig_friction_3x3();
    std::vector<double> xd;
    const Result rd = run(p, Method::Dantzig, FrictionMode::Frozen, xd);
    ASSERT_EQ(rd.status, Status::Converged);
    // ODE's Dantzig takes the bound from the normal before the friction row moved it
    EXPECT_GT(rd.residuals.friction, 1e-3);
    EXPECT_GT(std::abs(xd[1]), 0.5 * xd[0]);
    const auto frozen = problems::enumerate_frozen_friction(p);
    ASSERT_TRUE(frozen.has_value());
    EXPECT_LT(max_abs_diff(xd, *frozen), 1e-12);
    for (Method m : kBppMethods) {
        std::vector<double> x;
        const Result r = run(p, m, FrictionMode::Frozen, x);
        ASSERT_EQ(r.status, Status::Converged);
        EXPECT_LT(max_abs_diff(x, xd), 1e-12) << to_string(m);
    }
}

TEST(SolverFriction, ConsistentModeIsAFixedPointOfItsOwnBounds) {
    const auto p = problems::dantzig_friction_3x3();
    for (Method m : kBppMethods) {
        std::vector<double> x;
        const Result r = run(p, m, FrictionMode::Consistent, x);
        ASSERT_EQ(r.status, Status::Converged) << r.message;
        EXPECT_TRUE(r.pivoting.linked_solves > 0);
        EXPECT_LT(r.residuals.friction, 1e-8);
        EXPECT_LT(r.residuals.scaled_natural, 1e-8);
        // the fixed-bound problem with bounds +-mu x0 taken from the answer has the answer as solution
        const double bound = 0.5 * x[0];
        const auto again = problems::enumerate_boxed_lcp(p, {0, -bound, -INFINITY}, {INFINITY, bound, INFINITY});
        ASSERT_TRUE(again.has_value());
        EXPECT_LT(max_abs_diff(x, *again), 1e-8) << to_string(m);
    }
}

TEST(SolverFriction, FrozenBppMatchesOdesDantzigOnRandomContacts) {
    int compared = 0;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        const auto p = problems::random_boxed_mlcp(30, 3, 6, 1e4, seed);
        std::vector<double> xd, x;
        ASSERT_EQ(run(p, Method::Dantzig, FrictionMode::Frozen, xd).status, Status::Converged);
        const Result r = run(p, Method::Bpp, FrictionMode::Frozen, x);
        ASSERT_EQ(r.status, Status::Converged);
        double scale = 1;
        for (double v : xd) scale = std::max(scale, std::abs(v));
        EXPECT_LT(max_abs_diff(x, xd), 1e-9 * scale) << "seed " << seed;
        ++compared;
    }
    EXPECT_EQ(compared, 8);
}

TEST(SolverFriction, ConsistentModeKeepsEveryFrictionRowInsideItsCone) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        const auto p = problems::random_boxed_mlcp(30, 3, 6, 1e4, seed);
        for (Method m : kBppMethods) {
            Options o;
            o.tuning.max_friction_rounds = 200;
            std::vector<double> x;
            const Result r = run(p, m, FrictionMode::Consistent, x, o);
            ASSERT_EQ(r.status, Status::Converged) << to_string(m) << " seed " << seed << ": " << r.message;
            double scale = 1;
            for (double v : x) scale = std::max(scale, std::abs(v));
            EXPECT_LT(r.residuals.friction, 1e-8 * scale) << to_string(m) << " seed " << seed;
            EXPECT_LT(r.residuals.scaled_natural, 1e-8) << to_string(m) << " seed " << seed;
        }
    }
}

TEST(SolverFriction, ConsistentModeReportsWhenItsRoundsRunOut) {
    const auto p = problems::random_boxed_mlcp(30, 3, 6, 1e4, 2);
    Options o;
    o.tuning.link_friction = false;  // the outer rounds alone
    o.tuning.max_friction_rounds = 1;
    std::vector<double> x;
    const Result r = run(p, Method::Bpp, FrictionMode::Consistent, x, o);
    EXPECT_EQ(r.status, Status::FrictionNotConsistent);
    EXPECT_TRUE(is_usable(r.status));
    EXPECT_EQ(r.pivoting.friction_rounds, 1);
    EXPECT_FALSE(r.message.empty());
    for (double v : x) EXPECT_TRUE(std::isfinite(v));
}

/// Friction raising its own normals (a chain sliding over a drum under a heavy load, the
/// capstan): the map from bounds to normals expands, so bounds iterated between fixed-bound solves
/// do not settle within their rounds, while the linked solve (friction rows at a bound solved with
/// their normals) reaches the certificate. (Until capstan_mlcp's link centres stopped dangling,
/// the capstans here were garbage geometry, and "harder" ones defeated both.)
TEST(SolverFriction, CapstanNeedsTheLinkedSolve) {
    const auto p = problems::capstan_mlcp(30, 9.0, 1.0, 1000, 1e-10);
    std::vector<double> x;
    Options outer_only;
    outer_only.tuning.link_friction = false;
    const Result damped = run(p, Method::Bpp, FrictionMode::Consistent, x, outer_only);
    EXPECT_EQ(damped.status, Status::FrictionNotConsistent);
    const Result r = run(p, Method::Bpp, FrictionMode::Consistent, x);
    ASSERT_EQ(r.status, Status::Converged) << r.message;
    EXPECT_TRUE(r.pivoting.linked_solves > 0);
    EXPECT_EQ(r.pivoting.lemke_pivots, 0);
    // the certificate: natural residual with bounds from the answer's own normals
    const Residuals res = compute_residuals(p, ConstStrided{x.data(), 1});
    EXPECT_LE(res.scaled_natural, 1e-8);
    EXPECT_LE(res.friction, 1e-9 * (1 + *std::max_element(x.begin(), x.end())));
    EXPECT_LT(res.friction, damped.residuals.friction);
}

/// Where the linked solve runs out of budget (on the winch at compliance 1e-10, 2 % of the frames
/// with 300 steps), Lemke's method on the friction LCP finds the answer and a linked solve from its
/// index set certifies it. A budget of 3 steps reproduces that here on every BPP method.
TEST(SolverFriction, LemkeStageFinishesWhereTheLinkedSolveRunsOut) {
    const auto p = problems::capstan_mlcp(30, 9.0, 1.0, 1000, 1e-10);
    for (Method m : kBppMethods) {
        Options o;
        o.max_pivots = 3;
        o.tuning.lemke_friction = false;
        std::vector<double> x;
        const Result without = run(p, m, FrictionMode::Consistent, x, o);
        EXPECT_NE(without.status, Status::Converged) << to_string(m);
        o.tuning.lemke_friction = true;
        const Result r = run(p, m, FrictionMode::Consistent, x, o);
        ASSERT_EQ(r.status, Status::Converged) << to_string(m) << ": " << r.message;
        EXPECT_GT(r.pivoting.lemke_pivots, 0) << to_string(m);
        const Residuals res = compute_residuals(p, ConstStrided{x.data(), 1});
        EXPECT_LE(res.scaled_natural, 1e-8) << to_string(m);
        EXPECT_LE(res.friction, 1e-9 * (1 + *std::max_element(x.begin(), x.end()))) << to_string(m);
    }
}

// A cannon island (tests/data/captured/README.md): the sparse Lemke stage's path passes a nearly
// singular basis and ends at an answer that misses the LCP by more than its tolerance. Taken as
// the start of the certifying linked solve, it finishes; without it the outer rounds stall at a
// relative residual of 1.5e-8.
TEST(SolverFriction, LinkedSolveCertifiesAnInaccurateLemkeAnswer) {
    const ReadResult read =
        read_mlcp((io_test::data_dir() / "captured" / "cannon-consistent-inaccurate-lemke-291.mlcp").string());
    ASSERT_TRUE(read.ok) << read.error;
    Options o;
    o.friction = FrictionMode::Consistent;
    o.dantzig_fallback = false;
    std::vector<double> x(static_cast<std::size_t>(read.file.n));
    const Result r = solve(read.file.view(), o, x.data());
    ASSERT_EQ(r.status, Status::Converged) << r.message;
    EXPECT_GT(r.pivoting.lemke_pivots, 0);
    EXPECT_LE(r.residuals.relative_natural, 1e-8);
    EXPECT_LE(compute_residuals(read.file.view(), ConstStrided{x.data(), 1}).relative_natural, 1e-8);
}

TEST(SolverFriction, ZeroNormalPinsItsFrictionRowsAtZero) {
    auto p = problems::random_boxed_mlcp(12, 0, 2, 1e2, 5);
    p.b[0] = -10;  // contact 0 pulls: its normal stays at 0, so its friction must be 0
    for (FrictionMode f : {FrictionMode::Frozen, FrictionMode::Consistent})
        for (Method m : kBppMethods) {
            std::vector<double> x;
            const Result r = run(p, m, f, x);
            ASSERT_EQ(r.status, Status::Converged);
            ASSERT_EQ(x[0], 0.0);
            EXPECT_EQ(x[1], 0.0);
            EXPECT_EQ(x[2], 0.0);
            EXPECT_NE(r.states[1], RowState::Free);
        }
}

// From a warm start that is its own answer, Frozen friction's second solve starts there
// (Tuning::frozen_second_solve_from_warm_start), not where the frictionless solve left the
// normals (row 2 separating): one step fewer, the same answer. On the small-island path and on
// the skyline path (dense_island_rows 0).
TEST(SolverFriction, FrozenSecondSolveStartsFromTheWarmStart) {
    const auto p = problems::friction_presses_a_second_contact();
    const std::vector<double> expected = {0.92, 1, 0.32};
    for (int dense_rows : {32, 0}) {
        Options o;
        o.tuning.dense_island_rows = dense_rows;
        std::vector<double> cold;
        const Result first = run(p, Method::Bpp, FrictionMode::Frozen, cold, o);
        ASSERT_EQ(first.status, Status::Converged) << first.message;
        ASSERT_LT(max_abs_diff(cold, expected), 1e-12);
        ASSERT_EQ(first.states, (std::vector<RowState>{RowState::Free, RowState::AtHi, RowState::Free}));
        int pivots[2] = {0, 0};
        for (bool from_warm : {false, true}) {
            Options w = o;
            w.tuning.frozen_second_solve_from_warm_start = from_warm;
            Start start;
            start.states = first.states;
            std::vector<double> x(3, 0.0);
            const Result r = solve(p, w, x.data(), start);
            ASSERT_EQ(r.status, Status::Converged) << r.message;
            EXPECT_LT(max_abs_diff(x, expected), 1e-12) << "dense_island_rows " << dense_rows;
            pivots[from_warm] = r.pivoting.pivots;
        }
        EXPECT_LT(pivots[1], pivots[0]) << "dense_island_rows " << dense_rows;
    }
}

}  // namespace
}  // namespace ode_bpp
