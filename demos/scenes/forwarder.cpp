// demos/scenes/forwarder.cpp: Sec. 4.1.5, a forwarder's 16-link, 1,900 kg crane grasps a 400 kg
// log with friction in the claws and lifts it by raising its boom, then slews: the log stays in
// the grapple only through the claws' friction.
//
// As in the paper, the vehicle (here: the static environment carrying the slewing column) and
// the hydraulics are not in the island: each hydraulic cylinder is a barrel and a rod on a
// velocity-driven slider (its force limit is the pressure). The 16 links:
//   column, lift boom, lift barrel, lift rod, folding boom, fold barrel, fold rod,
//   telescope 1 and 2, hanger link, rotator housing, grapple frame, two claws,
//   claw barrel and claw rod.
// The cylinders close planar loops (column-boom-cylinder, boom-boom-cylinder,
// frame-claw-cylinder-claw) whose hinges repeat each other's out-of-plane rows: the redundancy
// that makes A ill-conditioned (Table 2: cond 1e11). A gear segment keeps the claws symmetric.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scenes/build_helpers.h"
#include "scenes/paper_scenes.h"

namespace ode_bpp::scenes {

namespace {

// masses [kg]: 1,900 kg of crane (Sec. 4.1.5) and a 400 kg log
constexpr double kColumnMass = 300, kLiftBoomMass = 520, kLiftBarrelMass = 40, kLiftRodMass = 20;
constexpr double kFoldBoomMass = 300, kFoldBarrelMass = 30, kFoldRodMass = 15;
constexpr double kTele1Mass = 150, kTele2Mass = 100, kHangerMass = 15, kHousingMass = 60;
constexpr double kFrameMass = 150, kClawMass = 90, kClawBarrelMass = 12, kClawRodMass = 8;
constexpr double kLogMass = 400, kLogRadius = 0.2, kLogLength = 4;

// geometry [m], in the x-z plane of the arm (y across)
const Vec3 kSlewBase{0, 0, 2.0}, kLiftPivot{0, 0, 3.5}, kLiftTip{4.0, 0, 4.5};
constexpr double kFoldLength = 3.0, kFoldAngle = -0.8727;  // 50 degrees down
constexpr double kTeleReach = 0.6;                          // telescope tip beyond the fold boom
constexpr double kClawSpread = 0.12;                        // claw hinges at x = +-0.12
constexpr double kClawOpen = 0.7;                           // [rad] opened at the start
constexpr double kLogHeight = 0.35;                         // centre, on two bearers

// drives: cylinder forces are their pressure limits
constexpr double kGripForce = 2.5e4, kLiftForce = 6e5, kHoldForce = 6e5;
constexpr double kSlewTorque = 6e4, kRotatorTorque = 3e3, kBrakeTorque = 1.5e3;
constexpr double kClawSpeed = 0.15, kLiftSpeed = 0.06, kSlewSpeed = 0.3;
constexpr double kGripStart = 0.5, kLiftStart = 4, kLiftEnd = 10, kSlewStart = 11, kSlewEnd = 15;

Vec3 planar(double x, double z) { return {x, 0, z}; }

class ForwarderScene final : public Scene {
public:
    std::string name() const override { return "forwarder"; }
    std::string description() const override {
        return "16-link 1.9 t forwarder crane grips a 400 kg log by claw friction, lifts and slews it";
    }
    TableTwo paper_table_two() const override { return {6500, 250, 1e11}; }

    void build(SceneWorld& w) override {
        column_ = add_beam(w, kColumnMass, 0.5, kSlewBase, kLiftPivot);
        slew_ = add_hinge(w, column_, nullptr, kSlewBase, {0, 0, 1});
        lift_boom_ = add_beam(w, kLiftBoomMass, 0.3, kLiftPivot, kLiftTip);
        add_hinge(w, column_, lift_boom_, kLiftPivot, {0, 1, 0});
        const Vec3 u1 = normalized(kLiftTip - kLiftPivot), up1{-u1.z, 0, u1.x};
        lift_cyl_ = cylinder(w, column_, kLiftPivot + Vec3{0.25, 0, -1.2}, lift_boom_,
                             kLiftPivot + 1.5 * u1 - 0.15 * up1, kLiftBarrelMass, kLiftRodMass);

        const Vec3 u2{std::cos(kFoldAngle), 0, std::sin(kFoldAngle)}, up2{-u2.z, 0, u2.x};
        const Vec3 fold_tip = kLiftTip + kFoldLength * u2;
        fold_boom_ = add_beam(w, kFoldBoomMass, 0.25, kLiftTip, fold_tip);
        add_hinge(w, lift_boom_, fold_boom_, kLiftTip, {0, 1, 0});
        fold_cyl_ = cylinder(w, lift_boom_, kLiftPivot + 2.6 * u1 + 0.25 * up1, fold_boom_,
                             kLiftTip + 0.5 * u2 + 0.2 * up2, kFoldBarrelMass, kFoldRodMass);

        const Vec3 tip = fold_tip + kTeleReach * u2;
        dBodyID tele1 = add_beam(w, kTele1Mass, 0.2, fold_tip - 1.5 * u2, fold_tip + 0.3 * u2);
        dBodyID tele2 = add_beam(w, kTele2Mass, 0.15, fold_tip - 0.6 * u2, tip);
        holds_.push_back(add_slider(w, tele1, fold_boom_, u2));
        holds_.push_back(add_slider(w, tele2, tele1, u2));

        build_grapple(w, tele2, tip);
        build_log(w, tip.x);
    }

    void control(SceneWorld& w, double t) override {
        (void)w;
        if (t >= kGripStart) drive_slider(claw_cyl_, kClawSpeed, kGripForce);
        const bool lifting = t >= kLiftStart && t < kLiftEnd;
        drive_slider(lift_cyl_, lifting ? kLiftSpeed : hold_velocity(lift_cyl_, lift_target_), lifting ? kLiftForce : kHoldForce);
        if (lifting) lift_target_ = dJointGetSliderPosition(lift_cyl_);
        drive_slider(fold_cyl_, hold_velocity(fold_cyl_, 0), kHoldForce);
        for (dJointID j : holds_) drive_slider(j, hold_velocity(j, 0), kHoldForce);
        const double slew = t >= kSlewStart && t < kSlewEnd ? kSlewSpeed * std::min(t - kSlewStart, 1.0) : 0.0;
        drive_hinge(slew_, slew, kSlewTorque);
        drive_hinge(rotator_, servo_velocity(dJointGetHingeAngle(rotator_), 0, 0.5), kRotatorTorque);
        for (dJointID j : brakes_) drive_hinge(j, 0, kBrakeTorque);
    }

    SuccessReport success(const SceneWorld& w) const override {
        const Vec3 log = position(log_);
        const Vec3 frame = position(frame_);
        const double lift = log.z - kLogHeight;
        const double off_centre = std::hypot(log.x - frame.x, log.y - frame.y);
        const double speed = norm(to_vec(dBodyGetLinearVel(log_)));
        const double slewed = std::abs(dJointGetHingeAngle(slew_)) * 180 / 3.14159265358979323846;
        std::ostringstream d;
        d << "log lifted " << lift << " m (needs 0.8), " << off_centre
          << " m from the grapple's axis (< 0.5), speed " << speed << " m/s (< 0.5), slewed "
          << slewed << " deg (needs 30), joint gap " << w.max_joint_error() << " m (< 0.01)";
        return {lift > 0.8 && off_centre < 0.5 && speed < 0.5 && slewed > 30 && w.max_joint_error() < 0.01,
                d.str()};
    }

private:
    // A hydraulic cylinder from point a on body A to point b on body B: barrel hinged at a, rod
    // hinged at b, the two on a slider along a -> b (its motor is the cylinder).
    dJointID cylinder(SceneWorld& w, dBodyID A, Vec3 a, dBodyID B, Vec3 b, double barrel_mass, double rod_mass) {
        const Vec3 u = normalized(b - a);
        const double len = norm(b - a);
        dBodyID barrel = add_beam(w, barrel_mass, 0.12, a, a + (0.55 * len) * u);
        dBodyID rod = add_beam(w, rod_mass, 0.06, b - (0.55 * len) * u, b);
        add_hinge(w, A, barrel, a, {0, 1, 0});
        add_hinge(w, rod, B, b, {0, 1, 0});
        return add_slider(w, rod, barrel, u);
    }

    // Hanger link and rotator housing (two braked hinges: the grapple swings only against the
    // brakes), the grapple frame on the rotator, two claws synchronised by a gear segment and
    // closed by a cylinder between their horns.
    void build_grapple(SceneWorld& w, dBodyID tele, Vec3 tip) {
        dBodyID hanger = add_beam(w, kHangerMass, 0.1, tip, tip - Vec3{0, 0, 0.25});
        brakes_.push_back(add_hinge(w, tele, hanger, tip, {1, 0, 0}));
        dBodyID housing = add_beam(w, kHousingMass, 0.2, tip - Vec3{0, 0, 0.25}, tip - Vec3{0, 0, 0.5});
        brakes_.push_back(add_hinge(w, hanger, housing, tip - Vec3{0, 0, 0.25}, {0, 1, 0}));

        const double hinge_z = tip.z - 0.8;
        frame_ = add_body(w, box_mass(kFrameMass, {0.5, 0.3, 0.28}), {tip.x, 0, hinge_z + 0.16});
        add_box(w, frame_, {0.5, 0.3, 0.28});
        rotator_ = add_hinge(w, housing, frame_, tip - Vec3{0, 0, 0.5}, {0, 0, 1});

        dBodyID claws[2];
        Vec3 horns[2];
        for (int k = 0; k < 2; ++k) {
            const double s = k == 0 ? -1 : 1;  // left claw at -x, right at +x
            const Vec3 hinge{tip.x + s * kClawSpread, 0, hinge_z};
            CompositeBody c;
            // closed-pose outline in the x-z plane, relative to the hinge, mirrored by s
            bar(c, {0, 0}, {s * 0.21, -0.55}, 0.4 * kClawMass);      // arm
            bar(c, {s * 0.21, -0.55}, {-s * 0.07, -0.83}, 0.35 * kClawMass);  // hook under the log
            bar(c, {0, 0}, {s * 0.23, 0.25}, 0.25 * kClawMass);      // horn
            claws[k] = c.build(w, hinge);
            // open: the lower arm swings outward
            rotate_about(claws[k], hinge, {0, 1, 0}, -s * kClawOpen);
            add_hinge(w, frame_, claws[k], hinge, {0, 1, 0});
            horns[k] = hinge + rotated_y(Vec3{s * 0.23, 0, 0.25}, -s * kClawOpen);
        }
        // the claw cylinder pushes the horns apart: the claws close
        claw_cyl_ = cylinder(w, claws[0], horns[0], claws[1], horns[1], kClawBarrelMass, kClawRodMass);
        // a gear segment on the claws' hubs: equal and opposite claw angles
        dJointID gear = dJointCreateTransmission(w.world(), nullptr);
        dJointAttach(gear, claws[0], claws[1]);
        dJointSetTransmissionMode(gear, dTransmissionParallelAxes);
        dJointSetTransmissionAxis(gear, 0, 1, 0);
        dJointSetTransmissionAnchor1(gear, tip.x - kClawSpread, 0, hinge_z);
        dJointSetTransmissionAnchor2(gear, tip.x + kClawSpread, 0, hinge_z);
        dJointSetTransmissionRatio(gear, 1);
    }

    // A claw member from p to q (x-z offsets from the claw hinge), 0.3 m wide across the log.
    static void bar(CompositeBody& c, std::pair<double, double> p, std::pair<double, double> q, double mass) {
        const double dx = q.first - p.first, dz = q.second - p.second;
        c.box({0.08, 0.3, std::hypot(dx, dz)}, planar(0.5 * (p.first + q.first), 0.5 * (p.second + q.second)),
              mass, {0, 1, 0}, std::atan2(dx, dz));
    }

    static Vec3 rotated_y(Vec3 v, double angle) {
        return {v.x * std::cos(angle) + v.z * std::sin(angle), v.y, -v.x * std::sin(angle) + v.z * std::cos(angle)};
    }

    void build_log(SceneWorld& w, double x) {
        log_ = add_body(w, cylinder_mass(kLogMass, kLogRadius, kLogLength), {x, 0, kLogHeight});
        align_z(log_, {0, 1, 0});
        add_cylinder(w, log_, kLogRadius, kLogLength);
        for (double y : {-1.5, 1.5}) {
            add_static_box(w, {0.5, 0.3, kLogHeight - kLogRadius}, {x, y, 0.5 * (kLogHeight - kLogRadius)});
        }
    }

    static double hold_velocity(dJointID slider, double target) {
        return servo_velocity(dJointGetSliderPosition(slider), target, 0.2, 0.3);
    }

    dBodyID column_ = nullptr, lift_boom_ = nullptr, fold_boom_ = nullptr, frame_ = nullptr, log_ = nullptr;
    dJointID slew_ = nullptr, lift_cyl_ = nullptr, fold_cyl_ = nullptr, claw_cyl_ = nullptr, rotator_ = nullptr;
    std::vector<dJointID> holds_, brakes_;
    double lift_target_ = 0;
};

}  // namespace

std::unique_ptr<Scene> make_forwarder() { return std::make_unique<ForwarderScene>(); }

}  // namespace ode_bpp::scenes
