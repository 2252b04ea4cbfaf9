// dense_cholesky and dense_cholesky_solve against Eigen's LLT: the factor, the solve, the upper
// triangle left alone, and the breakdown column of a singular matrix.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "linalg/dense_cholesky.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

TEST(LinalgDenseCholesky, MatchesEigenAndSolves) {
    std::mt19937 rng(5);
    for (int trial = 0; trial < 40; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 40);
        const MatrixXd A = random_envelope_spd(n, n, rng, 0.5, trial % 2 == 0 ? 1.0 : 0.0);
        const int lda = n + 2;
        std::vector<double> a = lower_row_major_poisoned(A, lda);
        std::vector<double> diagonal(static_cast<std::size_t>(n)), inverse_diagonal(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) diagonal[i] = A(i, i);
        ASSERT_EQ(linalg::dense_cholesky(a.data(), n, lda, diagonal.data(), inverse_diagonal.data()), -1);
        const MatrixXd L = oracle_factor(A);
        const double tol = factor_tolerance(A, L.cwiseAbs().maxCoeff());
        for (int i = 0; i < n; ++i) {
            EXPECT_NEAR(inverse_diagonal[i] * L(i, i), 1.0, 1e-14) << i;
            for (int j = 0; j <= i; ++j) EXPECT_NEAR(a[i * lda + j], L(i, j), tol) << "(" << i << "," << j << ")";
            for (int j = i + 1; j < lda; ++j)  // the poisoned upper triangle: neither read nor written
                EXPECT_TRUE(std::isnan(a[i * lda + j])) << "(" << i << "," << j << ")";
        }
        Eigen::VectorXd b = Eigen::VectorXd::Random(n);
        std::vector<double> x(b.data(), b.data() + n);
        linalg::dense_cholesky_solve(a.data(), inverse_diagonal.data(), n, lda, x.data());
        const Eigen::VectorXd expected = A.llt().solve(b);
        for (int i = 0; i < n; ++i)
            EXPECT_NEAR(x[i], expected[i], 1e-9 * condition_number(A) * (1 + expected.cwiseAbs().maxCoeff()));
    }
}

TEST(LinalgDenseCholesky, ReportsTheFirstDependentColumn) {
    // rows 0 and 2 equal: column 2 is dependent on columns 0 and 1 to rounding
    const int n = 4;
    MatrixXd A(n, n);
    A << 4, 1, 4, 0,  //
        1, 3, 1, 0,   //
        4, 1, 4, 0,   //
        0, 0, 0, 2;
    std::vector<double> a = lower_row_major_poisoned(A, n);
    const double diagonal[n] = {4, 3, 4, 2};
    double inverse_diagonal[n];
    EXPECT_EQ(linalg::dense_cholesky(a.data(), n, n, diagonal, inverse_diagonal), 2);
    // a NaN pivot breaks down too (no NaN enters the factor silently)
    MatrixXd B = A;
    B(2, 2) = 5;
    B(3, 3) = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> b = lower_row_major_poisoned(B, n);
    const double nan_diagonal[n] = {4, 3, 5, B(3, 3)};
    EXPECT_EQ(linalg::dense_cholesky(b.data(), n, n, nan_diagonal, inverse_diagonal), 3);
}

}  // namespace
}  // namespace ode_bpp::test
