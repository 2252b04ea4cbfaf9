// A plain ODE program for the launcher tests (tests/shell/launcher_debian_binary.sh): built with
// `g++ box_stack.cpp -lode` against Debian's libode-dev, it knows nothing of ode-bpp.
// A stack of boxes is dropped on a ground plane and stepped with dWorldStep (frictional
// contacts, so every step solves a boxed MLCP with findex); it prints each box's final
// position, one line per box: "box I x y z". The top box is pushed sideways at the start, so
// that it slides on the box below until friction stops it (friction rows at their bounds).
#include <ode/ode.h>

#include <cstdio>

namespace {

constexpr int kBoxes = 4;
constexpr dReal kSide = 0.5;      // edge of each cube (m)
constexpr dReal kGap = 0.05;      // initial gap between cubes, so the stack settles on contact
constexpr dReal kStep = 0.01;     // s
constexpr int kSteps = 300;       // 3 s: the stack comes to rest
constexpr int kMaxContacts = 8;
constexpr dReal kPush = 0.5;      // initial sideways speed of the top box (m/s)

struct Scene {
    dWorldID world;
    dJointGroupID contacts;
};

void collide_pair(void* data, dGeomID a, dGeomID b) {
    auto* scene = static_cast<Scene*>(data);
    dContact contact[kMaxContacts];
    const int n = dCollide(a, b, kMaxContacts, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
        contact[i].surface.mode = dContactApprox1;
        contact[i].surface.mu = 0.6;
        dJointID j = dJointCreateContact(scene->world, scene->contacts, &contact[i]);
        dJointAttach(j, dGeomGetBody(a), dGeomGetBody(b));
    }
}

}  // namespace

int main() {
    dInitODE2(0);
    Scene scene{dWorldCreate(), dJointGroupCreate(0)};
    dWorldSetGravity(scene.world, 0, 0, -9.81);
    dSpaceID space = dHashSpaceCreate(nullptr);
    dCreatePlane(space, 0, 0, 1, 0);

    dBodyID box[kBoxes];
    for (int i = 0; i < kBoxes; ++i) {
        box[i] = dBodyCreate(scene.world);
        dMass m;
        dMassSetBox(&m, 1000.0, kSide, kSide, kSide);
        dBodySetMass(box[i], &m);
        // a small offset per box so that contacts are not perfectly symmetric
        dBodySetPosition(box[i], 0.02 * i, -0.01 * i, kSide / 2 + kGap + i * (kSide + kGap));
        dGeomSetBody(dCreateBox(space, kSide, kSide, kSide), box[i]);
    }
    dBodySetLinearVel(box[kBoxes - 1], kPush, 0, 0);

    for (int s = 0; s < kSteps; ++s) {
        dSpaceCollide(space, &scene, &collide_pair);
        dWorldStep(scene.world, kStep);
        dJointGroupEmpty(scene.contacts);
    }

    for (int i = 0; i < kBoxes; ++i) {
        const dReal* p = dBodyGetPosition(box[i]);
        std::printf("box %d %.6f %.6f %.6f\n", i, p[0], p[1], p[2]);
    }
    dJointGroupDestroy(scene.contacts);
    dSpaceDestroy(space);
    dWorldDestroy(scene.world);
    dCloseODE();
    return 0;
}
