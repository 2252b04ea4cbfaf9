// The hook's per-step records (ode_bpp/ode.h, set_world_settings): a world without settings
// keeps no |T| per pivot step (an allocation per island otherwise), a world whose caller sets
// Options::record_steps gets them in last_island_result.
#include <gtest/gtest.h>

#include <memory>

#include "ode_bpp/ode.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

/// The last island's result after 30 steps of the motors scene with bpp.
Result last_result_of_motors(const WorldSettings* settings) {
    std::unique_ptr<Scene> scene = make_scene("motors");
    SceneParams params;
    params.solver = "bpp";
    SceneWorld w(params);
    if (settings != nullptr) set_world_settings(w.world(), *settings);
    scene->build(w);
    for (int s = 0; s < 30; ++s) {
        scene->control(w, w.time());
        EXPECT_TRUE(w.step()) << "step " << s;
    }
    return last_island_result(w.world());
}

TEST(HookStepRecords, OffByDefault) {
    const Result r = last_result_of_motors(nullptr);
    ASSERT_EQ(r.status, Status::Converged);
    EXPECT_GT(r.pivoting.pivots, 0);
    EXPECT_TRUE(r.pivoting.tight_per_step.empty());
}

TEST(HookStepRecords, KeptWhenTheCallerAsksForThem) {
    WorldSettings settings;
    settings.options.record_steps = true;
    const Result r = last_result_of_motors(&settings);
    ASSERT_EQ(r.status, Status::Converged);
    EXPECT_GT(r.pivoting.pivots, 0);
    EXPECT_EQ(static_cast<int>(r.pivoting.tight_per_step.size()), r.pivoting.pivots);
}

TEST(HookStepRecords, DefaultsReportedForAWorldWithoutSettings) {
    SceneWorld w(SceneParams{});
    EXPECT_FALSE(world_settings(w.world()).options.record_steps);
    EXPECT_TRUE(world_settings(w.world()).warm_start);
}

}  // namespace
}  // namespace ode_bpp::scenes
