/* A program run setgid by tests/shell/setgid_environment.sh: it reports whether the kernel made
 * it a secure-execution process (AT_SECURE), the solver ODE resolved, and steps one world so that
 * a linked ode-bpp has something to summarize at exit. */
#include <stdio.h>
#include <sys/auxv.h>

#include <ode/ode.h>

int main(void)
{
    dInitODE2(0);
    dWorldID world = dWorldCreate();
    dBodyID body = dBodyCreate(world);
    dJointID ball = dJointCreateBall(world, 0);
    dJointAttach(ball, body, 0);
    dSetDefaultMLCPSolver("no-such-solver"); /* an unknown name: ODE tries its plug-in */
    dWorldStep(world, 0.01);
    printf("secure=%lu\n", getauxval(AT_SECURE));
    printf("solver=%s\n", dWorldGetMLCPSolver(world));
    dWorldDestroy(world);
    dCloseODE();
    return 0;
}
