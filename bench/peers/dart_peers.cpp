#include "dart_peers.h"

#include <algorithm>
#include <optional>

#include <dart/constraint/DantzigBoxedLcpSolver.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>

#include "peer_problem.h"

namespace ode_bpp::peers {

namespace {

/// Runs the solver from x = 0; returns what it claimed, or nullopt (x zeroed) for a non-finite x.
std::optional<bool> run_dart(dart::constraint::BoxedLcpSolver& solver, const Problem& problem, double* x) {
    // DART's solvers take ODE's layout: A row-major with stride dPAD(n), and they modify A.
    DenseMlcp d = dense_copy(problem, ode_padded_stride(problem.n));
    std::fill(x, x + problem.n, 0.0);
    const bool ok = solver.solve(d.n, d.A.data(), x, d.b.data(), d.nub, d.lo.data(), d.hi.data(), d.findex.data(), false);
    if (all_finite(x, problem.n)) return ok;
    std::fill(x, x + problem.n, 0.0);
    return std::nullopt;
}

}  // namespace

bench::PeerStatus dart_dantzig(const Problem& problem, double* x) {
    dart::constraint::DantzigBoxedLcpSolver solver;
    const std::optional<bool> claimed = run_dart(solver, problem, x);
    return claimed.value_or(false) ? bench::PeerStatus::Solved : bench::PeerStatus::Failed;
}

bench::PeerStatus dart_pgs(const Problem& problem, int sweeps, double* x) {
    dart::constraint::PgsBoxedLcpSolver solver;
    solver.setOption(dart::constraint::PgsBoxedLcpSolver::Option(sweeps, 0.0, 0.0));
    // A fixed sweep count is not a claim of convergence: its accuracy is the residual's to judge.
    return run_dart(solver, problem, x) ? bench::PeerStatus::Iterated : bench::PeerStatus::Failed;
}

std::vector<bench::PeerMethod> dart_peer_methods(const std::vector<int>& sweep_counts) {
    std::vector<bench::PeerMethod> methods{{"dart-dantzig", 0, dart_dantzig}};
    for (int k : sweep_counts)
        methods.push_back({"dart-pgs-" + std::to_string(k), k,
                           [k](const Problem& problem, double* x) { return dart_pgs(problem, k, x); }});
    return methods;
}

}  // namespace ode_bpp::peers
