#include "ordering/order_rows.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <utility>

#include "ordering/cuthill_mckee.h"
#include "ordering/graph.h"
#include "structure_rules.h"

namespace ode_bpp::ordering {

namespace {

std::vector<int> identity_order(int n) {
    std::vector<int> perm(static_cast<std::size_t>(n));
    std::iota(perm.begin(), perm.end(), 0);
    return perm;
}

}  // namespace

void move_flagged_last(std::vector<int>& perm, const std::vector<char>& flagged) {
    std::stable_partition(perm.begin(), perm.end(), [&flagged](int old) { return flagged[old] == 0; });
}

bool is_permutation(const std::vector<int>& perm, int n) {
    if (static_cast<int>(perm.size()) != n) return false;
    // the hook asks once per island: an island of up to kMarksOnStack rows allocates nothing
    constexpr int kMarksOnStack = 512;
    std::array<char, kMarksOnStack> on_stack;
    std::vector<char> on_heap;
    char* seen = on_stack.data();
    if (n > kMarksOnStack) {
        on_heap.resize(static_cast<std::size_t>(n));
        seen = on_heap.data();
    }
    std::fill_n(seen, n, 0);
    for (int v : perm) {
        if (v < 0 || v >= n || seen[v]) return false;
        seen[v] = 1;
    }
    return true;
}

std::vector<int> expand_blocks(const std::vector<int>& block_perm, const int* block_row, int num_blocks) {
    std::vector<int> perm;
    perm.reserve(static_cast<std::size_t>(block_row[num_blocks]));
    for (int block : block_perm)
        for (int row = block_row[block]; row < block_row[block + 1]; ++row) perm.push_back(row);
    return perm;
}

OrderPair cuthill_mckee_pair(int n, const std::function<Graph()>& row_graph, int num_blocks, const int* block_row,
                             const int* block_body) {
    OrderPair pair;
    if (blocks_tile_rows(n, num_blocks, block_row, block_body)) {  // numbering the blocks numbers the rows
        std::vector<int> blocks = cuthill_mckee(block_graph(num_blocks, block_row, block_body), false);
        pair.forward = expand_blocks(blocks, block_row, num_blocks);
        std::reverse(blocks.begin(), blocks.end());
        pair.reverse = expand_blocks(blocks, block_row, num_blocks);
        return pair;
    }
    pair.forward = row_graph ? cuthill_mckee(row_graph(), false) : identity_order(n);
    pair.reverse = pair.forward;
    if (row_graph) std::reverse(pair.reverse.begin(), pair.reverse.end());
    return pair;
}

std::vector<int> order_rows(int n, const std::function<Graph()>& row_graph, int num_blocks, const int* block_row,
                            const int* block_body, OrderingKind kind, const std::vector<char>* likely_tight) {
    std::vector<int> perm;
    if (kind == OrderingKind::Identity) {
        perm = identity_order(n);
    } else {
        OrderPair pair = cuthill_mckee_pair(n, row_graph, num_blocks, block_row, block_body);
        perm = std::move(kind == OrderingKind::ReverseCuthillMcKee ? pair.reverse : pair.forward);
    }
    if (likely_tight != nullptr) move_flagged_last(perm, *likely_tight);
    return perm;
}

std::vector<int> order_rows(int n, const double* A, int lda, int num_blocks, const int* block_row,
                            const int* block_body, OrderingKind kind, const std::vector<char>* likely_tight) {
    std::function<Graph()> row_graph;
    if (A != nullptr) row_graph = [=] { return graph_from_lower(A, lda, n); };
    return order_rows(n, row_graph, num_blocks, block_row, block_body, kind, likely_tight);
}

}  // namespace ode_bpp::ordering
