// Lemke's complementary pivoting for the standard LCP
//     u = M z + q,   u >= 0,   z >= 0,   u'z = 0,
// along the path of u = M z + q + d z0 from z0 large to z0 = 0, with the lexicographic ratio
// test, which cannot cycle on degenerate problems (Cottle, Pang & Stone, The Linear
// Complementarity Problem, Sec. 4.4). On a copositive M that is not copositive-plus (the friction
// LCP of friction_lcp.h) the path can still end on a secondary ray. With d = (1, ..., 1) it did
// so on 11 % of the captured winch frames (135 of 1,200), from ties that d = 1 makes in the ratio
// test; with d spread over [0.5, 1.5) (spread_covering_vector) on 2 of 1,200, and a second spread
// vector finished both. Dense, O(N^2) per pivot on the basis
// inverse: a last resort for the few problems that block pivoting does not finish; large sparse
// LCPs go to sparse_lemke.h.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace ode_bpp::pivoting {

enum class LemkeOutcome {
    Solved,         ///< z solves the LCP (to the rounding of the basis inverse)
    RayTermination, ///< no blocking row for the entering variable: M is outside Lemke's class here
    MaxPivots,      ///< the pivot budget ran out
    SingularBasis,  ///< sparse_lemke.h: a refactorization found the basis singular (rounding)
    Inaccurate,     ///< sparse_lemke.h: the path ended, but its answer violates the LCP beyond rounding
};

struct LemkeSolution {
    LemkeOutcome outcome = LemkeOutcome::MaxPivots;
    int pivots = 0;
    Eigen::VectorXd z;          ///< N entries; nonbasic entries exactly 0 (meaningful when Solved)
    std::vector<char> z_basic;  ///< N flags: z_i is basic (may be > 0)
    std::vector<char> u_basic;  ///< N flags: u_i is basic (may be > 0); nonbasic u_i = 0
};

/// A covering vector with entries spread over [0.5, 1.5) by the golden-ratio sequence, different
/// for every attempt (reproducible: no random state).
Eigen::VectorXd spread_covering_vector(int n, int attempt);

/// Solves the LCP (M: in, N x N; q: in, N) along Lemke's path for the covering vector d (in, N,
/// every entry > 0). max_pivots: budget of complementary pivots.
LemkeSolution solve_lemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& d, int max_pivots);

}  // namespace ode_bpp::pivoting
