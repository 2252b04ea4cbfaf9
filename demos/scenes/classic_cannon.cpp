// classic_cannon.cpp: a heavy ball fired from a cannon into a wall of boxes (ODE's cannon demo,
// written anew). The wall first has to stand (resting contact, like the box stack); the impact
// then couples a 40 kg ball with 2 kg boxes in one island of many changing contacts.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

constexpr double kBrickDepth = 0.25, kBrickWidth = 0.6, kBrickHeight = 0.3;  // x, y, z [m]
constexpr double kBrickMass = 2.0;        // [kg]
constexpr int kWallColumns = 4, kWallRows = 5;
constexpr double kWallX = 4.0;            // centre plane of the wall
constexpr double kBrickGap = 0.01;        // between neighbouring columns [m]
constexpr double kBallRadius = 0.3;
constexpr double kBallMass = 40.0;        // 20:1 against a brick
constexpr double kMuzzle[3] = {-2.0, 0.0, 0.8};  // ball centre before the shot
constexpr double kBarrelLength = 1.4, kBarrelRadius = 0.35;
constexpr double kFireTime = 1.0;         // the wall settles first [s]
constexpr double kMuzzleSpeed = 12.0;     // [m/s]
// Aim at the lower third of the wall, so that the rows above lose their support.
constexpr double kAimHeight = kWallRows * kBrickHeight / 3.0;
// Success: before the shot the wall stood (every brick within a small fraction of its smallest
// side of where it was placed); afterwards at least this share of the bricks moved by more than
// a brick height and the ball ended beyond the wall.
constexpr double kStandingDriftFraction = 0.1;
constexpr double kMinKnockedShare = 1.0 / 3.0;

double distance(const dReal* p, const double* q) { return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]); }

/// The wall, a static barrel on a base, and a ball held kinematic in the muzzle until kFireTime.
class Cannon final : public Scene {
public:
    std::string name() const override { return "cannon"; }
    std::string description() const override {
        return "a 40 kg ball fired from a cannon through a wall of 22 bricks";
    }
    double default_seconds() const override { return 5.0; }

    void build(SceneWorld& w) override {
        build_wall(w);
        build_cannon(w);
    }

    void control(SceneWorld& w, double t) override {
        if (fired_ || t < kFireTime) return;
        standing_drift_ = largest_brick_drift();
        dBodySetDynamic(ball_);
        // Elevation for a straight shot at the aim point plus the ballistic drop g t^2 / 2 over
        // the flight time t ~ dx / v (the angle is small, so the horizontal speed is ~ v).
        const double g = w.params().gravity;
        const double dx = kWallX - kMuzzle[0];
        const double flight = dx / kMuzzleSpeed;
        const double rise = kAimHeight - kMuzzle[2] + 0.5 * g * flight * flight;
        const double norm = std::hypot(dx, rise);
        dBodySetLinearVel(ball_, kMuzzleSpeed * dx / norm, 0, kMuzzleSpeed * rise / norm);
        fired_ = true;
    }

    SuccessReport success(const SceneWorld&) const override {
        const double standing_limit = kStandingDriftFraction * std::min({kBrickDepth, kBrickWidth, kBrickHeight});
        int knocked = 0;
        for (const Brick& brick : bricks_)
            if (distance(dBodyGetPosition(brick.body), brick.rest) > kBrickHeight) ++knocked;
        const int needed = int(std::ceil(kMinKnockedShare * bricks_.size()));
        const double ball_x = dBodyGetPosition(ball_)[0];
        const double wall_back = kWallX + 0.5 * kBrickDepth;
        std::ostringstream detail;
        detail << (fired_ ? "" : "not fired; ") << "wall drift before the shot " << standing_drift_ << " m (limit "
               << standing_limit << "); " << knocked << " of " << bricks_.size() << " bricks knocked (needs "
               << needed << "); ball at x=" << ball_x << " (wall back face " << wall_back << ")";
        const bool ok = fired_ && standing_drift_ < standing_limit && knocked >= needed && ball_x > wall_back;
        return {ok, detail.str()};
    }

private:
    struct Brick {
        dBodyID body;
        double rest[3];
    };

    void build_wall(SceneWorld& w) {
        const double pitch = kBrickWidth + kBrickGap;
        for (int row = 0; row < kWallRows; ++row) {
            const double z = (row + 0.5) * kBrickHeight + (row + 1) * 1e-3 * kBrickHeight;
            // Running bond: odd rows are shifted by half a brick and closed by half bricks at
            // the ends, so that every brick rests on two below it and the impact spreads.
            const bool shifted = row % 2 == 1;
            const int full = kWallColumns - (shifted ? 1 : 0);
            for (int col = 0; col < full; ++col) add_brick(w, (col - 0.5 * (full - 1)) * pitch, z, kBrickWidth);
            if (!shifted) continue;
            const double half_y = 0.25 * (2 * kWallColumns - 1) * pitch;
            add_brick(w, -half_y, z, 0.5 * pitch - kBrickGap);
            add_brick(w, half_y, z, 0.5 * pitch - kBrickGap);
        }
    }

    void add_brick(SceneWorld& w, double y, double z, double width) {
        dBodyID body = w.create_body();
        dMass mass;
        dMassSetBoxTotal(&mass, kBrickMass * width / kBrickWidth, kBrickDepth, width, kBrickHeight);
        dBodySetMass(body, &mass);
        dBodySetPosition(body, kWallX, y, z);
        dGeomSetBody(dCreateBox(w.space(), kBrickDepth, width, kBrickHeight), body);
        bricks_.push_back({body, {kWallX, y, z}});
    }

    void build_cannon(SceneWorld& w) {
        ball_ = w.create_body();
        dMass mass;
        dMassSetSphereTotal(&mass, kBallMass, kBallRadius);
        dBodySetMass(ball_, &mass);
        dBodySetPosition(ball_, kMuzzle[0], kMuzzle[1], kMuzzle[2]);
        dBodySetKinematic(ball_);
        dGeomID ball_geom = dCreateSphere(w.space(), kBallRadius);
        dGeomSetBody(ball_geom, ball_);

        // Barrel behind the ball along x (cylinders lie along local z; turn it onto x), on a base.
        dGeomID barrel = dCreateCylinder(w.space(), kBarrelRadius, kBarrelLength);
        dMatrix3 R;
        dRFromAxisAndAngle(R, 0, 1, 0, M_PI / 2);
        dGeomSetRotation(barrel, R);
        dGeomSetPosition(barrel, kMuzzle[0] - 0.5 * kBarrelLength, kMuzzle[1], kMuzzle[2]);
        const double base_height = kMuzzle[2] - kBarrelRadius;
        dGeomID base = dCreateBox(w.space(), 0.6 * kBarrelLength, 2 * kBarrelRadius, base_height);
        dGeomSetPosition(base, kMuzzle[0] - 0.5 * kBarrelLength, kMuzzle[1], 0.5 * base_height);
        w.exclude_pair(barrel, ball_geom);
        w.exclude_pair(base, ball_geom);
    }

    double largest_brick_drift() const {
        double drift = 0;
        for (const Brick& brick : bricks_) drift = std::max(drift, distance(dBodyGetPosition(brick.body), brick.rest));
        return drift;
    }

    std::vector<Brick> bricks_;
    dBodyID ball_ = nullptr;
    bool fired_ = false;
    double standing_drift_ = 0;
};

}  // namespace

std::unique_ptr<Scene> make_classic_cannon() { return std::make_unique<Cannon>(); }

}  // namespace ode_bpp::scenes
