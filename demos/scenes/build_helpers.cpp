// demos/scenes/build_helpers.cpp
#include "scenes/build_helpers.h"

#include <algorithm>

namespace ode_bpp::scenes {

Vec3 world_point(dBodyID b, Vec3 local) {
    dVector3 r;
    dBodyGetRelPointPos(b, local.x, local.y, local.z, r);
    return to_vec(r);
}

Vec3 local_point(dBodyID b, Vec3 world) {
    dVector3 r;
    dBodyGetPosRelPoint(b, world.x, world.y, world.z, r);
    return to_vec(r);
}

Vec3 world_vector(dBodyID b, Vec3 local) {
    dVector3 r;
    dBodyVectorToWorld(b, local.x, local.y, local.z, r);
    return to_vec(r);
}

dMass box_mass(double mass, Vec3 size) {
    dMass m;
    dMassSetBoxTotal(&m, mass, size.x, size.y, size.z);
    return m;
}

dMass capsule_mass(double mass, double radius, double cylinder_length) {
    dMass m;
    dMassSetCapsuleTotal(&m, mass, 3, radius, cylinder_length);
    return m;
}

dMass cylinder_mass(double mass, double radius, double length) {
    dMass m;
    dMassSetCylinderTotal(&m, mass, 3, radius, length);
    return m;
}

dMass sphere_mass(double mass, double radius) {
    dMass m;
    dMassSetSphereTotal(&m, mass, radius);
    return m;
}

void scale_inertia(dMass& m, double factor) {
    for (dReal& entry : m.I) entry *= factor;
}

dBodyID add_body(SceneWorld& w, const dMass& m, Vec3 pos) {
    dBodyID b = w.create_body();
    dBodySetMass(b, &m);
    dBodySetPosition(b, pos.x, pos.y, pos.z);
    return b;
}

void align_z(dBodyID b, Vec3 axis) {
    dMatrix3 R;
    dRFromZAxis(R, axis.x, axis.y, axis.z);
    dBodySetRotation(b, R);
}

void set_yaw(dBodyID b, double yaw) {
    dMatrix3 R;
    dRFromAxisAndAngle(R, 0, 0, 1, yaw);
    dBodySetRotation(b, R);
}

dBodyID add_beam(SceneWorld& w, double mass, double section, Vec3 from, Vec3 to, dGeomID* geom) {
    const double length = norm(to - from);
    dBodyID b = add_body(w, box_mass(mass, {section, section, length}), 0.5 * (from + to));
    align_z(b, to - from);
    if (geom) *geom = add_box(w, b, {section, section, length});
    return b;
}

void rotate_about(dBodyID b, Vec3 pivot, Vec3 axis, double angle) {
    dMatrix3 turn, R;
    dRFromAxisAndAngle(turn, axis.x, axis.y, axis.z, angle);
    dMultiply0_333(R, turn, dBodyGetRotation(b));
    const Vec3 r = position(b) - pivot;
    dVector3 rr;
    const dReal rv[4] = {r.x, r.y, r.z, 0};
    dMultiply0_331(rr, turn, rv);
    dBodySetRotation(b, R);
    dBodySetPosition(b, pivot.x + rr[0], pivot.y + rr[1], pivot.z + rr[2]);
}

namespace {

dGeomID place(dGeomID g, dBodyID body, Vec3 offset, Vec3 axis) {
    dMatrix3 R;
    // dRFromZAxis turns x and y about z even for axis = z: boxes would swap their sides
    if (axis.x == 0 && axis.y == 0 && axis.z > 0) dRSetIdentity(R);
    else dRFromZAxis(R, axis.x, axis.y, axis.z);
    if (body) {
        dGeomSetBody(g, body);
        dGeomSetOffsetPosition(g, offset.x, offset.y, offset.z);
        dGeomSetOffsetRotation(g, R);
    } else {
        dGeomSetPosition(g, offset.x, offset.y, offset.z);
        dGeomSetRotation(g, R);
    }
    return g;
}

}  // namespace

dGeomID add_box(SceneWorld& w, dBodyID body, Vec3 size, Vec3 offset) {
    return place(dCreateBox(w.space(), size.x, size.y, size.z), body, offset, {0, 0, 1});
}

dGeomID add_capsule(SceneWorld& w, dBodyID body, double radius, double cylinder_length,
                    Vec3 offset, Vec3 axis) {
    return place(dCreateCapsule(w.space(), radius, cylinder_length), body, offset, axis);
}

dGeomID add_cylinder(SceneWorld& w, dBodyID body, double radius, double length, Vec3 offset,
                     Vec3 axis) {
    return place(dCreateCylinder(w.space(), radius, length), body, offset, axis);
}

dGeomID add_sphere(SceneWorld& w, dBodyID body, double radius, Vec3 offset) {
    return place(dCreateSphere(w.space(), radius), body, offset, {0, 0, 1});
}

dGeomID add_static_box(SceneWorld& w, Vec3 size, Vec3 centre, double pitch) {
    dGeomID g = dCreateBox(w.space(), size.x, size.y, size.z);
    dGeomSetPosition(g, centre.x, centre.y, centre.z);
    dMatrix3 R;
    dRFromAxisAndAngle(R, 0, 1, 0, pitch);
    dGeomSetRotation(g, R);
    return g;
}

dJointID add_ball(SceneWorld& w, dBodyID a, dBodyID b, Vec3 anchor) {
    dJointID j = dJointCreateBall(w.world(), nullptr);
    dJointAttach(j, a, b);
    dJointSetBallAnchor(j, anchor.x, anchor.y, anchor.z);
    w.track_joint(j);
    return j;
}

dJointID add_hinge(SceneWorld& w, dBodyID a, dBodyID b, Vec3 anchor, Vec3 axis) {
    dJointID j = dJointCreateHinge(w.world(), nullptr);
    dJointAttach(j, a, b);
    dJointSetHingeAnchor(j, anchor.x, anchor.y, anchor.z);
    dJointSetHingeAxis(j, axis.x, axis.y, axis.z);
    w.track_joint(j);
    return j;
}

dJointID add_slider(SceneWorld& w, dBodyID a, dBodyID b, Vec3 axis) {
    dJointID j = dJointCreateSlider(w.world(), nullptr);
    dJointAttach(j, a, b);
    dJointSetSliderAxis(j, axis.x, axis.y, axis.z);
    return j;
}

dJointID add_hydraulic_cylinder(SceneWorld& w, dBodyID A, Vec3 a, dBodyID B, Vec3 b, double barrel_mass,
                                double rod_mass, Vec3 hinge_axis) {
    const Vec3 u = normalized(b - a);
    const double length = norm(b - a);
    dBodyID barrel = add_beam(w, barrel_mass, 0.12, a, a + (0.55 * length) * u);
    dBodyID rod = add_beam(w, rod_mass, 0.06, b - (0.55 * length) * u, b);
    add_hinge(w, A, barrel, a, hinge_axis);
    add_hinge(w, rod, B, b, hinge_axis);
    return add_slider(w, rod, barrel, u);
}

dJointID add_fixed(SceneWorld& w, dBodyID a, dBodyID b) {
    dJointID j = dJointCreateFixed(w.world(), nullptr);
    dJointAttach(j, a, b);
    dJointSetFixed(j);
    return j;
}

void drive_hinge(dJointID hinge, double velocity, double max_force) {
    dJointSetHingeParam(hinge, dParamVel, velocity);
    dJointSetHingeParam(hinge, dParamFMax, max_force);
    dJointSetHingeParam(hinge, dParamCFM, kDriveCfm);
}

void drive_slider(dJointID slider, double velocity, double max_force) {
    dJointSetSliderParam(slider, dParamVel, velocity);
    dJointSetSliderParam(slider, dParamFMax, max_force);
    dJointSetSliderParam(slider, dParamCFM, kDriveCfm);
}

void limit_hinge(dJointID hinge, double lo, double hi) {
    dJointSetHingeParam(hinge, dParamLoStop, lo);
    dJointSetHingeParam(hinge, dParamHiStop, hi);
}

void limit_slider(dJointID slider, double lo, double hi) {
    dJointSetSliderParam(slider, dParamLoStop, lo);
    dJointSetSliderParam(slider, dParamHiStop, hi);
}

double servo_velocity(double current, double target, double max_speed, double settle) {
    return std::clamp((target - current) / settle, -max_speed, max_speed);
}

namespace {

// The point at arc length s along the polyline (clamped to its end).
Vec3 along_polyline(const std::vector<Vec3>& pts, double s) {
    for (size_t k = 0; k + 1 < pts.size(); ++k) {
        const double len = norm(pts[k + 1] - pts[k]);
        if (s <= len || k + 2 == pts.size()) return pts[k] + (std::min(s, len) / len) * (pts[k + 1] - pts[k]);
        s -= len;
    }
    return pts.back();
}

}  // namespace

Cable build_cable(SceneWorld& w, const CableSpec& spec) {
    std::vector<Vec3> pts{spec.start};
    pts.insert(pts.end(), spec.via.begin(), spec.via.end());
    pts.push_back(spec.end);
    double total = 0;
    for (size_t k = 0; k + 1 < pts.size(); ++k) total += norm(pts[k + 1] - pts[k]);
    Cable c;
    c.link_length = total / spec.links;
    // the capsule's caps end at the joints: cylinder part = link length - 2 r
    const double cylinder = std::max(c.link_length - 2 * spec.radius, 0.1 * c.link_length);
    dMass m = capsule_mass(spec.total_mass / spec.links, spec.radius, cylinder);
    scale_inertia(m, spec.inertia_factor);
    for (int i = 0; i < spec.links; ++i) {
        // joints on the polyline; a link at a corner is the chord between its two joints
        const Vec3 a = along_polyline(pts, i * c.link_length);
        const Vec3 b = along_polyline(pts, (i + 1) * c.link_length);
        dBodyID link = add_body(w, m, 0.5 * (a + b));
        align_z(link, b - a);
        if (spec.collide) c.geoms.push_back(add_capsule(w, link, spec.radius, cylinder));
        if (!c.links.empty()) c.joints.push_back(add_ball(w, c.links.back(), link, a));
        c.links.push_back(link);
    }
    return c;
}

Vec3 link_end(const Cable& c, size_t link, int k) {
    const double half = 0.5 * c.link_length;
    return world_point(c.links[link], {0, 0, k == 0 ? -half : half});
}

void CompositeBody::add(Shape shape, Vec3 size, Vec3 offset, const dMatrix3 R, dMass m) {
    Part part{shape, size, offset, {}, m};
    std::copy(R, R + 12, part.R);
    dMassRotate(&part.mass, R);
    parts_.push_back(part);
}

void CompositeBody::box(Vec3 size, Vec3 offset, double mass, Vec3 axis, double angle) {
    dMatrix3 R;
    dRFromAxisAndAngle(R, axis.x, axis.y, axis.z, angle);
    add(Shape::Box, size, offset, R, box_mass(mass, size));
}

void CompositeBody::capsule(double radius, double cylinder_length, Vec3 offset, Vec3 axis, double mass) {
    dMatrix3 R;
    dRFromZAxis(R, axis.x, axis.y, axis.z);
    add(Shape::Capsule, {radius, cylinder_length, 0}, offset, R, capsule_mass(mass, radius, cylinder_length));
}

void CompositeBody::cylinder(double radius, double length, Vec3 offset, Vec3 axis, double mass) {
    dMatrix3 R;
    dRFromZAxis(R, axis.x, axis.y, axis.z);
    add(Shape::Cylinder, {radius, length, 0}, offset, R, cylinder_mass(mass, radius, length));
}

void CompositeBody::point_mass(Vec3 offset, double mass) {
    dMatrix3 R;
    dRSetIdentity(R);
    // a small solid sphere: a point mass with an inertia that keeps M positive definite
    add(Shape::None, {}, offset, R, sphere_mass(mass, 0.05));
}

double CompositeBody::mass() const {
    double m = 0;
    for (const Part& p : parts_) m += p.mass.mass;
    return m;
}

Vec3 CompositeBody::centre() const {
    Vec3 c;
    for (const Part& p : parts_) c = c + p.mass.mass * p.offset;
    return (1.0 / mass()) * c;
}

dBodyID CompositeBody::build(SceneWorld& w, Vec3 reference, std::vector<dGeomID>* geoms) const {
    const Vec3 c = centre();
    dMass total;
    dMassSetZero(&total);
    for (const Part& p : parts_) {
        dMass m = p.mass;
        dMassTranslate(&m, p.offset.x - c.x, p.offset.y - c.y, p.offset.z - c.z);
        dMassAdd(&total, &m);
    }
    // dMassAdd leaves the centre at ~0 up to rounding; ODE insists on exactly 0
    dMassTranslate(&total, -total.c[0], -total.c[1], -total.c[2]);
    dBodyID body = add_body(w, total, reference + c);
    for (const Part& p : parts_) {
        dGeomID g = nullptr;
        switch (p.shape) {
        case Shape::Box: g = dCreateBox(w.space(), p.size.x, p.size.y, p.size.z); break;
        case Shape::Capsule: g = dCreateCapsule(w.space(), p.size.x, p.size.y); break;
        case Shape::Cylinder: g = dCreateCylinder(w.space(), p.size.x, p.size.y); break;
        case Shape::None: continue;
        }
        dGeomSetBody(g, body);
        dGeomSetOffsetPosition(g, p.offset.x - c.x, p.offset.y - c.y, p.offset.z - c.z);
        dGeomSetOffsetRotation(g, p.R);
        if (geoms) geoms->push_back(g);
    }
    return body;
}

double tilt(dBodyID b) {
    const Vec3 up = world_vector(b, {0, 0, 1});
    return std::acos(std::clamp(up.z, -1.0, 1.0));
}

void add_bin(SceneWorld& w, Vec3 centre, Vec3 inner, double thickness) {
    const double z = 0.5 * inner.z;
    const double half_x = 0.5 * (inner.x + thickness), half_y = 0.5 * (inner.y + thickness);
    const double outer_x = inner.x + 2 * thickness;
    for (int side : {-1, 1}) {
        add_static_box(w, {thickness, inner.y, inner.z}, {centre.x + side * half_x, centre.y, z});
        add_static_box(w, {outer_x, thickness, inner.z}, {centre.x, centre.y + side * half_y, z});
    }
}

double fastest_body_speed(const SceneWorld& w) {
    double fastest = 0;
    for (dBodyID b : w.bodies()) fastest = std::max(fastest, norm(to_vec(dBodyGetLinearVel(b))));
    return fastest;
}

}  // namespace ode_bpp::scenes
