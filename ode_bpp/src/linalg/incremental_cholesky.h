// A dense Cholesky factor of a principal submatrix M_SS whose index set S grows and shrinks by
// one index at a time: the factor behind single principal pivots (Murty's method), where each
// pivot adds one row to the free set F or removes one. Appending costs one triangular solve and
// removing one rank-1 update, O(|S|²) each, against O(|S|³) for a fresh factorization.
#pragma once

#include <vector>

#include "linalg/page_array.h"

namespace ode_bpp::linalg {

class IncrementalCholesky {
public:
    /// Empties S and makes room for up to `capacity` indices (allocates only when it grows).
    void reset(int capacity);

    /// |S|.
    int size() const { return size_; }

    /// Appends index j as S's last: column holds M(S_k, j) for k = 0 .. size()-1 in S's order,
    /// diagonal M_jj. The new row of L is l = L⁻¹ column, its pivot M_jj - |l|². False, leaving
    /// the factor unchanged, when that pivot breaks down (pivot_breaks_down of cholesky_pivot.h: j is dependent on S
    /// to machine precision).
    bool append(const double* column, double diagonal);

    /// Removes the index at position p of S (0 <= p < size()). With sigma = L(p+1:, p), the
    /// trailing block becomes chol(L33 L33ᵀ + sigma sigmaᵀ): a rank-1 *update* (nothing cancels,
    /// hence stable; the same maths as row_delete.h), by one Givens rotation per column, applied
    /// here row by row so that every access is contiguous; the rows below p then move up.
    void remove(int p);

    /// x <- M_SS⁻¹ x, x: size() entries in S's order.
    void solve(double* x) const;

    /// Gives the factor's storage back (a large one to the system at once, page_array.h): the
    /// next reset() allocates afresh. Empties S.
    void release();

private:
    double* row(int i) { return L_.data() + static_cast<long>(i) * capacity_; }
    const double* row(int i) const { return L_.data() + static_cast<long>(i) * capacity_; }

    int capacity_ = 0;
    int size_ = 0;
    PageArray L_;                       ///< row-major, stride capacity_; only the lower triangle is written or read
    std::vector<double> sigma_, cos_, sin_;  ///< remove(): sigma and the rotations, by position
};

}  // namespace ode_bpp::linalg
