// The factor strategies (pivoting/free_solver.h): every one solves A_FF x_F = rhs_F for any
// sequence of tight sets, checked against a dense Eigen solve of the gathered A_FF.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "pivoting/free_solver.h"
#include "ordering/ordering_choice.h"
#include "pivoting/strategies.h"
#include "linalg/symmetric_rows.h"
#include "problems/generators.h"
#include "problems/named.h"

namespace ode_bpp::pivoting {
namespace {

const Method kBppMethods[] = {Method::BppChol, Method::BppDown, Method::BppSky, Method::Bpp};
constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Permuted {
    problems::OwnedProblem owned;
    linalg::SymmetricRows Ap;
};

Permuted permuted_for(Method m, problems::OwnedProblem owned) {
    const Problem p = owned.view();
    const linalg::SymmetricRows A(p, {});
    const std::vector<int> perm = ordering::choose_ordering(m, p, A, {});
    return {std::move(owned), A.permuted(perm)};
}

Eigen::MatrixXd dense(const linalg::SymmetricRows& A) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(A.n(), A.n());
    for (int i = 0; i < A.n(); ++i) {
        M(i, i) = A.diag(i);
        for (int k = A.row_begin(i); k < A.row_end(i); ++k) M(i, A.col(k)) = A.val(k);
    }
    return M;
}

/// ||A_FF x_F - rhs_F||_inf / (||A_FF||_inf ||x_F||_inf + ||rhs_F||_inf): Cholesky's normwise
/// backward error, O(n eps) whatever the conditioning.
double backward_error(const Eigen::MatrixXd& A, const std::vector<char>& tight, const std::vector<double>& rhs,
                      const std::vector<double>& x) {
    double residual = 0, norm_A = 0, norm_x = 0, norm_rhs = 0;
    for (int i = 0; i < A.rows(); ++i) {
        if (tight[i]) continue;
        double r = -rhs[i], row = 0;
        for (int j = 0; j < A.cols(); ++j)
            if (!tight[j]) {
                r += A(i, j) * x[j];
                row += std::abs(A(i, j));
            }
        residual = std::max(residual, std::abs(r));
        norm_A = std::max(norm_A, row);
        norm_x = std::max(norm_x, std::abs(x[i]));
        norm_rhs = std::max(norm_rhs, std::abs(rhs[i]));
    }
    return residual / (norm_A * norm_x + norm_rhs);
}

std::vector<std::vector<char>> tight_set_sequence(int n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<std::vector<char>> sets;
    for (double share : {0.0, 0.05, 0.3, 0.02, 0.6, 0.1, 0.0, 0.15}) {
        std::vector<char> tight(n, 0);
        for (int i = 0; i < n; ++i) tight[i] = (rng() % 1000) < share * 1000;
        sets.push_back(tight);
    }
    std::vector<char> tail(n, 0);  // every row from 2n/3 on: Bpp solves with L0's leading block
    for (int i = 2 * n / 3; i < n; ++i) tail[i] = 1;
    sets.push_back(tail);
    std::vector<char> last_only(n, 0);
    last_only[n - 1] = 1;
    sets.push_back(last_only);
    std::vector<char> first_only(n, 0);
    first_only[0] = 1;
    sets.push_back(first_only);
    return sets;
}

class PivotingStrategy : public ::testing::TestWithParam<Method> {};

void check_sequence(Method m, problems::OwnedProblem owned, std::uint64_t seed) {
    const Permuted pp = permuted_for(m, std::move(owned));
    const Eigen::MatrixXd A = dense(pp.Ap);
    StrategyBuffers buffers;  // outlives the strategy
    auto solver = make_free_solver(m, pp.Ap, buffers);
    ASSERT_TRUE(solver);
    ASSERT_TRUE(solver->prepare(0));
    const int n = pp.Ap.n();
    std::vector<double> rhs(n);
    for (int i = 0; i < n; ++i) rhs[i] = std::sin(0.7 * i + 1);
    for (const auto& tight : tight_set_sequence(n, seed))
        for (bool fresh : {false, true}) {
            std::vector<double> x = rhs;
            const FactorOutcome outcome = solver->solve_free(tight, x, fresh);
            ASSERT_NE(outcome, FactorOutcome::Breakdown);
            if (fresh) { EXPECT_EQ(outcome, FactorOutcome::Refactored); }
            for (int i = 0; i < n; ++i)
                if (tight[i]) { EXPECT_EQ(x[i], 0.0); }
            EXPECT_LT(backward_error(A, tight, rhs, x), 10 * n * kEps) << to_string(m) << " fresh " << fresh;
        }
}

TEST_P(PivotingStrategy, SolvesEveryTightSetOfAChainIsland) { check_sequence(GetParam(), problems::chain_mlcp(25, 12), 3); }

TEST_P(PivotingStrategy, SolvesEveryTightSetOfADenseMatrix) {
    auto p = problems::random_boxed_mlcp(40, 0, 0, 1e6, 8);
    check_sequence(GetParam(), std::move(p), 4);
}

TEST_P(PivotingStrategy, FactorErrorIsSmallWhereDefined) {
    const Permuted pp = permuted_for(GetParam(), problems::chain_mlcp(20, 8));
    StrategyBuffers buffers;  // outlives the strategy
    auto solver = make_free_solver(GetParam(), pp.Ap, buffers);
    ASSERT_TRUE(solver->prepare(0));
    const auto tight = tight_set_sequence(pp.Ap.n(), 5)[4];
    const double e = solver->factor_error(tight);
    if (GetParam() == Method::BppChol) {
        EXPECT_TRUE(std::isnan(e));
    } else {
        const double scale = std::sqrt(dense(pp.Ap).diagonal().maxCoeff());  // ~ max |L_ij|
        EXPECT_GE(e, 0);
        EXPECT_LT(e, 1e-10 * scale * pp.Ap.n());
    }
}

TEST_P(PivotingStrategy, SingularMatrixBreaksDown) {
    const auto owned = problems::duplicated_rows();
    const linalg::SymmetricRows A(owned.view(), {});
    StrategyBuffers buffers;  // outlives the strategy
    auto solver = make_free_solver(GetParam(), A, buffers);
    std::vector<char> none(3, 0);
    std::vector<double> x = {1, 1, 1};
    const bool prepared = solver->prepare(0);
    // BppChol has no L0, and Bpp factors L0 lazily (skyline_solver.cpp): the breakdown shows
    // at the first solve that needs the failing column
    if (GetParam() == Method::BppChol || GetParam() == Method::Bpp) {
        EXPECT_TRUE(prepared);
        EXPECT_EQ(solver->solve_free(none, x, false), FactorOutcome::Breakdown);
    } else {
        EXPECT_FALSE(prepared);
    }
    // and taking one of the duplicates out leaves an SPD A_FF
    std::vector<char> one_out = {1, 0, 0};
    ASSERT_TRUE(solver->prepare(1e-9));
    x = {1, 1, 1};
    EXPECT_NE(solver->solve_free(one_out, x, true), FactorOutcome::Breakdown);
}

// Bpp's lazily factored L0 (skyline_solver.cpp) after a breakdown in column 1 of duplicated rows:
// the columns before the failure stay usable, and every later step that needs the failing column
// breaks down again instead of refactoring columns that now hold factor values, not A's.
TEST(PivotingStrategyBpp, LazyL0StaysBrokenFromItsFailingColumnOn) {
    // duplicated_rows scaled by 4: refactoring column 0 from its own factor values then gives
    // other values (at a diagonal of 1 it would give the same)
    auto owned = problems::duplicated_rows();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) owned.a(i, j) *= 4;
    const linalg::SymmetricRows A(owned.view(), {});
    StrategyBuffers buffers;
    auto solver = make_free_solver(Method::Bpp, A, buffers);
    ASSERT_TRUE(solver->prepare(0));
    const std::vector<char> none(3, 0), second_out = {0, 1, 0};
    std::vector<double> x = {1, 1, 1};
    EXPECT_EQ(solver->solve_free(none, x, false), FactorOutcome::Breakdown);
    x = {1, 1, 1};
    EXPECT_EQ(solver->solve_free(none, x, false), FactorOutcome::Breakdown);
    // rows {0, 2}: a refactoring from column 1 needs only L0's column 0
    const Eigen::Matrix3d M = dense(A);
    x = {1, 0, 0.3};
    ASSERT_EQ(solver->solve_free(second_out, x, true), FactorOutcome::Refactored);
    const Eigen::Vector2d expected =
        (Eigen::Matrix2d() << M(0, 0), M(0, 2), M(2, 0), M(2, 2)).finished().llt().solve(Eigen::Vector2d(1, 0.3));
    EXPECT_NEAR(x[0], expected[0], 1e-12);
    EXPECT_EQ(x[1], 0.0);
    EXPECT_NEAR(x[2], expected[1], 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllStrategies, PivotingStrategy, ::testing::ValuesIn(kBppMethods),
                         [](const auto& info) {
                             std::string s = to_string(info.param);
                             s.erase(std::remove(s.begin(), s.end(), '-'), s.end());
                             return s;
                         });

TEST(PivotingCostModel, DeletesFewLateRowsAndRefactorsManyEarlyOnes) {
    const Permuted pp = permuted_for(Method::Bpp, problems::chain_mlcp(40, 20));
    StrategyBuffers buffers;  // outlives the strategy
    auto solver = make_free_solver(Method::Bpp, pp.Ap, buffers);
    ASSERT_TRUE(solver->prepare(0));
    const int n = pp.Ap.n();
    std::vector<double> x(n, 1.0);
    std::vector<char> late(n, 0);  // one late row, not the last (a tight tail is not deleted at all)
    late[n - 2] = 1;
    EXPECT_EQ(solver->solve_free(late, x, false), FactorOutcome::Deleted);
    std::vector<char> many(n, 0);
    for (int i = 0; i < n; i += 2) many[i] = 1;
    EXPECT_EQ(solver->solve_free(many, x, false), FactorOutcome::Refactored);
}

/// Where T is every row from k0 on, L_FF is L0's leading block: Bpp factors L0 through k0 alone
/// and solves with that block (skyline_solve_leading), so the tight rows' own columns are never
/// factored. An A whose last diagonal makes it indefinite shows it: deleting the last row from
/// L0 would need L0's last column and break down, the leading block does not.
TEST(PivotingCostModel, ATightTailIsSolvedWithL0sLeadingBlock) {
    auto owned = problems::chain_mlcp(8, 4);
    const int n = owned.n;
    owned.a(n - 1, n - 1) = -1.0;
    const linalg::SymmetricRows A(owned.view(), {});
    const Eigen::MatrixXd M = dense(A);
    std::vector<double> rhs(n);
    for (int i = 0; i < n; ++i) rhs[i] = std::cos(0.3 * i);
    for (int k0 : {n - 1, n / 2}) {
        StrategyBuffers buffers;
        auto solver = make_free_solver(Method::Bpp, A, buffers);
        ASSERT_TRUE(solver->prepare(0));
        std::vector<char> tail(n, 0);
        for (int i = k0; i < n; ++i) tail[i] = 1;
        std::vector<double> x = rhs;
        ASSERT_EQ(solver->solve_free(tail, x, false), FactorOutcome::Refactored) << k0;
        const Eigen::VectorXd expected = M.topLeftCorner(k0, k0).llt().solve(Eigen::Map<const Eigen::VectorXd>(rhs.data(), k0));
        for (int i = 0; i < n; ++i) EXPECT_NEAR(x[i], i < k0 ? expected[i] : 0.0, 1e-9 * (1 + std::abs(expected[0]))) << i;
        // the same block answers another right-hand side
        std::vector<double> again(n, 1.0);
        solver->solve_again(again);
        const Eigen::VectorXd ones = M.topLeftCorner(k0, k0).llt().solve(Eigen::VectorXd::Ones(k0));
        for (int i = 0; i < n; ++i) EXPECT_NEAR(again[i], i < k0 ? ones[i] : 0.0, 1e-9 * (1 + ones.cwiseAbs().maxCoeff())) << i;
        // a step that needs all of L0 still meets the indefinite last column
        std::vector<char> none(n, 0);
        x = rhs;
        EXPECT_EQ(solver->solve_free(none, x, false), FactorOutcome::Breakdown) << k0;
    }
}

TEST(PivotingCostModel, PaperVariantsAlwaysDelete) {
    for (Method m : {Method::BppDown, Method::BppSky}) {
        const Permuted pp = permuted_for(m, problems::chain_mlcp(15, 6));
        StrategyBuffers buffers;  // outlives the strategy
        auto solver = make_free_solver(m, pp.Ap, buffers);
        ASSERT_TRUE(solver->prepare(0));
        std::vector<char> many(pp.Ap.n(), 0);
        for (int i = 0; i < pp.Ap.n(); i += 2) many[i] = 1;
        std::vector<double> x(pp.Ap.n(), 1.0);
        EXPECT_EQ(solver->solve_free(many, x, false), FactorOutcome::Deleted) << to_string(m);
    }
}

}  // namespace
}  // namespace ode_bpp::pivoting
