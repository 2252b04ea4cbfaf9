// A symmetric matrix as compressed rows holding both triangles: the one form of A that every
// solver path works on (paper Eq. 2's A = J M^-1 J^T + C/h^2, in ODE's scaling).
//
// The pivoting loop needs A only through products (w = A x - b, Eq. 5, and the right-hand side
// b_F - A_FT x_T of Eq. 6) and through the entries its factor strategies load. Keeping A's
// non-zeros once makes every product O(nnz) instead of O(n^2), and keeps memory at
// O(nnz + envelope). Built either from a dense lower triangle (files, tests, the CLI) or
// straight from the Jacobian (ode/assemble.h); both give the same rows, so one path follows.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp::linalg {

/// One strictly lower entry A(row, col), row > col.
struct LowerEntry {
    int row, col;
    double value;
};

class SymmetricRows {
public:
    SymmetricRows() = default;
    /// Ap(i,j) = A(perm[i], perm[j]) of the problem's matrix (original space: its dense lower
    /// triangle, or problem.sparse). perm: perm[new] = old, n entries, or empty for the identity.
    /// From a dense A the stored entries are the non-zeros and, when the problem has row blocks
    /// that tile its rows (Problem::block_row), A's structural pattern: every entry of a block
    /// against itself and against each earlier block that shares a body with it, exact zeros too
    /// (the entries ode/assemble.h forms from J, so a dense and a sparse island store the same).
    SymmetricRows(const Problem& problem, const std::vector<int>& perm);
    /// The same as constructing from (problem, perm), reusing this object's storage.
    void assign(const Problem& problem, const std::vector<int>& perm);
    /// The matrix with the given diagonal (n entries) and strictly lower entries, listed row by
    /// row with increasing columns (so every stored row is sorted by column). O(n + entries).
    /// diagonal is swapped in: the caller gets this object's former storage back to reuse.
    void assign_lower(std::vector<double>& diagonal, const std::vector<LowerEntry>& lower);
    /// The same matrix stored in the symmetric order `order` (order[new] = old, n entries, a
    /// permutation): what assign_lower and then permute_into(order) give, entry for entry and in
    /// the same order within each row, in one pass. O(n + entries).
    void assign_lower(const std::vector<double>& diagonal, const std::vector<LowerEntry>& lower,
                      const std::vector<int>& order);
    /// Where the last assign_lower stored each entry of its `lower`: lower[e] went to positions
    /// entry_positions()[2e] (in its row's stored row) and [2e+1] (in its column's) of col()/val().
    /// Kept only until the next assignment of any kind.
    const std::vector<int>& entry_positions() const { return build_.positions; }

    /// Writable views of the stored values, for a caller that assigns a matrix of the same
    /// pattern again (ode/assemble.h): diagonal[i] is A(i,i) and values[k] is val(k), in the
    /// stored order. Writing them keeps the pattern, the order and the profile; the caller must
    /// write every stored entry, both copies of an entry with the same value.
    struct Values {
        double* diagonal;
        double* values;
    };
    Values values_in_place() { return {diag_.data(), val_.data()}; }
    /// The same matrix under a further permutation: result(i,j) = this(perm[i], perm[j]).
    SymmetricRows permuted(const std::vector<int>& perm) const;
    /// The same, written into out (its storage reused); out must not be *this. Each row keeps
    /// its entries in their order here (not sorted by the new columns).
    void permute_into(const std::vector<int>& perm, SymmetricRows& out) const;
    /// This matrix in the order it was built in (order() undone) into out (storage reused), or
    /// *this itself when it is stored in that order already.
    const SymmetricRows& in_built_order(SymmetricRows& out) const;

    /// The order of the rows: stored row i is row order()[i] of the matrix as built (empty:
    /// the identity). Set by assign(problem, perm) and the ordered assign_lower and carried along
    /// by permute_into, so that a problem's compressed rows may come in the solver's order
    /// (Problem::sparse).
    const std::vector<int>& order() const { return order_; }
    /// order()[i], or i when the order is the identity.
    int built_row(int i) const { return order_.empty() ? i : order_[i]; }

    int n() const { return n_; }
    /// Stored off-diagonal entries (both triangles).
    int off_diagonal_entries() const { return rowptr_.empty() ? 0 : rowptr_[n_]; }
    /// Stored row i's diagonal entry (stored order, as every index of this class but built_row's
    /// result).
    double diag(int i) const { return diag_[i]; }
    double max_diag() const;
    /// Off-diagonal entries of row i: positions rowptr(i) .. rowptr(i+1)-1 of col()/val(). By
    /// increasing column after assign and assign_lower; by increasing built column
    /// (built_row(col(k))) after the ordered assign_lower; permute_into keeps each row's order.
    int row_begin(int i) const { return rowptr_[i]; }
    int row_end(int i) const { return rowptr_[i + 1]; }
    int col(int k) const { return col_[k]; }
    double val(int k) const { return val_[k]; }
    /// val(0) .. val(off_diagonal_entries() - 1), contiguous.
    const double* values() const { return val_.data(); }

    /// y = (Ap + shift I) x; x, y: n entries in stored order (the solver's permuted space).
    void multiply(const std::vector<double>& x, double shift, std::vector<double>& y) const;
    /// y = |Ap + shift I| |x| (the per-row scale of the tolerance), n entries.
    void abs_multiply(const std::vector<double>& x, double shift, std::vector<double>& y) const;
    /// y = (Ap + shift I) x and scale = |Ap + shift I| |x| in one pass over the entries (the
    /// pivoting loop's w and tolerance scale of Eq. 5), n entries each.
    void multiply_with_scale(const double* x, double shift, double* y, double* scale) const;
    /// Row i of multiply_with_scale, summed as it sums it (the diagonal term first, then the
    /// row's entries in stored order), so that a row computed alone equals the same row of the
    /// whole product bit for bit.
    void row_with_scale(int i, const double* x, double shift, double& y, double& scale) const {
        const double d = (diag_[i] + shift) * x[i];
        double sum = d, abs_sum = std::abs(d);
        for (int k = rowptr_[i]; k < rowptr_[i + 1]; ++k) {
            const double term = val_[k] * x[col_[k]];
            sum += term;
            abs_sum += std::abs(term);
        }
        y = sum;
        scale = abs_sum;
    }
    /// Row profile of the lower triangle, stored order: first[i] = min({i} U {j < i : Ap(i,j)
    /// stored}): the non-zeros and, with row blocks, A's structural pattern (see the constructor).
    std::vector<int> row_profile() const;
    /// The same into first (n entries, its storage reused). O(n) after assign_lower, which finds
    /// it while it counts (and after values_in_place, which keeps the pattern); O(n + nnz) after
    /// permute_into.
    void row_profile(std::vector<int>& first) const;
    /// Row profile of this matrix permuted by perm (perm[new] = old), without building it.
    std::vector<int> row_profile_under(const std::vector<int>& perm) const;
    /// The same for a perm that lists the rows by (rank[row], row): those of rank 0 in stored
    /// order, then those of rank 1, and so on (rows moved last, each group keeping its order).
    /// first: this matrix's own row_profile(). A row of rank 0 whose first stored neighbour has
    /// rank 0 too starts at that neighbour (the renumbering keeps the order of rank 0 and puts
    /// every other row after it), so only the other rows are read: O(n + their entries).
    /// rank: n entries, stored order.
    std::vector<int> row_profile_ranked(const std::vector<int>& perm, const std::vector<unsigned char>& rank,
                                        const std::vector<int>& first) const;
    /// Its entry for one row: the first column of stored row `row` (stored order) once the rows
    /// are renumbered by to_new (to_new[stored] = new), within row to_new[row]'s lower triangle.
    int first_under(int row, const std::vector<int>& to_new) const {
        int first = to_new[static_cast<std::size_t>(row)];
        for (int k = row_begin(row); k < row_end(row); ++k) first = std::min(first, to_new[col_[k]]);
        return first;
    }
    /// The lower triangle, diagonal included, as a dense row-major n x n array with row stride
    /// lda (the upper triangle is left as it is), in the order the matrix was built in (order()
    /// undone). O(n^2): for ODE's Dantzig and file capture.
    void to_dense_lower(double* A, int lda) const;

private:
    /// Rows from the per-row entry counts in build_.count and the strictly lower entries, each
    /// stored in rows to_new(row) and to_new(col) in the order of `lower` (so with increasing
    /// columns when `lower` is listed row by row and to_new keeps the order). O(n + entries).
    template <class ToNew>
    void fill_rows(const std::vector<LowerEntry>& lower, ToNew to_new);

    /// Buffers of assign and assign_lower, kept with the matrix so that assigning it again
    /// allocates nothing once they have grown. Not part of the matrix's value: copies start empty.
    struct BuildBuffers {
        BuildBuffers() = default;
        BuildBuffers(const BuildBuffers&) {}
        BuildBuffers& operator=(const BuildBuffers&) { return *this; }
        BuildBuffers(BuildBuffers&&) noexcept = default;
        BuildBuffers& operator=(BuildBuffers&&) noexcept = default;
        std::vector<int> to_new, count, next, positions, block_of;
        std::vector<char> coupled;
        std::vector<LowerEntry> lower;
        std::vector<double> diagonal;
    };

    int n_ = 0;
    std::vector<int> order_;
    std::vector<int> profile_;    ///< row_profile(), when profile_known_ (assign_lower finds it)
    bool profile_known_ = false;
    std::vector<double> diag_;
    std::vector<int> rowptr_, col_;
    std::vector<double> val_;
    BuildBuffers build_;
};

/// inverse[perm[i]] = i.
std::vector<int> inverse_permutation(const std::vector<int>& perm);

}  // namespace ode_bpp::linalg
