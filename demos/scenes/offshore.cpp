// demos/scenes/offshore.cpp: Sec. 4.1.4, a 50,000 kg knuckle-boom crane, fixed to a 5,500,000 kg
// ship, hoists a 15,000 kg subsea module on a light steel cable; the module slides up the hull.
//
// Needed: the ship (a dynamic body: it is the heavy end of Table 2's 4,400,000:1, resting on
// the sea bed), the crane fixed to it (pedestal, main boom and knuckle jib on held hinges, a
// hoist block sliding up the jib tip), the cable of 1.25 kg links, and the module. The cable
// hangs from inboard of the hull's side, so its tension presses the module against the hull:
// hoisting drags it up the hull with sliding friction.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scenes/build_helpers.h"
#include "scenes/paper_scenes.h"

namespace ode_bpp::scenes {

namespace {

// masses [kg]: Sec. 4.1.4
constexpr double kShipMass = 5.5e6, kCraneMass = 5e4, kModuleMass = 1.5e4;
constexpr double kPedestalMass = 2e4, kBoomMass = 1.8e4, kBlockMass = 300;
constexpr double kJibMass = kCraneMass - kPedestalMass - kBoomMass - kBlockMass;
constexpr int kCableLinks = 100;
constexpr double kLinkMass = 1.25, kCableRadius = 0.03;
// Link inertia x this (docs/modelling.md, light links under heavy loads): under the module's 1.5e5 N the links' transverse
// mode is far faster than 1/h; as in the crane, the inflated inertia keeps the joints closed.
constexpr double kCableInertiaFactor = 2e4;

// geometry [m]: the ship along x, its port side at y = -kShipBeam / 2
constexpr double kShipLength = 100, kShipBeam = 20, kShipDepth = 10;
constexpr double kModuleSize = 3;
// the main boom rises outward from the pedestal top, the knuckle jib folds back under it,
// inward and down, so that the hoist point sits 0.5 m inboard of the hanging module's centre
// and the cable hangs clear of the crane
constexpr double kPedestalHeight = 10;
const Vec3 kBoomRise{0, -5, 10};   // pedestal top -> knuckle
const Vec3 kJibReach{0, 2, -6};    // knuckle -> jib tip

// the hoist
constexpr double kHoistStart = 2, kHoistEnd = 16, kHoistSpeed = 0.4, kHoistRamp = 1;
constexpr double kHoistForce = 1e6, kHingeTorque = 1e8;

class OffshoreScene final : public Scene {
public:
    std::string name() const override { return "offshore"; }
    std::string description() const override {
        return "50 t knuckle-boom crane fixed to a 5,500 t ship hoists a 15 t module up the hull";
    }
    TableTwo paper_table_two() const override { return {4.4e6, 350, 1e9}; }

    void build(SceneWorld& w) override {
        const double side = -0.5 * kShipBeam;
        ship_ = add_body(w, box_mass(kShipMass, {kShipLength, kShipBeam, kShipDepth}), {0, 0, 0.5 * kShipDepth});
        add_box(w, ship_, {kShipLength, kShipBeam, kShipDepth});

        const Vec3 base{0, side + 2, kShipDepth};
        pedestal_ = add_body(w, box_mass(kPedestalMass, {3, 3, kPedestalHeight}), base + Vec3{0, 0, 0.5 * kPedestalHeight});
        add_box(w, pedestal_, {3, 3, kPedestalHeight});
        add_fixed(w, ship_, pedestal_);

        const Vec3 boom_pivot = base + Vec3{0, 0, kPedestalHeight};
        const Vec3 knuckle = boom_pivot + kBoomRise;
        boom_ = add_beam(w, kBoomMass, 1.2, boom_pivot, knuckle, &boom_geom_);
        boom_hinge_ = add_hinge(w, pedestal_, boom_, boom_pivot, {1, 0, 0});
        const Vec3 tip = knuckle + kJibReach;
        jib_ = add_beam(w, kJibMass, 1.0, knuckle, tip, &jib_geom_);
        jib_hinge_ = add_hinge(w, boom_, jib_, knuckle, {1, 0, 0});

        const Vec3 block_pos = tip;  // hoisting draws it up above the tip
        block_ = add_body(w, box_mass(kBlockMass, {0.5, 0.5, 0.5}), block_pos);
        hoist_ = add_slider(w, block_, jib_, {0, 0, 1});

        // the module stands on the sea bed against the hull, outboard of the hoist point
        const Vec3 module_pos{0, side - 0.5 * kModuleSize - 0.01, 0.5 * kModuleSize};
        module_ = add_body(w, box_mass(kModuleMass, {kModuleSize, kModuleSize, kModuleSize}), module_pos);
        add_box(w, module_, {kModuleSize, kModuleSize, kModuleSize});
        const Vec3 attach = module_pos + Vec3{0, 0, 0.5 * kModuleSize};

        CableSpec spec;
        spec.start = block_pos - Vec3{0, 0, 0.25};
        spec.end = attach;
        spec.links = kCableLinks;
        spec.radius = kCableRadius;
        spec.total_mass = kCableLinks * kLinkMass;
        spec.inertia_factor = kCableInertiaFactor;
        cable_ = build_cable(w, spec);
        add_ball(w, block_, cable_.links.front(), spec.start);
        add_ball(w, cable_.links.back(), module_, attach);
        // the rope runs over a sheave in the jib tip: the hauled-in links pass through the jib
        for (dGeomID link : cable_.geoms) {
            w.exclude_pair(link, jib_geom_);
            w.exclude_pair(link, boom_geom_);
        }
    }

    void control(SceneWorld& w, double t) override {
        (void)w;
        drive_hinge(boom_hinge_, servo_velocity(dJointGetHingeAngle(boom_hinge_), 0, 0.05), kHingeTorque);
        drive_hinge(jib_hinge_, servo_velocity(dJointGetHingeAngle(jib_hinge_), 0, 0.05), kHingeTorque);
        const double ramp = std::clamp(std::min(t - kHoistStart, kHoistEnd - t) / kHoistRamp, 0.0, 1.0);
        drive_slider(hoist_, kHoistSpeed * ramp, kHoistForce);
    }

    SuccessReport success(const SceneWorld& w) const override {
        const double lift = position(module_).z - 0.5 * kModuleSize;
        const double speed = norm(to_vec(dBodyGetLinearVel(module_)));
        const double gap = w.max_joint_error();
        std::ostringstream d;
        d << "module lifted " << lift << " m (needs 3), speed " << speed << " m/s (< 1), joint gap "
          << gap << " m (< 0.01)";
        return {lift > 3 && speed < 1 && gap < 0.01, d.str()};
    }

private:
    dBodyID ship_ = nullptr, pedestal_ = nullptr, boom_ = nullptr, jib_ = nullptr;
    dBodyID block_ = nullptr, module_ = nullptr;
    dJointID boom_hinge_ = nullptr, jib_hinge_ = nullptr, hoist_ = nullptr;
    dGeomID boom_geom_ = nullptr, jib_geom_ = nullptr;
    Cable cable_;
};

}  // namespace

std::unique_ptr<Scene> make_offshore() { return std::make_unique<OffshoreScene>(); }

}  // namespace ode_bpp::scenes
