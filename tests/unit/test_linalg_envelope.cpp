// Row profile, skyline shape and loading of a permuted matrix, against brute-force definitions.
#include <gtest/gtest.h>

#include "linalg/envelope.h"
#include "linalg/skyline.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

using linalg::SkylineShape;

std::vector<int> brute_force_profile(const MatrixXd& Ap) {
    const int n = static_cast<int>(Ap.rows());
    std::vector<int> first(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        first[i] = i;
        for (int j = i; j >= 0; --j)
            if (Ap(i, j) != 0.0) first[i] = j;
    }
    return first;
}

TEST(LinalgEnvelope, RowProfileMatchesDefinitionUnderPermutation) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 60);
        const MatrixXd A = random_envelope_spd(n, 1 + static_cast<int>(rng() % 8), rng);
        const int lda = n + 3;
        const std::vector<double> rows = lower_row_major_poisoned(A, lda);
        const std::vector<int> perm = random_permutation(n, rng);
        EXPECT_EQ(linalg::row_profile(rows.data(), lda, n, perm.data()), brute_force_profile(permuted(A, perm)));
        EXPECT_EQ(linalg::row_profile(rows.data(), lda, n, nullptr), brute_force_profile(A));
    }
}

TEST(LinalgEnvelope, ShapeIsTheColumnSkylineOfTheProfile) {
    std::mt19937 rng(12);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 50);
        std::vector<int> first(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) first[i] = static_cast<int>(rng() % (i + 1));
        const SkylineShape shape = SkylineShape::from_row_profile(first);
        ASSERT_TRUE(shape.valid());
        for (int k = 0; k < n; ++k) {
            int expected = k;
            for (int i = 0; i < n; ++i)
                if (first[i] <= k) expected = std::max(expected, i);
            EXPECT_EQ(shape.sky[k], expected) << "column " << k;
        }
        EXPECT_EQ(SkylineShape::size_of_row_profile(first), shape.size());
        SkylineShape searched = shape;  // a shape without the index searches sky
        searched.first_column.clear();
        const SkylineShape dense = SkylineShape::dense(n);
        for (int r = 0; r < n; ++r) {
            const int j = shape.first_column_holding(r);
            EXPECT_EQ(searched.first_column_holding(r), j) << "row " << r;
            EXPECT_EQ(dense.first_column_holding(r), 0) << "row " << r;
            EXPECT_GE(shape.sky[j], r);
            if (j > 0) {
                EXPECT_LT(shape.sky[j - 1], r);
            }
            EXPECT_LE(j, first[r]) << "row " << r << " must be stored from its first non-zero on";
        }
    }
}

TEST(LinalgEnvelope, LoadSkylineHoldsEveryEntryOfTheEnvelope) {
    std::mt19937 rng(13);
    for (int trial = 0; trial < 10; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 40);
        const MatrixXd A = random_envelope_spd(n, 5, rng);
        const int lda = n;
        const std::vector<double> rows = lower_row_major_poisoned(A, lda);
        const std::vector<int> perm = random_permutation(n, rng);
        const MatrixXd Ap = permuted(A, perm);
        const linalg::SkylineMatrix L = linalg::load_skyline(rows.data(), lda, n, perm.data());
        for (int k = 0; k < n; ++k)
            for (int r = k; r < n; ++r) EXPECT_EQ(L.get(r, k), Ap(r, k)) << r << "," << k;
    }
}

TEST(LinalgEnvelope, EnvelopeSizeCountsStrictlyLowerEntries) {
    EXPECT_EQ(linalg::envelope_size({0, 0, 1, 3}), 0 + 1 + 1 + 0);
    const SkylineShape dense = SkylineShape::dense(5);
    EXPECT_TRUE(dense.valid());
    EXPECT_EQ(dense.size(), 15);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(dense.sky[k], 4);
}

}  // namespace
}  // namespace ode_bpp::test
