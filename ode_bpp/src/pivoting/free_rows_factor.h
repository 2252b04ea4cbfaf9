// A dense Cholesky factor of (A + shift I)_FF for a free set F that changes by one row at a time
// (linalg/incremental_cholesky.h), and Eq. 6 solved with it: the factor behind the active-set
// stage (active_set.h), where each step moves one row between F and T, O(|F|²) instead of a
// deletion from L0 or a refactorization per step.
//
// Index space: the permuted space of the BoxedLcp.
#pragma once

#include <vector>

#include "linalg/incremental_cholesky.h"
#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/iterate.h"

namespace ode_bpp::pivoting {

class FreeRowsFactor {
public:
    /// F = the rows Free in `states` (n entries), factored afresh in increasing index, for lcp
    /// (which must outlive the factor's use). False on breakdown (a free row dependent on the
    /// others to machine precision).
    bool reset(const BoxedLcp& lcp, const std::vector<RowState>& states);

    /// Row i (not in F) joins F as the factor's last row; false, F unchanged, on breakdown.
    bool add(int i);
    /// Row i (in F) leaves F.
    void remove(int i);
    bool contains(int i) const { return position_[i] >= 0; }
    /// F in the factor's order.
    const std::vector<int>& members() const { return members_; }

    /// Eq. 6: x_F = (A + shift I)_FF⁻¹ (b - (A + shift I)_FT x_T)_F from x_T (x's entries outside
    /// F; those inside are overwritten), then w and the scales at the new x into `it`. A factor
    /// that misses Eq. 6 by more than accuracy_limit(tolerance, n) (after many updates) is
    /// refactored once (counted in counters.accuracy_refactors). False on breakdown there.
    bool solve(std::vector<double>& x, Iterate& it, double tolerance, PivotStats& counters);

private:
    void solve_free_rows(std::vector<double>& x, Iterate& it);
    bool refactor();
    double free_residual(const Iterate& it) const;

    const BoxedLcp* lcp_ = nullptr;
    linalg::IncrementalCholesky factor_;
    std::vector<int> members_;   ///< F in the factor's order
    std::vector<int> position_;  ///< position of row i in members_, -1 for a tight row
    std::vector<double> column_, rhs_, Ax_, x_tight_;
};

}  // namespace ode_bpp::pivoting
