#include "pivoting/small_island.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "linalg/dense_cholesky.h"
#include "ode_bpp/residuals.h"
#include "pivoting/classify_row.h"
#include "pivoting/friction_policy.h"
#include "pivoting/murty_rule.h"
#include "residuals.h"

namespace ode_bpp::pivoting {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

/// Polish rounds after convergence and the steps each may take, as in pivot_loop.cpp.
constexpr int kPolishRounds = 2;
constexpr int kPolishSteps = 6;

/// A(i, j) of the symmetric A from the lower triangle of the dense form.
double entry(const Problem& p, int i, int j) {
    return i >= j ? p.A[static_cast<std::ptrdiff_t>(i) * p.lda + j] : p.A[static_cast<std::ptrdiff_t>(j) * p.lda + i];
}

bool is_friction_row(const Problem& p, int i) { return p.findex != nullptr && p.findex[i] >= 0; }

/// Grows v to n entries and never shrinks it: the buffers are read by index below n only, and
/// islands of changing sizes would otherwise pay a zero fill at every growth.
template <typename T>
void at_least(std::vector<T>& v, std::size_t n) {
    if (v.size() < n) v.resize(n);
}

/// Eq. 6 densely: x_F = A_FF^-1 (b_F - A_FT x_T) for the free rows ws.free[0..nf) (original
/// order) with x_F = 0 on entry, A_FF factored afresh in ws.factor; false when A_FF is not
/// positive definite. x: n entries, in and out; ws.loaded[0..nl): the rows of x_T that are not 0,
/// ascending. Each row of A_FF is factored as soon as it is gathered, and the forward solve's
/// entry taken with it (linalg/dense_cholesky.h): one pass. always_inline, as classify_rows: the
/// plain steps and the active set both call it.
[[gnu::always_inline]] inline bool solve_free_rows(const Problem& p, int nf, int nl, SmallIslandBuffers& ws,
                                                   std::vector<double>& x) {
    const int n = p.n;
    const int* free = ws.free.data();
    const int* loaded = ws.loaded.data();
    double* a = ws.factor.data();
    double* y = ws.rhs.data();
    double* inverse_diagonal = ws.inverse_diagonal.data();
    for (int k = 0; k < nf; ++k) {
        const int i = free[k];
        const double* a_i = p.A + static_cast<std::ptrdiff_t>(i) * p.lda;
        double rhs = p.b[i];
        for (int l = 0; l < nl; ++l) rhs -= entry(p, i, loaded[l]) * x[loaded[l]];  // A_FT x_T
        y[k] = rhs;
        double* row = a + static_cast<std::ptrdiff_t>(k) * n;
        for (int l = 0; l < k; ++l) row[l] = a_i[free[l]];
        row[k] = a_i[i];
        if (!linalg::dense_cholesky_row(a, k, n, a_i[i], inverse_diagonal)) return false;
        linalg::dense_forward_entry(a, inverse_diagonal, k, n, y);
    }
    linalg::dense_backward_solve(a, inverse_diagonal, nf, n, y);
    for (int k = 0; k < nf; ++k) x[free[k]] = y[k];
    return true;
}

/// Júdice-Pires block step: every infeasible row changes set at once (Eq. 4).
void flip_all(const Infeasibility& inf, std::vector<RowState>& states) {
    for (int k = 0; k < inf.count(); ++k) states[inf.rows[k]] = inf.flip_to[k];
}

/// Block principal pivoting on the fixed bounds ws.lo, ws.hi (Alg. 1 with Eq. 4), one
/// refactorization of A_FF per step.
class SmallIsland {
public:
    SmallIsland(const Problem& p, const Options& o, SmallIslandBuffers& ws, Result& r) : p_(p), o_(o), ws_(ws), r_(r), n_(p.n) {
        at_least(ws_.factor, static_cast<std::size_t>(n_) * n_);
        for (auto* v : {&ws_.rhs, &ws_.inverse_diagonal, &ws_.w, &ws_.scale, &ws_.lo, &ws_.hi, &ws_.best_x, &ws_.target})
            at_least(*v, static_cast<std::size_t>(n_));
        at_least(ws_.free, static_cast<std::size_t>(n_));
        at_least(ws_.loaded, static_cast<std::size_t>(n_));
        at_least(ws_.unpinned, static_cast<std::size_t>(n_));
    }

    /// Frozen friction (Dantzig's semantics, as the driver's solve_frozen): friction rows held at
    /// 0 while the rest is solved, then bounds +-|mu x_normal| from those normals, kept fixed for a
    /// second solve that starts from `second` (friction_policy.h).
    bool solve(std::vector<RowState>& states, std::vector<double>& x, SecondStart second) {
        set_fixed_bounds();
        const bool friction = p_.findex != nullptr && std::any_of(p_.findex, p_.findex + n_, [](int f) { return f >= 0; });
        if (!friction) return converges(states, x);
        ws_.requested = states;
        unpinned_ = 0;
        for (int i = 0; i < n_; ++i) {
            if (is_friction_row(p_, i)) ws_.lo[i] = ws_.hi[i] = 0;
            else ws_.unpinned[unpinned_++] = i;
        }
        if (!converges(states, x)) return false;
        unpinned_ = n_;
        for (int i = 0; i < n_; ++i) {
            if (!is_friction_row(p_, i)) continue;
            std::tie(ws_.lo[i], ws_.hi[i]) = effective_bounds(p_, ConstStrided{x.data(), 1}, i);
            if (second == SecondStart::FrictionRowsRequested) states[i] = ws_.requested[i];
        }
        if (second == SecondStart::Requested) states = ws_.requested;
        return converges(states, x);
    }

private:
    /// Bounds of the rows that keep them: rows below nub unbounded, others as given.
    void set_fixed_bounds() {
        for (int i = 0; i < n_; ++i) {
            const bool unbounded = i < p_.nub;
            ws_.lo[i] = unbounded ? -kInf : p_.lo[i];
            ws_.hi[i] = unbounded ? kInf : p_.hi[i];
        }
    }

    /// One fixed-bound solve to convergence and its polish, within the pivot budget.
    bool converges(std::vector<RowState>& states, std::vector<double>& x) {
        const int budget = std::max(1, o_.max_pivots);
        int steps = 0;
        if (!pivot(states, x, budget, steps)) return false;
        polish(states, x, budget - steps);
        return true;
    }

    /// Rows that must be free are free, pinned rows tight, a tight state at an infinite bound
    /// free (as PivotLoop::normalize).
    void normalize(std::vector<RowState>& states) const {
        states.resize(static_cast<std::size_t>(n_), RowState::Free);
        for (int i = 0; i < n_; ++i) {
            RowState& s = states[i];
            const double lo = ws_.lo[i], hi = ws_.hi[i];
            if (s != RowState::AtLo && s != RowState::AtHi) s = RowState::Free;
            if (lo == hi) s = s == RowState::AtHi ? RowState::AtHi : RowState::AtLo;
            else if (s == RowState::AtLo && std::isinf(lo)) s = RowState::Free;
            else if (s == RowState::AtHi && std::isinf(hi)) s = RowState::Free;
        }
    }

    /// At most max_steps steps from states: block steps (Júdice-Pires: the count of infeasible rows
    /// must fall within small_island_murty_after steps, else Murty's single pivot on the largest
    /// infeasible index), and from Tuning::rescue_after steps on the active set, as the general
    /// driver's plain attempt hands over (fixed_bound_solve.h); true when an index set satisfies
    /// Eq. 4 in every row. steps: out, the steps taken.
    bool pivot(std::vector<RowState>& states, std::vector<double>& x, int max_steps, int& steps) {
        normalize(states);
        int least_count = n_ + 1;
        int block_steps_left = std::max(0, o_.tuning.small_island_murty_after);
        bool in_murty = false;
        best_count_ = n_ + 1;
        for (steps = 0; steps < max_steps;) {
            ++steps;
            if (!solve_step(states, x)) return false;
            const Infeasibility& inf = classify(states, x);
            if (inf.count() == 0) {
                orient_pinned_rows(states);
                return true;
            }
            remember_if_best(inf, states, x);  // Murty's phase and the active set start from it
            if (active_set_after(steps)) return by_active_set(states, x, max_steps, steps);
            if (inf.count() < least_count) {
                least_count = inf.count();
                block_steps_left = std::max(0, o_.tuning.small_island_murty_after);
                in_murty = false;
                flip_all(inf, states);
            } else if (block_steps_left > 0) {
                --block_steps_left;
                flip_all(inf, states);
            } else if (!in_murty) {
                in_murty = true;  // Murty's phase starts from the least infeasible set, as in pivot_loop.cpp
                states = ws_.best_states;
                flip_largest(ws_.best_inf, states);
            } else {
                flip_largest(inf, states);
            }
        }
        return false;
    }

    /// True when the plain steps are spent and the active set goes on (Tuning::rescue_after,
    /// Tuning::active_set; rescue_after 0: never).
    bool active_set_after(int steps) const {
        return o_.tuning.active_set && o_.tuning.rescue_after > 0 && steps >= o_.tuning.rescue_after;
    }

    /// The primal-feasible active-set method of active_set.h, densely: from the least infeasible
    /// iterate projected onto the bounds, x* = the face's minimizer (Eq. 6 with x_T fixed); a ratio
    /// test moves x towards it until the first free row meets a bound and joins T; at x* the tight
    /// row whose multiplier is most wrong (Eq. 4) leaves T, one at a time (Nocedal & Wright,
    /// Alg. 16.3; finite by their Thm. 16.5, A + CFM being SPD). Each step refactors A_FF. Where
    /// Murty's single pivots wander through the near null space of a sliding box's coplanar
    /// contacts (113 steps on a 12-row cannon island, docs/tuning.md) it finishes in a few dozen
    /// at most. Out of line: the plain steps' code stays as compact as before.
    [[gnu::noinline]] bool by_active_set(std::vector<RowState>& states, std::vector<double>& x, int max_steps,
                                         int& steps) {
        states = ws_.best_states;
        std::copy(ws_.best_x.begin(), ws_.best_x.begin() + n_, x.begin());
        project(states, x);
        while (steps < max_steps) {
            ++steps;
            ++r_.pivoting.murty_pivots;
            if (!solve_face(states, ws_.target)) return false;  // writes every entry of x*
            const Blocking block = step_length(x);
            if (block.row >= 0) {
                move(block, states, x);
                continue;
            }
            std::copy(ws_.target.begin(), ws_.target.begin() + n_, x.begin());
            refresh_w(x);
            const Infeasibility& inf = classify(states, x);
            if (inf.count() == 0) {
                orient_pinned_rows(states);
                return true;
            }
            states[inf.rows[most_violated(inf)]] = RowState::Free;  // tight: x* kept free rows within bounds
        }
        return false;
    }

    /// x onto [lo, hi]; a free row that lands on a bound is tight there, so that every free row
    /// is strictly inside its bounds.
    void project(std::vector<RowState>& states, std::vector<double>& x) const {
        for (int i = 0; i < n_; ++i) {
            if (states[i] != RowState::Free) {
                x[i] = bound(i, states[i]);
                continue;
            }
            x[i] = std::clamp(x[i], ws_.lo[i], ws_.hi[i]);
            if (x[i] == ws_.lo[i]) states[i] = RowState::AtLo;
            else if (x[i] == ws_.hi[i]) states[i] = RowState::AtHi;
        }
    }

    /// The ratio test along x* - x (x* in ws_.target): the first free row to reach a bound, and
    /// the fraction of the step that takes it there; row -1 when x* is within every bound.
    struct Blocking {
        int row = -1;
        RowState to = RowState::Free;
        double alpha = 1;
    };
    Blocking step_length(const std::vector<double>& x) const {
        Blocking b;
        for (int i = 0; i < n_; ++i) {
            const double target = ws_.target[i];
            if (target < ws_.lo[i] && target < x[i]) {
                const double alpha = (ws_.lo[i] - x[i]) / (target - x[i]);
                if (b.row < 0 || alpha < b.alpha) b = {i, RowState::AtLo, alpha};
            } else if (target > ws_.hi[i] && target > x[i]) {
                const double alpha = (ws_.hi[i] - x[i]) / (target - x[i]);
                if (b.row < 0 || alpha < b.alpha) b = {i, RowState::AtHi, alpha};
            }
        }
        return b;
    }

    /// x += alpha (x* - x) on the free rows; the blocking row, and any other the step takes onto a
    /// bound, joins T there.
    void move(const Blocking& b, std::vector<RowState>& states, std::vector<double>& x) const {
        const auto tighten = [&](int i, RowState to) {
            states[i] = to;
            x[i] = bound(i, to);
        };
        for (int i = 0; i < n_; ++i) {
            if (states[i] != RowState::Free) continue;
            x[i] += b.alpha * (ws_.target[i] - x[i]);
            if (x[i] <= ws_.lo[i]) tighten(i, RowState::AtLo);
            else if (x[i] >= ws_.hi[i]) tighten(i, RowState::AtHi);
        }
        tighten(b.row, b.to);
    }

    /// The bound a tight row sits at: lo for AtLo, hi for AtHi.
    double bound(int i, RowState tight) const { return tight == RowState::AtLo ? ws_.lo[i] : ws_.hi[i]; }

    /// Eq. 6 densely: x_T at its bounds, L_FF L_FF^T = A_FF, x_F = A_FF^-1 (b_F - A_FT x_T); then
    /// w = A x - b and the row scales. False when a Cholesky pivot breaks down.
    bool solve_step(const std::vector<RowState>& states, std::vector<double>& x) {
        if (!solve_face(states, x)) return false;
        refresh_w(x);
        return true;
    }

    /// x_T at its bounds and x_F = A_FF^-1 (b_F - A_FT x_T) (Eq. 6): the minimizer of
    /// 1/2 x'Ax - b'x on the face that fixes x_T. x: n entries, out. False when a Cholesky pivot
    /// breaks down. Counts one pivot step, a refactorization.
    [[gnu::always_inline]] bool solve_face(const std::vector<RowState>& states, std::vector<double>& x) {
        int nf = 0, nl = 0, tight = 0;
        for (int i = 0; i < n_; ++i) {
            if (states[i] == RowState::Free) {
                ws_.free[nf++] = i;
                x[i] = 0;
            } else {
                x[i] = bound(i, states[i]);
                if (x[i] != 0) ws_.loaded[nl++] = i;
                ++tight;
            }
        }
        ++r_.pivoting.pivots;
        ++r_.pivoting.refactor_steps;
        if (o_.record_steps) r_.pivoting.tight_per_step.push_back(tight);
        return nf == 0 || solve_free_rows(p_, nf, nl, ws_, x);
    }


    /// w = A x - b and the row scales |A||x| + |b| (residuals.h). In Frozen friction's first
    /// solve only on the rows that are not friction rows: those are pinned at 0, so Eq. 4 never
    /// reads their w, and their x adds nothing to the others'.
    void refresh_w(const std::vector<double>& x) {
        if (unpinned_ == n_) dense_residual_vectors(p_, ConstStrided{x.data(), 1}, ws_.w.data(), ws_.scale.data());
        else dense_residual_vectors_on(p_, ConstStrided{x.data(), 1}, ws_.unpinned.data(), unpinned_, ws_.w.data(), ws_.scale.data());
    }

    /// Eq. 4 row by row (classify_row.h).
    [[gnu::always_inline]] const Infeasibility& classify(const std::vector<RowState>& states, const std::vector<double>& x) {
        const auto diag = [this](int i) { return p_.A[static_cast<std::ptrdiff_t>(i) * p_.lda + i]; };
        classify_rows(n_, states, x, ws_.w, ws_.lo, ws_.hi, diag, ws_.scale, o_.tolerance, ws_.inf);
        return ws_.inf;
    }


    /// Murty's rule in the driver's orientation: only the infeasible row of largest index moves.
    void flip_largest(const Infeasibility& inf, std::vector<RowState>& states) {
        ++r_.pivoting.murty_pivots;
        states[inf.rows.back()] = inf.flip_to.back();
    }

    void remember_if_best(const Infeasibility& inf, const std::vector<RowState>& states, const std::vector<double>& x) {
        if (inf.count() > best_count_ || (inf.count() == best_count_ && inf.violation >= best_violation_)) return;
        best_count_ = inf.count();
        best_violation_ = inf.violation;
        ws_.best_states = states;
        std::copy(x.begin(), x.begin() + n_, ws_.best_x.begin());
        ws_.best_inf = inf;
    }

    /// As PivotLoop::polish: tight rows whose multiplier has the wrong sign beyond the factor's
    /// accuracy go free and the loop resumes; the new answer stands only if it converges too.
    void polish(std::vector<RowState>& states, std::vector<double>& x, int budget) {
        const double limit = std::max(0.1 * o_.tolerance, 100.0 * n_ * kEps);
        for (int round = 0; round < kPolishRounds && budget > 0; ++round) {
            const auto polished = [&](int i) {
                return ws_.lo[i] == ws_.hi[i] || wrong_sign(states[i], ws_.w[i]) <= limit * ws_.scale[i];
            };
            int i = 0;
            while (i < n_ && polished(i)) ++i;
            if (i == n_) return;
            ws_.trial = states;
            for (; i < n_; ++i)
                if (!polished(i)) ws_.trial[i] = RowState::Free;
            keep(states, x);
            int steps = 0;
            const bool converged = pivot(ws_.trial, x, std::min(kPolishSteps, budget), steps);
            budget -= steps;
            if (!converged) {
                restore_kept(states, x);
                return;
            }
            states.swap(ws_.trial);
        }
    }

    void keep(const std::vector<RowState>& states, const std::vector<double>& x) {
        ws_.kept_states = states;
        ws_.kept_x = x;
        ws_.kept_w = ws_.w;
        ws_.kept_scale = ws_.scale;
    }

    void restore_kept(std::vector<RowState>& states, std::vector<double>& x) {
        states = ws_.kept_states;
        x = ws_.kept_x;
        ws_.w = ws_.kept_w;
        ws_.scale = ws_.kept_scale;
    }

    /// A pinned row is at both bounds; report it at the one its w supports (w >= 0: at lo).
    void orient_pinned_rows(std::vector<RowState>& states) const {
        for (int i = 0; i < n_; ++i)
            if (ws_.lo[i] == ws_.hi[i]) states[i] = ws_.w[i] >= 0 ? RowState::AtLo : RowState::AtHi;
    }

    const Problem& p_;
    const Options& o_;
    SmallIslandBuffers& ws_;
    Result& r_;
    const int n_;
    int unpinned_ = n_;  ///< refresh_w's rows: all, or ws_.unpinned[0 .. unpinned_) in the first solve
    int best_count_ = 0;
    double best_violation_ = kInf;
};

}  // namespace

bool is_small_island(int n, const Options& options) {
    return options.method == Method::Bpp && options.friction == FrictionMode::Frozen && n >= 1 &&
           n <= options.tuning.dense_island_rows;
}

bool takes_small_island(const Problem& problem, const Options& options) {
    return is_small_island(problem.n, options) && problem.sparse == nullptr && problem.A != nullptr;
}

bool solve_small_island(const Problem& problem, const Options& options, const Start& start, SmallIslandBuffers& ws,
                        std::vector<double>& x, Result& r) {
    std::vector<RowState>& states = r.states;
    if (start.states.empty()) states.assign(static_cast<std::size_t>(problem.n), RowState::Free);
    else states.assign(start.states.begin(), start.states.end());
    x.assign(static_cast<std::size_t>(problem.n), 0.0);
    const SecondStart second = second_start(options, !start.states.empty());
    if (!SmallIsland(problem, options, ws, r).solve(states, x, second)) return false;
    // an answer that overflowed (finite but huge entries of A) is the general chain's to handle
    if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) return false;
    r.status = Status::Converged;
    r.tight = count_tight(states);
    // the loop's w and scale are those of x: every step refreshes them, a polish round that
    // fails restores them with x
    r.residuals = dense_residuals_from(problem, ConstStrided{x.data(), 1}, ws.w, ws.scale, &states);
    return true;
}

}  // namespace ode_bpp::pivoting
