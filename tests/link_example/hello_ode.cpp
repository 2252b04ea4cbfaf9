// An ordinary ODE program: a box falls onto the ground. The only ode-bpp line is ode_bpp_use().
#include <ode/ode.h>
#include <ode_bpp/ode.h>

#include <cmath>
#include <cstdio>

static dWorldID world;
static dJointGroupID contacts;

static void near(void*, dGeomID a, dGeomID b) {
    dContact c[4];
    const int n = dCollide(a, b, 4, &c[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
        c[i].surface.mode = dContactApprox1;
        c[i].surface.mu = 1.0;
        dJointAttach(dJointCreateContact(world, contacts, &c[i]), dGeomGetBody(a), dGeomGetBody(b));
    }
}

int main(int argc, char** argv) {
    const char* solver = argc > 1 ? argv[1] : "bpp";
    dInitODE2(0);
    world = dWorldCreate();
    dSpaceID space = dHashSpaceCreate(nullptr);
    contacts = dJointGroupCreate(0);
    dWorldSetGravity(world, 0, 0, -9.81);
    dCreatePlane(space, 0, 0, 1, 0);
    dBodyID box = dBodyCreate(world);
    dMass m;
    dMassSetBoxTotal(&m, 5.0, 1, 1, 1);
    dBodySetMass(box, &m);
    dBodySetPosition(box, 0, 0, 1.0);
    dGeomSetBody(dCreateBox(space, 1, 1, 1), box);

    if (!ode_bpp_use(world, solver)) {  // the one ode-bpp call
        std::fprintf(stderr, "unknown solver %s (valid: %s)\n", solver, dListMLCPSolvers());
        return 2;
    }
    for (int i = 0; i < 120; ++i) {
        dSpaceCollide(space, nullptr, &near);
        dWorldStep(world, 1.0 / 60.0);
        dJointGroupEmpty(contacts);
    }
    dMLCPStepStats total{};
    dWorldGetMLCPStats(world, nullptr, &total);
    const double z = dBodyGetPosition(box)[2];
    std::printf("solver=%s steps=%lld islands=%lld pivots=%lld failures=%lld z=%.6f\n", total.solver,
                static_cast<long long>(total.steps), static_cast<long long>(total.islands),
                static_cast<long long>(total.pivots), static_cast<long long>(total.failures), z);
    dJointGroupDestroy(contacts);
    dSpaceDestroy(space);
    dWorldDestroy(world);
    dCloseODE();
    return std::isfinite(z) && std::fabs(z - 0.5) < 0.01 && total.failures == 0 ? 0 : 1;
}
