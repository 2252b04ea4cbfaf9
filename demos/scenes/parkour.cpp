// demos/scenes/parkour.cpp: Sec. 4.1.3, a 15,000 kg eight-wheeled armoured vehicle crosses stairs,
// rectangular bumps and a hill. Its power train is a chain of coupled constraints:
//
//   engine (velocity motor, torque-limited: a boxed row)
//     --chain drive 4:1--> 4 differential carriers
//   carrier --hinge--> spider --bevel mesh (x2)--> left / right half-shaft
//   half-shaft --angular motor (velocity coupling, torque-limited: a boxed row)--> wheel
//   wheel on a hinge-2 suspension (spring and damper as the suspension's ERP and CFM)
//
// so that the engine's torque reaches the ground only through the whole coupled system
// (the paper's Fig. 5 sparsity). Every link in that chain is one of ODE 0.16's own joints:
// dJointTypeTransmission (chain drive, intersecting-axes bevel gears), hinge, amotor, hinge-2.
// The meshes are velocity constraints only (ERP 0, no backlash): ODE's transmission measures
// gear phase in each gear's own frame, which is wrong once a carrier turns the mesh point, and
// with backlash the engine drive slipped (engine/carrier 5.9 instead of 4) and the phase
// correction pumped energy into the vehicle. The bounded (unilateral) rows are therefore the
// torque limits and the wheels' contacts.
// The spider is the lightest body (0.65 kg against the 13 t hull: Table 2's 20,000:1).
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "scenes/build_helpers.h"
#include "scenes/paper_scenes.h"

namespace ode_bpp::scenes {

namespace {

// masses [kg]
constexpr double kVehicleMass = 15000;  // Sec. 4.1.3
constexpr double kWheelMass = 200, kEngineMass = 100, kCarrierMass = 40, kShaftMass = 15;
constexpr double kSpiderMass = 0.65;
constexpr int kAxles = 4;
constexpr double kHullMass = kVehicleMass - 2 * kAxles * (kWheelMass + kShaftMass) - kEngineMass -
                             kAxles * (kCarrierMass + kSpiderMass);

// geometry [m]
constexpr std::array<double, kAxles> kAxleX = {2.5, 1.2, -1.2, -2.5};
constexpr double kWheelRadius = 0.55, kWheelWidth = 0.4, kTrack = 1.3;  // wheel centre at y = +-kTrack
constexpr double kHubHeight = kWheelRadius + 0.05;                       // before the springs settle
constexpr double kHullLength = 7, kHullWidth = 2.2, kHullHeight = 1.2, kHullClearance = 0.55;
constexpr double kGearOffset = 0.1;  // side gears at y = +-0.1, the spider's pinion 0.1 above the axle

// drive
constexpr double kSprocketEngine = 0.1, kSprocketCarrier = 0.4;  // final drive 4:1
constexpr double kTargetSpeed = 5.0;  // [m/s]
constexpr double kEngineTorque = 2e4; // [Nm]
constexpr double kShaftCoupling = 1e5;  // [Nm] never reached: the CV joints do not slip
// suspension per wheel: spring k, damper c -> ERP = h k / (h k + c), CFM = 1 / (h k + c)
constexpr double kSpring = 4e5, kDamper = 3e4;

// course (x along the drive direction)
constexpr double kGoalX = 56;

class ParkourScene final : public Scene {
public:
    std::string name() const override { return "parkour"; }
    std::string description() const override {
        return "15 t 8x8 vehicle, engine-differential-wheel power train of coupled joints, over "
               "stairs, bumps and a hill";
    }
    TableTwo paper_table_two() const override { return {20000, 260, 1e19}; }

    void build(SceneWorld& w) override {
        build_course(w);
        const double h = w.params().step;
        hull_ = add_body(w, box_mass(kHullMass, {kHullLength, kHullWidth, kHullHeight}),
                         {0, 0, kHullClearance + 0.5 * kHullHeight + 0.05});
        add_box(w, hull_, {kHullLength, kHullWidth, kHullHeight});

        const Vec3 engine_pos{0, 0, kHubHeight + 0.2};
        dMass em = cylinder_mass(kEngineMass, 0.3, 0.3);
        engine_ = add_body(w, em, engine_pos);
        align_z(engine_, {0, 1, 0});
        engine_hinge_ = add_hinge(w, hull_, engine_, engine_pos, {0, 1, 0});

        for (double x : kAxleX) build_axle(w, x, engine_pos, h);
    }

    void control(SceneWorld& w, double t) override {
        (void)w;
        // engine speed for the target ground speed through the 4:1 drive, ramped over 3 s
        const double wheel_speed = kTargetSpeed / kWheelRadius;
        const double engine_speed = wheel_speed * kSprocketCarrier / kSprocketEngine;
        drive_hinge(engine_hinge_, -engine_speed * std::min(t / 3.0, 1.0), kEngineTorque);
    }

    SuccessReport success(const SceneWorld& w) const override {
        const Vec3 p = position(hull_);
        const double tilt_deg = tilt(hull_) * 180 / 3.14159265358979323846;
        std::ostringstream d;
        d << "hull at x = " << p.x << " m (goal " << kGoalX << "), tilt " << tilt_deg
          << " deg (< 45), joint gap " << w.max_joint_error() << " m (< 0.01)";
        return {p.x > kGoalX && tilt_deg < 45 && w.max_joint_error() < 0.01, d.str()};
    }

private:
    // Stairs up and down, three bumps, a hill: static boxes.
    static void build_course(SceneWorld& w) {
        const double width = 8;
        // stairs: nested slabs, step k from x = 8 + 2k to 22 - 2k, 0.2 (k + 1) m high
        for (int k = 0; k < 3; ++k) {
            const double height = 0.2 * (k + 1), from = 8 + 2 * k, to = 22 - 2 * k;
            add_static_box(w, {to - from, width, height}, {0.5 * (from + to), 0, 0.5 * height});
        }
        for (double x : {28.0, 31.0, 34.0}) add_static_box(w, {0.3, width, 0.25}, {x, 0, 0.125});
        // hill: a ramp up, a plateau, a ramp down
        const double slope = 0.2, ramp = 6, slab = 0.5, start = 40;
        const double run = ramp * std::cos(slope), rise = ramp * std::sin(slope), top = 3;
        auto ramp_box = [&](double x0, double sign) {
            // top face from (x0, 0) rising (sign +1) or falling (-1) along x
            const Vec3 mid{x0 + 0.5 * run, 0, 0.5 * rise};
            const Vec3 normal{-sign * std::sin(slope), 0, std::cos(slope)};
            add_static_box(w, {ramp, width, slab}, mid - (0.5 * slab) * normal, -sign * slope);
        };
        ramp_box(start, 1);
        add_static_box(w, {top, width, rise}, {start + run + 0.5 * top, 0, 0.5 * rise});
        ramp_box(start + run + top, -1);
    }

    void build_axle(SceneWorld& w, double x, Vec3 engine_pos, double h) {
        const Vec3 centre{x, 0, kHubHeight};
        // differential carrier on the hull, driven from the engine by a chain
        dBodyID carrier = add_body(w, cylinder_mass(kCarrierMass, 0.15, 0.3), centre);
        align_z(carrier, {0, 1, 0});
        add_hinge(w, hull_, carrier, centre, {0, 1, 0});
        dJointID chain = dJointCreateTransmission(w.world(), nullptr);
        dJointAttach(chain, engine_, carrier);
        dJointSetTransmissionMode(chain, dTransmissionChainDrive);
        dJointSetTransmissionAnchor1(chain, engine_pos.x, engine_pos.y, engine_pos.z);
        dJointSetTransmissionAnchor2(chain, centre.x, centre.y, centre.z);
        dJointSetTransmissionAxis(chain, 0, 1, 0);
        dJointSetTransmissionRadius1(chain, kSprocketEngine);
        dJointSetTransmissionRadius2(chain, kSprocketCarrier);
        dJointSetTransmissionParam(chain, dParamERP, 0);  // a velocity constraint (see the top)

        // spider: a cross shaft through the axle centre, across the axle, turning on the
        // carrier; its pinion 0.1 above the centre meshes with both side gears. Centred on the
        // axle it does not orbit, so its hinge does not drift (an orbiting 0.65 kg pinion
        // opens its hinge by ~5 mm at h = 1/60).
        const Vec3 pinion = centre + Vec3{0, 0, kGearOffset};
        dBodyID spider = add_body(w, cylinder_mass(kSpiderMass, 0.04, 2 * kGearOffset + 0.04), centre);
        add_hinge(w, carrier, spider, centre, {0, 0, 1});

        for (int side : {-1, 1}) {
            // half-shaft: its inner end is the side gear meshing with the spider
            const Vec3 shaft_pos{x, side * 0.5 * (kGearOffset + kTrack - 0.2), kHubHeight};
            dBodyID shaft = add_body(w, cylinder_mass(kShaftMass, 0.05, kTrack - 0.2 - kGearOffset), shaft_pos);
            align_z(shaft, {0, 1, 0});
            add_hinge(w, hull_, shaft, shaft_pos, {0, 1, 0});
            dJointID bevel = dJointCreateTransmission(w.world(), nullptr);
            dJointAttach(bevel, spider, shaft);
            dJointSetTransmissionMode(bevel, dTransmissionIntersectingAxes);
            dJointSetTransmissionAnchor1(bevel, pinion.x, pinion.y, pinion.z);
            dJointSetTransmissionAnchor2(bevel, x, side * kGearOffset, kHubHeight);
            dJointSetTransmissionAxis1(bevel, 0, 0, 1);
            dJointSetTransmissionAxis2(bevel, 0, side, 0);
            // ODE measures gear phase in each gear's own frame, which is wrong once the
            // carrier turns the mesh point; the mesh is a velocity constraint only (no ERP)
            dJointSetTransmissionParam(bevel, dParamERP, 0);

            // wheel on a hinge-2: axis 1 vertical (suspension, steering locked), axis 2 its axle
            const Vec3 hub{x, side * kTrack, kHubHeight};
            dBodyID wheel = add_body(w, cylinder_mass(kWheelMass, kWheelRadius, kWheelWidth), hub);
            align_z(wheel, {0, 1, 0});
            add_cylinder(w, wheel, kWheelRadius, kWheelWidth);
            dJointID susp = dJointCreateHinge2(w.world(), nullptr);
            dJointAttach(susp, hull_, wheel);
            dJointSetHinge2Anchor(susp, hub.x, hub.y, hub.z);
            const dReal axis1[3] = {0, 0, 1}, axis2[3] = {0, 1, 0};
            dJointSetHinge2Axes(susp, axis1, axis2);
            dJointSetHinge2Param(susp, dParamLoStop, 0);
            dJointSetHinge2Param(susp, dParamHiStop, 0);
            dJointSetHinge2Param(susp, dParamSuspensionERP, h * kSpring / (h * kSpring + kDamper));
            dJointSetHinge2Param(susp, dParamSuspensionCFM, 1 / (h * kSpring + kDamper));

            // the shaft's spin drives the wheel's spin (a constant-velocity joint)
            dJointID cv = dJointCreateAMotor(w.world(), nullptr);
            dJointAttach(cv, shaft, wheel);
            dJointSetAMotorMode(cv, dAMotorUser);
            dJointSetAMotorNumAxes(cv, 1);
            dJointSetAMotorAxis(cv, 0, 1, 0, 1, 0);
            dJointSetAMotorParam(cv, dParamVel, 0);
            dJointSetAMotorParam(cv, dParamFMax, kShaftCoupling);
        }
    }

    dBodyID hull_ = nullptr, engine_ = nullptr;
    dJointID engine_hinge_ = nullptr;
};

}  // namespace

std::unique_ptr<Scene> make_parkour() { return std::make_unique<ParkourScene>(); }

}  // namespace ode_bpp::scenes
