#include "pivoting/active_set.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "pivoting/classify_row.h"
#include "pivoting/iterate.h"
#include "pivoting/kept_buffers_impl.h"
#include "pivoting/murty_rule.h"
#include "pivoting/tuning.h"

namespace ode_bpp::pivoting {

struct ActiveSetBuffers {
    std::vector<RowState> entry_states;  ///< what the run started from, given back on failure
    std::vector<double> entry_x;
    std::vector<double> target;          ///< the face's minimizer x*
    Iterate it;
    Infeasibility inf;
    std::vector<std::pair<int, RowState>> reached;  ///< free rows a step took onto a bound
    std::vector<std::pair<int, RowState>> released;  ///< tight rows the latest release freed
    std::vector<int> to_release;                     ///< positions in inf of the rows a release frees
    std::vector<double> direction;                   ///< d of a bent step
};
template class KeptBuffers<ActiveSetBuffers>;

namespace {

class ActiveSet {
public:
    ActiveSet(const BoxedLcp& lcp, const PivotSettings& settings, PivotCounters& counters, ActiveSetBuffers& ws,
              FreeRowsFactor& factor)
        : lcp_(lcp), settings_(settings), counters_(counters), ws_(ws), factor_(factor), n_(lcp.n()) {
        ws_.it.lo = lcp.lo;
        ws_.it.hi = lcp.hi;
    }

    LoopOutcome run(std::vector<RowState>& states, std::vector<double>& x, const EnvelopeFactor& seed) {
        ws_.entry_states = states;
        ws_.entry_x = x;
        // a run that spent its budget right after a release leaves those rows in the kept
        // buffers; they are not this run's, and its factor does not hold them (fuzz_solve)
        ws_.released.clear();
        project(states, x);
        if (!factor_.reset(lcp_, states, x, seed)) return give_up(states, x, LoopOutcome::Breakdown);
        int polish_rounds = tuning::kPolishRounds;
        for (int step = 0; step < settings_.max_pivots; ++step) {
            ++counters_.pivots;
            ++counters_.murty_pivots;
            ++counters_.update_steps;
            if (settings_.record_steps)
                counters_.tight_per_step.push_back(n_ - static_cast<int>(factor_.members().size()));
            ws_.target = x;
            factor_.solve(ws_.target);
            const bool bent = ws_.released.size() > 1 && bent_step(states, x);
            ws_.released.clear();
            if (bent) continue;  // x moved along a descent direction short of the face's minimizer
            const double alpha = step_length(x, 1);
            if (alpha < 1) {
                move(alpha, states, x);
                continue;
            }
            // x = x*, feasible; Eq. 4 on the tight rows decides (every free row is strictly inside)
            const bool updated = factor_.updates() > 0;
            x.swap(ws_.target);
            tighten_rows_on_bounds(states, x);
            refresh_tight_residual(lcp_, x, states, ws_.it);
            classify_iterate(lcp_, ws_.it, states, x, settings_.tolerance, ws_.inf);
            const bool feasible = ws_.inf.count() == 0;
            if (updated && wants_accuracy_check(feasible) && !factor_accurate(states, x)) {
                ++counters_.accuracy_refactors;
                if (!factor_.refresh()) return give_up(states, x, LoopOutcome::Breakdown);
                continue;  // the face's minimizer again, on the fresh factor
            }
            if (feasible && !polish(states, x, polish_rounds)) return converged(states);
            if (!release(states)) return give_up(states, x, LoopOutcome::Breakdown);
        }
        return give_up(states, x, LoopOutcome::MaxIterations);
    }

private:
    /// An updated factor is checked (Eq. 6's backward error on F) where its x* would be the
    /// answer, and at every tuning::kActiveSetUncheckedMinima-th face minimizer on the way, so
    /// that wear from many updates does not steer the releases for long. A check costs the
    /// free rows' part of w (most of A's entries: F holds 75-85 % of the rows of the paper's
    /// machines); the tight rows' part is what Eq. 4 reads anyway, and nothing else reads the
    /// free rows' part (a bent step's slope: along_direction).
    bool wants_accuracy_check(bool feasible) {
        if (feasible || ++unchecked_minima_ >= tuning::kActiveSetUncheckedMinima) {
            unchecked_minima_ = 0;
            return true;
        }
        return false;
    }

    /// Eq. 6 on F at the face's minimizer x (accuracy_limit): its free rows' w completed.
    bool factor_accurate(const std::vector<RowState>& states, const std::vector<double>& x) {
        refresh_free_residual(lcp_, x, states, ws_.it);
        return factor_.accurate(ws_.it, settings_.tolerance);
    }

    /// x onto [lo, hi]; a row on a bound after that starts tight there (so that every free row
    /// is strictly inside), unless it may not be tight.
    void project(std::vector<RowState>& states, std::vector<double>& x) const {
        states.resize(static_cast<std::size_t>(n_));
        for (int i = 0; i < n_; ++i) {
            x[i] = std::clamp(x[i], lcp_.lo[i], lcp_.hi[i]);
            if (lcp_.always_free[i]) states[i] = RowState::Free;
            else if (x[i] == lcp_.lo[i]) states[i] = RowState::AtLo;
            else if (x[i] == lcp_.hi[i]) states[i] = RowState::AtHi;
            else states[i] = RowState::Free;
        }
    }

    /// The polish of pivot_loop.h at a converged x: the classification tolerance lets a tight
    /// row keep a multiplier of the wrong sign up to tol * scale; those wrong beyond the
    /// factor's accuracy go into ws_.inf for release (true), at most `rounds` times per run, on
    /// the unshifted problem and where settings.polish asks for it.
    /// The method goes on from there with q still falling, so its next answer is no worse.
    bool polish(const std::vector<RowState>& states, const std::vector<double>& x, int& rounds) {
        if (rounds == 0 || !settings_.polish || lcp_.shift != 0) return false;
        classify_iterate(lcp_, ws_.it, states, x, accuracy_limit(settings_.tolerance, n_), ws_.inf);
        if (ws_.inf.count() == 0) return false;
        --rounds;
        return true;
    }

    /// A pinned row (lo = hi) reported at the bound its multiplier supports, as the pivoting
    /// loop reports it (iterate.h).
    LoopOutcome converged(std::vector<RowState>& states) const {
        orient_pinned_rows(ws_.it, states);
        return LoopOutcome::Converged;
    }

    /// Frees the tight rows whose multipliers have the wrong sign (ws_.inf at a face's minimizer),
    /// the most violated first, so that it is ws_.released[0], then the next most violated up to
    /// settings.release_at_most in all; a row that would break the factor down stays tight. False
    /// when the most violated one does (nothing freed then), or when the refactorization that an
    /// addition's growth called for broke down (the factor then holds part of F only).
    bool release(std::vector<RowState>& states) {
        ws_.released.clear();
        choose_releases();
        for (std::size_t k = 0; k < ws_.to_release.size(); ++k) {
            const int i = ws_.inf.rows[ws_.to_release[k]];  // a tight row: free rows are feasible
            const FreeRowsFactor::AddOutcome added = factor_.add(i);
            if (added == FreeRowsFactor::AddOutcome::Broken) return false;
            if (added == FreeRowsFactor::AddOutcome::Rejected) {
                if (k == 0) return false;
                continue;
            }
            ws_.released.emplace_back(i, states[i]);
            states[i] = RowState::Free;
        }
        return true;
    }

    /// ws_.to_release: the most violated row of ws_.inf, then the others in ascending row order
    /// (as releasing every row frees them), or, where release_at_most is fewer, the
    /// release_at_most - 1 next by excess, in that order too.
    void choose_releases() {
        std::vector<int>& chosen = ws_.to_release;
        const int first = most_violated(ws_.inf);
        chosen.assign(1, first);
        for (int k = 0; k < ws_.inf.count(); ++k)
            if (k != first) chosen.push_back(k);
        const int cap = settings_.release_at_most;
        if (cap <= 0 || cap >= ws_.inf.count()) return;
        const auto by_excess = [&](int a, int b) { return ws_.inf.excess[a] > ws_.inf.excess[b]; };
        if (cap > 1) std::nth_element(chosen.begin() + 1, chosen.begin() + (cap - 1), chosen.end(), by_excess);
        chosen.resize(static_cast<std::size_t>(cap));
        std::sort(chosen.begin() + 1, chosen.end());
    }

    /// The first step after a release of several rows (active_set.h). If x* moves every released
    /// row strictly inwards: false, the face step as usual. Otherwise the bent step along d
    /// (true); or, should d be no descent direction through rounding, only the most violated row
    /// stays released and x* is solved again for the face step (false).
    bool bent_step(std::vector<RowState>& states, std::vector<double>& x) {
        if (!direction_without_outward_releases(x)) return false;
        const auto [slope, curvature] = along_direction();
        if (!(slope < 0) || !(curvature > 0)) {
            for (std::size_t k = 1; k < ws_.released.size(); ++k) retighten(ws_.released[k], states, x);
            ws_.target = x;
            factor_.solve(ws_.target);
            return false;
        }
        for (const auto& released : ws_.released)
            if (ws_.direction[released.first] == 0) retighten(released, states, x);
        for (int i : factor_.members()) ws_.target[i] = x[i] + ws_.direction[i];
        const double minimum = -slope / curvature;
        const double blocked = step_length(x, std::numeric_limits<double>::infinity());
        if (minimum < blocked) {
            for (int i : factor_.members()) x[i] += minimum * ws_.direction[i];
        } else {
            move(blocked, states, x);
        }
        return true;
    }

    /// d = x* - x on F, 0 on the released rows that x* does not move strictly inwards; true if
    /// there are any.
    bool direction_without_outward_releases(const std::vector<double>& x) {
        ws_.direction.assign(static_cast<std::size_t>(n_), 0.0);
        for (int i : factor_.members()) ws_.direction[i] = ws_.target[i] - x[i];
        bool outward = false;
        for (const auto& [row, was] : ws_.released) {
            const double p = ws_.direction[row];
            if (was == RowState::AtLo ? p > 0 : p < 0) continue;
            ws_.direction[row] = 0;
            outward = true;
        }
        return outward;
    }

    /// g'd and d'(A + shift I)d for q(x + t d) = q(x) + t g'd + t²/2 d'(A + shift I)d, g = w at x.
    /// x is the minimizer of the face before the release, where Eq. 6 makes g zero on that
    /// face's free rows (to the factor's accuracy, which the checks bound): g'd sums the released
    /// rows' terms, whose w was formed for Eq. 4, each negative (w of the wrong sign, d inwards).
    std::pair<double, double> along_direction() {
        double slope = 0;
        for (const auto& released : ws_.released) slope += ws_.it.w[released.first] * ws_.direction[released.first];
        return {slope, factor_.curvature(ws_.direction)};  // d lies in F, whose factor holds the released rows
    }

    /// A released row back to T at the bound it left.
    void retighten(const std::pair<int, RowState>& released, std::vector<RowState>& states, const std::vector<double>& x) {
        states[released.first] = released.second;
        factor_.remove(released.first, x[released.first]);
    }

    /// The ratio test: the largest alpha <= cap with x + alpha (x* - x) within the bounds.
    double step_length(const std::vector<double>& x, double cap) const {
        double alpha = cap;
        for (int i : factor_.members()) {
            const double p = ws_.target[i] - x[i];
            if (p < 0 && ws_.target[i] < lcp_.lo[i]) alpha = std::min(alpha, (lcp_.lo[i] - x[i]) / p);
            else if (p > 0 && ws_.target[i] > lcp_.hi[i]) alpha = std::min(alpha, (lcp_.hi[i] - x[i]) / p);
        }
        return alpha;
    }

    /// x += alpha (x* - x) on F; the rows that reach a bound join T there.
    void move(double alpha, std::vector<RowState>& states, std::vector<double>& x) {
        for (int i : factor_.members()) x[i] += alpha * (ws_.target[i] - x[i]);
        const int before = static_cast<int>(factor_.members().size());
        tighten_rows_on_bounds(states, x);
        if (static_cast<int>(factor_.members().size()) == before) tighten_nearest(states, x);
    }

    /// Free rows at or beyond a bound go to T at that bound (rounding in the step may leave the
    /// blocking row a hair inside: tighten_nearest catches that).
    void tighten_rows_on_bounds(std::vector<RowState>& states, std::vector<double>& x) {
        ws_.reached.clear();
        for (int i : factor_.members()) {
            if (lcp_.always_free[i]) continue;
            if (x[i] <= lcp_.lo[i]) ws_.reached.emplace_back(i, RowState::AtLo);
            else if (x[i] >= lcp_.hi[i]) ws_.reached.emplace_back(i, RowState::AtHi);
        }
        for (const auto& [row, to] : ws_.reached) tighten(row, to, states, x);
    }

    /// The free row closest to a bound in the direction it moves joins T: the blocking row.
    void tighten_nearest(std::vector<RowState>& states, std::vector<double>& x) {
        int row = -1;
        RowState to = RowState::Free;
        double least = 0;
        for (int i : factor_.members()) {
            const double p = ws_.target[i] - x[i];
            const double gap = p < 0 ? (x[i] - lcp_.lo[i]) / -p : p > 0 ? (lcp_.hi[i] - x[i]) / p : -1;
            if (gap < 0 || !std::isfinite(gap) || (row >= 0 && gap >= least)) continue;
            row = i;
            least = gap;
            to = p < 0 ? RowState::AtLo : RowState::AtHi;
        }
        if (row >= 0) tighten(row, to, states, x);
    }

    void tighten(int row, RowState to, std::vector<RowState>& states, std::vector<double>& x) {
        states[row] = to;
        x[row] = tight_value(lcp_, row, to);
        factor_.remove(row, x[row]);
    }

    LoopOutcome give_up(std::vector<RowState>& states, std::vector<double>& x, LoopOutcome outcome) const {
        states = ws_.entry_states;
        x = ws_.entry_x;
        return outcome;
    }

    const BoxedLcp& lcp_;
    const PivotSettings& settings_;
    PivotCounters& counters_;
    ActiveSetBuffers& ws_;
    FreeRowsFactor& factor_;
    const int n_;
    int unchecked_minima_ = 0;     ///< face minimizers since the updated factor was last checked
};

}  // namespace

bool active_set_applies(const BoxedLcp& lcp) {
    return !lcp.has_moving_bounds();
}

LoopOutcome active_set(const BoxedLcp& lcp, const PivotSettings& settings, std::vector<RowState>& states,
                       std::vector<double>& x, PivotCounters& counters, ActiveSetWorkspace& workspace,
                       FreeRowsFactor& factor, const EnvelopeFactor& seed) {
    return ActiveSet(lcp, settings, counters, workspace.contents(), factor).run(states, x, seed);
}

}  // namespace ode_bpp::pivoting
