// What every peer adapter needs from an ode_bpp::Problem: a dense, owning copy in the layout
// the ODE-derived peers take, and ODE's "frozen" friction for peers that only know fixed bounds.
//
// Index space: the problem's original row order throughout; nothing is permuted here.
#pragma once

#include <functional>
#include <vector>

#include "ode_bpp/solver.h"
#include "peer_registry.h"

namespace ode_bpp::peers {

/// An owning dense copy of ODE's MLCP  A x = b + w  with box bounds (solver.h):
/// A full and symmetric (mirrored from the problem's lower triangle), row-major with row stride
/// `stride` >= n (padding zero); rows < nub get lo = -inf, hi = +inf; a friction row i
/// (findex[i] >= 0) keeps hi_i = mu_i and gets lo_i = -mu_i, the form both ODE's Dantzig
/// (which overwrites them with +-|mu_i x_findex[i]|) and Bullet's PGS (which scales them by
/// x_findex[i]) expect.
struct DenseMlcp {
    int n = 0;
    int nub = 0;
    int stride = 0;
    std::vector<double> A;           ///< n * stride
    std::vector<double> b, lo, hi;   ///< n each
    std::vector<int> findex;         ///< n, -1 for none
    bool has_friction() const;
};

/// The copy described above; stride defaults to n.
DenseMlcp dense_copy(const Problem& problem, int stride = 0);

/// ODE's padded row stride dPAD(n) (ODE common.h, also DART's copy): n rounded up to a multiple
/// of 4 for n > 1. DART's solvers read A with this stride.
int ode_padded_stride(int n);

/// A solver for box bounds that do not depend on x: `fixed` has no friction rows (findex all -1),
/// x (n entries) is its start on entry and its answer on return; true when the peer reports success.
using FixedBoundSolver = std::function<bool(const DenseMlcp& fixed, double* x)>;

/// ODE's Dantzig friction semantics (ode_bpp's FrictionMode::Frozen) for fixed-bound peers:
/// a first solve with every friction row held at 0, then the friction bounds +-|mu_i x_findex[i]|
/// taken from those normals (the first answer projected onto its box, so rounding below a zero
/// bound gives a zero friction box) and kept fixed for a second solve started from the first answer.
/// Problems without friction are solved once. Rows whose box is a point (friction rows in the
/// first solve, or under a zero normal) are taken out of the problem the peer sees, with their
/// fixed values moved into b; Lemke-type peers degenerate on zero-width boxes. x: n entries,
/// original order.
bench::PeerStatus solve_frozen(const Problem& problem, const FixedBoundSolver& solver, double* x);

/// Replaces infinite bounds by +-big for peers that need finite ones (Lemke's 2n-variable
/// reformulation of a box): big = 1e6 * max_i |b_i| / A_ii, i.e. far beyond the impulses the
/// right-hand side can produce through the diagonal. An answer pinned at +-big is wrong, and the
/// natural residual (computed with the true bounds) shows it.
void make_bounds_finite(DenseMlcp& problem);

/// True when every x_i is finite.
bool all_finite(const double* x, int n);

}  // namespace ode_bpp::peers
