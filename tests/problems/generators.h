// Seeded problem generators shared by the tests and the benchmarks. Same arguments, same
// problem, on every machine (std::mt19937_64 and explicit transforms, no std distributions).
#pragma once

#include <cstdint>
#include <vector>

#include "problems/owned_problem.h"

namespace ode_bpp::problems {

/// A dense n x n SPD matrix Q diag(lambda) Q^T, row-major with stride n, Q a random orthogonal
/// matrix, lambda log-spaced from 1 down to 1/cond (so ||A||_2 = 1 and cond_2(A) = cond).
std::vector<double> random_spd(int n, double cond, std::uint64_t seed);

/// A boxed MLCP on random_spd(n, cond, seed): rows 0 .. nub-1 unbounded; then
/// friction_contacts ODE-style contacts, each a normal row (lo = 0, hi = inf) followed by two
/// friction rows (findex = the normal, hi = mu in [0.3, 1]); then rows with random boxes
/// ([-l, u], [0, inf) or (-inf, u]). b is scaled so that a good share of the rows end up tight.
/// Requires nub + 3 * friction_contacts <= n.
OwnedProblem random_boxed_mlcp(int n, int nub, int friction_contacts, double cond, std::uint64_t seed);

/// An ODE-like island: `links` >= 1 bodies in a chain lying on the ground, joined by links - 1
/// ball joints (3 unbounded rows each), the last link `mass_ratio` times heavier,
/// and `contacts` ground contacts (normal + 2 friction rows, mu = 0.8) spread along the chain,
/// listed after all joint rows as ODE does. A = J M^-1 J^T + (cfm / h) I with h = 1/60, b from
/// gravity and a sliding initial velocity. Carries the block structure (joints, bodies).
OwnedProblem chain_mlcp(int links, int contacts, double mass_ratio = 100, double cfm = 1e-8);

/// The capstan: a planar chain of `links` bodies (x, y, theta) lying over a fixed drum of radius 1
/// over `wrap` radians centred on the top, joined by
/// planar ball joints (2 unbounded rows each), one contact per link with the drum (normal +
/// one friction row, findex = the normal, coefficient mu), the last link `load_ratio` times
/// heavier, every link sliding along the drum. Friction raises the normals that bound it
/// (tension grows like e^(mu * angle) along a wrapped rope), so the map from friction bounds to
/// normals expands for mu * wrap large enough: bounds iterated outside the pivoting do not converge.
/// A = J M^-1 J^T + (cfm / h) I with h = 1/60.
OwnedProblem capstan_mlcp(int links, double wrap, double mu, double load_ratio, double cfm = 1e-8);

}  // namespace ode_bpp::problems
