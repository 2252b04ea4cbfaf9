// A Cholesky factor of (A + shift I)_FF for a free set F that changes by one row at a time
// (linalg/incremental_cholesky.h), and Eq. 6 solved with it: the factor behind the active-set
// stage (active_set.h), where each step moves one row between F and T at the cost of the
// factor's envelope, instead of a deletion from L0 or a refactorization per step. The
// right-hand side's A_FT x_T is kept up to date by one row of A per change of T, O(row entries),
// instead of a product with A per solve.
//
// Index space: the permuted space of the BoxedLcp, whose order (Cuthill-McKee) keeps A's envelope
// small: F factored in increasing index has the envelope of A_FF (a subset of A's), and a row
// joining F as the last one spans from its first neighbour in F on.
#pragma once

#include <vector>

#include "linalg/incremental_cholesky.h"
#include "ode_bpp/solver.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/free_solver.h"
#include "pivoting/iterate.h"

namespace ode_bpp::pivoting {

class FreeRowsFactor {
public:
    /// F = the rows Free in `states` (n entries), factored afresh in increasing index, for lcp
    /// (which must outlive the factor's use); x_T: the tight rows' values in x. False on breakdown
    /// (a free row dependent on the others to machine precision).
    bool reset(const BoxedLcp& lcp, const std::vector<RowState>& states, const std::vector<double>& x);
    /// The same from `seed`, a factor of the same A + shift I that the pivoting loop holds
    /// (FreeSolver::latest_factor) for its own free set F_s: L_FF of F_s is read off the seed as
    /// it stands, in increasing index, then the rows of F_s that `states` holds tight leave it
    /// and the free rows outside F_s join it, one update each (linalg/incremental_cholesky.h), in
    /// place of factoring F afresh. The plain reset where there is no seed, or where more than
    /// one row in four of F changes set against it (then the updates cost more than a fresh
    /// factorization).
    bool reset(const BoxedLcp& lcp, const std::vector<RowState>& states, const std::vector<double>& x,
               const EnvelopeFactor& seed);

    /// What add() did.
    enum class AddOutcome {
        Added,     ///< i is in F
        Rejected,  ///< i would break the factor down: F unchanged
        /// i joined, and the refactorization its growth called for (refresh) broke down: the
        /// factor holds part of F only, and nothing but reset() may use it again
        Broken,
    };
    /// Tight row i joins F as the factor's last row; refactors F afresh where the updates have
    /// grown the factor beyond kReorderGrowth times its entries when last built.
    AddOutcome add(int i);
    /// Free row i leaves F, held at `value` from now on.
    void remove(int i, double value);
    /// F in the factor's order.
    const std::vector<int>& members() const { return members_; }
    /// Rows added to or removed from F since the factor was last built (reset, refresh, or an
    /// add that refactored): 0 for a fresh factor, whose solves meet Eq. 6 to about n eps.
    int updates() const { return updates_; }

    /// Eq. 6: x_F = (A + shift I)_FF⁻¹ (b - A_FT x_T)_F with the tight values x_T given to
    /// reset() and remove(); x's other entries are left as they are.
    void solve(std::vector<double>& x) const;
    /// dᵀ (A + shift I)_FF d for d: n entries, 0 off F (only its F entries are read), from the
    /// factor (IncrementalCholesky::quadratic_form): O(its entries), no product with A.
    double curvature(const std::vector<double>& d) const;
    /// True when w and scales at a solve()'s x (`it`, iterate.h) meet Eq. 6 on F within
    /// accuracy_limit(tolerance, n); false after many updates have worn the factor.
    bool accurate(const Iterate& it, double tolerance) const;
    /// Refactors F afresh and recomputes A_FT x_T (after !accurate()); false on breakdown.
    bool refresh();
    /// Gives the factor's storage back (IncrementalCholesky::release): a stage that runs now and
    /// then on a large island does not keep its factor resident for the rest of the run. The
    /// next reset() allocates afresh.
    void release() { factor_.release(); }
    /// Bytes of the factor's storage now held (IncrementalCholesky::storage_bytes).
    std::size_t storage_bytes() const { return factor_.storage_bytes(); }

private:
    void add_column(int i, double factor);  ///< tight_product_ += factor A(:, i), off the diagonal
    bool append_row(int i);                 ///< add() without the reordering check
    void drop(int p);                       ///< the member at position p leaves F (factor and members only)
    void take_tight_values(const std::vector<RowState>& states, const std::vector<double>& x);
    void compute_tight_product();           ///< tight_product_ from tight_x_
    /// F = F_s with the seed's L_FF (reset's seeded form); seed_tight_ flags the seed's tight rows.
    void load_seed(const EnvelopeFactor& seed);

    const BoxedLcp* lcp_ = nullptr;
    linalg::IncrementalCholesky factor_;
    std::vector<int> members_;            ///< F in the factor's order
    std::vector<int> position_;           ///< position of row i in members_, -1 for a tight row
    std::vector<double> tight_x_;         ///< x_T, 0 on F
    std::vector<double> tight_product_;   ///< A x_T without the diagonal: on F, A_FT x_T
    std::vector<int> tight_columns_;      ///< compute_tight_product's scratch
    std::vector<double> column_;
    std::vector<int> refresh_rows_;
    std::vector<double*> seed_rows_;      ///< load_seed's rows of L_FF, indexed by F position
    std::vector<char> seed_tight_;        ///< the seed's tight rows, flagged
    std::vector<int> seed_first_;         ///< load_seed's first recorded column (F position) of each member row
    std::size_t refreshed_entries_ = 0;   ///< the factor's stored entries after the last refresh()
    int updates_ = 0;                     ///< updates()
    mutable std::vector<double> rhs_;
    mutable std::vector<double> transformed_;  ///< curvature()'s Lᵀ d
};

}  // namespace ode_bpp::pivoting
