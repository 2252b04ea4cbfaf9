// The box stack of the launcher's test programs (box_stack.cpp, quickstep_stack.cpp), built with
// plain `g++ PROGRAM.cpp -lode` against Debian's libode-dev: they know nothing of ode-bpp.
// A stack of boxes is dropped on a ground plane (frictional contacts, so every step has a boxed
// MLCP with findex); the program prints each box's final position, one line per box:
// "box I x y z". The top box is pushed sideways at the start, so that it slides on the box below
// until friction stops it (friction rows at their bounds).
//
// The stepping function is a parameter, so that each program imports only the one it uses
// (dWorldStep or dWorldQuickStep): the launcher tells them apart by their imports.
//
// Arguments: none, or --until-signal: print "stepping" once the usual steps are done (the stack
// rests on contacts) and go on stepping it (1 ms apart) until a signal ends the process.
#pragma once

#include <ode/ode.h>

#include <cstdio>
#include <cstring>

#include <unistd.h>

namespace stack_scene {

constexpr int kBoxes = 4;
constexpr dReal kSide = 0.5;      // edge of each cube (m)
constexpr dReal kGap = 0.05;      // initial gap between cubes, so the stack settles on contact
constexpr dReal kStep = 0.01;     // s
constexpr int kSteps = 300;       // 3 s: the stack comes to rest
constexpr int kMaxContacts = 8;
constexpr dReal kPush = 0.5;      // initial sideways speed of the top box (m/s)
constexpr useconds_t kPauseUntilSignal = 1000;  // between steps with --until-signal (us)

using StepFunction = int(dWorldID, dReal);

struct Scene {
    dWorldID world;
    dJointGroupID contacts;
};

inline void collide_pair(void* data, dGeomID a, dGeomID b) {
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

inline int run(int argc, char** argv, StepFunction* step) {
    const bool until_signal = argc > 1 && std::strcmp(argv[1], "--until-signal") == 0;
    if (argc > 1 && !until_signal) {
        std::fprintf(stderr, "usage: %s [--until-signal]\n", argv[0]);
        return 2;
    }
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

    for (int s = 0; s < kSteps || until_signal; ++s) {
        dSpaceCollide(space, &scene, &collide_pair);
        step(scene.world, kStep);
        dJointGroupEmpty(scene.contacts);
        if (until_signal && s == kSteps - 1) {
            std::printf("stepping\n");
            std::fflush(stdout);
        }
        if (until_signal) usleep(kPauseUntilSignal);
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

}  // namespace stack_scene
