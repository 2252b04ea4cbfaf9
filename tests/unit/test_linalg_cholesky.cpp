// skyline_cholesky against Eigen's LLT, on envelope and dense shapes, from k0 = 0 and k0 > 0,
// with and without removed indices.
#include <gtest/gtest.h>

#include "linalg/envelope.h"
#include "linalg/skyline_cholesky.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

using linalg::SkylineMatrix;
using linalg::SkylineShape;

struct Case {
    MatrixXd A;                 ///< the (already permuted) matrix
    std::vector<double> rows;   ///< its lower triangle, row-major, poisoned upper part
    int lda = 0;
};

Case make_case(int n, int band, std::mt19937& rng, double spread = 0.0) {
    Case c;
    c.A = random_envelope_spd(n, band, rng, 0.5, spread);
    c.lda = n + 1;
    c.rows = lower_row_major_poisoned(c.A, c.lda);
    return c;
}

/// Checks L against the oracle factor of A restricted to the kept indices; removed indices
/// must be exact identity rows/columns.
void expect_factor_of_restriction(const SkylineMatrix& L, const MatrixXd& A, const std::vector<char>& removed) {
    const int n = L.n();
    std::vector<char> flags = removed.empty() ? std::vector<char>(static_cast<std::size_t>(n), 0) : removed;
    const std::vector<int> kept = kept_indices(flags);
    if (kept.empty()) return;
    const MatrixXd A_FF = restricted(A, kept);
    const MatrixXd L_FF = oracle_factor(A_FF);
    const double tol = factor_tolerance(A_FF, L_FF.cwiseAbs().maxCoeff());
    std::vector<int> position(static_cast<std::size_t>(n), -1);
    for (int a = 0; a < static_cast<int>(kept.size()); ++a) position[kept[a]] = a;
    for (int k = 0; k < n; ++k) {
        for (int r = k; r < n; ++r) {
            const double got = L.get(r, k);
            if (flags[k] || flags[r]) {
                EXPECT_EQ(got, r == k ? 1.0 : 0.0) << "removed row/column at (" << r << "," << k << ")";
            } else {
                EXPECT_NEAR(got, L_FF(position[r], position[k]), tol) << "(" << r << "," << k << ")";
            }
        }
    }
}

TEST(LinalgCholesky, MatchesEigenOnEnvelopeMatrices) {
    std::mt19937 rng(21);
    for (int trial = 0; trial < 30; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 90);
        const Case c = make_case(n, 1 + static_cast<int>(rng() % 12), rng, trial % 3 == 0 ? 1.0 : 0.0);
        SkylineMatrix L = linalg::load_skyline(c.rows.data(), c.lda, n, nullptr);
        ASSERT_EQ(linalg::skyline_cholesky(L, 0, {}), -1);
        expect_factor_of_restriction(L, c.A, {});
    }
}

TEST(LinalgCholesky, MatchesEigenUnderPermutationAndOnDenseShape) {
    std::mt19937 rng(22);
    for (int trial = 0; trial < 10; ++trial) {
        const int n = 1 + static_cast<int>(rng() % 70);
        const Case c = make_case(n, 4, rng);
        const std::vector<int> perm = random_permutation(n, rng);
        SkylineMatrix L = linalg::load_skyline(c.rows.data(), c.lda, n, perm.data());
        ASSERT_EQ(linalg::skyline_cholesky(L, 0, {}), -1);
        expect_factor_of_restriction(L, permuted(c.A, perm), {});

        SkylineMatrix D = from_dense(c.A, SkylineShape::dense(n));
        ASSERT_EQ(linalg::skyline_cholesky(D, 0, {}), -1);
        expect_factor_of_restriction(D, c.A, {});
    }
}

/// L with columns < k0 from the factor `head` and columns >= k0 from A's lower triangle.
SkylineMatrix mixed(const SkylineMatrix& head, const SkylineMatrix& A_lower, int k0) {
    SkylineMatrix L = A_lower;
    L.copy_head_from(head, k0);
    return L;
}

TEST(LinalgCholesky, ResumesFromColumnK0) {
    std::mt19937 rng(23);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 80);
        const Case c = make_case(n, 1 + static_cast<int>(rng() % 10), rng);
        const bool dense = trial % 4 == 0;
        const SkylineMatrix A_lower = dense ? from_dense(c.A, SkylineShape::dense(n))
                                            : linalg::load_skyline(c.rows.data(), c.lda, n, nullptr);
        SkylineMatrix L0 = A_lower;
        ASSERT_EQ(linalg::skyline_cholesky(L0, 0, {}), -1);
        const int k0 = static_cast<int>(rng() % n);
        SkylineMatrix L = mixed(L0, A_lower, k0);
        ASSERT_EQ(linalg::skyline_cholesky(L, k0, {}), -1);
        expect_factor_of_restriction(L, c.A, {});
    }
}

TEST(LinalgCholesky, RemovedIndicesGiveTheFactorOfAFF) {
    std::mt19937 rng(24);
    for (int trial = 0; trial < 30; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 90);
        const Case c = make_case(n, 1 + static_cast<int>(rng() % 10), rng, trial % 2 ? 1.0 : 0.0);
        const bool dense = trial % 5 == 0;
        const SkylineMatrix A_lower = dense ? from_dense(c.A, SkylineShape::dense(n))
                                            : linalg::load_skyline(c.rows.data(), c.lda, n, nullptr);
        const std::vector<char> removed = random_removed(n, 0.05 + 0.3 * (trial % 3), rng);

        SkylineMatrix from_scratch = A_lower;
        ASSERT_EQ(linalg::skyline_cholesky(from_scratch, 0, removed), -1);
        expect_factor_of_restriction(from_scratch, c.A, removed);

        // Alg. 2's partial refactorization: L0's columns before the first removed index are
        // already the factor of A_FF there.
        SkylineMatrix L0 = A_lower;
        ASSERT_EQ(linalg::skyline_cholesky(L0, 0, {}), -1);
        const int k0 = static_cast<int>(std::find(removed.begin(), removed.end(), 1) - removed.begin());
        SkylineMatrix partial = mixed(L0, A_lower, k0);
        ASSERT_EQ(linalg::skyline_cholesky(partial, k0, removed), -1);
        expect_factor_of_restriction(partial, c.A, removed);
    }
}

/// The partial form: columns [k0, k1) in pieces give the whole factorization bit for bit, and
/// leave the columns from k1 on holding A (what a lazily factored L0 relies on).
TEST(LinalgCholesky, FactorsAColumnRangeExactlyAsTheWholeCall) {
    std::mt19937 rng(27);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 80);
        const Case c = make_case(n, 1 + static_cast<int>(rng() % 10), rng, trial % 2 ? 1.0 : 0.0);
        const SkylineMatrix A_lower = trial % 4 == 0 ? from_dense(c.A, SkylineShape::dense(n))
                                                     : linalg::load_skyline(c.rows.data(), c.lda, n, nullptr);
        SkylineMatrix whole = A_lower;
        ASSERT_EQ(linalg::skyline_cholesky(whole, 0, {}), -1);

        SkylineMatrix pieces = A_lower;
        const int k1 = static_cast<int>(rng() % (n + 1));
        ASSERT_EQ(linalg::skyline_cholesky(pieces, 0, k1, {}), -1);
        for (int k = k1; k < n; ++k)
            for (int r = k; r <= A_lower.sky(k); ++r)
                ASSERT_EQ(pieces.at(r, k), A_lower.at(r, k)) << "column " << k << " >= k1 = " << k1 << " was written";
        const int k2 = k1 + static_cast<int>(rng() % (n - k1 + 1));
        ASSERT_EQ(linalg::skyline_cholesky(pieces, k1, k2, {}), -1);
        ASSERT_EQ(linalg::skyline_cholesky(pieces, k2, {}), -1);
        for (int k = 0; k < n; ++k)
            for (int r = k; r <= whole.sky(k); ++r) ASSERT_EQ(pieces.at(r, k), whole.at(r, k)) << "(" << r << "," << k << ")";
    }
}

/// Columns tall enough to be factored in pairs (skyline_cholesky.cpp's kPairHeight, 256 rows):
/// dense and wide envelopes, where neighbouring columns mostly share their earlier columns and
/// sometimes do not (rows whose profiles start apart), with and without removed indices. The
/// factor is the oracle's, and every partition into column ranges, which pairs the columns
/// differently, gives the whole call's bits.
TEST(LinalgCholesky, TallColumnsFactoredInPairsGiveTheSameBitsInEveryPartition) {
    std::mt19937 rng(29);
    for (int trial = 0; trial < 6; ++trial) {
        const int n = 300 + static_cast<int>(rng() % 120);
        const Case c = make_case(n, trial % 2 == 0 ? n : 40 + static_cast<int>(rng() % 200), rng, trial % 3 == 0 ? 1.0 : 0.0);
        const SkylineMatrix A_lower = trial % 2 == 0 ? from_dense(c.A, SkylineShape::dense(n))
                                                     : linalg::load_skyline(c.rows.data(), c.lda, n, nullptr);
        const std::vector<char> removed = trial >= 4 ? random_removed(n, 0.2, rng) : std::vector<char>{};
        SkylineMatrix whole = A_lower;
        ASSERT_EQ(linalg::skyline_cholesky(whole, 0, removed), -1);
        expect_factor_of_restriction(whole, c.A, removed);
        for (int k1 : {1, 2, 3, 101, static_cast<int>(rng() % n)}) {
            SkylineMatrix pieces = A_lower;
            ASSERT_EQ(linalg::skyline_cholesky(pieces, 0, k1, removed), -1);
            ASSERT_EQ(linalg::skyline_cholesky(pieces, k1, removed), -1);
            for (int k = 0; k < n; ++k)
                for (int r = k; r <= whole.sky(k); ++r)
                    ASSERT_EQ(pieces.at(r, k), whole.at(r, k)) << "(" << r << "," << k << "), split at " << k1;
        }
    }
}

TEST(LinalgCholesky, ColumnRangeReportsABreakdownInsideItOnly) {
    const int n = 6;
    MatrixXd A = MatrixXd::Identity(n, n);
    A(4, 3) = A(3, 4) = 1.0;  // rows 3 and 4 equal: the pivot of column 4 is zero
    A(4, 4) = 1.0;
    const SkylineMatrix A_lower = from_dense(A, SkylineShape::dense(n));
    SkylineMatrix L = A_lower;
    EXPECT_EQ(linalg::skyline_cholesky(L, 0, 4, {}), -1);
    EXPECT_EQ(linalg::skyline_cholesky(L, 4, n, {}), 4);
}

/// Index of the first pivot of the (kept part of the) matrix that is not positive, from the
/// smallest eigenvalue of the leading principal submatrices.
int oracle_first_failure(const MatrixXd& A, const std::vector<int>& kept) {
    for (int m = 1; m <= static_cast<int>(kept.size()); ++m) {
        const std::vector<int> leading(kept.begin(), kept.begin() + m);
        const VectorXd ev = Eigen::SelfAdjointEigenSolver<MatrixXd>(restricted(A, leading)).eigenvalues();
        if (ev.minCoeff() <= 0.0) return kept[m - 1];
    }
    return -1;
}

TEST(LinalgCholesky, ReportsTheFirstNonPositivePivot) {
    std::mt19937 rng(25);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 3 + static_cast<int>(rng() % 40);
        Case c = make_case(n, 4, rng);
        const std::vector<char> removed = trial % 2 ? random_removed(n, 0.2, rng) : std::vector<char>{};
        std::vector<char> flags = removed.empty() ? std::vector<char>(static_cast<std::size_t>(n), 0) : removed;
        const std::vector<int> kept = kept_indices(flags);
        if (kept.size() < 2) continue;
        // Lower one kept diagonal entry below its Schur-complement pivot d_q: that pivot
        // becomes -d_q / 2 while every earlier one is untouched.
        const int q_pos = 1 + static_cast<int>(rng() % (kept.size() - 1));
        const int q = kept[q_pos];
        const std::vector<int> leading(kept.begin(), kept.begin() + q_pos + 1);
        const MatrixXd L_lead = oracle_factor(restricted(c.A, leading));
        const double d_q = L_lead(q_pos, q_pos) * L_lead(q_pos, q_pos);
        c.A(q, q) -= 1.5 * d_q;
        c.rows = lower_row_major_poisoned(c.A, c.lda);
        ASSERT_EQ(oracle_first_failure(c.A, kept), q);
        SkylineMatrix L = linalg::load_skyline(c.rows.data(), c.lda, n, nullptr);
        EXPECT_EQ(linalg::skyline_cholesky(L, 0, removed), q);
    }
}

TEST(LinalgCholesky, DetectsRankDeficiencyRelativeToTheDiagonal) {
    // A = J Jᵀ with row q of J a combination of earlier rows: the pivot at q is zero in exact
    // arithmetic; scaled by 1e6 so that an absolute threshold would not see it.
    std::mt19937 rng(26);
    std::normal_distribution<double> gauss;
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 4 + static_cast<int>(rng() % 30);
        MatrixXd J(n, n + 5);
        for (int i = 0; i < J.rows(); ++i)
            for (int j = 0; j < J.cols(); ++j) J(i, j) = gauss(rng);
        const int q = 2 + static_cast<int>(rng() % (n - 2));
        J.row(q) = 0.7 * J.row(0) - 1.3 * J.row(1);
        const MatrixXd A = 1e6 * J * J.transpose();
        SkylineMatrix L = from_dense(A, SkylineShape::dense(n));
        EXPECT_EQ(linalg::skyline_cholesky(L, 0, {}), q);
    }
}

TEST(LinalgCholesky, AcceptsIllConditionedButDefiniteMatrices) {
    // The same near-dependent rows, regularized by 1e-9 * ||A|| on the diagonal (a stiff
    // compliance): the pivot at q is about 1e-9 of its diagonal, far above rounding noise.
    std::mt19937 rng(29);
    std::normal_distribution<double> gauss;
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 4 + static_cast<int>(rng() % 30);
        MatrixXd J(n, n + 5);
        for (int i = 0; i < J.rows(); ++i)
            for (int j = 0; j < J.cols(); ++j) J(i, j) = gauss(rng);
        const int q = 2 + static_cast<int>(rng() % (n - 2));
        J.row(q) = 0.7 * J.row(0) - 1.3 * J.row(1);
        MatrixXd A = J * J.transpose();
        A.diagonal().array() += 1e-9 * A.norm();
        SkylineMatrix L = from_dense(A, SkylineShape::dense(n));
        ASSERT_EQ(linalg::skyline_cholesky(L, 0, {}), -1);
        expect_factor_of_restriction(L, A, {});
    }
}

TEST(LinalgCholesky, RejectsNonFiniteInput) {
    std::mt19937 rng(27);
    const int n = 10;
    Case c = make_case(n, 3, rng);
    c.A(6, 6) = std::numeric_limits<double>::infinity();
    SkylineMatrix L = from_dense(c.A, SkylineShape::dense(n));
    EXPECT_EQ(linalg::skyline_cholesky(L, 0, {}), 6);
    c.A(6, 6) = std::numeric_limits<double>::quiet_NaN();
    L = from_dense(c.A, SkylineShape::dense(n));
    EXPECT_EQ(linalg::skyline_cholesky(L, 0, {}), 6);
}

TEST(LinalgCholesky, NeverTouchesStorageOutsideTheEnvelope) {
    std::mt19937 rng(28);
    for (int trial = 0; trial < 10; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 60);
        const Case c = make_case(n, 6, rng);
        const SkylineMatrix packed = linalg::load_skyline(c.rows.data(), c.lda, n, nullptr);
        SkylineMatrix L(padded(packed.shape(), n));
        for (int k = 0; k < n; ++k)
            for (int r = k; r <= L.sky(k); ++r) L.at(r, k) = packed.at(r, k);
        poison_padding(L);
        const std::vector<char> removed = random_removed(n, 0.2, rng);
        ASSERT_EQ(linalg::skyline_cholesky(L, 0, removed), -1);
        EXPECT_TRUE(padding_untouched(L));
        expect_factor_of_restriction(L, c.A, removed);
    }
}

}  // namespace
}  // namespace ode_bpp::test
