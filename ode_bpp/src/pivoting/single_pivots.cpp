#include "pivoting/single_pivots.h"

#include <algorithm>

#include "linalg/incremental_cholesky.h"
#include "pivoting/classify_row.h"
#include "pivoting/iterate.h"
#include "pivoting/kept_buffers_impl.h"
#include "pivoting/murty_rule.h"
#include "pivoting/tuning.h"
#include "pivoting/visited_sets.h"

namespace ode_bpp::pivoting {

namespace {

/// The phase's vectors (SinglePivotsWorkspace), kept by the caller so that their capacity
/// outlives one run.
struct Workspace {
    linalg::IncrementalCholesky factor;
    std::vector<int> members;     ///< F in the factor's order
    std::vector<int> position;    ///< position[i] in members, -1 for a tight row
    std::vector<char> tight;
    std::vector<double> column, rhs, Ax;
    std::vector<RowState> entry;  ///< the index set the run started from
    Iterate it;
    Infeasibility inf;
    VisitedSets visited;
};

class SinglePivots {
public:
    SinglePivots(const BoxedLcp& lcp, const PivotSettings& settings, PivotCounters& counters, Workspace& ws)
        : lcp_(lcp), tolerance_(settings.tolerance), record_steps_(settings.record_steps), counters_(counters), n_(lcp.n()),
          ws_(ws) {
        ws_.it.lo = lcp.lo;
        ws_.it.hi = lcp.hi;
    }

    /// The most violated row flips, until the index set repeats (greedy single pivots can
    /// cycle); from there Murty's rule, until the count of infeasible rows falls below the least
    /// seen, then greedy again. Finite: each Murty phase is Murty's finite method cut short only
    /// at a new least count, which falls at most n times, and a greedy phase visits no index set
    /// twice. Against Murty's rule alone (with greedy pivots only at a new least count) it took
    /// 792 instead of 3,294 pivots on the captured islands of the slow tail (docs/tuning.md).
    LoopOutcome run(std::vector<RowState>& states, std::vector<double>& x, int max_pivots) {
        ws_.entry = states;
        if (!factor_free_rows(states)) return give_up(states, LoopOutcome::Breakdown);
        int least_count = n_ + 1, last_progress = 0;
        bool in_murty = false;
        ws_.visited.clear();
        for (int step = 0; step < max_pivots; ++step) {
            ++counters_.pivots;
            ++counters_.murty_pivots;
            ++counters_.update_steps;
            if (record_steps_) counters_.tight_per_step.push_back(n_ - ws_.factor.size());
            if (!solve(states, x)) return give_up(states, LoopOutcome::Breakdown);
            classify_iterate(lcp_, ws_.it, states, x, tolerance_, ws_.inf);
            if (ws_.inf.count() == 0) return LoopOutcome::Converged;
            if (ws_.inf.count() < least_count) {
                least_count = ws_.inf.count();
                last_progress = step;
                if (in_murty) ws_.visited.clear();
                in_murty = false;
            } else if (step - last_progress >= tuning::kSinglePivotPatience) {
                break;
            }
            if (!in_murty && ws_.visited.revisits(states)) in_murty = true;
            const int k = in_murty ? murty_choice(lcp_, ws_.inf) : most_violated(ws_.inf);
            if (!flip(k, states)) return give_up(states, LoopOutcome::Breakdown);
        }
        return give_up(states, LoopOutcome::MaxIterations);
    }

private:
    /// Row inf.rows[k] changes set, and the factor with it; false on breakdown.
    bool flip(int k, std::vector<RowState>& states) {
        const int row = ws_.inf.rows[k];
        const RowState to = ws_.inf.flip_to[k];
        if (to != RowState::Free) remove(row);
        else if (!add(row)) return false;
        states[row] = to;
        return true;
    }

    LoopOutcome give_up(std::vector<RowState>& states, LoopOutcome outcome) const {
        states = ws_.entry;
        return outcome;
    }

    /// L L^T = (A + shift I)_FF afresh, row by row in increasing index.
    bool factor_free_rows(const std::vector<RowState>& states) {
        ws_.factor.reset(n_);
        ws_.members.clear();
        ws_.position.assign(static_cast<std::size_t>(n_), -1);
        ws_.column.resize(static_cast<std::size_t>(n_));
        for (int i = 0; i < n_; ++i)
            if (states[i] == RowState::Free && !add(i)) return false;
        return true;
    }

    /// Row i joins F as the factor's last row: its column A(F, i) in F's order.
    bool add(int i) {
        const int m = ws_.factor.size();
        std::fill(ws_.column.begin(), ws_.column.begin() + m, 0.0);
        for (int k = lcp_.A->row_begin(i); k < lcp_.A->row_end(i); ++k) {
            const int p = ws_.position[lcp_.A->col(k)];
            if (p >= 0) ws_.column[p] = lcp_.A->val(k);
        }
        if (!ws_.factor.append(ws_.column.data(), lcp_.A->diag(i) + lcp_.shift)) return false;
        ws_.position[i] = m;
        ws_.members.push_back(i);
        return true;
    }

    void remove(int i) {
        const int p = ws_.position[i];
        ws_.factor.remove(p);
        ws_.members.erase(ws_.members.begin() + p);
        ws_.position[i] = -1;
        for (int k = p; k < static_cast<int>(ws_.members.size()); ++k) ws_.position[ws_.members[k]] = k;
    }

    /// x_T at its bounds, x_F from Eq. 6 with the updated factor, then w; a factor that misses
    /// Eq. 6 beyond accuracy_limit() is refactored once (iterate.h).
    bool solve(const std::vector<RowState>& states, std::vector<double>& x) {
        x.assign(static_cast<std::size_t>(n_), 0.0);
        ws_.tight.assign(static_cast<std::size_t>(n_), 0);
        for (int i = 0; i < n_; ++i)
            if (states[i] != RowState::Free) {
                ws_.tight[i] = 1;
                x[i] = tight_value(lcp_, i, states[i]);
            }
        lcp_.A->multiply(x, lcp_.shift, ws_.Ax);  // A_FT x_T on the free rows (x_F = 0 here)
        solve_free_rows(x);
        if (free_residual(ws_.it, ws_.tight) <= accuracy_limit(tolerance_, n_)) return true;
        ++counters_.accuracy_refactors;
        if (!factor_free_rows(states)) return false;
        solve_free_rows(x);
        return true;
    }

    void solve_free_rows(std::vector<double>& x) {
        const int m = ws_.factor.size();
        ws_.rhs.resize(static_cast<std::size_t>(m));
        for (int p = 0; p < m; ++p) ws_.rhs[p] = lcp_.b[ws_.members[p]] - ws_.Ax[ws_.members[p]];
        ws_.factor.solve(ws_.rhs.data());
        for (int p = 0; p < m; ++p) x[ws_.members[p]] = ws_.rhs[p];
        refresh_residual(lcp_, x, ws_.it);
    }

    const BoxedLcp& lcp_;
    const double tolerance_;
    const bool record_steps_;
    PivotCounters& counters_;
    const int n_;
    Workspace& ws_;
};

}  // namespace

bool single_pivots_apply(const BoxedLcp& lcp) {
    return !lcp.has_moving_bounds() && lcp.n() <= tuning::kSinglePivotMaxRows;
}

struct SinglePivotBuffers {
    Workspace single_pivots;
};
template class KeptBuffers<SinglePivotBuffers>;

LoopOutcome single_pivots(const BoxedLcp& lcp, const PivotSettings& settings, std::vector<RowState>& states,
                          std::vector<double>& x, PivotCounters& counters, SinglePivotsWorkspace& workspace) {
    return SinglePivots(lcp, settings, counters, workspace.contents().single_pivots).run(states, x, settings.max_pivots);
}

}  // namespace ode_bpp::pivoting
