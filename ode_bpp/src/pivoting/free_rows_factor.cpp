#include "pivoting/free_rows_factor.h"

#include <algorithm>
#include <cmath>

namespace ode_bpp::pivoting {

namespace {

/// Rows joining F out of order widen the factor's envelope (each spans from its first neighbour
/// in F to the end). Once the stored envelope exceeds this multiple of its size at the last
/// refresh (or than twice the island's rows), F is refactored in increasing index: a
/// factorization on the envelope costs about as much as a few solves on the widened one.
constexpr std::size_t kReorderGrowth = 2;

/// A seed serves while at most one row in this many of the new free set changes set against it.
/// Each change costs about what a fresh factorization spends on a row or more (a removal rotates
/// every row after it, an append is a forward solve). Where the start's projection tightens a
/// third of the seed's free rows (the rock pile's islands of 1,000 rows) the seeded reset took
/// three times the fresh one's instructions; on the forwarder one row in forty changes. 4 and 8
/// gave the same counts on both; 2 cost the rock pile 1.4 % (docs/tuning.md).
constexpr int kSeedRowsPerChange = 4;

/// Rows that leave or join F between the seed's free set and `states`'.
int changes_against(const EnvelopeFactor& seed, const std::vector<RowState>& states, std::vector<char>& seed_tight) {
    seed_tight.assign(states.size(), 0);
    for (int i : *seed.tight_rows) seed_tight[i] = 1;
    int changes = 0;
    for (std::size_t i = 0; i < states.size(); ++i) changes += (states[i] == RowState::Free) == static_cast<bool>(seed_tight[i]);
    return changes;
}

}  // namespace

bool FreeRowsFactor::reset(const BoxedLcp& lcp, const std::vector<RowState>& states, const std::vector<double>& x) {
    lcp_ = &lcp;
    take_tight_values(states, x);
    members_.clear();
    for (int i = 0; i < lcp.n(); ++i)
        if (states[i] == RowState::Free) members_.push_back(i);
    return refresh();
}

bool FreeRowsFactor::reset(const BoxedLcp& lcp, const std::vector<RowState>& states, const std::vector<double>& x,
                           const EnvelopeFactor& seed) {
    if (seed.L == nullptr || seed.L->n() != lcp.n()) return reset(lcp, states, x);
    const int free_rows = static_cast<int>(std::count(states.begin(), states.end(), RowState::Free));
    if (kSeedRowsPerChange * changes_against(seed, states, seed_tight_) > free_rows) return reset(lcp, states, x);
    lcp_ = &lcp;
    take_tight_values(states, x);
    compute_tight_product();
    load_seed(seed);
    // the last position first: a removal rotates only the rows after it (incremental_cholesky.h)
    for (int p = static_cast<int>(members_.size()) - 1; p >= 0; --p)
        if (states[members_[p]] != RowState::Free) drop(p);
    for (int i = 0; i < lcp.n(); ++i)
        if (states[i] == RowState::Free && position_[i] < 0 && !append_row(i)) return false;
    refreshed_entries_ = factor_.stored_entries();
    updates_ = 0;
    return true;
}

void FreeRowsFactor::take_tight_values(const std::vector<RowState>& states, const std::vector<double>& x) {
    const int n = lcp_->n();
    tight_x_.assign(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i)
        if (states[i] != RowState::Free) tight_x_[i] = x[i];
}

/// Over the columns of the rows held at a non-zero value only (tight_x_ is 0 on F; iterate.h's
/// off_diagonal_product), O(n + their entries) instead of a product with A.
void FreeRowsFactor::compute_tight_product() {
    off_diagonal_product(*lcp_->A, tight_x_, tight_columns_, tight_product_);
}

/// Row i of L_FF is L(i, j) over the free columns j from its first non-zero on (found by walking
/// row i from the first column holding it: a few entries), so its recorded envelope is what a
/// bordered factorization would record (incremental_cholesky.h), and every such column stores row
/// i (its sky reaches i): one pass down the seed's free columns writes each recorded entry once.
void FreeRowsFactor::load_seed(const EnvelopeFactor& seed) {
    const linalg::SkylineMatrix& L = *seed.L;
    const int n = lcp_->n();
    position_.assign(static_cast<std::size_t>(n), -1);
    members_.clear();
    for (int i = 0; i < n; ++i) {
        if (seed_tight_[i]) continue;
        position_[i] = static_cast<int>(members_.size());
        members_.push_back(i);
    }
    std::vector<int>& first = seed_first_;
    first.resize(members_.size());
    for (std::size_t p = 0; p < members_.size(); ++p) {
        const int i = members_[p];
        int j = L.shape().first_column_holding(i);
        while (j < i && (position_[j] < 0 || L.at(i, j) == 0.0)) ++j;
        first[p] = position_[j];
    }
    factor_.reset(n);
    factor_.load_shape(first.data(), static_cast<int>(members_.size()));
    seed_rows_.resize(members_.size());  // seed_rows_[p][q] = L_FF(p, q) for first[p] <= q <= p
    for (std::size_t p = 0; p < members_.size(); ++p) seed_rows_[p] = factor_.loaded_row(static_cast<int>(p)) - first[p];
    for (int j : members_) {
        const int q = position_[j];
        const double* column = L.column(j) - j;
        for (int r = j; r <= L.sky(j); ++r) {
            const int p = position_[r];
            if (p >= 0 && q >= first[static_cast<std::size_t>(p)]) seed_rows_[static_cast<std::size_t>(p)][q] = column[r];
        }
    }
    factor_.finish_load();
    column_.resize(static_cast<std::size_t>(n));
}

bool FreeRowsFactor::refresh() {
    const int n = lcp_->n();
    refresh_rows_.swap(members_);  // F, rebuilt below in increasing index
    std::sort(refresh_rows_.begin(), refresh_rows_.end());
    members_.clear();
    factor_.reset(n);
    position_.assign(static_cast<std::size_t>(n), -1);
    column_.resize(static_cast<std::size_t>(n));
    compute_tight_product();
    for (int i : refresh_rows_)
        if (!append_row(i)) return false;
    refreshed_entries_ = factor_.stored_entries();
    updates_ = 0;
    return true;
}

FreeRowsFactor::AddOutcome FreeRowsFactor::add(int i) {
    if (!append_row(i)) return AddOutcome::Rejected;
    ++updates_;
    const std::size_t rows = static_cast<std::size_t>(lcp_->n());
    if (factor_.stored_entries() > kReorderGrowth * std::max(refreshed_entries_, rows) && !refresh())
        return AddOutcome::Broken;
    return AddOutcome::Added;
}

bool FreeRowsFactor::append_row(int i) {
    const linalg::SymmetricRows& A = *lcp_->A;
    const int m = factor_.size();
    int first = m;  // the column's first non-zero in F's order: the new row's envelope starts there
    for (int k = A.row_begin(i); k < A.row_end(i); ++k) {
        const int p = position_[A.col(k)];
        if (p >= 0) first = std::min(first, p);
    }
    std::fill(column_.begin() + first, column_.begin() + m, 0.0);
    for (int k = A.row_begin(i); k < A.row_end(i); ++k) {
        const int p = position_[A.col(k)];
        if (p >= 0) column_[p] = A.val(k);
    }
    if (!factor_.append(column_.data(), first, A.diag(i) + lcp_->shift)) return false;
    position_[i] = m;
    members_.push_back(i);
    if (tight_x_[i] != 0) add_column(i, -tight_x_[i]);
    tight_x_[i] = 0;
    return true;
}

void FreeRowsFactor::remove(int i, double value) {
    drop(position_[i]);
    ++updates_;
    tight_x_[i] = value;
    if (value != 0) add_column(i, value);
}

void FreeRowsFactor::drop(int p) {
    factor_.remove(p);
    position_[members_[p]] = -1;
    members_.erase(members_.begin() + p);
    for (int k = p; k < static_cast<int>(members_.size()); ++k) position_[members_[k]] = k;
}

void FreeRowsFactor::add_column(int i, double factor) {
    const linalg::SymmetricRows& A = *lcp_->A;
    for (int k = A.row_begin(i); k < A.row_end(i); ++k) tight_product_[A.col(k)] += factor * A.val(k);
}

void FreeRowsFactor::solve(std::vector<double>& x) const {
    const int m = factor_.size();
    rhs_.resize(static_cast<std::size_t>(m));
    for (int p = 0; p < m; ++p) rhs_[p] = lcp_->b[members_[p]] - tight_product_[members_[p]];
    factor_.solve(rhs_.data());
    for (int p = 0; p < m; ++p) x[members_[p]] = rhs_[p];
}

double FreeRowsFactor::curvature(const std::vector<double>& d) const {
    const int m = factor_.size();
    rhs_.resize(static_cast<std::size_t>(m));
    transformed_.resize(static_cast<std::size_t>(m));
    for (int p = 0; p < m; ++p) rhs_[p] = d[members_[p]];
    return factor_.quadratic_form(rhs_.data(), transformed_.data());
}

bool FreeRowsFactor::accurate(const Iterate& it, double tolerance) const {
    double worst = 0;
    for (int i : members_)
        if (it.w[i] != 0) worst = std::max(worst, std::abs(it.w[i]) / it.scale[i]);
    return worst <= accuracy_limit(tolerance, lcp_->n());
}

}  // namespace ode_bpp::pivoting
