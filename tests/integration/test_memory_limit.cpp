// An island whose A alone outgrows the memory the process may use (docs/modelling.md, "Islands
// too large for an exact step"). Where A would pass Options::max_factor_entries it is answered by
// projected Gauss-Seidel on J without forming A (ode/jacobian_pgs.h); without that limit the solver
// call fails the island instead of letting std::bad_alloc cross ODE's C code, ODE's fallback finds
// no memory for its dense A either and answers x = 0, and the program goes on. Each run in a child
// process under an address-space limit.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <vector>

#include <ode/mlcp.h>
#include <ode/ode.h>

#include "ode_bpp/ode.h"

namespace {

/// The address space the process maps now, in bytes (/proc/self/statm's first field, in pages).
long mapped_bytes() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0;
    statm >> pages;
    return pages * sysconf(_SC_PAGESIZE);
}

struct Pile {
    dWorldID world;
    dSpaceID space;
    dJointGroupID contacts;
};

void touch(void* data, dGeomID o1, dGeomID o2) {
    auto* pile = static_cast<Pile*>(data);
    const dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    dContact c[4];
    for (dContact& k : c) {
        k.surface.mode = dContactSoftCFM;
        k.surface.mu = dInfinity;
        k.surface.soft_cfm = 0.01;
    }
    const int n = dCollide(o1, o2, 4, &c[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) dJointAttach(dJointCreateContact(pile->world, pile->contacts, c + i), b1, b2);
}

/// How the pile's island must end.
enum class Expected { AnsweredWithoutA, Failed };

/// In the child: 1,000 spheres dropped into a 2 x 2 x 1 m box at once (one island of about
/// 58,000 rows whose A needs some 500 MB), one step with bpp under a limit of 250 MB more than
/// the process maps, the factor limit below A's entries or off (max_factor_entries 0). Exit 0 when
/// the step ended as expected (answered through the "pgs" fallback, or failed) with every body
/// finite.
int step_pile_under_a_limit(Expected expected) {
    dInitODE2(0);
    dAllocateODEDataForThread(dAllocateMaskAll);
    Pile pile{dWorldCreate(), dSimpleSpaceCreate(nullptr), dJointGroupCreate(0)};
    dWorldSetGravity(pile.world, 0, 0, -0.5);
    dWorldSetCFM(pile.world, 1e-5);
    dRandSetSeed(1);
    std::vector<dBodyID> bodies;
    for (int i = 0; i < 1000; ++i) {
        const dBodyID b = dBodyCreate(pile.world);
        bodies.push_back(b);
        dBodySetPosition(b, dRandReal() * 2 - 1, dRandReal() * 2 - 1, dRandReal() + 2);
        const dReal r = (dRandReal() * 0.5 + 0.1) * 0.5;
        dMass m;
        dMassSetSphere(&m, 5.0, r);
        dBodySetMass(b, &m);
        dGeomSetBody(dCreateSphere(pile.space, r), b);
    }
    if (ode_bpp_use(pile.world, "bpp") != 1) return 1;
    // A holds about 7 million entries: within the default limit (its factor is not), so A is
    // formed there; under 2^20 it is not formed, and with no limit at all it is
    ode_bpp::WorldSettings settings;
    settings.options.max_factor_entries = expected == Expected::Failed ? 0 : std::int64_t{1} << 20;
    ode_bpp::set_world_settings(pile.world, settings);
    dSpaceCollide(pile.space, &pile, &touch);
    const rlimit limit{static_cast<rlim_t>(mapped_bytes() + (250L << 20)), RLIM_INFINITY};
    if (setrlimit(RLIMIT_AS, &limit) != 0) return 1;
    dWorldStep(pile.world, 0.05);
    dMLCPStepStats last{};
    last.struct_size = sizeof last;
    dWorldGetMLCPStats(pile.world, &last, nullptr);
    if (last.islands != 1 || last.max_rows < 40000) return 2;  // the pile this test is about
    if (last.failures != (expected == Expected::Failed ? 1 : 0)) return 3;
    if (expected == Expected::AnsweredWithoutA && ode_bpp::last_island_result(pile.world).fallback != ode_bpp::Fallback::Pgs)
        return 3;
    for (const dBodyID b : bodies)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(dBodyGetPosition(b)[k])) return 3;
    return 0;
}

/// step_pile_under_a_limit in a child; its exit status.
void expect_in_a_child(Expected expected) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        int code = 4;  // an exception left dWorldStep
        try {
            code = step_pile_under_a_limit(expected);
        } catch (...) {
        }
        _exit(code);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    EXPECT_EQ(WEXITSTATUS(status), 0)
        << "1: set-up, 2: not the pile expected, 3: not answered as expected, 4: an exception left dWorldStep";
}

TEST(MemoryLimit, AnIslandWhoseAWouldOutgrowMemoryIsAnsweredWithoutForming) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer reserves terabytes of shadow memory: no address-space limit fits";
#endif
    expect_in_a_child(Expected::AnsweredWithoutA);
}

TEST(MemoryLimit, WithoutTheFactorLimitAnIslandWhoseAOutgrowsMemoryFailsCleanly) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer reserves terabytes of shadow memory: no address-space limit fits";
#endif
    expect_in_a_child(Expected::Failed);
}

}  // namespace
