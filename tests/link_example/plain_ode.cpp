// An unchanged ODE program: it calls no ode-bpp function, so only the environment
// (ODE_LCP_SOLVER) can pick the solver; the patched libode must find ode-bpp by itself.
#include <ode/ode.h>

#include <cmath>
#include <cstdio>

int main() {
    dInitODE2(0);
    dWorldID world = dWorldCreate();
    dWorldSetGravity(world, 0, 0, -9.81);
    dBodyID bob = dBodyCreate(world);
    dMass m;
    dMassSetSphereTotal(&m, 2.0, 0.1);
    dBodySetMass(bob, &m);
    dBodySetPosition(bob, 1, 0, 2);
    dJointID rod = dJointCreateBall(world, nullptr);
    dJointAttach(rod, bob, nullptr);
    dJointSetBallAnchor(rod, 0, 0, 2);
    for (int i = 0; i < 60; ++i) dWorldStep(world, 1.0 / 60.0);
    dMLCPStepStats total{};
    dWorldGetMLCPStats(world, nullptr, &total);
    const dReal* p = dBodyGetPosition(bob);
    const double length = std::sqrt(p[0] * p[0] + p[1] * p[1] + (p[2] - 2) * (p[2] - 2));
    std::printf("solver=%s islands=%lld length=%.6f\n", total.solver, static_cast<long long>(total.islands), length);
    dWorldDestroy(world);
    dCloseODE();
    return std::fabs(length - 1) < 1e-2 ? 0 : 1;  // unsolved, the bob would fall away
}
