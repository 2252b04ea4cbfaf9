#include "baselines/dantzig.h"

namespace ode_bpp::baselines {

namespace {
DantzigBackend g_backend = nullptr;  // constant-initialized: safe to install from a static initializer
}  // namespace

void install_dantzig(DantzigBackend backend) { g_backend = backend; }

DantzigOutcome solve_dantzig(const Problem& problem, const linalg::SymmetricRows& A, std::vector<double>& x) {
    if (g_backend == nullptr) {
        x.assign(static_cast<std::size_t>(problem.n), 0.0);
        return DantzigOutcome::Unavailable;
    }
    return g_backend(problem, A, x) ? DantzigOutcome::Solved : DantzigOutcome::Refused;
}

}  // namespace ode_bpp::baselines
