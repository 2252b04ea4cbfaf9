// bench/world/peak_memory.h: the process's peak resident memory, for O(rows) checks.
#pragma once

namespace ode_bpp::bench {

/// The largest resident set of this process so far [kB] (getrusage's ru_maxrss on Linux).
/// A benchmark reads it before building its world and after the run: the difference is the
/// peak the run added, whatever the program's own image and libraries weigh.
long peak_resident_kb();

}  // namespace ode_bpp::bench
