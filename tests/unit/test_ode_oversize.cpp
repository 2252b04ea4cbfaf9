// The factor limit decided from an island's joints before A is formed (ode/oversize.h): the
// joints' pattern (ordering::block_row_profile) is the assembled A's in every order, the count is
// the one the solve itself makes on the assembled A (pivoting::planned_factor_entries) in the
// order it is handed, and each limit gets the verdict that count implies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "linalg/skyline.h"
#include "linalg/symmetric_rows.h"
#include "ode/assemble.h"
#include "ode/island_view.h"
#include "ode/jacobian_pgs.h"
#include "ode/oversize.h"
#include "test_ode_support.h"
#include "ordering/graph.h"
#include "ordering/ordering_choice.h"
#include "pivoting/bpp_driver.h"

namespace ode_bpp::ode {
namespace {

/// Joints of 1, 3 or 6 rows between random pairs of `bodies` bodies, a third of them to the
/// static environment, with random J and J M^-1 (the values do not matter here, the pattern
/// does) and contact-like bounds: each joint's first row a normal (lo 0), the rest unbounded.
struct Pile : test::SparseIsland {
    Pile(int bodies, int joint_count, unsigned seed) {
        std::mt19937 rng(seed);
        std::uniform_int_distribution<int> body(0, bodies - 1), size(0, 2);
        std::uniform_real_distribution<double> value(-1.0, 1.0);
        const int sizes[] = {1, 3, 6};
        int row = 0;
        for (int k = 0; k < joint_count; ++k) {
            dMLCPJoint joint{};
            joint.row = row;
            joint.m = sizes[size(rng)];
            joint.body[0] = body(rng);
            joint.body[1] = k % 3 == 0 ? -1 : body(rng);
            if (joint.body[1] == joint.body[0]) joint.body[1] = -1;
            joints.push_back(joint);
            row += joint.m;
        }
        p.m = row;
        p.nb = bodies;
        J.resize(2 * static_cast<std::size_t>(p.m) * dMLCP_J_ROW);
        JinvM.resize(2 * static_cast<std::size_t>(p.m) * dMLCP_JINVM_ROW);
        for (double& v : J) v = value(rng);
        for (double& v : JinvM) v = value(rng);
        cfm.assign(static_cast<std::size_t>(p.m), 1e-3);
        pairsbx.assign(2 * static_cast<std::size_t>(p.m), 0.0);
        pairslh.assign(2 * static_cast<std::size_t>(p.m), 0.0);
        findex.assign(static_cast<std::size_t>(p.m), -1);
        for (const dMLCPJoint& joint : joints)
            for (int i = joint.row; i < joint.row + joint.m; ++i) {
                pairslh[2 * i] = i == joint.row ? 0.0 : -INFINITY;
                pairslh[2 * i + 1] = INFINITY;
            }
        point_at_arrays();
    }
};

using test::assembled;

std::vector<int> shuffled(int n, unsigned seed) {
    std::vector<int> perm(static_cast<std::size_t>(n));
    std::iota(perm.begin(), perm.end(), 0);
    std::mt19937 rng(seed);
    std::shuffle(perm.begin(), perm.end(), rng);
    return perm;
}

/// The solve's own count on the assembled A, factored in `order`.
std::int64_t planned_on_assembled(const Problem& rows, const linalg::SymmetricRows& A, const Options& o,
                                  const std::vector<int>& order) {
    Problem q = rows;
    q.sparse = &A;
    Start start;
    start.ordering = order;
    linalg::SymmetricRows scratch;
    std::vector<int> chosen;
    return pivoting::planned_factor_entries(q, A, o, start, scratch, chosen);
}

/// Options whose limit the island's dense triangle passes, so that the count is made.
Options with_limit(std::int64_t entries) {
    Options o;
    o.max_factor_entries = entries;
    return o;
}

TEST(OdeOversize, TheJointsPatternIsTheAssembledOneInEveryOrder) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        Pile pile(12, 30, seed);
        const Problem rows = pile.rows();
        const linalg::SymmetricRows A = assembled(pile.p);
        std::vector<int> identity(static_cast<std::size_t>(rows.n));
        std::iota(identity.begin(), identity.end(), 0);
        for (const std::vector<int>& perm :
             {identity, shuffled(rows.n, seed), ordering::block_ordering(Method::Bpp, rows),
              ordering::block_ordering(Method::BppSky, rows)}) {
            EXPECT_EQ(ordering::block_row_profile(rows.num_blocks, rows.block_row, rows.block_body, perm),
                      A.row_profile_under(perm))
                << "seed " << seed;
        }
    }
}

TEST(OdeOversize, CountsTheFactorTheSolveWouldHoldAndJudgesEachLimitByIt) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        Pile pile(12, 30, seed);
        const Problem rows = pile.rows();
        const linalg::SymmetricRows A = assembled(pile.p);
        const std::int64_t a_entries = A.off_diagonal_entries() / 2 + A.n();
        std::vector<std::int64_t> scratch;
        const std::int64_t a_bound = coupled_entries_lower_bound(pile.p, scratch);

        // a new island: counted in the joint graph's order, which the solve is handed
        std::vector<int> order;
        const std::int64_t factor = planned_on_assembled(rows, A, Options{}, ordering::block_ordering(Method::Bpp, rows));
        ASSERT_GT(factor, a_entries) << "no fill: the pile does not tell the two counts apart";
        const Oversize past_factor = oversize(pile.p, rows, with_limit(a_entries), order, scratch);
        EXPECT_EQ(past_factor.measure, Oversize::Measure::FactorEntries) << "seed " << seed;
        EXPECT_EQ(past_factor.entries, factor);
        EXPECT_EQ(order, ordering::block_ordering(Method::Bpp, rows));
        order.clear();
        EXPECT_EQ(oversize(pile.p, rows, with_limit(factor - 1), order, scratch).entries, factor);
        order.clear();
        EXPECT_FALSE(oversize(pile.p, rows, with_limit(factor), order, scratch)) << "exact at the envelope";
        EXPECT_EQ(order, ordering::block_ordering(Method::Bpp, rows)) << "the solve factors in it";

        // A's own entries, bounded from below, decide first
        order.clear();
        const Oversize past_a = oversize(pile.p, rows, with_limit(a_bound - 1), order, scratch);
        EXPECT_EQ(past_a.measure, Oversize::Measure::MatrixEntries);
        EXPECT_EQ(past_a.entries, a_bound);

        // a remembered order is counted as it is
        std::vector<int> remembered = shuffled(rows.n, seed + 100);
        const std::vector<int> kept = remembered;
        const std::int64_t in_remembered = planned_on_assembled(rows, A, Options{}, kept);
        const Oversize past = oversize(pile.p, rows, with_limit(in_remembered - 1), remembered, scratch);
        EXPECT_EQ(past.measure, Oversize::Measure::FactorEntries);
        EXPECT_EQ(past.entries, in_remembered);
        EXPECT_EQ(remembered, kept);
    }
}

TEST(OdeOversize, DenseStrategiesHoldTheTriangleAndSmallOrDefectiveIslandsAreNotJudged) {
    Pile pile(12, 30, 3);
    const Problem rows = pile.rows();
    const auto n = static_cast<std::int64_t>(rows.n);
    std::vector<std::int64_t> scratch;
    std::vector<int> order;
    Options dense = with_limit(coupled_entries_lower_bound(pile.p, scratch));
    dense.method = Method::BppDown;
    const Oversize triangle = oversize(pile.p, rows, dense, order, scratch);
    EXPECT_EQ(triangle.measure, Oversize::Measure::FactorEntries);
    EXPECT_EQ(triangle.entries, n * (n + 1) / 2);
    EXPECT_TRUE(order.empty()) << "a dense strategy factors in the island's own order";

    EXPECT_FALSE(oversize(pile.p, rows, with_limit(n * (n + 1) / 2), order, scratch)) << "within the dense triangle";
    Options off = with_limit(0);
    EXPECT_FALSE(oversize(pile.p, rows, off, order, scratch)) << "0: no limit";
    Options pgs = with_limit(1);
    pgs.method = Method::Pgs;
    EXPECT_FALSE(oversize(pile.p, rows, pgs, order, scratch)) << "not a factoring method";

    pile.joints[4].body[1] = pile.p.nb;  // outside [-1, nb): left to the solve, which reports it
    EXPECT_FALSE(oversize(pile.p, pile.rows(), with_limit(1), order, scratch));
}

}  // namespace
}  // namespace ode_bpp::ode
