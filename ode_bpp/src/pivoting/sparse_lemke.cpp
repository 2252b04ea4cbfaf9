#include "pivoting/sparse_lemke.h"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "pivoting/lemke_rules.h"

namespace ode_bpp::pivoting {

namespace {

/// An answer whose complementarity is violated by more than this, relative to the LCP's scale
/// (|q| + |M||z|), came through a nearly singular basis and is rejected.
constexpr double kAnswerTolerance = 1e-9;
/// Eta vectors kept before the basis is factored afresh (each adds N to every solve): 100 was
/// 10 % faster on two bin islands, 200 lost the accuracy of one answer (docs/tuning.md).
constexpr int kRefactorPeriod = 50;

using SparseMatrix = Eigen::SparseMatrix<double>;

/// The basis of the tableau I u - M z - d z0 = q (variables u_i = i, z_i = N + i, z0 = 2N) as
/// B = L U of the basis at the last refactorization times the eta matrices of the pivots since.
class SparseBasis {
public:
    SparseBasis(const SparseMatrix& M, const Eigen::VectorXd& d, std::vector<int> basis)
        : M_(M), d_(d), n_(static_cast<int>(d.size())), basis_(std::move(basis)) {}

    int n() const { return n_; }
    int basic(int row) const { return basis_[row]; }
    const std::vector<int>& variables() const { return basis_; }

    /// Factors the current basis afresh (dropping the etas); false when it is singular.
    bool refactor() {
        std::vector<Eigen::Triplet<double>> entries;
        for (int r = 0; r < n_; ++r) add_column(basis_[r], r, entries);
        SparseMatrix B(n_, n_);
        B.setFromTriplets(entries.begin(), entries.end());
        lu_.analyzePattern(B);
        lu_.factorize(B);
        etas_.clear();
        return lu_.info() == Eigen::Success;
    }

    /// v <- B^-1 v.
    void solve(Eigen::VectorXd& v) const {
        v = lu_.solve(v).eval();
        for (const auto& [r, c] : etas_) {
            const double vr = v[r] / c[r];
            v -= c * vr;
            v[r] = vr;
        }
    }

    /// c = B^-1 a_var, a_var the variable's column of [I, -M, -d].
    void column(int var, Eigen::VectorXd& c) const {
        c.setZero(n_);
        if (var < n_) {
            c[var] = 1;
        } else if (var < 2 * n_) {
            for (SparseMatrix::InnerIterator it(M_, var - n_); it; ++it) c[it.row()] = -it.value();
        } else {
            c = -d_;
        }
        solve(c);
    }

    /// q - B x_B for the basic values xb.
    Eigen::VectorXd residual(const Eigen::VectorXd& q, const Eigen::VectorXd& xb) const {
        Eigen::VectorXd r = q;
        for (int row = 0; row < n_; ++row) {
            const int var = basis_[row];
            if (var < n_)
                r[var] -= xb[row];
            else if (var < 2 * n_)
                for (SparseMatrix::InnerIterator it(M_, var - n_); it; ++it) r[it.row()] += it.value() * xb[row];
            else
                r += d_ * xb[row];
        }
        return r;
    }

    /// The basic variable of row r becomes `entering`, whose column B^-1 a is c.
    void exchange(int r, int entering, const Eigen::VectorXd& c) {
        basis_[r] = entering;
        etas_.emplace_back(r, c);
    }

    int etas() const { return static_cast<int>(etas_.size()); }

private:
    void add_column(int var, int col, std::vector<Eigen::Triplet<double>>& entries) const {
        if (var < n_) {
            entries.emplace_back(var, col, 1.0);
        } else if (var < 2 * n_) {
            for (SparseMatrix::InnerIterator it(M_, var - n_); it; ++it) entries.emplace_back(it.row(), col, -it.value());
        } else {
            for (int i = 0; i < n_; ++i)
                if (d_[i] != 0) entries.emplace_back(i, col, -d_[i]);
        }
    }

    const SparseMatrix& M_;
    const Eigen::VectorXd& d_;
    int n_;
    std::vector<int> basis_;
    Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu_;
    std::vector<std::pair<int, Eigen::VectorXd>> etas_;
};

/// The path's state: the basis, B^-1 q, and the starting basis whose columns give the
/// lexicographic keys.
class SparseTableau {
public:
    SparseTableau(const SparseMatrix& M, const Eigen::VectorXd& q, const Eigen::VectorXd& d, std::vector<int> basis)
        : q_(q), start_(basis), basis_(M, d, std::move(basis)) {}

    int n() const { return basis_.n(); }
    int artificial() const { return 2 * n(); }
    int complement(int var) const { return var < n() ? var + n() : var - n(); }
    int basic(int row) const { return basis_.basic(row); }
    const Eigen::VectorXd& rhs() const { return rhs_; }

    /// Factors the basis and computes B^-1 q; false when the basis is singular.
    bool refresh() {
        if (!basis_.refactor()) return false;
        rhs_ = q_;
        basis_.solve(rhs_);
        return rhs_.allFinite();
    }

    void column(int var, Eigen::VectorXd& c) const { basis_.column(var, c); }

    /// The leaving row for the entering column c (lemke_rules.h), or -1 for a ray; the keys are
    /// the columns of B^-1 B0, one solve each, computed only while rows tie.
    int ratio_test(const Eigen::VectorXd& c) const {
        return lexicographic_ratio_test(rhs_, c, basis_.variables(),
                                        [this](int k, Eigen::VectorXd& key) { basis_.column(start_[k], key); });
    }

    /// Exchanges the basic variable of row r for `entering`, whose column is c; refactors when
    /// the etas have piled up. False when that refactorization finds the basis singular.
    bool pivot(int r, int entering, const Eigen::VectorXd& c) {
        const double step = rhs_[r] / c[r];
        rhs_ -= c * step;
        rhs_[r] = step;
        basis_.exchange(r, entering, c);
        return basis_.etas() < kRefactorPeriod || refresh();
    }

    /// Nothing: pivot() refactors every kRefactorPeriod etas itself.
    void after_pivot(int) {}

    /// The basic solution with one step of iterative refinement, negatives clamped to 0.
    void extract(LemkeSolution& s) const {
        Eigen::VectorXd xb = rhs_;
        Eigen::VectorXd correction = basis_.residual(q_, xb);
        basis_.solve(correction);
        xb += correction;
        read_lemke_solution(basis_.variables(), xb, s);
    }

private:
    const Eigen::VectorXd& q_;
    std::vector<int> start_;
    SparseBasis basis_;
    Eigen::VectorXd rhs_;
};

/// The starting basis: z_i where start says so, u_i elsewhere (the slack basis for empty start).
std::vector<int> basis_of(const std::vector<char>& start, int n) {
    std::vector<int> basis(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) basis[i] = !start.empty() && start[i] ? n + i : i;
    return basis;
}

/// d = B0 s for the basis B0 (variables per row): B0^-1 d = s.
Eigen::VectorXd covering_vector(const Eigen::SparseMatrix<double>& M, const std::vector<int>& basis,
                                const Eigen::VectorXd& spread) {
    const int n = static_cast<int>(spread.size());
    Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
    for (int r = 0; r < n; ++r) {
        const int var = basis[r];
        if (var < n)
            d[var] += spread[r];
        else
            for (Eigen::SparseMatrix<double>::InnerIterator it(M, var - n); it; ++it) d[it.row()] -= it.value() * spread[r];
    }
    return d;
}

/// max_i max(-z_i, -u_i, |min(z_i, u_i)|) with u = M z + q, relative to max(1, |q| + |M||z|).
double violation(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& q, const Eigen::VectorXd& z) {
    const Eigen::VectorXd u = M * z + q;
    const Eigen::VectorXd scale = q.cwiseAbs() + M.cwiseAbs() * z.cwiseAbs();
    double worst = 0;
    for (Eigen::Index i = 0; i < z.size(); ++i)
        worst = std::max({worst, -z[i], -u[i], std::abs(std::min(z[i], u[i]))});
    return worst / std::max(1.0, scale.maxCoeff());
}

}  // namespace

LemkeSolution solve_sparse_lemke(const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& q,
                                 const std::vector<char>& start, const Eigen::VectorXd& spread, int max_pivots) {
    const int n = static_cast<int>(q.size());
    LemkeSolution s;
    std::vector<int> basis = basis_of(start, n);
    Eigen::VectorXd d = covering_vector(M, basis, spread);
    auto tableau = std::make_unique<SparseTableau>(M, q, d, basis);
    if (!tableau->refresh()) {  // a singular guess: the slack basis, d = spread
        basis = basis_of({}, n);
        d = spread;
        tableau = std::make_unique<SparseTableau>(M, q, d, basis);
        tableau->refresh();
    }
    SparseTableau& t = *tableau;
    if (n == 0 || t.rhs().minCoeff() >= 0) {  // the starting basis solves it
        t.extract(s);
        s.outcome = violation(M, q, s.z) <= kAnswerTolerance ? LemkeOutcome::Solved : LemkeOutcome::Inaccurate;
        return s;
    }
    // z0 enters at the row of the least x_r / s_r: then every basic value is >= 0
    Eigen::Index first = 0;
    t.rhs().cwiseQuotient(spread).minCoeff(&first);
    s.outcome = follow_lemke_path(t, static_cast<int>(first), max_pivots, s.pivots);
    if (s.outcome != LemkeOutcome::Solved) return s;
    t.refresh();  // the answer from a fresh factor rather than through up to kRefactorPeriod etas
    t.extract(s);
    if (violation(M, q, s.z) > kAnswerTolerance) s.outcome = LemkeOutcome::Inaccurate;
    return s;
}

}  // namespace ode_bpp::pivoting
