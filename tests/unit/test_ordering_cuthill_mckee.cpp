// Graph builders and Cuthill-McKee against brute-force definitions and envelope bounds.
#include <gtest/gtest.h>

#include <set>

#include "linalg/envelope.h"
#include "ordering/cuthill_mckee.h"
#include "ordering/graph.h"
#include "ordering/order_rows.h"
#include "test_linalg_support.h"

namespace ode_bpp::test {
namespace {

using ordering::Graph;

std::set<std::pair<int, int>> edge_set(const Graph& g) {
    std::set<std::pair<int, int>> edges;
    for (int v = 0; v < g.n(); ++v)
        for (int e = g.xadj[v]; e < g.xadj[v + 1]; ++e) edges.emplace(v, g.adj[e]);
    return edges;
}

/// Bandwidth and envelope of g's adjacency under perm (perm[new] = old), diagonal excluded.
struct Profile {
    int bandwidth = 0;
    long envelope = 0;
};
Profile profile_under(const Graph& g, const std::vector<int>& perm) {
    const int n = g.n();
    std::vector<int> position(static_cast<std::size_t>(n));
    for (int p = 0; p < n; ++p) position[perm[p]] = p;
    Profile out;
    for (int i = 0; i < n; ++i) {
        int first = i;
        for (int e = g.xadj[perm[i]]; e < g.xadj[perm[i] + 1]; ++e) first = std::min(first, position[g.adj[e]]);
        out.bandwidth = std::max(out.bandwidth, i - first);
        out.envelope += i - first;
    }
    return out;
}

Graph path_graph(const std::vector<int>& labels) {
    std::vector<std::pair<int, int>> edges;
    for (std::size_t a = 0; a + 1 < labels.size(); ++a) edges.emplace_back(labels[a], labels[a + 1]);
    return ordering::graph_from_edges(static_cast<int>(labels.size()), edges);
}

TEST(OrderingGraph, FromLowerMatchesTheNonZeros) {
    std::mt19937 rng(61);
    const int n = 40;
    const MatrixXd A = random_envelope_spd(n, 6, rng);
    const std::vector<double> rows = lower_row_major_poisoned(A, n + 2);
    const Graph g = ordering::graph_from_lower(rows.data(), n + 2, n);
    std::set<std::pair<int, int>> expected;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            if (i != j && A(i, j) != 0.0) expected.emplace(i, j);
    EXPECT_EQ(edge_set(g), expected);
    for (int v = 0; v < n; ++v) EXPECT_TRUE(std::is_sorted(g.adj.begin() + g.xadj[v], g.adj.begin() + g.xadj[v + 1]));
}

TEST(OrderingGraph, BlockGraphLinksBlocksSharingABody) {
    std::mt19937 rng(62);
    BlockStructure blocks;
    for (int b = 0; b < 50; ++b) blocks.add(1 + static_cast<int>(rng() % 3), static_cast<int>(rng() % 20) - 2,
                                            static_cast<int>(rng() % 20) - 2);
    const Graph g = ordering::block_graph(blocks.num_blocks(), blocks.block_row.data(), blocks.block_body.data());
    std::set<std::pair<int, int>> expected;
    for (int a = 0; a < blocks.num_blocks(); ++a)
        for (int b = 0; b < blocks.num_blocks(); ++b) {
            if (a == b) continue;
            bool share = false;
            for (int sa = 0; sa < 2; ++sa)
                for (int sb = 0; sb < 2; ++sb) {
                    const int body = blocks.block_body[2 * a + sa];
                    share = share || (body >= 0 && body == blocks.block_body[2 * b + sb]);
                }
            if (share) expected.emplace(a, b);
        }
    EXPECT_EQ(edge_set(g), expected);
    for (int v = 0; v < g.n(); ++v) EXPECT_TRUE(std::is_sorted(g.adj.begin() + g.xadj[v], g.adj.begin() + g.xadj[v + 1]));
}

/// A block that owns no rows has no entries in A, so it couples nothing, even on a shared body;
/// a block with both sides on one body is adjacent once to each other block on it.
TEST(OrderingGraph, BlockGraphLeavesEmptyBlocksAloneAndRepeatsNoNeighbour) {
    const std::vector<int> block_row = {0, 3, 3, 6, 9};
    const std::vector<int> block_body = {0, 0, 0, 1, 0, 1, 1, -1};
    const Graph g = ordering::block_graph(4, block_row.data(), block_body.data());
    const std::set<std::pair<int, int>> expected = {{0, 2}, {2, 0}, {2, 3}, {3, 2}};
    EXPECT_EQ(edge_set(g), expected);
    EXPECT_EQ(g.adj.size(), expected.size());
}

TEST(OrderingCuthillMcKee, ShuffledPathGetsBandwidthOne) {
    std::mt19937 rng(63);
    for (int trial = 0; trial < 10; ++trial) {
        const int n = 2 + static_cast<int>(rng() % 80);
        const Graph g = path_graph(random_permutation(n, rng));
        for (bool reverse : {false, true}) {
            const std::vector<int> perm = ordering::cuthill_mckee(g, reverse);
            ASSERT_TRUE(ordering::is_permutation(perm, n));
            EXPECT_EQ(profile_under(g, perm).bandwidth, 1);
            EXPECT_EQ(g.degree(perm.front()), 1) << "starts at an end of the path";
        }
    }
}

TEST(OrderingCuthillMcKee, ShuffledLoopGetsBandwidthTwo) {
    std::mt19937 rng(64);
    for (int n : {3, 4, 9, 30, 101}) {
        std::vector<int> labels = random_permutation(n, rng);
        std::vector<std::pair<int, int>> edges;
        for (int a = 0; a < n; ++a) edges.emplace_back(labels[a], labels[(a + 1) % n]);
        const Graph g = ordering::graph_from_edges(n, edges);
        for (bool reverse : {false, true}) {
            const std::vector<int> perm = ordering::cuthill_mckee(g, reverse);
            ASSERT_TRUE(ordering::is_permutation(perm, n));
            EXPECT_LE(profile_under(g, perm).bandwidth, 2);
        }
    }
}

int eccentricity(const Graph& g, int root) {
    std::vector<int> distance(g.n(), -1);
    std::vector<int> queue{root};
    distance[root] = 0;
    for (std::size_t head = 0; head < queue.size(); ++head)
        for (int e = g.xadj[queue[head]]; e < g.xadj[queue[head] + 1]; ++e)
            if (distance[g.adj[e]] < 0) {
                distance[g.adj[e]] = distance[queue[head]] + 1;
                queue.push_back(g.adj[e]);
            }
    return *std::max_element(distance.begin(), distance.end());
}

TEST(OrderingCuthillMcKee, StartsAtAPeripheralVertexOfATree) {
    // On a tree, George & Liu's iteration reaches an end of a diameter: the start vertex's
    // eccentricity equals the diameter. Random trees, plus a long path with a pendant vertex at
    // its middle labelled 0 (minimal degree and lowest label, but not peripheral).
    std::mt19937 rng(68);
    for (int trial = 0; trial < 20; ++trial) {
        const int n = 5 + static_cast<int>(rng() % 60);
        std::vector<std::pair<int, int>> edges;
        if (trial == 0) {
            for (int v = 1; v + 1 < n; ++v) edges.emplace_back(v, v + 1);
            edges.emplace_back(0, n / 2);
        } else {
            for (int v = 1; v < n; ++v) edges.emplace_back(v, static_cast<int>(rng() % v));
        }
        const Graph g = ordering::graph_from_edges(n, edges);
        int diameter = 0;
        for (int v = 0; v < n; ++v) diameter = std::max(diameter, eccentricity(g, v));
        const std::vector<int> perm = ordering::cuthill_mckee(g, false);
        EXPECT_EQ(eccentricity(g, perm.front()), diameter) << "trial " << trial;
        EXPECT_EQ(ordering::cuthill_mckee(g, true).back(), perm.front());
    }
}

TEST(OrderingCuthillMcKee, IsABreadthFirstOrderByIncreasingDegree) {
    std::mt19937 rng(65);
    for (int trial = 0; trial < 10; ++trial) {
        const int n = 60;
        std::vector<std::pair<int, int>> edges;
        for (int v = 1; v < n; ++v) edges.emplace_back(v, static_cast<int>(rng() % v));  // a random tree
        for (int e = 0; e < 15; ++e) edges.emplace_back(static_cast<int>(rng() % n), static_cast<int>(rng() % n));
        const Graph g = ordering::graph_from_edges(n, edges);
        const std::vector<int> perm = ordering::cuthill_mckee(g, false);
        ASSERT_TRUE(ordering::is_permutation(perm, n));
        std::vector<int> position(n);
        for (int p = 0; p < n; ++p) position[perm[p]] = p;
        // Each vertex after the first is numbered from its earliest numbered neighbour (its BFS
        // parent); children of one parent come by non-decreasing degree, parents in order.
        std::vector<std::pair<int, int>> parent_and_degree;
        for (int p = 1; p < n; ++p) {
            int parent = n;
            for (int e = g.xadj[perm[p]]; e < g.xadj[perm[p] + 1]; ++e) parent = std::min(parent, position[g.adj[e]]);
            ASSERT_LT(parent, p);
            parent_and_degree.emplace_back(parent, g.degree(perm[p]));
        }
        EXPECT_TRUE(std::is_sorted(parent_and_degree.begin(), parent_and_degree.end()));
    }
}

TEST(OrderingCuthillMcKee, TreesAndChainsOfBlocksShrinkTheirEnvelope) {
    // Block graphs of chains and trees of bodies, with the blocks listed in a shuffled order
    // (the worst case): the row-level envelope of A must not grow, and the reversed order's
    // envelope is never larger than Cuthill-McKee's (Liu & Sherman 1976).
    std::mt19937 rng(66);
    for (int trial = 0; trial < 12; ++trial) {
        BlockStructure tree;
        const int bodies = 10 + static_cast<int>(rng() % 40);
        for (int body = 1; body < bodies; ++body)
            tree.add(1 + static_cast<int>(rng() % 6), body, trial % 2 ? body - 1 : static_cast<int>(rng() % body));
        if (trial % 3 == 0) tree.add(3, 0, bodies - 1);  // closes a loop
        const BlockStructure blocks = tree.reordered(random_permutation(tree.num_blocks(), rng));
        const MatrixXd A = constraint_matrix(blocks, rng);
        const int n = blocks.rows();
        const std::vector<double> rows = lower_row_major_poisoned(A, n);
        const auto envelope = [&](const std::vector<int>& perm) {
            return linalg::envelope_size(linalg::row_profile(rows.data(), n, n, perm.data()));
        };
        const Graph g = ordering::block_graph(blocks.num_blocks(), blocks.block_row.data(), blocks.block_body.data());
        std::vector<int> original(n);
        std::iota(original.begin(), original.end(), 0);
        const auto cm = ordering::expand_blocks(ordering::cuthill_mckee(g, false), blocks.block_row.data(), blocks.num_blocks());
        const auto rcm = ordering::expand_blocks(ordering::cuthill_mckee(g, true), blocks.block_row.data(), blocks.num_blocks());
        ASSERT_TRUE(ordering::is_permutation(cm, n));
        ASSERT_TRUE(ordering::is_permutation(rcm, n));
        EXPECT_LE(envelope(cm), envelope(original)) << "trial " << trial;
        EXPECT_LE(envelope(rcm), envelope(original)) << "trial " << trial;
        EXPECT_LE(profile_under(g, ordering::cuthill_mckee(g, true)).envelope,
                  profile_under(g, ordering::cuthill_mckee(g, false)).envelope);
    }
}

TEST(OrderingCuthillMcKee, OrdersEveryComponentContiguously) {
    std::mt19937 rng(67);
    // A shuffled path of 10, a shuffled loop of 7, and 5 isolated vertices, labels mixed.
    const int n = 22;
    const std::vector<int> label = random_permutation(n, rng);
    std::vector<std::pair<int, int>> edges;
    for (int a = 0; a + 1 < 10; ++a) edges.emplace_back(label[a], label[a + 1]);
    for (int a = 0; a < 7; ++a) edges.emplace_back(label[10 + a], label[10 + (a + 1) % 7]);
    const Graph g = ordering::graph_from_edges(n, edges);
    std::vector<int> component(n);
    for (int a = 0; a < n; ++a) component[label[a]] = a < 10 ? 0 : a < 17 ? 1 : 2 + a;
    for (bool reverse : {false, true}) {
        const std::vector<int> perm = ordering::cuthill_mckee(g, reverse);
        ASSERT_TRUE(ordering::is_permutation(perm, n));
        int changes = 0;
        for (int p = 1; p < n; ++p) changes += component[perm[p]] != component[perm[p - 1]];
        EXPECT_EQ(changes, 2 + 5 - 1) << "each component occupies one contiguous range";
        EXPECT_LE(profile_under(g, perm).bandwidth, 2);
    }
}

}  // namespace
}  // namespace ode_bpp::test
