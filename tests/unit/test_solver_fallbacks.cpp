// The fallback chain of solve() (documented at the top of solver.cpp): regularization on
// Cholesky breakdown, Dantzig after that, and never a non-finite x.
#include <gtest/gtest.h>

#include <cmath>

#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "linalg/skyline.h"
#include "linalg/symmetric_rows.h"
#include "problems/generators.h"
#include "problems/named.h"

namespace ode_bpp {
namespace {

const Method kBppMethods[] = {Method::BppChol, Method::BppDown, Method::BppSky, Method::Bpp};

bool all_finite(const std::vector<double>& x) {
    for (double v : x)
        if (!std::isfinite(v)) return false;
    return true;
}

Result run(const problems::OwnedProblem& p, Method m, std::vector<double>& x, Options o = {}) {
    o.method = m;
    x.assign(p.n, 0.0);
    return solve(p, o, x.data());
}

/// Indefinite: eigenvalues 3 and -1, beyond any regularization the chain allows.
problems::OwnedProblem indefinite() {
    auto p = problems::OwnedProblem::zeros("indefinite", 2);
    p.a(0, 0) = p.a(1, 1) = 1;
    p.a(0, 1) = p.a(1, 0) = 2;
    p.b = {1, 1};
    return p;
}

TEST(SolverFallback, DuplicatedRowsAreRegularizedAndStillSolved) {
    const auto p = problems::duplicated_rows();
    for (Method m : kBppMethods) {
        std::vector<double> x;
        const Result r = run(p, m, x);
        ASSERT_TRUE(all_finite(x));
        EXPECT_EQ(r.status, Status::FallbackUsed) << to_string(m) << ": " << r.message;
        EXPECT_EQ(r.fallback, Fallback::Regularized) << to_string(m);
        EXPECT_GT(r.regularization, 0);
        EXPECT_FALSE(r.message.empty());
        // A + delta I is solved exactly; against A itself the residual is ~ delta |x|
        EXPECT_LT(r.residuals.natural, 1e3 * r.regularization * (1 + std::abs(x[0]) + std::abs(x[1])));
        // the two duplicated normals share the load (any split solves the singular problem)
        EXPECT_NEAR(x[0] + x[1] + 0.2 * x[2], 1.0, 1e-6);
    }
}

TEST(SolverFallback, IndefiniteMatrixGoesToDantzigWhenAllowed) {
    const auto p = indefinite();
    for (Method m : kBppMethods) {
        std::vector<double> x;
        const Result r = run(p, m, x);
        ASSERT_TRUE(all_finite(x));
        EXPECT_EQ(r.status, Status::FallbackUsed) << to_string(m);
        EXPECT_TRUE(r.fallback == Fallback::Dantzig || r.fallback == Fallback::RegularizedDantzig) << to_string(m);
    }
}

TEST(SolverFallback, IndefiniteMatrixIsNotSpdWithoutDantzigAndXIsZero) {
    const auto p = indefinite();
    for (Method m : kBppMethods) {
        Options o;
        o.dantzig_fallback = false;
        std::vector<double> x = {7, 7};
        o.method = m;
        const Result r = solve(p, o, x.data());
        EXPECT_EQ(r.status, Status::NotSpd) << to_string(m);
        EXPECT_FALSE(r.message.empty());
        EXPECT_EQ(x[0], 0.0);
        EXPECT_EQ(x[1], 0.0);
        EXPECT_FALSE(is_usable(r.status));
    }
}

TEST(SolverFallback, IndefiniteMatrixWithSubnormalDiagonalEndsAsNotSpd) {
    // 1e-12 * max diag underflows to 0 here: the regularization ladder cannot rise and must stop
    // (fuzz_solve found it retrying at shift 0 forever)
    auto p = indefinite();
    p.a(0, 0) = p.a(1, 1) = 5e-320;
    for (Method m : kBppMethods) {
        Options o;
        o.dantzig_fallback = false;
        std::vector<double> x = {7, 7};
        o.method = m;
        const Result r = solve(p, o, x.data());
        EXPECT_EQ(r.status, Status::NotSpd) << to_string(m);
        EXPECT_EQ(x[0], 0.0);
        EXPECT_EQ(x[1], 0.0);
    }
}

TEST(SolverFallback, DantzigOnItsOwnDoesNotFallBackToItself) {
    const auto p = indefinite();
    std::vector<double> x;
    const Result r = run(p, Method::Dantzig, x);
    EXPECT_TRUE(all_finite(x));
    EXPECT_EQ(r.fallback, Fallback::None);
}

TEST(SolverFallback, NearlySingularChainNeverProducesNonFiniteValues) {
    // CFM 0: ODE's stiffest setting, redundant rows where contacts meet joints
    const auto p = problems::chain_mlcp(30, 15, 1e4, 0.0);
    for (const std::string& name : method_names()) {
        std::vector<double> x;
        const Result r = run(p, *method_from_string(name), x);
        EXPECT_TRUE(all_finite(x)) << name;
        EXPECT_NE(r.status, Status::InvalidInput) << name;
        if (r.status != Status::NotSpd) { EXPECT_TRUE(is_usable(r.status)) << name; }
    }
}

/// An island whose factor would exceed Options::max_factor_entries (here a 58-row chain with a
/// limit below its envelope) is answered by projected Gauss-Seidel on the sparse A, says so, and
/// keeps every bound; within the limit the same island is solved exactly. The dense methods are
/// measured by their whole triangle.
TEST(SolverFallback, IslandTooLargeForAFactorIsAnsweredByPgs) {
    const auto p = problems::chain_mlcp(16, 4);
    ASSERT_GT(p.n, 32);  // past the small-island path
    for (Method m : kBppMethods) {
        Options o;
        std::vector<double> x;
        ASSERT_EQ(run(p, m, x, o).status, Status::Converged);  // leaves its w in the thread's workspace
        o.max_factor_entries = 2 * p.n;  // below the chain's banded envelope
        const Result r = run(p, m, x, o);
        EXPECT_EQ(r.status, Status::FallbackUsed) << to_string(m) << ": " << r.message;
        EXPECT_EQ(r.fallback, Fallback::Pgs) << to_string(m);
        EXPECT_NE(r.message.find("max_factor_entries"), std::string::npos) << r.message;
        EXPECT_EQ(r.pivoting.pivots, o.pgs_iterations);
        ASSERT_TRUE(all_finite(x));
        // the residuals of PGS's own answer, not of w an earlier solve of the same size left
        EXPECT_EQ(r.residuals.natural, compute_residuals(p, ConstStrided{x.data(), 1}).natural);
        EXPECT_GT(r.residuals.natural, 0.0);
        for (int i = p.nub; i < p.n; ++i)
            if (p.findex[i] < 0) {
                EXPECT_GE(x[i], p.lo[i]) << i;
                EXPECT_LE(x[i], p.hi[i]) << i;
            }
        o.max_factor_entries = static_cast<std::int64_t>(p.n) * (p.n + 1) / 2;
        const Result exact = run(p, m, x, o);
        EXPECT_EQ(exact.status, Status::Converged) << to_string(m) << ": " << exact.message;
        EXPECT_EQ(exact.fallback, Fallback::None);
    }
    EXPECT_STREQ(to_string(Fallback::Pgs), "pgs");
}

/// The limit is on the envelope of the factor the solve itself builds, in its own ordering:
/// Bpp solves an island whose envelope is exactly max_factor_entries and hands one entry less to
/// PGS; the ordering it picks to find out is the one it factors in (the same answer, bit for bit,
/// as a solve without the limit).
TEST(SolverFallback, FactorLimitIsTheEnvelopeOfTheSolvesOwnOrdering) {
    const auto p = problems::chain_mlcp(16, 4);
    std::vector<double> unlimited_x;
    const Result unlimited = run(p, Method::Bpp, unlimited_x);
    ASSERT_EQ(unlimited.status, Status::Converged);
    ASSERT_FALSE(unlimited.ordering.empty());
    const linalg::SymmetricRows A(p, {});
    const auto envelope = static_cast<std::int64_t>(
        linalg::SkylineShape::from_row_profile(A.row_profile_under(unlimited.ordering)).size());
    ASSERT_LT(envelope, static_cast<std::int64_t>(p.n) * (p.n + 1) / 2);  // the limit is looked at
    Options o;
    o.max_factor_entries = envelope;
    std::vector<double> x;
    const Result at_limit = run(p, Method::Bpp, x, o);
    EXPECT_EQ(at_limit.status, Status::Converged) << at_limit.message;
    EXPECT_EQ(at_limit.ordering, unlimited.ordering);
    EXPECT_EQ(x, unlimited_x);
    EXPECT_EQ(at_limit.pivoting.pivots, unlimited.pivoting.pivots);
    o.max_factor_entries = envelope - 1;
    EXPECT_EQ(run(p, Method::Bpp, x, o).fallback, Fallback::Pgs);
    // a given ordering is priced as given
    Start given;
    given.ordering.resize(static_cast<std::size_t>(p.n));
    for (int i = 0; i < p.n; ++i) given.ordering[i] = p.n - 1 - i;
    const auto given_envelope = static_cast<std::int64_t>(
        linalg::SkylineShape::from_row_profile(A.row_profile_under(given.ordering)).size());
    o.method = Method::Bpp;
    o.max_factor_entries = given_envelope;
    const Result within = solve(p, o, x.data(), given);
    EXPECT_EQ(within.fallback, Fallback::None);
    EXPECT_EQ(within.ordering, given.ordering);
    o.max_factor_entries = given_envelope - 1;
    EXPECT_EQ(solve(p, o, x.data(), given).fallback, Fallback::Pgs);
}

}  // namespace
}  // namespace ode_bpp
