// ode_bpp/validation.h: checking an MLCP before any solver touches it.
//
// Index space: the caller's original row order (messages name original rows).
#pragma once

#include "ode_bpp/export.h"

#include <string>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp {

/// The verdict of validate(): valid, or the first defect found, naming the row and the reason.
struct ValidationResult {
    bool valid = true;
    std::string message;  ///< empty when valid, e.g. "row 7: lo (1.5) > hi (0.3)"
};

/// Checks a problem against the contract of ODE's MLCP (ode/src/lcp.h) that every method relies on:
///  - n >= 1, A/b/lo/hi non-null, lda >= n, strides >= 1, 0 <= nub <= n;
///  - A's lower triangle (diagonal included) finite, diagonal > 0 (a sparse A: n rows);
///  - b finite; lo, hi not NaN (+-inf allowed), lo <= hi, and lo <= 0 <= hi as ODE requires
///    (its Dantzig starts from x = 0, which must be feasible); a friction row's lo is ignored;
///  - findex (if given): -1 or in [0, n), never the row itself, never a friction row (a normal
///    cannot itself be a friction row), never a friction row inside the first nub rows, and the
///    friction coefficient hi_i = mu_i >= 0 (+inf allowed: ODE's "never slips", an unbounded row;
///    NaN and negative refused);
///  - block structure (if num_blocks > 0): block_row strictly increasing from 0 to n, bodies >= -1
///    (the findex and block rules are the file format's too: structure_rules.h).
/// Reads only; O(n^2) for a dense A's lower triangle, O(non-zeros) for a sparse A.
ODE_BPP_API ValidationResult validate(const Problem& problem);

/// validate() without A's entries (sizes, bounds, findex, blocks). O(n).
ODE_BPP_API ValidationResult validate_structure(const Problem& problem);

/// validate_structure() for a problem whose A the caller holds in another form (an ODE island's
/// J, J M^-1 and CFM, which a matrix-free method reads instead: ode/jacobian_pgs.h), so that
/// A and lda are not looked at. O(n).
ODE_BPP_API ValidationResult validate_rows(const Problem& problem);

/// A's entries (lower triangle and diagonal): finite, diagonal > 0; the same first defect and
/// message as validate() on the dense form. O(non-zeros).
ODE_BPP_API ValidationResult validate_matrix(const linalg::SymmetricRows& A);
/// The same for a problem that passed validate_structure, whichever form its A comes in: O(n^2)
/// for the dense form's lower triangle, O(non-zeros) for the sparse form.
ODE_BPP_API ValidationResult validate_matrix(const Problem& problem);

/// Checks that a warm start fits the problem: empty (no warm start) or exactly n entries.
ODE_BPP_API ValidationResult validate_warm_start(const Problem& problem, const std::vector<RowState>& warm_start);

}  // namespace ode_bpp
