// The outer update of the friction bounds in FrictionMode::Consistent (one value per friction
// row, in the driver's order).
#pragma once

#include <deque>
#include <vector>

namespace ode_bpp::pivoting {

/// Fixed-point iteration beta <- beta + d (t(beta) - beta) on the bounds beta, t = mu |x_normal|
/// from the last fixed-bound solve, d the damping. Its rate is linear, often only ~0.5 per
/// round, so while the residual f = t - beta keeps falling the step is Anderson-accelerated
/// (Walker & Ni 2011, depth kDepth): beta + d f - (dB + d dF) gamma, gamma minimizing
/// |f - dF gamma| over the last differences dB, dF of bounds and residuals. When |f| grows (an
/// index-set change broke the piecewise-linear model) the history is dropped and the plain
/// damped step is taken. Bounds never go negative.
class FrictionBoundUpdate {
public:
    static constexpr int kDepth = 5;
    explicit FrictionBoundUpdate(double damping) : damping_(damping) {}
    /// bound, target: current bounds and their targets (same size). Returns the next bounds.
    std::vector<double> next(const std::vector<double>& bound, const std::vector<double>& target);

private:
    double damping_;
    std::vector<double> last_bound_, last_residual_;
    std::deque<std::vector<double>> bound_differences_, residual_differences_;
};

}  // namespace ode_bpp::pivoting
