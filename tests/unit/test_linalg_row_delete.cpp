// Row/column deletion from a Cholesky factor against a fresh factor of A_FF.
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

/// Largest entry-wise error of the kept part of L against the oracle factor of A_FF, divided by
/// the perturbation-theory tolerance; removed rows/columns must be exactly the identity.
double scaled_error_against_fresh_factor(const SkylineMatrix& L, const MatrixXd& A, const std::vector<char>& removed) {
    const int n = L.n();
    const std::vector<int> kept = kept_indices(removed);
    std::vector<int> position(static_cast<std::size_t>(n), -1);
    for (int a = 0; a < static_cast<int>(kept.size()); ++a) position[kept[a]] = a;
    MatrixXd L_FF;
    double tol = 1.0;
    if (!kept.empty()) {
        const MatrixXd A_FF = restricted(A, kept);
        L_FF = oracle_factor(A_FF);
        tol = factor_tolerance(A_FF, L_FF.cwiseAbs().maxCoeff());
    }
    double worst = 0.0;
    for (int k = 0; k < n; ++k) {
        for (int r = k; r < n; ++r) {
            const double got = L.get(r, k);
            if (removed[k] || removed[r]) {
                if (got != (r == k ? 1.0 : 0.0)) return std::numeric_limits<double>::infinity();
            } else {
                if (!std::isfinite(got)) return std::numeric_limits<double>::infinity();
                worst = std::max(worst, std::abs(got - L_FF(position[r], position[k])) / tol);
            }
        }
    }
    return worst;
}

std::vector<int> indices_of(const std::vector<char>& flags) {
    std::vector<int> out;
    for (int k = 0; k < static_cast<int>(flags.size()); ++k)
        if (flags[k]) out.push_back(k);
    return out;
}

SkylineMatrix factor_of(const MatrixXd& A, const SkylineShape& shape) {
    SkylineMatrix L = from_dense(A, shape);
    EXPECT_EQ(linalg::skyline_cholesky(L, 0, {}), -1);
    return L;
}

SkylineShape envelope_shape(const MatrixXd& A) {
    const int n = static_cast<int>(A.rows());
    const std::vector<double> rows = lower_row_major_poisoned(A, n);
    return SkylineShape::from_row_profile(linalg::row_profile(rows.data(), n, n, nullptr));
}

TEST(LinalgRowDelete, AscendingDeletionsMatchAFreshFactorOfAFF) {
    std::mt19937 rng(31);
    std::vector<double> work;
    for (int trial = 0; trial < 40; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 120);
        const MatrixXd A = random_envelope_spd(n, 1 + static_cast<int>(rng() % 14), rng, 0.2, trial % 2 ? 1.5 : 0.0);
        const SkylineMatrix L0 = factor_of(A, envelope_shape(A));
        const std::vector<char> removed = random_removed(n, 0.02 + 0.1 * (trial % 4), rng);
        SkylineMatrix L = L0;
        for (int i : indices_of(removed)) linalg::skyline_delete_row(L, i, work);
        EXPECT_LE(scaled_error_against_fresh_factor(L, A, removed), 1.0) << "trial " << trial << " n " << n;
    }
}

TEST(LinalgRowDelete, OrderOfDeletionsDoesNotMatter) {
    std::mt19937 rng(32);
    std::vector<double> work;
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 80);
        const MatrixXd A = random_envelope_spd(n, 8, rng);
        const SkylineMatrix L0 = factor_of(A, envelope_shape(A));
        const std::vector<char> removed = random_removed(n, 0.2, rng);
        std::vector<int> order = indices_of(removed);
        std::shuffle(order.begin(), order.end(), rng);
        SkylineMatrix L = L0;
        for (int i : order) linalg::skyline_delete_row(L, i, work);
        if (!order.empty()) linalg::skyline_delete_row(L, order.front(), work);  // twice: a no-op
        EXPECT_LE(scaled_error_against_fresh_factor(L, A, removed), 1.0) << "trial " << trial;
    }
}

TEST(LinalgRowDelete, DenseShapeAgreesWithTheEnvelope) {
    std::mt19937 rng(33);
    std::vector<double> work;
    for (int trial = 0; trial < 15; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 100);
        const MatrixXd A = random_envelope_spd(n, 10, rng);
        const std::vector<char> removed = random_removed(n, 0.15, rng);
        SkylineMatrix envelope = factor_of(A, envelope_shape(A));
        SkylineMatrix dense = factor_of(A, SkylineShape::dense(n));
        for (int i : indices_of(removed)) {
            linalg::skyline_delete_row(envelope, i, work);
            linalg::skyline_delete_row(dense, i, work);
        }
        EXPECT_LE(scaled_error_against_fresh_factor(dense, A, removed), 1.0);
        const double scale = to_dense(dense).cwiseAbs().maxCoeff();
        EXPECT_LE((to_dense(envelope) - to_dense(dense)).cwiseAbs().maxCoeff(),
                  100 * n * std::numeric_limits<double>::epsilon() * scale);
    }
}

TEST(LinalgRowDelete, ReadsAndWritesNothingOutsideTheEnvelope) {
    // The factor lives in storage with NaN padding between columns: a read one row past
    // sky[k] (or above the diagonal) would turn the result into NaN, a write would clear a NaN.
    std::mt19937 rng(34);
    std::vector<double> work;
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 120);
        const MatrixXd A = random_envelope_spd(n, 1 + static_cast<int>(rng() % 10), rng);
        SkylineMatrix L = from_dense(A, padded(envelope_shape(A), n));
        poison_padding(L);
        ASSERT_EQ(linalg::skyline_cholesky(L, 0, {}), -1);
        const std::vector<char> removed = random_removed(n, 0.1, rng);
        for (int i : indices_of(removed)) linalg::skyline_delete_row(L, i, work);
        EXPECT_TRUE(padding_untouched(L));
        EXPECT_LE(scaled_error_against_fresh_factor(L, A, removed), 1.0) << "trial " << trial;

        VectorXd x = VectorXd::Random(n);
        for (int i = 0; i < n; ++i)
            if (removed[i]) x(i) = 0.0;
        linalg::skyline_solve(L, x.data());
        EXPECT_TRUE(x.allFinite());
    }
}

TEST(LinalgRowDelete, TailAndRowCopiesRestoreL0) {
    // Alg. 2 starts every pivot step from L0: copying the tail from the smallest deleted index
    // plus the deleted rows' earlier entries must undo every write of the previous deletions.
    std::mt19937 rng(35);
    std::vector<double> work;
    for (int trial = 0; trial < 10; ++trial) {
        const int n = 10 + static_cast<int>(rng() % 60);
        const MatrixXd A = random_envelope_spd(n, 6, rng);
        const SkylineMatrix L0 = factor_of(A, trial % 2 ? SkylineShape::dense(n) : envelope_shape(A));
        SkylineMatrix L = L0;
        const std::vector<int> deleted = indices_of(random_removed(n, 0.2, rng));
        if (deleted.empty()) continue;
        for (int i : deleted) linalg::skyline_delete_row(L, i, work);
        L.copy_tail_from(L0, deleted.front());
        L.copy_rows_from(L0, deleted, deleted.front());
        EXPECT_EQ(L.values(), L0.values());

        // The same after a refactorization with the deleted indices removed.
        SkylineMatrix A_lower = from_dense(A, L0.shape());
        L.copy_tail_from(A_lower, deleted.front());
        std::vector<char> removed(n, 0);
        for (int i : deleted) removed[i] = 1;
        ASSERT_EQ(linalg::skyline_cholesky(L, deleted.front(), removed), -1);
        L.copy_tail_from(L0, deleted.front());
        L.copy_rows_from(L0, deleted, deleted.front());
        EXPECT_EQ(L.values(), L0.values());
    }
}

}  // namespace
}  // namespace ode_bpp::test
