#include "siconos_peers.h"

#include <algorithm>
#include <cstring>
#include <memory>

#include <siconos/numerics/NumericsMatrix.h>
#include <siconos/numerics/RelayProblem.h>
#include <siconos/numerics/Relay_Solvers.h>
#include <siconos/numerics/SolverOptions.h>
#include <siconos/numerics/relay_cst.h>

#include "peer_problem.h"

namespace ode_bpp::peers {

namespace {

using SolverFunction = void (*)(RelayProblem*, double*, double*, int*, SolverOptions*);

/// One fixed-bound relay solve through `function`; true when Siconos reports info == 0.
bool solve_relay(const DenseMlcp& fixed, int solver_id, SolverFunction function, int max_iterations, double tolerance,
                 double* x) {
    DenseMlcp finite = fixed;
    make_bounds_finite(finite);
    const int n = fixed.n;
    // Siconos' dense storage is column-major; A is symmetric, so the row-major copy is the same.
    std::unique_ptr<NumericsMatrix, NumericsMatrix* (*)(NumericsMatrix*)> M(NM_create(NM_DENSE, n, n), NM_free);
    for (int i = 0; i < n; ++i)
        std::memcpy(M->matrix0 + static_cast<std::size_t>(i) * n, finite.A.data() + static_cast<std::size_t>(i) * finite.stride,
                    sizeof(double) * n);
    std::vector<double> q(n), w(n, 0.0);
    for (int i = 0; i < n; ++i) q[i] = -finite.b[i];
    RelayProblem relay{n, M.get(), q.data(), finite.lo.data(), finite.hi.data()};
    std::unique_ptr<SolverOptions, void (*)(SolverOptions*)> options(solver_options_create(solver_id), solver_options_delete);
    options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iterations;
    options->dparam[SICONOS_DPARAM_TOL] = tolerance;
    int info = 0;
    function(&relay, x, w.data(), &info, options.get());
    if (all_finite(x, n)) return info == 0;
    std::fill(x, x + n, 0.0);
    return false;
}

}  // namespace

bench::PeerStatus siconos_lemke(const Problem& problem, int max_rows, double* x) {
    if (problem.n > max_rows) {
        std::fill(x, x + problem.n, 0.0);
        return bench::PeerStatus::Skipped;
    }
    const FixedBoundSolver lemke = [](const DenseMlcp& fixed, double* answer) {
        return solve_relay(fixed, SICONOS_RELAY_LEMKE, relay_lexicolemke, std::max(1000, 20 * fixed.n), 1e-12, answer);
    };
    return solve_frozen(problem, lemke, x);
}

bench::PeerStatus siconos_pgs(const Problem& problem, int sweeps, double* x) {
    const FixedBoundSolver pgs = [sweeps](const DenseMlcp& fixed, double* answer) {
        // tolerance 0: every sweep runs, so info (not converged) carries no news; finiteness does.
        solve_relay(fixed, SICONOS_RELAY_PGS, relay_pgs, sweeps, 0.0, answer);
        return all_finite(answer, fixed.n);
    };
    const bench::PeerStatus status = solve_frozen(problem, pgs, x);
    return status == bench::PeerStatus::Solved ? bench::PeerStatus::Iterated : status;
}

std::vector<bench::PeerMethod> siconos_peer_methods(const std::vector<int>& sweep_counts, int lemke_max_rows) {
    std::vector<bench::PeerMethod> methods{
        {"siconos-lemke", 0, [lemke_max_rows](const Problem& p, double* x) { return siconos_lemke(p, lemke_max_rows, x); }}};
    for (int k : sweep_counts)
        methods.push_back({"siconos-pgs-" + std::to_string(k), k,
                           [k](const Problem& problem, double* x) { return siconos_pgs(problem, k, x); }});
    return methods;
}

}  // namespace ode_bpp::peers
