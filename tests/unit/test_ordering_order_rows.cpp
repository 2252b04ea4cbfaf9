// order_rows: block or row graph, ODE-like matrices, likely-tight rows last.
#include <gtest/gtest.h>

#include "linalg/envelope.h"
#include "ordering/cuthill_mckee.h"
#include "ordering/graph.h"
#include "ordering/order_rows.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

using ordering::OrderingKind;

struct Island {
    BlockStructure blocks;
    MatrixXd A;
    std::vector<double> rows;
    int n() const { return blocks.rows(); }
    std::ptrdiff_t envelope(const std::vector<int>& perm) const {
        return linalg::envelope_size(linalg::row_profile(rows.data(), n(), n(), perm.data()));
    }
    std::vector<int> order(OrderingKind kind, bool use_blocks, const std::vector<char>* tight = nullptr) const {
        return ordering::order_rows(n(), rows.data(), n(), use_blocks ? blocks.num_blocks() : 0,
                                    use_blocks ? blocks.block_row.data() : nullptr,
                                    use_blocks ? blocks.block_body.data() : nullptr, kind, tight);
    }
};

Island winch(int links, std::mt19937& rng) {
    Island island;
    island.blocks = winch_blocks(links);
    island.A = constraint_matrix(island.blocks, rng);
    island.rows = lower_row_major_poisoned(island.A, island.n());
    return island;
}

std::vector<int> identity(int n) {
    std::vector<int> perm(n);
    std::iota(perm.begin(), perm.end(), 0);
    return perm;
}

TEST(OrderingOrderRows, WinchWithContactsLastGetsAMuchSmallerEnvelope) {
    std::mt19937 rng(71);
    for (int links : {8, 30, 60}) {
        const Island island = winch(links, rng);
        const std::ptrdiff_t original = island.envelope(identity(island.n()));
        for (OrderingKind kind : {OrderingKind::CuthillMcKee, OrderingKind::ReverseCuthillMcKee})
            for (bool use_blocks : {true, false}) {
                const std::vector<int> perm = island.order(kind, use_blocks);
                ASSERT_TRUE(ordering::is_permutation(perm, island.n()));
                EXPECT_LE(island.envelope(perm), original) << links << " links";
                if (links >= 30) {
                    // chain-like: a few blocks per row on average, whatever the length
                    EXPECT_LE(island.envelope(perm), 8 * island.n()) << links << " links";
                    EXPECT_LT(3 * island.envelope(perm), original) << links << " links";
                }
            }
    }
}

TEST(OrderingOrderRows, BlockOrderKeepsEachBlockContiguousAndInOrder) {
    std::mt19937 rng(72);
    const Island island = winch(20, rng);
    const std::vector<int> perm = island.order(OrderingKind::ReverseCuthillMcKee, true);
    ASSERT_TRUE(ordering::is_permutation(perm, island.n()));
    const BlockStructure& b = island.blocks;
    for (int p = 0; p < island.n();) {
        const int row = perm[p];
        const int block = static_cast<int>(std::upper_bound(b.block_row.begin(), b.block_row.end(), row) - b.block_row.begin()) - 1;
        ASSERT_EQ(row, b.block_row[block]) << "a block starts with its first row";
        for (int r = b.block_row[block]; r < b.block_row[block + 1]; ++r, ++p) ASSERT_EQ(perm[p], r);
    }
}

TEST(OrderingOrderRows, InconsistentBlocksFallBackToTheRowGraph) {
    std::mt19937 rng(73);
    const Island island = winch(12, rng);
    const int blocks = island.blocks.num_blocks();
    // every block on a body of its own: the block graph has no edge, so numbering the blocks
    // keeps them in order, which numbering A's rows does not; a fallback shows
    std::vector<int> own_bodies;
    for (int k = 0; k < blocks; ++k) own_bodies.insert(own_bodies.end(), {k, -1});
    const auto order = [&](const std::vector<int>& block_row, const std::vector<int>& block_body) {
        return ordering::order_rows(island.n(), island.rows.data(), island.n(), static_cast<int>(block_row.size()) - 1,
                                    block_row.data(), block_body.data(), OrderingKind::CuthillMcKee, nullptr);
    };
    const auto from_rows = island.order(OrderingKind::CuthillMcKee, false);
    ASSERT_EQ(order(island.blocks.block_row, own_bodies), identity(island.n()));
    ASSERT_NE(from_rows, identity(island.n()));

    std::vector<int> past_the_end = island.blocks.block_row;
    past_the_end.back() += 1;  // claims one row more than A has
    EXPECT_EQ(order(past_the_end, own_bodies), from_rows);
    // an empty block (a repeated block_row entry) breaks the tiling rule too (structure_rules.h)
    std::vector<int> with_empty = island.blocks.block_row;
    with_empty.insert(with_empty.begin() + 1, with_empty[1]);
    std::vector<int> bodies_with_empty = own_bodies;
    bodies_with_empty.insert(bodies_with_empty.end(), {blocks, -1});
    EXPECT_EQ(order(with_empty, bodies_with_empty), from_rows);

    const Island& i = island;
    const std::vector<int> expected = ordering::cuthill_mckee(ordering::graph_from_lower(i.rows.data(), i.n(), i.n()), false);
    EXPECT_EQ(from_rows, expected);
}

TEST(OrderingOrderRows, ReverseKindReversesTheGraphOrder) {
    std::mt19937 rng(75);
    const Island island = winch(15, rng);
    std::vector<int> cm_rows = island.order(OrderingKind::CuthillMcKee, false);
    std::reverse(cm_rows.begin(), cm_rows.end());
    EXPECT_EQ(island.order(OrderingKind::ReverseCuthillMcKee, false), cm_rows);

    const BlockStructure& b = island.blocks;
    const ordering::Graph g = ordering::block_graph(b.num_blocks(), b.block_row.data(), b.block_body.data());
    std::vector<int> cm_blocks = ordering::cuthill_mckee(g, false);
    EXPECT_EQ(island.order(OrderingKind::CuthillMcKee, true), ordering::expand_blocks(cm_blocks, b.block_row.data(), b.num_blocks()));
    std::reverse(cm_blocks.begin(), cm_blocks.end());
    EXPECT_EQ(island.order(OrderingKind::ReverseCuthillMcKee, true),
              ordering::expand_blocks(cm_blocks, b.block_row.data(), b.num_blocks()));
    EXPECT_EQ(island.order(OrderingKind::Identity, true), identity(island.n()));
}

TEST(OrderingOrderRows, PairIsBothKindsFromOneNumbering) {
    std::mt19937 rng(76);
    const Island island = winch(15, rng);
    const BlockStructure& b = island.blocks;
    const auto row_graph = [&island] { return ordering::graph_from_lower(island.rows.data(), island.n(), island.n()); };
    const ordering::OrderPair blocks =
        ordering::cuthill_mckee_pair(island.n(), row_graph, b.num_blocks(), b.block_row.data(), b.block_body.data());
    EXPECT_EQ(blocks.forward, island.order(OrderingKind::CuthillMcKee, true));
    EXPECT_EQ(blocks.reverse, island.order(OrderingKind::ReverseCuthillMcKee, true));
    EXPECT_NE(blocks.forward, blocks.reverse);
    const ordering::OrderPair rows = ordering::cuthill_mckee_pair(island.n(), row_graph, 0, nullptr, nullptr);
    EXPECT_EQ(rows.forward, island.order(OrderingKind::CuthillMcKee, false));
    EXPECT_EQ(rows.reverse, island.order(OrderingKind::ReverseCuthillMcKee, false));
    const ordering::OrderPair none = ordering::cuthill_mckee_pair(island.n(), nullptr, 0, nullptr, nullptr);
    EXPECT_EQ(none.forward, identity(island.n()));
    EXPECT_EQ(none.reverse, identity(island.n()));
}

TEST(OrderingOrderRows, LikelyTightRowsGoLastInTheirOrder) {
    std::mt19937 rng(74);
    const Island island = winch(25, rng);
    const std::vector<char> tight = random_removed(island.n(), 0.2, rng);
    for (OrderingKind kind : {OrderingKind::Identity, OrderingKind::CuthillMcKee, OrderingKind::ReverseCuthillMcKee}) {
        const std::vector<int> plain = island.order(kind, true);
        const std::vector<int> perm = island.order(kind, true, &tight);
        ASSERT_TRUE(ordering::is_permutation(perm, island.n()));
        std::vector<int> expected;
        for (int row : plain)
            if (!tight[row]) expected.push_back(row);
        for (int row : plain)
            if (tight[row]) expected.push_back(row);
        EXPECT_EQ(perm, expected);
    }
}

TEST(OrderingOrderRows, IsPermutationRejectsBadInput) {
    EXPECT_TRUE(ordering::is_permutation({2, 0, 1}, 3));
    EXPECT_FALSE(ordering::is_permutation({2, 0, 0}, 3));
    EXPECT_FALSE(ordering::is_permutation({2, 0, 3}, 3));
    EXPECT_FALSE(ordering::is_permutation({0, 1}, 3));
    EXPECT_FALSE(ordering::is_permutation({0, -1, 1}, 3));
}

TEST(OrderingOrderRows, ExpandBlocksListsRowsBlockByBlock) {
    const std::vector<int> block_row = {0, 2, 2, 5, 6};
    EXPECT_EQ(ordering::expand_blocks({3, 0, 2, 1}, block_row.data(), 4), (std::vector<int>{5, 0, 1, 2, 3, 4}));
}

TEST(OrderingOrderRows, IsPermutationOnEitherSideOfItsStackMarks) {
    for (int n : {0, 1, 7, 511, 512, 513, 2000}) {
        std::vector<int> perm(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) perm[i] = n - 1 - i;
        EXPECT_TRUE(ordering::is_permutation(perm, n)) << n;
        EXPECT_FALSE(ordering::is_permutation(perm, n + 1)) << n;
        if (n < 2) continue;
        std::vector<int> repeated = perm;
        repeated[n / 2] = repeated[0];
        EXPECT_FALSE(ordering::is_permutation(repeated, n)) << n;
        std::vector<int> outside = perm;
        outside[n - 1] = n;
        EXPECT_FALSE(ordering::is_permutation(outside, n)) << n;
        outside[n - 1] = -1;
        EXPECT_FALSE(ordering::is_permutation(outside, n)) << n;
    }
}

}  // namespace
}  // namespace ode_bpp::test
