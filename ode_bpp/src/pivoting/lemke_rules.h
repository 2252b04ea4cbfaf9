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

/// Lemke's complementary path (Cottle, Pang & Stone, Alg. 4.4.5) from z0 entering at row `first`:
/// the complement of each variable that leaves enters next, until z0 leaves (Solved), no row
/// blocks (RayTermination), a pivot meets a singular basis (SingularBasis) or `max_pivots`
/// pivots are made (MaxPivots). pivots: out, the pivots made, z0's entry included.
/// Tableau: column(var, c) = B^-1 a_var, ratio_test(c) (-1 for a ray), basic(row),
/// complement(var), artificial(), pivot(row, entering, c) (false on a singular basis), and
/// after_pivot(pivots) for the upkeep of the basis (a periodic refresh).
template <class Tableau>
LemkeOutcome follow_lemke_path(Tableau& t, int first, int max_pivots, int& pivots) {
    Eigen::VectorXd c;
    t.column(t.artificial(), c);
    int entering = t.complement(t.basic(first));
    pivots = 1;
    if (!t.pivot(first, t.artificial(), c)) return LemkeOutcome::SingularBasis;
    while (pivots < max_pivots) {
        t.column(entering, c);
        const int r = t.ratio_test(c);
        if (r < 0) return LemkeOutcome::RayTermination;
        const int leaving = t.basic(r);
        ++pivots;
        if (!t.pivot(r, entering, c)) return LemkeOutcome::SingularBasis;
        if (leaving == t.artificial()) return LemkeOutcome::Solved;
        t.after_pivot(pivots);
        entering = t.complement(leaving);
    }
    return LemkeOutcome::MaxPivots;
}

}  // namespace ode_bpp::pivoting
