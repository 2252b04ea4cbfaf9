#include "linalg/symmetric_rows.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>

#include "ordering/graph.h"
#include "structure_rules.h"

namespace ode_bpp::linalg {

std::vector<int> inverse_permutation(const std::vector<int>& perm) {
    std::vector<int> inverse(perm.size());
    for (std::size_t i = 0; i < perm.size(); ++i) inverse[perm[i]] = static_cast<int>(i);
    return inverse;
}

SymmetricRows::SymmetricRows(const Problem& p, const std::vector<int>& perm) { assign(p, perm); }

namespace {

/// block_of[i]: the block of row i, when p's blocks tile its rows (blocks_tile_rows); false,
/// block_of untouched, when p has no blocks or they do not tile.
bool mark_block_rows(const Problem& p, std::vector<int>& block_of) {
    if (!blocks_tile_rows(p.n, p.num_blocks, p.block_row, p.block_body)) return false;
    block_of.resize(static_cast<std::size_t>(p.n));
    for (int k = 0; k < p.num_blocks; ++k) std::fill(block_of.begin() + p.block_row[k], block_of.begin() + p.block_row[k + 1], k);
    return true;
}

/// coupled[q] = 1 for the blocks q <= k whose entries against block k are A's structure: k itself,
/// and its neighbours in the constraint graph (blocks that share a body with it).
void mark_coupled_blocks(const ordering::Graph& blocks, int k, std::vector<char>& coupled) {
    coupled.assign(static_cast<std::size_t>(blocks.n()), 0);
    for (int e = blocks.xadj[k]; e < blocks.xadj[k + 1] && blocks.adj[e] < k; ++e) coupled[blocks.adj[e]] = 1;
    coupled[k] = 1;
}

/// True when a[0 .. 4) are all zero, of either sign: one test for four entries of a row that is
/// mostly zeros (a dense island's A: 89 % on the forwarder).
bool four_zeros(const double* a) {
    std::uint64_t bits[4];
    std::memcpy(bits, a, sizeof bits);
    return ((bits[0] | bits[1] | bits[2] | bits[3]) << 1) == 0;  // the sign bits shifted out
}

/// Appends row i's strictly lower entries A(i, j), j in [from, to) (original space), to lower in
/// the new numbering to_new, in increasing j: every one when `all` (a coupled block: A's
/// structure, zeros included), else the non-zeros only (a NaN is one).
void append_row_run(const double* row, int i, int from, int to, bool all, const std::vector<int>& to_new,
                    std::vector<LowerEntry>& lower) {
    const int a = to_new[i];
    const auto append = [&](int j) {
        const int b = to_new[j];
        lower.push_back(a > b ? LowerEntry{a, b, row[j]} : LowerEntry{b, a, row[j]});
    };
    if (all) {
        for (int j = from; j < to; ++j) append(j);
        return;
    }
    for (int j = from; j < to;) {
        if (j + 4 <= to && four_zeros(row + j)) {
            j += 4;
            continue;
        }
        if (row[j] != 0) append(j);
        ++j;
    }
}

}  // namespace

void SymmetricRows::assign(const Problem& p, const std::vector<int>& perm) {
    if (p.sparse != nullptr) {
        const std::vector<int>& stored = p.sparse->order();
        if (perm.empty() && stored.empty()) {
            *this = *p.sparse;
            return;
        }
        std::vector<int>& from_stored = build_.count;  // perm in the stored order: stored^-1 o perm
        from_stored.resize(static_cast<std::size_t>(p.n));
        std::vector<int>& to_stored = build_.next;
        to_stored.resize(static_cast<std::size_t>(p.n));
        for (int i = 0; i < p.n; ++i) to_stored[p.sparse->built_row(i)] = i;
        for (int i = 0; i < p.n; ++i) from_stored[i] = to_stored[perm.empty() ? i : perm[i]];
        p.sparse->permute_into(from_stored, *this);
        return;
    }
    std::vector<int>& to_new = build_.to_new;
    std::vector<LowerEntry>& lower = build_.lower;  // one pass over the dense triangle; A is mostly zeros
    to_new.resize(static_cast<std::size_t>(p.n));
    if (perm.empty()) std::iota(to_new.begin(), to_new.end(), 0);
    else
        for (int i = 0; i < p.n; ++i) to_new[perm[i]] = i;
    std::vector<double>& diagonal = build_.diagonal;
    diagonal.assign(static_cast<std::size_t>(p.n), 0.0);
    lower.clear();
    const bool structural = mark_block_rows(p, build_.block_of);
    const ordering::Graph blocks = structural ? ordering::block_graph(p.num_blocks, p.block_row, p.block_body)
                                              : ordering::Graph{};
    std::vector<char>& coupled = build_.coupled;  // coupled[q]: block q couples with row i's block
    for (int i = 0; i < p.n; ++i) {
        const double* row = p.A + static_cast<std::ptrdiff_t>(i) * p.lda;
        diagonal[to_new[i]] = row[i];
        if (!structural) {
            append_row_run(row, i, 0, i, false, to_new, lower);
            continue;
        }
        // the row in runs of consecutive blocks alike (the blocks tile the rows in order): the
        // coupled blocks' runs whole, the others' non-zeros; the entries in increasing column
        const int own = build_.block_of[i];
        if (i == 0 || own != build_.block_of[i - 1]) mark_coupled_blocks(blocks, own, coupled);
        for (int q = 0; q <= own;) {
            int end = q + 1;
            while (end <= own && coupled[end] == coupled[q]) ++end;
            append_row_run(row, i, p.block_row[q], std::min(p.block_row[end], i), coupled[q] != 0, to_new, lower);
            q = end;
        }
    }
    if (!perm.empty())  // assign_lower wants rows in order; a permutation scrambles them
        std::sort(lower.begin(), lower.end(),
                  [](const LowerEntry& x, const LowerEntry& y) { return x.row != y.row ? x.row < y.row : x.col < y.col; });
    assign_lower(diagonal, lower);
    order_ = perm;
}

void SymmetricRows::assign_lower(std::vector<double>& diagonal, const std::vector<LowerEntry>& lower) {
    n_ = static_cast<int>(diagonal.size());
    order_.clear();
    diag_.swap(diagonal);
    std::vector<int>& count = build_.count;
    count.assign(static_cast<std::size_t>(n_), 0);
    profile_.resize(static_cast<std::size_t>(n_));
    std::iota(profile_.begin(), profile_.end(), 0);
    for (const LowerEntry& e : lower) {
        ++count[e.row];
        ++count[e.col];
        profile_[e.row] = std::min(profile_[e.row], e.col);
    }
    profile_known_ = true;
    // row-major order of `lower` fills each row with increasing columns: A(r, j < r) while the
    // sweep is at row r, then A(i > r, r) as it passes the later rows i
    fill_rows(lower, [](int i) { return i; });
}

void SymmetricRows::assign_lower(const std::vector<double>& diagonal, const std::vector<LowerEntry>& lower,
                                 const std::vector<int>& order) {
    n_ = static_cast<int>(diagonal.size());
    order_ = order;
    std::vector<int>&to_new = build_.to_new, &count = build_.count;
    to_new.resize(order.size());
    for (int i = 0; i < n_; ++i) to_new[order[i]] = i;
    diag_.resize(diagonal.size());
    count.assign(static_cast<std::size_t>(n_), 0);
    for (int i = 0; i < n_; ++i) diag_[i] = diagonal[order[i]];
    profile_.resize(order.size());
    std::iota(profile_.begin(), profile_.end(), 0);
    for (const LowerEntry& e : lower) {
        const int r = to_new[e.row], c = to_new[e.col];
        ++count[r];
        ++count[c];
        if (c < r) profile_[r] = std::min(profile_[r], c);
        else profile_[c] = std::min(profile_[c], r);
    }
    profile_known_ = true;
    // as in the unordered assign_lower, each row fills with increasing built columns: the order
    // in which permute_into would have copied it
    fill_rows(lower, [&to_new](int i) { return to_new[i]; });
}

template <class ToNew>
void SymmetricRows::fill_rows(const std::vector<LowerEntry>& lower, ToNew to_new) {
    const std::vector<int>& count = build_.count;
    std::vector<int>& next = build_.next;
    rowptr_.assign(static_cast<std::size_t>(n_) + 1, 0);
    for (int i = 0; i < n_; ++i) rowptr_[i + 1] = rowptr_[i] + count[i];
    col_.resize(static_cast<std::size_t>(rowptr_[n_]));
    val_.resize(col_.size());
    next.assign(rowptr_.begin(), rowptr_.end() - 1);
    std::vector<int>& positions = build_.positions;
    positions.resize(2 * lower.size());
    int* position = positions.data();
    for (const LowerEntry& e : lower) {
        const int r = to_new(e.row), c = to_new(e.col);
        *position++ = next[r];
        col_[next[r]] = c;
        val_[next[r]++] = e.value;
        *position++ = next[c];
        col_[next[c]] = r;
        val_[next[c]++] = e.value;
    }
}

void SymmetricRows::to_dense_lower(double* A, int lda) const {
    for (int i = 0; i < n_; ++i) std::fill(A + static_cast<std::ptrdiff_t>(i) * lda, A + static_cast<std::ptrdiff_t>(i) * lda + i, 0.0);
    for (int i = 0; i < n_; ++i) {
        const int r = built_row(i);
        double* row = A + static_cast<std::ptrdiff_t>(r) * lda;
        row[r] = diag_[i];
        for (int k = rowptr_[i]; k < rowptr_[i + 1]; ++k)
            if (built_row(col_[k]) < r) row[built_row(col_[k])] = val_[k];
    }
}

const SymmetricRows& SymmetricRows::in_built_order(SymmetricRows& out) const {
    if (order_.empty()) return *this;
    permute_into(inverse_permutation(order_), out);
    return out;
}

SymmetricRows SymmetricRows::permuted(const std::vector<int>& perm) const {
    SymmetricRows out;
    permute_into(perm, out);
    return out;
}

void SymmetricRows::permute_into(const std::vector<int>& perm, SymmetricRows& out) const {
    std::vector<int>& to_new = out.build_.to_new;
    to_new.resize(perm.size());
    for (std::size_t i = 0; i < perm.size(); ++i) to_new[perm[i]] = static_cast<int>(i);
    out.n_ = n_;
    out.profile_known_ = false;
    out.order_.resize(perm.size());
    bool identity = true;
    for (std::size_t i = 0; i < perm.size(); ++i) {
        out.order_[i] = built_row(perm[i]);
        identity = identity && out.order_[i] == static_cast<int>(i);
    }
    if (identity) out.order_.clear();
    out.diag_.resize(diag_.size());
    out.rowptr_.assign(rowptr_.size(), 0);
    for (int i = 0; i < n_; ++i) {
        out.diag_[i] = diag_[perm[i]];
        out.rowptr_[i + 1] = out.rowptr_[i] + (row_end(perm[i]) - row_begin(perm[i]));
    }
    out.col_.resize(col_.size());
    out.val_.resize(val_.size());
    for (int i = 0; i < n_; ++i) {
        int dst = out.rowptr_[i];
        for (int k = row_begin(perm[i]); k < row_end(perm[i]); ++k, ++dst) {
            out.col_[dst] = to_new[col_[k]];
            out.val_[dst] = val_[k];
        }
    }
}

double SymmetricRows::max_diag() const {
    return diag_.empty() ? 0.0 : *std::max_element(diag_.begin(), diag_.end());
}

void SymmetricRows::multiply(const std::vector<double>& x, double shift, std::vector<double>& y) const {
    y.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) {
        double sum = (diag_[i] + shift) * x[i];
        for (int k = rowptr_[i]; k < rowptr_[i + 1]; ++k) sum += val_[k] * x[col_[k]];
        y[i] = sum;
    }
}

void SymmetricRows::abs_multiply(const std::vector<double>& x, double shift, std::vector<double>& y) const {
    y.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) {
        double sum = std::abs((diag_[i] + shift) * x[i]);
        for (int k = rowptr_[i]; k < rowptr_[i + 1]; ++k) sum += std::abs(val_[k] * x[col_[k]]);
        y[i] = sum;
    }
}

void SymmetricRows::multiply_with_scale(const double* x, double shift, double* y, double* scale) const {
    for (int i = 0; i < n_; ++i) row_with_scale(i, x, shift, y[i], scale[i]);
}

std::vector<int> SymmetricRows::row_profile() const {
    std::vector<int> first;
    row_profile(first);
    return first;
}

void SymmetricRows::row_profile(std::vector<int>& first) const {
    if (profile_known_) {
        first = profile_;
        return;
    }
    first.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) {
        first[i] = i;
        for (int k = rowptr_[i]; k < rowptr_[i + 1]; ++k) first[i] = std::min(first[i], col_[k]);
    }
}

std::vector<int> SymmetricRows::row_profile_under(const std::vector<int>& perm) const {
    const std::vector<int> to_new = inverse_permutation(perm);
    std::vector<int> first(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) first[i] = first_under(perm[i], to_new);
    return first;
}

std::vector<int> SymmetricRows::row_profile_ranked(const std::vector<int>& perm, const std::vector<unsigned char>& rank,
                                                   const std::vector<int>& first) const {
    const std::vector<int> to_new = inverse_permutation(perm);
    std::vector<int> moved_first(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) {
        const int row = perm[i];
        const int f = first[row];
        moved_first[i] = rank[row] == 0 && rank[f] == 0 ? to_new[f] : first_under(row, to_new);
    }
    return moved_first;
}

}  // namespace ode_bpp::linalg
