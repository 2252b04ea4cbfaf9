// residuals.h against a direct dense computation with the full matrix (both triangles).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "ode_bpp/residuals.h"
#include "problems/generators.h"
#include "problems/named.h"
#include "problems/oracle.h"

namespace ode_bpp {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::MatrixXd full_matrix(const problems::OwnedProblem& p) {
    Eigen::MatrixXd A(p.n, p.n);
    for (int i = 0; i < p.n; ++i)
        for (int j = 0; j < p.n; ++j) A(i, j) = p.a(i, j);
    return A;
}

/// The natural residual written out from its definition, with the bounds given explicitly.
double reference_natural(const problems::OwnedProblem& p, const Eigen::VectorXd& x, const std::vector<double>& lo,
                         const std::vector<double>& hi) {
    const Eigen::VectorXd w = full_matrix(p) * x - Eigen::Map<const Eigen::VectorXd>(p.b.data(), p.n);
    double r = 0;
    for (int i = 0; i < p.n; ++i) r = std::max(r, std::abs(x[i] - std::clamp(x[i] - w[i], lo[i], hi[i])));
    return r;
}

TEST(Residuals, MatchTheDefinitionOnBoxedRows) {
    auto p = problems::random_boxed_mlcp(12, 2, 0, 1e4, 3);
    p.findex.clear();
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(p.n, -0.7, 0.9);
    std::vector<double> lo = p.lo, hi = p.hi;
    for (int i = 0; i < p.nub; ++i) lo[i] = -kInf, hi[i] = kInf;
    const Residuals r = compute_residuals(p, ConstStrided{x.data(), 1});
    EXPECT_DOUBLE_EQ(r.natural, reference_natural(p, x, lo, hi));
    EXPECT_DOUBLE_EQ(r.relative_natural,
                     r.natural / std::max(1.0, Eigen::Map<const Eigen::VectorXd>(p.b.data(), p.n).cwiseAbs().maxCoeff()));
    EXPECT_GT(r.natural, 0);
    EXPECT_EQ(r.friction, 0);
}

TEST(Residuals, LeadingNubRowsAreUnboundedWhateverTheirBoundsSay) {
    auto p = problems::random_boxed_mlcp(6, 3, 0, 10, 5);
    p.findex.clear();
    for (int i = 0; i < 3; ++i) p.lo[i] = p.hi[i] = 0;  // ignored: i < nub
    const Eigen::VectorXd x = Eigen::VectorXd::Constant(p.n, 0.3);
    std::vector<double> lo = p.lo, hi = p.hi;
    for (int i = 0; i < 3; ++i) lo[i] = -kInf, hi[i] = kInf;
    EXPECT_DOUBLE_EQ(compute_residuals(p, ConstStrided{x.data(), 1}).natural, reference_natural(p, x, lo, hi));
}

TEST(Residuals, VanishAtTheEnumeratedSolution) {
    const auto p = problems::random_boxed_mlcp(8, 1, 0, 1e3, 11);
    const auto x = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
    ASSERT_TRUE(x.has_value());
    const Residuals r = compute_residuals(p, ConstStrided{x->data(), 1});
    EXPECT_LT(r.scaled_natural, 1e-12);
    EXPECT_LT(r.free, 1e-12);
}

TEST(Residuals, FrictionBoundsComeFromTheReturnedNormals) {
    const auto p = problems::dantzig_friction_3x3();  // row 1: friction of row 0, mu = 0.5
    const std::vector<double> x = {0.4, 0.3, -0.1};   // |x1| = 0.3 > 0.5 * 0.4
    const Residuals r = compute_residuals(p, ConstStrided{x.data(), 1});
    EXPECT_NEAR(r.friction, 0.3 - 0.2, 1e-15);
    const Eigen::VectorXd xv = Eigen::Map<const Eigen::VectorXd>(x.data(), 3);
    EXPECT_DOUBLE_EQ(r.natural, reference_natural(p, xv, {0, -0.2, -kInf}, {kInf, 0.2, kInf}));
}

TEST(Residuals, StridedXGivesTheSameNumbers) {
    const auto p = problems::chain_mlcp(4, 3);
    std::vector<double> x(p.n), pairs(2 * p.n);
    for (int i = 0; i < p.n; ++i) {
        x[i] = std::sin(1.0 + i);
        pairs[2 * i + 1] = x[i];
        pairs[2 * i] = 1e300;  // ODE's interleaved b: must not be read as x
    }
    const Residuals a = compute_residuals(p, ConstStrided{x.data(), 1});
    const Residuals b = compute_residuals(p, ConstStrided{pairs.data() + 1, 2});
    EXPECT_EQ(a.natural, b.natural);
    EXPECT_EQ(a.scaled_natural, b.scaled_natural);
    EXPECT_EQ(a.friction, b.friction);
}

// mu = +inf is ODE's "never slips": the friction row is unbounded at any normal impulse, zero
// included (docs/modelling.md), never bounded by a NaN from inf * 0.
TEST(Residuals, InfiniteMuMakesTheFrictionRowUnbounded) {
    auto p = problems::dantzig_friction_3x3();
    p.hi[1] = kInf;
    EXPECT_TRUE(is_unbounded_friction_row(p, 1));
    EXPECT_FALSE(is_unbounded_friction_row(p, 0));
    EXPECT_FALSE(is_unbounded_friction_row(problems::dantzig_friction_3x3(), 1));
    for (const double normal : {0.0, 0.4}) {
        const std::vector<double> x = {normal, 0.1, 0.0};
        const auto bounds = effective_bounds(p, ConstStrided{x.data(), 1}, 1);
        EXPECT_EQ(bounds.first, -kInf);
        EXPECT_EQ(bounds.second, kInf);
        const Residuals r = compute_residuals(p, ConstStrided{x.data(), 1});
        EXPECT_TRUE(std::isfinite(r.natural));
        EXPECT_EQ(r.friction, 0.0);
    }
}

// The fixed-bound residual bounds each friction row by its own magnitude: a row at a bound with
// a multiplier of the right sign passes, one of the wrong sign does not; other rows as natural.
TEST(Residuals, FixedBoundResidualTakesEachFrictionBoundFromTheAnswer) {
    const auto p = problems::dantzig_friction_3x3();  // rows: normal, its friction (mu 0.5), free
    const Eigen::MatrixXd A = full_matrix(p);
    const Eigen::Vector3d b(p.b[0], p.b[1], p.b[2]);
    /// x with x1 given and rows 0 and 2 exact (w0 = w2 = 0)
    auto answer_with = [&](double x1) {
        Eigen::Matrix2d M;
        M << A(0, 0), A(0, 2), A(2, 0), A(2, 2);
        const Eigen::Vector2d rest = M.inverse() * Eigen::Vector2d(b[0] - A(0, 1) * x1, b[2] - A(2, 1) * x1);
        return Eigen::Vector3d(rest[0], x1, rest[1]);
    };
    // w1 < 0 for both: right at the upper bound +0.3, wrong at the lower bound -0.3
    const Eigen::Vector3d at_hi = answer_with(0.3), at_lo = answer_with(-0.3);
    ASSERT_GT(at_hi[0], 0);
    ASSERT_LT((A * at_hi - b)[1], 0);
    ASSERT_LT((A * at_lo - b)[1], -0.6);
    EXPECT_LT(compute_residuals(p, ConstStrided{at_hi.data(), 1}).fixed_bound, 1e-15);
    // |x1 - clamp(x1 - w1, -0.3, 0.3)| = 0.6, over max(1, |b|) = 1
    EXPECT_NEAR(compute_residuals(p, ConstStrided{at_lo.data(), 1}).fixed_bound, 0.6, 1e-15);
    // the natural residual judges the same answers by mu x0 instead
    EXPECT_GT(compute_residuals(p, ConstStrided{at_hi.data(), 1}).relative_natural, 0.05);
}

TEST(Residuals, FreeResidualUsesTheGivenIndexSet) {
    const auto p = problems::random_boxed_mlcp(7, 7, 0, 100, 2);  // all unbounded
    std::vector<double> x(p.n, 0.25);
    const Eigen::VectorXd w = full_matrix(p) * Eigen::Map<Eigen::VectorXd>(x.data(), p.n) -
                              Eigen::Map<const Eigen::VectorXd>(p.b.data(), p.n);
    std::vector<RowState> states(p.n, RowState::AtLo);
    states[4] = RowState::Free;
    EXPECT_DOUBLE_EQ(compute_residuals(p, ConstStrided{x.data(), 1}, &states).free, std::abs(w[4]));
    EXPECT_DOUBLE_EQ(compute_residuals(p, ConstStrided{x.data(), 1}).free, w.cwiseAbs().maxCoeff());
}

TEST(Residuals, ScaledResidualIsInvariantUnderRowScaling) {
    // D A D, D b, bounds / D: the same problem in other units must get the same scaled number
    auto p = problems::random_boxed_mlcp(8, 0, 0, 1e3, 4);
    p.findex.clear();
    std::vector<double> x(p.n);
    for (int i = 0; i < p.n; ++i) x[i] = 0.3 * std::cos(i);
    const double before = compute_residuals(p, ConstStrided{x.data(), 1}).scaled_natural;
    for (int i = 0; i < p.n; ++i) {
        const double d = std::pow(10.0, i % 4);
        for (int j = 0; j < p.n; ++j) {
            p.a(i, j) *= d;
            p.a(j, i) *= d;
        }
        p.b[i] *= d;
        p.lo[i] /= d;
        p.hi[i] /= d;
        x[i] /= d;
    }
    EXPECT_NEAR(compute_residuals(p, ConstStrided{x.data(), 1}).scaled_natural, before, 1e-12 * before);
}

/// A friction row's bound mu |x_n| is known only to its normal's scale: a friction impulse of
/// rounding size beside a separating contact (x_n = 0) must not read as a large scaled residual.
TEST(Residuals, FrictionRowsAreScaledByTheirNormals) {
    auto p = problems::OwnedProblem::zeros("friction_beside_resting_normal", 3);
    p.a(0, 0) = 2;
    p.a(1, 0) = p.a(0, 1) = 0.5;
    p.a(1, 1) = 1;
    p.a(2, 2) = 1;
    p.nub = 1;
    p.lo[1] = 0;                   // normal
    p.findex = {-1, -1, 1};        // row 2: friction on row 1
    p.hi[2] = 0.5;
    p.lo[2] = -0.5;
    p.b = {2, 0.25, 1e-14};        // x = (1, 0, 1e-14): rows 0, 1 exact, row 2 off its bound 0 by 1e-14
    const std::vector<double> x = {1, 0, 1e-14};
    const Residuals r = compute_residuals(p, ConstStrided{x.data(), 1});
    EXPECT_DOUBLE_EQ(r.natural, 1e-14);
    EXPECT_DOUBLE_EQ(r.friction, 1e-14);
    // the row's own scale is 2e-14 (0.5 by it); its normal's, times mu, is 0.375
    EXPECT_LT(r.scaled_natural, 1e-13);
    EXPECT_GT(r.scaled_natural, 1e-14);
}

}  // namespace
}  // namespace ode_bpp
