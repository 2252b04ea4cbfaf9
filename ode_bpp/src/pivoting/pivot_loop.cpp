#include "pivoting/pivot_loop.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "pivoting/classify_row.h"
#include "pivoting/friction_link.h"
#include "pivoting/iterate.h"
#include "pivoting/kept_buffers_impl.h"
#include "pivoting/murty_rule.h"
#include "pivoting/visited_sets.h"
#include "pivoting/tuning.h"

namespace ode_bpp::pivoting {

namespace {

/// An answer set aside: the least infeasible iterate of a run, or a converged answer while the
/// polish tries another.
struct Snapshot {
    std::vector<RowState> states;
    std::vector<double> x;
    Iterate iterate;
    void take(const std::vector<RowState>& s, const std::vector<double>& xs, const Iterate& it) {
        states = s;
        x = xs;
        iterate = it;
    }
    void give(std::vector<RowState>& s, std::vector<double>& xs, Iterate& it) const {
        s = states;
        xs = x;
        it = iterate;
    }
    /// Capacity for n rows before any take: memory then follows the largest island met, not the
    /// first run that takes a path as rare as the polish (a 100,000-step soak of the crane saw its
    /// live heap step up by 17 kB at step 38,500, docs/soak.md). A no-op once the capacity is there.
    void reserve(int n) {
        const auto rows = static_cast<std::size_t>(n);
        states.reserve(rows);
        x.reserve(rows);
        for (std::vector<double>* v : {&iterate.w, &iterate.scale, &iterate.lo, &iterate.hi}) v->reserve(rows);
    }
};

/// The loop's vectors (LoopWorkspace), kept by the caller so that their capacity outlives one
/// run: on small islands allocating them afresh at every run cost a third of the solve
/// (callgrind, ODE's demo_motors). A run uses them from start to end.
struct Workspace {
    std::vector<char> tight;
    std::vector<double> Ax, x_free;         ///< A_FT x_T (on the free rows), x_F
    std::vector<int> columns;               ///< tight_columns_product's scratch
    Iterate current;
    Infeasibility inf;
    Snapshot best;              ///< the least infeasible iterate so far
    Infeasibility best_inf;     ///< its infeasible rows (where Murty's phase starts)
    std::vector<int> linked;    ///< linked friction rows of the current step
    VisitedSets visited;
    std::vector<RowState> trial;  ///< the index set a polish round starts from
    Snapshot kept;              ///< the converged answer while a polish round tries another
    /// The x of the latest run's answer, kept when the run converged on the unshifted problem:
    /// `current` holds its w and scales then (converged_iterate).
    std::vector<double> answer;
    bool answer_kept = false;
};

/// A friction row at a bound whose normal is free: its value moves with the normal.
bool is_linked(const BoxedLcp& lcp, int i, const std::vector<RowState>& states) {
    return lcp.has_moving_bounds() && lcp.friction_normal[i] >= 0 && states[lcp.friction_normal[i]] == RowState::Free;
}

/// Bounds -+mu |x_n| of row i from its normal's value.
void set_friction_bound(const BoxedLcp& lcp, int i, double normal_value, Iterate& it) {
    it.hi[i] = lcp.friction_mu[i] * std::abs(normal_value);
    it.lo[i] = -it.hi[i];
}

/// Moving bounds of the friction rows whose normal is tight, from the normal's bound value.
void bounds_from_tight_normals(const BoxedLcp& lcp, const std::vector<RowState>& states, Iterate& it) {
    for (int i = 0; i < lcp.n(); ++i) {
        const int normal = lcp.friction_normal[i];
        if (normal < 0 || states[normal] == RowState::Free) continue;
        set_friction_bound(lcp, i, states[normal] == RowState::AtLo ? it.lo[normal] : it.hi[normal], it);
    }
}

/// Moving bounds of the friction rows whose normal is free, from the step's x.
void bounds_from_free_normals(const BoxedLcp& lcp, const std::vector<char>& tight, const std::vector<double>& x, Iterate& it) {
    for (int i = 0; i < lcp.n(); ++i) {
        const int normal = lcp.friction_normal[i];
        if (normal >= 0 && !tight[normal]) set_friction_bound(lcp, i, x[normal], it);
    }
}

/// Rows that must be free are free; pinned rows (lo == hi) are tight; a tight state at an
/// infinite bound cannot hold and starts free, as does anything that is not a RowState.
void normalize(const BoxedLcp& lcp, const Iterate& it, std::vector<RowState>& states) {
    states.resize(static_cast<std::size_t>(lcp.n()), RowState::Free);
    for (int i = 0; i < lcp.n(); ++i) {
        RowState& s = states[i];
        if (lcp.always_free[i]) {
            s = RowState::Free;
            continue;
        }
        if (s != RowState::AtLo && s != RowState::AtHi) s = RowState::Free;  // also garbage values
        if (it.lo[i] == it.hi[i]) s = s == RowState::AtHi ? RowState::AtHi : RowState::AtLo;
        else if (s == RowState::AtLo && std::isinf(it.lo[i])) s = RowState::Free;
        else if (s == RowState::AtHi && std::isinf(it.hi[i])) s = RowState::Free;
    }
}

/// The least infeasible iterate, projected onto [lo, hi]; a free row pushed onto a bound is
/// recorded at that bound so that the index set describes x.
void give_projected(const Snapshot& best, std::vector<RowState>& states, std::vector<double>& x, Iterate& it) {
    best.give(states, x, it);
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x[i] < it.lo[i]) { x[i] = it.lo[i]; states[i] = RowState::AtLo; }
        else if (x[i] > it.hi[i]) { x[i] = it.hi[i]; states[i] = RowState::AtHi; }
    }
    orient_pinned_rows(it, states);
}

/// Frees the tight rows whose w has the wrong sign beyond limit (relative to the row scale);
/// true if any. Pinned rows stay.
bool free_wrong_sign_rows(const Iterate& it, double limit, std::vector<RowState>& states) {
    bool any = false;
    for (std::size_t i = 0; i < states.size(); ++i) {
        if (states[i] == RowState::Free || it.lo[i] == it.hi[i]) continue;  // a free row has no sign to be wrong
        if (wrong_sign(states[i], it.w[i]) > limit * it.scale[i]) {
            states[i] = RowState::Free;
            any = true;
        }
    }
    return any;
}

/// Júdice-Pires block step: every infeasible row changes set at once (Eq. 4).
void block_pivot(const Infeasibility& inf, std::vector<RowState>& states) {
    for (int k = 0; k < inf.count(); ++k) states[inf.rows[k]] = inf.flip_to[k];
}

class PivotLoop {
public:
    PivotLoop(const BoxedLcp& lcp, FreeSolver& solver, const PivotSettings& settings, PivotCounters& counters,
              Workspace& ws)
        : lcp_(lcp), solver_(solver), settings_(settings), counters_(counters), n_(lcp.n()), ws_(ws) {
        it().lo = lcp.lo;
        it().hi = lcp.hi;
        ws_.kept.reserve(n_);
        ws_.trial.reserve(static_cast<std::size_t>(n_));
    }

    LoopOutcome run(std::vector<RowState>& states, std::vector<double>& x) {
        ws_.answer_kept = false;
        normalize(lcp_, it(), states);
        const LoopOutcome outcome = pivot(states, x, settings_.max_pivots);
        if (outcome == LoopOutcome::Converged && settings_.polish && lcp_.shift == 0)
            polish(states, x, settings_.max_pivots - steps_taken_);
        if (outcome == LoopOutcome::Converged && lcp_.shift == 0 && settings_.answer == AnswerUse::Final) {  // w, scale of it() are x's
            complete_residual(lcp_, x, it());
            ws_.answer = x;
            ws_.answer_kept = true;
        }
        return outcome;
    }

private:
    Iterate& it() { return ws_.current; }
    const Iterate& it() const { return ws_.current; }

    /// The polish of a converged index set (docs/tuning.md): the classification tolerance lets a
    /// tight row keep a multiplier of the wrong sign up to tol * (|A||x| + |b|)_i, which where A is
    /// nearly singular admits answers far from the exact one (opposed friction at its bounds).
    /// Rows wrong beyond the factor's accuracy are freed and the loop resumes from there; its new
    /// answer is kept only if it converges, else the first one stands.
    void polish(std::vector<RowState>& states, std::vector<double>& x, int budget) {
        for (int round = 0; round < tuning::kPolishRounds && budget > 0; ++round) {
            ws_.trial = states;
            if (!free_wrong_sign_rows(it(), accuracy_limit(), ws_.trial)) return;
            ws_.kept.take(states, x, it());
            const LoopOutcome outcome = pivot(ws_.trial, x, std::min(tuning::kPolishSteps, budget));
            budget -= steps_taken_;
            if (outcome != LoopOutcome::Converged) {
                ws_.kept.give(states, x, it());
                return;
            }
            states.swap(ws_.trial);
        }
    }

    /// The pivoting loop proper, at most max_steps solves of Eq. 6 from `states`: block steps
    /// while the count of infeasible rows falls (or for murty_after steps without a new least),
    /// then Murty's single pivots from the least infeasible set until it falls again.
    LoopOutcome pivot(std::vector<RowState>& states, std::vector<double>& x, int max_steps) {
        int least_count = n_ + 1;        // Júdice-Pires: fewest infeasible rows seen so far
        int block_steps_left = settings_.murty_after;
        bool in_murty = false;
        int last_progress = 0;           // step of the latest new least count
        best_count_ = n_ + 1;
        best_violation_ = std::numeric_limits<double>::infinity();
        best_pending_ = false;
        ws_.visited.clear();
        steps_taken_ = 0;
        for (int step = 0; step < max_steps; ++step) {
            if (settings_.stall_after > 0 && !in_murty && ws_.visited.revisits(states)) return give_best(states, x, LoopOutcome::Stalled);
            ++steps_taken_;
            settle_best(x);
            if (!solve_step(states, x)) return LoopOutcome::Breakdown;
            const Infeasibility& inf = classify(states, x);
            remember_if_best(inf, states);
            if (inf.count() == 0) {
                orient_pinned_rows(it(), states);
                return LoopOutcome::Converged;
            }
            if (settings_.hand_over_above > 0 && inf.count() > settings_.hand_over_above)
                return give_best(states, x, LoopOutcome::MaxIterations);
            if (inf.count() < least_count) {
                least_count = inf.count();
                last_progress = step;
                block_steps_left = settings_.murty_after;
                in_murty = false;
                block_pivot(inf, states);
            } else if (settings_.stall_after > 0 && step - last_progress >= settings_.stall_after) {
                return give_best(states, x, LoopOutcome::Stalled);
            } else if (block_steps_left > 0) {
                --block_steps_left;
                block_pivot(inf, states);
            } else if (!in_murty) {
                // Murty's phase starts from the least infeasible index set seen, not from
                // wherever the unproductive block steps left it (fewer single pivots on
                // random and chain problems; termination is unaffected: each phase is
                // Murty's finite method and ends only below a count that never rises)
                in_murty = true;
                settle_best(x);
                states = ws_.best.states;
                murty_pivot(ws_.best_inf, states);
            } else {
                murty_pivot(inf, states);
            }
        }
        return give_best(states, x, LoopOutcome::MaxIterations);
    }

    /// One pivot step: x_T at its bounds (Alg. 1 lines 6-7), x_F from Eq. 6, then w (line 9).
    /// With moving friction bounds, linked rows (friction_link.h) are solved with x_F.
    bool solve_step(const std::vector<RowState>& states, std::vector<double>& x) {
        ws_.tight.assign(static_cast<std::size_t>(n_), 0);
        x.assign(static_cast<std::size_t>(n_), 0.0);
        if (lcp_.has_moving_bounds()) bounds_from_tight_normals(lcp_, states, it());
        ws_.linked.clear();
        int tight_count = 0;
        for (int i = 0; i < n_; ++i)
            if (states[i] != RowState::Free) {
                ws_.tight[i] = 1;
                ++tight_count;
                if (is_linked(lcp_, i, states)) ws_.linked.push_back(i);  // x_i = 0 until solved with x_F
                else x[i] = value_at(i, states[i]);
            }
        ++counters_.pivots;
        if (settings_.record_steps) counters_.tight_per_step.push_back(tight_count);
        if (!solve_free_rows(x)) return false;
        if (ws_.linked.empty()) return true;
        if (!solve_linked_rows(lcp_, solver_, ws_.linked, states, ws_.tight, x)) {
            // singular link: keep the linked rows at the previous iterate's bounds for this step
            for (int i : ws_.linked) x[i] = value_at(i, states[i]);
            ws_.linked.clear();
            if (!solve_free_rows(x)) return false;
        }
        bounds_from_free_normals(lcp_, ws_.tight, x, it());
        refresh_w(x);
        return true;
    }

    /// x_F from Eq. 6 with x_T as given in x (linked rows 0), with the loss-of-accuracy guard.
    bool solve_free_rows(std::vector<double>& x) {
        tight_columns_product(*lcp_.A, ws_.tight, x, ws_.columns, ws_.Ax);
        FactorOutcome outcome = solve_free(x, /*fresh=*/false);
        if (outcome == FactorOutcome::Breakdown) return false;
        if (outcome == FactorOutcome::Deleted && ws_.linked.empty() && free_residual(x) > accuracy_limit()) {
            // MuJoCo-style loss-of-accuracy guard: a deleted factor that misses Eq. 6 by more
            // than a fresh factor would is replaced by a refactorization for this step.
            ++counters_.accuracy_refactors;
            outcome = solve_free(x, /*fresh=*/true);
            if (outcome == FactorOutcome::Breakdown) return false;
        }
        (outcome == FactorOutcome::Deleted ? counters_.downdate_steps : counters_.refactor_steps) += 1;
        return true;
    }

    /// Solves for x_F with the right-hand side b_F - A_FT x_T (A_FT x_T in Ax), then refreshes w
    /// and the scales.
    FactorOutcome solve_free(std::vector<double>& x, bool fresh) {
        ws_.x_free.resize(static_cast<std::size_t>(n_));  // the tight rows' entries: ignored by the strategy
        for (int i = 0; i < n_; ++i) ws_.x_free[i] = lcp_.b[i] - ws_.Ax[i];
        const FactorOutcome outcome = solver_.solve_free(ws_.tight, ws_.x_free, fresh);
        if (outcome == FactorOutcome::Breakdown) return outcome;
        for (int i = 0; i < n_; ++i)
            if (!ws_.tight[i]) x[i] = ws_.x_free[i];
        refresh_w(x);
        return outcome;
    }

    /// w and the scales: on every row at a run's first step, which with a warm start is most
    /// often its last, so that the answer needs no second pass; on the rows Eq. 4 reads only
    /// (refresh_bounded_residual) at the later ones, and at every step of a run whose answer is
    /// not read whole (AnswerUse::Intermediate).
    void refresh_w(const std::vector<double>& x) {
        if (steps_taken_ <= 1 && settings_.answer == AnswerUse::Final) refresh_residual(lcp_, x, it());
        else refresh_bounded_residual(lcp_, x, it());
    }

    double value_at(int i, RowState s) const { return s == RowState::AtLo ? it().lo[i] : it().hi[i]; }

    /// Eq. 6's backward error at x, the step's iterate, over every free row.
    double free_residual(const std::vector<double>& x) {
        complete_residual(lcp_, x, it());
        return pivoting::free_residual(it(), ws_.tight);
    }
    double accuracy_limit() const { return pivoting::accuracy_limit(settings_.tolerance, n_); }

    /// Eq. 4 row by row (classify_row.h).
    const Infeasibility& classify(const std::vector<RowState>& states, const std::vector<double>& x) {
        classify_iterate(lcp_, it(), states, x, settings_.tolerance, ws_.inf);
        return ws_.inf;
    }

    /// Murty's single pivot (murty_rule.h).
    void murty_pivot(const Infeasibility& inf, std::vector<RowState>& states) {
        ++counters_.murty_pivots;
        const int chosen = murty_choice(lcp_, inf);
        states[inf.rows[chosen]] = inf.flip_to[chosen];
    }

    /// Marks the step's iterate as the least infeasible so far. Only its index set is copied
    /// now (the pivot changes it next); x, it() and inf stay as they are until the next step
    /// overwrites them, and are copied then (settle_best), or never when the loop stops here.
    void remember_if_best(const Infeasibility& inf, const std::vector<RowState>& states) {
        if (inf.count() > best_count_ || (inf.count() == best_count_ && inf.violation >= best_violation_)) return;
        best_count_ = inf.count();
        best_violation_ = inf.violation;
        ws_.best.states = states;
        best_pending_ = true;
    }

    /// Completes the snapshot that remember_if_best began, from the step's x, it() and inf,
    /// which must be unchanged since. w and the scales are swapped in (the next step rewrites
    /// the rows it reads, and the rest are marked stale by it); the bounds are copied (moving
    /// bounds change only some).
    void settle_best(const std::vector<double>& x) {
        if (!best_pending_) return;
        best_pending_ = false;
        Iterate& kept = ws_.best.iterate;
        ws_.best.x = x;
        kept.w.swap(it().w);
        kept.scale.swap(it().scale);
        kept.complete = it().complete;
        kept.lo = it().lo;
        kept.hi = it().hi;
        ws_.best_inf = ws_.inf;
    }

    LoopOutcome give_best(std::vector<RowState>& states, std::vector<double>& x, LoopOutcome outcome) {
        settle_best(x);
        give_projected(ws_.best, states, x, it());
        return outcome;
    }

    const BoxedLcp& lcp_;
    FreeSolver& solver_;
    const PivotSettings& settings_;
    PivotCounters& counters_;
    const int n_;
    Workspace& ws_;
    int steps_taken_ = 0;  ///< solves of Eq. 6 made by the latest pivot()
    int best_count_ = 0;
    bool best_pending_ = false;  ///< ws_.best holds only the states of the current step's iterate (settle_best)
    double best_violation_ = std::numeric_limits<double>::infinity();
};

}  // namespace

struct LoopBuffers {
    Workspace loop;
};
template class KeptBuffers<LoopBuffers>;

LoopOutcome pivot_fixed_bounds(const BoxedLcp& lcp, FreeSolver& solver, const PivotSettings& settings,
                               std::vector<RowState>& states, std::vector<double>& x, PivotCounters& counters,
                               LoopWorkspace& workspace) {
    return PivotLoop(lcp, solver, settings, counters, workspace.contents().loop).run(states, x);
}

const Iterate* converged_iterate(LoopWorkspace& workspace, const std::vector<double>& x) {
    const Workspace& ws = workspace.contents().loop;
    const bool same = ws.answer_kept && ws.answer.size() == x.size() &&
                      std::memcmp(ws.answer.data(), x.data(), x.size() * sizeof(double)) == 0;
    return same ? &ws.current : nullptr;
}

LoopOutcome pivot_fixed_bounds(const BoxedLcp& lcp, FreeSolver& solver, const PivotSettings& settings,
                               std::vector<RowState>& states, std::vector<double>& x, PivotCounters& counters) {
    LoopWorkspace workspace;
    return pivot_fixed_bounds(lcp, solver, settings, states, x, counters, workspace);
}

}  // namespace ode_bpp::pivoting
