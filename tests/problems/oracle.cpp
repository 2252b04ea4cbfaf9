#include "problems/oracle.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace ode_bpp::problems {

namespace {

enum class Set { Free, Lo, Hi };

/// Decodes index set number `code` in base 3; false if it puts a row at an infinite bound or
/// a row < nub at any bound.
bool decode(long code, const OwnedProblem& p, const std::vector<double>& lo, const std::vector<double>& hi,
            std::vector<Set>& sets) {
    for (int i = 0; i < p.n; ++i, code /= 3) {
        sets[i] = static_cast<Set>(code % 3);
        if (sets[i] == Set::Lo && (i < p.nub || std::isinf(lo[i]))) return false;
        if (sets[i] == Set::Hi && (i < p.nub || std::isinf(hi[i]))) return false;
    }
    return true;
}

bool satisfies(const OwnedProblem& p, const std::vector<double>& lo, const std::vector<double>& hi,
               const std::vector<Set>& sets, const Eigen::VectorXd& x, double rel_tol) {
    for (int i = 0; i < p.n; ++i) {
        double w = -p.b[i], scale = std::abs(p.b[i]);
        for (int j = 0; j < p.n; ++j) {
            w += p.a(i, j) * x[j];
            scale += std::abs(p.a(i, j) * x[j]);
        }
        const double w_tol = rel_tol * scale, x_tol = w_tol / p.a(i, i);
        const bool unbounded = i < p.nub;
        switch (sets[i]) {
            case Set::Free:
                if (!unbounded && (x[i] < lo[i] - x_tol || x[i] > hi[i] + x_tol)) return false;
                if (std::abs(w) > 1e3 * w_tol + 1e-300) return false;
                break;
            case Set::Lo:
                if (w < -w_tol) return false;
                break;
            case Set::Hi:
                if (w > w_tol) return false;
                break;
        }
    }
    return true;
}

}  // namespace

std::optional<std::vector<double>> enumerate_boxed_lcp(const OwnedProblem& p, const std::vector<double>& lo,
                                                       const std::vector<double>& hi, double rel_tol) {
    long total = 1;
    for (int i = 0; i < p.n; ++i) total *= 3;
    std::vector<Set> sets(p.n);
    for (long code = 0; code < total; ++code) {
        if (!decode(code, p, lo, hi, sets)) continue;
        Eigen::VectorXd x = Eigen::VectorXd::Zero(p.n);
        std::vector<int> free;
        for (int i = 0; i < p.n; ++i) {
            if (sets[i] == Set::Free) free.push_back(i);
            else x[i] = sets[i] == Set::Lo ? lo[i] : hi[i];
        }
        const int nf = static_cast<int>(free.size());
        Eigen::MatrixXd Aff(nf, nf);
        Eigen::VectorXd rhs(nf);
        for (int a = 0; a < nf; ++a) {
            rhs[a] = p.b[free[a]];
            for (int j = 0; j < p.n; ++j)
                if (sets[j] != Set::Free) rhs[a] -= p.a(free[a], j) * x[j];
            for (int c = 0; c < nf; ++c) Aff(a, c) = p.a(free[a], free[c]);
        }
        if (nf > 0) {
            const Eigen::VectorXd xf = Aff.ldlt().solve(rhs);
            for (int a = 0; a < nf; ++a) x[free[a]] = xf[a];
        }
        if (satisfies(p, lo, hi, sets, x, rel_tol)) return std::vector<double>(x.data(), x.data() + p.n);
    }
    return std::nullopt;
}

std::optional<std::vector<double>> enumerate_frozen_friction(const OwnedProblem& p, double rel_tol) {
    std::vector<double> lo = p.lo, hi = p.hi;
    const bool friction = !p.findex.empty();
    if (friction)
        for (int i = 0; i < p.n; ++i)
            if (p.findex[i] >= 0) lo[i] = hi[i] = 0;
    std::optional<std::vector<double>> x = enumerate_boxed_lcp(p, lo, hi, rel_tol);
    if (!x || !friction) return x;
    for (int i = 0; i < p.n; ++i)
        if (p.findex[i] >= 0) {
            const double normal = (*x)[p.findex[i]];
            hi[i] = normal == 0 ? 0.0 : std::abs(p.hi[i] * normal);
            lo[i] = -hi[i];
        }
    return enumerate_boxed_lcp(p, lo, hi, rel_tol);
}

}  // namespace ode_bpp::problems
