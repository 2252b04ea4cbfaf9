// Shared oracles and generators for the test_linalg_* and test_ordering_* suites.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "linalg/skyline.h"

namespace ode_bpp::test {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Random symmetric positive definite n x n matrix whose row i is non-zero exactly in columns
/// first[i] .. i (first[i] >= i - max_band), made definite by diagonal dominance
/// A(i,i) = margin + sum_j |A(i,j)|, then scaled D A D with D spanning 10^[-spread, spread]
/// (mass ratios). margin > 0 bounds cond(A) before scaling.
inline MatrixXd random_envelope_spd(int n, int max_band, std::mt19937& rng, double margin = 0.5,
                                    double spread = 0.0) {
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    std::uniform_int_distribution<int> band(0, max_band);
    MatrixXd A = MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
        const int first = std::max(0, i - band(rng));
        for (int j = first; j < i; ++j) {
            double v = value(rng);
            if (j == first && v == 0.0) v = 0.5;
            A(i, j) = A(j, i) = v;
        }
    }
    for (int i = 0; i < n; ++i) A(i, i) = margin + A.row(i).cwiseAbs().sum();
    std::uniform_real_distribution<double> exponent(-spread, spread);
    VectorXd d(n);
    for (int i = 0; i < n; ++i) d(i) = std::pow(10.0, exponent(rng));
    return d.asDiagonal() * A * d.asDiagonal();
}

/// Row-major copy of the lower triangle with row stride lda >= n; the strictly upper triangle and
/// the padding hold NaN, so any code reading them produces NaN.
inline std::vector<double> lower_row_major_poisoned(const MatrixXd& A, int lda) {
    const int n = static_cast<int>(A.rows());
    std::vector<double> out(static_cast<std::size_t>(n) * lda, std::numeric_limits<double>::quiet_NaN());
    for (int i = 0; i < n; ++i)
        for (int j = 0; j <= i; ++j) out[static_cast<std::size_t>(i) * lda + j] = A(i, j);
    return out;
}

/// Ap = P A Pᵀ with perm[new] = old.
inline MatrixXd permuted(const MatrixXd& A, const std::vector<int>& perm) {
    const int n = static_cast<int>(A.rows());
    MatrixXd Ap(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) Ap(i, j) = A(perm[i], perm[j]);
    return Ap;
}

inline std::vector<int> random_permutation(int n, std::mt19937& rng) {
    std::vector<int> perm(static_cast<std::size_t>(n));
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    return perm;
}

/// Removed flags: each index removed with probability p.
inline std::vector<char> random_removed(int n, double p, std::mt19937& rng) {
    std::bernoulli_distribution coin(p);
    std::vector<char> removed(static_cast<std::size_t>(n), 0);
    for (auto& r : removed) r = coin(rng) ? 1 : 0;
    return removed;
}

inline std::vector<int> kept_indices(const std::vector<char>& removed) {
    std::vector<int> kept;
    for (int k = 0; k < static_cast<int>(removed.size()); ++k)
        if (!removed[k]) kept.push_back(k);
    return kept;
}

/// A_FF: rows/columns of A at the kept indices.
inline MatrixXd restricted(const MatrixXd& A, const std::vector<int>& kept) {
    const int m = static_cast<int>(kept.size());
    MatrixXd out(m, m);
    for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) out(a, b) = A(kept[a], kept[b]);
    return out;
}

/// The oracle factor: Eigen's LLT of A_FF.
inline MatrixXd oracle_factor(const MatrixXd& A_FF) { return MatrixXd(A_FF.llt().matrixL()); }

/// 2-norm condition number (symmetric positive definite A).
inline double condition_number(const MatrixXd& A) {
    const VectorXd ev = Eigen::SelfAdjointEigenSolver<MatrixXd>(A).eigenvalues();
    return ev.maxCoeff() / ev.minCoeff();
}

/// Entry-wise tolerance for a computed factor of A: the first-order perturbation bound
/// |dL| <~ n eps cond(A) |L|, with a safety factor of 10.
inline double factor_tolerance(const MatrixXd& A, double max_abs_L) {
    return 10.0 * A.rows() * std::numeric_limits<double>::epsilon() * condition_number(A) * max_abs_L;
}

/// Dense n x n copy of a skyline factor (zeros outside the envelope).
inline MatrixXd to_dense(const linalg::SkylineMatrix& L) {
    MatrixXd out = MatrixXd::Zero(L.n(), L.n());
    for (int k = 0; k < L.n(); ++k)
        for (int r = k; r <= L.sky(k); ++r) out(r, k) = L.at(r, k);
    return out;
}

/// The skyline matrix of a dense lower triangle, in the given shape.
inline linalg::SkylineMatrix from_dense(const MatrixXd& M, const linalg::SkylineShape& shape) {
    linalg::SkylineMatrix L(shape);
    for (int k = 0; k < L.n(); ++k)
        for (int r = k; r <= L.sky(k); ++r) L.at(r, k) = M(r, k);
    return L;
}

/// The same shape with `pad` unused slots before every column and after the last one, so that
/// anything read just outside a column's stored rows lands in padding.
inline linalg::SkylineShape padded(const linalg::SkylineShape& shape, int pad) {
    linalg::SkylineShape out = shape;
    for (int k = 0; k <= shape.n; ++k) out.colptr[k] = shape.colptr[k] + static_cast<std::ptrdiff_t>(k + 1) * pad;
    return out;
}

/// Flags the value slots that hold stored entries (the rest is padding).
inline std::vector<char> stored_slots(const linalg::SkylineMatrix& L) {
    std::vector<char> used(L.values().size(), 0);
    for (int k = 0; k < L.n(); ++k)
        for (int r = k; r <= L.sky(k); ++r) used[static_cast<std::size_t>(L.shape().colptr[k] + (r - k))] = 1;
    return used;
}

/// Marks every value slot outside the stored rows (the padding) as NaN.
inline void poison_padding(linalg::SkylineMatrix& L) {
    const std::vector<char> used = stored_slots(L);
    for (std::size_t s = 0; s < used.size(); ++s)
        if (!used[s]) L.values()[s] = std::numeric_limits<double>::quiet_NaN();
}

/// True when every padding slot still holds NaN (nothing was written outside the envelope).
inline bool padding_untouched(const linalg::SkylineMatrix& L) {
    const std::vector<char> used = stored_slots(L);
    for (std::size_t s = 0; s < used.size(); ++s)
        if (!used[s] && !std::isnan(L.values()[s])) return false;
    return true;
}

/// Blocks of constraint rows (one block per joint or contact) coupling pairs of bodies, in the
/// layout of Problem::block_row / block_body (body -1: the static environment).
struct BlockStructure {
    std::vector<int> block_row{0};  ///< num_blocks + 1 row offsets
    std::vector<int> block_body;    ///< 2 per block
    int num_blocks() const { return static_cast<int>(block_body.size() / 2); }
    int rows() const { return block_row.back(); }
    void add(int rows_in_block, int body_a, int body_b) {
        block_row.push_back(block_row.back() + rows_in_block);
        block_body.push_back(body_a);
        block_body.push_back(body_b);
    }
    /// The same blocks listed in the order block_order[new] = old.
    BlockStructure reordered(const std::vector<int>& block_order) const {
        BlockStructure out;
        for (int b : block_order) out.add(block_row[b + 1] - block_row[b], block_body[2 * b], block_body[2 * b + 1]);
        return out;
    }
};

/// A = J M⁻¹ Jᵀ + cfm I for random Jacobian rows acting on the 6 velocity coordinates of each
/// block's bodies and random masses: block (a, b) of A is non-zero iff blocks a and b share a body,
/// the sparsity ODE's world step produces.
inline MatrixXd constraint_matrix(const BlockStructure& blocks, std::mt19937& rng, double cfm = 1e-6) {
    int num_bodies = 0;
    for (int body : blocks.block_body) num_bodies = std::max(num_bodies, body + 1);
    std::uniform_real_distribution<double> entry(-1.0, 1.0), log_mass(0.0, 2.0);
    MatrixXd J = MatrixXd::Zero(blocks.rows(), 6 * num_bodies);
    for (int b = 0; b < blocks.num_blocks(); ++b)
        for (int side = 0; side < 2; ++side) {
            const int body = blocks.block_body[2 * b + side];
            if (body < 0) continue;
            for (int r = blocks.block_row[b]; r < blocks.block_row[b + 1]; ++r)
                for (int c = 0; c < 6; ++c) J(r, 6 * body + c) = entry(rng);
        }
    VectorXd inverse_mass(6 * num_bodies);
    for (int body = 0; body < num_bodies; ++body)
        inverse_mass.segment(6 * body, 6).setConstant(std::pow(10.0, -log_mass(rng)));
    MatrixXd A = J * inverse_mass.asDiagonal() * J.transpose();
    A.diagonal().array() += cfm;
    return A;
}

/// A winch-like island: a chain of `links` bodies joined by 3-row ball joints, the first link
/// hinged to a heavy drum body; the first links touch the drum and the last third lies on the
/// ground (3-row contacts), and the contacts come last, as ODE lists contact joints after the
/// others.
inline BlockStructure winch_blocks(int links) {
    BlockStructure blocks;
    const int drum = links;
    blocks.add(5, drum, -1);  // the drum's hinge to the world
    blocks.add(3, drum, 0);
    for (int l = 0; l + 1 < links; ++l) blocks.add(3, l, l + 1);
    for (int l = 0; l < std::min(links, 4); ++l) blocks.add(3, l, drum);
    for (int l = links - links / 3; l < links; ++l) blocks.add(3, l, -1);
    return blocks;
}

}  // namespace ode_bpp::test
