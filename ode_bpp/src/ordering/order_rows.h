// The row ordering used before factoring (paper Sec. 3.4 and its future-work section).
#pragma once

#include <functional>
#include <vector>

#include "ordering/graph.h"

namespace ode_bpp::ordering {

enum class OrderingKind {
    Identity,             ///< keep the caller's order
    CuthillMcKee,         ///< Cuthill-McKee on the constraint graph (the paper's choice)
    ReverseCuthillMcKee,  ///< its reverse (never a larger envelope)
};

/// True when perm holds each of 0 .. n-1 exactly once.
bool is_permutation(const std::vector<int>& perm, int n);

/// Row permutation (perm[new] = old) that lists the rows of block block_perm[0], then of
/// block_perm[1], ..., each block's rows contiguous and in their original order.
/// block_row: num_blocks + 1 offsets, block k owns rows block_row[k] .. block_row[k+1]-1.
std::vector<int> expand_blocks(const std::vector<int>& block_perm, const int* block_row, int num_blocks);

/// Moves the rows flagged in `flagged` (n flags, original row indices) to the end of perm
/// (perm[new] = old), both groups keeping their relative order.
void move_flagged_last(std::vector<int>& perm, const std::vector<char>& flagged);

/// The symmetric permutation to factor A in: perm[new] = old, n entries.
/// Graph: the block (constraint) graph when block_row and block_body are given and consistent
/// (block_row[0] == 0, non-decreasing, block_row[num_blocks] == n; see block_graph), else the row
/// graph of A's lower triangle (A n x n row-major, stride lda; may be null only with blocks or
/// for Identity). likely_tight: n flags in original row indices, or null; flagged rows are moved
/// to the end of the order, both groups keeping their relative order (the paper's future work:
/// rows deleted late in the order make deletion cheap).
std::vector<int> order_rows(int n, const double* A, int lda, int num_blocks, const int* block_row,
                            const int* block_body, OrderingKind kind, const std::vector<char>* likely_tight);

/// Cuthill-McKee and reverse Cuthill-McKee (perm[new] = old each) from one numbering of the
/// graph: the reverse numbering is the forward one read backwards (cuthill_mckee.h), so the
/// pair costs one ordering. Graph and fallbacks as order_rows below; no rows moved.
struct OrderPair {
    std::vector<int> forward;
    std::vector<int> reverse;
};
OrderPair cuthill_mckee_pair(int n, const std::function<Graph()>& row_graph, int num_blocks, const int* block_row,
                             const int* block_body);

/// The same with the row graph of A from a callable, called only when the blocks are not usable
/// (e.g. graph_from_rows of a sparse A); null: the identity then.
std::vector<int> order_rows(int n, const std::function<Graph()>& row_graph, int num_blocks, const int* block_row,
                            const int* block_body, OrderingKind kind, const std::vector<char>* likely_tight);

}  // namespace ode_bpp::ordering
