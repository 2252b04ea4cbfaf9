// mu = dInfinity ("never slips") is legal ODE input: its friction rows are unbounded
// (docs/maths.md, Infinite friction). A scene whose every contact has it runs with bpp in both
// friction modes without a single island handed to ODE's Dantzig, and still meets its criterion.
// Before, Consistent friction ended friction-not-consistent on 26 of the cannon's islands
// ("Lemke stage skipped: a friction coefficient is infinite").
#include <gtest/gtest.h>
#include <ode/mlcp.h>

#include <cmath>
#include <string>

#include "ode_bpp/ode.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

struct StatusCount {
    dWorldID world = nullptr;
    long islands = 0, converged = 0;
    std::string first_other;
};

void count_status(const dMLCP*, const dMLCPIslandStats* after, void* data) {
    if (after == nullptr) return;
    auto& c = *static_cast<StatusCount*>(data);
    const Result r = last_island_result(c.world);
    ++c.islands;
    if (r.status == Status::Converged) ++c.converged;
    else if (c.first_other.empty()) c.first_other = std::string(to_string(r.status)) + ": " + r.message;
}

class InfiniteFriction : public ::testing::TestWithParam<FrictionMode> {};

TEST_P(InfiniteFriction, CannonNeverFallsBackAndMeetsItsCriterion) {
    std::unique_ptr<Scene> scene = make_scene("cannon");
    ASSERT_NE(scene, nullptr);
    SceneParams params;
    params.mu = dInfinity;
    SceneWorld w(params);
    WorldSettings settings;
    settings.options.friction = GetParam();
    set_world_settings(w.world(), settings);
    scene->build(w);
    StatusCount count;
    count.world = w.world();
    dWorldSetMLCPObserver(w.world(), &count_status, &count);
    const long steps = std::lround(scene->default_seconds() / params.step);
    for (long s = 0; s < steps; ++s) {
        scene->control(w, w.time());
        ASSERT_TRUE(w.step()) << "step " << s;
    }
    dWorldSetMLCPObserver(w.world(), nullptr, nullptr);
    dMLCPStepStats total{};
    ASSERT_TRUE(dWorldGetMLCPStats(w.world(), nullptr, &total));
    EXPECT_GT(count.islands, 1000);
    EXPECT_EQ(count.converged, count.islands) << count.first_other;
    EXPECT_EQ(total.failures, 0);
    const SuccessReport report = scene->success(w);
    EXPECT_TRUE(report.ok) << report.detail;
}

INSTANTIATE_TEST_SUITE_P(Modes, InfiniteFriction, ::testing::Values(FrictionMode::Frozen, FrictionMode::Consistent),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace ode_bpp::scenes
