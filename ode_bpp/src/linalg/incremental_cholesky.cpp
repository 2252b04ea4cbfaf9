#include "linalg/incremental_cholesky.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

#include "linalg/cholesky_pivot.h"

namespace ode_bpp::linalg {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using FactorMap = Eigen::Map<const RowMajor, 0, Eigen::OuterStride<>>;

}  // namespace

void IncrementalCholesky::reset(int capacity) {
    capacity_ = capacity;
    size_ = 0;
    const std::size_t entries = static_cast<std::size_t>(capacity) * capacity;
    L_.reserve(entries);
    sigma_.resize(static_cast<std::size_t>(capacity));
    cos_.resize(static_cast<std::size_t>(capacity));
    sin_.resize(static_cast<std::size_t>(capacity));
}

bool IncrementalCholesky::append(const double* column, double diagonal) {
    Eigen::Map<Eigen::VectorXd> l(row(size_), size_);
    l = Eigen::Map<const Eigen::VectorXd>(column, size_);
    FactorMap(L_.data(), size_, size_, Eigen::OuterStride<>(capacity_)).triangularView<Eigen::Lower>().solveInPlace(l);
    const double pivot = diagonal - l.squaredNorm();
    if (pivot_breaks_down(pivot, diagonal)) return false;
    row(size_)[size_] = std::sqrt(pivot);
    ++size_;
    return true;
}

void IncrementalCholesky::remove(int p) {
    for (int i = p + 1; i < size_; ++i) sigma_[i] = row(i)[p];
    // Row i (old position) meets the rotations of columns p+1 .. i-1 in turn, then defines its
    // own: (L_ik, sigma_i) <- (c_k L_ik + s_k sigma_i, c_k sigma_i - s_k L_ik), and
    // r = sqrt(L_ii² + sigma_i²), c_i = L_ii / r, s_i = sigma_i / r, L_ii <- r.
    // It is written one row up and, from column p on, one column left: row i-1 is consumed.
    for (int i = p + 1; i < size_; ++i) {
        double* from = row(i);
        double* to = row(i - 1);
        double sigma = sigma_[i];
        std::copy(from, from + p, to);
        for (int k = p + 1; k < i; ++k) {
            const double l = from[k];
            to[k - 1] = cos_[k] * l + sin_[k] * sigma;
            sigma = cos_[k] * sigma - sin_[k] * l;
        }
        const double d = from[i];
        const double r = std::sqrt(d * d + sigma * sigma);
        cos_[i] = d / r;
        sin_[i] = sigma / r;
        to[i - 1] = r;
    }
    --size_;
}

void IncrementalCholesky::solve(double* x) const {
    // Eigen's blocked triangular solves: at the hundreds of rows this factor is for, a third of
    // the instructions of plain loops (callgrind, forwarder islands)
    const FactorMap L(L_.data(), size_, size_, Eigen::OuterStride<>(capacity_));
    Eigen::Map<Eigen::VectorXd> v(x, size_);
    L.triangularView<Eigen::Lower>().solveInPlace(v);
    L.transpose().triangularView<Eigen::Upper>().solveInPlace(v);
}

void IncrementalCholesky::release() {
    L_.release();
    capacity_ = 0;
    size_ = 0;
}

}  // namespace ode_bpp::linalg
