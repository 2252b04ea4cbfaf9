// classic_islands.cpp: many tiny independent mechanisms, each its own island of 3 to 12 rows,
// as games built on ODE step them (a ball maze: marbles, crates, swinging gates). The world step
// then solves dozens of tiny MLCPs per step, where a solver's fixed cost per island, not its
// pivoting, decides its speed (the small-island benchmark of docs/benchmarks.md).
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

#include "scenes/build_helpers.h"
#include "scenes/joint_gap.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

constexpr int kEach = 16;                // mechanisms of each kind
constexpr double kPitch = 2.0;           // grid spacing of crates and pendulums [m]
constexpr double kMarbleRadius = 0.1;    // [m]
constexpr double kMarbleMass = 0.2;      // [kg]
constexpr double kLaneWidth = 0.5;       // marbles roll in parallel lanes, never meeting [m]
constexpr double kMarbleSpeed = 0.3;     // [m/s] of the slowest marble; lane k rolls (1 + k/8) times faster
constexpr double kCrateEdge = 0.4;       // [m]
constexpr double kCrateMass = 5.0;       // [kg]
constexpr double kDrop = 1e-3;           // crates start this far above the ground [m]
constexpr double kPivotHeight = 2.0;     // [m] of the pendulums' and gates' pivots
constexpr double kArm = 0.5;             // pendulum arm and gate link length [m]
constexpr double kBobMass = 1.0;         // [kg]
constexpr double kRelease = 0.6;         // pendulums and gates start this far from hanging [rad]
// A marble rolling without slip on a level plane keeps its speed (ODE has no rolling friction):
// it must cover its speed x time within this fraction.
constexpr double kRollTolerance = 0.05;
// A crate at rest stays where it was put, within this distance [m] (a tenth of the contact
// surface layer's order of give, far below a visible slide).
constexpr double kCrateDrift = 0.01;
// Joints (hinges and balls) keep their anchors within this gap [m]. Joint rows are linearised, so
// a body turning at omega drifts by about (omega h)^2 L / 2 per step while ERP removes a fraction
// ERP of the gap per step: the gap stays below (omega h)^2 L / (2 ERP), 2.4 mm at the fastest bob
// here (omega ~ 2.6 rad/s, classic_chain.cpp makes the same estimate); a solver that leaves joint
// rows unsatisfied lets it grow step after step.
constexpr double kMaxGap = 0.01;

struct Marble {
    dBodyID body;
    double start_x;
    double speed;
};

struct Crate {
    dBodyID body;
    Vec3 rest;
};

/// kEach marbles rolling in lanes (3 rows each: one contact with friction), kEach crates resting
/// on the ground (four contacts, 12 rows), kEach hinged pendulums (5 rows) and kEach two-link
/// gates on ball joints (6 rows): 4 kEach islands. Success: every marble rolled its speed x time
/// (within kRollTolerance) on the ground, every crate stayed within kCrateDrift of its place,
/// every joint kept its anchors within kMaxGap over the whole run.
class TinyIslands final : public Scene {
public:
    std::string name() const override { return "islands"; }
    std::string description() const override {
        return "64 tiny independent islands: marbles, crates, pendulums, two-link gates (3 to 12 rows each)";
    }
    double default_seconds() const override { return 10.0; }

    void build(SceneWorld& w) override {
        for (int k = 0; k < kEach; ++k) {
            add_marble(w, k);
            const double x = (k % 4) * kPitch, y = (k / 4) * kPitch;
            add_crate(w, {x, y, 0});
            add_pendulum(w, {x + 4 * kPitch, y, kPivotHeight});
            add_gate(w, {x + 8 * kPitch, y, kPivotHeight});
        }
    }

    void control(SceneWorld& w, double t) override {
        (void)t;
        worst_gap_ = std::max(worst_gap_, max_anchor_gap(w.bodies()));
        elapsed_ = w.time();
    }

    SuccessReport success(const SceneWorld& w) const override {
        const double elapsed = std::max(elapsed_, w.time());
        const double gap = std::max(worst_gap_, max_anchor_gap(w.bodies()));
        double worst_roll = 0, worst_height = 0, worst_drift = 0;
        for (const Marble& m : marbles_) {
            const double expected = m.speed * elapsed;
            const double rolled = position(m.body).x - m.start_x;
            worst_roll = std::max(worst_roll, expected > 0 ? std::fabs(rolled / expected - 1) : 1.0);
            worst_height = std::max(worst_height, std::fabs(position(m.body).z - kMarbleRadius));
        }
        for (const Crate& c : crates_) worst_drift = std::max(worst_drift, norm(position(c.body) - c.rest));
        std::ostringstream d;
        d << "marbles rolled within " << 100 * worst_roll << " % of speed x time (limit " << 100 * kRollTolerance
          << " %), off the ground by " << worst_height << " m; crates drifted " << worst_drift << " m (< "
          << kCrateDrift << "); joint gap " << gap << " m (< " << kMaxGap << ")";
        const bool ok = elapsed > 0 && worst_roll < kRollTolerance && worst_height < kCrateDrift &&
                        worst_drift < kCrateDrift && gap < kMaxGap;
        return {ok, d.str()};
    }

private:
    void add_marble(SceneWorld& w, int lane) {
        const double speed = kMarbleSpeed * (1 + lane / 8.0);
        const Vec3 start{0, -4 - lane * kLaneWidth, kMarbleRadius};
        dBodyID b = add_body(w, sphere_mass(kMarbleMass, kMarbleRadius), start);
        add_sphere(w, b, kMarbleRadius);
        dBodySetLinearVel(b, speed, 0, 0);
        dBodySetAngularVel(b, 0, speed / kMarbleRadius, 0);  // rolling along +x without slip
        marbles_.push_back({b, start.x, speed});
    }

    void add_crate(SceneWorld& w, Vec3 ground) {
        const Vec3 rest = ground + Vec3{0, 0, 0.5 * kCrateEdge};
        dBodyID b = add_body(w, box_mass(kCrateMass, {kCrateEdge, kCrateEdge, kCrateEdge}), rest + Vec3{0, 0, kDrop});
        add_box(w, b, {kCrateEdge, kCrateEdge, kCrateEdge});
        crates_.push_back({b, rest});
    }

    static Vec3 swung(Vec3 pivot, double length) {
        return pivot + Vec3{length * std::sin(kRelease), 0, -length * std::cos(kRelease)};
    }

    void add_pendulum(SceneWorld& w, Vec3 pivot) {
        dBodyID bob = add_body(w, sphere_mass(kBobMass, 0.1), swung(pivot, kArm));
        add_hinge(w, nullptr, bob, pivot, {0, 1, 0});
    }

    void add_gate(SceneWorld& w, Vec3 pivot) {
        const Vec3 joint = swung(pivot, kArm);
        dBodyID upper = add_beam(w, kBobMass, 0.05, pivot, joint);
        dBodyID lower = add_beam(w, kBobMass, 0.05, joint, swung(joint, kArm));
        add_ball(w, nullptr, upper, pivot);
        add_ball(w, upper, lower, joint);
    }

    std::vector<Marble> marbles_;
    std::vector<Crate> crates_;
    double worst_gap_ = 0;
    double elapsed_ = 0;
};

}  // namespace

std::unique_ptr<Scene> make_classic_islands() { return std::make_unique<TinyIslands>(); }

}  // namespace ode_bpp::scenes
