#include "ordering/graph.h"

#include <algorithm>
#include <cstddef>
#include <utility>

#include "linalg/symmetric_rows.h"

namespace ode_bpp::ordering {

Graph graph_from_edges(int n, std::vector<std::pair<int, int>> edges) {
    std::vector<std::pair<int, int>> arcs;
    arcs.reserve(2 * edges.size());
    for (const auto& [a, b] : edges) {
        if (a == b) continue;
        arcs.emplace_back(a, b);
        arcs.emplace_back(b, a);
    }
    std::sort(arcs.begin(), arcs.end());
    arcs.erase(std::unique(arcs.begin(), arcs.end()), arcs.end());
    Graph g;
    g.xadj.assign(static_cast<std::size_t>(n) + 1, 0);
    g.adj.reserve(arcs.size());
    for (const auto& [from, to] : arcs) {
        ++g.xadj[from + 1];
        g.adj.push_back(to);
    }
    for (int v = 0; v < n; ++v) g.xadj[v + 1] += g.xadj[v];
    return g;
}

Graph graph_from_lower(const double* A, int lda, int n) {
    std::vector<std::pair<int, int>> edges;
    for (int i = 0; i < n; ++i) {
        const double* row = A + static_cast<std::ptrdiff_t>(i) * lda;
        for (int j = 0; j < i; ++j)
            if (row[j] != 0.0) edges.emplace_back(i, j);
    }
    return graph_from_edges(n, std::move(edges));
}

Graph graph_from_rows(const linalg::SymmetricRows& A) {
    Graph g;
    g.xadj.assign(static_cast<std::size_t>(A.n()) + 1, 0);
    g.adj.reserve(static_cast<std::size_t>(A.off_diagonal_entries()));
    for (int i = 0; i < A.n(); ++i) {
        for (int k = A.row_begin(i); k < A.row_end(i); ++k) g.adj.push_back(A.col(k));
        g.xadj[i + 1] = static_cast<int>(g.adj.size());
    }
    return g;  // rows are sorted by column, both directions stored, no diagonal: a Graph as is
}

namespace {

/// Appends to adj the union of two ascending runs of block indices, ascending and without
/// repeats, leaving out `self`.
void merge_runs(const std::pair<int, int>* a, const std::pair<int, int>* a_end, const std::pair<int, int>* b,
                const std::pair<int, int>* b_end, int self, std::vector<int>& adj) {
    int last = -1;
    while (a != a_end || b != b_end) {
        const bool take_a = b == b_end || (a != a_end && a->second <= b->second);
        const int block = take_a ? (a++)->second : (b++)->second;
        if (block != self && block != last) adj.push_back(block);
        last = block;
    }
}

}  // namespace

Graph block_graph(int num_blocks, const int* block_row, const int* block_body) {
    // (body, block) incidences, sorted: each body's blocks form one run, in increasing order.
    // A block's neighbours are the union of its two bodies' runs, so the adjacency comes out
    // sorted without listing each body's clique of edges (O(sum of run lengths over blocks)).
    std::vector<std::pair<int, int>> incidences;
    incidences.reserve(2 * static_cast<std::size_t>(num_blocks));
    for (int block = 0; block < num_blocks; ++block) {
        if (block_row && block_row[block + 1] == block_row[block]) continue;
        for (int side = 0; side < 2; ++side) {
            const int body = block_body[2 * block + side];
            if (body >= 0) incidences.emplace_back(body, block);
        }
    }
    std::sort(incidences.begin(), incidences.end());
    // runs[2 block + k]: the run of the block's k-th incidence, as [begin, end) into incidences
    std::vector<std::pair<int, int>> runs(2 * static_cast<std::size_t>(num_blocks), {0, 0});
    std::vector<char> filled(static_cast<std::size_t>(num_blocks), 0);
    for (std::size_t begin = 0; begin < incidences.size();) {
        std::size_t end = begin;
        while (end < incidences.size() && incidences[end].first == incidences[begin].first) ++end;
        for (std::size_t k = begin; k < end; ++k) {
            const int block = incidences[k].second;
            runs[2 * block + filled[block]++] = {static_cast<int>(begin), static_cast<int>(end)};
        }
        begin = end;
    }
    Graph g;
    g.xadj.assign(static_cast<std::size_t>(num_blocks) + 1, 0);
    const std::pair<int, int>* at = incidences.data();
    for (int block = 0; block < num_blocks; ++block) {
        const auto [a, a_end] = runs[2 * block];
        const auto [b, b_end] = runs[2 * block + 1];
        merge_runs(at + a, at + a_end, at + b, at + b_end, block, g.adj);
        g.xadj[block + 1] = static_cast<int>(g.adj.size());
    }
    return g;
}

std::vector<int> block_row_profile(int num_blocks, const int* block_row, const int* block_body,
                                   const std::vector<int>& perm) {
    const int n = static_cast<int>(perm.size());
    std::vector<int> position(perm.size());
    for (int k = 0; k < n; ++k) position[perm[k]] = k;
    int bodies = 0;
    for (int k = 0; k < 2 * num_blocks; ++k) bodies = std::max(bodies, block_body[k] + 1);
    // block_first: each block's earliest row; body_first: the earliest row of the blocks on a body
    std::vector<int> block_first(static_cast<std::size_t>(num_blocks), n);
    std::vector<int> body_first(static_cast<std::size_t>(bodies), n);
    for (int block = 0; block < num_blocks; ++block) {
        for (int row = block_row[block]; row < block_row[block + 1]; ++row)
            block_first[block] = std::min(block_first[block], position[row]);
        for (int side = 0; side < 2; ++side)
            if (const int body = block_body[2 * block + side]; body >= 0)
                body_first[body] = std::min(body_first[body], block_first[block]);
    }
    // a row couples with every row of its own block and of the blocks on either of its bodies
    std::vector<int> first(perm.size());
    for (int block = 0; block < num_blocks; ++block) {
        int earliest = block_first[block];
        for (int side = 0; side < 2; ++side)
            if (const int body = block_body[2 * block + side]; body >= 0)
                earliest = std::min(earliest, body_first[body]);
        for (int row = block_row[block]; row < block_row[block + 1]; ++row) first[position[row]] = earliest;
    }
    return first;
}

}  // namespace ode_bpp::ordering
