// One island of the patched world step (<ode/mlcp.h>) as a Problem (solver.h): the single view
// that the solver hook and file capture share.
//
// Index space: ODE's island row order (original). b, lo and hi are read in place from ODE's
// interleaved pairs (b = pairsbx[2i], lo = pairslh[2i], hi = pairslh[2i+1]); joint k becomes row
// block k with its two bodies; A is ODE's dense lower triangle (row stride skip) or, in the sparse
// form, assembled from J, J M^-1 and the CFM (ode/assemble.h).
#pragma once

#include <ode/mlcp.h>

#include <string>
#include <vector>

#include "linalg/symmetric_rows.h"
#include "ode/assemble.h"
#include "ode_bpp/solver.h"

namespace ode_bpp::ode {

/// The storage a view needs beyond ODE's arrays; reused from island to island.
class IslandView {
public:
    /// The view of `island`, valid while this object and the island's arrays live (it points
    /// into both). An island in the sparse form is assembled (ode/assemble.h): into compressed
    /// rows, O(entries of A); or, with dense_lower, into a dense lower triangle for the
    /// small-island path (pivoting/small_island.h), O(m^2). O(rows) otherwise.
    /// order: empty, or the row order the solver will factor in (Start::ordering): compressed
    /// rows are stored in it (linalg::SymmetricRows::order) when it is a permutation of the
    /// island's rows other than the identity.
    Problem of(const dMLCP& island, bool dense_lower = false, const std::vector<int>& order = {});
    /// The view of `island` without A (A, sparse null): b, lo, hi, findex, nub and the joints'
    /// blocks, for a method that reads the sparse form itself (ode/jacobian_pgs.h). O(rows).
    Problem rows_of(const dMLCP& island);

private:
    std::vector<int> block_row_, block_body_;
    linalg::SymmetricRows assembled_;
    std::vector<double> dense_;  ///< row stride m, m x m entries or more: the lower triangle of a small island
    AssemblyBuffers assembly_;
};

/// The first joint whose rows do not continue where the previous joint's ended (joints must tile
/// rows 0 .. m-1 in order, each with m > 0), or -1 when they tile.
int first_untiled_joint(const dMLCP& island);

/// An empty message, or what keeps a method that reads the sparse form itself from reading the
/// island safely: no joints, joints that do not tile rows 0 .. m-1 in order (each row's J is
/// found through its joint), or a body outside [-1, nb) (per-body arrays are indexed by it).
std::string structure_defect(const dMLCP& island);

}  // namespace ode_bpp::ode
