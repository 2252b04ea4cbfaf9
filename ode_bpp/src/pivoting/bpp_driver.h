// The BPP methods end to end: ordering, factor strategy, friction policy, the rescue
// continuation of a fixed-bound solve that does not converge plainly (Tuning::rescue_after), the
// optional up-front continuation and the regularize-on-breakdown retry around the pivoting loop.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "ode_bpp/solver.h"
#include "linalg/symmetric_rows.h"
#include "pivoting/kept_buffers.h"
#include "residuals.h"

namespace ode_bpp::pivoting {

/// The buffers of solve_bpp (bpp_driver.cpp: the permuted problem, the factor strategies' and the
/// pivoting loop's), kept by the caller so that their capacity outlives one solve. One solve per
/// workspace at a time.
struct BppBuffers;
using BppWorkspace = KeptBuffers<BppBuffers>;
extern template class KeptBuffers<BppBuffers>;  // instantiated where BppBuffers is defined

/// The block principal pivoting methods: BppChol, BppDown, BppSky and Bpp.
bool is_bpp(Method method);

/// The factor strategy solve_bpp takes: the method's own, except Bpp on small islands
/// (Tuning::dense_island_rows), which factors densely as BppChol.
Method strategy_of(const Problem& problem, const Options& options);

/// True for the strategies that factor in a chosen permutation (Bpp, BppSky; the others in the
/// problem's order, densely).
bool strategy_orders(Method strategy);

/// n (n + 1) / 2: the entries of an n-row dense triangle, which the strategies that do not order
/// factor in, and the most any factor of n rows holds.
std::int64_t dense_triangle_entries(int n);

/// True when a BPP method's factor of an n-row island might exceed Options::max_factor_entries:
/// its dense triangle (dense_triangle_entries) would. An island within the limit that way is not ordered or
/// counted to find out (solve() and the world hook both ask this first).
bool factor_may_be_too_large(int n, const Options& options);

/// Solves a validated problem with options.method in {BppChol, BppDown, BppSky, Bpp}.
/// A: linalg::SymmetricRows(problem, {}) or problem.sparse, the problem's matrix, stored in any
/// order (SymmetricRows::order; stored in the order the solver factors in, it is not copied).
/// x: out, n entries, original space (zero when the status is NotSpd).
/// Fills status, message, fallback ("regularized" or empty), the counters, tight, states
/// (original space) and factor_error; leaves the residual fields to the caller.
/// at_answer: out, w = A x - b and the row scales |A||x| + |b| at x (original space, each row
/// summed as residual_vectors sums it) when x is the pivoting loop's converged iterate on the
/// unshifted problem, whose w the loop has computed already; empty otherwise.
Result solve_bpp(const Problem& problem, const linalg::SymmetricRows& A, const Options& options, const Start& start,
                 std::vector<double>& x, BppWorkspace& workspace, ResidualBuffers& at_answer);

/// Entries of the envelope (linalg::SkylineShape::size) that solve_bpp's factor of this problem
/// would hold, in the permutation solve_bpp would factor in: A's stored order where
/// start.ordering names it (O(n)), start.ordering where it is a permutation, else the one it
/// would choose (ordering::choose_ordering with the same warm-start hint), returned in chosen so
/// that a solve handed it as Start::ordering does not order A again (chosen is empty in the
/// other cases). n(n+1)/2 for the strategies that factor densely. A: stored in any order;
/// scratch: A in the problem's order where it is stored in another.
std::int64_t planned_factor_entries(const Problem& problem, const linalg::SymmetricRows& A, const Options& options,
                                    const Start& start, linalg::SymmetricRows& scratch, std::vector<int>& chosen);

}  // namespace ode_bpp::pivoting
