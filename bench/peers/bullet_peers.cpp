#include "bullet_peers.h"

#include <algorithm>
#include <limits>

#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btLemkeSolver.h>
#include <BulletDynamics/MLCPSolvers/btSolveProjectedGaussSeidel.h>

#include "peer_problem.h"

namespace ode_bpp::peers {

namespace {

/// btDantzigSolver without its |x| < 1000 acceptance cut (a protected member).
class UncappedDantzig : public btDantzigSolver {
public:
    UncappedDantzig() { m_acceptableUpperLimitSolution = std::numeric_limits<btScalar>::infinity(); }
};

/// Bullet's containers, filled from the dense copy.
struct BulletMlcp {
    btMatrixXu A;
    btVectorXu b, x, lo, hi;
    btAlignedObjectArray<int> dependency;
};

BulletMlcp to_bullet(const DenseMlcp& d) {
    BulletMlcp m;
    m.A.resize(d.n, d.n);
    m.A.setZero();
    m.b.resize(d.n);
    m.x.resize(d.n);
    m.lo.resize(d.n);
    m.hi.resize(d.n);
    m.dependency.resize(d.n);
    for (int i = 0; i < d.n; ++i) {
        for (int j = 0; j < d.n; ++j) {
            const double a = d.A[static_cast<std::size_t>(i) * d.stride + j];
            if (a != 0.0) m.A.setElem(i, j, a);  // setElem keeps Bullet's non-zero bookkeeping
        }
        m.b[i] = d.b[i];
        m.x[i] = 0.0;
        m.lo[i] = d.lo[i];
        m.hi[i] = d.hi[i];
        m.dependency[i] = d.findex[i];
    }
    return m;
}

/// Copies Bullet's x out; false (x zeroed) when it is not finite.
bool copy_out(const btVectorXu& from, int n, double* x) {
    for (int i = 0; i < n; ++i) x[i] = from[i];
    if (all_finite(x, n)) return true;
    std::fill(x, x + n, 0.0);
    return false;
}

}  // namespace

bench::PeerStatus bullet_dantzig(const Problem& problem, double* x) {
    BulletMlcp m = to_bullet(dense_copy(problem));
    UncappedDantzig solver;
    const bool ok = solver.solveMLCP(m.A, m.b, m.x, m.lo, m.hi, m.dependency, 0, true);
    return copy_out(m.x, problem.n, x) && ok ? bench::PeerStatus::Solved : bench::PeerStatus::Failed;
}

bench::PeerStatus bullet_pgs(const Problem& problem, int sweeps, double* x) {
    BulletMlcp m = to_bullet(dense_copy(problem));
    btSolveProjectedGaussSeidel solver;
    solver.solveMLCP(m.A, m.b, m.x, m.lo, m.hi, m.dependency, sweeps, true);
    return copy_out(m.x, problem.n, x) ? bench::PeerStatus::Iterated : bench::PeerStatus::Failed;
}

bench::PeerStatus bullet_lemke(const Problem& problem, int max_rows, double* x) {
    if (problem.n > max_rows) {
        std::fill(x, x + problem.n, 0.0);
        return bench::PeerStatus::Skipped;
    }
    const FixedBoundSolver lemke = [](const DenseMlcp& fixed, double* answer) {
        DenseMlcp finite = fixed;
        make_bounds_finite(finite);
        BulletMlcp m = to_bullet(finite);
        btLemkeSolver solver;
        solver.m_maxValue = std::numeric_limits<btScalar>::infinity();
        solver.m_maxLoops = std::max(1000, 20 * fixed.n);
        const bool ok = solver.solveMLCP(m.A, m.b, m.x, m.lo, m.hi, m.dependency, 0, true);
        return copy_out(m.x, fixed.n, answer) && ok;
    };
    return solve_frozen(problem, lemke, x);
}

std::vector<bench::PeerMethod> bullet_peer_methods(const std::vector<int>& sweep_counts, int lemke_max_rows) {
    std::vector<bench::PeerMethod> methods{
        {"bullet-dantzig", 0, bullet_dantzig},
        {"bullet-lemke", 0, [lemke_max_rows](const Problem& p, double* x) { return bullet_lemke(p, lemke_max_rows, x); }}};
    for (int k : sweep_counts)
        methods.push_back({"bullet-pgs-" + std::to_string(k), k,
                           [k](const Problem& problem, double* x) { return bullet_pgs(problem, k, x); }});
    return methods;
}

}  // namespace ode_bpp::peers
