// ode_bpp/ode.h: ode-bpp inside ODE's world step.
//
// Linking libode_bpp registers its solvers with the patched ODE's MLCP registry
// (<ode/mlcp.h>) when the library loads: "bpp", "bpp-sky", "bpp-down", "bpp-chol" and "pgs"
// join ODE's built-in "dantzig". A world then switches with one call:
//
//     ode_bpp_use(world, "bpp");            // or dWorldSetMLCPSolver(world, "bpp")
//
// and an unchanged program switches with the environment: ODE_LCP_SOLVER=bpp.
#pragma once

#include "ode_bpp/export.h"

#include <ode/ode.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Registers ode-bpp's solvers with ODE (idempotent; already done when the library loads).
/// Returns the number of solvers registered.
ODE_BPP_API int ode_bpp_register_solvers(void);

/// Registers ode-bpp's solver `method` (a name of ode_bpp::method_names(), e.g. "bpp") a second
/// time, as `as_name`, in ODE's dense form: the world step then forms its m x m A and the solver
/// reads it, as before the sparse form existed. For comparing the two forms (they give the same
/// answers bit for bit, ode/assemble.h); never faster. Returns 1 on success, 0 for an unknown
/// method or a name ODE refuses.
ODE_BPP_API int ode_bpp_register_dense_form(const char* method, const char* as_name);

/// Selects the named solver for this world (registering first). Returns 1 on success, 0 for an
/// unknown name (the world's choice is then unchanged). A null name selects the process's
/// default, as dWorldSetMLCPSolver does.
ODE_BPP_API int ode_bpp_use(dWorldID world, const char* solver_name);

#ifdef __cplusplus
}

#include <string>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp {

/// Per-world settings of the hooked solver. The method is the one named in dWorldSetMLCPSolver;
/// the rest is taken from here.
struct WorldSettings {
    Options options;                ///< friction mode, budgets, tolerances (method is ignored)
    bool warm_start = true;         ///< start each island from the previous step's index sets
};

/// Replaces the settings of a world (thread-safe). Worlds without settings use the defaults
/// with one exception: Options::record_steps is false (no Result::pivoting.tight_per_step in
/// last_island_result, which would cost every island an allocation). Settings a caller passes
/// here are used as given, so WorldSettings{} records the steps again.
ODE_BPP_API void set_world_settings(dWorldID world, const WorldSettings& settings);
/// The settings of a world: those last set, or the hook's defaults (record_steps false).
ODE_BPP_API WorldSettings world_settings(dWorldID world);

/// The full Result of the last island that the hook solved in this world (for demos and tests:
/// residuals, pivots, tight count, fallback). A default-constructed Result if none.
ODE_BPP_API Result last_island_result(dWorldID world);

/// The warm start the hook solved the calling thread's latest island from: the index set it
/// recalled (empty when it knew none of the island's rows) and the ordering it handed to the solve
/// (the one remembered for the island's structure; empty when the solver chose afresh). ODE calls
/// the observer's "after" call on the thread that solved the island, so capture reads it there
/// (ode_bpp/io.h, set_start_metadata); it holds until that thread's next island.
ODE_BPP_API Start last_island_start();

/// The island's A as a dense m x m row-major array holding the lower triangle (diagonal included;
/// the upper triangle zero), whichever form ODE handed over: read from the dense A, or assembled
/// from J, J M^-1 and the CFM in the sparse form. O(m^2): for capture and diagnostics, never
/// on the solve path. Valid in the observer's "before" call. A: out, resized to m*m; all zero
/// for an island that carries neither form.
ODE_BPP_API void island_matrix_lower(const dMLCP& island, std::vector<double>& A);

/// Forgets the warm-start state and settings of a world. dWorldDestroy does this itself (the
/// hook listens for it, <ode/mlcp.h> dAddMLCPWorldDestroyedListener), so that a world created
/// later at the same address starts afresh; calling it earlier is harmless.
ODE_BPP_API void forget_world(dWorldID world);

}  // namespace ode_bpp
#endif
