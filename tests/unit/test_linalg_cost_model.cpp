// CostModel against brute-force counts over the stored entries, and factor_error against Eigen.
#include <gtest/gtest.h>

#include "linalg/cost_model.h"
#include "linalg/factor_error.h"
#include "linalg/skyline.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

using linalg::SkylineShape;

SkylineShape random_shape(int n, std::mt19937& rng) {
    std::vector<int> first(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) first[i] = std::max(0, i - static_cast<int>(rng() % 9));
    return SkylineShape::from_row_profile(first);
}

bool stored(const SkylineShape& s, int r, int k) { return k <= r && r <= s.sky[k]; }

/// Counts, entry by entry, what the left-looking factorization does from column k0 on, with the
/// indices in `removed` skipped as columns and as the earlier columns j: one multiply-add for each
/// stored L(r,k) (k >= k0) and each earlier column j holding both L(k,j) and L(r,j), plus one per
/// stored entry of column k for the pivot and scaling.
double counted_refactor_removing(const SkylineShape& s, int k0, const std::vector<char>& removed) {
    double count = 0;
    for (int k = k0; k < s.n; ++k) {
        if (removed[k]) continue;
        for (int r = k; r < s.n; ++r) {
            if (!stored(s, r, k)) continue;
            count += 1;
            for (int j = 0; j < k; ++j)
                if (!removed[j] && stored(s, k, j) && stored(s, r, j)) count += 1;
        }
    }
    return count;
}

double counted_refactor(const SkylineShape& s, int k0) {
    return counted_refactor_removing(s, k0, std::vector<char>(static_cast<std::size_t>(s.n), 0));
}

/// Entries of the trailing columns k > i inside the storage (each one rotated against sigma).
double counted_delete(const SkylineShape& s, int i) {
    double count = 0;
    for (int k = i + 1; k < s.n; ++k)
        for (int r = k; r < s.n; ++r) count += stored(s, r, k) ? 1 : 0;
    return count;
}

TEST(LinalgCostModel, MatchesEntryByEntryCounts) {
    std::mt19937 rng(51);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 40);
        const SkylineShape shape = trial % 5 == 0 ? SkylineShape::dense(n) : random_shape(n, rng);
        const linalg::CostModel model(shape);
        EXPECT_EQ(linalg::full_refactor_cost(shape), counted_refactor(shape, 0));
        for (int k = 0; k < n; ++k) {
            EXPECT_EQ(model.refactor_cost(k), counted_refactor(shape, k)) << "k0 " << k;
            EXPECT_EQ(model.delete_cost(k), counted_delete(shape, k)) << "i " << k;
            double entries = 0;
            for (int c = k; c < n; ++c) entries += shape.height(c);
            EXPECT_EQ(model.copy_cost(k), entries);
        }
    }
}

TEST(LinalgCostModel, RefactorWithRemovedRowsMatchesEntryByEntryCounts) {
    std::mt19937 rng(53);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 40);
        const SkylineShape shape = trial % 5 == 0 ? SkylineShape::dense(n) : random_shape(n, rng);
        const linalg::CostModel model(shape);
        std::vector<char> removed(static_cast<std::size_t>(n), 0);
        std::vector<int> removed_rows;
        for (int i = 0; i < n; ++i)
            if (rng() % 3 == 0) {
                removed[i] = 1;
                removed_rows.push_back(i);
            }
        for (int k = 0; k < n; ++k) {
            EXPECT_EQ(model.refactor_cost(k, removed_rows), counted_refactor_removing(shape, k, removed)) << "k0 " << k;
            EXPECT_EQ(model.refactor_cost(k, {}), model.refactor_cost(k)) << "k0 " << k;
        }
        if (!removed_rows.empty()) {
            EXPECT_LT(model.refactor_cost(0, removed_rows), model.refactor_cost(0));
        }
    }
}

TEST(LinalgCostModel, DenseCountsFollowTheClosedForms) {
    const int n = 30;
    const linalg::CostModel model(SkylineShape::dense(n));
    // sum_{k} sum_{r>=k} (k + 1) = sum_k (k+1)(n-k): the multiply-adds of an n x n Cholesky.
    double expected = 0;
    for (int k = 0; k < n; ++k) expected += static_cast<double>(k + 1) * (n - k);
    EXPECT_EQ(model.refactor_cost(0), expected);
    EXPECT_EQ(model.delete_cost(0), static_cast<double>(n - 1) * n / 2);
    EXPECT_EQ(model.delete_cost(n - 1), 0.0);
}

TEST(LinalgFactorError, IsTheFrobeniusNormOverKeptEntries) {
    std::mt19937 rng(52);
    const int n = 25;
    const MatrixXd A = random_envelope_spd(n, 5, rng);
    const std::vector<double> rows = lower_row_major_poisoned(A, n);
    MatrixXd Ma = MatrixXd::Random(n, n).triangularView<Eigen::Lower>();
    MatrixXd Mb = MatrixXd::Random(n, n).triangularView<Eigen::Lower>();
    const linalg::SkylineMatrix La = from_dense(Ma, SkylineShape::dense(n));
    const linalg::SkylineMatrix Lb = from_dense(Mb, SkylineShape::dense(n));
    const std::vector<char> removed = random_removed(n, 0.3, rng);
    MatrixXd diff = Ma - Mb;
    for (int i = 0; i < n; ++i)
        if (removed[i]) {
            diff.row(i).setZero();
            diff.col(i).setZero();
        }
    EXPECT_NEAR(linalg::factor_error(La, Lb, removed), diff.norm(), 1e-12 * diff.norm());
    EXPECT_NEAR(linalg::factor_error(La, Lb, {}), (Ma - Mb).norm(), 1e-12 * (Ma - Mb).norm());

    // Different shapes: entries outside one skyline count as zeros.
    const SkylineShape band = random_shape(n, rng);
    const linalg::SkylineMatrix Lc = from_dense(Ma, band);
    MatrixXd Mc = to_dense(Lc);
    EXPECT_NEAR(linalg::factor_error(Lc, Lb, {}), (Mc - Mb).norm(), 1e-12 * (Mc - Mb).norm());
}

}  // namespace
}  // namespace ode_bpp::test
