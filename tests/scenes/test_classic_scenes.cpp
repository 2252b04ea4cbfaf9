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
#include "scene_test_support.h"

namespace ode_bpp::scenes {
namespace {

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
        const BuiltScene b = build_scene(name);
        ASSERT_NE(b.scene, nullptr) << name;
        EXPECT_FALSE(b.success().ok) << name << ": " << b.success().detail;
    }
}

// ...and a stack shoved off the place where it was built does not count as standing.
TEST(ClassicCriteria, RejectAShovedStack) {
    const BuiltScene b = build_scene("boxstack");
    ASSERT_NE(b.scene, nullptr);
    for (dBodyID body : b.world->bodies()) dBodySetLinearVel(body, 3.0, 0, 0);  // every box shoved sideways
    const long steps = std::lround(1.0 / b.world->params().step);
    for (long i = 0; i < steps; ++i) ASSERT_TRUE(b.world->step());
    EXPECT_FALSE(b.success().ok) << b.success().detail;
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
