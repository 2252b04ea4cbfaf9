// Tests of bench/report/factor_precision.h: the precision floor that Table 4's factor error is
// read against.
#include "factor_precision.h"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace ode_bpp::bench {
namespace {

/// A file of n rows whose A is the tridiagonal (−1, d, −1): SPD for d > 2, as ill-conditioned as
/// d is close to 2 (cond ~ 4 / (d − 2) for large n).
MlcpFile tridiagonal(int n, double d) {
    MlcpFile file;
    file.n = n;
    file.A.assign(static_cast<std::size_t>(n) * n, 0.0);
    for (int i = 0; i < n; ++i) {
        file.A[static_cast<std::size_t>(i) * n + i] = d;
        if (i > 0) file.A[static_cast<std::size_t>(i) * n + i - 1] = file.A[static_cast<std::size_t>(i - 1) * n + i] = -1.0;
    }
    file.b.assign(static_cast<std::size_t>(n), 1.0);
    file.lo.assign(static_cast<std::size_t>(n), 0.0);
    file.hi.assign(static_cast<std::size_t>(n), 1e300);
    return file;
}

/// A file of n rows whose A = Q diag(lambda) Qᵀ, Q a seeded random orthogonal matrix and lambda
/// spread geometrically from 1 down to smallest: cond(A) = 1 / smallest.
MlcpFile spectrum(int n, double smallest, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal;
    Eigen::MatrixXd G(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j) G(i, j) = normal(rng);
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(G).householderQ();
    Eigen::VectorXd lambda(n);
    for (Eigen::Index k = 0; k < n; ++k) lambda(k) = std::pow(smallest, static_cast<double>(k) / (n - 1));
    const Eigen::MatrixXd A = Q * lambda.asDiagonal() * Q.transpose();
    MlcpFile file = tridiagonal(n, 4.0);
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j)
            file.A[static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j)] = 0.5 * (A(i, j) + A(j, i));
    return file;
}

std::vector<int> identity(int n) {
    std::vector<int> perm(static_cast<std::size_t>(n));
    std::iota(perm.begin(), perm.end(), 0);
    return perm;
}

TEST(BenchFactorPrecision, NoTightRowMeansNoDeletionAndNoFloor) {
    const MlcpFile file = tridiagonal(8, 4.0);
    const FactorPrecision p = factor_precision(file, identity(8), std::vector<RowState>(8, RowState::Free));
    EXPECT_EQ(p.fresh, 0.0);
    EXPECT_EQ(p.deleted, 0.0);
}

TEST(BenchFactorPrecision, BothFactorsSitAtRoundingLevelOnAWellConditionedMatrix) {
    const int n = 40;
    const MlcpFile file = tridiagonal(n, 4.0);
    std::vector<RowState> states(n, RowState::Free);
    for (int i : {3, 17, 18, 39}) states[static_cast<std::size_t>(i)] = RowState::AtLo;
    const FactorPrecision p = factor_precision(file, identity(n), states);
    ASSERT_TRUE(std::isfinite(p.fresh) && std::isfinite(p.deleted));
    EXPECT_LT(p.fresh, 1e-14);
    EXPECT_LT(p.deleted, 1e-14);
}

TEST(BenchFactorPrecision, TheFloorGrowsWithTheConditioning) {
    const int n = 60;
    std::vector<RowState> states(n, RowState::Free);
    for (int i : {5, 30, 31, 44}) states[static_cast<std::size_t>(i)] = RowState::AtHi;
    const FactorPrecision well = factor_precision(spectrum(n, 1e-1, 7), identity(n), states);
    const FactorPrecision ill = factor_precision(spectrum(n, 1e-11, 7), identity(n), states);
    ASSERT_TRUE(std::isfinite(well.fresh) && std::isfinite(ill.fresh) && std::isfinite(ill.deleted));
    EXPECT_GT(ill.fresh, 100 * well.fresh);
    EXPECT_GT(ill.deleted, 100 * well.deleted);
    // the downdate loses nothing against refactoring (docs/benchmarks.md, "Table 4 at the
    // precision floor"): within a small factor of the fresh factor's own error
    EXPECT_LT(ill.deleted, 20 * ill.fresh);
}

TEST(BenchFactorPrecision, SizesThatDisagreeGiveNaN) {
    const MlcpFile file = tridiagonal(5, 4.0);
    const FactorPrecision p = factor_precision(file, identity(4), std::vector<RowState>(5, RowState::AtLo));
    EXPECT_TRUE(std::isnan(p.fresh));
    EXPECT_TRUE(std::isnan(p.deleted));
}

TEST(BenchFactorPrecision, AMatrixThatIsNotPositiveDefiniteGivesNaN) {
    const MlcpFile file = tridiagonal(6, 1.0);  // eigenvalues 1 - 2 cos(k pi / 7) < 0 for small k
    std::vector<RowState> states(6, RowState::Free);
    states[2] = RowState::AtLo;
    const FactorPrecision p = factor_precision(file, identity(6), states);
    EXPECT_TRUE(std::isnan(p.fresh));
    EXPECT_TRUE(std::isnan(p.deleted));
}

}  // namespace
}  // namespace ode_bpp::bench
