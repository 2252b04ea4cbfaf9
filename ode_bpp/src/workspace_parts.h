// What a Workspace (ode_bpp/workspace.h) holds: one part per stage of solve() (solver.cpp), each
// handed to that stage alone.
#pragma once

#include <vector>

#include "linalg/symmetric_rows.h"
#include "ode_bpp/workspace.h"
#include "pivoting/bpp_driver.h"
#include "pivoting/small_island.h"
#include "residuals.h"
#include "unbounded_friction.h"

namespace ode_bpp {

struct Workspace::Parts {
    /// A dense problem's matrix read into compressed rows (original order).
    linalg::SymmetricRows rows;
    /// The view with friction rows of mu = +inf as unbounded rows.
    UnboundedFriction unbounded_friction;
    pivoting::SmallIslandBuffers small_island;
    pivoting::BppWorkspace bpp;
    ResidualBuffers residuals;
    /// The answer in the caller's order before it is copied into the caller's x.
    std::vector<double> answer;
    /// A spent Result's index set (Workspace::recycle), whose capacity the next small-island
    /// Result takes over.
    std::vector<RowState> spare_states;
};

/// The workspace of the calling thread, for the overloads of solve() without one.
Workspace& thread_workspace();

}  // namespace ode_bpp
