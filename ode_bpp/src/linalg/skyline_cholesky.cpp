#include "linalg/skyline_cholesky.h"
#include "linalg/kernel_clones.h"

#include <Eigen/Core>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace ode_bpp::linalg {

namespace {

using Segment = Eigen::Map<Eigen::VectorXd>;

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

/// target[0 .. length) -= l * source[0 .. length).
void subtract_scaled(double* target, const double* source, double l, int length) {
    for (int r = 0; r < length; ++r) target[r] -= l * source[r];
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
    group.size = size;
    subtract_group(target, group);
}

/// The pivot d_k = Ap(k,k) - sum_j L(k,j)² sums earlier_columns terms bounded by Ap(k,k): its
/// rounding error is about (earlier_columns + 1) eps Ap(k,k). A pivot below that is not
/// distinguishable from zero.
bool pivot_is_positive(double pivot, double diagonal, int earlier_columns) {
    const double noise = (earlier_columns + 1) * std::numeric_limits<double>::epsilon() * diagonal;
    return diagonal > 0.0 && pivot > noise && std::isfinite(pivot);
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
        double* column = L.column(k);
        const double diagonal = column[0];
        subtract_earlier_columns(L, k, j_first);
        if (!pivot_is_positive(column[0], diagonal, k - j_first)) return k;
        const double l_kk = std::sqrt(column[0]);
        column[0] = l_kk;
        Segment(column + 1, L.shape().height(k) - 1) *= 1.0 / l_kk;
    }
    return -1;
}

}  // namespace ode_bpp::linalg
