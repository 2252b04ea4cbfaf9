// demos/scenes/crane.cpp: Sec. 4.1.2, a 30,000 kg mobile crane hoists a 2,000 kg concrete pipe
// with a 70 kg steel cable and a 70 kg hook; contacts appear when the hook touches the pipe.
//
// What the phenomenon needs, and nothing else:
//  - the crane: a chassis standing on the ground and a boom on a held luffing hinge, so that the
//    heavy crane and the light cable share one island (mass ratio, Table 2);
//  - a hoist: a block sliding up the boom tip on a velocity-driven slider (the rope pay-in);
//  - the cable: capsule links on ball joints, their inertia inflated (docs/modelling.md, light links under heavy loads);
//  - a C-hook (with its counterweight, as real C-hooks have) whose lower arm sits in the pipe's
//    bore: hoisting brings it into contact with the bore, and the pipe hangs by that contact;
//  - the pipe: a ring of boxes resting on the ground.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scenes/build_helpers.h"
#include "scenes/paper_scenes.h"

namespace ode_bpp::scenes {

namespace {

constexpr double kPi = 3.14159265358979323846;

// masses [kg]: Sec. 4.1.2
constexpr double kCraneMass = 30000, kBoomMass = 4000, kBlockMass = 300;
constexpr double kChassisMass = kCraneMass - kBoomMass - kBlockMass;
constexpr double kCableMass = 70, kHookMass = 70, kPipeMass = 2000;

// geometry [m]
constexpr double kBoomLength = 18, kBoomElevation = 50 * kPi / 180;
constexpr int kCableLinks = 130;     // sets the island's size (Table 2: 430 rows)
constexpr double kCableRadius = 0.02;
// Link inertia x this: at h = 1/60 the links' true inertia lets the cable tear under the
// 2 t load (docs/modelling.md, light links under heavy loads): under 2e4 N the links' transverse mode is far faster than
// 1/h. 1e3 still leaves mm gaps; 1e4 keeps the joints closed to ~2e-5 m.
constexpr double kCableInertiaFactor = 10000;
constexpr double kPipeOuter = 0.70, kPipeInner = 0.55, kPipeLength = 1.5;
constexpr int kPipeSegments = 12;
constexpr double kArmRadius = 0.1;   // the hook's lower arm
constexpr double kArmHeight = 0.80;  // above ground, inside the bore (0.15 .. 1.25)
constexpr double kHookDrop = 1.0;    // from the attachment point down to the lower arm

// the hoist [s, m/s]
constexpr double kHoistStart = 2.0, kHoistEnd = 14.0, kHoistSpeed = 0.25, kHoistRamp = 1.0;
constexpr double kHoistForce = 2e5;         // [N] a 20 t winch
constexpr double kLuffTorque = 5e7;         // [Nm] holds the boom and its load

class CraneScene final : public Scene {
public:
    std::string name() const override { return "crane"; }
    std::string description() const override {
        return "30 t mobile crane hoists a 2 t concrete pipe on a 70 kg cable and 70 kg C-hook";
    }
    TableTwo paper_table_two() const override { return {6300, 430, 1e9}; }

    void build(SceneWorld& w) override {
        chassis_ = add_body(w, box_mass(kChassisMass, {10, 3, 2}), {0, 0, 1});
        add_box(w, chassis_, {10, 3, 2});

        const Vec3 pivot{-3, 0, 2.2};
        const Vec3 along{std::cos(kBoomElevation), 0, std::sin(kBoomElevation)};
        const Vec3 tip = pivot + kBoomLength * along;
        boom_ = add_body(w, box_mass(kBoomMass, {kBoomLength, 0.8, 0.8}), pivot + (0.5 * kBoomLength) * along);
        dMatrix3 R;
        dRFromAxisAndAngle(R, 0, 1, 0, -kBoomElevation);
        dBodySetRotation(boom_, R);
        add_box(w, boom_, {kBoomLength, 0.8, 0.8});
        luff_ = add_hinge(w, chassis_, boom_, pivot, {0, 1, 0});

        const Vec3 block_pos = tip - Vec3{0, 0, 0.6};
        block_ = add_body(w, box_mass(kBlockMass, {0.5, 0.5, 0.5}), block_pos);
        hoist_ = add_slider(w, block_, boom_, {0, 0, 1});

        const Vec3 pipe_centre{tip.x, 0, kPipeOuter};
        build_pipe(w, pipe_centre);
        const Vec3 attach{tip.x, 0, kArmHeight + kHookDrop};
        build_hook(w, attach);

        CableSpec spec;
        spec.start = block_pos - Vec3{0, 0, 0.25};
        spec.end = attach;
        spec.links = kCableLinks;
        spec.radius = kCableRadius;
        spec.total_mass = kCableMass;
        spec.inertia_factor = kCableInertiaFactor;
        spec.collide = false;  // it hangs free: no contact the phenomenon needs
        cable_ = build_cable(w, spec);
        add_ball(w, block_, cable_.links.front(), spec.start);
        add_ball(w, cable_.links.back(), hook_, attach);
    }

    void control(SceneWorld& w, double t) override {
        (void)w;
        drive_hinge(luff_, servo_velocity(dJointGetHingeAngle(luff_), 0, 0.05), kLuffTorque);
        const double ramp = std::clamp(std::min(t - kHoistStart, kHoistEnd - t) / kHoistRamp, 0.0, 1.0);
        drive_slider(hoist_, kHoistSpeed * ramp, kHoistForce);
    }

    SuccessReport success(const SceneWorld& w) const override {
        const Vec3 pipe = position(pipe_);
        const Vec3 hook = position(hook_);
        const double lift = pipe.z - kPipeOuter;
        const double speed = norm(to_vec(dBodyGetLinearVel(pipe_)));
        const double offset = std::hypot(pipe.x - hook.x, pipe.y - hook.y);
        const double gap = w.max_joint_error();
        std::ostringstream d;
        d << "pipe lifted " << lift << " m (needs 1.5), speed " << speed << " m/s (< 0.5), "
          << offset << " m beside the hook (< 1), joint gap " << gap << " m (< 0.01)";
        return {lift > 1.5 && speed < 0.5 && offset < 1.0 && gap < 0.01, d.str()};
    }

private:
    // A ring of boxes around the x axis; the flat bottom segment rests on the ground.
    void build_pipe(SceneWorld& w, Vec3 centre) {
        CompositeBody pipe;
        const double mid = 0.5 * (kPipeOuter + kPipeInner), wall = kPipeOuter - kPipeInner;
        const double width = 2 * kPipeOuter * std::tan(kPi / kPipeSegments);
        for (int k = 0; k < kPipeSegments; ++k) {
            const double phi = 2 * kPi * k / kPipeSegments;
            pipe.box({kPipeLength, width, wall}, {0, -mid * std::sin(phi), mid * std::cos(phi)},
                     kPipeMass / kPipeSegments, {1, 0, 0}, phi);
        }
        pipe_ = pipe.build(w, centre);
    }

    // A C-hook: the top arm carries the cable attachment (the reference point) and a
    // counterweight that puts the hook's centre of mass under the attachment; the vertical
    // arm passes outside the pipe's end; the lower arm reaches into the bore, past the pipe's
    // centre, so that the pipe balances on it.
    void build_hook(SceneWorld& w, Vec3 attach) {
        const double arm_x = -1.2, lower_mass = 15, vertical_mass = 15;
        const double counterweight_x = 1.2;
        // moment balance about the attachment: sum m_i x_i = 0
        const double counterweight = -(vertical_mass * arm_x + lower_mass * -0.5) / counterweight_x;
        const double top_mass = kHookMass - lower_mass - vertical_mass - counterweight;
        CompositeBody hook;
        hook.box({2.6, 0.2, 0.2}, {0, 0, 0}, top_mass);
        hook.box({0.2, 0.2, 0.3}, {counterweight_x, 0, -0.05}, counterweight);
        hook.box({0.2, 0.2, kHookDrop}, {arm_x, 0, -0.5 * kHookDrop}, vertical_mass);
        hook.capsule(kArmRadius, 1.2, {-0.5, 0, -kHookDrop}, {1, 0, 0}, lower_mass);
        hook_ = hook.build(w, attach);
    }

    dBodyID chassis_ = nullptr, boom_ = nullptr, block_ = nullptr, hook_ = nullptr, pipe_ = nullptr;
    dJointID luff_ = nullptr, hoist_ = nullptr;
    Cable cable_;
};

}  // namespace

std::unique_ptr<Scene> make_crane() { return std::make_unique<CraneScene>(); }

}  // namespace ode_bpp::scenes
