// Which symmetric permutation each BPP method factors in (paper Sec. 3.4 and our variant).
#pragma once

#include <limits>
#include <vector>

#include "ode_bpp/solver.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::ordering {

/// What a Bpp solve's first fixed-bound solve holds tight besides the warm start's tight rows.
enum class FirstSolve {
    AsWarmStart,        ///< nothing more
    FrictionRowsTight,  ///< every friction row (findex >= 0): Frozen friction holds them at 0 there
                        ///< (pivoting/friction_policy.h, solve_frozen)
};

/// perm[new] = old (n entries) for the method:
///  - BppChol, BppDown: the identity (Alg. 1 and Alg. 2 without skyline use no ordering);
///  - BppSky: Cuthill-McKee over the constraint graph (Sec. 3.4);
///  - Bpp: the caller's order wherever factoring in it costs less than computing an ordering
///    (small islands), or, with `first`'s rows to hold, that order with them moved last where
///    that prices lower (warm_solve_price); else reverse Cuthill-McKee, whose envelope is never
///    larger than Cuthill-McKee's (Liu & Sherman); where rows are expected tight (the warm start's, original space, n entries or
///    empty, and those of `first`), also both orders with those rows moved last (where deleting
///    or refactoring them touches the fewest columns), and the lowest warm_solve_price wins
///    (moving them can widen the envelope more than it saves). A candidate whose factorization
///    alone costs at least the best price (flagged_rows_factor_bound, then
///    linalg::full_refactor_cost) is rejected unpriced: the choice is the same. Without
///    `price_reorderings` (Tuning::price_tight_last_orderings) reverse Cuthill-McKee stands
///    unpriced; the caller's order is priced either way.
/// A: the problem's matrix in original order (for envelope sizes).
std::vector<int> choose_ordering(Method method, const Problem& problem, const linalg::SymmetricRows& A,
                                 const std::vector<RowState>& warm_start, FirstSolve first = FirstSolve::AsWarmStart,
                                 bool price_reorderings = true);

/// True when factoring in the caller's own order, kStepsPerWarmSolve times, costs less than
/// computing an ordering at all (kOrderingCostPerEntry per row and entry of A): Bpp then keeps
/// that order, or moves the friction rows last (priced either way). A: original order.
bool ordering_cannot_pay(const linalg::SymmetricRows& A);

/// choose_ordering's first candidate from the problem's row blocks alone, without A: for BppSky
/// Cuthill-McKee on the block graph (its whole choice), for Bpp the reverse (the order the
/// tight-last candidates compete with, and the choice for islands without rows expected tight);
/// the identity for the other methods, and where the blocks do not tile the rows. O(n + the block
/// graph's edges).
std::vector<int> block_ordering(Method method, const Problem& problem);

/// Warm-started solves take a few steps (two fixed-bound solves in Frozen mode).
constexpr double kStepsPerWarmSolve = 3;

/// Estimated price (step_cost.h units) of factoring L0 in the ordering perm (perm[new] = old) and
/// taking kStepsPerWarmSolve steps, each the cheaper of deletion and refactoring: the first at
/// the tight set `first_tight`, the others at `tight` (original space, n flags each; an empty
/// first_tight: every step at `tight`). A step with no tight row solves with L0 and costs
/// nothing more. A: original order.
double warm_solve_price(const linalg::SymmetricRows& A, const std::vector<int>& perm, const std::vector<char>& tight,
                        const std::vector<char>& first_tight = {});

/// A lower bound of linalg::full_refactor_cost in the shape of A under perm (perm[new] = old),
/// from the rows flagged in `rows` (original space, n flags) alone: O(n + their entries), where
/// the whole shape costs O(entries of A). Each flagged row of width w adds w (w + 1) / 2, in the
/// order of perm, until the sum reaches `limit` (what it returns then is still a lower bound).
double flagged_rows_factor_bound(const linalg::SymmetricRows& A, const std::vector<int>& perm,
                                 const std::vector<char>& rows,
                                 double limit = std::numeric_limits<double>::infinity());

}  // namespace ode_bpp::ordering
