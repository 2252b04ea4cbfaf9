#include "linalg/skyline_cholesky.h"
#include "linalg/kernel_clones.h"
#include "linalg/short_update.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace ode_bpp::linalg {

namespace {

bool is_removed(const std::vector<char>& removed, int k) { return !removed.empty() && removed[k] != 0; }

/// L(r, j) = 0 for every stored j < r.
void zero_row(SkylineMatrix& L, int r) {
    for (int j = L.shape().first_column_holding(r); j < r; ++j) L.at(r, j) = 0.0;
}

void make_identity_column(SkylineMatrix& L, int k) {
    double* column = L.column(k);
    column[0] = 1.0;
    std::fill(column + 1, column + L.shape().height(k), 0.0);
}

#ifndef NDEBUG
bool is_identity_row_column(const SkylineMatrix& L, int k) {
    for (int r = k + 1; r <= L.sky(k); ++r)
        if (L.at(r, k) != 0.0) return false;
    for (int j = L.shape().first_column_holding(k); j < k; ++j)
        if (L.at(k, j) != 0.0) return false;
    return L.at(k, k) == 1.0;
}
#endif

/// Zeroing the removed rows up front makes every later update of a removed row exactly zero
/// (L(r,k) = Ap(r,k) - sum_j L(r,j) L(k,j) with both terms zero), so the main loop needs no test.
void embed_removed(SkylineMatrix& L, int k0, int k1, const std::vector<char>& removed) {
    if (removed.empty()) return;
    assert(static_cast<int>(removed.size()) == L.n());
    for (int k = 0; k < k1; ++k) {
        if (!removed[k]) continue;
        if (k < k0) {
            assert(is_identity_row_column(L, k));
            continue;
        }
        zero_row(L, k);
        make_identity_column(L, k);
    }
}

/// Source columns shorter than this reach column k one at a time, in a plain loop: collecting
/// them into groups costs more than it saves (forwarder: 11 % more instructions), as did Eigen's
/// vectorized form, whose set-up outweighed the arithmetic (callgrind, a 34-row buggy island's
/// L0: the factorization was a fifth of the whole world step).
constexpr int kShortColumn = 8;

/// target[0 .. length) -= l * source[0 .. length), length < kShortColumn (short_update.h).
[[gnu::always_inline]] inline void subtract_scaled(double* target, const double* source, double l, int length) {
    static_assert(kShortColumn <= kShortRun, "short columns are short runs");
    subtract_multiple_short(target, source, l, length);
}

/// Up to kGroup earlier columns updating column k at once: column k's entries are loaded and
/// stored once per group instead of once per column, which halves the instructions of a long
/// update (callgrind: the axpy form spent about 4 instructions per multiply-add on parkour's
/// 180-row islands, whose column skyline is nearly dense).
constexpr int kGroup = 8;

struct SourceGroup {
    const double* source[kGroup];  ///< L(k .. , j) of each member column j, from row k
    double l[kGroup];              ///< L(k, j)
    int length[kGroup];            ///< sky[j] - k + 1: non-decreasing, as sky is
    int size = 0;
};

/// target[r] -= sum_{m < M} l[m] source[m][r] for r in [from, to), summed in member order.
template <int M>
[[gnu::always_inline]] inline void subtract_combination(double* target, const double* const* source, const double* l, int from, int to) {
    for (int r = from; r < to; ++r) {
        double sum = l[0] * source[0][r];
        for (int m = 1; m < M; ++m) sum += l[m] * source[m][r];
        target[r] -= sum;
    }
}

/// The same over the group's members from `first` on, for rows [from, to) that all of them reach.
[[gnu::always_inline]] inline void subtract_members(double* target, const SourceGroup& g, int first, int from, int to) {
    const double* const* s = g.source + first;
    const double* l = g.l + first;
    switch (g.size - first) {
        case 1: return subtract_combination<1>(target, s, l, from, to);
        case 2: return subtract_combination<2>(target, s, l, from, to);
        case 3: return subtract_combination<3>(target, s, l, from, to);
        case 4: return subtract_combination<4>(target, s, l, from, to);
        case 5: return subtract_combination<5>(target, s, l, from, to);
        case 6: return subtract_combination<6>(target, s, l, from, to);
        case 7: return subtract_combination<7>(target, s, l, from, to);
        default: return subtract_combination<8>(target, s, l, from, to);
    }
}

/// Column k -= the group's columns: rows below the shortest member take the members that
/// still reach them (the lengths are non-decreasing). On x86-64 also compiled for AVX2 and
/// chosen by the CPU at load time (kernel_clones.h): four rows per instruction instead of two,
/// the same bits (with AVX2, parkour's islands factor 1.3-1.5 times as fast: docs/benchmarks.md).
KERNEL_FOR_AVX2_TOO
void subtract_group(double* target, SourceGroup& g) {
    int from = 0;
    for (int first = 0; first < g.size; ++first) {
        assert(from <= g.length[first]);
        subtract_members(target, g, first, from, g.length[first]);
        from = g.length[first];
    }
    g.size = 0;
}

/// Eight members subtracted from two target columns k and k+1 at once (g0 from row k, g1 the
/// same columns from row k+1: sources one row on, l = L(k+1, j)), for rows r in [from, to) from
/// row k, r >= 1: each member's entry is loaded once for both targets, and each target's entry
/// is computed exactly as subtract_combination<8> computes it (same products, same order), so
/// the bits are those of two calls. t0: column k from row k; t1: column k+1 from row k+1.
/// Columns k, k+1 and the members are disjoint parts of L (restrict).
[[gnu::always_inline]] KERNEL_VECTORIZED_WITH_REMAINDER inline void subtract_eight_pair(
    double* __restrict t0, double* __restrict t1, const SourceGroup& g0, const SourceGroup& g1, int from, int to) {
    const double* __restrict s0 = g0.source[0];
    const double* __restrict s1 = g0.source[1];
    const double* __restrict s2 = g0.source[2];
    const double* __restrict s3 = g0.source[3];
    const double* __restrict s4 = g0.source[4];
    const double* __restrict s5 = g0.source[5];
    const double* __restrict s6 = g0.source[6];
    const double* __restrict s7 = g0.source[7];
    const double a0 = g0.l[0], a1 = g0.l[1], a2 = g0.l[2], a3 = g0.l[3], a4 = g0.l[4], a5 = g0.l[5], a6 = g0.l[6],
                 a7 = g0.l[7];
    const double b0 = g1.l[0], b1 = g1.l[1], b2 = g1.l[2], b3 = g1.l[3], b4 = g1.l[4], b5 = g1.l[5], b6 = g1.l[6],
                 b7 = g1.l[7];
    for (int r = from; r < to; ++r) {
        const double v0 = s0[r], v1 = s1[r], v2 = s2[r], v3 = s3[r], v4 = s4[r], v5 = s5[r], v6 = s6[r], v7 = s7[r];
        t0[r] -= a0 * v0 + a1 * v1 + a2 * v2 + a3 * v3 + a4 * v4 + a5 * v5 + a6 * v6 + a7 * v7;
        t1[r - 1] -= b0 * v0 + b1 * v1 + b2 * v2 + b3 * v3 + b4 * v4 + b5 * v5 + b6 * v6 + b7 * v7;
    }
}

/// subtract_group(t0, g0) and subtract_group(t1, g1) for two full groups of the same members:
/// the rows all eight reach in one pass over their entries (subtract_eight_pair), the rows
/// below the shortest member target by target, as subtract_group takes them.
KERNEL_FOR_AVX2_TOO KERNEL_VECTORIZED_WITH_REMAINDER
void subtract_group_pair(double* t0, double* t1, SourceGroup& g0, SourceGroup& g1) {
    assert(g0.size == kGroup && g1.size == kGroup);
    subtract_members(t0, g0, 0, 0, 1);  // row k: column k's alone (every member reaches it)
    subtract_eight_pair(t0, t1, g0, g1, 1, g0.length[0]);
    int from0 = g0.length[0], from1 = g1.length[0];
    for (int first = 1; first < kGroup; ++first) {
        subtract_members(t0, g0, first, from0, g0.length[first]);
        subtract_members(t1, g1, first, from1, g1.length[first]);
        from0 = g0.length[first];
        from1 = g1.length[first];
    }
    g0.size = 0;
    g1.size = 0;
}

/// Appends a member to a group; true when the group is full.
bool add_member(SourceGroup& g, const double* source, int length) {
    g.source[g.size] = source;
    g.l[g.size] = source[0];
    g.length[g.size] = length;
    return ++g.size == kGroup;
}

/// Left-looking step for column k: L(k:sky[k], k) -= sum_j L(k,j) L(k:sky[j], j) over the
/// earlier columns j >= j_first that reach row k (sky[j] <= sky[k] keeps it in storage).
/// Skips exact zeros L(k,j) = 0: removed indices, or zeros outside the profile that stay zero.
/// The grouping depends on column k's own sources only, so a column is computed alike in every
/// call (skyline_cholesky.h's bit-for-bit promise).
void subtract_earlier_columns(SkylineMatrix& L, int k, int j_first) {
    double* target = L.column(k);
    SourceGroup group;
    int size = 0;  // group.size, in a register: through memory each member waited on the last one's store
    for (int j = j_first; j < k; ++j) {
        const double* source = L.column(j) + (k - j);
        if (source[0] == 0.0) continue;
        const int length = L.sky(j) - k + 1;
        if (length < kShortColumn) {
            subtract_scaled(target, source, source[0], length);
            continue;
        }
        group.source[size] = source;
        group.l[size] = source[0];
        group.length[size] = length;
        if (++size == kGroup) {
            group.size = size;
            subtract_group(target, group);
            size = 0;
        }
    }
    if (size == 0) return;  // most columns of a sparse island: no group, and no call to its clone
    group.size = size;
    subtract_group(target, group);
}

/// Columns at least this high are factored in pairs where they can be (factor_column_pair): the
/// members' entries then come from beyond the first-level caches, and loading each once for two
/// columns pays. Below it the pair's set-up outweighs that (callgrind, parkour's 194-row
/// islands: 1.5 % more instructions). The bits are the same either way.
constexpr int kPairHeight = 256;

/// True when columns k and k+1 take the same earlier columns j_first .. k-1 the same way
/// (subtract_earlier_columns): each reaches row k+1, L(k,j) and L(k+1,j) are zero together, and
/// no non-zero member is short for one column and long for the other. Then every update of both
/// can be made in one pass (subtract_pair_earlier_columns).
bool same_sources(const SkylineMatrix& L, int k, int j_first) {
    if (L.sky(j_first) < k + 1) return false;
    for (int j = j_first; j < k; ++j) {
        const double* source = L.column(j) + (k - j);
        if ((source[0] == 0.0) != (source[1] == 0.0)) return false;
        if (source[0] != 0.0 && L.sky(j) - k + 1 == kShortColumn) return false;
    }
    return true;
}

/// subtract_earlier_columns for columns k and k+1 over the columns j < k, where same_sources
/// holds: the same operations on each column in the same order, each member loaded once for
/// both. Leaves in g0 and g1 the members of the last group, not yet subtracted: column k's
/// update ends by subtracting g0; column k+1's continues with column k itself.
void subtract_pair_earlier_columns(SkylineMatrix& L, int k, int j_first, SourceGroup& g0, SourceGroup& g1) {
    double* t0 = L.column(k);
    double* t1 = L.column(k + 1);
    for (int j = j_first; j < k; ++j) {
        const double* source = L.column(j) + (k - j);
        if (source[0] == 0.0) continue;
        const int length = L.sky(j) - k + 1;
        if (length < kShortColumn) {
            subtract_scaled(t0, source, source[0], length);
            subtract_scaled(t1, source + 1, source[1], length - 1);
            continue;
        }
        add_member(g1, source + 1, length - 1);
        if (add_member(g0, source, length)) subtract_group_pair(t0, t1, g0, g1);
    }
}

/// The pivot d_k = Ap(k,k) - sum_j L(k,j)² sums earlier_columns terms bounded by Ap(k,k): its
/// rounding error is about (earlier_columns + 1) eps Ap(k,k). A pivot below that is not
/// distinguishable from zero.
bool pivot_is_positive(double pivot, double diagonal, int earlier_columns) {
    const double noise = (earlier_columns + 1) * std::numeric_limits<double>::epsilon() * diagonal;
    return diagonal > 0.0 && pivot > noise && std::isfinite(pivot);
}

/// Column k's square root and scaling, once its updates are done; false when its pivot fails.
/// No Eigen map: most columns of a sparse island hold a few entries, where its alignment set-up
/// cost more than the products (callgrind, the crane: 94 instructions per column, a quarter of
/// its factorization), and those columns take straight-line code (short_update.h); each entry is
/// multiplied by the same 1 / L(k,k).
bool finish_column(SkylineMatrix& L, int k, double diagonal, int earlier_columns) {
    double* column = L.column(k);
    if (!pivot_is_positive(column[0], diagonal, earlier_columns)) return false;
    const double l_kk = std::sqrt(column[0]);
    column[0] = l_kk;
    const double inverse = 1.0 / l_kk;
    const int height = L.shape().height(k);
    if (height > kShortRun) {
        for (int r = 1; r < height; ++r) column[r] *= inverse;
        return true;
    }
    scale_short(column + 1, inverse, height - 1);  // straight-line code on short columns
    return true;
}

/// Columns k and k+1 (both kept, same_sources) factored together; -1 on success, else the
/// column whose pivot failed. Column k+1 ends as subtract_earlier_columns would end it: the
/// pending group of the earlier columns, then column k, short or appended to that group.
int factor_column_pair(SkylineMatrix& L, int k, int j_first) {
    const double diagonal0 = L.column(k)[0];
    const double diagonal1 = L.column(k + 1)[0];
    SourceGroup g0, g1;
    subtract_pair_earlier_columns(L, k, j_first, g0, g1);
    subtract_group(L.column(k), g0);
    if (!finish_column(L, k, diagonal0, k - j_first)) return k;
    double* t1 = L.column(k + 1);
    const double* source = L.column(k) + 1;  // column k from row k+1
    const int length = L.sky(k) - k;
    if (source[0] != 0.0) {
        if (length < kShortColumn) subtract_scaled(t1, source, source[0], length);
        else if (add_member(g1, source, length)) subtract_group(t1, g1);
    }
    subtract_group(t1, g1);
    return finish_column(L, k + 1, diagonal1, k + 1 - j_first) ? -1 : k + 1;
}

}  // namespace

int skyline_cholesky(SkylineMatrix& L, int k0, const std::vector<char>& removed) {
    return skyline_cholesky(L, k0, L.n(), removed);
}

int skyline_cholesky(SkylineMatrix& L, int k0, int k1, const std::vector<char>& removed) {
    assert(0 <= k0 && k0 <= k1 && k1 <= L.n());
    embed_removed(L, k0, k1, removed);
    int j_first = k0 < k1 ? L.shape().first_column_holding(k0) : k1;
    for (int k = k0; k < k1; ++k) {
        while (L.sky(j_first) < k) ++j_first;
        if (is_removed(removed, k)) continue;
        if (k + 1 < k1 && L.shape().height(k) >= kPairHeight && !is_removed(removed, k + 1) &&
            same_sources(L, k, j_first)) {
            if (const int failed = factor_column_pair(L, k, j_first); failed >= 0) return failed;
            ++k;
            continue;
        }
        const double diagonal = L.column(k)[0];
        subtract_earlier_columns(L, k, j_first);
        if (!finish_column(L, k, diagonal, k - j_first)) return k;
    }
    return -1;
}

}  // namespace ode_bpp::linalg
