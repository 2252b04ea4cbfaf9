// The boxed LCP with fixed bounds that one run of the pivoting loop solves (paper Eq. 3-6),
// in the permuted index space of the factor strategy.
#pragma once

#include <vector>

#include "ode_bpp/solver.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::pivoting {

/// (A + shift I) x = b + w with, per row, x = lo and w >= 0, x = hi and w <= 0, or
/// lo < x < hi and w = 0. All vectors n entries, permuted space.
struct BoxedLcp {
    const linalg::SymmetricRows* A = nullptr;
    double shift = 0;               ///< regularization delta added to A's diagonal
    std::vector<double> b, lo, hi;  ///< lo may be -inf, hi +inf
    std::vector<char> always_free;  ///< rows < nub and rows with infinite bounds: never tight
    /// Murty's fixed order: rank of each row (n distinct values; the driver uses the caller's
    /// original index, so every strategy pivots alike), or empty for the permuted index.
    std::vector<int> murty_rank;

    /// Consistent friction inside the loop (empty: every bound fixed). Row i with
    /// friction_normal[i] >= 0 has the bounds -+friction_mu[i] |x[friction_normal[i]]|, moving with
    /// x; at a bound while its normal is free it is linked, x_i = +-mu_i x_normal, and each step
    /// solves the linked rows with the free ones (pivoting/friction_link.h). lo/hi of these rows
    /// are only the starting bounds. n entries each; mu finite and >= 0.
    std::vector<int> friction_normal;
    std::vector<double> friction_mu;

    int n() const { return A->n(); }
    bool has_moving_bounds() const { return !friction_normal.empty(); }
    /// A row with lo == hi is pinned at that value: always tight and never infeasible (ODE's
    /// Dantzig treats lo = hi = 0 friction rows the same way).
    bool is_pinned(int i) const { return lo[i] == hi[i]; }
};

struct FrictionSet;

/// The BoxedLcp of a validated problem in the permutation perm (perm[new] = old, n entries; the
/// identity for the caller's order), on Ap = A permuted (lcp.A points at it): b, lo, hi
/// permuted, rows below nub unbounded, shift 0, no moving bounds, murty_rank = perm (every
/// strategy pivots alike); friction (out): its friction rows with their normals and mu (their
/// lo/hi in lcp are the problem's until a friction policy sets them).
void build_boxed_lcp(const Problem& problem, const linalg::SymmetricRows& Ap, const std::vector<int>& perm,
                     BoxedLcp& lcp, FrictionSet& friction);

/// The value a tight row takes: lo for AtLo, hi for AtHi (paper Alg. 1 lines 6-7).
inline double tight_value(const BoxedLcp& lcp, int i, RowState s) { return s == RowState::AtLo ? lcp.lo[i] : lcp.hi[i]; }

}  // namespace ode_bpp::pivoting
