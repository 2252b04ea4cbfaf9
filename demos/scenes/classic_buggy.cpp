// classic_buggy.cpp: a four-wheeled car on hinge-2 joints with sprung suspension, rear-wheel
// drive and motor steering, driving a slalom over two bumps (ODE's buggy demo, written anew).
// Each wheel's hinge-2 adds 4 joint rows (one of them soft: the suspension) and a motor or limit
// row (steering, drive, locked rear steering), and each wheel a contact with friction: a small
// island that mixes unbounded, force-limited and friction rows.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <sstream>

#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

constexpr double kChassisLength = 1.6, kChassisWidth = 0.8, kChassisHeight = 0.3;  // [m]
constexpr double kChassisMass = 60.0;     // [kg]
constexpr double kWheelRadius = 0.3;
constexpr double kWheelMass = 5.0;
constexpr double kWheelbaseHalf = 0.6, kTrackHalf = 0.55;
constexpr double kRideHeight = 0.5;       // chassis centre above the ground at rest [m]
// Suspension as a spring-damper (k, c) turned into hinge-2 ERP/CFM: ERP = hk/(hk+c), CFM = 1/(hk+c).
constexpr double kSpringStiffness = 6000.0;   // [N/m]
constexpr double kSpringDamping = 400.0;      // [N s/m]
constexpr double kDriveSpeed = 10.0;      // wheel speed [rad/s]: 3 m/s without slip
constexpr double kDriveTorque = 80.0;     // per rear wheel [N m]
constexpr double kSteerGain = 8.0;        // steering rate per radian of angle error [1/s]
constexpr double kSteerTorque = 100.0;
constexpr double kSteerLimit = 0.5;       // [rad]
constexpr double kSlalomAmplitude = 0.25; // [rad]
constexpr double kSlalomPeriod = 4.0;     // [s]
constexpr double kLaunchTime = 0.5;       // let the suspension settle first [s]
constexpr double kBumpRadius = 0.06;
constexpr std::array<double, 2> kBumpX = {4.0, 9.0};
// Success: forward travel at least this fraction of what the driven wheel speed allows
// without slip, with the chassis upright throughout.
constexpr double kMinTravelFraction = 0.5;
constexpr double kMinUprightCosine = 0.7;  // about 45 degrees of roll or pitch

/// A car: chassis box and four sphere wheels on hinge-2 joints (axis 1 steering, axis 2 spin).
/// Success: its forward (x) travel reaches kMinTravelFraction of the no-slip distance of the
/// drive phase and the chassis never tips past kMinUprightCosine.
class Buggy final : public Scene {
public:
    std::string name() const override { return "buggy"; }
    std::string description() const override {
        return "four-wheeled car on hinge-2 suspension driving a slalom over two bumps";
    }
    double default_seconds() const override { return 8.0; }

    void build(SceneWorld& w) override {
        for (double x : kBumpX) add_bump(w, x);
        chassis_ = add_chassis(w);
        for (int i = 0; i < 4; ++i) {
            const bool front = i < 2;
            const double x = front ? kWheelbaseHalf : -kWheelbaseHalf;
            const double y = (i % 2 == 0) ? kTrackHalf : -kTrackHalf;
            wheels_[i] = add_wheel(w, x, y, front);
        }
        start_x_ = dBodyGetPosition(chassis_)[0];
    }

    void control(SceneWorld&, double t) override {
        const bool driving = t >= kLaunchTime;
        const double steer_target = driving ? kSlalomAmplitude * std::sin(2 * M_PI * (t - kLaunchTime) / kSlalomPeriod) : 0.0;
        for (int i = 0; i < 4; ++i) {
            dJointID joint = wheels_[i];
            if (i < 2) {
                // Steering by a velocity motor proportional to the angle error.
                dJointSetHinge2Param(joint, dParamVel, kSteerGain * (steer_target - dJointGetHinge2Angle1(joint)));
                dJointSetHinge2Param(joint, dParamFMax, kSteerTorque);
            } else {
                dJointSetHinge2Param(joint, dParamVel2, driving ? kDriveSpeed : 0.0);
                dJointSetHinge2Param(joint, dParamFMax2, kDriveTorque);
            }
        }
        worst_up_cosine_ = std::min(worst_up_cosine_, double(dBodyGetRotation(chassis_)[10]));
    }

    SuccessReport success(const SceneWorld& w) const override {
        const double drive_time = std::max(0.0, w.time() - kLaunchTime);
        const double no_slip_distance = kDriveSpeed * kWheelRadius * drive_time;
        const double travel = dBodyGetPosition(chassis_)[0] - start_x_;
        const double up = std::min(worst_up_cosine_, double(dBodyGetRotation(chassis_)[10]));
        std::ostringstream detail;
        detail << "travelled " << travel << " m in x (needs " << kMinTravelFraction * no_slip_distance
               << " of the no-slip " << no_slip_distance << "); smallest up-cosine " << up << " (limit "
               << kMinUprightCosine << ")";
        return {travel > kMinTravelFraction * no_slip_distance && up > kMinUprightCosine, detail.str()};
    }

private:
    dBodyID add_chassis(SceneWorld& w) {
        dBodyID body = w.create_body();
        dMass mass;
        dMassSetBoxTotal(&mass, kChassisMass, kChassisLength, kChassisWidth, kChassisHeight);
        dBodySetMass(body, &mass);
        dBodySetPosition(body, 0, 0, kRideHeight);
        dGeomSetBody(dCreateBox(w.space(), kChassisLength, kChassisWidth, kChassisHeight), body);
        return body;
    }

    dJointID add_wheel(SceneWorld& w, double x, double y, bool front) {
        dBodyID wheel = w.create_body();
        dMass mass;
        dMassSetSphereTotal(&mass, kWheelMass, kWheelRadius);
        dBodySetMass(wheel, &mass);
        dBodySetPosition(wheel, x, y, kWheelRadius);
        dGeomSetBody(dCreateSphere(w.space(), kWheelRadius), wheel);

        dJointID joint = dJointCreateHinge2(w.world(), nullptr);
        dJointAttach(joint, chassis_, wheel);
        dJointSetHinge2Anchor(joint, x, y, kWheelRadius);
        // ODE's hinge-2 motor speed is body 1 (chassis) relative to body 2 (wheel); about -y it
        // is then the wheel's spin about +y, which rolls the car towards +x.
        const dReal steering_axis[3] = {0, 0, 1}, spin_axis[3] = {0, -1, 0};
        dJointSetHinge2Axes(joint, steering_axis, spin_axis);
        const double h = w.params().step;
        const double hk = h * kSpringStiffness;
        dJointSetHinge2Param(joint, dParamSuspensionERP, hk / (hk + kSpringDamping));
        dJointSetHinge2Param(joint, dParamSuspensionCFM, 1.0 / (hk + kSpringDamping));
        const double steer_limit = front ? kSteerLimit : 0.0;  // rear wheels: steering locked
        dJointSetHinge2Param(joint, dParamLoStop, -steer_limit);
        dJointSetHinge2Param(joint, dParamHiStop, steer_limit);
        return joint;
    }

    static void add_bump(SceneWorld& w, double x) {
        // A static capsule lying across the track (capsules lie along local z; turn it onto y).
        dGeomID bump = dCreateCapsule(w.space(), kBumpRadius, 4.0);
        dMatrix3 R;
        dRFromAxisAndAngle(R, 1, 0, 0, M_PI / 2);
        dGeomSetRotation(bump, R);
        dGeomSetPosition(bump, x, 0, 0);
    }

    dBodyID chassis_ = nullptr;
    std::array<dJointID, 4> wheels_{};
    double start_x_ = 0;
    double worst_up_cosine_ = 1;
};

}  // namespace

std::unique_ptr<Scene> make_classic_buggy() { return std::make_unique<Buggy>(); }

}  // namespace ode_bpp::scenes
