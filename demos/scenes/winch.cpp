// demos/scenes/winch.cpp: Sec. 4.1.6, a chain of 50 x 1 kg capsule links on spherical joints is
// wound onto a 400 kg winch drum turning at constant angular velocity; the part still on the
// ground is dragged along it, so many friction rows slide (tight).
//
// Needed: the drum (hinged to the static environment, driven by a velocity motor), the links
// with their ground, drum and link-link contacts. Nothing else.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scenes/build_helpers.h"
#include "scenes/paper_scenes.h"

namespace ode_bpp::scenes {

namespace {

constexpr int kLinks = 50;
constexpr double kLinkMass = 1.0, kDrumMass = 400;           // Sec. 4.1.6
constexpr double kLinkLength = 0.2, kLinkRadius = 0.025;     // a 10 m chain
// The links' rotational inertia x this (docs/modelling.md, light links under heavy loads): the dragged chain pulls with
// up to ~500 N, and at h = 1/60 the true inertia of a 1 kg link lets the chain kink apart.
constexpr double kLinkInertiaFactor = 100;
constexpr double kDrumRadius = 0.3, kDrumLength = 1.0, kDrumHeight = 1.2;
constexpr double kDrumSpeed = 1.0;       // [rad/s], reached after a 1 s ramp
constexpr double kDrumTorque = 1e5;      // [Nm] enough to keep the speed constant
// A link counts as wound when its centre is this close to the drum's axis.
constexpr double kWoundRadius = kDrumRadius + 0.3;
constexpr int kWoundNeeded = 20;

class WinchScene final : public Scene {
public:
    std::string name() const override { return "winch"; }
    std::string description() const override {
        return "chain of 50 x 1 kg capsules wound onto a 400 kg drum, dragged along the ground";
    }
    TableTwo paper_table_two() const override { return {400, 370, 1e8}; }

    void build(SceneWorld& w) override {
        // the drum sits on a frame above the ground (the frame is the static environment);
        // the chain hangs from the drum's bottom down to the ground at 45 degrees
        drum_centre_ = {0, 0, kDrumHeight};
        dMass m = capsule_mass(kDrumMass, kDrumRadius, kDrumLength);
        drum_ = add_body(w, m, drum_centre_);
        align_z(drum_, {0, 1, 0});
        add_capsule(w, drum_, kDrumRadius, kDrumLength);
        hinge_ = add_hinge(w, drum_, nullptr, drum_centre_, {0, 1, 0});

        CableSpec spec;
        spec.start = {0, 0, kDrumHeight - kDrumRadius - kLinkRadius};
        const double drop = spec.start.z - kLinkRadius;
        spec.via = {{drop, 0, kLinkRadius}};
        spec.end = {kLinks * kLinkLength - drop * std::sqrt(2.0) + drop, 0, kLinkRadius};
        spec.links = kLinks;
        spec.radius = kLinkRadius;
        spec.total_mass = kLinks * kLinkMass;
        spec.inertia_factor = kLinkInertiaFactor;
        chain_ = build_cable(w, spec);
        add_ball(w, drum_, chain_.links.front(), spec.start);
    }

    void control(SceneWorld& w, double t) override {
        (void)w;
        // positive about +y: the drum's bottom moves toward -x, away from the chain, so the
        // chain is pulled in under the drum and wound up its back
        drive_hinge(hinge_, kDrumSpeed * std::min(t, 1.0), kDrumTorque);
    }

    SuccessReport success(const SceneWorld& w) const override {
        const int wound = wound_links();
        const double gap = w.max_joint_error();
        std::ostringstream d;
        d << wound << " of " << kLinks << " links on the drum (needs " << kWoundNeeded
          << "), joint gap " << gap << " m (< 0.01)";
        return {wound >= kWoundNeeded && gap < 0.01, d.str()};
    }

private:
    int wound_links() const {
        int wound = 0;
        for (dBodyID link : chain_.links) {
            const Vec3 p = position(link);
            const double r = std::hypot(p.x - drum_centre_.x, p.z - drum_centre_.z);
            if (r < kWoundRadius && std::abs(p.y) < 0.5 * kDrumLength + kDrumRadius) ++wound;
        }
        return wound;
    }

    Vec3 drum_centre_;
    dBodyID drum_ = nullptr;
    dJointID hinge_ = nullptr;
    Cable chain_;
};

}  // namespace

std::unique_ptr<Scene> make_winch() { return std::make_unique<WinchScene>(); }

}  // namespace ode_bpp::scenes
