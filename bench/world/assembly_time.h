// bench/world/assembly_time.h: the least time to form an island's A = J M^-1 J^T + diag(cfm)
// from its Jacobian (ode/assemble.h), the work that the physical limit
// (bench/report/physical_limit.h) leaves out and that no solver handed ODE's sparse form can.
#pragma once

#include <ode/mlcp.h>

namespace ode_bpp::bench {

/// Median over `repeat` rounds of the time [us] of ode::assemble_rows on the island with its
/// pattern already known (the path the world step takes while an island keeps its structure:
/// values written in place, nothing listed or sorted), in the island's own row order. The first
/// assembly, which finds the pattern, is not timed. Each round assembles enough times to lie
/// well above the clock's resolution and reports the time per assembly. NaN when the island is
/// not in the sparse form.
double assembly_time_us(const dMLCP& island, int repeat);

}  // namespace ode_bpp::bench
