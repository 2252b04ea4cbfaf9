// ODE's classic demos, ported as Scenes: each must meet its own physical success criterion
// (stack stands, chain stays connected, buggy drives, wall falls, motors hold their stops)
// with ODE's Dantzig and with the solver under test, and keep every body's state finite.
#include <gtest/gtest.h>
#include <ode/mlcp.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "scenes/classic.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

/// The solver under test: $ODE_BPP_SCENE_SOLVER, "bpp" by default.
std::string solver_under_test() {
    const char* name = std::getenv("ODE_BPP_SCENE_SOLVER");
    return (name && *name) ? name : "bpp";
}

std::vector<std::string> classic_names() {
    std::vector<std::string> names;
    for (const auto& [name, factory] : classic_scenes()) names.push_back(name);
    return names;
}

std::unique_ptr<Scene> make_classic(const std::string& name) {
    for (const auto& [scene_name, factory] : classic_scenes())
        if (scene_name == name) return factory();
    return nullptr;
}

bool finite3(const dReal* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

/// Name of the first body whose position, orientation or velocity is not finite, or "".
std::string first_non_finite_body(const SceneWorld& w) {
    for (size_t i = 0; i < w.bodies().size(); ++i) {
        dBodyID b = w.bodies()[i];
        const dReal* q = dBodyGetQuaternion(b);
        const bool ok = finite3(dBodyGetPosition(b)) && finite3(dBodyGetLinearVel(b)) &&
                        finite3(dBodyGetAngularVel(b)) && std::isfinite(q[0]) && finite3(q + 1);
        if (!ok) return "body " + std::to_string(i);
    }
    return "";
}

/// Builds the scene with the given solver and steps it for `seconds`, stopping at the first
/// failed step. Returns the number of steps that succeeded.
long run_scene(Scene& scene, SceneWorld& w, double seconds) {
    scene.build(w);
    const long steps = std::lround(seconds / w.params().step);
    for (long i = 0; i < steps; ++i) {
        scene.control(w, w.time());
        if (!w.step()) return i;
    }
    return steps;
}

void expect_scene_succeeds(const std::string& name, const std::string& solver) {
    if (!is_solver_registered(solver)) GTEST_SKIP() << "solver '" << solver << "' is not registered ("
                                                    << dListMLCPSolvers() << ")";
    std::unique_ptr<Scene> scene = make_classic(name);
    ASSERT_NE(scene, nullptr);
    SceneParams params;
    params.solver = solver;
    params.seconds = scene->default_seconds();
    SceneWorld w(params);
    ASSERT_EQ(std::string(dWorldGetMLCPSolver(w.world())), solver);

    const long steps = std::lround(params.seconds / params.step);
    EXPECT_EQ(run_scene(*scene, w, params.seconds), steps) << "a world step failed or a body left the reals";
    EXPECT_EQ(first_non_finite_body(w), "");
    const SuccessReport report = scene->success(w);
    EXPECT_TRUE(report.ok) << name << " with " << solver << ": " << report.detail;
    ::testing::Test::RecordProperty("detail", report.detail);

    // Islands the solver gave up on were answered by ODE's Dantzig: the criterion above then
    // partly judges Dantzig, so say how many.
    dMLCPStepStats total{};
    if (dWorldGetMLCPStats(w.world(), nullptr, &total)) {
        ::testing::Test::RecordProperty("islands_answered_by_dantzig_fallback", total.failures);
        if (solver != "dantzig" && total.failures > 0)
            std::printf("note: %s with %s: %ld island solves fell back to ODE's Dantzig\n", name.c_str(),
                        solver.c_str(), static_cast<long>(total.failures));
    }
}

class ClassicScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ClassicScene, MeetsItsCriterionWithDantzig) { expect_scene_succeeds(GetParam(), "dantzig"); }

TEST_P(ClassicScene, MeetsItsCriterionWithSolverUnderTest) { expect_scene_succeeds(GetParam(), solver_under_test()); }

TEST_P(ClassicScene, DescribesItself) {
    std::unique_ptr<Scene> scene = make_classic(GetParam());
    ASSERT_NE(scene, nullptr);
    EXPECT_EQ(scene->name(), GetParam());
    EXPECT_FALSE(scene->description().empty());
    EXPECT_GT(scene->default_seconds(), 0.0);
    EXPECT_NE(make_scene(GetParam()), nullptr) << "the registry does not list " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Classic, ClassicScene, ::testing::ValuesIn(classic_names()),
                         [](const auto& info) { return info.param; });

// The criteria must be able to fail: scenes whose criterion needs motion are not yet
// successful when nothing has happened...
TEST(ClassicCriteria, RejectAnUnrunScene) {
    for (const std::string name : {"chain", "buggy", "cannon", "motors", "islands"}) {
        std::unique_ptr<Scene> scene = make_classic(name);
        ASSERT_NE(scene, nullptr) << name;
        SceneParams params;
        params.solver = "dantzig";
        SceneWorld w(params);
        scene->build(w);
        EXPECT_FALSE(scene->success(w).ok) << name << ": " << scene->success(w).detail;
    }
}

// ...and a stack shoved off the place where it was built does not count as standing.
TEST(ClassicCriteria, RejectAShovedStack) {
    std::unique_ptr<Scene> scene = make_classic("boxstack");
    ASSERT_NE(scene, nullptr);
    SceneParams params;
    params.solver = "dantzig";
    SceneWorld w(params);
    scene->build(w);
    for (dBodyID b : w.bodies()) dBodySetLinearVel(b, 3.0, 0, 0);  // every box shoved sideways
    const long steps = std::lround(1.0 / params.step);
    for (long i = 0; i < steps; ++i) ASSERT_TRUE(w.step());
    EXPECT_FALSE(scene->success(w).ok) << scene->success(w).detail;
}

// ...and marbles that do not roll (stopped after the build) do not pass as rolling.
TEST(ClassicCriteria, RejectStoppedMarbles) {
    std::unique_ptr<Scene> scene = make_classic("islands");
    ASSERT_NE(scene, nullptr);
    SceneParams params;
    params.solver = "dantzig";
    SceneWorld w(params);
    scene->build(w);
    for (dBodyID b : w.bodies()) {
        dBodySetLinearVel(b, 0, 0, 0);
        dBodySetAngularVel(b, 0, 0, 0);
    }
    const long steps = std::lround(1.0 / params.step);
    for (long i = 0; i < steps; ++i) {
        scene->control(w, w.time());
        ASSERT_TRUE(w.step());
    }
    EXPECT_FALSE(scene->success(w).ok) << scene->success(w).detail;
}

}  // namespace
}  // namespace ode_bpp::scenes
