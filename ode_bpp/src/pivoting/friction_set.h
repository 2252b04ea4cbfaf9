// The friction rows of one BPP solve and the bounds they imply (ODE's box friction: row i with
// findex[i] >= 0 has |x_i| <= mu_i |x_normal|), in the permuted space of the solve.
#pragma once

#include <vector>

#include "pivoting/boxed_lcp.h"
#include "pivoting/friction_lcp.h"

namespace ode_bpp::pivoting {

struct FrictionSet {
    std::vector<int> rows;       ///< the friction rows, ascending (permuted index)
    std::vector<int> normal_of;  ///< rows[k]'s normal (permuted index)
    std::vector<double> mu;      ///< rows[k]'s coefficient (ODE's hi_i), >= 0, may be +inf

    bool empty() const { return rows.empty(); }
    std::size_t size() const { return rows.size(); }
    void clear();
    FrictionRows view() const { return {rows, normal_of, mu}; }

    /// mu_k |x_normal(k)|, 0 when the normal is 0 (ODE's rule, keeps mu = inf defined).
    std::vector<double> targets(const std::vector<double>& x) const;
    /// Fixes the bounds of rows[k] at -+bound[k] in lcp.
    void set_bounds(BoxedLcp& lcp, const std::vector<double>& bound) const;
    /// The bounds in force: lcp.hi of each friction row.
    std::vector<double> bounds(const BoxedLcp& lcp) const;
    /// Makes lcp's friction bounds move with the normals inside every pivot step (BoxedLcp's
    /// friction_normal, friction_link.h): rows with finite mu only.
    void link(BoxedLcp& lcp) const;
    /// Every friction row consistent with the bound its own normal implies, t_k = mu_k |x_n|: a
    /// row at a bound needs |x_k| (its bound) within tolerance of t_k; a free row only needs
    /// |x_k| <= t_k, as its bound does not enter x (Eq. 4 classifies it free either way). The
    /// tolerance is the larger of the row's own x-tolerance tol (|A||x| + |b|)_i / A_ii and |mu|
    /// times its normal's, since t_k is known only to within the latter (a friction row at a
    /// small bound has a small scale of its own, below the rounding of a large normal impulse).
    bool consistent(const BoxedLcp& lcp, double tolerance, const std::vector<RowState>& states,
                    const std::vector<double>& x) const;
};

}  // namespace ode_bpp::pivoting
