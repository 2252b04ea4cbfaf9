// The paper's six scenes (Sec. 4.1), each run for its full 20 s inside dWorldStep:
//  - with the solver named by ODE_BPP_SCENE_SOLVER (default "bpp"), the scene's own success
//    criterion must hold (skipped, with a message, if that solver is not registered);
//  - with ODE's stock Dantzig, the outcome is recorded (test output and XML property), and only
//    a finite world is required: the paper's point is that Dantzig is the baseline, not an oracle.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <string>

#include "scenes/paper_scenes.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

struct Outcome {
    bool finite = true;     ///< every step succeeded and every body position stayed finite
    long steps = 0;
    double seconds = 0;     ///< simulated
    SuccessReport success;
};

Outcome run(const std::string& scene_name, const std::string& solver, double compliance = 0) {
    std::unique_ptr<Scene> scene = make_scene(scene_name);
    SceneParams params;
    params.solver = solver;
    if (compliance > 0) params.cfm = cfm_from_compliance(compliance, params.step);
    SceneWorld w(params);
    scene->build(w);
    Outcome out;
    const long steps = std::lround(scene->default_seconds() / params.step);
    for (long s = 0; s < steps && out.finite; ++s) {
        scene->control(w, w.time());
        out.finite = w.step();
        ++out.steps;
    }
    out.seconds = w.time();
    out.success = scene->success(w);
    return out;
}

std::string solver_under_test() {
    const char* env = std::getenv("ODE_BPP_SCENE_SOLVER");
    return env && *env ? env : "bpp";
}

class PaperScene : public ::testing::TestWithParam<std::string> {};

TEST_P(PaperScene, MeetsItsSuccessCriterion) {
    const std::string solver = solver_under_test();
    if (!is_solver_registered(solver)) {
        GTEST_SKIP() << "MLCP solver '" << solver << "' is not registered (have: "
                     << dListMLCPSolvers() << "); set ODE_BPP_SCENE_SOLVER or link libode_bpp";
    }
    const Outcome out = run(GetParam(), solver);
    ASSERT_TRUE(out.finite) << GetParam() << " with " << solver << " blew up after " << out.steps << " steps";
    EXPECT_TRUE(out.success.ok) << GetParam() << " with " << solver << ": " << out.success.detail;
}

TEST_P(PaperScene, DantzigOutcomeIsRecorded) {
    const Outcome out = run(GetParam(), "dantzig");
    RecordProperty("dantzig_success", out.success.ok ? "yes" : "no");
    RecordProperty("dantzig_detail", out.success.detail);
    std::cout << "[ dantzig  ] " << GetParam() << ": " << (out.success.ok ? "succeeds" : "FAILS") << " ("
              << out.success.detail << ")\n";
    EXPECT_TRUE(out.finite) << GetParam() << " with dantzig blew up after " << out.steps << " steps";
}

std::vector<std::string> paper_scene_names() {
    std::vector<std::string> names;
    for (const auto& [name, factory] : paper_scenes()) names.push_back(name);
    return names;
}

INSTANTIATE_TEST_SUITE_P(Paper, PaperScene, ::testing::ValuesIn(paper_scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// At the paper's compliance 1e-8 (CFM = c/h = 6e-7) the machines still do their job: their drives
// keep ODE's stiff CFM (scenes/build_helpers.h, kDriveCfm), where a drive at the world's CFM let
// the crane's boom and the forwarder's arm sink under load with either solver. Not the offshore
// rig: at this compliance its cable of 1.25 kg links opens by ~1 m under the 15 t module (joint
// gap 0.96 m, with Dantzig too): compliant joints in series, the physics of that c, not a drive.
class PaperSceneAtCompliance : public ::testing::TestWithParam<std::string> {};

TEST_P(PaperSceneAtCompliance, MeetsItsSuccessCriterionAtThePapersCompliance) {
    const std::string solver = solver_under_test();
    if (!is_solver_registered(solver)) GTEST_SKIP() << "MLCP solver '" << solver << "' is not registered";
    const Outcome out = run(GetParam(), solver, 1e-8);
    ASSERT_TRUE(out.finite) << GetParam() << " with " << solver << " blew up after " << out.steps << " steps";
    EXPECT_TRUE(out.success.ok) << GetParam() << " at compliance 1e-8 with " << solver << ": " << out.success.detail;
}

std::vector<std::string> scenes_that_hold_at_compliance() {
    std::vector<std::string> names;
    for (const std::string& name : paper_scene_names())
        if (name != "offshore") names.push_back(name);
    return names;
}

INSTANTIATE_TEST_SUITE_P(Paper, PaperSceneAtCompliance, ::testing::ValuesIn(scenes_that_hold_at_compliance()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace ode_bpp::scenes
