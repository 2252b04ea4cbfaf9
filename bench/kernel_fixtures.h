// Test matrices shared by the kernel benchmarks: band matrices like ODE chains after ordering,
// and Fig. 4's random dense SPD matrices, each built and factored once per size.
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <random>
#include <tuple>
#include <vector>

#include "linalg/envelope.h"
#include "linalg/skyline.h"
#include "linalg/skyline_cholesky.h"

namespace ode_bpp::bench {

using Eigen::MatrixXd;
using linalg::SkylineMatrix;
using linalg::SkylineShape;

/// Half-width of the band matrices: the skyline height of ODE chains after ordering (docs/maths.md).
constexpr int kHalfBandwidth = 12;
/// The matrix sizes m of every benchmark.
inline const int kSizes[] = {50, 100, 200, 400, 1000};

/// Symmetric, diagonally dominant band matrix (half-width kHalfBandwidth), row-major.
inline std::vector<double> banded_spd(int m, std::mt19937& rng) {
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    std::vector<double> A(static_cast<std::size_t>(m) * m, 0.0);
    auto at = [&A, m](int i, int j) -> double& { return A[static_cast<std::size_t>(i) * m + j]; };
    for (int i = 0; i < m; ++i)
        for (int j = std::max(0, i - kHalfBandwidth); j < i; ++j) at(i, j) = at(j, i) = value(rng);
    for (int i = 0; i < m; ++i) {
        double off_diagonal = 0.0;
        for (int j = 0; j < m; ++j) off_diagonal += std::abs(at(i, j));
        at(i, i) = 1.0 + off_diagonal;
    }
    return A;
}

/// Random dense SPD matrix B Bᵀ / m + I (Fig. 4's test matrices), row-major.
inline std::vector<double> dense_spd(int m, std::mt19937& rng) {
    std::normal_distribution<double> gauss;
    MatrixXd B(m, m);
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) B(i, j) = gauss(rng);
    const MatrixXd A = B * B.transpose() / m + MatrixXd::Identity(m, m);
    return std::vector<double>(A.data(), A.data() + A.size());  // symmetric: same either major
}

/// A in its skyline (envelope) storage, or in dense storage.
inline SkylineMatrix load(const std::vector<double>& A, int m, bool dense) {
    SkylineMatrix packed = linalg::load_skyline(A.data(), m, m, nullptr);
    if (!dense) return packed;
    SkylineMatrix L(SkylineShape::dense(m));
    for (int k = 0; k < m; ++k)
        for (int r = k; r < m; ++r) L.at(r, k) = A[static_cast<std::size_t>(r) * m + k];
    return L;
}

/// Column-major view of the symmetric row-major matrix A.
inline MatrixXd to_eigen(const std::vector<double>& A, int m) { return Eigen::Map<const MatrixXd>(A.data(), m, m); }

/// One problem per (kind, size), built once: A, its lower triangle in storage, and L0.
struct Fixture {
    int m = 0;
    std::vector<double> A;
    SkylineMatrix A_lower, L0;
};

/// The fixture of size m: Fig. 4's random dense SPD matrix (dense_matrix) or the band matrix,
/// in dense storage (dense_storage) or in its envelope. Both matrices are safely definite, so
/// a failed factorization means a broken kernel: abort rather than time garbage.
inline const Fixture& fixture(bool dense_matrix, bool dense_storage, int m) {
    static std::map<std::tuple<bool, bool, int>, std::unique_ptr<Fixture>> cache;
    auto& slot = cache[{dense_matrix, dense_storage, m}];
    if (!slot) {
        std::mt19937 rng(1000 + m);
        slot = std::make_unique<Fixture>();
        slot->m = m;
        slot->A = dense_matrix ? dense_spd(m, rng) : banded_spd(m, rng);
        slot->A_lower = load(slot->A, m, dense_storage);
        slot->L0 = slot->A_lower;
        if (linalg::skyline_cholesky(slot->L0, 0, {}) != -1) std::abort();
    }
    return *slot;
}

}  // namespace ode_bpp::bench
