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

Graph block_graph(int num_blocks, const int* block_row, const int* block_body) {
    // (body, block) incidences grouped by body: every two blocks on one body are adjacent.
    std::vector<std::pair<int, int>> incidences;
    for (int block = 0; block < num_blocks; ++block) {
        if (block_row && block_row[block + 1] == block_row[block]) continue;
        for (int side = 0; side < 2; ++side) {
            const int body = block_body[2 * block + side];
            if (body >= 0) incidences.emplace_back(body, block);
        }
    }
    std::sort(incidences.begin(), incidences.end());
    std::vector<std::pair<int, int>> edges;
    for (std::size_t begin = 0; begin < incidences.size();) {
        std::size_t end = begin;
        while (end < incidences.size() && incidences[end].first == incidences[begin].first) ++end;
        for (std::size_t a = begin; a < end; ++a)
            for (std::size_t b = a + 1; b < end; ++b) edges.emplace_back(incidences[a].second, incidences[b].second);
        begin = end;
    }
    return graph_from_edges(num_blocks, std::move(edges));
}

}  // namespace ode_bpp::ordering
