// Linked friction rows of FrictionMode::Consistent, solved with the free rows in one pivot step
// (permuted space throughout).
//
// A friction row j at a bound while its normal n(j) is free takes x_j = s_j mu_j x_n(j), s_j = +1
// at hi and -1 at lo: its bound moves with the solution. Fixing it at the previous iterate's bound
// and iterating on the bounds outside the pivoting loop converges only while the map from bounds
// to normals contracts; where friction raises its own normals (a chain wrapped around a drum,
// the capstan effect) it expands, and no damping helps. Within one index set the linked system is
// linear, so each step solves it exactly:
//     A_FF x_F + A_FC x_C = r_F,   x_C = D E x_F,   D = diag(s_j mu_j),  E x_F = (x_n(j))_j
//  => y = A_FF^-1 r_F,  Z = A_FF^-1 A_FC  (|C| more solves with the step's factor),
//     (I + D E Z) x_C = D E y,   x_F = y - Z x_C.
// The normals are taken as signed (x_n >= 0 for contacts; a negative one makes its row infeasible
// and the next step frees or pins it), so the system stays linear.
#pragma once

#include <vector>

#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/free_solver.h"

namespace ode_bpp::pivoting {

/// Solves the linked rows (ascending permuted indices, each tight with a free normal) with the
/// free ones. in: tight (n flags; linked rows are tight), states (n), x (n): x_F = y, the answer
/// of the step with x = 0 at the linked rows, whose factor is the solver's latest solve_free.
/// out: x_F corrected and x_C set. Returns false, leaving x untouched, when I + D E Z is singular
/// to working precision (the caller then keeps the linked rows at their previous bounds).
bool solve_linked_rows(const BoxedLcp& lcp, FreeSolver& solver, const std::vector<int>& linked,
                       const std::vector<RowState>& states, const std::vector<char>& tight, std::vector<double>& x);

}  // namespace ode_bpp::pivoting
