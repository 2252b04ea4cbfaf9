#include "linalg/incremental_cholesky.h"

#include <algorithm>
#include <cmath>

#include "linalg/cholesky_pivot.h"
#include "linalg/kernel_clones.h"

namespace ode_bpp::linalg {

namespace {

/// sum_k a[k] b[k] over k < n, in four partial sums (k mod 4) added as (s0 + s1) + (s2 + s3):
/// one fixed order, which the AVX2 copy of a kernel keeps in one register and the baseline in
/// two, with the same bits (kernel_clones.h). Short envelope rows are most of the calls, so the
/// loop has no set-up beyond its tail.
[[gnu::always_inline]] inline double dot(const double* a, const double* b, int n) {
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    int k = 0;
    for (; k + 4 <= n; k += 4) {
        s0 += a[k] * b[k];
        s1 += a[k + 1] * b[k + 1];
        s2 += a[k + 2] * b[k + 2];
        s3 += a[k + 3] * b[k + 3];
    }
    if (k < n) s0 += a[k] * b[k];
    if (k + 1 < n) s1 += a[k + 1] * b[k + 1];
    if (k + 2 < n) s2 += a[k + 2] * b[k + 2];
    return (s0 + s1) + (s2 + s3);
}

}  // namespace

void IncrementalCholesky::reset(int capacity) {
    size_ = 0;
    const auto rows = static_cast<std::size_t>(capacity);
    start_.assign(1, 0);
    start_.reserve(rows + 1);
    first_.resize(rows);
    inverse_pivot_.resize(rows);
    sigma_.resize(rows);
    pending_row_.resize(rows);
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

namespace {

/// The new row l = L⁻¹ c of append (l[k - first] = c_k on entry, for first <= k < m): forward
/// substitution, one dot product per row over the overlap of the two envelopes; then |l|². Rows
/// of L are packed at L + start[k], from column first_col[k]; inverse[k] = 1 / L(k, k). On x86-64
/// also compiled for AVX2 (kernel_clones.h): the same bits.
KERNEL_FOR_AVX2_TOO
double forward_new_row(const double* L, const std::size_t* start, const int* first_col, const double* inverse,
                       double* l, int first, int m) {
    for (int k = first; k < m; ++k) {
        const int fk = first_col[k];
        const int from = std::max(fk, first);
        const double* Lk = L + start[k];
        l[k - first] = (l[k - first] - dot(Lk + (from - fk), l + (from - first), k - from)) * inverse[k];
    }
    return dot(l, l, m - first);
}

}  // namespace

bool IncrementalCholesky::append(const double* column, int first, double diagonal) {
    const int m = size_;
    const std::size_t begin = start_[static_cast<std::size_t>(m)];
    grow(begin + static_cast<std::size_t>(m - first + 1));
    double* l = L_.data() + begin;  // l[k - first] = L(m, k)
    std::copy(column + first, column + m, l);
    const double pivot =
        diagonal - forward_new_row(L_.data(), start_.data(), first_.data(), inverse_pivot_.data(), l, first, m);
    if (pivot_breaks_down(pivot, diagonal)) return false;
    l[m - first] = std::sqrt(pivot);
    inverse_pivot_[static_cast<std::size_t>(m)] = 1.0 / l[m - first];
    first_[static_cast<std::size_t>(m)] = first;
    start_.push_back(begin + static_cast<std::size_t>(m - first + 1));
    ++size_;
    return true;
}

void IncrementalCholesky::load_shape(const int* first, int size) {
    size_ = 0;  // nothing kept: grow() copies no entries
    start_.resize(static_cast<std::size_t>(size) + 1);
    start_[0] = 0;
    for (int i = 0; i < size; ++i) {
        first_[static_cast<std::size_t>(i)] = first[i];
        start_[static_cast<std::size_t>(i) + 1] = start_[static_cast<std::size_t>(i)] + static_cast<std::size_t>(i - first[i] + 1);
    }
    grow(start_.back());
    size_ = size;
}

void IncrementalCholesky::finish_load() {
    for (int i = 0; i < size_; ++i) inverse_pivot_[static_cast<std::size_t>(i)] = 1.0 / row_entries(i)[i - first(i)];
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
    int i = p + 1;
    for (; i + 1 < size_; i += 2) to_start = rotate_row_pair(p, i, to_start);
    if (i < size_) {
        RotatedRow row(*this, p, i, L_.data() + to_start);
        row.rotate_from(row.k_begin, i);
        to_start = row.finish(to_start);
    }
    start_[static_cast<std::size_t>(size_ - 1)] = to_start;
    start_.pop_back();
    --size_;
}

IncrementalCholesky::RotatedRow::RotatedRow(IncrementalCholesky& factor, int p, int i, double* to)
    : factor(factor), i(i), f(factor.first(i)), new_first(f <= p ? f : f - 1), k_begin(std::max(p + 1, f)),
      from(factor.row_entries(i)), to(to), sigma(factor.sigma_[i]) {
    if (f < p) std::copy(from, from + (p - f), to);
}

std::size_t IncrementalCholesky::RotatedRow::finish(std::size_t to_start) {
    const double d = from[i - f];
    const double r = std::sqrt(d * d + sigma * sigma);
    factor.cos_[i] = d / r;
    factor.sin_[i] = sigma / r;
    to[i - 1 - new_first] = r;
    factor.inverse_pivot_[static_cast<std::size_t>(i - 1)] = 1.0 / r;
    factor.first_[static_cast<std::size_t>(i - 1)] = new_first;
    factor.start_[static_cast<std::size_t>(i - 1)] = to_start;
    return to_start + static_cast<std::size_t>(i - new_first);
}

std::size_t IncrementalCholesky::rotate_row_pair(int p, int i, std::size_t to_start) {
    // Row i+1's new entries go to a buffer first: in place they could land on its own entries not
    // yet read, which row i's sequence leaves alone only when the rows take their turns.
    RotatedRow a(*this, p, i, L_.data() + to_start);
    RotatedRow b(*this, p, i + 1, pending_row_.data());
    // Both rows meet the rotations k < i; each row's dependent chain runs beside the other's, and
    // each takes its own rotations in their order, so the bits are those of one row at a time.
    const int shared = std::max(a.k_begin, b.k_begin);
    a.rotate_from(a.k_begin, std::min(shared, i));
    b.rotate_from(b.k_begin, std::min(shared, i));
    for (int k = shared; k < i; ++k) {
        a.rotate(k);
        b.rotate(k);
    }
    to_start = a.finish(to_start);
    b.rotate_from(std::max(b.k_begin, i), i + 1);  // the rotation row i has just defined
    const std::size_t end = b.finish(to_start);
    std::copy(pending_row_.data(), pending_row_.data() + (end - to_start), L_.data() + to_start);
    return end;
}

namespace {

/// x <- (L Lᵀ)⁻¹ x for the n packed rows of L (as in forward_new_row): L y = x by a dot product
/// per row over its envelope, then Lᵀ x = y, row i of L being column i of Lᵀ, by an axpy per
/// row. On x86-64 also compiled for AVX2 (kernel_clones.h): the same bits.
KERNEL_FOR_AVX2_TOO
void solve_packed(const double* __restrict L, const std::size_t* start, const int* first_col, const double* inverse,
                  int n, double* __restrict x) {
    for (int i = 0; i < n; ++i) {
        const int f = first_col[i];
        const double* Li = L + start[i];
        x[i] = (x[i] - dot(Li, x + f, i - f)) * inverse[i];
    }
    for (int i = n - 1; i >= 0; --i) {
        const int f = first_col[i];
        const double* Li = L + start[i];
        const double xi = x[i] * inverse[i];
        x[i] = xi;
        double* xf = x + f;
        for (int k = 0; k < i - f; ++k) xf[k] -= xi * Li[k];
    }
}

}  // namespace

void IncrementalCholesky::solve(double* x) const {
    solve_packed(L_.data(), start_.data(), first_.data(), inverse_pivot_.data(), size_, x);
}

double IncrementalCholesky::quadratic_form(const double* v, double* y) const {
    std::fill(y, y + size_, 0.0);
    for (int i = 0; i < size_; ++i) {  // row i of L is column i of Lᵀ: y += v_i L(i, :)
        const int f = first_[static_cast<std::size_t>(i)];
        const double* Li = row_entries(i);
        const double vi = v[i];
        for (int k = 0; k <= i - f; ++k) y[f + k] += Li[k] * vi;
    }
    double sum = 0;
    for (int k = 0; k < size_; ++k) sum += y[k] * y[k];
    return sum;
}

void IncrementalCholesky::release() {
    L_.release();
    size_ = 0;
    start_.assign(1, 0);
}

}  // namespace ode_bpp::linalg
