#include "pivoting/free_rows_factor.h"

#include <algorithm>
#include <cmath>

namespace ode_bpp::pivoting {

bool FreeRowsFactor::reset(const BoxedLcp& lcp, const std::vector<RowState>& states) {
    lcp_ = &lcp;
    const int n = lcp.n();
    factor_.reset(n);
    members_.clear();
    position_.assign(static_cast<std::size_t>(n), -1);
    column_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
        if (states[i] == RowState::Free && !add(i)) return false;
    return true;
}

bool FreeRowsFactor::add(int i) {
    const linalg::SymmetricRows& A = *lcp_->A;
    const int m = factor_.size();
    std::fill(column_.begin(), column_.begin() + m, 0.0);
    for (int k = A.row_begin(i); k < A.row_end(i); ++k) {
        const int p = position_[A.col(k)];
        if (p >= 0) column_[p] = A.val(k);
    }
    if (!factor_.append(column_.data(), A.diag(i) + lcp_->shift)) return false;
    position_[i] = m;
    members_.push_back(i);
    return true;
}

void FreeRowsFactor::remove(int i) {
    const int p = position_[i];
    factor_.remove(p);
    members_.erase(members_.begin() + p);
    position_[i] = -1;
    for (int k = p; k < static_cast<int>(members_.size()); ++k) position_[members_[k]] = k;
}

bool FreeRowsFactor::solve(std::vector<double>& x, Iterate& it, double tolerance, PivotStats& counters) {
    solve_free_rows(x, it);
    if (free_residual(it) <= accuracy_limit(tolerance, lcp_->n())) return true;
    ++counters.accuracy_refactors;
    if (!refactor()) return false;
    solve_free_rows(x, it);
    return true;
}

void FreeRowsFactor::solve_free_rows(std::vector<double>& x, Iterate& it) {
    x_tight_ = x;
    for (int i : members_) x_tight_[i] = 0;
    lcp_->A->multiply(x_tight_, lcp_->shift, Ax_);  // A_FT x_T on the free rows
    const int m = factor_.size();
    rhs_.resize(static_cast<std::size_t>(m));
    for (int p = 0; p < m; ++p) rhs_[p] = lcp_->b[members_[p]] - Ax_[members_[p]];
    factor_.solve(rhs_.data());
    for (int p = 0; p < m; ++p) x[members_[p]] = rhs_[p];
    refresh_residual(*lcp_, x, it);
}

bool FreeRowsFactor::refactor() {
    std::vector<int> rows = members_;  // rare: only where updates have lost accuracy
    std::sort(rows.begin(), rows.end());
    factor_.reset(lcp_->n());
    members_.clear();
    std::fill(position_.begin(), position_.end(), -1);
    for (int i : rows)
        if (!add(i)) return false;
    return true;
}

double FreeRowsFactor::free_residual(const Iterate& it) const {
    double worst = 0;
    for (int i : members_)
        if (it.w[i] != 0) worst = std::max(worst, std::abs(it.w[i]) / it.scale[i]);
    return worst;
}

}  // namespace ode_bpp::pivoting
