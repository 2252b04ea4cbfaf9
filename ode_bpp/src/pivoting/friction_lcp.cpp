#include "pivoting/friction_lcp.h"

#include <cmath>
#include <limits>

namespace ode_bpp::pivoting {

namespace {

/// A + shift I, dense (permuted space).
Eigen::MatrixXd dense(const linalg::SymmetricRows& A, double shift) {
    const int n = A.n();
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
        D(i, i) = A.diag(i) + shift;
        for (int e = A.row_begin(i); e < A.row_end(i); ++e) D(i, A.col(e)) = A.val(e);
    }
    return D;
}

/// Row i is unbounded before the friction rows are classified: always free, or both bounds
/// infinite. classify and has_sparse_form share this rule, so the route the Lemke stage takes
/// and what build_sparse accepts cannot drift apart.
bool is_unbounded_row(const BoxedLcp& lcp, int i) {
    return lcp.always_free[i] || (lcp.lo[i] == -INFINITY && lcp.hi[i] == INFINITY);
}

}  // namespace

std::optional<FrictionLcp> FrictionLcp::build(const BoxedLcp& lcp, const FrictionRows& friction, std::string& why) {
    FrictionLcp f;
    if (!f.classify(lcp, friction, why)) return std::nullopt;
    f.number_variables();
    if (!f.eliminate_unbounded(dense(*lcp.A, lcp.shift), lcp, why)) return std::nullopt;
    if (!f.scale_.allFinite() || !f.M_.allFinite() || !f.q_.allFinite()) {
        why = "the Schur complement of the bounded rows is not positive definite";
        return std::nullopt;
    }
    return f;
}

std::optional<FrictionLcp> FrictionLcp::build_sparse(const BoxedLcp& lcp, const FrictionRows& friction, std::string& why) {
    FrictionLcp f;
    if (!f.classify(lcp, friction, why)) return std::nullopt;
    f.number_variables();
    if (!f.unbounded_.empty()) {
        why = "the island has unbounded rows (their Schur complement is dense)";
        return std::nullopt;
    }
    f.G_.resize(0, static_cast<Eigen::Index>(f.bounded_.size()));
    f.g_.resize(0);
    f.assemble_sparse(lcp);
    if (!f.scale_.allFinite() || !f.q_.allFinite()) {
        why = "the bounded rows' block of A is not positive definite";
        return std::nullopt;
    }
    return f;
}

bool FrictionLcp::has_sparse_form(const BoxedLcp& lcp, const FrictionRows& friction) {
    std::vector<char> is_friction(static_cast<std::size_t>(lcp.n()), 0);
    for (int i : friction.rows) is_friction[i] = 1;
    for (int i = 0; i < lcp.n(); ++i)
        if (!is_friction[i] && is_unbounded_row(lcp, i)) return false;
    return true;
}

bool FrictionLcp::classify(const BoxedLcp& lcp, const FrictionRows& friction, std::string& why) {
    const int n = lcp.n();
    rows_.assign(static_cast<std::size_t>(n), Row{});
    for (int i = 0; i < n; ++i) {
        Row& r = rows_[i];
        const double lo = lcp.lo[i], hi = lcp.hi[i];
        if (is_unbounded_row(lcp, i)) r.kind = Kind::Unbounded;
        else if (lo == hi) r = Row{Kind::Known, lo};
        else if (hi == INFINITY) r = Row{Kind::Lower, lo};
        else if (lo == -INFINITY) r = Row{Kind::Upper, hi};
        else r = Row{Kind::Box, lo, hi - lo};
    }
    for (std::size_t k = 0; k < friction.rows.size(); ++k) {
        const double mu = std::abs(friction.mu[k]);
        const int normal = friction.normals[k];
        Row& r = rows_[friction.rows[k]];
        if (!std::isfinite(mu)) {
            why = "a friction coefficient is infinite";
            return false;
        }
        const Row& nr = rows_[normal];
        if (mu == 0) {
            r = Row{Kind::Known, 0.0};
        } else if (nr.kind == Kind::Known) {  // a fixed normal fixes the box
            const double bound = mu * std::abs(nr.value);
            r = bound == 0 ? Row{Kind::Known, 0.0} : Row{Kind::Box, -bound, 2 * bound};
        } else if ((nr.kind == Kind::Lower || nr.kind == Kind::Box) && nr.value >= 0) {
            r = Row{Kind::Friction, 0.0, 0.0, mu, normal};
        } else {
            why = "a friction row's normal can be negative or is unbounded";
            return false;
        }
    }
    for (std::size_t k = 0; k < friction.rows.size(); ++k)
        if (rows_[friction.normals[k]].kind == Kind::Friction) {
            why = "a friction row's normal is itself a friction row";
            return false;
        }
    return true;
}

void FrictionLcp::number_variables() {
    for (int i = 0; i < static_cast<int>(rows_.size()); ++i) {
        Row& r = rows_[i];
        if (r.kind == Kind::Unbounded) {
            r.local = static_cast<int>(unbounded_.size());
            unbounded_.push_back(i);
        } else if (r.kind != Kind::Known) {
            r.local = static_cast<int>(bounded_.size());
            bounded_.push_back(i);
            r.y = num_y_;
            num_y_ += r.kind == Kind::Friction ? 2 : 1;
        }
    }
    for (Row& r : rows_)
        if (r.kind == Kind::Box || r.kind == Kind::Friction) r.l = num_y_ + num_l_++;
}

bool FrictionLcp::eliminate_unbounded(const Eigen::MatrixXd& A, const BoxedLcp& lcp, std::string& why) {
    std::vector<int> known;
    Eigen::VectorXd x_known;
    for (int i = 0; i < static_cast<int>(rows_.size()); ++i)
        if (rows_[i].kind == Kind::Known) known.push_back(i);
    x_known.resize(static_cast<Eigen::Index>(known.size()));
    for (std::size_t a = 0; a < known.size(); ++a) x_known[a] = rows_[known[a]].value;
    const auto rhs = [&](const std::vector<int>& rows) {  // b_rows - A_rows,K x_K
        Eigen::VectorXd v(rows.size());
        for (std::size_t a = 0; a < rows.size(); ++a) v[a] = lcp.b[rows[a]];
        return Eigen::VectorXd(v - A(rows, known) * x_known);
    };
    const Eigen::MatrixXd A_RR = A(bounded_, bounded_);
    const Eigen::VectorXd b_R = rhs(bounded_);
    if (unbounded_.empty()) {
        G_.resize(0, static_cast<Eigen::Index>(bounded_.size()));
        g_.resize(0);
        assemble(A_RR, b_R);
        return true;
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(A(unbounded_, unbounded_));
    if (llt.info() != Eigen::Success) {
        why = "the unbounded rows' block A_UU is not positive definite";
        return false;
    }
    const Eigen::MatrixXd A_UR = A(unbounded_, bounded_);
    G_ = llt.solve(A_UR);
    g_ = llt.solve(rhs(unbounded_));
    // S = A_RR - A_RU A_UU^-1 A_UR,  b~ = b_R - A_RU A_UU^-1 (b_U - A_UK x_K)
    assemble(A_RR - A_UR.transpose() * G_, b_R - A_UR.transpose() * g_);
    return true;
}

Eigen::VectorXd FrictionLcp::offset_x0() const {
    Eigen::VectorXd x0 = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(bounded_.size()));
    for (int i : bounded_) x0[rows_[i].local] = rows_[i].value;
    return x0;
}

void FrictionLcp::y_rows(std::vector<int>& row_of, std::vector<double>& sign) const {
    row_of.assign(static_cast<std::size_t>(num_y_), 0);
    sign.assign(static_cast<std::size_t>(num_y_), 1.0);
    for (int i : bounded_) {
        const Row& r = rows_[i];
        row_of[r.y] = r.local;
        sign[r.y] = r.kind == Kind::Upper ? -1.0 : 1.0;
        if (r.kind == Kind::Friction) {
            row_of[r.y + 1] = r.local;
            sign[r.y + 1] = -1.0;
        }
    }
}

template <class Add>
void FrictionLcp::add_bound_rows(Add add) {
    for (int i : bounded_) {
        const Row& r = rows_[i];
        if (r.kind == Kind::Box) {  // v = (hi - lo) - y
            add(r.y, r.l, 1.0);
            add(r.l, r.y, -1.0);
            q_[r.l] = r.width;
        } else if (r.kind == Kind::Friction) {  // v = mu (lo_n + y_n) - y+ - y-
            const Row& nr = rows_[r.normal];
            add(r.y, r.l, 1.0);
            add(r.y + 1, r.l, 1.0);
            add(r.l, r.y, -1.0);
            add(r.l, r.y + 1, -1.0);
            add(r.l, nr.y, r.mu);
            q_[r.l] = r.mu * nr.value;
        }
    }
}

void FrictionLcp::assemble(const Eigen::MatrixXd& S, const Eigen::VectorXd& b_reduced) {
    const int N = num_y_ + num_l_;
    M_ = Eigen::MatrixXd::Zero(N, N);
    q_ = Eigen::VectorXd::Zero(N);
    // u_y = Q'(S (x0 + Q y) - b~) + E l, Q a signed selection: (Q'SQ)_kl = sign_k sign_l S(row_k, row_l)
    const Eigen::VectorXd w0 = S * offset_x0() - b_reduced;
    std::vector<int> row_of;
    std::vector<double> sign;
    y_rows(row_of, sign);
    for (int l = 0; l < num_y_; ++l) {
        for (int k = 0; k < num_y_; ++k) M_(k, l) = sign[k] * sign[l] * S(row_of[k], row_of[l]);
        q_[l] = sign[l] * w0[row_of[l]];
    }
    add_bound_rows([this](int k, int l, double v) { M_(k, l) += v; });
    balance_scale(M_.diagonal().head(num_y_));
    balance();
}

void FrictionLcp::assemble_sparse(const BoxedLcp& lcp) {
    const int N = num_y_ + num_l_;
    q_ = Eigen::VectorXd::Zero(N);
    // S = A_RR + shift I (no unbounded rows), w0 = (A x0 + A_RK x_K) - b on R: one product with x
    // holding x0 on R and x_K on K
    const linalg::SymmetricRows& A = *lcp.A;
    std::vector<double> x_full(rows_.size(), 0.0), w_full;
    for (std::size_t i = 0; i < rows_.size(); ++i)
        if (rows_[i].kind != Kind::Unbounded) x_full[i] = rows_[i].value;
    A.multiply(x_full, lcp.shift, w_full);
    std::vector<int> row_of;
    std::vector<double> sign;
    y_rows(row_of, sign);
    std::vector<Eigen::Triplet<double>> entries;
    const auto vars = [&](int i) {  // the y variables of row i: first and count
        const Row& r = rows_[i];
        return std::pair<int, int>(r.y, r.kind == Kind::Friction ? 2 : 1);
    };
    const auto couple = [&](int i, int j, double a) {
        const auto [yi, ci] = vars(i);
        const auto [yj, cj] = vars(j);
        for (int k = yi; k < yi + ci; ++k)
            for (int l = yj; l < yj + cj; ++l) entries.emplace_back(k, l, sign[k] * sign[l] * a);
    };
    Eigen::VectorXd y_diagonal(num_y_);
    for (int i : bounded_) {
        const double a_ii = A.diag(i) + lcp.shift;
        couple(i, i, a_ii);
        const auto [yi, ci] = vars(i);
        for (int k = yi; k < yi + ci; ++k) {
            y_diagonal[k] = a_ii;
            q_[k] = sign[k] * (w_full[i] - lcp.b[i]);
        }
        for (int e = A.row_begin(i); e < A.row_end(i); ++e) {
            const int j = A.col(e);
            if (rows_[j].kind != Kind::Known) couple(i, j, A.val(e));
        }
    }
    add_bound_rows([&entries](int k, int l, double v) { entries.emplace_back(k, l, v); });
    balance_scale(y_diagonal);
    for (auto& t : entries) t = Eigen::Triplet<double>(t.row(), t.col(), scale_[t.row()] * t.value() * scale_[t.col()]);
    sparse_M_.resize(N, N);
    sparse_M_.setFromTriplets(entries.begin(), entries.end());
    q_ = scale_.asDiagonal() * q_;
}

void FrictionLcp::balance_scale(const Eigen::VectorXd& y_diagonal) {
    // D = 1/sqrt(M_kk) on y gives Q'SQ a unit diagonal (its scale spans the mass ratio); a
    // multiplier l is a force of its rows' scale, D_l = sqrt(M_kk) of its first y, which keeps
    // the couplings +-1 and mu near one. On 300 winch frames (c = 1e-10) unbalanced answers were
    // off by a natural residual above 1e-6 on 20 frames (up to 2.9) and 2 paths met a ray;
    // balanced, 2 frames and no ray (the linked solve that follows polishes what is left).
    scale_.resize(q_.size());
    for (int k = 0; k < num_y_; ++k)  // S is SPD, so M_kk > 0; otherwise NaN, which build() rejects
        scale_[k] = y_diagonal[k] > 0 ? 1 / std::sqrt(y_diagonal[k]) : std::numeric_limits<double>::quiet_NaN();
    for (const Row& r : rows_)
        if (r.l >= 0) scale_[r.l] = 1 / scale_[r.y];
}

void FrictionLcp::balance() {
    // M <- D M D, q <- D q, z = D z': u' = D u keeps the complementarity and M's copositivity.
    M_ = scale_.asDiagonal() * M_ * scale_.asDiagonal();
    q_ = scale_.asDiagonal() * q_;
}

std::vector<char> FrictionLcp::basis_guess(const std::vector<RowState>& states, const std::vector<double>& x) const {
    std::vector<char> z_basic(static_cast<std::size_t>(num_y_ + num_l_), 0);
    for (int i : bounded_) {
        const Row& r = rows_[i];
        const RowState st = states[i];
        switch (r.kind) {
            case Kind::Lower:
            case Kind::Upper: z_basic[r.y] = st == RowState::Free; break;
            case Kind::Box:
                z_basic[r.y] = st != RowState::AtLo;
                z_basic[r.l] = st == RowState::AtHi;
                break;
            case Kind::Friction: {  // at a bound: l > 0 and the y of its sign; free: the y of x's sign
                const bool at_bound = st != RowState::Free;
                const bool plus = at_bound ? st == RowState::AtHi : x[i] >= 0;
                z_basic[plus ? r.y : r.y + 1] = 1;
                z_basic[r.l] = at_bound;
                break;
            }
            default: break;
        }
    }
    return z_basic;
}

void FrictionLcp::recover(const LemkeSolution& s, std::vector<double>& x, std::vector<RowState>& states) const {
    const int n = static_cast<int>(rows_.size());
    x.assign(static_cast<std::size_t>(n), 0.0);
    states.assign(static_cast<std::size_t>(n), RowState::Free);
    Eigen::VectorXd x_R(static_cast<Eigen::Index>(bounded_.size()));
    for (int i = 0; i < n; ++i) {
        const Row& r = rows_[i];
        const auto z = [&](int v) { return scale_[v] * s.z[v]; };
        const auto slack_zero = [&](int v) { return !s.u_basic[v]; };  // nonbasic u_v = 0
        switch (r.kind) {
            case Kind::Unbounded: break;
            case Kind::Known:
                x[i] = r.value;
                states[i] = RowState::AtLo;
                break;
            case Kind::Lower:
            case Kind::Upper:
                x[i] = r.kind == Kind::Lower ? r.value + z(r.y) : r.value - z(r.y);
                if (!s.z_basic[r.y]) states[i] = r.kind == Kind::Lower ? RowState::AtLo : RowState::AtHi;
                break;
            case Kind::Box:
                x[i] = r.value + z(r.y);
                if (!s.z_basic[r.y]) states[i] = RowState::AtLo;
                else if (slack_zero(r.l)) states[i] = RowState::AtHi;
                break;
            case Kind::Friction: {
                x[i] = z(r.y) - z(r.y + 1);
                const bool plus = s.z_basic[r.y], minus = s.z_basic[r.y + 1];
                if (slack_zero(r.l) && plus != minus) states[i] = plus ? RowState::AtHi : RowState::AtLo;
                else if (slack_zero(r.l) && !plus) states[i] = RowState::AtHi;  // bound 0: x = 0
                break;
            }
        }
        if (r.local >= 0 && r.kind != Kind::Unbounded) x_R[r.local] = x[i];
    }
    if (unbounded_.empty()) return;
    const Eigen::VectorXd x_U = g_ - G_ * x_R;  // A_UU^-1 (b_U - A_UK x_K - A_UR x_R)
    for (std::size_t a = 0; a < unbounded_.size(); ++a) x[unbounded_[a]] = x_U[a];
}

}  // namespace ode_bpp::pivoting
