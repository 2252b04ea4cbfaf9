// IncrementalCholesky: after any sequence of appends (in increasing index or out of order) and
// removals (first, last, middle or random positions), the factor is the Cholesky factor of M_SS in
// S's order (against Eigen's LLT of M_SS gathered afresh, and L Lᵀ reconstructed from the
// factor's own entries), solve() is M_SS⁻¹, quadratic_form() is vᵀ M_SS v, the recorded envelope holds every non-zero of that
// factor, and a dependent row is refused. Appends, removals and solves also give, bit for bit,
// the row-at-a-time operations that incremental_cholesky.cpp documents (its dot products' four
// partial sums included), so a faster kernel must keep them. Banded matrices (small envelopes)
// and arbitrary sparse and dense SPD matrices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "linalg/incremental_cholesky.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

/// Random SPD n x n matrix with off-diagonal entries at random places (probability `density`),
/// so that its envelope is not its pattern: diagonal dominance, margin 0.5.
MatrixXd random_sparse_spd(int n, double density, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0), coin(0.0, 1.0);
    MatrixXd A = MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < i; ++j)
            if (coin(rng) < density) A(i, j) = A(j, i) = u(rng);
    for (int i = 0; i < n; ++i) A(i, i) = 0.5 + A.row(i).cwiseAbs().sum();
    return A;
}

/// M_SS in S's order.
MatrixXd gathered(const MatrixXd& M, const std::vector<int>& S) {
    const int m = static_cast<int>(S.size());
    MatrixXd M_SS(m, m);
    for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) M_SS(a, b) = M(S[a], S[b]);
    return M_SS;
}

/// Position of the first non-zero of row a of M_SS (a when there is none before the diagonal).
int first_nonzero(const MatrixXd& M_SS, int a) {
    int k = 0;
    while (k < a && M_SS(a, k) == 0.0) ++k;
    return k;
}

/// Appends index j of M to the factor of M_SS, passing its column from its first non-zero on;
/// the entries before it are NaN, so that reading them would show.
bool append(linalg::IncrementalCholesky& f, const MatrixXd& M, std::vector<int>& S, int j) {
    const int m = static_cast<int>(S.size());
    int first = 0;
    while (first < m && M(S[first], j) == 0.0) ++first;
    std::vector<double> column(static_cast<std::size_t>(m), std::numeric_limits<double>::quiet_NaN());
    for (int k = first; k < m; ++k) column[k] = M(S[k], j);
    if (!f.append(column.data(), first, M(j, j))) return false;
    S.push_back(j);
    return true;
}

/// The factor's L as a dense matrix, through entry().
MatrixXd factor_of(const linalg::IncrementalCholesky& f) {
    const int m = f.size();
    MatrixXd L = MatrixXd::Zero(m, m);
    for (int i = 0; i < m; ++i)
        for (int k = 0; k <= i; ++k) L(i, k) = f.entry(i, k);
    return L;
}

void expect_factor(const linalg::IncrementalCholesky& f, const MatrixXd& M, const std::vector<int>& S) {
    const int m = static_cast<int>(S.size());
    ASSERT_EQ(f.size(), m);
    if (m == 0) return;
    const MatrixXd M_SS = gathered(M, S);
    const MatrixXd L = factor_of(f);
    const MatrixXd oracle = oracle_factor(M_SS);
    const double tol = factor_tolerance(M_SS, oracle.cwiseAbs().maxCoeff());
    EXPECT_LT((L - oracle).cwiseAbs().maxCoeff(), tol);
    // backward stability, |L Lᵀ - M_SS| <~ m eps |L| |L|ᵀ, with room for the updates' rounding
    const double reconstruction_tol = 100.0 * m * std::numeric_limits<double>::epsilon() *
                                      (L.cwiseAbs() * L.cwiseAbs().transpose()).maxCoeff();
    EXPECT_LT((L * L.transpose() - M_SS).cwiseAbs().maxCoeff(), reconstruction_tol);
    std::size_t stored = 0;
    for (int i = 0; i < m; ++i) {
        // every non-zero of the factor (whose envelope is M_SS's) lies inside the recorded one
        EXPECT_LE(f.first(i), first_nonzero(M_SS, i)) << "row " << i;
        for (int k = 0; k < f.first(i); ++k) ASSERT_EQ(oracle(i, k), 0.0) << "row " << i << " column " << k;
        stored += static_cast<std::size_t>(i - f.first(i) + 1);
    }
    EXPECT_EQ(f.stored_entries(), stored);
}

/// After appends in increasing index only, the recorded envelope is M_SS's exactly.
void expect_tight_envelope(const linalg::IncrementalCholesky& f, const MatrixXd& M, const std::vector<int>& S) {
    const MatrixXd M_SS = gathered(M, S);
    for (int i = 0; i < f.size(); ++i) EXPECT_EQ(f.first(i), first_nonzero(M_SS, i)) << "row " << i;
}

void expect_solves(const linalg::IncrementalCholesky& f, const MatrixXd& M, const std::vector<int>& S, std::mt19937& rng) {
    const int m = static_cast<int>(S.size());
    ASSERT_EQ(f.size(), m);
    if (m == 0) return;
    const MatrixXd M_SS = gathered(M, S);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::VectorXd rhs(m);
    for (int a = 0; a < m; ++a) rhs[a] = u(rng);
    const Eigen::VectorXd expected = M_SS.llt().solve(rhs);
    std::vector<double> x(rhs.data(), rhs.data() + m);
    f.solve(x.data());
    const double tol = 1e-10 * condition_number(M_SS) * (1 + expected.cwiseAbs().maxCoeff());
    for (int a = 0; a < m; ++a) EXPECT_NEAR(x[a], expected[a], tol) << "position " << a;
    // quadratic_form is vᵀ M_SS v, to rounding in |v|ᵀ|M_SS||v|
    std::vector<double> y(static_cast<std::size_t>(m), std::numeric_limits<double>::quiet_NaN());
    const double form = rhs.dot(M_SS * rhs);
    const double scale = rhs.cwiseAbs().dot(M_SS.cwiseAbs() * rhs.cwiseAbs());
    EXPECT_NEAR(f.quadratic_form(rhs.data(), y.data()), form, 1e-12 * m * scale);
}

/// remove(p) on the dense factor L, one row at a time as incremental_cholesky.cpp documents it: row
/// i takes the rotations of columns p+1 .. i-1 in turn, then defines its own. The exact sequence
/// of operations that remove() must give, bit for bit, however it interleaves the rows.
MatrixXd removed_row_at_a_time(const MatrixXd& L, int p) {
    const int n = static_cast<int>(L.rows());
    MatrixXd out = MatrixXd::Zero(n - 1, n - 1);
    std::vector<double> c(static_cast<std::size_t>(n)), s(static_cast<std::size_t>(n));
    for (int i = 0; i < p; ++i)
        for (int k = 0; k <= i; ++k) out(i, k) = L(i, k);
    for (int i = p + 1; i < n; ++i) {
        for (int k = 0; k < p; ++k) out(i - 1, k) = L(i, k);
        double sigma = L(i, p);
        for (int k = p + 1; k < i; ++k) {
            const double l = L(i, k);
            out(i - 1, k - 1) = c[k] * l + s[k] * sigma;
            sigma = c[k] * sigma - s[k] * l;
        }
        const double d = L(i, i);
        const double r = std::sqrt(d * d + sigma * sigma);
        c[i] = d / r;
        s[i] = sigma / r;
        out(i - 1, i - 1) = r;
    }
    return out;
}

/// sum_j a_j b_j in the order incremental_cholesky.cpp documents: term j into partial sum j mod 4,
/// in increasing j, then (s0 + s1) + (s2 + s3).
double dot_in_four_sums(const std::vector<double>& a, const std::vector<double>& b) {
    double s[4] = {0, 0, 0, 0};
    for (std::size_t j = 0; j < a.size(); ++j) s[j % 4] += a[j] * b[j];
    return (s[0] + s[1]) + (s[2] + s[3]);
}

/// y_k <- (y_k - L(k, from:k) . y(from:k)) / L(k, k) for k = first .. m-1, from = max(first(k),
/// first), one row at a time: the exact operations append() and solve() must give, bit for bit,
/// however they interleave the rows. y[k - first] holds entry k.
void forward_row_at_a_time(const linalg::IncrementalCholesky& f, std::vector<double>& y, int first, int m) {
    for (int k = first; k < m; ++k) {
        const int from = std::max(f.first(k), first);
        std::vector<double> l_row, y_part;
        for (int c = from; c < k; ++c) {
            l_row.push_back(f.entry(k, c));
            y_part.push_back(y[static_cast<std::size_t>(c - first)]);
        }
        double& yk = y[static_cast<std::size_t>(k - first)];
        yk = (yk - dot_in_four_sums(l_row, y_part)) * (1.0 / f.entry(k, k));
    }
}

/// The row that appending `column` (entries first .. m-1) to f must give, L(m, first .. m).
std::vector<double> appended_row_at_a_time(const linalg::IncrementalCholesky& f, const std::vector<double>& column,
                                           int first, double diagonal) {
    const int m = f.size();
    std::vector<double> l(column.begin() + first, column.end());
    forward_row_at_a_time(f, l, first, m);
    l.push_back(std::sqrt(diagonal - dot_in_four_sums(l, l)));
    return l;
}

/// x <- (L Lᵀ)⁻¹ x as solve() must give it: forward_row_at_a_time, then by columns of Lᵀ.
std::vector<double> solved_row_at_a_time(const linalg::IncrementalCholesky& f, std::vector<double> x) {
    const int m = f.size();
    forward_row_at_a_time(f, x, 0, m);
    for (int i = m - 1; i >= 0; --i) {
        const double xi = x[static_cast<std::size_t>(i)] * (1.0 / f.entry(i, i));
        x[static_cast<std::size_t>(i)] = xi;
        for (int k = f.first(i); k < i; ++k) x[static_cast<std::size_t>(k)] -= xi * f.entry(i, k);
    }
    return x;
}

/// append(), its new row compared entry for entry with appended_row_at_a_time.
bool append_bit_for_bit(linalg::IncrementalCholesky& f, const MatrixXd& M, std::vector<int>& S, int j) {
    const int m = static_cast<int>(S.size());
    int first = 0;
    while (first < m && M(S[first], j) == 0.0) ++first;
    std::vector<double> column(static_cast<std::size_t>(m));
    for (int k = first; k < m; ++k) column[k] = M(S[k], j);
    const std::vector<double> expected = appended_row_at_a_time(f, column, first, M(j, j));
    if (!append(f, M, S, j)) return false;
    for (int k = 0; k <= m; ++k) {
        const double want = k < first ? 0.0 : expected[static_cast<std::size_t>(k - first)];
        EXPECT_EQ(f.entry(m, k), want) << "(" << m << "," << k << ")";
    }
    return true;
}

/// solve() on a random right-hand side, compared entry for entry with solved_row_at_a_time.
void expect_solve_bits(const linalg::IncrementalCholesky& f, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> x(static_cast<std::size_t>(f.size()));
    for (double& v : x) v = u(rng);
    const std::vector<double> expected = solved_row_at_a_time(f, x);
    f.solve(x.data());
    for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(x[i], expected[i]) << "position " << i;
}

/// Random appends (out of order) and removals (random positions) from a random half of M's rows.
void random_moves(const MatrixXd& M, std::mt19937& rng) {
    const int n = static_cast<int>(M.rows());
    linalg::IncrementalCholesky f;
    f.reset(n);
    std::vector<int> S, outside;
    for (int i = 0; i < n; ++i) (rng() % 2 ? S : outside).push_back(i);
    std::vector<int> start = S;
    S.clear();
    for (int i : start) ASSERT_TRUE(append_bit_for_bit(f, M, S, i));
    expect_tight_envelope(f, M, S);
    expect_factor(f, M, S);
    expect_solves(f, M, S, rng);
    for (int move = 0; move < 3 * n; ++move) {
        if (!outside.empty() && (S.empty() || rng() % 2)) {
            const std::size_t k = rng() % outside.size();
            ASSERT_TRUE(append_bit_for_bit(f, M, S, outside[k]));
            outside.erase(outside.begin() + static_cast<std::ptrdiff_t>(k));
        } else {
            const int p = static_cast<int>(rng() % S.size());
            const MatrixXd expected = removed_row_at_a_time(factor_of(f), p);
            f.remove(p);
            outside.push_back(S[p]);
            S.erase(S.begin() + p);
            for (int i = 0; i < f.size(); ++i)
                for (int k = 0; k <= i; ++k) ASSERT_EQ(f.entry(i, k), expected(i, k)) << "(" << i << "," << k << ")";
        }
        expect_factor(f, M, S);
        expect_solves(f, M, S, rng);
        expect_solve_bits(f, rng);
    }
}

TEST(LinalgIncrementalCholesky, RandomMovesOnBandedMatrices) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 5 + static_cast<int>(rng() % 40);
        random_moves(random_envelope_spd(n, 1 + static_cast<int>(rng() % 6), rng, 0.5, 1.0), rng);
    }
}

TEST(LinalgIncrementalCholesky, RandomMovesOnArbitrarySpdMatrices) {
    std::mt19937 rng(12);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 5 + static_cast<int>(rng() % 40);
        if (trial % 2 == 0) random_moves(random_envelope_spd(n, n, rng, 0.5, 1.0), rng);
        else random_moves(random_sparse_spd(n, 0.1, rng), rng);
    }
}

TEST(LinalgIncrementalCholesky, RemovesTheFirstLastAndMiddleRowAndAppendsOutOfOrder) {
    std::mt19937 rng(13);
    const int n = 30;
    const MatrixXd M = random_envelope_spd(n, 3, rng, 0.5, 1.0);
    linalg::IncrementalCholesky f;
    f.reset(n);
    std::vector<int> S;
    for (int i = 0; i < n; ++i) ASSERT_TRUE(append(f, M, S, i));
    expect_tight_envelope(f, M, S);
    expect_factor(f, M, S);
    const auto remove_at = [&](int p) {
        f.remove(p);
        S.erase(S.begin() + p);
        expect_factor(f, M, S);
        expect_solves(f, M, S, rng);
    };
    remove_at(0);
    remove_at(static_cast<int>(S.size()) - 1);
    remove_at(static_cast<int>(S.size()) / 2);  // index 15: rows 16 .. 18 may lean on it
    remove_at(static_cast<int>(S.size()) / 2);  // index 14
    // back as the last rows: their envelopes start at their first neighbour in S
    for (int j : {15, 0, 29, 14}) {
        ASSERT_TRUE(append(f, M, S, j));
        expect_factor(f, M, S);
        expect_solves(f, M, S, rng);
    }
    const MatrixXd M_SS = gathered(M, S);
    for (int i = f.size() - 4; i < f.size(); ++i) EXPECT_EQ(f.first(i), first_nonzero(M_SS, i)) << "appended row " << i;
    // the envelope is work, not the dense triangle: 29 banded rows plus the four appended ones
    EXPECT_LT(f.stored_entries(), static_cast<std::size_t>(30 * 4 + 4 * 30));
    while (f.size() > 0) remove_at(0);
}

TEST(LinalgIncrementalCholesky, RefusesARowDependentOnTheSet) {
    // rows 0 and 1 span row 2 exactly: M = V Vᵀ with v2 = v0 + v1
    MatrixXd V(3, 3);
    V << 1, 0, 0.5, 0, 2, 0.25, 1, 2, 0.75;
    const MatrixXd M = V * V.transpose();
    linalg::IncrementalCholesky f;
    f.reset(3);
    std::vector<int> S;
    ASSERT_TRUE(append(f, M, S, 0));
    ASSERT_TRUE(append(f, M, S, 1));
    EXPECT_FALSE(append(f, M, S, 2));
    EXPECT_EQ(f.size(), 2);
    std::mt19937 rng(3);
    expect_solves(f, M, S, rng);
    f.remove(0);  // without row 0, row 2 is independent of row 1
    S.erase(S.begin());
    EXPECT_TRUE(append(f, M, S, 2));
    expect_solves(f, M, S, rng);
}

}  // namespace
}  // namespace ode_bpp::test
