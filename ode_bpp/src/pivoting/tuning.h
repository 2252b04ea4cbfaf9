// The tuned constants of the BPP driver, in one place. Each states what it bounds; how it was
// measured and what the alternatives gave is in docs/tuning.md. Deltas are relative to
// max_i A_ii (an upper bound of max |A_ij| for SPD A).
#pragma once

namespace ode_bpp::pivoting::tuning {

// ---- regularization (regularization.h) -------------------------------------------------------
/// Breakdown ladder: first delta, growth per rung, last delta before A counts as not SPD.
constexpr double kFirstShift = 1e-12;
constexpr double kShiftGrowth = 100;
constexpr double kLastShift = 1e-6;
/// Up-front continuation (Tuning::continuation_stages): delta_k = start * span^(k / stages).
constexpr double kContinuationStart = 1e-4;
constexpr double kContinuationSpan = 1e-8;
/// Rescue continuation: first delta; the most regularization tried when even that stalls.
constexpr double kRescueStart = 1e-4;
constexpr double kRescueCeiling = 0.1;
/// delta_{k+1} = delta_k * ratio: the first ratio, its floor (a stage converging in one step
/// squares it) and the ratio past which a stalled rescue gives up.
constexpr double kRescueFirstRatio = 0.1;
constexpr double kRescueMinRatio = 1e-6;
constexpr double kRescueMaxRatio = 0.9;
/// Below this delta the next stage is the target itself.
constexpr double kRescueFloor = 1e-12;
/// A rescue stage stalls when its least count of infeasible rows has not fallen for
/// Tuning::murty_after + this many steps (Murty's phase gets that many single pivots), or at
/// once when its block steps revisit an index set.
constexpr int kMurtyPatience = 2;

// ---- the active set (active_set.h) ----------------------------------------------------------
/// Steps of the active-set method per row of the island, plus kActiveSetStepsExtra, before the
/// fixed-bound solve goes on to the rescue: the method terminates finitely anyway; this bounds
/// what one island may cost.
constexpr int kActiveSetStepsPerRow = 10;
constexpr int kActiveSetStepsExtra = 50;
/// Face minimizers an updated free-set factor may steer before its accuracy is checked (it always
/// is where its answer would be accepted): active_set.cpp's wants_accuracy_check.
constexpr int kActiveSetUncheckedMinima = 4;

// ---- friction (friction_policy.h) --------------------------------------------------------------
/// A linked solve (Consistent friction) may take this many times Options::max_pivots.
constexpr int kLinkedBudgetFactor = 1;
/// Lemke's method gets this many complementary pivots per LCP variable (plus 10).
constexpr int kLemkePivotsPerVariable = 10;
/// Covering vectors the dense Lemke stage tries when a path ends on a ray (each with a budget
/// of its own).
constexpr int kLemkeAttempts = 5;
/// The same for the sparse stage, whose attempts share one budget (kSparseLemkeMaxPivots), so
/// that a path ending on a ray early costs little: a 291-row cannon island (cond 4.9e9) saw
/// rays from the guessed basis and four covering vectors and was solved by the fifth, then
/// certified at 4.8e-11 (docs/tuning.md).
constexpr int kSparseLemkeAttempts = 8;
/// Largest friction LCP (variables) and island (rows) the dense Lemke stage takes on.
constexpr int kLemkeMaxVariables = 1000;
constexpr int kLemkeMaxRows = 1500;
/// Above those, the sparse Lemke stage (sparse_lemke.h, islands without unbounded rows) takes
/// friction LCPs of up to this many variables. Its pivot costs one sparse solve (0.1-0.5 ms at
/// 1,000-2,700 variables on the shared machine), and its paths on piles are long (1.5-27 pivots
/// per variable), so its cost is bounded by a pivot budget for all its covering vectors
/// together: this many per variable, and at most kSparseLemkeMaxPivots (up to about 20 s).
constexpr int kSparseLemkeMaxVariables = 3000;
constexpr int kSparseLemkePivotsPerVariable = 40;
constexpr int kSparseLemkeMaxPivots = 50000;
/// From this many variables on, an island the sparse stage can take (no unbounded rows: every
/// pile) goes to it even where the dense stage would fit: the dense stage forms M densely and
/// pays O(N^2) per pivot, the sparse one a sparse solve. A 357-row bin island (990 variables)
/// took 3.6 s dense and 0.15 s sparse; at 161-217 variables 0.25-0.8 times the dense time, at
/// 105-133 within 10 % of it (docs/tuning.md).
constexpr int kSparseLemkeFromVariables = 150;

// ---- the pivoting loop (pivot_loop.h) ----------------------------------------------------------
/// Polish of a converged index set: rounds, and pivot steps per round.
constexpr int kPolishRounds = 2;
constexpr int kPolishSteps = 6;

}  // namespace ode_bpp::pivoting::tuning
