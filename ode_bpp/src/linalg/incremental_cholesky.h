// A Cholesky factor of a principal submatrix M_SS whose index set S grows and shrinks by one
// index at a time: the factor behind single principal pivots (the active-set stage), where each
// step adds one row to the free set F or removes one. Appending costs one triangular solve and
// removing one rank-1 update, against a fresh factorization per change.
//
// The factor is kept on its envelope: row i of L is stored from its first column first(i) to
// the diagonal, packed row after row, and every operation touches only those entries, so that
// a matrix ordered for a small envelope (Cuthill-McKee) costs envelope work, not O(|S|²) per
// change and O(|S|³) per refactorization.
//
// Why the envelope is exact, with first(i) = the first column k <= i with M_SS(i, k) != 0:
//  - the Cholesky factor's envelope is the matrix's: L_ik = (M_ik - sum_{j<k} L_ij L_kj) / L_kk
//    is zero for k < first(i) by induction on k (M_ik = 0 and every L_ij with j < k is zero);
//  - append: the new row l solves L l = c with c_k = 0 for k < first; forward substitution
//    gives l_k = 0 there by the same induction, so l starts at c's first non-zero;
//  - remove(p): the trailing block becomes chol(L33 L33ᵀ + sigma sigmaᵀ) with sigma = L(p+1:, p)
//    (row_delete.h), applied by one Givens rotation per column. Row i's entry of sigma is zero
//    when first(i) > p, and a rotation of column k mixes row i's L_ik with its running sigma, both
//    zero while k < first(i): the rank-1 update widens only rows where sigma is non-zero, and
//    those start at or before p anyway. So after the rows below p move up one place, a row with
//    first <= p keeps its first, a row with first > p starts one column earlier, like its column.
// Recorded envelopes never shrink on removal (a row whose only early non-zero was in column p
// keeps a zero entry), which is safe: stored entries may be zero, no entry outside is non-zero.
//
// The reciprocal of every pivot L(i, i) is kept beside it, and the substitutions multiply by it:
// each row of a triangular solve waits on the one before, and a division's latency lay end to end
// on that chain (the same change as the skyline solves'; docs/benchmarks.md).
#pragma once

#include <cstddef>
#include <vector>

#include "linalg/page_array.h"

namespace ode_bpp::linalg {

class IncrementalCholesky {
public:
    /// Empties S and makes room for up to `capacity` indices (allocates only when it grows).
    void reset(int capacity);

    /// |S|.
    int size() const { return size_; }

    /// Appends index j as S's last: column[k] = M(S_k, j) for k = first .. size()-1 in S's
    /// order, where M(S_k, j) = 0 for every k < first (those entries are not read; first =
    /// size() when j has no off-diagonal entry in S), diagonal M_jj. The new row of L is
    /// l = L⁻¹ column, zero before first, its pivot M_jj - |l|². False, leaving the factor
    /// unchanged, when that pivot breaks down (pivot_breaks_down of cholesky_pivot.h: j is
    /// dependent on S to machine precision). Requires 0 <= first <= size() < capacity.
    bool append(const double* column, int first, double diagonal);

    /// Makes S `size` indices whose factor is known from elsewhere (FreeRowsFactor's reset from
    /// the pivoting loop's skyline factor), row i of L recorded from column first[i] <= i on:
    /// the caller then writes L(i, first[i] .. i) through loaded_row(i), the diagonal positive,
    /// and calls finish_load() before any other call. Requires size <= capacity.
    void load_shape(const int* first, int size);
    /// Row i's recorded entries, L(i, first(i)) .. L(i, i), for load_shape's caller to write.
    double* loaded_row(int i) { return row_entries(i); }
    /// Ends a load: takes the reciprocals of the written pivots.
    void finish_load();

    /// Removes the index at position p of S (0 <= p < size()). With sigma = L(p+1:, p), the
    /// trailing block becomes chol(L33 L33ᵀ + sigma sigmaᵀ): a rank-1 *update* (nothing cancels,
    /// hence stable; the same maths as row_delete.h), by one Givens rotation per column, applied
    /// row by row over each row's envelope; the rows below p then move up.
    void remove(int p);

    /// x <- M_SS⁻¹ x, x: size() entries in S's order.
    void solve(double* x) const;
    /// vᵀ M_SS v = |Lᵀ v|² (M_SS = L Lᵀ), v: size() entries in S's order (input); y: size()
    /// entries of scratch (output: Lᵀ v). O(stored entries), without M: the curvature of a
    /// quadratic along a direction within S.
    double quadratic_form(const double* v, double* y) const;

    /// The first column of row i's recorded envelope (0 <= i < size()): L(i, k) = 0 for k < first(i).
    int first(int i) const { return first_[static_cast<std::size_t>(i)]; }
    /// L(i, k) for 0 <= k <= i < size(): 0 outside the recorded envelope.
    double entry(int i, int k) const { return k < first(i) ? 0.0 : row_entries(i)[k - first(i)]; }
    /// Stored entries of L (the envelope, diagonal included).
    std::size_t stored_entries() const { return size_ == 0 ? 0 : start_[static_cast<std::size_t>(size_)]; }

    /// Gives the factor's storage back (a large one to the system at once, page_array.h): the
    /// next append allocates afresh. Empties S.
    void release();
    /// Bytes of the entries' storage now held (its capacity, not its use).
    std::size_t storage_bytes() const { return L_.capacity() * sizeof(double); }

private:
    /// L(i, first(i)) .. L(i, i), contiguous.
    double* row_entries(int i) { return L_.data() + start_[static_cast<std::size_t>(i)]; }
    const double* row_entries(int i) const { return L_.data() + start_[static_cast<std::size_t>(i)]; }
    /// Room for `entries` stored entries, the current ones kept.
    void grow(std::size_t entries);

    /// One row i of remove(p) in flight: its old entries (from), where its new ones go (to, from
    /// column new_first), and its running sigma.
    struct RotatedRow {
        RotatedRow(IncrementalCholesky& factor, int p, int i, double* to);
        /// Rotation k (already defined: k < i) applied to the row.
        void rotate(int k) {
            const double l = from[k - f];
            to[k - 1 - new_first] = factor.cos_[k] * l + factor.sin_[k] * sigma;
            sigma = factor.cos_[k] * sigma - factor.sin_[k] * l;
        }
        void rotate_from(int k0, int k1) {
            for (int k = k0; k < k1; ++k) rotate(k);
        }
        /// The row's own rotation and pivot, its position i-1 recorded at to_start; returns the
        /// next row's start.
        std::size_t finish(std::size_t to_start);

        IncrementalCholesky& factor;
        const int i, f, new_first, k_begin;
        const double* from;
        double* to;
        double sigma;
    };
    /// Rows i and i+1 of remove(p) rotated together; returns where the row after them goes.
    std::size_t rotate_row_pair(int p, int i, std::size_t to_start);

    int size_ = 0;
    PageArray L_;                      ///< row i at start_[i] .. start_[i+1]-1: L(i, first_[i] .. i)
    std::vector<std::size_t> start_;   ///< size_ + 1 offsets into L_
    std::vector<int> first_;           ///< each row's first column
    std::vector<double> inverse_pivot_;      ///< 1 / L(i, i), by position
    std::vector<double> sigma_, cos_, sin_;  ///< remove(): sigma and the rotations, by position
    std::vector<double> pending_row_;        ///< remove(): a row's new entries before they move in
};

}  // namespace ode_bpp::linalg
