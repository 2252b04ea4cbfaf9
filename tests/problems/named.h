// Named problems with a known story, used by the tests.
#pragma once

#include "problems/owned_problem.h"

namespace ode_bpp::problems {

/// NOTES' example where Dantzig's frozen friction bound breaks the friction cone:
/// A = [[2,.3,.1],[.3,1.5,.2],[.1,.2,1.8]], b = (1, .9, -.2); row 0 a normal (lo = 0),
/// row 1 its friction row (mu = 0.5), row 2 unbounded (through infinite bounds, nub = 0).
OwnedProblem dantzig_friction_3x3();

/// A 3x3 SPD boxed problem on which Júdice-Pires block steps without Murty's safeguard, started
/// from all rows free, cycle forever; with the safeguard the loop terminates.
OwnedProblem block_pivoting_cycle();

/// Not positive definite: rows 0 and 1 duplicated (two identical contact normals with zero
/// CFM, as nearly redundant contacts produce in ODE), so A is singular positive semidefinite.
OwnedProblem duplicated_rows();

}  // namespace ode_bpp::problems
