// The shifts A + delta I that one fixed-bound solve works on (docs/maths.md: what makes BPP
// converge inside ODE), decided in one place:
//  - the target: the problem itself (delta 0), unless a Cholesky breakdown showed A not
//    numerically positive definite; then the next rung of a ladder 1e-12 .. 1e-6 max_i A_ii,
//    x100 per rung, and the answer reports the delta it solves (Fallback::Regularized);
//  - the rescue: where block pivoting on the target does not converge within
//    Tuning::rescue_after steps, a continuation on A + delta I with delta falling from 1e-4
//    max_i A_ii to the target, as fast as the index set can follow (RescueSchedule);
//  - the optional up-front continuation (Tuning::continuation_stages): delta_k falling
//    geometrically from 1e-4 to 1e-12 max_i A_ii before the first solve.
// Every delta is relative to max_i A_ii, an upper bound of max |A_ij| for SPD A.
#pragma once

namespace ode_bpp::pivoting {

class Regularization {
public:
    explicit Regularization(double max_diag) : max_diag_(max_diag) {}

    /// delta of the problem the answer solves: 0 unless raise_target() was called.
    double target() const { return target_; }
    /// After a breakdown at target(): the next rung. False once past the last one, or where the
    /// ladder cannot rise (a max diag so small, e.g. subnormal, that the first rung rounds to 0:
    /// without this a breakdown there retried at shift 0 forever, found by fuzz_solve).
    bool raise_target();

    /// The up-front continuation's delta of stage k of `stages` (k < stages).
    double continuation(int k, int stages) const;

    double max_diag() const { return max_diag_; }

private:
    double max_diag_;
    double target_ = 0;
};

/// The deltas of one rescue continuation, adapted to how the stages go. A stage solves with A +
/// delta() I from the index set of the last converged stage (the first from the warm start):
/// nearly redundant contact rows make A_FF nearly singular at the target, so block pivots there
/// swing x wildly; delta bounds the swing and shrinks only as fast as the index set can follow.
/// On the captured ODE frames (winch, forklift, parkour at CFM 1e-10 and 6e-7) block pivoting
/// converged on A + 1e-4 max diag I in 3-8 steps where the target cycled (x jumping by 1e4-1e6).
class RescueSchedule {
public:
    explicit RescueSchedule(const Regularization& r);

    double delta() const { return delta_; }
    /// True when the current stage is the target itself (its convergence ends the rescue).
    bool at_target() const { return delta_ == target_; }
    /// The stage converged in `steps` steps: go on to a smaller delta. A stage that converged in
    /// one step squares the ratio of the next (down to a floor).
    void converged(int steps);
    /// The stage stalled: retry from the last converged delta with a milder step (or, before any
    /// converged, with more regularization). False when the rescue should give up.
    bool stalled();

private:
    void next_delta();

    double max_diag_, target_;
    double delta_;
    double accepted_ = -1;  ///< delta of the last converged stage (-1: none yet)
    double ratio_;          ///< delta_{k+1} = accepted * ratio
};

}  // namespace ode_bpp::pivoting
