// Lemke's method (pivoting/lemke.h) and the friction LCP it solves for Consistent friction
// (pivoting/friction_lcp.h): solutions checked by their own certificate (z >= 0, u = Mz + q >= 0,
// z'u = 0), rays where no solution exists, and the friction LCP's answer checked as an answer of
// the MLCP with bounds from its own normals (compute_residuals).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>

#include "ode_bpp/residuals.h"
#include "pivoting/friction_lcp.h"
#include "pivoting/lemke.h"
#include "pivoting/sparse_lemke.h"
#include "linalg/symmetric_rows.h"
#include "problems/generators.h"
#include "test_pivoting_support.h"

namespace ode_bpp::pivoting {
namespace {

/// max over i of the violations of z >= 0, u >= 0 and z_i u_i = 0, relative to the LCP's scale.
double lcp_violation(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& z) {
    const Eigen::VectorXd u = M * z + q;
    const double scale = 1 + q.cwiseAbs().maxCoeff() + (M.cwiseAbs() * z.cwiseAbs()).maxCoeff();
    double v = 0;
    for (int i = 0; i < z.size(); ++i) v = std::max({v, -z[i], -u[i], std::abs(std::min(z[i], u[i]))});
    return v / scale;
}

Eigen::MatrixXd random_matrix(int n, int m, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Eigen::MatrixXd G(n, m);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) G(i, j) = static_cast<double>(rng() % 2001) / 1000.0 - 1.0;
    return G;
}

/// Semidefinite M (copositive-plus): Lemke solves every feasible instance.
TEST(Lemke, SolvesPositiveSemidefiniteLcps) {
    int solved = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        const int n = 5 + static_cast<int>(seed) * 4;
        const Eigen::MatrixXd G = random_matrix(n, n / 2, seed);  // rank n/2
        const Eigen::MatrixXd M = G * G.transpose();
        // q = u* - M z* with z*, u* >= 0: z* is feasible, so a solution exists
        const Eigen::VectorXd z_star = random_matrix(n, 1, seed + 100).col(0).cwiseAbs();
        const Eigen::VectorXd u_star = random_matrix(n, 1, seed + 200).col(0).cwiseAbs();
        const Eigen::VectorXd q = u_star - M * z_star;
        const LemkeSolution s = solve_lemke(M, q, spread_covering_vector(n, 0), 20 * n);
        ASSERT_EQ(s.outcome, LemkeOutcome::Solved) << "seed " << seed;
        EXPECT_LT(lcp_violation(M, q, s.z), 1e-12) << "seed " << seed;
        ++solved;
    }
    EXPECT_EQ(solved, 10);
}

TEST(Lemke, SolvesPositiveDefiniteLcpsWithEveryCoveringVector) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        const int n = 40;
        const Eigen::MatrixXd G = random_matrix(n, n, seed);
        const Eigen::MatrixXd M = G * G.transpose() + 1e-3 * Eigen::MatrixXd::Identity(n, n);
        const Eigen::VectorXd q = random_matrix(n, 1, seed + 50).col(0);
        for (int attempt = -1; attempt < 3; ++attempt) {
            const Eigen::VectorXd d = attempt < 0 ? Eigen::VectorXd::Ones(n) : spread_covering_vector(n, attempt);
            const LemkeSolution s = solve_lemke(M, q, d, 20 * n);
            ASSERT_EQ(s.outcome, LemkeOutcome::Solved) << "seed " << seed << " attempt " << attempt;
            EXPECT_LT(lcp_violation(M, q, s.z), 1e-11) << "seed " << seed << " attempt " << attempt;
            for (int i = 0; i < n; ++i)
                if (!s.z_basic[i]) {
                    EXPECT_EQ(s.z[i], 0.0);
                }
        }
    }
}

/// Degenerate: duplicated rows and columns, and zeros in q, make ties in the ratio test that the
/// lexicographic rule must break without cycling.
TEST(Lemke, FinishesOnDegenerateProblems) {
    const int base = 12;
    const Eigen::MatrixXd G = random_matrix(base, base, 7);
    Eigen::MatrixXd B = G * G.transpose() + Eigen::MatrixXd::Identity(base, base);
    Eigen::MatrixXd M(2 * base, 2 * base);
    M << B, B, B, B;  // every row twice
    Eigen::VectorXd q(2 * base);
    q << -Eigen::VectorXd::Ones(base), -Eigen::VectorXd::Ones(base);
    q.segment(0, 3).setZero();
    const LemkeSolution s = solve_lemke(M, q, Eigen::VectorXd::Ones(2 * base), 40 * base);
    ASSERT_EQ(s.outcome, LemkeOutcome::Solved);
    EXPECT_LT(lcp_violation(M, q, s.z), 1e-12);
}

TEST(Lemke, EndsOnARayWhenNoSolutionExists) {
    // u = -z - 1 < 0 for every z >= 0
    const Eigen::MatrixXd M = -Eigen::MatrixXd::Identity(1, 1);
    const Eigen::VectorXd q = -Eigen::VectorXd::Ones(1);
    EXPECT_EQ(solve_lemke(M, q, Eigen::VectorXd::Ones(1), 10).outcome, LemkeOutcome::RayTermination);
}

TEST(Lemke, ZeroIsTheAnswerWhenQIsNonNegative) {
    const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(3, 3);
    const Eigen::VectorXd q = Eigen::VectorXd::Constant(3, 2.0);
    const LemkeSolution s = solve_lemke(M, q, Eigen::VectorXd::Ones(3), 10);
    ASSERT_EQ(s.outcome, LemkeOutcome::Solved);
    EXPECT_EQ(s.pivots, 0);
    EXPECT_EQ(s.z.norm(), 0.0);
}

TEST(Lemke, StopsAtItsBudget) {
    const Eigen::MatrixXd G = random_matrix(30, 30, 3);
    const Eigen::MatrixXd M = G * G.transpose() + Eigen::MatrixXd::Identity(30, 30);
    const Eigen::VectorXd q = -Eigen::VectorXd::Ones(30);  // every row ends positive: >= 30 pivots
    const LemkeSolution s = solve_lemke(M, q, Eigen::VectorXd::Ones(30), 5);
    EXPECT_EQ(s.outcome, LemkeOutcome::MaxPivots);
    EXPECT_EQ(s.pivots, 5);
}

TEST(Lemke, SpreadCoveringVectorsArePositiveAndDiffer) {
    const Eigen::VectorXd a = spread_covering_vector(50, 0), b = spread_covering_vector(50, 1);
    EXPECT_GE(a.minCoeff(), 0.5);
    EXPECT_LT(a.maxCoeff(), 1.5);
    EXPECT_GT((a - b).cwiseAbs().maxCoeff(), 0.1);
    EXPECT_EQ(a, spread_covering_vector(50, 0));  // reproducible
}

/// A sparse positive definite M: a random banded G G' plus a diagonal.
Eigen::SparseMatrix<double> banded_spd(int n, int band, std::uint64_t seed) {
    const Eigen::MatrixXd R = random_matrix(n, band, seed);
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < band && i + k < n; ++k) G(i, i + k) = R(i, k);
    const Eigen::MatrixXd M = G * G.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    return M.sparseView();
}

TEST(SparseLemke, SolvesWhatTheDenseLemkeSolves) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        const int n = 60 + 20 * static_cast<int>(seed);
        const Eigen::SparseMatrix<double> M = banded_spd(n, 4, seed);
        const Eigen::VectorXd q = random_matrix(n, 1, seed + 50).col(0).array() - 0.7;  // most rows end positive
        const LemkeSolution s = solve_sparse_lemke(M, q, {}, spread_covering_vector(n, 0), 20 * n);
        ASSERT_EQ(s.outcome, LemkeOutcome::Solved) << "seed " << seed;
        EXPECT_LT(lcp_violation(Eigen::MatrixXd(M), q, s.z), 1e-11) << "seed " << seed;
        const LemkeSolution dense = solve_lemke(Eigen::MatrixXd(M), q, spread_covering_vector(n, 0), 20 * n);
        ASSERT_EQ(dense.outcome, LemkeOutcome::Solved);
        EXPECT_LT((s.z - dense.z).cwiseAbs().maxCoeff(), 1e-9 * (1 + dense.z.cwiseAbs().maxCoeff())) << "seed " << seed;
        EXPECT_GT(s.pivots, 50) << "seed " << seed;  // long enough for several refactorizations
    }
}

TEST(SparseLemke, AGuessThatIsTheAnswerEndsTheMomentItStarts) {
    const int n = 120;
    const Eigen::SparseMatrix<double> M = banded_spd(n, 5, 11);
    const Eigen::VectorXd q = random_matrix(n, 1, 12).col(0);
    const LemkeSolution cold = solve_sparse_lemke(M, q, {}, spread_covering_vector(n, 0), 20 * n);
    ASSERT_EQ(cold.outcome, LemkeOutcome::Solved);
    const LemkeSolution warm = solve_sparse_lemke(M, q, cold.z_basic, spread_covering_vector(n, 1), 20 * n);
    ASSERT_EQ(warm.outcome, LemkeOutcome::Solved);
    EXPECT_EQ(warm.pivots, 0);
    EXPECT_LT((warm.z - cold.z).cwiseAbs().maxCoeff(), 1e-10 * (1 + cold.z.cwiseAbs().maxCoeff()));
    // a guess with a few wrong entries takes a few pivots, far fewer than the cold path
    std::vector<char> near = cold.z_basic;
    for (int i = 0; i < n; i += 20) near[i] = !near[i];
    const LemkeSolution close = solve_sparse_lemke(M, q, near, spread_covering_vector(n, 1), 20 * n);
    ASSERT_EQ(close.outcome, LemkeOutcome::Solved);
    EXPECT_LT(lcp_violation(Eigen::MatrixXd(M), q, close.z), 1e-11);
    EXPECT_LT(close.pivots, cold.pivots / 2);
}

TEST(SparseLemke, EndsOnARayWhenNoSolutionExists) {
    const Eigen::MatrixXd M = -Eigen::MatrixXd::Identity(1, 1);
    const Eigen::VectorXd q = -Eigen::VectorXd::Ones(1);
    EXPECT_EQ(solve_sparse_lemke(M.sparseView(), q, {}, Eigen::VectorXd::Ones(1), 10).outcome,
              LemkeOutcome::RayTermination);
}

using test::DriverLcp;

TEST(FrictionLcp, SparseFormIsTheDenseForm) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const auto p = problems::random_boxed_mlcp(40, 0, 8, 1e4, seed);
        DriverLcp s(p);
        std::string why;
        const auto dense = FrictionLcp::build(s.lcp, s.friction.view(), why);
        const auto sparse = FrictionLcp::build_sparse(s.lcp, s.friction.view(), why);
        ASSERT_TRUE(dense.has_value() && sparse.has_value()) << why;
        EXPECT_LT((Eigen::MatrixXd(sparse->sparse_M()) - dense->M()).cwiseAbs().maxCoeff(), 1e-12 * dense->M().cwiseAbs().maxCoeff());
        EXPECT_LT((sparse->q() - dense->q()).cwiseAbs().maxCoeff(), 1e-12 * (1 + dense->q().cwiseAbs().maxCoeff()));
    }
    const auto with_unbounded = problems::random_boxed_mlcp(40, 4, 8, 1e4, 1);
    DriverLcp s(with_unbounded);
    std::string why;
    EXPECT_FALSE(FrictionLcp::build_sparse(s.lcp, s.friction.view(), why).has_value());
    EXPECT_NE(why.find("unbounded"), std::string::npos) << why;
}

/// The Lemke stage routes by has_sparse_form before building (friction_policy.cpp), so it must
/// say yes exactly where build_sparse takes the problem: islands with and without always-free rows
/// (nub) and free rows beyond them.
TEST(FrictionLcp, HasSparseFormExactlyWhereBuildSparseTakesTheProblem) {
    for (const int nub : {0, 3}) {
        for (std::uint64_t seed = 1; seed <= 4; ++seed) {
            const auto p = problems::random_boxed_mlcp(40, nub, 8, 1e4, seed);
            DriverLcp s(p);
            std::string why;
            const bool taken = FrictionLcp::build_sparse(s.lcp, s.friction.view(), why).has_value();
            EXPECT_EQ(FrictionLcp::has_sparse_form(s.lcp, s.friction.view()), taken) << "nub " << nub << ", seed " << seed << ": " << why;
            EXPECT_EQ(taken, nub == 0) << why;
            // a row beyond nub with both bounds infinite is unbounded too
            if (nub == 0 && s.friction.rows.size() < static_cast<std::size_t>(s.lcp.n())) {
                int free_row = 0;
                while (std::find(s.friction.rows.begin(), s.friction.rows.end(), free_row) != s.friction.rows.end()) ++free_row;
                s.lcp.lo[free_row] = -INFINITY;
                s.lcp.hi[free_row] = INFINITY;
                EXPECT_FALSE(FrictionLcp::has_sparse_form(s.lcp, s.friction.view()));
                EXPECT_FALSE(FrictionLcp::build_sparse(s.lcp, s.friction.view(), why).has_value());
            }
        }
    }
}

TEST(FrictionLcp, TheGuessFromAnAnswerIsItsBasis) {
    const auto p = problems::random_boxed_mlcp(60, 0, 12, 1e3, 5);
    DriverLcp s(p);
    std::string why;
    const auto lcp = FrictionLcp::build_sparse(s.lcp, s.friction.view(), why);
    ASSERT_TRUE(lcp.has_value()) << why;
    const int N = static_cast<int>(lcp->q().size());
    const LemkeSolution cold = solve_sparse_lemke(lcp->sparse_M(), lcp->q(), {}, spread_covering_vector(N, 0), 10 * N);
    ASSERT_EQ(cold.outcome, LemkeOutcome::Solved);
    std::vector<double> x;
    std::vector<RowState> states;
    lcp->recover(cold, x, states);
    const LemkeSolution warm =
        solve_sparse_lemke(lcp->sparse_M(), lcp->q(), lcp->basis_guess(states, x), spread_covering_vector(N, 1), 10 * N);
    ASSERT_EQ(warm.outcome, LemkeOutcome::Solved);
    EXPECT_LE(warm.pivots, cold.pivots / 10) << "cold: " << cold.pivots;  // degenerate rows may need a pivot or two
    std::vector<double> x_warm;
    lcp->recover(warm, x_warm, states);
    EXPECT_LT(compute_residuals(p, ConstStrided{x_warm.data(), 1}).scaled_natural, 1e-8);
}

TEST(FrictionLcp, LemkesAnswerSolvesTheMlcpWithBoundsFromItsOwnNormals) {
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        const auto p = problems::random_boxed_mlcp(40, 4, 8, 1e4, seed);
        DriverLcp s(p);
        std::string why;
        const auto lcp = FrictionLcp::build(s.lcp, s.friction.view(), why);
        ASSERT_TRUE(lcp.has_value()) << why;
        const int N = static_cast<int>(lcp->q().size());
        const LemkeSolution sol = solve_lemke(lcp->M(), lcp->q(), spread_covering_vector(N, 0), 10 * N);
        ASSERT_EQ(sol.outcome, LemkeOutcome::Solved) << "seed " << seed;
        std::vector<double> x;
        std::vector<RowState> states;
        lcp->recover(sol, x, states);
        const Residuals r = compute_residuals(p, ConstStrided{x.data(), 1});
        double scale = 1;
        for (double v : x) scale = std::max(scale, std::abs(v));
        EXPECT_LT(r.scaled_natural, 1e-8) << "seed " << seed;
        EXPECT_LT(r.friction, 1e-9 * scale) << "seed " << seed;
        for (int i = 0; i < p.n; ++i) {  // the index set matches x
            if (states[i] == RowState::AtLo && p.findex[i] < 0) {
                EXPECT_EQ(x[i], p.lo[i]) << "row " << i;
            }
            if (i < p.nub) {
                EXPECT_EQ(states[i], RowState::Free);
            }
        }
    }
}

TEST(FrictionLcp, FrictionOnAnUnboundedNormalIsOutsideTheFormulation) {
    auto p = problems::random_boxed_mlcp(20, 4, 3, 1e2, 3);
    p.findex[5] = 0;  // row 0 is unbounded: |x_0| could be any sign
    DriverLcp s(p);
    std::string why;
    EXPECT_FALSE(FrictionLcp::build(s.lcp, s.friction.view(), why).has_value());
    EXPECT_NE(why.find("normal"), std::string::npos) << why;
}

}  // namespace
}  // namespace ode_bpp::pivoting
