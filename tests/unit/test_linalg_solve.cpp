// skyline_solve against Eigen, with and without removed rows.
#include <gtest/gtest.h>

#include "linalg/envelope.h"
#include "linalg/row_delete.h"
#include "linalg/skyline_cholesky.h"
#include "linalg/skyline_solve.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

using linalg::SkylineMatrix;
using linalg::SkylineShape;

/// Forward error bound of a backward-stable solve: |dx| <~ n eps cond(A) |x|, safety 10.
double solve_tolerance(const MatrixXd& A, const VectorXd& x) {
    return 10.0 * A.rows() * std::numeric_limits<double>::epsilon() * condition_number(A) * x.cwiseAbs().maxCoeff();
}

TEST(LinalgSolve, MatchesEigenOnTheFullMatrix) {
    std::mt19937 rng(41);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 100);
        const MatrixXd A = random_envelope_spd(n, 1 + static_cast<int>(rng() % 12), rng, 0.3, trial % 2 ? 1.0 : 0.0);
        const std::vector<double> rows = lower_row_major_poisoned(A, n);
        SkylineMatrix L = trial % 3 == 0 ? from_dense(A, SkylineShape::dense(n))
                                         : linalg::load_skyline(rows.data(), n, n, nullptr);
        ASSERT_EQ(linalg::skyline_cholesky(L, 0, {}), -1);
        const VectorXd b = VectorXd::Random(n);
        const VectorXd expected = A.llt().solve(b);
        VectorXd x = b;
        linalg::skyline_solve(L, x.data());
        EXPECT_LE((x - expected).cwiseAbs().maxCoeff(), solve_tolerance(A, expected));
    }
}

TEST(LinalgSolve, RemovedRowsSolveAFFWithZeroedRhs) {
    std::mt19937 rng(42);
    std::vector<double> work;
    for (int trial = 0; trial < 30; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 100);
        const MatrixXd A = random_envelope_spd(n, 1 + static_cast<int>(rng() % 12), rng, 0.3, trial % 2 ? 1.0 : 0.0);
        const std::vector<double> rows = lower_row_major_poisoned(A, n);
        const std::vector<char> removed = random_removed(n, 0.25, rng);
        const std::vector<int> kept = kept_indices(removed);
        if (kept.empty()) continue;

        // Both ways of getting the factor of A_FF: deleting rows, and refactoring with removed.
        SkylineMatrix deleted = linalg::load_skyline(rows.data(), n, n, nullptr);
        ASSERT_EQ(linalg::skyline_cholesky(deleted, 0, {}), -1);
        for (int i = 0; i < n; ++i)
            if (removed[i]) linalg::skyline_delete_row(deleted, i, work);
        SkylineMatrix refactored = linalg::load_skyline(rows.data(), n, n, nullptr);
        ASSERT_EQ(linalg::skyline_cholesky(refactored, 0, removed), -1);

        const VectorXd b = VectorXd::Random(n);
        const MatrixXd A_FF = restricted(A, kept);
        VectorXd b_F(kept.size());
        for (std::size_t a = 0; a < kept.size(); ++a) b_F(a) = b(kept[a]);
        const VectorXd expected = A_FF.llt().solve(b_F);
        const double tol = solve_tolerance(A_FF, expected);

        for (const SkylineMatrix* L : {&deleted, &refactored}) {
            VectorXd x = b;
            for (int i = 0; i < n; ++i)
                if (removed[i]) x(i) = 0.0;
            linalg::skyline_solve(*L, x.data());
            for (int i = 0; i < n; ++i)
                if (removed[i]) {
                    EXPECT_EQ(x(i), 0.0);
                }
            for (std::size_t a = 0; a < kept.size(); ++a) EXPECT_NEAR(x(kept[a]), expected(a), tol);
        }
    }
}

}  // namespace
}  // namespace ode_bpp::test
