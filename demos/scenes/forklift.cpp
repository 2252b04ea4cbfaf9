// demos/scenes/forklift.cpp: Sec. 4.1.1, a 3,000 kg forklift picks up a 100 kg crate, accelerates,
// then makes a 360 degree turn around a traffic cone; friction keeps the crate on the fork, and
// the wheels skid in the turn.
//
// Needed, and why:
//  - chassis with counterweight and mast; two driven front wheels on hinges, turning at one
//    commanded speed (no differential, as on many forklifts: in the turn one wheel must skid);
//    two steered rear wheels on hinge-2 joints;
//  - the mast, hinged to the chassis at its foot and tilted by two hydraulic tilt cylinders: it
//    tilts back once the crate is lifted, as a driver does before travelling, so that the load
//    leans against the carriage (the cylinders close two planar loops, whose hinges repeat each
//    other's out-of-plane rows);
//  - the lift: a crosshead on the mast, raised by a slider motor (the lift cylinder), and the
//    fork carriage sliding on the mast, hanging from the crosshead by two lift chains of 20
//    light links: the load path of the crate runs through 0.85 kg links (Table 2's 2,700:1
//    against the chassis; with the mast and the chains' links, Table 2's 300 rows);
//  - a pallet whose stringers the tines slip between, and the crate on the pallet: the crate
//    stays on only through the crate-pallet and pallet-tine friction;
//  - the cone: a static marker at the turn's centre.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scenes/build_helpers.h"
#include "scenes/paper_scenes.h"

namespace ode_bpp::scenes {

namespace {

constexpr double kPi = 3.14159265358979323846;

// masses [kg]: Sec. 4.1.1 (forklift 3,000 kg, crate 100 kg)
constexpr double kForkliftMass = 3000, kCrateMass = 100, kPalletMass = 25;
constexpr double kFrontWheelMass = 60, kRearWheelMass = 40, kCarriageMass = 120, kCrossheadMass = 40;
constexpr double kMastMass = 260, kTiltBarrelMass = 15, kTiltRodMass = 8;
constexpr int kChainLinks = 20;
constexpr double kLinkMass = 0.85;
constexpr double kChassisMass = kForkliftMass - 2 * kFrontWheelMass - 2 * kRearWheelMass - kCarriageMass -
                                kCrossheadMass - kMastMass - 2 * (kTiltBarrelMass + kTiltRodMass) -
                                2 * kChainLinks * kLinkMass;
// Link inertia x this (docs/modelling.md, light links under heavy loads): ~1.2 kN per chain on
// 0.85 kg links.
constexpr double kChainInertiaFactor = 200;

// geometry [m]: the forklift faces +x
constexpr double kFrontAxleX = 0.6, kRearAxleX = -0.8, kFrontRadius = 0.3, kRearRadius = 0.25;
constexpr double kMastX = 1.05, kCarriageX = 1.13, kTineLength = 1.0, kTineY = 0.225;
const Vec3 kMastFoot{kMastX, 0, 0.3};
const Vec3 kTiltBase{0.55, 0.35, 0.95}, kTiltEnd{kMastX - 0.06, 0.35, 1.3};  // tilt cylinder ends (y: +-)
// Tilt cylinder speed per mast angular speed [m/rad]: the cylinders shorten (about their lever of
// 1 m about the mast foot) as the mast tilts back, which is a growing hinge angle.
constexpr double kTiltLever = -1.0;
constexpr double kTineZ = 0.06;  // tine centre height when lowered (pallet opening 0 .. 0.12)
constexpr double kPalletX = kCarriageX + 0.05 + 0.5 * kTineLength;

// the run [s, m/s, rad]
constexpr double kLiftEnd = 2.0, kLiftSpeed = 0.15, kLiftForce = 2e4;
constexpr double kTiltBack = 0.07, kTiltForce = 3e4;  // mast tilted back 4 deg after the lift
constexpr double kDriveStart = 2.0, kDriveSpeed = 3.0, kAccel = 1.0, kDriveTorque = 1500;
constexpr double kTurnStart = 6.0, kSteerAngle = 0.5;
constexpr double kSteerTorque = 2000;

class ForkliftScene final : public Scene {
public:
    std::string name() const override { return "forklift"; }
    std::string description() const override {
        return "3 t forklift lifts a 100 kg crate on a pallet, accelerates and turns 360 deg around a cone";
    }
    TableTwo paper_table_two() const override { return {2700, 300, 1e8}; }

    void build(SceneWorld& w) override {
        build_chassis(w);
        build_mast(w);
        build_wheels(w);
        build_lift(w);
        build_load(w);
        // the cone: where the turn's centre lies (measured from this scene's own run)
        cone_ = add_cylinder(w, nullptr, 0.15, 0.7, {kConeX, kConeY, 0.35});
        w.set_contact_tuner([this](dGeomID a, dGeomID b, dContact&) {
            if (a == cone_ || b == cone_) cone_hit_ = true;
            return false;
        });
    }

    void control(SceneWorld& w, double t) override {
        (void)w;
        track_heading();
        drive_slider(lift_, t < kLiftEnd ? kLiftSpeed * std::min(t / 0.3, 1.0) : 0.0, kLiftForce);
        const double mast_target = t < kLiftEnd ? 0.0 : kTiltBack;
        const double tilt_rate = servo_velocity(dJointGetHingeAngle(mast_hinge_), mast_target, 0.1);
        for (dJointID j : tilt_) drive_slider(j, kTiltLever * tilt_rate, kTiltForce);
        if (t >= kTurnStart && !turning_ && !turned_) {
            turning_ = true;
            heading_at_turn_ = heading_;
        }
        if (turning_ && heading_ - heading_at_turn_ >= 2 * kPi) {
            turning_ = false;
            turned_ = true;
        }
        const double speed = turned_ ? 0.0 : std::clamp(kAccel * (t - kDriveStart), 0.0, kDriveSpeed);
        // both drive wheels at one speed: no differential
        for (dJointID j : drive_) drive_hinge(j, -speed / kFrontRadius, kDriveTorque);
        // rear-wheel steering: turning left (counter-clockwise) steers the rear wheels right
        const double steer = turning_ ? kSteerAngle : 0.0;
        for (dJointID j : steer_) {
            dJointSetHinge2Param(j, dParamVel, servo_velocity(dJointGetHinge2Angle1(j), steer, 1.0, 0.2));
            dJointSetHinge2Param(j, dParamFMax, kSteerTorque);
        }
    }

    SuccessReport success(const SceneWorld& w) const override {
        const Vec3 crate_now = local_point(carriage_, position(crate_));
        const double shift = norm(crate_now - crate_on_carriage_);
        const double crate_height = position(crate_).z;
        const double turned_deg = (turned_ ? 2 * kPi : heading_ - heading_at_turn_) * 180 / kPi;
        const double tilt_deg = tilt(chassis_) * 180 / kPi;
        std::ostringstream d;
        d << "turned " << (turning_ || turned_ ? turned_deg : 0.0) << " deg (needs 360), crate moved "
          << shift << " m on the fork (< 0.15), crate centre " << crate_height
          << " m up (> 0.6), mast tilted back " << dJointGetHingeAngle(mast_hinge_) * 180 / kPi
          << " deg, forklift tilt " << tilt_deg << " deg (< 20), joint gap "
          << w.max_joint_error() << " m (< 0.01), cone " << (cone_hit_ ? "hit" : "not hit");
        return {!cone_hit_ && turned_ && shift < 0.15 && crate_height > 0.6 && tilt_deg < 20 && w.max_joint_error() < 0.01,
                d.str()};
    }

private:
    // the cone's place, at the centre of the turn this scene drives
    static constexpr double kConeX = 9.1, kConeY = 2.8;

    void build_chassis(SceneWorld& w) {
        CompositeBody c;
        c.box({2.0, 1.1, 0.7}, {0, 0, 0.55}, 0.6 * kChassisMass);            // frame and engine
        c.box({0.5, 1.1, 0.7}, {-1.2, 0, 0.65}, 0.4 * kChassisMass);          // counterweight
        chassis_ = c.build(w, {0, 0, 0});
    }

    // The mast on a hinge at its foot, and a tilt cylinder on each side from the frame to the mast.
    void build_mast(SceneWorld& w) {
        mast_ = add_body(w, box_mass(kMastMass, {0.12, 0.9, 2.2}), {kMastX, 0, 1.3});
        add_box(w, mast_, {0.12, 0.9, 2.2});
        mast_hinge_ = add_hinge(w, chassis_, mast_, kMastFoot, {0, 1, 0});
        for (int side : {-1, 1})
            tilt_.push_back(add_hydraulic_cylinder(w, chassis_, {kTiltBase.x, side * kTiltBase.y, kTiltBase.z}, mast_,
                                                   {kTiltEnd.x, side * kTiltEnd.y, kTiltEnd.z}, kTiltBarrelMass, kTiltRodMass));
    }

    void build_wheels(SceneWorld& w) {
        for (int side : {-1, 1}) {
            const Vec3 hub{kFrontAxleX, side * 0.68, kFrontRadius};
            dBodyID wheel = add_body(w, cylinder_mass(kFrontWheelMass, kFrontRadius, 0.22), hub);
            align_z(wheel, {0, 1, 0});
            add_cylinder(w, wheel, kFrontRadius, 0.22);
            drive_.push_back(add_hinge(w, chassis_, wheel, hub, {0, 1, 0}));
        }
        for (int side : {-1, 1}) {
            const Vec3 hub{kRearAxleX, side * 0.45, kRearRadius};
            dBodyID wheel = add_body(w, cylinder_mass(kRearWheelMass, kRearRadius, 0.18), hub);
            align_z(wheel, {0, 1, 0});
            add_cylinder(w, wheel, kRearRadius, 0.18);
            dJointID j = dJointCreateHinge2(w.world(), nullptr);
            dJointAttach(j, chassis_, wheel);
            dJointSetHinge2Anchor(j, hub.x, hub.y, hub.z);
            const dReal up[3] = {0, 0, 1}, axle[3] = {0, 1, 0};
            dJointSetHinge2Axes(j, up, axle);
            dJointSetHinge2Param(j, dParamLoStop, -0.7);
            dJointSetHinge2Param(j, dParamHiStop, 0.7);
            steer_.push_back(j);
        }
    }

    // Crosshead on the mast (the lift cylinder's slider motor), carriage and tines hanging from
    // it by two chains, guided by the mast (a slider without a motor).
    void build_lift(SceneWorld& w) {
        const double carriage_top = 0.9, crosshead_z = 1.7;
        crosshead_ = add_body(w, box_mass(kCrossheadMass, {0.1, 0.8, 0.1}), {kCarriageX, 0, crosshead_z});
        lift_ = add_slider(w, crosshead_, mast_, {0, 0, 1});

        CompositeBody c;
        c.box({0.05, 1.0, carriage_top - 0.05}, {kCarriageX, 0, 0.5 * (carriage_top + 0.05)}, 0.7 * kCarriageMass);
        for (int side : {-1, 1}) {
            c.box({kTineLength, 0.12, 0.05}, {kCarriageX + 0.05 + 0.5 * kTineLength, side * kTineY, kTineZ},
                  0.15 * kCarriageMass);
        }
        carriage_ = c.build(w, {0, 0, 0});
        add_slider(w, carriage_, mast_, {0, 0, 1});

        for (int side : {-1, 1}) {
            CableSpec chain;
            chain.start = {kCarriageX, side * 0.3, crosshead_z - 0.05};
            chain.end = {kCarriageX, side * 0.3, carriage_top};
            chain.links = kChainLinks;
            chain.radius = 0.015;
            chain.total_mass = kChainLinks * kLinkMass;
            chain.inertia_factor = kChainInertiaFactor;
            chain.collide = false;  // runs inside the mast
            Cable cable = build_cable(w, chain);
            add_ball(w, crosshead_, cable.links.front(), chain.start);
            add_ball(w, cable.links.back(), carriage_, chain.end);
        }
    }

    // Pallet (deck on three stringers; the tines sit in the two openings) and crate on it.
    void build_load(SceneWorld& w) {
        CompositeBody p;
        p.box({1.0, 1.0, 0.03}, {0, 0, 0.135}, 0.4 * kPalletMass);
        for (double y : {-0.45, 0.0, 0.45}) p.box({1.0, 0.1, 0.12}, {0, y, 0.06}, 0.2 * kPalletMass);
        pallet_ = p.build(w, {kPalletX, 0, 0});
        const double size = 0.8;
        crate_ = add_body(w, box_mass(kCrateMass, {size, size, size}), {kPalletX, 0, 0.15 + 0.5 * size});
        add_box(w, crate_, {size, size, size});
        crate_on_carriage_ = local_point(carriage_, position(crate_));
    }

    void track_heading() {
        const Vec3 x = world_vector(chassis_, {1, 0, 0});
        const double raw = std::atan2(x.y, x.x);
        double delta = raw - last_raw_heading_;
        delta -= 2 * kPi * std::round(delta / (2 * kPi));
        heading_ += delta;
        last_raw_heading_ = raw;
    }

    dBodyID chassis_ = nullptr, mast_ = nullptr, crosshead_ = nullptr, carriage_ = nullptr, pallet_ = nullptr, crate_ = nullptr;
    dJointID lift_ = nullptr, mast_hinge_ = nullptr;
    std::vector<dJointID> tilt_;
    std::vector<dJointID> drive_, steer_;
    Vec3 crate_on_carriage_;
    double heading_ = 0, last_raw_heading_ = 0, heading_at_turn_ = 0;
    bool turning_ = false, turned_ = false;
    dGeomID cone_ = nullptr;
    bool cone_hit_ = false;
};

}  // namespace

std::unique_ptr<Scene> make_forklift() { return std::make_unique<ForkliftScene>(); }

}  // namespace ode_bpp::scenes
