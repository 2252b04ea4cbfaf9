// bench/world/world_method.h: how a benchmark steps a world. Either dWorldStep with an MLCP
// solver, ODE's dWorldQuickStep with a number of iterations, or dWorldQuickStep routed to an MLCP
// solver (dWorldSetQuickStepMLCPSolver), named on the command line as
//     bpp | dantzig | <any registered MLCP solver>   dWorldStep with that solver
//     quickstep-<k>                                  dWorldQuickStep, k iterations
//     quickstep-<solver>                             dWorldQuickStep routed to that solver
#pragma once

#include <optional>
#include <string>

#include "scenes/scene.h"

namespace ode_bpp::bench {

struct WorldMethod {
    std::string name;             ///< as on the command line
    std::string solver = "bpp";   ///< dWorldStep's MLCP solver (QuickStep runs: "dantzig", unused)
    bool quickstep = false;       ///< steps with dWorldQuickStep
    int iterations = 0;           ///< QuickStep's iterations; 0 when routed
    std::string route;            ///< QuickStep routed to this MLCP solver; empty: QuickStep itself
    /// True when the world step calls an MLCP solver, whose statistics dWorldGetMLCPStats then has.
    bool uses_mlcp() const { return !quickstep || !route.empty(); }
};

/// The method of a name (see the header), or empty for a malformed QuickStep name
/// ("quickstep-0", "quickstep-"). MLCP solver names are checked when the world is made.
std::optional<WorldMethod> parse_world_method(const std::string& name);

/// base with the method's solver and stepper.
scenes::SceneParams params_for(const WorldMethod& method, scenes::SceneParams base);

/// Sets what the world needs beyond params_for: QuickStep's iterations or its routing.
/// Throws std::invalid_argument when the routed solver is not registered.
void configure_world(const WorldMethod& method, scenes::SceneWorld& world);

}  // namespace ode_bpp::bench
