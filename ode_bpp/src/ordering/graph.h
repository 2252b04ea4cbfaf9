// Undirected graphs for the fill-reducing ordering (paper Sec. 3.4: Cuthill-McKee on the
// constraint graph).
#pragma once

#include <utility>
#include <vector>

namespace ode_bpp::linalg {
class SymmetricRows;
}

namespace ode_bpp::ordering {

/// Undirected graph in compressed adjacency form: the neighbours of v are
/// adj[xadj[v] .. xadj[v+1]-1], sorted increasingly, each edge stored in both directions,
/// no self loops, no duplicates.
struct Graph {
    std::vector<int> xadj;  ///< n + 1
    std::vector<int> adj;   ///< 2 * edges
    int n() const { return xadj.empty() ? 0 : static_cast<int>(xadj.size()) - 1; }
    int degree(int v) const { return xadj[v + 1] - xadj[v]; }
};

/// Builds a Graph on n vertices from an edge list (pairs (a, b), either order; self loops and
/// repeated edges are dropped).
Graph graph_from_edges(int n, std::vector<std::pair<int, int>> edges);

/// The row graph of a symmetric matrix: rows i != j adjacent iff A(i,j) != 0, read from the
/// lower triangle (j < i) of row-major A (n x n, row stride lda). Original row indices.
Graph graph_from_lower(const double* A, int lda, int n);

/// The same from compressed symmetric rows (its stored off-diagonal entries). O(n + nnz).
Graph graph_from_rows(const linalg::SymmetricRows& A);

/// The constraint graph on blocks (one block per joint): blocks a != b adjacent iff they share a
/// body index >= 0. block_body: 2 * num_blocks entries, the two bodies of block k at [2k], [2k+1],
/// -1 for the static environment (which couples nothing). block_row: num_blocks + 1 row offsets
/// or null; when given, a block owning no rows gets no edges (it has no entries in A).
Graph block_graph(int num_blocks, const int* block_row, const int* block_body);

/// The row profile, in the order perm (perm[new] = old, n entries), of a symmetric matrix with
/// the blocks' structural pattern: block (a, b) whole where a == b or a and b share a body >= 0
/// (block_graph's edges), every other entry zero. Returns first (new index space, n entries):
/// first[i] <= i, the first column of row i's lower envelope (linalg::SkylineShape's row
/// profile). Blocks as block_graph's with block_row given, tiling rows 0 .. n-1 in order.
/// O(n + blocks + bodies), without the graph's edges.
std::vector<int> block_row_profile(int num_blocks, const int* block_row, const int* block_body,
                                   const std::vector<int>& perm);

}  // namespace ode_bpp::ordering
