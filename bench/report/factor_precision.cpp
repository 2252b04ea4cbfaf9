// bench/report/factor_precision.cpp
#include "factor_precision.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <cstddef>

#include "linalg/envelope.h"
#include "linalg/row_delete.h"
#include "linalg/skyline_cholesky.h"

namespace ode_bpp::bench {

namespace {

using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

/// The tight rows' positions in the order perm (perm[new] = old), ascending.
std::vector<int> tight_positions(const std::vector<int>& perm, const std::vector<RowState>& states) {
    std::vector<int> tight;
    for (int k = 0; k < static_cast<int>(perm.size()); ++k)
        if (states[static_cast<std::size_t>(perm[static_cast<std::size_t>(k)])] != RowState::Free) tight.push_back(k);
    return tight;
}

/// M = P A Pᵀ with the rows and columns at `tight` replaced by the identity.
Eigen::MatrixXd free_block_embedded(const MlcpFile& file, const std::vector<int>& perm, const std::vector<int>& tight) {
    const auto n = static_cast<Eigen::Index>(file.n);
    Eigen::MatrixXd M(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j)
            M(i, j) = file.A[static_cast<std::size_t>(perm[static_cast<std::size_t>(i)]) * static_cast<std::size_t>(n) +
                             static_cast<std::size_t>(perm[static_cast<std::size_t>(j)])];
    for (int k : tight) {
        M.row(k).setZero();
        M.col(k).setZero();
        M(k, k) = 1.0;
    }
    return M;
}

/// L0 = chol(P A Pᵀ) in envelope storage with the rows at `tight` deleted, as a dense lower
/// triangle; false when L0 breaks down.
bool deleted_factor(const MlcpFile& file, const std::vector<int>& perm, const std::vector<int>& tight,
                    LongMatrix& out) {
    linalg::SkylineMatrix L = linalg::load_skyline(file.A.data(), file.n, file.n, perm.data());
    if (linalg::skyline_cholesky(L, 0, {}) >= 0) return false;
    std::vector<double> work;
    for (int k : tight) linalg::skyline_delete_row(L, k, work);
    out = LongMatrix::Zero(file.n, file.n);
    for (int k = 0; k < file.n; ++k)
        for (int r = k; r <= L.sky(k); ++r) out(r, k) = L.at(r, k);
    return true;
}

}  // namespace

FactorPrecision factor_precision(const MlcpFile& file, const std::vector<int>& ordering,
                                 const std::vector<RowState>& states) {
    const auto n = static_cast<std::size_t>(file.n);
    if (ordering.size() != n || states.size() != n) return {};
    const std::vector<int> tight = tight_positions(ordering, states);
    if (tight.empty()) return {0.0, 0.0};
    const Eigen::MatrixXd M = free_block_embedded(file, ordering, tight);
    const Eigen::LLT<Eigen::MatrixXd> fresh(M);
    const Eigen::LLT<LongMatrix> exact(M.cast<long double>());
    LongMatrix deleted;
    if (fresh.info() != Eigen::Success || exact.info() != Eigen::Success || !deleted_factor(file, ordering, tight, deleted))
        return {};
    const LongMatrix L_exact = exact.matrixL().toDenseMatrix();
    const LongMatrix L_fresh = fresh.matrixL().toDenseMatrix().cast<long double>();
    return {static_cast<double>((L_fresh - L_exact).norm()), static_cast<double>((deleted - L_exact).norm())};
}

}  // namespace ode_bpp::bench
