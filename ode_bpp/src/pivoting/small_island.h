// The small-island path of Method::Bpp: block principal pivoting (paper Alg. 1, Júdice-Pires with
// Murty's safeguard) on a dense A of at most Tuning::dense_island_rows rows, in the caller's
// order, with Frozen friction; after Tuning::rescue_after steps, the active-set method of
// active_set.h, densely, as the general driver's plain attempt hands over to it.
//
// On an island of a few rows the general driver's set-up (ordering, factor strategy, permuted
// copies, rescue bookkeeping) costs several times the pivoting itself (docs/benchmarks.md, small
// islands). This path keeps only what such an island needs: A_FF gathered and factored densely
// at every step (linalg/dense_cholesky.h), the classification of classify_row.h, the polish of a
// converged index set, and no allocation once its buffers (kept by the caller) have grown, and
// the residuals of its answer from the loop's own w. Whatever it cannot
// finish (its budget runs out, a Cholesky pivot breaks down, Consistent friction) it leaves to
// the general driver, which then solves the island from the same warm start.
//
// Index space: the caller's original row order throughout (no permutation).
#pragma once

#include <vector>

#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "pivoting/classify_row.h"

namespace ode_bpp::pivoting {

/// The buffers of one small-island solve, kept by the caller (Workspace) so that their capacity
/// outlives it: a warm solve allocates nothing. One solve per buffers at a time. The vectors of
/// n entries may hold more (they only grow); entries from n on mean nothing.
struct SmallIslandBuffers {
    std::vector<double> factor;   ///< n x n, row stride n: A_FF, then L_FF, in its leading block
    std::vector<double> rhs, inverse_diagonal, lo, hi, w, scale;  ///< inverse_diagonal: 1 / L_FF(k,k)
    std::vector<int> free, loaded, unpinned;  ///< free rows, tight rows with x != 0, rows that are not pinned friction
    std::vector<RowState> requested, best_states, trial, kept_states;
    std::vector<double> kept_x, kept_w, kept_scale;
    std::vector<double> best_x;  ///< x of the least infeasible iterate (best_states), where the active set starts
    std::vector<double> target;  ///< the active set's face minimizer x*
    Infeasibility inf, best_inf;
};

/// True when an island of n rows belongs on this path: Method::Bpp, Frozen friction and
/// 1 <= n <= options.tuning.dense_island_rows (callers that assemble A choose its form by this).
bool is_small_island(int n, const Options& options);

/// True when solve_small_island may take the problem: is_small_island and A in the dense form
/// (Problem::A, no Problem::sparse).
bool takes_small_island(const Problem& problem, const Options& options);

/// Solves a validated problem that takes_small_island accepts, from start.states (or all free).
/// x: out, n entries. r: out; on success status Converged, the pivot counters (every step a
/// refactorization), tight_per_step, states, tight and the residuals of x (as compute_residuals
/// gives them). Returns false, leaving x and r unspecified, when the island needs the general
/// driver (a spent budget, a breakdown, or an answer that is not finite).
bool solve_small_island(const Problem& problem, const Options& options, const Start& start, SmallIslandBuffers& buffers,
                        std::vector<double>& x, Result& r);

}  // namespace ode_bpp::pivoting
