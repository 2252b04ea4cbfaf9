// A = J M^-1 J^T + diag(cfm) from the world step's Jacobian (paper Eq. 2), straight into
// compressed symmetric rows, without the dense m x m array ODE would otherwise fill.
//
// Index space: ODE's island row order (original). Input layout: <ode/mlcp.h> (the sparse form).
#pragma once

#include <ode/mlcp.h>

#include <cstddef>
#include <vector>

#include "linalg/symmetric_rows.h"

namespace ode_bpp::ode {

/// Joints by body: the joints on body b are joints[first[b] .. first[b+1]-1], increasing.
struct Incidence {
    std::vector<int> first, joints, next;
};

/// The bodies two joints p and q share, as pairs of sides (p's side, q's side), p's body[0]
/// first: the order in which ODE adds their terms.
struct SharedSides {
    int count = 0;
    int p_side[2] = {0, 0}, q_side[2] = {0, 0};
};

/// For each joint p, the earlier joints it shares a body with (increasing) and the sides they
/// share: joint[k] and sides[k] for k in first[p] .. first[p+1]-1. Block (p, joint[k]) of A.
struct Couplings {
    std::vector<int> first, joint;
    std::vector<SharedSides> sides;
};

/// Where assemble_rows stored the entries of the island it assembled last, so that an island of
/// the same structure (as a rule the same island one step later) writes its values straight into
/// the stored rows, without listing its entries and building the rows again.
struct AssemblyPattern {
    const linalg::SymmetricRows* rows = nullptr;  ///< the matrix it describes; null: none
    /// m, nb, nj, then each joint's row, m and two bodies: what fixes the entries formed
    std::vector<int> structure;
    std::vector<int> order;      ///< the order the rows were stored in (empty: the island's own)
    std::vector<int> to_stored;  ///< m entries: the stored row of each island row
    /// Two per lower entry formed, in the order they are formed: its positions in its row's and
    /// its column's stored row (linalg::SymmetricRows::entry_positions)
    std::vector<int> slots;
    Couplings couplings;  ///< the island's couplings, which the structure fixes
};

/// The buffers of an assembly, kept by the caller (ode/island_view.h) so that assembling the
/// next island allocates nothing once they have grown. One assembly per buffers at a time, and
/// one output matrix per buffers.
struct AssemblyBuffers {
    Incidence incidence;
    std::vector<int> neighbours;
    Couplings couplings;
    std::vector<linalg::LowerEntry> lower;
    std::vector<double> diagonal;
    std::vector<int> structure;
    AssemblyPattern pattern;
};

/// True when the island comes in the sparse form (J, JinvM, cfm and the joints, A null).
bool has_sparse_form(const dMLCP& island);

/// Row r's Jacobian (or J M^-1: width dMLCP_J_ROW or dMLCP_JINVM_ROW) for side s (0: body[0],
/// 1: body[1]) of its joint: the joint's m rows for body[0], then its m rows for body[1], from
/// row 2 * joint.row on (<ode/mlcp.h>).
inline const dReal* side_row(const dReal* base, int width, const dMLCPJoint& joint, int side, int r) {
    const int index = 2 * joint.row + side * joint.m + (r - joint.row);
    return base + static_cast<std::ptrdiff_t>(index) * width;
}

/// Assembles A of an island in the sparse form into out (its storage reused).
///
/// Block (p,q) of A, for joints p and q that share a body, is the sum over the shared bodies b of
/// JinvM_{p,b} J_{q,b}^T; no other block is formed, so the cost is O(entries of A) (6 multiply-adds
/// each) and the memory O(entries). Each entry is summed in the order ODE's Stage2b/2c use
/// (lower entry (i,j), i > j: row i's JinvM against row j's J, body[0] of row i's joint first,
/// the diagonal starting from cfm_i), so the values equal those read from ODE's dense A bit for
/// bit. Every entry of these blocks is stored, an exact zero too: the pattern is the joints'
/// (linalg::SymmetricRows's structural pattern, which a dense A with its blocks gets too), so it
/// does not follow entries that ODE's sums give as 0 one step and 1e-30 the next.
/// Island: has_sparse_form. order: empty, or a permutation of the island's rows (order[new] =
/// old) to store A in (linalg::SymmetricRows::order), the one the solver will factor in, so that
/// it need not permute A again (the same rows, entry for entry).
/// When out was last assembled with these buffers from an island of the same structure and in the
/// same order, the pattern is the same: the values are written in place (buffers.pattern),
/// O(entries) with no listing, counting or sorting.
void assemble_rows(const dMLCP& island, linalg::SymmetricRows& out, AssemblyBuffers& buffers,
                   const std::vector<int>& order = {});

/// The same entries, summed the same way, into a dense lower triangle: A[i * lda + j] for j <= i
/// (output; the strict upper triangle is not written), lda >= island.m. O(m^2) to clear it, then
/// O(entries): for small islands (Tuning::dense_island_rows), whose solve reads A densely.
void assemble_dense_lower(const dMLCP& island, double* A, int lda, AssemblyBuffers& buffers);

}  // namespace ode_bpp::ode
