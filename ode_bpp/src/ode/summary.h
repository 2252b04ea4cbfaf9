// The process summary line that ode-bpp-run promises (docs/launcher.md): one line on stderr, and
// appended to ODE_BPP_SUMMARY_FILE, when a process that stepped a world ends, whether by exit()
// or by SIGINT or SIGTERM.
//
//   ode-bpp: solver=bpp steps=300 islands=290 rows=13470 pivots=697 fallbacks=0 failures=0
//            solve_seconds=0.053800[ quickstep_steps=N][ (note)][ (ended by SIGTERM)]
//
// ODE_BPP_SUMMARY (read once, when libode_bpp loads): unset, empty or "0": no line; "1": a line
// from every process that made a world step (dWorldStep, or dWorldQuickStep routed or not);
// "always": a line from every process. ODE_BPP_SUMMARY_FILE: the file the line is appended to.
// Both are read with secure_getenv (ignored in setuid and setgid programs).
#pragma once

#include <cstddef>

#include "ode_bpp/export.h"

namespace ode_bpp::summary {

// The handlers of SIGINT and SIGTERM are installed when libode_bpp loads, over the default
// disposition only (a program's own handler, or an inherited SIG_IGN, stays). ode-bpp-run's
// preload (tools/run) moves SIGINT's to the program's first world step instead, and
// counts the quick steps that QuickStep solved; the functions below are its interface, exported
// from libode_bpp.so for it (ODE_BPP_API) though not part of the public headers.

/// Counts one dWorldQuickStep that ODE's QuickStep iterations solved (not routed to an MLCP
/// solver): the summary reports them as quickstep_steps. Lock-free.
ODE_BPP_API void count_unrouted_quickstep();

/// Takes back the SIGINT handler installed at load (if still ours) and installs it at the first
/// note_world_step() instead: CPython turns SIGINT into KeyboardInterrupt only where it finds the
/// default disposition when it starts (docs/launcher.md), after any preloaded library has loaded.
ODE_BPP_API void arm_sigint_at_first_step();

/// Called at every world step the program makes; lock-free after the first call.
ODE_BPP_API void note_world_step();

/// What the summary knows at this moment; every field lock-free to read.
struct Totals {
    bool any_island = false;            ///< an island with constraints was solved by an MLCP solver
    long long steps = 0;                ///< world steps through the MLCP solvers (routed quick steps too)
    long long islands = 0, rows = 0, pivots = 0, fallbacks = 0, failures = 0;
    double solve_seconds = 0;
    long long quickstep_steps = 0;      ///< dWorldQuickStep steps solved by QuickStep's iterations
    const char* solver = nullptr;       ///< the solver of the latest island; nullptr if none
};
ODE_BPP_API Totals current_totals();

/// Writes the summary line of `t` into `out` (at most `size` bytes, NUL-terminated) and returns
/// its length. signal_number > 0 adds "(ended by SIGINT)" or the like. Async-signal-safe: no
/// allocation, no locale, no stdio.
ODE_BPP_API std::size_t format_line(const Totals& t, int signal_number, char* out, std::size_t size);

}  // namespace ode_bpp::summary
