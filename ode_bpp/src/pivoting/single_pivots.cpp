#include "pivoting/single_pivots.h"

#include <algorithm>

#include "pivoting/classify_row.h"
#include "pivoting/free_rows_factor.h"
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
    std::vector<RowState> entry;  ///< the index set the run started from
    Iterate it;
    Infeasibility inf;
    VisitedSets visited;
};

class SinglePivots {
public:
    SinglePivots(const BoxedLcp& lcp, const PivotSettings& settings, PivotCounters& counters, Workspace& ws,
                 FreeRowsFactor& factor)
        : lcp_(lcp), tolerance_(settings.tolerance), record_steps_(settings.record_steps), counters_(counters), n_(lcp.n()),
          ws_(ws), factor_(factor) {
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
        if (!factor_.reset(lcp_, states)) return give_up(states, LoopOutcome::Breakdown);
        int least_count = n_ + 1, last_progress = 0;
        bool in_murty = false;
        ws_.visited.clear();
        for (int step = 0; step < max_pivots; ++step) {
            ++counters_.pivots;
            ++counters_.murty_pivots;
            ++counters_.update_steps;
            if (record_steps_) counters_.tight_per_step.push_back(n_ - static_cast<int>(factor_.members().size()));
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
        if (to != RowState::Free) factor_.remove(row);
        else if (!factor_.add(row)) return false;
        states[row] = to;
        return true;
    }

    LoopOutcome give_up(std::vector<RowState>& states, LoopOutcome outcome) const {
        states = ws_.entry;
        return outcome;
    }

    /// x_T at its bounds, x_F from Eq. 6 with the updated factor, then w.
    bool solve(const std::vector<RowState>& states, std::vector<double>& x) {
        x.assign(static_cast<std::size_t>(n_), 0.0);
        for (int i = 0; i < n_; ++i)
            if (states[i] != RowState::Free) x[i] = tight_value(lcp_, i, states[i]);
        return factor_.solve(x, ws_.it, tolerance_, counters_);
    }

    const BoxedLcp& lcp_;
    const double tolerance_;
    const bool record_steps_;
    PivotCounters& counters_;
    const int n_;
    Workspace& ws_;
    FreeRowsFactor& factor_;
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
                          std::vector<double>& x, PivotCounters& counters, SinglePivotsWorkspace& workspace,
                          FreeRowsFactor& factor) {
    return SinglePivots(lcp, settings, counters, workspace.contents().single_pivots, factor)
        .run(states, x, settings.max_pivots);
}

}  // namespace ode_bpp::pivoting
