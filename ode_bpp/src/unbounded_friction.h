// Friction rows with mu = +inf ("never slips", legal ODE input) handed to the methods as the
// unbounded rows they are (docs/modelling.md, "Infinite friction"): a bound mu |x_n| that is
// infinite for any positive normal impulse bounds nothing, and a method that links friction to
// its normal (x_f = +-mu x_n, Lemke's split of the friction cone) cannot work with mu = inf.
//
// Index space: the caller's original row order; only findex, lo and hi change.
#pragma once

#include <limits>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp {

/// Row i is a friction row (findex >= 0, at or after nub) with mu = hi = +inf: the definition of
/// is_unbounded_friction_row (ode_bpp/residuals.h), inline for the loops that test every row.
inline bool unbounded_friction_row(const Problem& problem, int i) {
    return i >= problem.nub && problem.findex != nullptr && problem.findex[i] >= 0 &&
           problem.hi[i] == std::numeric_limits<double>::infinity();
}

/// True when some friction row (findex >= 0, at or after nub) has mu = hi = +inf. O(n).
bool has_unbounded_friction(const Problem& problem);

/// The storage of a view in which those rows are plain unbounded rows; reused from call to call.
class UnboundedFriction {
public:
    /// `problem` with every friction row of mu = +inf turned into an unbounded row (findex -1,
    /// lo = -inf, hi = +inf); the other rows, A and b as they are. Valid while this object and
    /// problem's arrays live and view() is not called again. Requires a validated problem. O(n).
    Problem view(const Problem& problem);

private:
    std::vector<int> findex_;
    std::vector<double> lo_, hi_;
};

}  // namespace ode_bpp
