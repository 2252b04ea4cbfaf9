// solve(): validation, dispatch on Options::method, the fallback chain, and the common Result
// fields (residuals, states) computed the same way for every method.
//
// Fallback chain, in order:
//  1. Invalid input (validate(), a warm start of the wrong size, a non-finite or negative
//     tolerance): Status::InvalidInput, x = 0 (when x is writable), message names the row.
//  2. BPP methods: a Cholesky pivot that is not safely positive (linalg/cholesky_pivot.h, pivot_breaks_down) makes the
//     fixed-bound solve restart with A + delta I, delta = 1e-12 * max_i A_ii, growing x100 up to
//     1e-6 * max_i A_ii; the answer then has fallback "regularized", Result::regularization = delta
//     and status FallbackUsed (or MaxIterations / FrictionNotConsistent if those also happened).
//  3. Breakdown even at 1e-6: Status::NotSpd. With Options::dantzig_fallback the problem goes to
//     ODE's Dantzig: status FallbackUsed, fallback "dantzig" (or "regularized+dantzig" when step 2
//     had already been taken). Without it, or if Dantzig fails too, x = 0 and NotSpd.
//  4. Any method whose answer holds a NaN or an infinity: treated as step 3 (Dantzig if allowed
//     and not already used, else x = 0 and NotSpd). So x is never written non-finite.
//  An island whose BPP factor would exceed Options::max_factor_entries never reaches steps 2-4:
//  Options::pgs_iterations sweeps of projected Gauss-Seidel on the sparse A answer it (status
//  FallbackUsed, fallback "pgs"), and a non-finite answer there is not handed to Dantzig, whose
//  dense A would be larger still (x = 0, NotSpd).
//  Budget exhaustion (MaxIterations) and inconsistent friction (FrictionNotConsistent) are not
//  failures: x is the best finite iterate, within its bounds, and is returned as is.
//
// The status agrees with the answer's residual, for every method (agree_with_residual). An
// answer certifies when its natural residual, friction bounds from its own normals, is at most
// certification_level(tolerance): the smaller of the scaled (componentwise) and the relative one,
// as each misreads what the other reads well (certified_by). Converged stays only where the
// residual of the method's own friction semantics does not refute it (Frozen friction and ODE's
// Dantzig: the fixed-bound residuals, Residuals::fixed_bound), and a certified answer is
// Converged whatever the method's own iteration said (a budget that ran out on an answer already
// exact, PGS's sweeps). Friction rows with mu = +inf are unbounded rows for every method
// (unbounded_friction.h). A converged bpp answer that certifies by its scaled residual but not
// relative to |b| is solved once more, from its own index set at a hundredth of the tolerance,
// and replaced when that certifies (kPolishFactor; the message says so).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "baselines/dantzig.h"
#include "baselines/pgs.h"
#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "ode_bpp/validation.h"
#include "pivoting/bpp_driver.h"
#include "pivoting/small_island.h"
#include "linalg/symmetric_rows.h"
#include "residuals.h"
#include "unbounded_friction.h"
#include "workspace_parts.h"

namespace ode_bpp {

namespace {

struct MethodName {
    Method method;
    const char* name;
};
constexpr MethodName kMethods[] = {
    {Method::BppChol, "bpp-chol"}, {Method::BppDown, "bpp-down"}, {Method::BppSky, "bpp-sky"},
    {Method::Bpp, "bpp"},          {Method::Dantzig, "dantzig"},  {Method::Pgs, "pgs"},
};

/// certification_level(): this many times Options::tolerance, the solver's per-row
/// classification tolerance: 1e-8 by default, the level issue 13's targets certify answers to.
/// On captured scenes the converged answers of bpp sit at most at 3e-9 (Frozen, fixed-bound) and
/// 7e-10 (Consistent), ODE's Dantzig's at 5e-12 except after its "s <= 0" exit (1.0).
constexpr double kCertificationFactor = 10;
/// The level never falls below rounding of the residual itself (Options::tolerance = 0).
constexpr double kCertificationFloor = 1e-14;

bool all_finite(const std::vector<double>& x) {
    return std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
}

Result run_dantzig(const Problem& p, const linalg::SymmetricRows& A, std::vector<double>& x) {
    Result r;
    switch (baselines::solve_dantzig(p, A, x)) {
        case baselines::DantzigOutcome::Solved: break;
        case baselines::DantzigOutcome::Refused:
            r.status = Status::NotSpd;
            r.message = "ODE's Dantzig refused the problem (no memory)";
            return r;
        case baselines::DantzigOutcome::Unavailable:
            r.status = Status::InvalidInput;
            r.message = "method dantzig needs ODE's Dantzig, which the ODE glue (libode_bpp) provides; "
                        "ode_bpp_core alone has none";
            return r;
    }
    r.status = Status::Converged;
    r.states = states_of(p, x);
    r.tight = count_tight(r.states);
    return r;
}

/// MaxIterations: PGS has no test of its own; agree_with_residual() makes a certified answer Converged.
Result run_pgs(const Problem& p, const linalg::SymmetricRows& A, const Options& o, std::vector<double>& x) {
    Result r;
    baselines::solve_pgs(p, A, std::max(0, o.pgs_iterations), x);
    r.pivoting.pivots = std::max(0, o.pgs_iterations);  // sweeps: PGS has no pivot steps
    r.states = states_of(p, x);
    r.tight = count_tight(r.states);
    r.status = Status::MaxIterations;
    return r;
}

/// at_answer: out, w and the row scales at x when the method computed them at its answer
/// (solve_bpp), else empty.
/// A: the problem's, stored in any order (the BPP methods take it as it is, the others in the
/// problem's order: scratch holds it then).
Result dispatch(const Problem& p, const linalg::SymmetricRows& A, const Options& o, const Start& start,
                std::vector<double>& x, pivoting::BppWorkspace& bpp, ResidualBuffers& at_answer,
                linalg::SymmetricRows& scratch) {
    at_answer.w.clear();
    if (pivoting::is_bpp(o.method)) return pivoting::solve_bpp(p, A, o, start, x, bpp, at_answer);
    if (o.method == Method::Dantzig) return run_dantzig(p, A.in_built_order(scratch), x);
    return run_pgs(p, A.in_built_order(scratch), o, x);
}

/// Fallback::Pgs: Options::pgs_iterations sweeps on the sparse A for an island whose factor
/// would exceed Options::max_factor_entries (`entries` of it). A: in the problem's order.
/// at_answer: out, emptied as dispatch empties it (PGS leaves no w at its answer).
Result pgs_fallback(const Problem& p, const linalg::SymmetricRows& A, const Options& o, std::int64_t entries,
                    std::vector<double>& x, ResidualBuffers& at_answer) {
    at_answer.w.clear();
    Result r = run_pgs(p, A, o, x);
    r.status = Status::FallbackUsed;
    r.fallback = Fallback::Pgs;
    std::ostringstream m;
    m << "the Cholesky factor would hold " << entries << " entries, more than max_factor_entries = "
      << o.max_factor_entries << "; answered by " << std::max(0, o.pgs_iterations)
      << " sweeps of projected Gauss-Seidel on the sparse A";
    r.message = m.str();
    return r;
}

/// Steps 3-4 of the chain above; true when x was replaced. A: stored in any order (scratch holds
/// it in the problem's for Dantzig).
bool apply_fallbacks(const Problem& p, const linalg::SymmetricRows& A, const Options& o, Result& r,
                     std::vector<double>& x, linalg::SymmetricRows& scratch) {
    const bool failed = r.status == Status::NotSpd || !all_finite(x);
    if (!failed) return false;
    std::string reason = r.status == Status::NotSpd ? r.message : "the answer was not finite";
    // an island too large for a factor is too large for Dantzig's dense A (n^2 entries) too
    if (o.dantzig_fallback && o.method != Method::Dantzig && r.fallback != Fallback::Pgs) {
        std::vector<double> xd;
        const baselines::DantzigOutcome outcome = baselines::solve_dantzig(p, A.in_built_order(scratch), xd);
        if (outcome == baselines::DantzigOutcome::Solved && all_finite(xd)) {
            x = std::move(xd);
            r.status = Status::FallbackUsed;
            r.fallback = r.fallback == Fallback::Regularized ? Fallback::RegularizedDantzig : Fallback::Dantzig;
            r.message = reason + "; answered by ODE's Dantzig";
            r.states = states_of(p, x);
            r.tight = count_tight(r.states);
            return true;
        }
        reason += outcome == baselines::DantzigOutcome::Unavailable ? "; no Dantzig to fall back on (ode_bpp_core alone)"
                                                                    : "; ODE's Dantzig failed too";
    }
    x.assign(static_cast<std::size_t>(p.n), 0.0);
    r.status = Status::NotSpd;
    r.message = reason + "; x set to zero";
    r.states.assign(static_cast<std::size_t>(p.n), RowState::Free);
    r.tight = 0;
    return true;
}

/// The certifying value of a pair of residuals of one answer: the smaller. The scaled residual
/// divides each row by its own scale, which is rounding itself where an exact x_i is 0 and its
/// neighbours too (an exact forklift answer: 7e-3 from rows with x ~ 1e-14 and |w| ~ 1e-16); the
/// relative one divides by max(1, ||b||), which internal impulses far above b outgrow (a log
/// clamped by 3e3 N s: 1.7e-8 where every row was exact to 1e-10 of its scale).
double certified_by(double scaled, double relative) { return std::min(scaled, relative); }

double natural_certificate(const Result& r) { return certified_by(r.residuals.scaled_natural, r.residuals.relative_natural); }

/// The residual that can refute a Converged answer: friction bounds from the answer's own normals
/// where the method keeps friction consistent (PGS projects onto them at every sweep), the
/// fixed-bound residuals where it freezes them (ODE's Dantzig; BPP's Frozen mode).
bool keeps_friction_consistent(const Options& o) {
    return o.method == Method::Pgs || (pivoting::is_bpp(o.method) && o.friction == FrictionMode::Consistent);
}

double refuting_residual(const Options& o, const Result& r) {
    return keeps_friction_consistent(o) ? natural_certificate(r)
                                        : certified_by(r.residuals.scaled_fixed_bound, r.residuals.fixed_bound);
}

std::string residual_text(double residual, double level) {
    std::ostringstream m;
    m << residual << (residual > level ? " > " : " <= ") << level;
    return m.str();
}

/// See the header comment: Converged exactly where the residuals allow it.
void agree_with_residual(const Options& o, Result& r) {
    const double level = certification_level(o.tolerance);
    const double refuting = refuting_residual(o, r);
    if (r.status == Status::Converged && refuting > level) {
        const bool fixed = refuting != natural_certificate(r);
        r.status = Status::MaxIterations;
        r.message = std::string(to_string(o.method)) + " ended, but its answer's " +
                    (fixed ? "fixed-bound residual is " : "residual is ") + residual_text(refuting, level);
    } else if ((r.status == Status::MaxIterations || r.status == Status::FrictionNotConsistent) &&
               natural_certificate(r) <= level) {
        r.message = "certified by its residual " + residual_text(natural_certificate(r), level) +
                    (r.message.empty() ? "" : "; the method said: " + r.message);
        r.status = Status::Converged;
    } else if (r.status == Status::MaxIterations && r.message.empty()) {
        r.message = "not certified: residual " + residual_text(natural_certificate(r), level);
    }
}

/// A converged bpp answer certifies by the smaller of its scaled and its relative residual
/// (certified_by), and its tolerance bounds the scaled one, row by row against (|A||x| + |b|)_i.
/// Where contacts carry impulses far above |b| (a heavy box on a pile), a row within that
/// tolerance can still miss by more than the level relative to |b| (a friction row at its bound
/// with w of the wrong sign by 5e-7 against an impulse of 70: relative 4.7e-8). Such an answer is
/// solved once more from its own index set and ordering, at the tolerance divided by this; the
/// tighter answer is kept when it certifies relative to |b| too.
constexpr double kPolishFactor = 100;

/// The residual relative to max(1, ||b||) of the kind that refutes a Converged answer
/// (refuting_residual).
double relative_refuting_residual(const Options& o, const Result& r) {
    return keeps_friction_consistent(o) ? r.residuals.relative_natural : r.residuals.fixed_bound;
}

bool wants_polish(const Options& o, const Result& r) {
    return pivoting::is_bpp(o.method) && r.status == Status::Converged && r.fallback == Fallback::None &&
           relative_refuting_residual(o, r) > certification_level(o.tolerance) &&
           o.tolerance / kPolishFactor >= kCertificationFloor;
}

void add_counts(PivotStats& into, const PivotStats& from) {
    into.pivots += from.pivots;
    into.murty_pivots += from.murty_pivots;
    into.downdate_steps += from.downdate_steps;
    into.refactor_steps += from.refactor_steps;
    into.update_steps += from.update_steps;
    into.accuracy_refactors += from.accuracy_refactors;
    into.rescues += from.rescues;
    into.linked_solves += from.linked_solves;
    into.friction_rounds += from.friction_rounds;
    into.lemke_pivots += from.lemke_pivots;
}

/// The residuals of x: from w and the row scales in buffers when they are x's (at_x, as the
/// method left them: the loop's last w is the answer's), else from a pass over A.
void fill_residuals(const Problem& p, const linalg::SymmetricRows& A, Result& r, const std::vector<double>& x,
                    ResidualBuffers& buffers, bool at_x) {
    const std::vector<RowState>* states = r.states.empty() ? nullptr : &r.states;
    if (at_x) r.residuals = residuals_from(p, A, ConstStrided{x.data(), 1}, states, buffers);
    else r.residuals = compute_residuals(p, A, ConstStrided{x.data(), 1}, states, buffers);
}

/// A as compressed rows: the caller's sparse A as it is (in the order it is stored in, which may
/// be the solver's: ode/island_view.h), or the dense lower triangle read once (the only O(n^2)
/// pass of a dense problem) into rows (storage reused).
const linalg::SymmetricRows& rows_of(const Problem& problem, linalg::SymmetricRows& rows) {
    if (problem.sparse != nullptr) return *problem.sparse;
    rows.assign(problem, {});
    return rows;
}

/// The small-island path (pivoting/small_island.h); true when it answered, with r complete and
/// x written. answer: scratch, n entries.
bool solve_small(const Problem& problem, const Options& options, const Start& start, pivoting::SmallIslandBuffers& buffers,
                 std::vector<double>& answer, Result& r, Strided x) {
    if (!pivoting::solve_small_island(problem, options, start, buffers, answer, r)) return false;
    r.method = options.method;
    r.friction = options.friction;
    agree_with_residual(options, r);
    for (int i = 0; i < problem.n; ++i) x[i] = answer[i];
    return true;
}

/// kPolishFactor's second solve of a converged bpp answer r (x: answer, n entries); true when
/// its answer replaced r and answer, with the pivot counts of both solves.
bool polish(const Problem& problem, const linalg::SymmetricRows& A, const Options& options, Workspace::Parts& parts,
            Result& r, std::vector<double>& answer) {
    Options tighter = options;
    tighter.tolerance = options.tolerance / kPolishFactor;
    Start from;
    from.states = r.states;
    from.ordering = r.ordering;
    std::vector<double> polished;
    Result p = dispatch(problem, A, tighter, from, polished, parts.bpp, parts.residuals, parts.rows);
    if (p.status != Status::Converged || p.fallback != Fallback::None || !all_finite(polished)) return false;
    fill_residuals(problem, A, p, polished, parts.residuals, parts.residuals.w.size() == polished.size());
    if (relative_refuting_residual(options, p) > certification_level(options.tolerance)) return false;
    std::ostringstream m;
    m << "solved again at tolerance " << tighter.tolerance << " from its own index set: the first answer's residual "
      << "relative to |b| was " << relative_refuting_residual(options, r);
    p.message = m.str();
    p.method = options.method;
    p.friction = options.friction;
    add_counts(p.pivoting, r.pivoting);
    r = std::move(p);
    answer.swap(polished);
    return true;
}

ValidationResult validate_call(const Problem& problem, const Options& options, const Start& start) {
    ValidationResult v = validate_structure(problem);
    if (v.valid) v = validate_warm_start(problem, start.states);
    if (v.valid && !(options.tolerance >= 0 && std::isfinite(options.tolerance)))
        v = {false, "tolerance must be finite and >= 0"};
    if (v.valid && !(options.tuning.friction_damping > 0 && options.tuning.friction_damping <= 1))
        v = {false, "tuning.friction_damping must be in (0, 1]"};
    return v;
}

Result invalid_input(const Problem& p, Strided x, std::string message) {
    Result r;
    r.status = Status::InvalidInput;
    r.message = std::move(message);
    if (x.data != nullptr && x.stride >= 1)
        for (int i = 0; i < p.n; ++i) x[i] = 0.0;
    return r;
}

}  // namespace

const char* to_string(Method m) {
    for (const MethodName& entry : kMethods)
        if (entry.method == m) return entry.name;
    return "unknown";
}

std::optional<Method> method_from_string(std::string_view name) {
    for (const MethodName& entry : kMethods)
        if (name == entry.name) return entry.method;
    return std::nullopt;
}

std::vector<std::string> method_names() {
    std::vector<std::string> names;
    for (const MethodName& entry : kMethods) names.emplace_back(entry.name);
    return names;
}

const char* to_string(Fallback f) {
    switch (f) {
        case Fallback::None: return "none";
        case Fallback::Regularized: return "regularized";
        case Fallback::Dantzig: return "dantzig";
        case Fallback::RegularizedDantzig: return "regularized+dantzig";
        case Fallback::Pgs: return "pgs";
    }
    return "unknown";
}

const char* to_string(FrictionMode f) { return f == FrictionMode::Frozen ? "frozen" : "consistent"; }

std::optional<FrictionMode> friction_from_string(std::string_view name) {
    if (name == "frozen") return FrictionMode::Frozen;
    if (name == "consistent") return FrictionMode::Consistent;
    return std::nullopt;
}

const char* to_string(Status s) {
    switch (s) {
        case Status::Converged: return "converged";
        case Status::MaxIterations: return "max-iterations";
        case Status::FallbackUsed: return "fallback-used";
        case Status::NotSpd: return "not-spd";
        case Status::InvalidInput: return "invalid-input";
        case Status::FrictionNotConsistent: return "friction-not-consistent";
    }
    return "unknown";
}

bool is_usable(Status s) {
    return s == Status::Converged || s == Status::FallbackUsed || s == Status::MaxIterations ||
           s == Status::FrictionNotConsistent;
}

double certification_level(double tolerance) { return std::max(kCertificationFactor * tolerance, kCertificationFloor); }

Result solve(const Problem& caller_problem, const Options& options, Strided x, const Start& start, Workspace& workspace) {
    if (x.data == nullptr || x.stride < 1) {
        Result r = invalid_input(caller_problem, x, "x is null or has a stride < 1");
        r.method = options.method;
        r.friction = options.friction;
        return r;
    }
    Workspace::Parts& parts = workspace.parts();
    ValidationResult v = validate_call(caller_problem, options, start);
    const Problem problem = v.valid && has_unbounded_friction(caller_problem)
                                ? parts.unbounded_friction.view(caller_problem)
                                : caller_problem;
    const bool small = v.valid && pivoting::takes_small_island(problem, options);
    if (small) v = validate_matrix(problem);
    const linalg::SymmetricRows* A = v.valid && !small ? &rows_of(problem, parts.rows) : nullptr;
    if (A != nullptr) v = validate_matrix(*A);
    if (!v.valid) {
        Result r = invalid_input(problem, problem.n > 0 ? x : Strided{}, v.message);
        r.method = options.method;
        r.friction = options.friction;
        return r;
    }
    std::vector<double>& answer = parts.answer;
    Result small_attempt;
    if (small) small_attempt.states.swap(parts.spare_states);  // its capacity, not its entries
    if (small && solve_small(problem, options, start, parts.small_island, answer, small_attempt, x)) {
        if (wants_polish(options, small_attempt) &&
            polish(problem, rows_of(problem, parts.rows), options, parts, small_attempt, answer)) {
            agree_with_residual(options, small_attempt);
            for (int i = 0; i < problem.n; ++i) x[i] = answer[i];
        }
        return small_attempt;
    }
    if (A == nullptr) A = &rows_of(problem, parts.rows);
    // the factor's size in the order the solve would factor in; an ordering chosen to find it
    // out is handed on, so that the solve does not order A again
    Start ordered;
    const bool sized = pivoting::factor_may_be_too_large(problem.n, options);
    const std::int64_t entries =
        sized ? pivoting::planned_factor_entries(problem, *A, options, start, parts.rows, ordered.ordering) : 0;
    if (!ordered.ordering.empty()) ordered.states = start.states;
    Result r = sized && entries > options.max_factor_entries
                   ? pgs_fallback(problem, A->in_built_order(parts.rows), options, entries, answer, parts.residuals)
                   : dispatch(problem, *A, options, ordered.ordering.empty() ? start : ordered, answer, parts.bpp,
                              parts.residuals, parts.rows);
    r.method = options.method;
    r.friction = options.friction;
    r.pivoting.pivots += small_attempt.pivoting.pivots;  // the steps of a small-island attempt that did not finish
    const bool replaced = apply_fallbacks(problem, *A, options, r, answer, parts.rows);
    const bool vectors_at_answer = !replaced && parts.residuals.w.size() == answer.size();
    fill_residuals(problem, *A, r, answer, parts.residuals, vectors_at_answer);
    agree_with_residual(options, r);
    if (wants_polish(options, r) && polish(problem, *A, options, parts, r, answer)) agree_with_residual(options, r);
    if (!pivoting::is_bpp(options.method)) r.factor_error = std::numeric_limits<double>::quiet_NaN();
    if (r.status != Status::Converged && r.message.empty()) r.message = to_string(r.status);
    for (int i = 0; i < problem.n; ++i) x[i] = answer[i];
    return r;
}

Result solve(const Problem& problem, const Options& options, Strided x, const Start& start) {
    return solve(problem, options, x, start, thread_workspace());
}

Result solve(const Problem& problem, const Options& options, double* x, const Start& start) {
    return solve(problem, options, Strided{x, 1}, start, thread_workspace());
}

}  // namespace ode_bpp
