// demos/scenes/build_helpers.h: small building blocks shared by the paper's scenes (bodies with
// a total mass, geoms, joints that the world tracks, motors, cables of capsule links).
// World frame everywhere: z up, the ground is the plane z = 0.
#pragma once

#include <ode/ode.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "scenes/scene.h"

namespace ode_bpp::scenes {

struct Vec3 {
    double x = 0, y = 0, z = 0;
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalized(Vec3 a) { return (1.0 / norm(a)) * a; }
inline Vec3 to_vec(const dReal* v) { return {v[0], v[1], v[2]}; }

/// Position of a body's centre of mass, world frame.
inline Vec3 position(dBodyID b) { return to_vec(dBodyGetPosition(b)); }
/// A point given in the body's frame, expressed in the world frame.
Vec3 world_point(dBodyID b, Vec3 local);
/// A world point expressed in the body's frame.
Vec3 local_point(dBodyID b, Vec3 world);
/// A body-frame direction in the world frame.
Vec3 world_vector(dBodyID b, Vec3 local);

/// Mass properties of solid shapes with a prescribed total mass [kg] (lengths in m).
/// Capsules and cylinders lie along the body's z axis.
dMass box_mass(double mass, Vec3 size);
dMass capsule_mass(double mass, double radius, double cylinder_length);
dMass cylinder_mass(double mass, double radius, double length);
dMass sphere_mass(double mass, double radius);
/// Multiplies the rotational inertia by `factor` (the mass stays). Cables take a factor > 1:
/// at h = 1/60 a chain of light links under a heavy load tears with their true inertia (docs/modelling.md).
void scale_inertia(dMass& m, double factor);

/// A tracked body (see SceneWorld::create_body) with mass `m` at `pos`, axes aligned with the world.
dBodyID add_body(SceneWorld& w, const dMass& m, Vec3 pos);
/// Rotates a body so that its z axis points along `axis` (capsules and cylinders along a line).
void align_z(dBodyID b, Vec3 axis);
/// Rotates a body about the world z axis by `yaw` [rad].
void set_yaw(dBodyID b, double yaw);

/// A box-section beam from `from` to `to` (its z axis along the beam), optionally with its geom.
dBodyID add_beam(SceneWorld& w, double mass, double section, Vec3 from, Vec3 to, dGeomID* geom = nullptr);
/// Turns a body (and its geoms) by `angle` [rad] about the world line through `pivot` along `axis`.
void rotate_about(dBodyID b, Vec3 pivot, Vec3 axis, double angle);

/// Geoms on `body` (null: static), centred at `offset` in the body's frame (world frame if
/// static). `axis` (unit, body frame) orients capsules and cylinders; default z.
dGeomID add_box(SceneWorld& w, dBodyID body, Vec3 size, Vec3 offset = {});
dGeomID add_capsule(SceneWorld& w, dBodyID body, double radius, double cylinder_length,
                    Vec3 offset = {}, Vec3 axis = {0, 0, 1});
dGeomID add_cylinder(SceneWorld& w, dBodyID body, double radius, double length,
                     Vec3 offset = {}, Vec3 axis = {0, 0, 1});
dGeomID add_sphere(SceneWorld& w, dBodyID body, double radius, Vec3 offset = {});
/// A static box rotated about the world y axis by `pitch` [rad] (ramps, hills).
dGeomID add_static_box(SceneWorld& w, Vec3 size, Vec3 centre, double pitch = 0);

/// Joints in the world's main group; a null body means the static environment.
/// ball and hinge are tracked by the world (anchor drift, SceneWorld::max_joint_error).
dJointID add_ball(SceneWorld& w, dBodyID a, dBodyID b, Vec3 anchor);
dJointID add_hinge(SceneWorld& w, dBodyID a, dBodyID b, Vec3 anchor, Vec3 axis);
dJointID add_slider(SceneWorld& w, dBodyID a, dBodyID b, Vec3 axis);
dJointID add_fixed(SceneWorld& w, dBodyID a, dBodyID b);

/// A hydraulic cylinder from point `a` on body A to point `b` on body B (world frame, null: the
/// static environment): a barrel hinged to A at a and a rod hinged to B at b, both about
/// `hinge_axis`, sliding on each other along a -> b. Returns the slider: its motor is the
/// cylinder (drive_slider), its force limit the pressure.
dJointID add_hydraulic_cylinder(SceneWorld& w, dBodyID A, Vec3 a, dBodyID B, Vec3 b, double barrel_mass,
                                double rod_mass, Vec3 hinge_axis = {0, 1, 0});

/// Velocity motors: the joint drives its coordinate at `velocity` [rad/s or m/s] with at most
/// `max_force` [Nm or N] (one boxed row of the MLCP, |impulse| <= max_force * h). The motor row's
/// CFM is kDriveCfm whatever the world's: the paper's compliance is that of the joints and
/// contacts; a drive with CFM = c/h is a damper that yields CFM x its load per step (the crane's
/// luff drive, ~6.5e5 Nm at CFM 6e-7 (c = 1e-8): 0.4 rad/s, so the boom sank and the pipe
/// stayed on the ground with either solver).
constexpr double kDriveCfm = 1e-10;  ///< ODE's default CFM: a drive as stiff as ODE makes it
void drive_hinge(dJointID hinge, double velocity, double max_force);
void drive_slider(dJointID slider, double velocity, double max_force);
/// Stops on a hinge or slider coordinate [rad or m] (a unilateral row when one is reached).
void limit_hinge(dJointID hinge, double lo, double hi);
void limit_slider(dJointID slider, double lo, double hi);
/// Velocity that moves a joint coordinate toward `target` at no more than `max_speed`,
/// reaching it without overshoot within about `settle` seconds (a servo for position targets).
double servo_velocity(double current, double target, double max_speed, double settle = 0.5);

/// A cable or chain: capsule links joined by ball joints from `start` through `via` to `end`;
/// the joints lie on that polyline, equally spaced along it.
struct CableSpec {
    Vec3 start, end;
    std::vector<Vec3> via;         ///< corners between start and end, in order
    int links = 10;
    double radius = 0.02;          ///< capsule radius [m]
    double total_mass = 10;        ///< [kg], shared equally by the links
    double inertia_factor = 1;     ///< see scale_inertia()
    bool collide = true;           ///< links get capsule geoms
};
struct Cable {
    std::vector<dBodyID> links;    ///< from start to end
    std::vector<dGeomID> geoms;    ///< empty unless collide
    std::vector<dJointID> joints;  ///< links.size() - 1 ball joints
    double link_length = 0;
};
/// Builds the links and the ball joints between them; attaching the ends is the caller's.
Cable build_cable(SceneWorld& w, const CableSpec& spec);
/// World position of the start (k = 0) or end (k = 1) point of a link of the cable.
Vec3 link_end(const Cable& c, size_t link, int k);

/// A rigid body made of several geoms, each carrying part of the mass. Offsets and axes are
/// given in a reference frame whose axes are the world's; build() moves the body origin to the
/// combined centre of mass (ODE requires it there) and shifts the geoms to match.
class CompositeBody {
public:
    void box(Vec3 size, Vec3 offset, double mass, Vec3 axis = {0, 0, 1}, double angle = 0);
    void capsule(double radius, double cylinder_length, Vec3 offset, Vec3 axis, double mass);
    void cylinder(double radius, double length, Vec3 offset, Vec3 axis, double mass);
    /// Mass carried without a geom (e.g. a counterweight inside a housing).
    void point_mass(Vec3 offset, double mass);
    /// Centre of mass in the reference frame.
    Vec3 centre() const;
    double mass() const;
    /// Creates the body with its reference point at `reference` (world), axes along the world.
    dBodyID build(SceneWorld& w, Vec3 reference, std::vector<dGeomID>* geoms = nullptr) const;

private:
    enum class Shape { Box, Capsule, Cylinder, None };
    struct Part {
        Shape shape;
        Vec3 size;      ///< box: sides; capsule/cylinder: (radius, length, 0)
        Vec3 offset;
        dMatrix3 R;
        dMass mass;     ///< about the part's own centre, rotated into the reference frame
    };
    std::vector<Part> parts_;
    void add(Shape shape, Vec3 size, Vec3 offset, const dMatrix3 R, dMass m);
};

/// An open bin on the ground: four static walls around the rectangle |x - centre.x| < inner.x / 2,
/// |y - centre.y| < inner.y / 2 (inner.z: the walls' height), `thickness` thick; the ground is
/// its floor.
void add_bin(SceneWorld& w, Vec3 centre, Vec3 inner, double thickness);

/// Largest linear speed [m/s] of the world's bodies (at rest: near 0).
double fastest_body_speed(const SceneWorld& w);

/// Seeded uniform numbers, the same on every machine (std::mt19937_64 with an explicit
/// transform: the standard distributions differ between libraries), for scenes whose bodies
/// are placed at random.
class SceneRandom {
public:
    explicit SceneRandom(std::uint64_t seed) : engine_(seed) {}
    /// Uniform in [lo, hi).
    double uniform(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    }

private:
    std::mt19937_64 engine_;
};

/// The angle [rad] between the body's z axis and the world's z axis (tilt of a vehicle).
double tilt(dBodyID b);

}  // namespace ode_bpp::scenes
