// Shared pieces for the test_ode_* suites: an island in ODE's sparse form (<ode/mlcp.h>) that owns
// its arrays, and A assembled from it.
#pragma once

#include <ode/mlcp.h>

#include <vector>

#include "linalg/symmetric_rows.h"
#include "ode/assemble.h"
#include "ode/island_view.h"
#include "ode_bpp/solver.h"

namespace ode_bpp::ode::test {

/// The arrays of an island in the sparse form. A generator fills joints, J, JinvM, cfm, pairsbx,
/// pairslh and findex and sets p.m and p.nb; point_at_arrays then points p at them.
struct SparseIsland {
    void point_at_arrays() {
        p.nj = static_cast<int>(joints.size());
        p.joints = joints.data();
        p.J = J.data();
        p.JinvM = JinvM.data();
        p.cfm = cfm.data();
        p.pairsbx = pairsbx.data();
        p.pairslh = pairslh.data();
        p.findex = findex.data();
    }
    /// b, lo, hi, findex, nub and the joints' blocks as the world hook views them (A not formed).
    Problem rows() { return view.rows_of(p); }
    /// x where ODE keeps it, interleaved with b.
    Strided x() { return Strided{pairsbx.data() + 1, 2}; }

    std::vector<dMLCPJoint> joints;
    std::vector<double> J, JinvM, cfm, pairsbx, pairslh;
    std::vector<int> findex;
    dMLCP p{};
    IslandView view;
};

/// A of an island, assembled from scratch in its own row order.
inline linalg::SymmetricRows assembled(const dMLCP& island) {
    linalg::SymmetricRows rows;
    AssemblyBuffers buffers;
    assemble_rows(island, rows, buffers, {});
    return rows;
}

}  // namespace ode_bpp::ode::test
