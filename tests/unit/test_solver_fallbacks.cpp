// The fallback chain of solve() (documented at the top of solver.cpp): regularization on
// Cholesky breakdown, Dantzig after that, and never a non-finite x.
#include <gtest/gtest.h>

#include <cmath>

#include "ode_bpp/solver.h"
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

}  // namespace
}  // namespace ode_bpp
