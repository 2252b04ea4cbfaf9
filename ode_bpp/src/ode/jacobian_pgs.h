// Projected Gauss-Seidel on an island in ODE's sparse form, A = J M^-1 J^T + diag(cfm), without
// forming A, as ODE's quickstep iterates: the answer for an island whose A alone would outgrow the
// memory (docs/modelling.md, "Islands too large for an exact step").
//
// Index space: the island's own row order (ODE's). Layout of J and J M^-1: <ode/mlcp.h>.
#pragma once

#include <cstdint>
#include <vector>

#include <ode/mlcp.h>

#include "ode/oversize.h"
#include "ode_bpp/solver.h"
#include "residuals.h"

namespace ode_bpp::ode {

/// A lower bound on the entries of A's lower triangle (diagonal included): rows i and j couple
/// where their joints share a body, so a body with r_b rows holds r_b (r_b + 1) / 2 such pairs,
/// and a pair is counted by at most its two bodies: the largest of those counts, and half their
/// sum. O(joints + bodies). rows_on_body: scratch.
std::int64_t coupled_entries_lower_bound(const dMLCP& island, std::vector<std::int64_t>& rows_on_body);

/// What solve_by_jacobian_pgs works in, reused from island to island.
struct JacobianPgsBuffers {
    std::vector<double> impulse;    ///< 6 per body: J^T x restricted to the body, sum_j x_j J_j(body)
    std::vector<double> magnitude;  ///< 6 per body: sum_j |x_j| |J_j(body)|, for the scale bound
    std::vector<double> x;          ///< the iterate, m entries
    ResidualBuffers vectors;        ///< w, the scale bound and A's diagonal at the answer
};

/// The island answered by Options::pgs_iterations sweeps of projected Gauss-Seidel from x = 0 in
/// row order: x_i <- clamp(x_i - w_i / A_ii, lo_i(x), hi_i(x)), with
///     w_i = sum over the bodies of row i of JinvM_i . (J^T x)(body) + cfm_i x_i - b_i
/// (baselines::solve_pgs's iterates on the assembled A, up to rounding) and a friction row's
/// bounds from the current value of its normal (quickstep's rule). Status FallbackUsed,
/// fallback Pgs, method and friction mode the options', the message says why (`oversize`: the
/// count over Options::max_factor_entries, ode/oversize.h); the residuals are
/// compute_residuals' except that the row scale is the bound
/// |JinvM_i| . (|J|^T |x|)(body) + cfm_i |x_i| + |b_i| >= (|A||x| + |b|)_i.
/// A problem that fails validate_rows, joints that do not tile the rows, a body outside [-1, nb),
/// input that is not finite (J, J M^-1, cfm) or a diagonal A_ii that is not positive: status
/// InvalidInput, x = 0; an answer that is not finite: status NotSpd, x = 0. x is written only
/// with the final answer. problem: the island's b, lo, hi, findex and nub, without A
/// (IslandView::rows_of). x: out, m entries (ODE's pairsbx). O(sweeps * m) time, O(m + bodies)
/// memory.
Result solve_by_jacobian_pgs(const dMLCP& island, const Problem& problem, const Options& options,
                             const Oversize& oversize, Strided x, JacobianPgsBuffers& buffers);

}  // namespace ode_bpp::ode
