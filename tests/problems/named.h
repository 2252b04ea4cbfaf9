// Named problems with a known story, used by the tests.
#pragma once

#include "problems/owned_problem.h"

namespace ode_bpp::problems {

/// docs/maths.md's example where Dantzig's frozen friction bound breaks the friction cone:
/// A = [[2,.3,.1],[.3,1.5,.2],[.1,.2,1.8]], b = (1, .9, -.2); row 0 a normal (lo = 0),
/// row 1 its friction row (mu = 0.5), row 2 unbounded (through infinite bounds, nub = 0).
OwnedProblem dantzig_friction_3x3();

/// Frozen friction's two solves part ways on a normal: row 0 a normal, row 1 its friction row
/// (mu = 1), row 2 a second normal that the friction row presses into contact. Held at 0, the
/// friction row leaves row 2 separating (at lo); at its bound mu x_0 = 1 it makes row 2 carry
/// 0.32. Answer: x = (0.92, 1, 0.32), states (free, at hi, free).
OwnedProblem friction_presses_a_second_contact();

/// A 3x3 SPD boxed problem on which Júdice-Pires block steps without Murty's safeguard, started
/// from all rows free, cycle forever; with the safeguard the loop terminates.
OwnedProblem block_pivoting_cycle();

/// Not positive definite: rows 0 and 1 duplicated (two identical contact normals with zero
/// CFM, as nearly redundant contacts produce in ODE), so A is singular positive semidefinite.
OwnedProblem duplicated_rows();

/// A 2-D box resting on two contacts (normal and friction row each, mu = 0.5, findex), A = J M^-1
/// J^T + cfm I with cfm = 1e-9 relative to its diagonal. The two friction rows act on the same
/// degree of freedom, so equal and opposite friction impulses are an internal force that only
/// cfm sees: with both friction rows at opposite bounds, their multipliers have the wrong sign by
/// about cfm |x|, within the 1e-9 classification tolerance, though the exact friction is 0.
/// Rows: 0 normal, 1 its friction, 2 normal, 3 its friction.
OwnedProblem opposed_friction_pair();

/// Two unbounded rows held by nearly opposite impulses of about 1e3 (A's leading block
/// [[1, -a], [-a, 1]], a = 1 - 1e-6, b = 1e-3 each) and a unilateral row 2 (lo = 0) that sees
/// their difference: A(2, .) = (1, -1, 2), b_2 = 1e-7. The exact answer has row 2 free at about
/// 1e-7. Started with row 2 at its bound, w_2 = -1e-7 is within the 1e-9 tolerance of the row's
/// scale (|A||x| ~ 2e3): an answer certified by its scaled residual (5e-11) but not relative to
/// |b| (1e-7), as heavy contacts on a pile give (docs/benchmarks.md, the pyramid's step 60).
OwnedProblem heavy_internal_impulse();

/// mu = +inf, ODE's "never slips" (legal input, dContact::surface.mu = dInfinity): chain_mlcp(6, 4,
/// 100, 1e-10) (27 rows: 5 ball joints and 4 ground contacts) with every friction coefficient
/// infinite. Such friction rows are unbounded (docs/modelling.md). Before they were, Consistent
/// friction linked x_f = +-inf x_n, skipped its Lemke stage and ended friction-not-consistent.
OwnedProblem never_slipping_chain();

}  // namespace ode_bpp::problems
