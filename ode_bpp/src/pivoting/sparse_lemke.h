// Lemke's method (lemke.h) for a large sparse LCP u = M z + q, with its basis kept as a sparse LU
// factor and updated per pivot in product form (eta vectors, refactored periodically), instead of
// a dense basis inverse: a pivot costs one solve with the factor, O(nnz(LU) + etas N), not O(N^2),
// and nothing of size N^2 is ever stored (Bartels & Golub's idea as used in sparse simplex codes;
// Cottle, Pang & Stone, Sec. 4.4, for the path and its lexicographic ratio test).
//
// The path may start from a guessed complementary basis B0 (a warm start from an index set)
// instead of the slack basis: with the covering vector d = B0 s (s > 0), the basic solution
// x_B(z0) = B0^-1 q + z0 s is non-negative for large z0, so the path starts at B0 and, when the
// guess is close to an answer, ends after a few pivots. The lexicographic keys are then the rows
// of B^-1 B0 (the identity at the start, as B^-1 is for the slack basis).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <vector>

#include "pivoting/lemke.h"

namespace ode_bpp::pivoting {

/// Solves the LCP (M: in, N x N, column-major sparse; q: in, N) along Lemke's path.
/// start: N flags, z_i basic in the starting basis where set (u_i otherwise), or empty for the
/// slack basis; a singular starting basis falls back to the slack basis. spread: N entries, all
/// > 0 (spread_covering_vector). max_pivots: budget of complementary pivots. The solution's z,
/// z_basic and u_basic mean what they mean for solve_lemke.
LemkeSolution solve_sparse_lemke(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& q,
                                 const std::vector<char>& start, const Eigen::VectorXd& spread, int max_pivots);

}  // namespace ode_bpp::pivoting
