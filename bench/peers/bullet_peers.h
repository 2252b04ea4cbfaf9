// Bullet 3.24's MLCP solvers (libbullet-dev, double precision: bullet-float64) on an
// ode_bpp::Problem.
#pragma once

#include <string>
#include <vector>

#include "ode_bpp/solver.h"
#include "peer_registry.h"

namespace ode_bpp::peers {

/// btDantzigSolver (Bullet's copy of ODE's Dantzig, friction through limitDependency = findex).
/// Its sanity cut-off |x_i| >= 1000 (a guard for game-scale impulses) is lifted, since the
/// paper's scenes carry tonnes. x: n entries, original order.
bench::PeerStatus bullet_dantzig(const Problem& problem, double* x);

/// btSolveProjectedGaussSeidel with exactly `sweeps` sweeps from x = 0; friction bounds scaled
/// by the current normal (limitDependency = findex) inside each sweep.
bench::PeerStatus bullet_pgs(const Problem& problem, int sweeps, double* x);

/// btLemkeSolver with lo/hi bounds (a 2n-variable LCP built on a dense inverse of A): fixed
/// bounds only, so friction is frozen (solve_frozen) and infinite bounds are made finite
/// (make_bounds_finite). Its |x_i| > 1e5 rejection is lifted as for Dantzig; its loop budget is
/// raised to max(1000, 20 n) pivots. Skipped above max_rows rows (its cost is O(n^3) per solve).
bench::PeerStatus bullet_lemke(const Problem& problem, int max_rows, double* x);

/// "bullet-dantzig", "bullet-lemke" and "bullet-pgs-<k>" for each k of sweep_counts.
std::vector<bench::PeerMethod> bullet_peer_methods(const std::vector<int>& sweep_counts, int lemke_max_rows);

}  // namespace ode_bpp::peers
