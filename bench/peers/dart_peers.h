// DART 6.12's boxed-LCP solvers (libdart-dev) on an ode_bpp::Problem.
#pragma once

#include <string>
#include <vector>

#include "ode_bpp/solver.h"
#include "peer_registry.h"

namespace ode_bpp::peers {

/// dart::constraint::DantzigBoxedLcpSolver (DART's copy of ODE's Dantzig, friction through
/// findex). x: n entries, original order. A, b and the bounds are copied first, since the solver
/// overwrites them; the copy is part of the call's cost, as it is for any caller.
bench::PeerStatus dart_dantzig(const Problem& problem, double* x);

/// dart::constraint::PgsBoxedLcpSolver with exactly `sweeps` sweeps (its early-exit tolerances
/// set to 0), starting from x = 0; friction through findex. Returns Solved when x is finite.
bench::PeerStatus dart_pgs(const Problem& problem, int sweeps, double* x);

/// "dart-dantzig" and "dart-pgs-<k>" for each k of sweep_counts.
std::vector<bench::PeerMethod> dart_peer_methods(const std::vector<int>& sweep_counts);

}  // namespace ode_bpp::peers
