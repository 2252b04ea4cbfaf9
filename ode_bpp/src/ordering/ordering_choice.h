// Which symmetric permutation each BPP method factors in (paper Sec. 3.4 and our variant).
#pragma once

#include <vector>

#include "ode_bpp/solver.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::ordering {

/// perm[new] = old (n entries) for the method:
///  - BppChol, BppDown: the identity (Alg. 1 and Alg. 2 without skyline use no ordering);
///  - BppSky: Cuthill-McKee over the constraint graph (Sec. 3.4);
///  - Bpp: the identity wherever factoring in it costs less than computing an ordering (small
///    islands); else the one of Cuthill-McKee and reverse
///    Cuthill-McKee with the smaller envelope; with a
///    warm start (original space, n entries or empty) that has tight rows, also both orders with
///    those rows moved last (where deleting or refactoring them touches the fewest columns), and
///    the lowest warm_solve_price wins (moving them can widen the envelope more than it saves).
/// A: the problem's matrix in original order (for envelope sizes).
std::vector<int> choose_ordering(Method method, const Problem& problem, const linalg::SymmetricRows& A,
                                 const std::vector<RowState>& warm_start);

/// Warm-started solves take a few steps (two fixed-bound solves in Frozen mode).
constexpr double kStepsPerWarmSolve = 3;

/// Estimated price (step_cost.h units) of factoring L0 in the ordering perm (perm[new] = old) and
/// taking kStepsPerWarmSolve steps at the tight set `tight` (original space, n flags), each the
/// cheaper of deletion and refactoring. A: original order.
double warm_solve_price(const linalg::SymmetricRows& A, const std::vector<int>& perm, const std::vector<char>& tight);

}  // namespace ode_bpp::ordering
