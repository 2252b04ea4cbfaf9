// The ways an island reaches a solver in the patched world step (<ode/mlcp.h>, API 3), each checked
// against a second world stepped the reference way from the same start:
//  - a sparse-form solver that fails: ODE builds the dense A from J for its Dantzig, and the world
//    moves exactly as one stepped with "dantzig" (counted in dMLCPStepStats::dense_builds);
//  - dWorldQuickStep routed to an MLCP solver: exactly dWorldStep with that solver; unrouted it is
//    QuickStep again and no MLCP is solved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "ode_bpp/ode.h"
#include "scenes/scene.h"
#include "scene_test_support.h"

namespace ode_bpp::scenes {
namespace {

constexpr const char* kFailing = "test-failing-sparse";
constexpr int kSteps = 60;

dMLCPStatus always_fail(const dMLCP*, dMLCPIslandStats*, void*) { return dMLCPFailed; }

struct World {
    World(const std::string& scene_name, const std::string& solver, const std::string& stepper = "step")
        : scene(make_scene(scene_name)), world(params(solver, stepper)) {
        scene->build(world);
    }
    static SceneParams params(const std::string& solver, const std::string& stepper) {
        SceneParams p;
        p.solver = solver;
        p.stepper = stepper;
        return p;
    }
    bool step() {
        scene->control(world, world.time());
        return world.step();
    }
    dMLCPStepStats total() const {
        dMLCPStepStats t{};
        dWorldGetMLCPStats(world.world(), nullptr, &t);
        return t;
    }
    std::unique_ptr<Scene> scene;
    SceneWorld world;
};

/// Steps both worlds kSteps times and returns the largest body position difference seen.
double step_together(World& a, World& b) {
    double worst = 0;
    for (int s = 0; s < kSteps; ++s) {
        EXPECT_TRUE(a.step());
        EXPECT_TRUE(b.step());
        worst = std::max(worst, largest_position_difference(a.world, b.world));
    }
    return worst;
}

TEST(WorldStepRoutes, AFailedSparseSolveIsAnsweredByDantzigOnADenseABuiltFromJ) {
    ASSERT_EQ(dRegisterMLCPSolverEx(kFailing, &always_fail, nullptr, dMLCP_API_VERSION, dMLCP_SPARSE), 1);
    World failing("chain", kFailing), dantzig("chain", "dantzig");
    EXPECT_EQ(step_together(failing, dantzig), 0.0) << "ODE's Dantzig on the A built from J must be the dense step's";
    const dMLCPStepStats t = failing.total();
    EXPECT_GT(t.islands, 0);
    EXPECT_EQ(t.failures, t.islands);
    EXPECT_EQ(t.dense_builds, t.islands) << "every failed island came in the sparse form";
    EXPECT_EQ(dantzig.total().dense_builds, 0);
}

TEST(WorldStepRoutes, RegistrationRefusesUnknownFlags) {
    EXPECT_EQ(dRegisterMLCPSolverEx("test-bad-flags", &always_fail, nullptr, dMLCP_API_VERSION, 0x80u), 0);
    EXPECT_EQ(dRegisterMLCPSolverEx("test-old-api", &always_fail, nullptr, dMLCP_API_VERSION - 1, 0), 0);
}

TEST(WorldStepRoutes, ARoutedQuickStepIsTheExactStepWithThatSolver) {
    World routed("crane", "bpp", "quickstep"), exact("crane", "bpp");
    ASSERT_EQ(dWorldSetQuickStepMLCPSolver(routed.world.world(), "bpp"), 1);
    EXPECT_STREQ(dWorldGetQuickStepMLCPSolver(routed.world.world()), "bpp");
    EXPECT_EQ(step_together(routed, exact), 0.0);
    const dMLCPStepStats t = routed.total();
    EXPECT_GT(t.islands, 0);
    EXPECT_STREQ(t.solver, "bpp");
    EXPECT_EQ(t.steps, kSteps);
}

TEST(WorldStepRoutes, AnUnroutedQuickStepSolvesNoMLCP) {
    World quick("crane", "bpp", "quickstep");
    ASSERT_EQ(dWorldSetQuickStepMLCPSolver(quick.world.world(), "bpp"), 1);
    ASSERT_EQ(dWorldSetQuickStepMLCPSolver(quick.world.world(), nullptr), 1);
    EXPECT_EQ(dWorldGetQuickStepMLCPSolver(quick.world.world()), nullptr);
    for (int s = 0; s < 5; ++s) ASSERT_TRUE(quick.step());
    EXPECT_EQ(quick.total().islands, 0);
    EXPECT_EQ(dWorldSetQuickStepMLCPSolver(quick.world.world(), "no-such-solver"), 0);
}

}  // namespace
}  // namespace ode_bpp::scenes
