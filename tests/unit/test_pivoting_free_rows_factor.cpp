// FreeRowsFactor (pivoting/free_rows_factor.h): after a reset and any sequence of rows joining
// and leaving F, solve() is Eq. 6, x_F = (A + shift I)_FF⁻¹ (b - A_FT x_T)_F with the tight
// values given (against a dense solve); rows joining out of order make F refactor itself in
// increasing index once they have widened its envelope, with the same answers; a reset seeded
// with the pivoting loop's skyline factor of another free set solves it too.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "linalg/skyline.h"
#include "linalg/skyline_cholesky.h"
#include "linalg/symmetric_rows.h"
#include "pivoting/free_rows_factor.h"
#include "test_linalg_support.h"

namespace ode_bpp::pivoting {
namespace {

using test::MatrixXd;

struct Fixture {
    MatrixXd dense;
    linalg::SymmetricRows A;
    BoxedLcp lcp;

    Fixture(int n, int band, double shift, std::mt19937& rng) : dense(test::random_envelope_spd(n, band, rng, 0.5, 1.0)) {
        std::vector<double> diagonal(static_cast<std::size_t>(n));
        std::vector<linalg::LowerEntry> lower;
        for (int i = 0; i < n; ++i) {
            diagonal[i] = dense(i, i);
            for (int j = 0; j < i; ++j)
                if (dense(i, j) != 0.0) lower.push_back({i, j, dense(i, j)});
        }
        A.assign_lower(diagonal, lower);
        std::uniform_real_distribution<double> u(-1, 1);
        lcp.A = &A;
        lcp.shift = shift;
        lcp.b.resize(static_cast<std::size_t>(n));
        for (double& v : lcp.b) v = u(rng);
        lcp.lo.assign(static_cast<std::size_t>(n), -1.0);
        lcp.hi.assign(static_cast<std::size_t>(n), 1.0);
    }

    /// Eq. 6 solved densely: F = the rows with tight[i] false, x_T = x on the others.
    std::vector<double> expected(const std::vector<char>& tight, const std::vector<double>& x) const {
        const int n = static_cast<int>(dense.rows());
        std::vector<int> F;
        for (int i = 0; i < n; ++i)
            if (!tight[i]) F.push_back(i);
        const int m = static_cast<int>(F.size());
        MatrixXd A_FF(m, m);
        Eigen::VectorXd rhs(m);
        for (int a = 0; a < m; ++a) {
            rhs[a] = lcp.b[F[a]];
            for (int j = 0; j < n; ++j)
                if (tight[j]) rhs[a] -= dense(F[a], j) * x[j];
            for (int c = 0; c < m; ++c) A_FF(a, c) = dense(F[a], F[c]) + (a == c ? lcp.shift : 0.0);
        }
        const Eigen::VectorXd xF = A_FF.llt().solve(rhs);
        std::vector<double> out = x;
        for (int a = 0; a < m; ++a) out[F[a]] = xF[a];
        return out;
    }
};

void expect_eq6(const FreeRowsFactor& factor, const Fixture& f, const std::vector<char>& tight, const std::vector<double>& x) {
    std::vector<double> got = x;
    factor.solve(got);
    const std::vector<double> want = f.expected(tight, x);
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-9 * (1 + std::abs(want[i]))) << "row " << i;
}

/// `moves` random rows join or leave F in turn (a leaving row held at a random value), Eq. 6
/// checked after each.
void move_rows_checking_eq6(FreeRowsFactor& factor, const Fixture& f, std::vector<char>& tight, std::vector<double>& x,
                            int moves, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    const int n = static_cast<int>(x.size());
    for (int move = 0; move < moves; ++move) {
        const int i = static_cast<int>(rng() % n);
        if (tight[i]) {
            ASSERT_EQ(factor.add(i), FreeRowsFactor::AddOutcome::Added);
            tight[i] = 0;
        } else {
            x[i] = u(rng);
            factor.remove(i, x[i]);
            tight[i] = 1;
        }
        expect_eq6(factor, f, tight, x);
    }
}

TEST(PivotingFreeRowsFactor, SolvesEq6AfterRowsJoinAndLeave) {
    std::mt19937 rng(21);
    for (int trial = 0; trial < 10; ++trial) {
        const int n = 10 + static_cast<int>(rng() % 50);
        const Fixture f(n, 1 + static_cast<int>(rng() % 8), trial % 2 ? 1e-3 : 0.0, rng);
        std::uniform_real_distribution<double> u(-1, 1);
        std::vector<RowState> states(static_cast<std::size_t>(n), RowState::Free);
        std::vector<char> tight(static_cast<std::size_t>(n), 0);
        std::vector<double> x(static_cast<std::size_t>(n), 0.0);
        for (int i = 0; i < n; ++i)
            if (rng() % 3 == 0) {
                states[i] = RowState::AtLo;
                tight[i] = 1;
                x[i] = u(rng);
            }
        FreeRowsFactor factor;
        ASSERT_TRUE(factor.reset(f.lcp, states, x));
        expect_eq6(factor, f, tight, x);
        move_rows_checking_eq6(factor, f, tight, x, 2 * n, rng);
    }
}

/// n rows, the odd ones tight at their upper bound and held at 0.5, the even ones free at 0.
struct OddRowsTight {
    std::vector<RowState> states;
    std::vector<char> tight;
    std::vector<double> x;
    explicit OddRowsTight(int n)
        : states(static_cast<std::size_t>(n), RowState::Free), tight(static_cast<std::size_t>(n), 0),
          x(static_cast<std::size_t>(n), 0.0) {
        for (int i = 1; i < n; i += 2) {
            states[i] = RowState::AtHi;
            tight[i] = 1;
            x[i] = 0.5;
        }
    }
};

TEST(PivotingFreeRowsFactor, RefactorsInIncreasingIndexOnceRowsJoiningOutOfOrderWidenIt) {
    std::mt19937 rng(22);
    const int n = 80;
    const Fixture f(n, 3, 0.0, rng);
    OddRowsTight start(n);
    const std::vector<RowState>& states = start.states;
    std::vector<char>& tight = start.tight;
    std::vector<double>& x = start.x;
    FreeRowsFactor factor;
    ASSERT_TRUE(factor.reset(f.lcp, states, x));
    // the odd rows join last to first: each spans from its first neighbour in F to the end
    bool reordered = false;
    for (int i = n - 1; i > 0; i -= 2) {
        ASSERT_EQ(factor.add(i), FreeRowsFactor::AddOutcome::Added);
        tight[i] = 0;
        const std::vector<int>& F = factor.members();
        if (F.back() != i) {
            reordered = true;
            EXPECT_TRUE(std::is_sorted(F.begin(), F.end()));
        }
        expect_eq6(factor, f, tight, x);
    }
    EXPECT_TRUE(reordered);
}

// updates() counts the rows that joined or left F since the factor was built: 0 after a reset, a
// refresh, and an add that refactored in increasing index (the active set checks an updated
// factor's accuracy only).
TEST(PivotingFreeRowsFactor, CountsItsUpdatesSinceItWasBuilt) {
    std::mt19937 rng(24);
    const int n = 80;
    const Fixture f(n, 3, 0.0, rng);
    const OddRowsTight start(n);
    FreeRowsFactor factor;
    ASSERT_TRUE(factor.reset(f.lcp, start.states, start.x));
    EXPECT_EQ(factor.updates(), 0);
    factor.remove(0, 0.25);
    EXPECT_EQ(factor.updates(), 1);
    ASSERT_EQ(factor.add(n - 1), FreeRowsFactor::AddOutcome::Added);
    EXPECT_EQ(factor.updates(), 2);
    ASSERT_TRUE(factor.refresh());
    EXPECT_EQ(factor.updates(), 0);
    bool reordered = false;  // rows joining last to first widen the envelope until F is refactored
    for (int i = n - 3; i > 0 && !reordered; i -= 2) {
        const int before = factor.updates();
        ASSERT_EQ(factor.add(i), FreeRowsFactor::AddOutcome::Added);
        reordered = factor.members().back() != i;
        EXPECT_EQ(factor.updates(), reordered ? 0 : before + 1);
    }
    EXPECT_TRUE(reordered);
}

/// A skyline factor of A + shift I with the rows of seed_tight removed (the pivoting loop's L), and
/// those rows.
struct Seed {
    linalg::SkylineMatrix L;
    std::vector<int> tight_rows;
    Seed(const Fixture& f, const std::vector<char>& seed_tight) {
        MatrixXd shifted = f.dense;
        shifted.diagonal().array() += f.lcp.shift;
        L = test::from_dense(shifted, linalg::SkylineShape::from_row_profile(f.A.row_profile()));
        EXPECT_LT(linalg::skyline_cholesky(L, 0, seed_tight), 0);
        for (int i = 0; i < static_cast<int>(seed_tight.size()); ++i)
            if (seed_tight[i]) tight_rows.push_back(i);
    }
    EnvelopeFactor view() const { return {&L, &tight_rows}; }
};

/// The states of `tight` (at their upper bound, random values) and their values.
void states_of(const std::vector<char>& tight, std::vector<RowState>& states, std::vector<double>& x, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    states.assign(tight.size(), RowState::Free);
    x.assign(tight.size(), 0.0);
    for (std::size_t i = 0; i < tight.size(); ++i)
        if (tight[i]) {
            states[i] = RowState::AtHi;
            x[i] = u(rng);
        }
}

// The seeded reset reads L_FF off a skyline factor of another free set (the pivoting loop's), then
// lets rows leave and join: Eq. 6 holds at the new free set and through further moves. A row that
// joins is appended last, so F out of increasing index shows that the seed served (the plain reset
// builds F in increasing index).
TEST(PivotingFreeRowsFactor, SeededResetSolvesEq6AtTheNewFreeSet) {
    std::mt19937 rng(23);
    for (int trial = 0; trial < 10; ++trial) {
        const int n = 16 + static_cast<int>(rng() % 50);
        const Fixture f(n, 1 + static_cast<int>(rng() % 8), trial % 2 ? 1e-3 : 0.0, rng);
        std::vector<char> seed_tight(static_cast<std::size_t>(n), 0);
        for (int i = 0; i < n; i += 3) seed_tight[i] = 1;  // a third tight; row 0 among them
        const Seed seed(f, seed_tight);
        std::vector<char> tight = seed_tight;
        tight[0] = 0;  // joins: the seed's free rows follow it
        for (int k = 0; k < n / 16; ++k) {  // and a few more change set
            const int i = 1 + static_cast<int>(rng() % (n - 1));
            tight[i] = !tight[i];
        }
        std::vector<RowState> states;
        std::vector<double> x;
        states_of(tight, states, x, rng);
        FreeRowsFactor factor;
        ASSERT_TRUE(factor.reset(f.lcp, states, x, seed.view()));
        EXPECT_FALSE(std::is_sorted(factor.members().begin(), factor.members().end())) << "the seed did not serve";
        std::vector<int> free_rows = factor.members();
        std::sort(free_rows.begin(), free_rows.end());
        EXPECT_EQ(free_rows, test::kept_indices(tight)) << "trial " << trial;
        expect_eq6(factor, f, tight, x);
        move_rows_checking_eq6(factor, f, tight, x, n, rng);
    }
}

// A seed that most rows disagree with is not used (the updates would cost more than a fresh
// factorization), and neither is a missing one: the plain reset, in increasing index.
TEST(PivotingFreeRowsFactor, SeededResetFactorsAfreshWhereTheSeedIsFarOrMissing) {
    std::mt19937 rng(24);
    const int n = 40;
    const Fixture f(n, 4, 0.0, rng);
    std::vector<char> seed_tight(static_cast<std::size_t>(n), 0);
    for (int i = 0; i < n; i += 2) seed_tight[i] = 1;
    const Seed seed(f, seed_tight);
    std::vector<char> tight(static_cast<std::size_t>(n), 0);
    for (int i = 1; i < n; i += 4) tight[i] = 1;  // three quarters of the rows change set
    std::vector<RowState> states;
    std::vector<double> x;
    states_of(tight, states, x, rng);
    for (const EnvelopeFactor& given : {seed.view(), EnvelopeFactor{}}) {
        FreeRowsFactor factor;
        ASSERT_TRUE(factor.reset(f.lcp, states, x, given));
        EXPECT_EQ(factor.members(), test::kept_indices(tight));
        expect_eq6(factor, f, tight, x);
    }
}

}  // namespace
}  // namespace ode_bpp::pivoting
