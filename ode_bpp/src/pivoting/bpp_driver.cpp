#include "pivoting/bpp_driver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "ordering/order_rows.h"
#include "pivoting/boxed_lcp.h"
#include "pivoting/free_solver.h"
#include "pivoting/friction_lcp.h"
#include "pivoting/friction_update.h"
#include "pivoting/ordering_choice.h"
#include "pivoting/pivot_loop.h"
#include "linalg/symmetric_rows.h"

namespace ode_bpp::pivoting {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Regularize-on-breakdown ladder, relative to max_i A_ii (an upper bound of max |A_ij| for SPD A).
constexpr double kFirstShift = 1e-12;
constexpr double kShiftGrowth = 100;
constexpr double kLastShift = 1e-6;
/// Continuation: delta_k = kContinuationStart * max diag * kContinuationSpan^(k / stages).
constexpr double kContinuationStart = 1e-4;
constexpr double kContinuationSpan = 1e-8;

/// Rescue continuation (solve_fixed), deltas relative to max_i A_ii. On the captured ODE frames
/// (winch, forklift, parkour at CFM 1e-10 and 6e-7) block pivoting from a warm start converged
/// on A + 1e-4 max diag I in 3-8 steps, while the unregularized problems cycled between index sets
/// whose A_FF hold nearly redundant contact rows (x jumping by 1e4-1e6 from step to step).
constexpr double kRescueStart = 1e-4;
/// Not even the first stage converged: more regularization, x10 per try, up to this.
constexpr double kRescueCeiling = 0.1;
/// delta_{k+1} = delta_k * ratio. A stage that converges in one step squares the ratio (down to
/// kRescueMinRatio); one that stalls retries from the last converged delta with sqrt(ratio), and
/// the rescue gives up once the ratio passes kRescueMaxRatio (the index set would not follow).
constexpr double kRescueFirstRatio = 0.1;
constexpr double kRescueMinRatio = 1e-6;
constexpr double kRescueMaxRatio = 0.9;
/// Below this delta the next stage is the target itself: on the measured frames no stage under
/// 1e-8 max diag changed the index set any more (each converged in its first step).
constexpr double kRescueFloor = 1e-12;
/// A stage has stalled when its least count of infeasible rows has not fallen for murty_after +
/// kMurtyPatience steps: Murty's phase gets that many single pivots. A small delta step changes
/// few rows, so a stage either converges in a few steps or has met the cycling of the plain
/// problem (measured: converged stages took 1-8 steps; murty_after 3 with this patience left
/// fewer winch solves over budget than murty_after 5 or 10). It also stalls at once when its
/// block steps revisit an index set (PivotSettings::stall_after): stalled stages had taken 6-30
/// steps; stopping them at the revisit saved 0-7 % of all pivots inside ODE and let the winch's
/// last frames over budget converge.
constexpr int kMurtyPatience = 2;

/// A linked solve (consistent friction) may take this many times Options::max_pivots. Before the
/// Lemke stage, 3 (300 steps) finished 97.8 % of the winch frames at compliance 1e-10 against
/// 96.8 % with 1; with Lemke behind it every frame finishes either way, and 1 halved the winch's
/// total solve time (57 s -> 30 s for 1,200 frames, slowest frame 496 -> 145 ms). Less is slower
/// again (40 and 20 linked steps: +19 % and +52 %), as Lemke (~27 ms there) then runs on more
/// frames.
constexpr int kLinkedBudgetFactor = 1;

/// Lemke's method (lemke.h) gets this many complementary pivots per LCP variable; it usually
/// needs fewer than one each.
constexpr int kLemkePivotsPerVariable = 10;
/// Lemke paths tried, each with another covering vector, when one ends on a ray (lemke.h). An
/// attempt runs only after the previous one ended on a ray, at about one Lemke solve each (~30 ms
/// on the winch). Measured: on the bench corpus of 2026-11-23 (2,995 cold islands) three vectors
/// left one winch island (338 LCP variables) on a ray, where the fourth finished it.
constexpr int kLemkeAttempts = 5;
/// Largest friction LCP the Lemke stage takes on: dense, N^2 doubles and O(N^2) per pivot over
/// ~N pivots. The winch's reach 604 variables (27 ms median); 1,000 keeps the worst case near a
/// tenth of a second instead of seconds on islands of thousands of rows.
constexpr int kLemkeMaxVariables = 1000;
/// Largest island the Lemke stage takes on: it forms A densely and factors its unbounded block
/// (n^2 doubles, O(n^3)); 1,500 rows is 18 MB and a fraction of a second.
constexpr int kLemkeMaxRows = 1500;

bool is_identity(const std::vector<int>& perm) {
    for (std::size_t i = 0; i < perm.size(); ++i)
        if (perm[i] != static_cast<int>(i)) return false;
    return true;
}

/// The driver's per-solve vectors, kept per thread so that their capacity outlives one solve
/// (allocation dominated small islands; see pivot_loop.cpp). One solve at a time per thread:
/// nothing a solve calls starts another.
struct DriverWorkspace {
    BoxedLcp lcp;
    std::vector<int> perm;
    linalg::SymmetricRows permuted_A;
    std::vector<int> friction_rows, normal_of;
    std::vector<double> mu;
};

[[gnu::noinline]] DriverWorkspace& thread_workspace() {
    thread_local DriverWorkspace workspace;
    DriverWorkspace& w = workspace;
    w.lcp.A = nullptr;
    w.lcp.shift = 0;
    w.lcp.friction_normal.clear();
    w.lcp.friction_mu.clear();
    w.friction_rows.clear();
    w.normal_of.clear();
    w.mu.clear();
    return w;
}

class BppDriver {
public:
    BppDriver(const Problem& p, const linalg::SymmetricRows& A, const Options& o) : p_(p), A_original_(A), o_(o) {
        settings_.max_pivots = std::max(1, o.max_pivots);
        settings_.murty_after = std::max(0, o.murty_after);
        settings_.tolerance = o.tolerance;
        settings_.record_steps = o.record_steps;
    }

    Result run(std::vector<double>& x_out) {
        const Method strategy = strategy_method();
        const bool given = (strategy == Method::Bpp || strategy == Method::BppSky) &&
                           ordering::is_permutation(o_.ordering, p_.n);
        static const std::vector<RowState> kNoHint;
        perm_ = given ? o_.ordering
                      : choose_ordering(strategy, p_, A_original_, o_.order_tight_last ? o_.warm_start : kNoHint);
        if (!is_identity(perm_)) {
            A_original_.permute_into(perm_, permuted_A_);
            Ap_ = &permuted_A_;
        }
        solver_ = make_free_solver(strategy, *Ap_);
        Result r;
        if (!solver_) {
            x_out.assign(static_cast<std::size_t>(p_.n), 0.0);
            r.status = Status::InvalidInput;
            r.message = std::string("method ") + to_string(o_.method) + " is not a BPP method or is not available";
            return r;
        }
        max_diag_ = Ap_->max_diag();
        build_permuted_problem();
        std::vector<RowState> states = permuted_warm_start();
        std::vector<double> x;
        const bool ok = o_.friction == FrictionMode::Consistent ? solve_consistent(states, x) : solve_frozen(states, x);
        return finish(ok, states, x, x_out);
    }

private:
    // ---- set-up, permuted space -------------------------------------------------------
    /// The factor strategy: the method's own, except Bpp on small islands (dense_island_rows).
    Method strategy_method() const {
        return o_.method == Method::Bpp && p_.n <= o_.dense_island_rows ? Method::BppChol : o_.method;
    }

    void build_permuted_problem() {
        const int n = p_.n;
        const std::vector<int> to_new = linalg::inverse_permutation(perm_);
        lcp_.A = Ap_;
        lcp_.b.resize(n);
        lcp_.lo.resize(n);
        lcp_.hi.resize(n);
        lcp_.always_free.assign(static_cast<std::size_t>(n), 0);
        lcp_.murty_rank = perm_;  // the caller's order: every strategy makes the same pivots
        for (int i = 0; i < n; ++i) {
            const int old = perm_[i];
            lcp_.b[i] = p_.b[old];
            const bool unbounded = old < p_.nub;
            lcp_.lo[i] = unbounded ? -kInf : p_.lo[old];
            lcp_.hi[i] = unbounded ? kInf : p_.hi[old];
            lcp_.always_free[i] = lcp_.lo[i] == -kInf && lcp_.hi[i] == kInf;
            if (p_.findex != nullptr && p_.findex[old] >= 0) {
                friction_rows_.push_back(i);
                normal_of_.push_back(to_new[p_.findex[old]]);
                mu_.push_back(p_.hi[old]);
                lcp_.always_free[i] = 0;
            }
        }
    }

    std::vector<RowState> permuted_warm_start() const {
        std::vector<RowState> states(static_cast<std::size_t>(p_.n), RowState::Free);
        if (!o_.warm_start.empty())
            for (int i = 0; i < p_.n; ++i) states[i] = o_.warm_start[perm_[i]];
        return states;
    }

    // ---- friction policies -------------------------------------------------------------
    /// Dantzig's semantics (ODE lcp.cpp): every friction row fixed at 0 while the others are
    /// solved, then bounds +-|mu x_normal| from those normals, kept fixed for a second solve.
    bool solve_frozen(std::vector<RowState>& states, std::vector<double>& x) {
        if (friction_rows_.empty()) return solve_fixed(states, x);
        const std::vector<RowState> requested = states;
        set_friction_bounds(std::vector<double>(friction_rows_.size(), 0.0));
        if (!solve_fixed(states, x)) return false;
        set_friction_bounds(friction_targets(x));
        for (int i : friction_rows_) states[i] = requested[i];
        return solve_fixed(states, x);
    }

    /// Consistent friction. With a warm start, first a linked solve straight from it
    /// (Options::link_friction, friction_link.h): friction bounds move with the normals inside
    /// every pivot step, the linked rows solved exactly with the free ones. Where that runs out of
    /// budget, Lemke's method on the friction LCP (Options::lemke_friction, friction_lcp.h),
    /// whose answer a linked solve certifies. Without a warm start, or where Lemke cannot run, the
    /// Frozen answer and a linked solve from it; then the Lemke stage (once per solve); then
    /// damped, Anderson-accelerated outer rounds of fixed-bound solves (FrictionBoundUpdate) from
    /// the best iterate. Those converge only while the map from bounds to normals contracts,
    /// which the capstan effect of a chain on a drum breaks. Done when every row is consistent
    /// with the bound its own normal implies (friction_consistent), so the answer solves the MLCP
    /// with bounds from its own normals.
    /// Measured on the winch at compliance 1e-10 (1,200 ODE frames): outer rounds only 81.8 %
    /// consistent; + linked solve from the Frozen answer 95-96 %; + outer rounds continuing from
    /// its best iterate rather than the Frozen answer 96.3 %; + linked solve from the warm start
    /// 96.8 %; + a linked budget of 3 x max_pivots 97.8 %; + the Lemke stage 100 %.
    bool solve_consistent(std::vector<RowState>& states, std::vector<double>& x) {
        if (o_.link_friction && !o_.warm_start.empty() && !friction_rows_.empty()) {
            const std::vector<RowState> warm = states;
            set_friction_bounds(mu_);  // placeholders: every step sets them from the normals first
            if (linked_solve_finishes(states, x, /*from_answer=*/false)) return true;
            if (breakdown_) return false;
            states = warm;
            if (lemke_finishes(states, x)) return true;
            if (breakdown_) return false;
        }
        if (!solve_frozen(states, x)) return false;
        if (friction_rows_.empty()) return true;
        if (o_.link_friction) {
            if (linked_solve_finishes(states, x, /*from_answer=*/true)) return true;
            if (breakdown_) return false;
            if (lemke_finishes(states, x)) return true;
            if (breakdown_) return false;
            // the outer rounds go on from the linked solve's least infeasible iterate (96.3 %
            // against 92 % from the Frozen answer) and re-solve with its bounds fixed first: that
            // iterate may be consistent in its friction but not yet a solution of the other rows
            set_friction_bounds(friction_targets(x));
            ++friction_rounds_;
            if (!solve_fixed(states, x)) return false;
        }
        const double d = o_.friction_damping > 0 && o_.friction_damping <= 1 ? o_.friction_damping : 1.0;
        FrictionBoundUpdate update(d);
        for (;;) {
            const std::vector<double> target = friction_targets(x);
            if (friction_consistent(target, states, x)) return true;
            if (friction_rounds_ >= o_.max_friction_rounds) {
                friction_inconsistent_ = true;
                return true;
            }
            set_friction_bounds(update.next(current_friction_bounds(), target));
            ++friction_rounds_;
            if (!solve_fixed(states, x)) return false;
        }
    }

    /// A linked solve (moving friction bounds, BoxedLcp::friction_normal) from states, with
    /// kLinkedBudgetFactor times the pivot budget. from_answer: start from the bounds mu |x_n| of
    /// the answer in x (else from the bounds already set). True when it converged to a consistent
    /// answer (which clears an earlier stage's spent budget: the answer is certified); false otherwise (breakdown_ set on a Cholesky breakdown), leaving its least
    /// infeasible iterate in states and x and the budget flag as it was.
    bool linked_solve_finishes(std::vector<RowState>& states, std::vector<double>& x, bool from_answer) {
        if (from_answer) set_friction_bounds(friction_targets(x));
        lcp_.friction_normal.assign(static_cast<std::size_t>(p_.n), -1);
        lcp_.friction_mu.assign(static_cast<std::size_t>(p_.n), 0.0);
        for (std::size_t k = 0; k < friction_rows_.size(); ++k)
            if (std::isfinite(mu_[k])) {
                lcp_.friction_normal[friction_rows_[k]] = normal_of_[k];
                lcp_.friction_mu[friction_rows_[k]] = std::abs(mu_[k]);
            }
        ++counters_.linked_solves;
        const bool exhausted_before = budget_exhausted_;
        const PivotSettings plain = settings_;
        settings_.max_pivots = kLinkedBudgetFactor * plain.max_pivots;
        breakdown_ = !solve_fixed(states, x);
        settings_ = plain;
        lcp_.friction_normal.clear();
        lcp_.friction_mu.clear();
        if (breakdown_) return false;
        if (last_fixed_converged_ && friction_consistent(friction_targets(x), states, x)) {
            budget_exhausted_ = false;  // a certified answer: earlier stages' budgets no longer matter
            return true;
        }
        budget_exhausted_ = exhausted_before;
        return false;
    }

    /// Lemke's method on the friction LCP (friction_lcp.h: a copositive LCP, which Lemke solves
    /// where block pivoting with moving bounds cycles), then a linked solve from the index set of
    /// its answer, which certifies that answer to the loop's own tolerance (usually in one step).
    /// True when that linked solve converged consistent; otherwise states and x are left as they
    /// came in.
    bool lemke_finishes(std::vector<RowState>& states, std::vector<double>& x) {
        if (lemke_tried_ || !o_.lemke_friction) return false;
        lemke_tried_ = true;
        if (p_.n > kLemkeMaxRows || lemke_variables_at_most() > kLemkeMaxVariables) {
            lemke_note_ = "Lemke stage skipped: the island is too large for a dense LCP";
            return false;
        }
        std::string why;
        const std::optional<FrictionLcp> lcp = FrictionLcp::build(lcp_, {friction_rows_, normal_of_, mu_}, why);
        if (!lcp) {
            lemke_note_ = "Lemke stage skipped: " + why;
            return false;
        }
        const int size = static_cast<int>(lcp->q().size());
        LemkeSolution s;
        for (int attempt = 0; attempt < kLemkeAttempts && s.outcome != LemkeOutcome::Solved; ++attempt) {
            s = solve_lemke(lcp->M(), lcp->q(), spread_covering_vector(size, attempt),
                            kLemkePivotsPerVariable * size + 10);
            lemke_pivots_ += s.pivots;
        }
        if (s.outcome != LemkeOutcome::Solved) {
            lemke_note_ = s.outcome == LemkeOutcome::RayTermination ? "Lemke stage ended on a ray"
                                                                     : "Lemke stage ran out of pivots";
            return false;
        }
        std::vector<RowState> lemke_states;
        std::vector<double> lemke_x;
        lcp->recover(s, lemke_x, lemke_states);
        if (!std::all_of(lemke_x.begin(), lemke_x.end(), [](double v) { return std::isfinite(v); })) {
            lemke_note_ = "Lemke's answer was not finite";
            return false;
        }
        if (!linked_solve_finishes(lemke_states, lemke_x, /*from_answer=*/true)) {
            if (!breakdown_) lemke_note_ = "Lemke's answer did not pass the linked solve";
            return false;
        }
        states = lemke_states;
        x = lemke_x;
        return true;
    }

    /// An upper bound of the friction LCP's size (friction_lcp.h): 3 variables per friction row,
    /// 2 per other row bounded on both sides, 1 per one-sided row.
    int lemke_variables_at_most() const {
        int count = static_cast<int>(friction_rows_.size());  // + 2 each below: their bounds are finite
        for (int i = 0; i < p_.n; ++i)
            if (!lcp_.always_free[i]) count += std::isfinite(lcp_.lo[i]) && std::isfinite(lcp_.hi[i]) ? 2 : 1;
        return count;
    }

    std::vector<double> current_friction_bounds() const {
        std::vector<double> bound(friction_rows_.size());
        for (std::size_t k = 0; k < bound.size(); ++k) bound[k] = lcp_.hi[friction_rows_[k]];
        return bound;
    }

    /// mu_k |x_normal(k)|, 0 when the normal is 0 (ODE's rule, keeps mu = inf defined).
    std::vector<double> friction_targets(const std::vector<double>& x) const {
        std::vector<double> target(friction_rows_.size());
        for (std::size_t k = 0; k < target.size(); ++k) {
            const double normal = x[normal_of_[k]];
            target[k] = normal == 0 ? 0.0 : std::abs(mu_[k] * normal);
        }
        return target;
    }

    void set_friction_bounds(const std::vector<double>& bound) {
        for (std::size_t k = 0; k < bound.size(); ++k) {
            lcp_.hi[friction_rows_[k]] = bound[k];
            lcp_.lo[friction_rows_[k]] = -bound[k];
        }
    }

    /// Every friction row consistent with the bound its own normal implies, t_k = mu_k |x_n|:
    /// a row at a bound needs |x_k| (its bound) within tolerance of t_k; a free row only needs
    /// |x_k| <= t_k, as its bound does not enter x (Eq. 4 classifies it free either way). The
    /// tolerance is the larger of the row's own x-tolerance tol (|A||x| + |b|)_i / A_ii and |mu|
    /// times its normal's, since t_k is known only to within the latter (a friction row at a small
    /// bound has a small scale of its own, below the rounding of a large normal impulse).
    bool friction_consistent(const std::vector<double>& target, const std::vector<RowState>& states,
                             const std::vector<double>& x) const {
        std::vector<double> scale;
        Ap_->abs_multiply(x, lcp_.shift, scale);
        const auto x_tolerance = [&](int i) {
            return o_.tolerance * (scale[i] + std::abs(lcp_.b[i])) / (Ap_->diag(i) + lcp_.shift);
        };
        for (std::size_t k = 0; k < target.size(); ++k) {
            const int i = friction_rows_[k];
            const double normal_tolerance = std::isfinite(mu_[k]) ? std::abs(mu_[k]) * x_tolerance(normal_of_[k]) : 0.0;
            if (inconsistency(k, target, states, x) > std::max(x_tolerance(i), normal_tolerance)) return false;
        }
        return true;
    }

    /// Row k's distance from consistency (see friction_consistent).
    double inconsistency(std::size_t k, const std::vector<double>& target, const std::vector<RowState>& states,
                         const std::vector<double>& x) const {
        const int i = friction_rows_[k];
        if (states[i] == RowState::Free) return std::max(0.0, std::abs(x[i]) - target[k]);
        return std::abs(std::abs(x[i]) - target[k]);  // x_i sits at its bound: that bound must be t_k
    }

    // ---- one fixed-bound solve: plain attempt, rescue, regularize on breakdown ------------
    /// False only when even the largest regularization breaks down (NotSpd).
    bool solve_fixed(std::vector<RowState>& states, std::vector<double>& x) {
        const std::vector<RowState> start = states;
        if (!continuation_done_) run_continuation(states, x);
        for (;;) {
            if (prepare(shift_)) {
                const LoopOutcome outcome = solve_at_target(start, states, x);
                last_fixed_converged_ = outcome == LoopOutcome::Converged;
                if (outcome == LoopOutcome::MaxIterations) budget_exhausted_ = true;
                if (outcome != LoopOutcome::Breakdown) return true;
            }
            if (!raise_shift()) return false;
            states = start;
        }
    }

    /// One fixed-bound solve on A + shift_ I (prepared) within settings_.max_pivots steps: the
    /// plain loop gets Options::rescue_after steps; if it has not converged by then, the rescue
    /// continuation starts afresh from `start` (the warm start) with the rest of the budget, and
    /// should it give up, the plain loop resumes from its least infeasible index set.
    /// Returns Converged, MaxIterations or Breakdown.
    LoopOutcome solve_at_target(const std::vector<RowState>& start, std::vector<RowState>& states,
                                std::vector<double>& x) {
        const int first = counters_.pivots;
        const auto left = [&] { return settings_.max_pivots - (counters_.pivots - first); };
        const bool rescue_allowed = o_.rescue_after > 0;
        PivotSettings plain = settings_;
        if (rescue_allowed) plain.max_pivots = std::min(settings_.max_pivots, o_.rescue_after);
        LoopOutcome outcome = pivot_fixed_bounds(lcp_, *solver_, plain, states, x, counters_);
        if (outcome != LoopOutcome::MaxIterations || !rescue_allowed || left() <= 0) return outcome;
        outcome = rescue(start, states, x, left());
        if (outcome != LoopOutcome::Stalled) return outcome;
        if (!prepare(shift_)) return LoopOutcome::Breakdown;
        if (left() <= 0) return LoopOutcome::MaxIterations;
        PivotSettings rest = settings_;
        rest.max_pivots = left();
        return pivot_fixed_bounds(lcp_, *solver_, rest, states, x, counters_);
    }

    /// Rescue continuation (docs/maths.md: what makes BPP converge inside ODE): solves with A + delta I,
    /// delta falling from kRescueStart * max diag to the target shift_, the first stage warm-started
    /// from `start`, every later one from the last converged stage's index set, with adaptive
    /// steps (constants above). Nearly redundant contact rows make A_FF nearly singular at
    /// the target, so block pivots there swing x wildly; A + delta I bounds that swing, and
    /// delta shrinks only as fast as the index set can follow. At most `budget` steps.
    /// Returns Converged (states, x: the answer on A + shift_ I), Breakdown, or Stalled when it
    /// gives up, leaving states and x as they came in and the solver prepared for another delta.
    LoopOutcome rescue(const std::vector<RowState>& start, std::vector<RowState>& states, std::vector<double>& x,
                       int budget) {
        const std::vector<RowState> entry_states = states;
        const std::vector<double> entry_x = x;
        const int first = counters_.pivots;
        PivotSettings stage = settings_;
        const int no_stall = 0;
        stage.stall_after = settings_.murty_after > std::numeric_limits<int>::max() - kMurtyPatience
                                ? no_stall
                                : settings_.murty_after + kMurtyPatience;
        std::vector<RowState> accepted = start, trial;
        double delta = std::max(shift_, kRescueStart * max_diag_);
        double accepted_delta = -1;  // none yet
        double ratio = kRescueFirstRatio;
        while (counters_.pivots - first < budget) {
            if (!prepare(delta)) return LoopOutcome::Breakdown;
            stage.max_pivots = budget - (counters_.pivots - first);
            trial = accepted;
            const int before = counters_.pivots;
            const LoopOutcome outcome = pivot_fixed_bounds(lcp_, *solver_, stage, trial, x, counters_);
            if (outcome == LoopOutcome::Breakdown) return outcome;
            if (outcome == LoopOutcome::Converged) {
                accepted = trial;
                if (delta == shift_) {
                    states = accepted;
                    ++counters_.rescues;
                    return outcome;
                }
                if (accepted_delta > 0 && counters_.pivots - before <= 1) ratio = std::max(ratio * ratio, kRescueMinRatio);
                accepted_delta = delta;
            } else if (accepted_delta < 0) {
                if (delta >= kRescueCeiling * max_diag_) break;
                delta *= 10;
                continue;
            } else {
                ratio = std::sqrt(ratio);
                if (ratio > kRescueMaxRatio) break;
            }
            delta = accepted_delta * ratio;
            if (delta < kRescueFloor * max_diag_ || delta <= shift_) delta = shift_;
        }
        states = entry_states;
        x = entry_x;
        return LoopOutcome::Stalled;
    }

    /// Solves with A + delta_k I, delta_k falling geometrically, each stage warm-started from the
    /// last one's index set (docs/maths.md: what makes BPP converge inside ODE). Only the
    /// first fixed-bound solve of a call runs it; later ones start warm anyway.
    void run_continuation(std::vector<RowState>& states, std::vector<double>& x) {
        continuation_done_ = true;
        const int stages = o_.continuation_stages;
        for (int k = 0; k < stages; ++k) {
            const double delta = kContinuationStart * max_diag_ * std::pow(kContinuationSpan, double(k) / stages);
            if (delta <= shift_ || !prepare(delta)) break;
            std::vector<RowState> trial = states;
            if (pivot_fixed_bounds(lcp_, *solver_, settings_, trial, x, counters_) == LoopOutcome::Breakdown) break;
            states = trial;
        }
    }

    bool prepare(double shift) {
        lcp_.shift = shift;
        if (prepared_ && prepared_shift_ == shift) return true;
        prepared_ = solver_->prepare(shift);
        prepared_shift_ = shift;
        return prepared_;
    }

    /// The next rung of the ladder; false once past kLastShift or when the ladder cannot rise
    /// (a max diag so small, e.g. subnormal, that kFirstShift * max diag rounds to 0: without
    /// this check a breakdown there retried at shift 0 forever, found by fuzz_solve).
    bool raise_shift() {
        const double next = shift_ == 0 ? kFirstShift * max_diag_ : shift_ * kShiftGrowth;
        if (!(next > shift_) || next > kLastShift * max_diag_ * (1 + 1e-9)) return false;
        shift_ = next;
        return true;
    }

    // ---- results, original space ---------------------------------------------------------
    Result finish(bool ok, const std::vector<RowState>& states, const std::vector<double>& x, std::vector<double>& x_out) {
        Result r;
        r.pivots = counters_.pivots;
        r.murty_pivots = counters_.murty_pivots;
        r.downdate_steps = counters_.downdate_steps;
        r.refactor_steps = counters_.refactor_steps;
        r.accuracy_refactors = counters_.accuracy_refactors;
        r.rescues = counters_.rescues;
        r.friction_rounds = friction_rounds_;
        r.linked_friction = counters_.linked_solves > 0;
        r.lemke_pivots = lemke_pivots_;
        r.tight_per_step = counters_.tight_per_step;
        r.factor_error = std::numeric_limits<double>::quiet_NaN();
        x_out.assign(static_cast<std::size_t>(p_.n), 0.0);
        if (!ok) {
            r.status = Status::NotSpd;
            std::ostringstream m;
            m << "Cholesky breaks down even on A + " << kLastShift << " * max diag * I: A is not positive definite";
            r.message = m.str();
            r.regularization = shift_;
            return r;
        }
        r.ordering = perm_;
        r.states.resize(static_cast<std::size_t>(p_.n));
        for (int i = 0; i < p_.n; ++i) {
            x_out[perm_[i]] = x[i];
            r.states[perm_[i]] = states[i];
            r.tight += states[i] != RowState::Free;
        }
        r.regularization = shift_;
        if (shift_ > 0) r.fallback = Fallback::Regularized;
        r.status = overall_status();
        r.message = status_message();
        if (o_.compute_factor_error) r.factor_error = solver_->factor_error(tight_set(states));
        return r;
    }

    Status overall_status() const {
        if (budget_exhausted_) return Status::MaxIterations;
        if (friction_inconsistent_) return Status::FrictionNotConsistent;
        if (shift_ > 0) return Status::FallbackUsed;
        return Status::Converged;
    }

    std::string status_message() const {
        if (!budget_exhausted_ && !friction_inconsistent_ && shift_ == 0) return {};  // no stream on the hot path
        std::ostringstream m;
        if (budget_exhausted_)
            m << "pivot budget of " << settings_.max_pivots << " steps ran out; x is the least infeasible iterate. ";
        if (friction_inconsistent_)
            m << "friction bounds still moving after " << friction_rounds_ << " rounds. ";
        if ((budget_exhausted_ || friction_inconsistent_) && !lemke_note_.empty()) m << lemke_note_ << ". ";
        if (shift_ > 0) m << "Cholesky broke down; solved with A + " << shift_ << " I. ";
        std::string s = m.str();
        if (!s.empty()) s.pop_back();
        return s;
    }

    static std::vector<char> tight_set(const std::vector<RowState>& states) {
        std::vector<char> tight(states.size());
        for (std::size_t i = 0; i < states.size(); ++i) tight[i] = states[i] != RowState::Free;
        return tight;
    }

    const Problem& p_;
    const linalg::SymmetricRows& A_original_;
    const Options& o_;
    PivotSettings settings_;
    PivotCounters counters_;
    DriverWorkspace& ws_ = thread_workspace();
    std::vector<int>& perm_ = ws_.perm;
    linalg::SymmetricRows& permuted_A_ = ws_.permuted_A;  // A in the solver's order, unless that is the caller's
    const linalg::SymmetricRows* Ap_ = &A_original_;     // the matrix the solve works on (permuted space)
    std::unique_ptr<FreeSolver> solver_;
    BoxedLcp& lcp_ = ws_.lcp;
    std::vector<int>&friction_rows_ = ws_.friction_rows, &normal_of_ = ws_.normal_of;  // permuted indices
    std::vector<double>& mu_ = ws_.mu;
    double max_diag_ = 0;
    double shift_ = 0;  // regularization adopted after a breakdown (0: none)
    bool prepared_ = false;
    double prepared_shift_ = 0;
    bool continuation_done_ = false;
    bool budget_exhausted_ = false;
    bool last_fixed_converged_ = false;
    bool breakdown_ = false;
    bool friction_inconsistent_ = false;
    int friction_rounds_ = 0;
    int lemke_pivots_ = 0;
    bool lemke_tried_ = false;
    std::string lemke_note_;  // why the Lemke stage did not finish, for the message
};

}  // namespace

Result solve_bpp(const Problem& problem, const linalg::SymmetricRows& A, const Options& options, std::vector<double>& x) {
    return BppDriver(problem, A, options).run(x);
}

}  // namespace ode_bpp::pivoting
