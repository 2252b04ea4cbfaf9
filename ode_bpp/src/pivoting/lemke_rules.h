// The parts of Lemke's method (lemke.h) that do not depend on how the basis is kept, a dense
// inverse (lemke.cpp) or a sparse factor (sparse_lemke.cpp): the lexicographic minimum ratio test
// and reading the solution off the basis. Variables of the tableau I u - M z - d z0 = q are
// numbered u_i = i, z_i = N + i, z0 = 2N; basis[r] is the variable basic in row r.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "pivoting/lemke.h"

namespace ode_bpp::pivoting {

/// Writes column k of B^-1 B0 (N entries), B0 the starting basis: the keys of the lexicographic
/// rule (B0 = I for the slack basis).
using LemkeKeyColumn = std::function<void(int k, Eigen::VectorXd& key)>;

/// The leaving row for an entering column c = B^-1 a (N entries) at basic values rhs = B^-1 q, by
/// the lexicographic minimum ratio rule (Cottle, Pang & Stone, Sec. 4.4), or -1 when no entry
/// blocks (a ray). The artificial variable leaves whenever it ties.
int lexicographic_ratio_test(const Eigen::VectorXd& rhs, const Eigen::VectorXd& c, const std::vector<int>& basis,
                             const LemkeKeyColumn& key_column);

/// s.z, s.z_basic and s.u_basic from the basic values xb (N entries): nonbasic entries 0,
/// negatives (rounding of a degenerate basis) clamped to 0.
void read_lemke_solution(const std::vector<int>& basis, const Eigen::VectorXd& xb, LemkeSolution& s);

}  // namespace ode_bpp::pivoting
