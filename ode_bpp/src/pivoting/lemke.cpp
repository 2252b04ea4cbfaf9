#include "pivoting/lemke.h"

#include <algorithm>
#include <cmath>

#include "pivoting/lemke_rules.h"

namespace ode_bpp::pivoting {

namespace {

/// B^-1 is updated in product form (rank one per pivot); it is rebuilt from the basis columns
/// every max(kMinRefreshPeriod, N) pivots, which costs as much as N pivots (O(N^3)).
constexpr int kMinRefreshPeriod = 64;

/// The tableau I u - M z - d z0 = q, kept as B^-1 and B^-1 q. Variables: u_i = i,
/// z_i = N + i, z0 = 2N.
class LemkeTableau {
public:
    LemkeTableau(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& d)
        : M_(M), q_(q), d_(d), n_(static_cast<int>(q.size())), Binv_(Eigen::MatrixXd::Identity(n_, n_)), rhs_(q), basis_(n_) {
        for (int i = 0; i < n_; ++i) basis_[i] = i;
    }

    int artificial() const { return 2 * n_; }
    int complement(int var) const { return var < n_ ? var + n_ : var - n_; }
    int basic(int row) const { return basis_[row]; }

    /// c = B^-1 a_var, a_var the variable's column of [I, -M, -d].
    void column(int var, Eigen::VectorXd& c) const {
        if (var < n_)
            c = Binv_.col(var);
        else if (var < 2 * n_)
            c.noalias() = -(Binv_ * M_.col(var - n_));
        else
            c.noalias() = -(Binv_ * d_);
    }

    /// The leaving row for an entering column c (lemke_rules.h), or -1 for a ray; the keys are
    /// the columns of B^-1 itself.
    int ratio_test(const Eigen::VectorXd& c) const {
        return lexicographic_ratio_test(rhs_, c, basis_, [this](int k, Eigen::VectorXd& key) { key = Binv_.col(k); });
    }

    /// Exchanges the basic variable of row r for `entering`, whose column is c (always true: the
    /// dense inverse meets no singular basis it could detect here).
    bool pivot(int r, int entering, const Eigen::VectorXd& c) {
        const double p = c[r];
        const Eigen::RowVectorXd pivot_row = Binv_.row(r) / p;
        const double pivot_rhs = rhs_[r] / p;
        Eigen::VectorXd eliminate = c;
        eliminate[r] = 0;
        // B^-1 <- E B^-1 with the eta matrix E of column c at row r
        Binv_.noalias() -= eliminate * pivot_row;
        rhs_ -= eliminate * pivot_rhs;
        Binv_.row(r) = pivot_row;
        rhs_[r] = pivot_rhs;
        basis_[r] = entering;
        return true;
    }

    /// A refresh every max(kMinRefreshPeriod, N) pivots.
    void after_pivot(int pivots) {
        if (pivots % std::max(kMinRefreshPeriod, n_) == 0) refresh();
    }

    /// B^-1 and B^-1 q afresh from the basis columns (product-form updates drift).
    void refresh() {
        const Eigen::PartialPivLU<Eigen::MatrixXd> lu(basis_matrix());
        Binv_ = lu.inverse();
        rhs_ = lu.solve(q_);
    }

    /// The basic solution: z_i and u_i from B x_B = q, nonbasic entries 0, negatives (rounding of a
    /// degenerate basis) clamped to 0. x_B = B^-1 q as updated, plus one step of iterative
    /// refinement, x_B += B^-1 (q - B x_B): O(N^2), where a fresh LU of B (O(N^3)) took about a
    /// third of the stage's time on the winch's 400-600-variable LCPs.
    void extract(LemkeSolution& s) const {
        Eigen::VectorXd xb = rhs_;
        xb += Binv_ * (q_ - basis_matrix() * xb);
        read_lemke_solution(basis_, xb, s);
    }

private:
    Eigen::MatrixXd basis_matrix() const {
        Eigen::MatrixXd B(n_, n_);
        for (int r = 0; r < n_; ++r) {
            const int var = basis_[r];
            if (var < n_)
                B.col(r) = Eigen::VectorXd::Unit(n_, var);
            else if (var < 2 * n_)
                B.col(r) = -M_.col(var - n_);
            else
                B.col(r) = -d_;
        }
        return B;
    }

    const Eigen::MatrixXd& M_;
    const Eigen::VectorXd& q_;
    const Eigen::VectorXd& d_;
    int n_;
    Eigen::MatrixXd Binv_;
    Eigen::VectorXd rhs_;
    std::vector<int> basis_;
};

}  // namespace

Eigen::VectorXd spread_covering_vector(int n, int attempt) {
    constexpr double kGoldenFraction = 0.6180339887498949;
    Eigen::VectorXd d(n);
    for (int i = 0; i < n; ++i) {
        const double t = (i + 1 + static_cast<double>(attempt) * n) * kGoldenFraction;
        d[i] = 0.5 + (t - std::floor(t));
    }
    return d;
}

LemkeSolution solve_lemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& q, const Eigen::VectorXd& d, int max_pivots) {
    const int n = static_cast<int>(q.size());
    LemkeSolution s;
    LemkeTableau t(M, q, d);
    if (n == 0 || q.minCoeff() >= 0) {  // z = 0 solves it
        t.extract(s);
        s.outcome = LemkeOutcome::Solved;
        return s;
    }
    // z0 enters at the row of the least q_i / d_i: then B^-1 q >= 0
    Eigen::Index first = 0;
    q.cwiseQuotient(d).minCoeff(&first);
    s.outcome = follow_lemke_path(t, static_cast<int>(first), max_pivots, s.pivots);
    if (s.outcome == LemkeOutcome::Solved) t.extract(s);
    return s;
}

}  // namespace ode_bpp::pivoting
