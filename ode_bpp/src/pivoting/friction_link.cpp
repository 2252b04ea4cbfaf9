#include "pivoting/friction_link.h"

#include <Eigen/Dense>
#include <limits>

namespace ode_bpp::pivoting {

namespace {

/// I + D E Z with a reciprocal condition below this is singular: x_C would carry the rounding of
/// Z amplified by more than 1e10.
constexpr double kMinReciprocalCondition = 1e6 * std::numeric_limits<double>::epsilon();

/// z = A_F,j: column j of A at the free rows, 0 at the tight ones (A symmetric: row j is column j).
void free_column(const linalg::SymmetricRows& A, const std::vector<char>& tight, int j, std::vector<double>& z) {
    std::fill(z.begin(), z.end(), 0.0);
    for (int e = A.row_begin(j); e < A.row_end(j); ++e)
        if (!tight[A.col(e)]) z[A.col(e)] = A.val(e);
}

}  // namespace

bool solve_linked_rows(const BoxedLcp& lcp, FreeSolver& solver, const std::vector<int>& linked,
                       const std::vector<RowState>& states, const std::vector<char>& tight, std::vector<double>& x) {
    const int n = lcp.n();
    const int k = static_cast<int>(linked.size());
    Eigen::MatrixXd Z(n, k);  // Z = A_FF^-1 A_FC
    std::vector<double> z(static_cast<std::size_t>(n));
    for (int b = 0; b < k; ++b) {
        free_column(*lcp.A, tight, linked[b], z);
        solver.solve_again(z);
        for (int i = 0; i < n; ++i) Z(i, b) = z[i];
    }
    // (I + D E Z) x_C = D E y
    Eigen::MatrixXd M = Eigen::MatrixXd::Identity(k, k);
    Eigen::VectorXd rhs(k);
    for (int a = 0; a < k; ++a) {
        const int j = linked[a];
        const int normal = lcp.friction_normal[j];
        const double d = (states[j] == RowState::AtHi ? 1.0 : -1.0) * lcp.friction_mu[j];
        M.row(a) += d * Z.row(normal);
        rhs[a] = d * x[normal];
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
    if (!(lu.rcond() > kMinReciprocalCondition)) return false;
    const Eigen::VectorXd xc = lu.solve(rhs);
    if (!xc.allFinite()) return false;
    const Eigen::VectorXd correction = Z * xc;  // x_F = y - Z x_C
    for (int i = 0; i < n; ++i)
        if (!tight[i]) x[i] -= correction[i];
    for (int a = 0; a < k; ++a) x[linked[a]] = xc[a];
    return true;
}

}  // namespace ode_bpp::pivoting
