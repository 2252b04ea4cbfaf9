// demos/scenes/sweep_run.h: one stability run of a sweep scene with one method, measured and
// classified (held / drifted / exploded / solver error). Shared by bench/stability and the
// stability tests.
//
// Tolerances (docs/stability.md): a constraint of ODE with CFM and ERP is a spring of stiffness
// ERP / (h CFM), so under the largest carried weight W it yields by W h CFM / ERP. The drift
// tolerance of a run is
//     tau = 0.02 ell + 0.001 m + 2 W h CFM / ERP
// (ell: the scene's link length; 0.001 m: the contact surface layer); joint errors and contact
// penetrations above tau are drift, and each placement check of the scene is widened by tau per
// compliant constraint in series.
#pragma once

#include <string>
#include <vector>

#include "ode_bpp/solver.h"
#include "scenes/sweep_scenes.h"

namespace ode_bpp::scenes {

enum class Outcome {
    Held,         ///< finite, within every tolerance, no solver error
    Drifted,      ///< finite, but a joint error, a penetration or a placement beyond tolerance
    Exploded,     ///< a non-finite state, or an energy gain above the scene's reference energy
    SolverError,  ///< physics held, but the solver reported trouble (see RunResult counters)
};
const char* to_string(Outcome o);

/// The methods of the sweeps: the MLCP solver names of dWorldStep, and "quickstep" (ODE's
/// dWorldQuickStep, world level).
std::vector<std::string> sweep_methods();

struct RunSpec {
    SweepSpec scene;
    std::string method = "bpp";      ///< a registered MLCP solver name, or "quickstep"
    int iterations = 35;             ///< pgs sweeps or quickstep iterations
    double step = 1.0 / 60.0;        ///< h [s]
    double seconds = 5;              ///< simulated time [s]
    double cfm = 1e-10;              ///< world and contact CFM
    double erp = 0.2;
    double mu = 1.0;
    /// Solver options for the ode-bpp methods (method and pgs_iterations are overridden).
    Options options;
    /// ode-bpp methods: start each island from the previous step's index sets (the hook's
    /// default); false makes every solve start cold, all rows free.
    bool warm_start = true;
};

struct RunResult {
    Outcome outcome = Outcome::Held;
    std::string cause;               ///< why it is not Held (empty when Held)
    long steps = 0;                  ///< steps taken (a run stops at the first non-finite state)
    double tolerance = 0;            ///< tau [m], see the header comment
    double max_joint_error = 0;      ///< [m], over tracked joints and steps
    double max_penetration = 0;      ///< [m], deepest contact seen after a step
    double worst_placement = 0;      ///< [m], largest excursion out of a placement interval
    /// Largest gain of total energy (kinetic + potential) over its start, divided by the
    /// reference g * (sum of masses) * scene height (1: enough to lift everything by the scene).
    double energy_drift = 0;
    double final_slide = 0;          ///< SlidingPair: the heavy box's x travel [m]; else 0
    // solver trouble, counted over islands (ode-bpp methods) or messages (Dantzig)
    int lcp_internal_errors = 0;     ///< ODE's Dantzig "LCP internal error" messages
    int islands = 0;                 ///< islands solved through the MLCP hook
    int failures = 0;                ///< islands handed back to ODE's Dantzig by the world step
    int fallbacks = 0;               ///< islands answered through a fallback of the solver
    int max_iterations = 0;          ///< ode-bpp islands that ran out of pivot budget
    int not_spd = 0;                 ///< ode-bpp islands whose A_FF broke down even regularized
    int regularized = 0;             ///< ode-bpp islands answered by A + delta I
    int friction_not_consistent = 0; ///< consistent friction mode: rounds ran out
    long murty_pivots = 0;           ///< Murty single pivots, summed
    long rescues = 0;                ///< fixed-bound solves finished by the rescue continuation
    long friction_rounds = 0;        ///< consistent friction mode: outer bound updates, summed
    /// Largest friction-cone excess max(0, |x_t| - mu |x_n|) over friction rows and islands,
    /// divided by the island's max |x|, measured on ODE's arrays after an ode-bpp solve (0 for
    /// "dantzig", "quickstep" and islands handed to ODE's Dantzig: it rewrites the bounds).
    /// Frozen friction may exceed the cone by design (Dantzig's semantics: bounds from the
    /// normals of a first solve); consistent friction must not, unless flagged.
    double friction_excess = 0;
    /// Islands whose friction excess is above 1e-6 although the solver reported no
    /// FrictionNotConsistent status: an undocumented failure.
    int friction_unflagged = 0;
    long pivots = 0;                 ///< pivot steps, summed (PGS: sweeps)
    double seconds_wall = 0;         ///< wall time of the run (for the report only, never tested)
};

/// Builds spec.scene in a fresh world, runs it for spec.seconds with spec.method and measures it.
/// Throws std::invalid_argument for an unknown method. While it runs, ODE's message handler is
/// replaced by one that counts "LCP internal error" messages (restored afterwards).
RunResult run_sweep(const RunSpec& spec);

}  // namespace ode_bpp::scenes
