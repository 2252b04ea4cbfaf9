// IncrementalCholesky: after any sequence of appends and removals, solve() is M_SS⁻¹ in S's
// order (against Eigen's LLT of M_SS gathered afresh), and a dependent row is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "linalg/incremental_cholesky.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

/// Appends index j of M to the factor of M_SS.
bool append(linalg::IncrementalCholesky& f, const MatrixXd& M, std::vector<int>& S, int j) {
    std::vector<double> column;
    for (int i : S) column.push_back(M(i, j));
    if (!f.append(column.data(), M(j, j))) return false;
    S.push_back(j);
    return true;
}

void expect_solves(const linalg::IncrementalCholesky& f, const MatrixXd& M, const std::vector<int>& S, std::mt19937& rng) {
    const int m = static_cast<int>(S.size());
    ASSERT_EQ(f.size(), m);
    if (m == 0) return;
    MatrixXd M_SS(m, m);
    for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) M_SS(a, b) = M(S[a], S[b]);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::VectorXd rhs(m);
    for (int a = 0; a < m; ++a) rhs[a] = u(rng);
    const Eigen::VectorXd expected = M_SS.llt().solve(rhs);
    std::vector<double> x(rhs.data(), rhs.data() + m);
    f.solve(x.data());
    const double tol = 1e-10 * condition_number(M_SS) * (1 + expected.cwiseAbs().maxCoeff());
    for (int a = 0; a < m; ++a) EXPECT_NEAR(x[a], expected[a], tol) << "position " << a;
}

TEST(LinalgIncrementalCholesky, AppendsAndRemovalsKeepTheFactorOfTheSubmatrix) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 5 + static_cast<int>(rng() % 40);
        const MatrixXd M = random_envelope_spd(n, n, rng, 0.5, 1.0);
        linalg::IncrementalCholesky f;
        f.reset(n);
        std::vector<int> S, outside;
        for (int i = 0; i < n; ++i) (rng() % 2 ? S : outside).push_back(i);
        std::vector<int> start = S;
        S.clear();
        for (int i : start) ASSERT_TRUE(append(f, M, S, i));
        expect_solves(f, M, S, rng);
        for (int move = 0; move < 3 * n; ++move) {
            if (!outside.empty() && (S.empty() || rng() % 2)) {
                const std::size_t k = rng() % outside.size();
                ASSERT_TRUE(append(f, M, S, outside[k]));
                outside.erase(outside.begin() + static_cast<std::ptrdiff_t>(k));
            } else {
                const int p = static_cast<int>(rng() % S.size());
                f.remove(p);
                outside.push_back(S[p]);
                S.erase(S.begin() + p);
            }
            expect_solves(f, M, S, rng);
        }
    }
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
