// SceneWorld (demos/scenes/scene.cpp) against physics and bookkeeping oracles: contacts hold a
// resting box at its half height, Coulomb friction holds a box on a slope exactly when
// tan(slope) < mu, excluded and jointed pairs do not touch, a non-finite body ends the run,
// and the registry knows the paper's six scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "scenes/build_helpers.h"
#include "scenes/joint_gap.h"
#include "scenes/paper_scenes.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

constexpr double kPi = 3.14159265358979323846;

SceneParams dantzig_params() {
    SceneParams p;
    p.solver = "dantzig";
    return p;
}

void run(SceneWorld& w, double seconds) {
    const long steps = std::lround(seconds / w.params().step);
    for (long s = 0; s < steps; ++s) ASSERT_TRUE(w.step());
}

TEST(SceneWorld, UnknownSolverIsRejected) {
    SceneParams p;
    p.solver = "no-such-solver";
    EXPECT_THROW(SceneWorld w(p), std::invalid_argument);
    EXPECT_FALSE(is_solver_registered("no-such-solver"));
    EXPECT_TRUE(is_solver_registered("dantzig"));
}

TEST(SceneWorld, BoxComesToRestOnTheGround) {
    SceneWorld w(dantzig_params());
    const double side = 1.0;
    dBodyID box = add_body(w, box_mass(100, {side, side, side}), {0, 0, 0.5 * side + 0.2});
    add_box(w, box, {side, side, side});
    run(w, 2.0);
    // at rest on the plane: centre at half the side, within ODE's contact surface layer
    EXPECT_NEAR(position(box).z, 0.5 * side, 2e-3 * side);
    EXPECT_LT(norm(to_vec(dBodyGetLinearVel(box))), 1e-3);
    EXPECT_GT(w.last_contacts(), 0);
}

TEST(SceneWorld, ExcludedPairDoesNotTouch) {
    SceneWorld w(dantzig_params());
    const double z0 = 1.0, t = 0.5;
    dBodyID box = add_body(w, box_mass(1, {0.2, 0.2, 0.2}), {0, 0, z0});
    dGeomID g = add_box(w, box, {0.2, 0.2, 0.2});
    w.exclude_pair(g, w.ground());
    run(w, t);
    // free fall (ODE's semi-implicit Euler: z = z0 - g h^2 n (n + 1) / 2 after n steps)
    const double h = w.params().step, n = std::round(t / h);
    EXPECT_NEAR(position(box).z, z0 - w.params().gravity * h * h * n * (n + 1) / 2, 1e-9);
    EXPECT_EQ(w.last_contacts(), 0);
}

TEST(SceneWorld, JointedBodiesDoNotCollide) {
    SceneWorld w(dantzig_params());
    // two overlapping boxes high above the ground, joined by a ball joint
    dBodyID a = add_body(w, box_mass(1, {1, 1, 1}), {0, 0, 10});
    dBodyID b = add_body(w, box_mass(1, {1, 1, 1}), {0.5, 0, 10});
    add_box(w, a, {1, 1, 1});
    add_box(w, b, {1, 1, 1});
    add_ball(w, a, b, {0.25, 0, 10});
    ASSERT_TRUE(w.step());
    EXPECT_EQ(w.last_contacts(), 0);
    EXPECT_LT(w.max_joint_error(), 1e-9);
}

constexpr double kSlope = 30 * kPi / 180;  // tan = 0.577
constexpr double kSlideTime = 1.0;

// Distance a block slides in kSlideTime from rest down a slope under Coulomb friction mu:
// a = g (sin - mu cos) when tan(slope) > mu, else it sticks.
double coulomb_slide(double mu, double g) {
    const double a = g * (std::sin(kSlope) - mu * std::cos(kSlope));
    return a > 0 ? 0.5 * a * kSlideTime * kSlideTime : 0.0;
}

// Distance down the slope that a box on a static ramp covers in kSlideTime.
double slide_on_ramp(double mu, bool tune_to_frictionless) {
    SceneParams p = dantzig_params();
    p.mu = mu;
    SceneWorld w(p);
    const double slope = kSlope;
    // pitch -slope turns x up the slope and z into the ramp's normal (-sin, 0, cos);
    // the ramp's top face passes through a point high above the ground plane
    const Vec3 n{-std::sin(slope), 0, std::cos(slope)}, on_top{0, 0, 10};
    add_static_box(w, {40, 4, 1}, on_top - 0.5 * n, -slope);
    dBodyID box = add_body(w, box_mass(10, {0.4, 0.4, 0.4}), on_top + (0.2 - 1e-4) * n);  // touching from the first step
    dMatrix3 R;
    dRFromAxisAndAngle(R, 0, 1, 0, -slope);
    dBodySetRotation(box, R);
    add_box(w, box, {0.4, 0.4, 0.4});
    if (tune_to_frictionless) {
        w.set_contact_tuner([](dGeomID, dGeomID, dContact& c) {
            c.surface.mu = 0;
            return true;
        });
    }
    const Vec3 start = position(box);
    const Vec3 down{-std::cos(slope), 0, -std::sin(slope)};
    run(w, kSlideTime);
    return dot(position(box) - start, down);
}

TEST(SceneWorld, CoulombFrictionHoldsBelowTheFrictionAngle) {
    const double g = dantzig_params().gravity;
    const double frictionless = coulomb_slide(0, g);
    // tan 30 deg < 1: sticks
    EXPECT_LT(std::abs(slide_on_ramp(1.0, false)), 1e-6 * frictionless);
    // tan 30 deg > 0.3: slides; ODE's friction pyramid (dContactApprox1) bounds each tangent
    // direction separately, so the friction force lies between mu N and sqrt(2) mu N
    const double slid = slide_on_ramp(0.3, false);
    EXPECT_GT(slid, 0.5 * coulomb_slide(0.3 * std::sqrt(2.0), g));
    // (ODE's semi-implicit Euler covers a (t + h) t / 2: 1.7 % more than a t^2 / 2 here)
    EXPECT_LT(slid, 1.05 * coulomb_slide(0.3, g));
}

TEST(SceneWorld, ContactTunerOverridesTheDefaults) {
    const double frictionless = coulomb_slide(0, dantzig_params().gravity);
    EXPECT_NEAR(slide_on_ramp(1.0, true), frictionless, 0.05 * frictionless);
}

TEST(SceneWorld, NonFiniteBodyEndsTheRun) {
    SceneWorld w(dantzig_params());
    dBodyID box = add_body(w, box_mass(1, {1, 1, 1}), {0, 0, 5});
    dBodySetLinearVel(box, std::nan(""), 0, 0);
    EXPECT_FALSE(w.step());
}

TEST(SceneWorld, JointErrorIsTheAnchorGap) {
    SceneWorld w(dantzig_params());
    dBodyID a = add_body(w, box_mass(1, {1, 1, 1}), {0, 0, 10});
    dBodyID b = add_body(w, box_mass(1, {1, 1, 1}), {2, 0, 10});
    add_ball(w, a, b, {1, 0, 10});
    dBodySetPosition(b, 2.3, 0.4, 10);  // moves b's anchor by (0.3, 0.4, 0): 0.5 m
    EXPECT_NEAR(w.max_joint_error(), 0.5, 1e-12);
}

// The world-wide measure sees joints nobody tracked, and a hinge-2 joint's gap only across its
// axis 1, along which ODE's suspension lets the anchors part by design.
TEST(SceneWorld, AnchorGapOfEveryJointHinge2AcrossItsAxis) {
    SceneWorld w(dantzig_params());
    dBodyID a = add_body(w, box_mass(1, {1, 1, 1}), {0, 0, 10});
    dBodyID b = add_body(w, box_mass(1, {1, 1, 1}), {2, 0, 10});
    dJointID hinge2 = dJointCreateHinge2(w.world(), nullptr);
    dJointAttach(hinge2, a, b);
    dJointSetHinge2Anchor(hinge2, 1, 0, 10);
    const dReal axis1[3] = {0, 0, 1}, axis2[3] = {0, 1, 0};
    dJointSetHinge2Axes(hinge2, axis1, axis2);
    EXPECT_NEAR(max_anchor_gap(w.bodies()), 0.0, 1e-12);
    EXPECT_NEAR(w.max_joint_error(), 0.0, 1e-12);  // not tracked
    dBodySetPosition(b, 2.3, 0, 10.2);  // 0.2 m along axis 1 (suspension), 0.3 m across it
    EXPECT_NEAR(*anchor_gap(hinge2), 0.3, 1e-12);
    EXPECT_NEAR(max_anchor_gap(w.bodies()), 0.3, 1e-12);
    dJointID slider = add_slider(w, a, b, {1, 0, 0});
    EXPECT_FALSE(anchor_gap(slider).has_value());
}

TEST(SceneRegistry, KnowsThePapersSixScenes) {
    const std::vector<std::string> names = scene_names();
    for (const char* paper : {"crane", "winch", "parkour", "offshore", "forklift", "forwarder"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), paper), names.end()) << paper;
        std::unique_ptr<Scene> scene = make_scene(paper);
        ASSERT_TRUE(scene) << paper;
        EXPECT_EQ(scene->name(), paper);
        EXPECT_GT(scene->paper_table_two().rows, 0) << paper;
    }
    EXPECT_EQ(make_scene("no-such-scene"), nullptr);
}

}  // namespace
}  // namespace ode_bpp::scenes
