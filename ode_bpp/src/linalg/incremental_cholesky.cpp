#include "linalg/incremental_cholesky.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

#include "linalg/cholesky_pivot.h"

namespace ode_bpp::linalg {

namespace {

using Segment = Eigen::Map<Eigen::VectorXd>;
using ConstSegment = Eigen::Map<const Eigen::VectorXd>;

}  // namespace

void IncrementalCholesky::reset(int capacity) {
    size_ = 0;
    const auto rows = static_cast<std::size_t>(capacity);
    start_.assign(1, 0);
    start_.reserve(rows + 1);
    first_.resize(rows);
    sigma_.resize(rows);
    cos_.resize(rows);
    sin_.resize(rows);
}

void IncrementalCholesky::grow(std::size_t entries) {
    if (entries <= L_.capacity()) return;
    PageArray larger;
    larger.reserve(std::max(entries, 2 * L_.capacity()));
    std::copy(L_.data(), L_.data() + stored_entries(), larger.data());
    L_ = std::move(larger);
}

bool IncrementalCholesky::append(const double* column, int first, double diagonal) {
    const int m = size_;
    const std::size_t begin = start_[static_cast<std::size_t>(m)];
    grow(begin + static_cast<std::size_t>(m - first + 1));
    double* l = L_.data() + begin;  // l[k - first] = L(m, k)
    std::copy(column + first, column + m, l);
    // Forward substitution, one dot product per row over the overlap of the two envelopes
    for (int k = first; k < m; ++k) {
        const int from = std::max(first_[static_cast<std::size_t>(k)], first);
        const double* Lk = row_entries(k);
        const int fk = first_[static_cast<std::size_t>(k)];
        const double dot = ConstSegment(Lk + (from - fk), k - from).dot(ConstSegment(l + (from - first), k - from));
        l[k - first] = (l[k - first] - dot) / Lk[k - fk];
    }
    const double pivot = diagonal - ConstSegment(l, m - first).squaredNorm();
    if (pivot_breaks_down(pivot, diagonal)) return false;
    l[m - first] = std::sqrt(pivot);
    first_[static_cast<std::size_t>(m)] = first;
    start_.push_back(begin + static_cast<std::size_t>(m - first + 1));
    ++size_;
    return true;
}

void IncrementalCholesky::remove(int p) {
    for (int i = p + 1; i < size_; ++i) sigma_[i] = first(i) <= p ? entry(i, p) : 0.0;
    // Row i (old position) meets the rotations of columns max(p+1, first(i)) .. i-1 in turn (the
    // earlier ones see a zero entry and a zero sigma: the header's argument), then defines its
    // own: (L_ik, sigma_i) <- (c_k L_ik + s_k sigma_i, c_k sigma_i - s_k L_ik), and
    // r = sqrt(L_ii² + sigma_i²), c_i = L_ii / r, s_i = sigma_i / r, L_ii <- r.
    // It is written one row up and, from column p on, one column left, packed after row i-2's
    // new entries: that never passes an entry of row i not yet read (the rows shrink or keep
    // their length, and row p's entries are gone).
    std::size_t to_start = start_[static_cast<std::size_t>(p)];
    for (int i = p + 1; i < size_; ++i) {
        const int f = first(i);
        const int new_first = f <= p ? f : f - 1;
        const double* from = row_entries(i);  // from[k - f] = L(i, k)
        double* to = L_.data() + to_start;      // to[k - new_first] = new L(i - 1, k)
        double sigma = sigma_[i];
        if (f < p) std::copy(from, from + (p - f), to);
        for (int k = std::max(p + 1, f); k < i; ++k) {
            const double l = from[k - f];
            to[k - 1 - new_first] = cos_[k] * l + sin_[k] * sigma;
            sigma = cos_[k] * sigma - sin_[k] * l;
        }
        const double d = from[i - f];
        const double r = std::sqrt(d * d + sigma * sigma);
        cos_[i] = d / r;
        sin_[i] = sigma / r;
        to[i - 1 - new_first] = r;
        first_[static_cast<std::size_t>(i - 1)] = new_first;
        start_[static_cast<std::size_t>(i - 1)] = to_start;
        to_start += static_cast<std::size_t>(i - new_first);
    }
    start_[static_cast<std::size_t>(size_ - 1)] = to_start;
    start_.pop_back();
    --size_;
}

void IncrementalCholesky::solve(double* x) const {
    // L y = x: a dot product per row over its envelope
    for (int i = 0; i < size_; ++i) {
        const int f = first(i);
        const double* Li = row_entries(i);
        x[i] = (x[i] - ConstSegment(Li, i - f).dot(ConstSegment(x + f, i - f))) / Li[i - f];
    }
    // Lᵀ x = y: row i of L is column i of Lᵀ, an axpy per row
    for (int i = size_ - 1; i >= 0; --i) {
        const int f = first(i);
        const double* Li = row_entries(i);
        x[i] /= Li[i - f];
        Segment(x + f, i - f) -= x[i] * ConstSegment(Li, i - f);
    }
}

void IncrementalCholesky::release() {
    L_.release();
    size_ = 0;
    start_.assign(1, 0);
}

}  // namespace ode_bpp::linalg
