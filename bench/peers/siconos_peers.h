// Siconos numerics 4.4 (libsiconos-numerics-dev) relay solvers on an ode_bpp::Problem.
//
// A relay problem  w = M z + q,  -w in N_[lb,ub](z)  is ODE's boxed MLCP with M = A, q = -b,
// z = x, [lb, ub] = [lo, hi] when the bounds are fixed; friction is therefore frozen
// (solve_frozen), and infinite bounds are made finite (make_bounds_finite).
#pragma once

#include <string>
#include <vector>

#include "ode_bpp/solver.h"
#include "peer_registry.h"

namespace ode_bpp::peers {

/// relay_lexicolemke (the relay turned into an LCP of 2n variables, lexicographic Lemke),
/// pivot budget max(1000, 20 n). Skipped above max_rows rows. x: n entries, original order.
bench::PeerStatus siconos_lemke(const Problem& problem, int max_rows, double* x);

/// relay_pgs with exactly `sweeps` sweeps (tolerance 0) from x = 0, in each fixed-bound solve.
bench::PeerStatus siconos_pgs(const Problem& problem, int sweeps, double* x);

/// "siconos-lemke" and "siconos-pgs-<k>" for each k of sweep_counts.
std::vector<bench::PeerMethod> siconos_peer_methods(const std::vector<int>& sweep_counts, int lemke_max_rows);

}  // namespace ode_bpp::peers
