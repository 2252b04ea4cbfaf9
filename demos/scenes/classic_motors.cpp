// classic_motors.cpp: joint motors driving bodies against joint limits (ODE's motor and
// slider demos, written anew). A hinge arm is driven up against its upper stop, held there
// against gravity, then driven down against its lower stop; a carriage on a vertical slider is
// lifted by a motor against its top stop. At a stop the MLCP holds a limit row (x >= 0) and a
// motor row (|x| <= FMax) acting together: both must end up at their bounds.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

// Hinge arm on the side of a pedestal; hinge axis +y, so a positive angle turns the tip down.
constexpr double kPedestalHeight = 1.5, kPedestalSide = 0.3;   // [m]
constexpr double kArmLength = 1.2, kArmThickness = 0.1;
constexpr double kArmMass = 2.0;                                // [kg]
constexpr double kArmUpStop = -1.0, kArmDownStop = 0.6;         // hinge angle limits [rad]
constexpr double kArmSpeed = 1.5;                               // motor speed [rad/s]
constexpr double kArmTorque = 60.0;                             // vs. ~12 N m of gravity [N m]
constexpr double kArmReverseTime = 3.0;                         // up until then, down after [s]
// Vertical slider: a carriage lifted along a rail.
constexpr double kRailX = 2.0, kRailHeight = 2.0, kRailSide = 0.1;
constexpr double kCarriageSide = 0.3, kCarriageMass = 5.0;
constexpr double kSliderTop = 1.0;                              // stroke [m]
constexpr double kLiftSpeed = 0.5;                              // [m/s]
constexpr double kLiftForce = 200.0;                            // vs. 49 N of gravity [N]
// Success: each joint ends (and the arm, just before reversing, was) within this fraction of
// its range from the stop it was driven to, nearly at rest there (speed below this fraction of
// the motor speed), and never overshot a stop by more than kOvershootSteps steps of motor travel:
// ODE activates a limit row only once the joint is past its stop, so one step (v h) is inherent.
constexpr double kStopToleranceFraction = 0.02;
constexpr double kRestSpeedFraction = 0.05;
constexpr double kOvershootSteps = 2.0;

/// Whether a joint coordinate sits at the stop it was driven to and holds still there.
struct StopCheck {
    double position, speed;
    double stop, range, motor_speed;
    bool holds() const {
        return std::abs(position - stop) < kStopToleranceFraction * range &&
               std::abs(speed) < kRestSpeedFraction * motor_speed;
    }
};

std::ostream& operator<<(std::ostream& out, const StopCheck& c) {
    return out << "at " << c.position << " (stop " << c.stop << ", tolerance " << kStopToleranceFraction * c.range
               << "), speed " << c.speed << " (limit " << kRestSpeedFraction * c.motor_speed << ")";
}

/// A hinge arm and a slider carriage, each driven by a velocity motor against its limits.
class Motors final : public Scene {
public:
    std::string name() const override { return "motors"; }
    std::string description() const override {
        return "hinge arm driven against both stops and a slider lifted against its top stop";
    }
    double default_seconds() const override { return 6.0; }

    void build(SceneWorld& w) override {
        build_arm(w);
        build_slider(w);
    }

    void control(SceneWorld&, double t) override {
        const bool lifting = t < kArmReverseTime;
        if (lifting) arm_at_upper_ = arm_check(kArmUpStop, -kArmSpeed);
        dJointSetHingeParam(hinge_, dParamVel, lifting ? -kArmSpeed : kArmSpeed);
        dJointSetHingeParam(hinge_, dParamFMax, kArmTorque);
        dJointSetSliderParam(slider_, dParamVel, kLiftSpeed);
        dJointSetSliderParam(slider_, dParamFMax, kLiftForce);
        const double angle = dJointGetHingeAngle(hinge_);
        const double lift = dJointGetSliderPosition(slider_);
        arm_overshoot_ = std::max({arm_overshoot_, kArmUpStop - angle, angle - kArmDownStop});
        lift_overshoot_ = std::max({lift_overshoot_, lift - kSliderTop, -lift});
    }

    SuccessReport success(const SceneWorld& w) const override {
        const StopCheck arm_down = arm_check(kArmDownStop, kArmSpeed);
        const StopCheck lift{dJointGetSliderPosition(slider_), dJointGetSliderPositionRate(slider_), kSliderTop,
                             kSliderTop, kLiftSpeed};
        const double arm_overshoot_limit = kOvershootSteps * kArmSpeed * w.params().step;
        const double lift_overshoot_limit = kOvershootSteps * kLiftSpeed * w.params().step;
        std::ostringstream detail;
        detail << "arm before reversing " << arm_at_upper_ << "; arm at the end " << arm_down << "; slider " << lift
               << "; overshoot arm " << arm_overshoot_ << " rad (limit " << arm_overshoot_limit << "), slider "
               << lift_overshoot_ << " m (limit " << lift_overshoot_limit << ")";
        const bool ok = arm_at_upper_.holds() && arm_down.holds() && lift.holds() &&
                        arm_overshoot_ < arm_overshoot_limit && lift_overshoot_ < lift_overshoot_limit;
        return {ok, detail.str()};
    }

private:
    StopCheck arm_check(double stop, double motor_speed) const {
        return {dJointGetHingeAngle(hinge_), dJointGetHingeAngleRate(hinge_), stop, kArmDownStop - kArmUpStop,
                std::abs(motor_speed)};
    }

    void build_arm(SceneWorld& w) {
        dGeomID pedestal = dCreateBox(w.space(), kPedestalSide, kPedestalSide, kPedestalHeight);
        dGeomSetPosition(pedestal, 0, 0, 0.5 * kPedestalHeight);
        const double hinge[3] = {0, -0.5 * kPedestalSide - kArmThickness, kPedestalHeight};

        dBodyID arm = w.create_body();
        dMass mass;
        dMassSetBoxTotal(&mass, kArmMass, kArmLength, kArmThickness, kArmThickness);
        dBodySetMass(arm, &mass);
        dBodySetPosition(arm, hinge[0] + 0.5 * kArmLength, hinge[1], hinge[2]);
        dGeomID arm_geom = dCreateBox(w.space(), kArmLength, kArmThickness, kArmThickness);
        dGeomSetBody(arm_geom, arm);
        w.exclude_pair(pedestal, arm_geom);

        hinge_ = dJointCreateHinge(w.world(), nullptr);
        dJointAttach(hinge_, arm, nullptr);
        dJointSetHingeAnchor(hinge_, hinge[0], hinge[1], hinge[2]);
        dJointSetHingeAxis(hinge_, 0, 1, 0);
        dJointSetHingeParam(hinge_, dParamLoStop, kArmUpStop);
        dJointSetHingeParam(hinge_, dParamHiStop, kArmDownStop);
    }

    void build_slider(SceneWorld& w) {
        dGeomID rail = dCreateBox(w.space(), kRailSide, kRailSide, kRailHeight);
        dGeomSetPosition(rail, kRailX, 0, 0.5 * kRailHeight);

        dBodyID carriage = w.create_body();
        dMass mass;
        dMassSetBoxTotal(&mass, kCarriageMass, kCarriageSide, kCarriageSide, kCarriageSide);
        dBodySetMass(carriage, &mass);
        // In front of the rail, starting clear of the ground.
        dBodySetPosition(carriage, kRailX, -0.5 * (kRailSide + kCarriageSide), 0.5 * kCarriageSide + 0.1);
        dGeomID carriage_geom = dCreateBox(w.space(), kCarriageSide, kCarriageSide, kCarriageSide);
        dGeomSetBody(carriage_geom, carriage);
        w.exclude_pair(rail, carriage_geom);

        slider_ = dJointCreateSlider(w.world(), nullptr);
        dJointAttach(slider_, carriage, nullptr);
        dJointSetSliderAxis(slider_, 0, 0, 1);  // position 0 where the carriage starts, + is up
        dJointSetSliderParam(slider_, dParamLoStop, 0.0);
        dJointSetSliderParam(slider_, dParamHiStop, kSliderTop);
    }

    dJointID hinge_ = nullptr;
    dJointID slider_ = nullptr;
    StopCheck arm_at_upper_{0, 0, kArmUpStop, kArmDownStop - kArmUpStop, kArmSpeed};
    double arm_overshoot_ = 0;   // [rad]
    double lift_overshoot_ = 0;  // [m]
};

}  // namespace

std::unique_ptr<Scene> make_classic_motors() { return std::make_unique<Motors>(); }

}  // namespace ode_bpp::scenes
