// The contact-rich scenes (demos/scenes/contact.h): a pyramid of boxes, a tall stack with a mass
// gradient, capsules dropped into a bin and a pile of rocks. With the solver under test each must
// meet its own criterion with every body finite, and reach the island size it is there for; what
// ODE's Dantzig does is recorded (it lets the pyramid and the stack collapse) but not required.
// Each test prints the solver's fallbacks, pivot steps and slowest step: the record for the work
// on the slow tail, never a timed assertion.
#include <gtest/gtest.h>
#include <ode/mlcp.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "scene_test_support.h"
#include "scenes/contact.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

/// The rows of the largest island each scene exists to produce (its description says so).
struct Expectation {
    std::string scene;
    long min_rows;
    /// Simulated seconds of ODE's Dantzig to record: 0 for the scene's own length. The rock pile's
    /// first second only (its landing, islands of up to about 900 rows, 2 s of wall time): once
    /// the pile stands Dantzig takes about a second per step, too long for the suite.
    double dantzig_seconds;
};

const Expectation kExpectations[] = {
    {"pyramid", 900, 0},
    {"stack", 400, 0},
    {"bin", 450, 0},
    {"rockpile", 1000, 1.0},
};

void PrintTo(const Expectation& e, std::ostream* os) { *os << e.scene; }

void print_record(const std::string& scene, const std::string& solver, const SceneOutcome& out) {
    std::printf("[ %-8s ] %s: %s; largest island %ld rows, %ld pivot steps, %ld islands to ODE's Dantzig, slowest "
                "step %.1f ms (%s)\n",
                solver.c_str(), scene.c_str(), out.success.ok ? "succeeds" : "FAILS", static_cast<long>(out.total.max_rows),
                static_cast<long>(out.total.pivots), static_cast<long>(out.total.failures), out.slowest_step_ms,
                out.success.detail.c_str());
}

class ContactScene : public ::testing::TestWithParam<Expectation> {};

TEST_P(ContactScene, MeetsItsCriterionWithSolverUnderTest) {
    const Expectation& e = GetParam();
    SceneOutcome out;
    expect_scene_succeeds(e.scene, solver_under_test(), &out);
    if (out.steps == 0) return;  // skipped
    EXPECT_GE(out.total.max_rows, e.min_rows) << "the scene no longer builds the island it is there for";
    print_record(e.scene, solver_under_test(), out);
}

TEST_P(ContactScene, DantzigOutcomeIsRecorded) {
    const Expectation& e = GetParam();
    const double seconds = e.dantzig_seconds > 0 ? e.dantzig_seconds : make_scene(e.scene)->default_seconds();
    const SceneOutcome out = run_scene(e.scene, "dantzig", seconds);
    EXPECT_EQ(out.steps_done, out.steps);
    EXPECT_EQ(out.non_finite_body, "");
    if (e.dantzig_seconds > 0) {  // a partial run: the criterion, judged at the end, says nothing
        std::printf("[ dantzig  ] %s, first %.1f s: largest island %ld rows, slowest step %.1f ms\n", e.scene.c_str(),
                    seconds, static_cast<long>(out.total.max_rows), out.slowest_step_ms);
        return;
    }
    RecordProperty("dantzig_success", out.success.ok ? "yes" : "no");
    RecordProperty("dantzig_detail", out.success.detail);
    print_record(e.scene, "dantzig", out);
}

TEST_P(ContactScene, DescribesItselfAndIsRegistered) {
    const Expectation& e = GetParam();
    std::unique_ptr<Scene> scene = make_scene(e.scene);
    ASSERT_NE(scene, nullptr);
    EXPECT_EQ(scene->name(), e.scene);
    EXPECT_FALSE(scene->description().empty());
    EXPECT_GT(scene->default_seconds(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Contact, ContactScene, ::testing::ValuesIn(kExpectations),
                         [](const ::testing::TestParamInfo<Expectation>& info) { return info.param.scene; });

TEST(ContactScenes, AreAllTested) {
    std::vector<std::string> listed;
    for (const auto& [name, factory] : contact_scenes()) listed.push_back(name);
    ASSERT_EQ(listed.size(), std::size(kExpectations));
    for (std::size_t k = 0; k < listed.size(); ++k) EXPECT_EQ(listed[k], kExpectations[k].scene);
}

// The criteria can fail: piles still in the air are not settled in their bin...
TEST(ContactCriteria, RejectAPileNotYetDropped) {
    for (const std::string name : {"bin", "rockpile"}) {
        const BuiltScene b = build_scene(name);
        EXPECT_FALSE(b.success().ok) << name << ": " << b.success().detail;
    }
}

// ...and a pyramid or stack whose top box is shoved off the place where it was built does not stand.
TEST(ContactCriteria, RejectAShovedPyramidOrStack) {
    for (const std::string name : {"pyramid", "stack"}) {
        const BuiltScene b = build_scene(name);
        EXPECT_TRUE(b.success().ok) << name << " as built: " << b.success().detail;
        dBodySetLinearVel(b.world->bodies().back(), 2.0, 0, 0);
        for (int i = 0; i < 30; ++i) ASSERT_TRUE(b.world->step());
        EXPECT_FALSE(b.success().ok) << name << ": " << b.success().detail;
    }
}

}  // namespace
}  // namespace ode_bpp::scenes
