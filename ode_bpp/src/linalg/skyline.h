// Skyline (envelope) storage of a lower-triangular factor, column by column.
//
// Index space: whatever the caller uses (the pivoting loop uses the *permuted* space, after
// ordering). Column k stores rows k .. sky[k] contiguously, diagonal first:
//     L(r, k) = values[colptr[k] + (r - k)]  for k <= r <= sky[k].
// sky is non-decreasing in k (it is the column profile of a row envelope), which is what keeps
// every row deletion inside the storage: deleting rows never widens the envelope (docs/maths.md).
#pragma once

#include <cassert>
#include <cstddef>
#include <vector>

namespace ode_bpp::linalg {

struct SkylineShape {
    int n = 0;
    std::vector<int> sky;               ///< n: last row stored in column k, sky[k] >= k, non-decreasing
    std::vector<std::ptrdiff_t> colptr; ///< n + 1: start of column k in values; colptr[n] = size
    /// n: first_column[r] = min{ j : sky[j] >= r } (non-decreasing), what first_column_holding
    /// returns; made by from_row_profile and dense. Empty in a shape built otherwise, whose
    /// first_column_holding then searches sky.
    std::vector<int> first_column;

    /// The shape of the envelope of a symmetric matrix given its row profile first[i] <= i
    /// (first non-zero column of row i in the lower triangle): sky[k] = max{ i : first[i] <= k }.
    static SkylineShape from_row_profile(const std::vector<int>& first);
    /// from_row_profile(first).size() without the shape: O(n), nothing kept.
    static std::ptrdiff_t size_of_row_profile(const std::vector<int>& first);
    /// Dense lower-triangular storage: sky[k] = n - 1 for every column (paper's "Downdating"
    /// without skyline uses this shape with the same kernels).
    static SkylineShape dense(int n);
    std::ptrdiff_t size() const { return colptr.empty() ? 0 : colptr.back(); }
    /// Rows stored in column k, diagonal included: sky[k] - k + 1.
    int height(int k) const { return sky[k] - k + 1; }
    /// Smallest column j whose storage holds row r (sky[j] >= r), so row r of L lives in
    /// columns first_column_holding(r) .. r. Deleting row r writes zeros into row r of these
    /// columns (restore them with SkylineMatrix::copy_rows_from). O(1) from first_column (the
    /// factorization asks it for every column it updates), else O(log n).
    int first_column_holding(int r) const {
        assert(r >= 0 && r < n);
        return first_column.empty() ? search_first_column(r) : first_column[static_cast<std::size_t>(r)];
    }
    /// True when sky is non-decreasing with k <= sky[k] <= n-1 and every column fits before
    /// the next one (colptr[k+1] - colptr[k] >= height(k)). Gaps between columns are allowed:
    /// the kernels never touch them (the tests fill them with NaN to prove it); and first_column,
    /// where present, is sky's.
    bool valid() const;

private:
    int search_first_column(int r) const;
    void index_first_columns();
};

class SkylineMatrix {
public:
    SkylineMatrix() = default;
    explicit SkylineMatrix(SkylineShape shape);
    /// The zero matrix of this shape, reusing this object's storage (no allocation once it has
    /// held a shape as large).
    void reset(const SkylineShape& shape);
    /// This shape with its values left unspecified (storage reused, nothing written): for a
    /// matrix that copy_tail_from(other, 0) or the like overwrites before anything reads it.
    void reshape(const SkylineShape& shape);

    int n() const { return shape_.n; }
    const SkylineShape& shape() const { return shape_; }
    int sky(int k) const { return shape_.sky[k]; }
    bool in_envelope(int r, int k) const { return k <= r && r <= shape_.sky[k]; }
    double& at(int r, int k) { return values_[shape_.colptr[k] + (r - k)]; }
    double at(int r, int k) const { return values_[shape_.colptr[k] + (r - k)]; }
    /// L(r,k) if inside the envelope, else 0.
    double get(int r, int k) const { return in_envelope(r, k) ? at(r, k) : 0.0; }
    double* column(int k) { return values_.data() + shape_.colptr[k]; }
    const double* column(int k) const { return values_.data() + shape_.colptr[k]; }
    std::vector<double>& values() { return values_; }
    const std::vector<double>& values() const { return values_; }

    /// Copies columns k0 .. n-1 of other (same shape) into this. Deleting rows >= k0 changes
    /// these columns and, in earlier columns, only the deleted rows (see copy_rows_from).
    void copy_tail_from(const SkylineMatrix& other, int k0);
    /// Copies columns 0 .. k1-1 of other (same shape) into this.
    void copy_head_from(const SkylineMatrix& other, int k1);
    /// Copies, for each r in rows, the stored entries L(r, j) with j < min(r, k_end) from other
    /// (same shape). Deleting or removing row r zeroes exactly its entries in columns < r, so
    ///     copy_tail_from(L0, k0); copy_rows_from(L0, rows_changed_before, k0);
    /// restores L0 after deletions of rows_changed_before (all >= k0) at O(copy of the tail +
    /// one row each) instead of a copy from first_column_holding(min row), which for dense
    /// storage is the whole matrix.
    void copy_rows_from(const SkylineMatrix& other, const std::vector<int>& rows, int k_end);

private:
    SkylineShape shape_;
    std::vector<double> values_;
};

}  // namespace ode_bpp::linalg
