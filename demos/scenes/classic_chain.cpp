// classic_chain.cpp: a chain of capsules on ball joints, hung from a fixed point and released
// horizontally so that it swings (ODE's chain demos, written anew). The chain is one island of
// 3 rows per joint coupled end to end: a banded MLCP whose joint rows are all unbounded.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

constexpr int kLinks = 12;
constexpr double kLinkLength = 0.4;      // capsule length incl. caps [m]
constexpr double kLinkRadius = 0.05;
constexpr double kLinkMass = 1.0;        // [kg]
constexpr double kBobRadius = 0.15;
constexpr double kBobMass = 10.0;        // a heavy end mass, 10:1 against a link
constexpr double kAnchorHeight = 6.5;    // above the ground; the hanging chain clears it
constexpr double kReleaseAngle = 0.5;    // straight chain released this far below the horizontal [rad]
// A chain "stays connected" when every ball joint's two anchors stay within this fraction
// of a link length of each other over the whole run. Joint rows are linearised, so a link
// turning at omega drifts by about (omega h)^2 L / 2 per step while ERP removes a fraction ERP
// of the gap per step: the gap stays below (omega h)^2 L / (2 ERP), 8 % of L at the fastest
// link here (omega ~ 11 rad/s). Dantzig keeps it at 2.4 %; a solver that leaves joint rows
// unsatisfied lets the gap grow step after step.
constexpr double kMaxJointErrorFraction = 0.05;
// The chain must actually swing: its tip has to pass below the anchor by most of its length.
constexpr double kMinTipDropFraction = 0.8;

/// Point at arc length s [m] along the straight chain as released.
struct ReleaseLine {
    double x(double s) const { return s * std::cos(kReleaseAngle); }
    double z(double s) const { return kAnchorHeight - s * std::sin(kReleaseAngle); }
};

/// kLinks capsules and an end bob released as a straight line kReleaseAngle below the
/// horizontal. Success: the largest ball-joint error over the run stays below
/// kMaxJointErrorFraction * link length, and the tip swung down past kMinTipDropFraction of the
/// chain's length below the anchor.
class Chain final : public Scene {
public:
    std::string name() const override { return "chain"; }
    std::string description() const override {
        return "12 capsules and a 10 kg bob on ball joints swinging from a fixed point";
    }
    double default_seconds() const override { return 6.0; }

    void build(SceneWorld& w) override {
        dBodyID previous = nullptr;  // the static environment
        for (int i = 0; i < kLinks; ++i) {
            dBodyID link = add_link(w, (i + 0.5) * kLinkLength);
            connect(w, previous, link, i * kLinkLength);
            previous = link;
        }
        tip_ = add_bob(w, kLinks * kLinkLength + kBobRadius);
        connect(w, previous, tip_, kLinks * kLinkLength);
    }

    void control(SceneWorld& w, double) override {
        worst_error_ = std::max(worst_error_, w.max_joint_error());
        lowest_tip_ = std::min(lowest_tip_, double(dBodyGetPosition(tip_)[2]));
    }

    SuccessReport success(const SceneWorld& w) const override {
        const double worst = std::max(worst_error_, w.max_joint_error());
        const double error_limit = kMaxJointErrorFraction * kLinkLength;
        const double chain_length = kLinks * kLinkLength + kBobRadius;
        const double tip_drop = kAnchorHeight - std::min(lowest_tip_, double(dBodyGetPosition(tip_)[2]));
        std::ostringstream detail;
        detail << kLinks + 1 << " ball joints: largest anchor gap " << worst << " m (limit " << error_limit
               << "); tip dropped " << tip_drop << " m (needs " << kMinTipDropFraction * chain_length << ")";
        return {worst < error_limit && tip_drop > kMinTipDropFraction * chain_length, detail.str()};
    }

private:
    dBodyID add_link(SceneWorld& w, double s) {
        dBodyID link = w.create_body();
        dMass mass;
        dMassSetCapsuleTotal(&mass, kLinkMass, 3, kLinkRadius, kLinkLength - 2 * kLinkRadius);
        dBodySetMass(link, &mass);
        // Capsules lie along their local z axis: turn it onto the release line (cos a, 0, -sin a).
        dMatrix3 R;
        dRFromAxisAndAngle(R, 0, 1, 0, M_PI / 2 + kReleaseAngle);
        dBodySetRotation(link, R);
        dBodySetPosition(link, line_.x(s), 0, line_.z(s));
        dGeomSetBody(dCreateCapsule(w.space(), kLinkRadius, kLinkLength - 2 * kLinkRadius), link);
        return link;
    }

    dBodyID add_bob(SceneWorld& w, double s) {
        dBodyID bob = w.create_body();
        dMass mass;
        dMassSetSphereTotal(&mass, kBobMass, kBobRadius);
        dBodySetMass(bob, &mass);
        dBodySetPosition(bob, line_.x(s), 0, line_.z(s));
        dGeomSetBody(dCreateSphere(w.space(), kBobRadius), bob);
        return bob;
    }

    void connect(SceneWorld& w, dBodyID a, dBodyID b, double s) {
        dJointID joint = dJointCreateBall(w.world(), nullptr);
        dJointAttach(joint, b, a);  // body 1 is never the environment
        dJointSetBallAnchor(joint, line_.x(s), 0, line_.z(s));
        w.track_joint(joint);
    }

    ReleaseLine line_;
    dBodyID tip_ = nullptr;
    double worst_error_ = 0;
    double lowest_tip_ = kAnchorHeight;
};

}  // namespace

std::unique_ptr<Scene> make_classic_chain() { return std::make_unique<Chain>(); }

}  // namespace ode_bpp::scenes
