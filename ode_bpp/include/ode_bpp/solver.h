// ode_bpp/solver.h: the public face of the solver.
//
// A Problem (a view, owning nothing) and Options go in; a Result comes out.
// The MLCP is ODE's (ode/src/lcp.h):
//     A x = b + w,   and for each row i one of
//         x_i = lo_i and w_i >= 0,   x_i = hi_i and w_i <= 0,   lo_i < x_i < hi_i and w_i = 0.
// A friction row i (findex[i] >= 0) has the bounds hi_i <- |hi_i * x[findex[i]]|, lo_i <- -hi_i,
// i.e. its input hi_i is the friction coefficient mu_i.
// All index spaces in this header are the caller's original row order.
#pragma once

#include "ode_bpp/export.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ode_bpp/workspace.h"

namespace ode_bpp {

/// A read-only strided vector, so that ODE's interleaved pairs (b at [2i], x at [2i+1])
/// are used in place without copies.
struct ConstStrided {
    const double* data = nullptr;
    int stride = 1;
    double operator[](int i) const { return data[static_cast<std::ptrdiff_t>(i) * stride]; }
};

/// A writable strided vector (the solution x).
struct Strided {
    double* data = nullptr;
    int stride = 1;
    double& operator[](int i) const { return data[static_cast<std::ptrdiff_t>(i) * stride]; }
};

namespace linalg {
class SymmetricRows;
}

/// One MLCP, as a view. A comes in one of two forms:
///  - dense: n x n, row-major with row stride lda >= n; only the lower triangle (diagonal
///    included) is read, as ODE fills only the lower block triangle;
///  - sparse: `sparse` non-null (A and lda are then ignored), A's non-zeros as compressed
///    symmetric rows in the original order (linalg/symmetric_rows.h), e.g. assembled from ODE's
///    Jacobian by the world hook (ode/assemble.h). Validation, solve and residuals then cost
///    O(non-zeros); the dense form is converted into this one in one pass.
struct Problem {
    int n = 0;                     ///< rows; 0 is a valid, empty problem
    const double* A = nullptr;     ///< dense form: n rows of stride lda, lower triangle read
    int lda = 0;                   ///< dense form: row stride, >= n
    const linalg::SymmetricRows* sparse = nullptr;  ///< sparse form, or null for the dense one
    /// n entries each, read only: w = A x - b; bounds lo_i <= x_i <= hi_i, where a friction
    /// row's hi_i is its mu_i >= 0 and its bounds are +-mu_i |x_findex[i]| (its lo_i plays no part).
    ConstStrided b, lo, hi;
    const int* findex = nullptr;   ///< n entries, -1 for none; may be null
    /// Leading rows that are unbounded whatever lo/hi say. A lower bound only: every row with
    /// lo = -inf and hi = +inf is unbounded too (ODE 0.16.2 passes the count of joints, not rows).
    int nub = 0;
    /// Optional constraint-graph structure for the ordering: row blocks (one per joint),
    /// block k owning rows block_row[k] .. block_row[k+1]-1, and coupling bodies
    /// block_body[2k], block_body[2k+1] (-1 for the static environment). Null: the
    /// graph is read off A's non-zeros instead.
    int num_blocks = 0;
    const int* block_row = nullptr;   ///< num_blocks + 1 entries
    const int* block_body = nullptr;  ///< 2 * num_blocks entries
};

/// The solvers, selectable at run time by name (see method_from_string).
enum class Method {
    BppChol,   ///< "bpp-chol": Alg. 1, a fresh dense Cholesky of A_FF at every pivot step
    BppDown,   ///< "bpp-down": Alg. 2, factor once, copy L and delete tight rows, dense storage
    BppSky,    ///< "bpp-sky":  Alg. 2 + 3, Cuthill-McKee ordering, deletion and solve inside the skyline
    Bpp,       ///< "bpp": envelope storage, cost model choosing deletion or partial refactoring per step
    Dantzig,   ///< "dantzig": ODE's stock Dantzig through dSolveMLCPDantzig (needs the ODE library)
    Pgs,       ///< "pgs": projected Gauss-Seidel, Options::pgs_iterations sweeps
};
/// The method's name as above ("unknown" for a value outside the enum).
ODE_BPP_API const char* to_string(Method m);
/// The method of that exact (case-sensitive) name, or nullopt.
ODE_BPP_API std::optional<Method> method_from_string(std::string_view name);
/// All method names, in the order of the enum.
ODE_BPP_API std::vector<std::string> method_names();

/// How friction bounds follow the normal impulses.
enum class FrictionMode {
    Frozen,      ///< Dantzig's semantics: bounds fixed from the normals of a first solve
    Consistent,  ///< at convergence |x_i| <= mu_i * x_findex[i] for every friction row
};
/// "frozen" or "consistent".
ODE_BPP_API const char* to_string(FrictionMode f);
/// The mode of that exact (case-sensitive) name, or nullopt.
ODE_BPP_API std::optional<FrictionMode> friction_from_string(std::string_view name);

/// How a solve ended; Result::message says more whenever it is not Converged.
enum class Status {
    /// an answer within certification_level() of exact in the residual of its friction semantics
    /// (the natural residuals for Consistent friction and PGS, the fixed-bound ones for Frozen
    /// friction and ODE's Dantzig, whose frozen bounds the answer does not carry; of each pair the
    /// smaller of the scaled and the relative one), and any answer whose natural residual is that
    /// small, whatever its method said (solver.cpp, agree_with_residual)
    Converged,
    /// not certified: the pivot budget ran out (x is the best iterate), PGS's last sweep, or a
    /// method that ended with a residual above the certification level (message says which)
    MaxIterations,
    FallbackUsed,    ///< the answer came through a documented fallback (see Result::fallback)
    NotSpd,          ///< A is not positive definite, and regularization did not rescue it
    InvalidInput,    ///< validation failed (NaN/Inf, lo > hi, bad findex, bad sizes); x is zero
    FrictionNotConsistent,  ///< consistent mode: the outer bound loop ran out of iterations
};
/// "converged", "max-iterations", "fallback-used", "not-spd", "invalid-input",
/// "friction-not-consistent" ("unknown" outside the enum).
ODE_BPP_API const char* to_string(Status s);
/// True when x is a usable answer: Converged, FallbackUsed, or a finite but uncertified iterate
/// (MaxIterations, FrictionNotConsistent); false for NotSpd and InvalidInput, whose x is zero.
ODE_BPP_API bool is_usable(Status s);

/// The fallback an answer came through (solver.cpp's chain), if any.
enum class Fallback : std::int8_t {
    None,                ///< the method's own answer
    Regularized,         ///< solved on A + delta I after a Cholesky breakdown (Result::regularization)
    Dantzig,             ///< the method failed; ODE's Dantzig answered
    RegularizedDantzig,  ///< regularization did not rescue the method either; ODE's Dantzig answered
    Pgs,                 ///< the island's factor would exceed Options::max_factor_entries; PGS answered
};
/// "none", "regularized", "dantzig", "regularized+dantzig", "pgs".
ODE_BPP_API const char* to_string(Fallback f);

/// Per-row state of an index set: the paper's F, T_lo and T_hi (Eq. 4).
enum class RowState : std::int8_t {
    Free = 0,  ///< w_i = 0, lo_i <= x_i <= hi_i at an answer
    AtLo = 1,  ///< x_i = lo_i and w_i >= 0
    AtHi = 2,  ///< x_i = hi_i and w_i <= 0
};

/// The algorithm's tuned internals. The defaults were measured on the paper's scenes inside ODE
/// (docs/tuning.md, with what the alternatives gave); a user rarely needs to change them.
struct Tuning {
    /// Block steps without a fall in the number of infeasible rows before Murty's single pivot.
    int murty_after = 3;
    /// The same on the small-island path (dense_island_rows). There every step refactors A_FF,
    /// so a block step that does not lower the count is a factorization spent for nothing; and on
    /// islands of nearly redundant friction rows (a box on three coplanar contacts, where A_FF has
    /// a near null space) such a step frees the redundant rows together and swings x by orders of
    /// magnitude, which the next block steps chase back and forth (docs/tuning.md). 0: Murty's
    /// pivot at the first step that does not improve.
    int small_island_murty_after = 0;
    /// Steps of the plain attempt of a fixed-bound solve. If it has not converged by then, the
    /// active-set method below goes on from its least infeasible iterate; where that does not
    /// finish, the solve starts again from its start through a regularization continuation
    /// (A + delta I, delta falling adaptively from 1e-4 max_i A_ii to the problem's own,
    /// pivoting/regularization.h), with the rest of the budget; if that gives up, the plain
    /// attempt resumes. 0: none of this (the plain attempt has the whole budget). The
    /// small-island path counts its steps alike and runs the active set densely; what that does
    /// not finish goes to the general driver (pivoting/small_island.h).
    int rescue_after = 8;
    /// The same for Frozen friction's second fixed-bound solve from a warm start (Start::states,
    /// as inside ODE): its friction rows have just been bounded anew by mu times the frictionless
    /// normals, which the previous step's friction states mostly miss, and block steps then flip
    /// tens of nearly redundant friction rows back and forth where the active set settles them
    /// (docs/tuning.md). Used only while rescue_after > 0; at least 1.
    int rescue_after_moved_bounds = 2;
    /// The same for that solve without a warm start (a new island, the corpus): its friction
    /// rows start free, not in states that miss their bounds, so block steps get further, but on
    /// most forwarder and winch islands they still end cycling after the first few steps, and the
    /// active set, which starts from the loop's own factor, finishes sooner (docs/tuning.md).
    int rescue_after_moved_bounds_cold = 4;
    /// Frozen friction's second fixed-bound solve, from a warm start (Start::states), starts
    /// every row from that warm start; false: its non-friction rows from the first, frictionless
    /// solve's answer, as a solve without a warm start does. The frictionless answer solves
    /// another problem: on a resting pile it misses the frictional answer's normals in tens of
    /// rows, and the active set then took hundreds of single steps to come back to the warm
    /// start, which was the answer (a 1,083-row rock pile at rest: 561 steps against 1,
    /// docs/tuning.md).
    bool frozen_second_solve_from_warm_start = true;
    /// A plain step that leaves more rows infeasible than this ends the plain attempt at once,
    /// before rescue_after steps, and the active set goes on from it; Frozen friction's second
    /// solve keeps its own counts above. From a step that leaves several rows infeasible, block
    /// steps seldom finish at the next step (islands captured inside ODE: 46 % with 2 such rows,
    /// 16 % with 5, almost none with 8 or more), while a step with one infeasible row is the active
    /// set's own single pivot without the setup of its factor (docs/tuning.md). 0: rescue_after
    /// alone counts. Used only where the active set applies.
    int hand_over_above = 1;
    /// Where that plain attempt does not converge, an active-set method on the box QP from its
    /// least infeasible iterate: it terminates finitely, the rows with wrong-sign multipliers
    /// leaving the tight set several at a time and a ratio test keeping x within its bounds,
    /// each row added to or removed from a factor of A_FF kept on its envelope
    /// (pivoting/active_set.h), before the regularization continuation. Islands of any size.
    /// Needs rescue_after > 0.
    bool active_set = true;
    /// Where a face's minimizer leaves tight rows with wrong-sign multipliers, the active set
    /// releases at most this many of them at once, the most violated (0 or less: all of them).
    /// Released together, most of a pile's wrong-sign rows came back one step each: a bin island
    /// of creeping capsules released 3,643 rows in 64 releases to free 305 on net, and spent
    /// 1,575 of its 1,703 steps tightening them again; at most 8 at once halves the bin's solver
    /// instructions and takes 30 % off a rock pile's, within -2.3 % to +0.3 % on the paper
    /// scenes (docs/tuning.md).
    int active_set_release_at_most = 8;
    /// The active set's factor (its L_FF on the envelope) keeps its storage for the next run up
    /// to this many bytes, as the workspace keeps its other buffers; a larger one goes back to the
    /// system after its run (0: after every run). Fresh storage costs a page fault per page on
    /// first touch, and the paper scenes run the stage often (the forwarder about twice a step)
    /// with factors of at most 180 kB: kept, parkour's mean step inside ODE fell 12-15 % and its
    /// slowest 1 % 27 % (docs/tuning.md). The bound keeps a pile's rarer large factor (up to
    /// 0.9 MB on the pyramid's 984 rows) from staying resident.
    std::size_t active_set_kept_factor_bytes = std::size_t{256} << 10;
    /// Consistent friction: most outer bound updates, damped (new = (1-d)*old + d*target).
    int max_friction_rounds = 100;
    /// d of those updates, in (0, 1] (1: no damping); outside it solve() answers InvalidInput.
    double friction_damping = 0.6;
    /// Consistent friction: first solve with the friction bounds moving with the normals inside
    /// each pivot step, friction rows at a bound solved together with their normals
    /// (pivoting/friction_link.h); the outer damped bound updates only where that fails.
    bool link_friction = true;
    /// Consistent friction: where the linked solve does not finish within its budget, Lemke's
    /// method on the friction LCP (pivoting/friction_lcp.h: the friction rows split into
    /// non-negative parts with a multiplier for mu x_n - |x_f|), whose answer a linked solve then
    /// certifies. False: outer damped rounds as the last resort.
    bool lemke_friction = true;
    /// An up-front regularization continuation: solve with A + delta I, delta falling
    /// geometrically over this many stages, each from the last. 0 disables it.
    int continuation_stages = 0;
    /// Bpp: islands of at most this many rows take the small-island path (pivoting/small_island.h)
    /// in Frozen mode, or refactor densely at every step in the caller's order otherwise: there
    /// the skyline's set-up (ordering, shape, cost model, L0 and its copy) costs more than a dense
    /// Cholesky of the whole island. 0: always the skyline.
    int dense_island_rows = 32;
    /// Bpp: also consider orderings with the start's tight rows last (deleting them then touches
    /// few columns) and, with Frozen friction, with the friction rows last (its first fixed-bound
    /// solve holds them at 0, so it refactors a short tail), priced by the cost model against the
    /// envelope they may widen (ordering/ordering_choice.h). False: Cuthill-McKee or its reverse only.
    bool order_tight_last = true;
    /// Bpp, with order_tight_last, on islands large enough for an ordering: price the
    /// Cuthill-McKee orderings with the tight rows last against reverse Cuthill-McKee. False:
    /// reverse Cuthill-McKee, unpriced (the caller's order with the friction rows last, on islands
    /// too small for an ordering, is priced either way). The ODE hook turns it off for an island
    /// structure it has not met before, and prices the structure when it returns: most of those
    /// met once never do, and on them the pricing cost about what the choice saved
    /// (docs/tuning.md).
    bool price_tight_last_orderings = true;
};

/// Settings of one solve.
struct Options {
    Method method = Method::Bpp;                   ///< the solver (to_string(Method) names them)
    FrictionMode friction = FrictionMode::Frozen;  ///< how friction bounds follow the normals
    /// Pivot-step budget per fixed-bound solve (Frozen friction makes two, Consistent one per
    /// round), at least 1 (a smaller value counts as 1). The paper used 35.
    int max_pivots = 100;
    /// Relative tolerance: a row is infeasible when it breaks its bound by more than
    /// tol * (|A||x| + |b|)_i (scaled per row, never an absolute constant).
    double tolerance = 1e-9;
    /// Projected Gauss-Seidel sweeps (Method::Pgs, and the BPP methods' fallback below).
    int pgs_iterations = 35;
    /// BPP methods: the most entries the Cholesky factor's storage may hold (its envelope in
    /// the ordering, or n(n+1)/2 for the dense methods; the solve keeps about four arrays of
    /// that size). An island whose factor would hold more (a pile of thousands of overlapping
    /// bodies, whose envelope is nearly dense) is answered by pgs_iterations sweeps of projected
    /// Gauss-Seidel on the sparse A instead, as dWorldQuickStep would answer it: status
    /// FallbackUsed, fallback Pgs. Where even ODE's Dantzig would need a dense A of n^2 entries,
    /// an exact solve would take minutes and gigabytes (docs/modelling.md). 0 or less: no limit.
    std::int64_t max_factor_entries = std::int64_t{1} << 24;
    /// On failure of the method, finish with ODE's Dantzig if it is available.
    bool dantzig_fallback = true;
    /// Compute Table 4's ||L_deleted - chol(A_FF)||_F at the final index set (costly).
    bool compute_factor_error = false;
    /// Record |T| at every pivot step in Result::pivoting.tight_per_step.
    bool record_steps = true;
    Tuning tuning;  ///< the algorithm's internals; the defaults rarely need changing
};

/// Where a solve starts: what an earlier solve of the same island left behind (the world hook
/// keeps both per island, matched by row identity and by joint structure). Original row order.
struct Start {
    /// Initial index set (n entries), or empty for all rows free.
    std::vector<RowState> states;
    /// Bpp and BppSky: the symmetric row permutation to factor in (perm[new] = old, n entries),
    /// e.g. Result::ordering of the same island's previous step, skipping the ordering; empty, or
    /// not a permutation of 0..n-1: computed afresh.
    std::vector<int> ordering;
};

/// The quality measures of an answer (ode_bpp/residuals.h computes them), the same for every
/// method so that ours, Dantzig, PGS and the peers are judged by the same numbers.
struct Residuals {
    /// ||x - clamp(x - w, lo(x), hi(x))||_inf with w = A x - b and the friction bounds taken
    /// from x's own normal impulses.
    double natural = 0;
    /// natural / max(1, ||b||_inf).
    double relative_natural = 0;
    /// Scale-free version: max_i |x_i - clamp(x_i - w_i / A_ii, lo_i(x), hi_i(x))| / s_i with the
    /// row's own scale s_i = ((|A||x|)_i + |b_i|) / A_ii (0 where the numerator is 0), for a
    /// friction row at least |mu_i| s_findex[i], as its bound is known only to its normal's scale.
    /// The diagonal scaling keeps the same solution set and makes both terms units of x; this is
    /// the quantity the per-row tolerance Options::tolerance bounds.
    double scaled_natural = 0;
    /// ||A_FF x_F - (b_F - A_FT x_T)||_inf = max over free rows of |w_i|.
    double free = 0;
    /// max over friction rows of max(0, |x_i| - mu_i |x_findex[i]|).
    double friction = 0;
    /// relative_natural of the fixed-bound problem the answer implies: each friction row with a
    /// finite mu bounded by +-|x_i|, its own magnitude, instead of +-mu_i |x_findex[i]|. Frozen
    /// friction and ODE's Dantzig fix friction bounds that the answer does not carry; whatever
    /// they were, an exact answer of that fixed-bound problem has this residual at rounding level
    /// (a friction row strictly inside its bounds has w_i = 0, one at a bound has w_i of the sign
    /// that keeps it there), so a larger value refutes it. It cannot certify one: a row stopped
    /// short of its bound passes.
    double fixed_bound = 0;
    /// scaled_natural of the same fixed-bound problem.
    double scaled_fixed_bound = 0;
};

/// What the pivoting did to reach an answer, all fixed-bound solves and friction rounds together.
struct PivotStats {
    int pivots = 0;              ///< pivot steps (solves of A_FF x_F = rhs)
    int murty_pivots = 0;        ///< of which single pivots (Murty's, and the active set's steps)
    int downdate_steps = 0;      ///< steps whose L_FF came from copying L and deleting rows
    int refactor_steps = 0;      ///< steps whose L_FF came from a (partial) refactorization
    /// steps whose L_FF came from the active set's incremental factor (rows added or removed one
    /// at a time, one or more per step; Tuning::active_set); pivots = downdate_steps +
    /// refactor_steps + update_steps
    int update_steps = 0;
    int accuracy_refactors = 0;  ///< deleted factors rejected by the free-residual check and refactored
    int rescues = 0;             ///< fixed-bound solves the rescue continuation finished (Tuning::rescue_after)
    /// Consistent friction: solves with the friction bounds moving with the normals
    /// (Tuning::link_friction); 0 when the linked stage did not run.
    int linked_solves = 0;
    /// Consistent friction: outer bound updates after the linked solve (0 when it alone converged).
    int friction_rounds = 0;
    /// Consistent friction: complementary pivots of the Lemke stage, which runs only where the
    /// linked solves did not finish (pivoting/friction_lcp.h); 0 when it was not needed.
    int lemke_pivots = 0;
    std::vector<int> tight_per_step;  ///< |T| at each pivot step (Options::record_steps)
};

/// What a solve returns besides x: DART's {status, iterations, residual, message} shape, with
/// the pivoting's counts and every residual.
struct Result {
    /// How the solve ended. A default-constructed Result (no solve yet, e.g. last_island_result
    /// of a world that has stepped none) says InvalidInput.
    Status status = Status::InvalidInput;
    std::string message;          ///< human-readable reason, always set when not Converged
    Method method = Method::Bpp;  ///< the method that was asked for
    FrictionMode friction = FrictionMode::Frozen;  ///< the friction semantics it solved with
    Fallback fallback = Fallback::None;  ///< the fallback the answer came through, if any
    PivotStats pivoting;          ///< pivot steps and friction rounds, all stages together
    /// The answer's residuals, friction bounds taken from its own normal impulses.
    Residuals residuals;
    int tight = 0;                ///< |T| at the answer
    /// Table 4's ||L_deleted - chol(A_FF)||_F at the final index set (NaN unless requested with
    /// Options::compute_factor_error and meaningful for the method).
    double factor_error = std::numeric_limits<double>::quiet_NaN();
    /// delta of the A + delta*I the answer solves (0 unless the fallback was Regularized).
    double regularization = 0;
    std::vector<RowState> states; ///< final index set, original row order (for warm starts)
    std::vector<int> ordering;    ///< BPP methods: the permutation factored in (perm[new] = old)
};

/// The residual at or below which an answer is certified (Status::Converged), for every method:
/// 10 x the classification tolerance, at least 1e-14 (1e-8 by default).
ODE_BPP_API double certification_level(double tolerance);

/// Solves the problem with the chosen method from `start` and writes x (n entries), working in
/// `workspace` (one solve per workspace at a time; ode_bpp/workspace.h).
/// Never throws on bad input and never writes non-finite values into x.
ODE_BPP_API Result solve(const Problem& problem, const Options& options, Strided x, const Start& start,
                         Workspace& workspace);

/// The same in the calling thread's own workspace (one per thread, kept for the thread's
/// lifetime): safe from any number of threads at once, but not from inside a solve.
ODE_BPP_API Result solve(const Problem& problem, const Options& options, Strided x, const Start& start = {});

/// Convenience overload for contiguous x, in the calling thread's workspace.
ODE_BPP_API Result solve(const Problem& problem, const Options& options, double* x, const Start& start = {});

}  // namespace ode_bpp
