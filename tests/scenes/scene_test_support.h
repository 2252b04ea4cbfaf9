// Helpers shared by the scene tests: running a scene by name and judging what it left behind.
#pragma once

#include <gtest/gtest.h>
#include <ode/mlcp.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include "scenes/scene.h"

namespace ode_bpp::scenes {

/// Largest difference [m] of any body's position between two worlds built from the same scene
/// (bodies compared in creation order).
inline double largest_position_difference(const SceneWorld& a, const SceneWorld& b) {
    double worst = 0;
    for (std::size_t k = 0; k < a.bodies().size() && k < b.bodies().size(); ++k) {
        const dReal *pa = dBodyGetPosition(a.bodies()[k]), *pb = dBodyGetPosition(b.bodies()[k]);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, static_cast<double>(std::abs(pa[c] - pb[c])));
    }
    return worst;
}

/// The solver under test: $ODE_BPP_SCENE_SOLVER, "bpp" by default.
inline std::string solver_under_test() {
    const char* name = std::getenv("ODE_BPP_SCENE_SOLVER");
    return (name && *name) ? name : "bpp";
}

inline bool finite3(const dReal* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

/// Name of the first body whose position, orientation or velocity is not finite, or "".
inline std::string first_non_finite_body(const SceneWorld& w) {
    for (std::size_t i = 0; i < w.bodies().size(); ++i) {
        dBodyID b = w.bodies()[i];
        const dReal* q = dBodyGetQuaternion(b);
        const bool ok = finite3(dBodyGetPosition(b)) && finite3(dBodyGetLinearVel(b)) &&
                        finite3(dBodyGetAngularVel(b)) && std::isfinite(q[0]) && finite3(q + 1);
        if (!ok) return "body " + std::to_string(i);
    }
    return "";
}

/// A scene built into its own world, not yet stepped (for tests of the criteria).
struct BuiltScene {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<SceneWorld> world;
    SuccessReport success() const { return scene->success(*world); }
};

/// Builds the scene `name` (null members for an unknown name) with `solver`.
inline BuiltScene build_scene(const std::string& name, const std::string& solver = "dantzig") {
    BuiltScene b;
    b.scene = make_scene(name);
    if (!b.scene) return b;
    SceneParams params;
    params.solver = solver;
    b.world = std::make_unique<SceneWorld>(params);
    b.scene->build(*b.world);
    return b;
}

/// What one run of a scene did.
struct SceneOutcome {
    long steps = 0;               ///< asked for
    long steps_done = 0;          ///< done before a world step failed (== steps when none did)
    std::string non_finite_body;  ///< first_non_finite_body() at the end
    SuccessReport success;
    dMLCPStepStats total{};       ///< ODE's statistics over the run
    double slowest_step_ms = 0;   ///< wall time of the slowest world step (for the record only)
};

/// Builds the scene `name` with `solver` and ODE's defaults otherwise, and steps it for `seconds`
/// (stopping at the first failed step).
inline SceneOutcome run_scene(const std::string& name, const std::string& solver, double seconds) {
    SceneOutcome out;
    std::unique_ptr<Scene> scene = make_scene(name);
    if (!scene) {
        out.success.detail = "no scene named " + name;
        return out;
    }
    SceneParams params;
    params.solver = solver;
    params.seconds = seconds;
    SceneWorld w(params);
    scene->build(w);
    out.steps = std::lround(seconds / params.step);
    dMLCPStepStats last{};
    for (; out.steps_done < out.steps; ++out.steps_done) {
        scene->control(w, w.time());
        if (!w.step()) break;
        if (dWorldGetMLCPStats(w.world(), &last, nullptr))
            out.slowest_step_ms = std::max(out.slowest_step_ms, 1e3 * last.seconds);
    }
    out.non_finite_body = first_non_finite_body(w);
    out.success = scene->success(w);
    dWorldGetMLCPStats(w.world(), nullptr, &out.total);
    return out;
}

/// A run of `name` with `solver` for the scene's own time must step to the end, keep every body
/// finite and meet the scene's criterion (skipped when no such solver is registered). Records the
/// islands that ODE's Dantzig answered (the criterion then partly judges Dantzig); the outcome
/// goes to `outcome` if given.
inline void expect_scene_succeeds(const std::string& name, const std::string& solver, SceneOutcome* outcome = nullptr) {
    if (!is_solver_registered(solver)) GTEST_SKIP() << "solver '" << solver << "' is not registered (" << dListMLCPSolvers() << ")";
    const SceneOutcome out = run_scene(name, solver, make_scene(name)->default_seconds());
    EXPECT_EQ(out.steps_done, out.steps) << "a world step failed or a body left the reals";
    EXPECT_EQ(out.non_finite_body, "");
    EXPECT_TRUE(out.success.ok) << name << " with " << solver << ": " << out.success.detail;
    ::testing::Test::RecordProperty("detail", out.success.detail);
    ::testing::Test::RecordProperty("islands_answered_by_dantzig_fallback", static_cast<int>(out.total.failures));
    if (solver != "dantzig" && out.total.failures > 0)
        std::printf("note: %s with %s: %ld island solves fell back to ODE's Dantzig\n", name.c_str(), solver.c_str(),
                    static_cast<long>(out.total.failures));
    if (outcome != nullptr) *outcome = out;
}

}  // namespace ode_bpp::scenes
