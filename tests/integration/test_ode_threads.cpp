// ode-bpp inside ODE's multi-threaded island stepping: islands are solved concurrently by a
// thread pool, each worker with its own per-thread workspaces (pivot loop, driver, factor
// buffers) and all of them sharing one world's warm-start memory behind the hook's lock.
// The threaded run must give the single-threaded run's motion. Not bit for bit: ODE's threaded
// island stepping itself differs from its serial stepping by up to ~1e-10 m now and then (seen
// with its own Dantzig), and a warm start may then pick another pivot path. Since the polish of
// the pivoting loop (OdeStacks below) the two runs agree within 3.3e-10 m for every bpp variant
// over 100-150 nudged fields; before it, a 1e-11 m difference could make a pile slide by
// centimetres in one run only (a CI failure). What the hook must not add is any dependence on
// the order in which islands finish (tests/unit/test_ode_row_memory.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "ode_bpp/ode.h"
#include "ode_lifetime.h"

namespace {

using ode_bpp::test::OdeLifetime;

/// Separate islands: piles of frictional boxes (skyline path, > 32 rows) and hinge chains
/// (dense path), far enough apart never to touch. nudge: box (k, level) starts nudge*(k+1)*(level+1)
/// metres off its pile's axis.
class IslandField {
public:
    explicit IslandField(double nudge = 0) {
        world = dWorldCreate();
        space = dHashSpaceCreate(nullptr);
        contacts = dJointGroupCreate(0);
        dWorldSetGravity(world, 0, 0, -9.81);
        dCreatePlane(space, 0, 0, 1, 0);
        for (int k = 0; k < 4; ++k) {
            for (int level = 0; level < 3; ++level)
                add_box(6.0 * k + nudge * (k + 1) * (level + 1), 0, 0.25 + 0.5 * level,
                        level == 2 ? 50.0 : 1.0);  // heavy on top
            add_chain(6.0 * k, 8, 6);
        }
    }
    ~IslandField() {
        dJointGroupDestroy(contacts);
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    void step() {
        dSpaceCollide(space, this, &IslandField::near);
        dWorldStep(world, 1.0 / 60.0);
        dJointGroupEmpty(contacts);
    }
    std::vector<double> positions() const {
        std::vector<double> p;
        for (dBodyID b : bodies) {
            const dReal* x = dBodyGetPosition(b);
            p.insert(p.end(), x, x + 3);
        }
        return p;
    }

    dWorldID world;
    dSpaceID space;
    dJointGroupID contacts;
    std::vector<dBodyID> bodies;

private:
    dBodyID add_box(double x, double y, double z, double mass) {
        dBodyID b = dBodyCreate(world);
        dMass m;
        dMassSetBoxTotal(&m, mass, 0.5, 0.5, 0.5);
        dBodySetMass(b, &m);
        dBodySetPosition(b, x, y, z);
        dGeomSetBody(dCreateBox(space, 0.5, 0.5, 0.5), b);
        bodies.push_back(b);
        return b;
    }
    void add_chain(double x, double y, int links) {
        dBodyID previous = nullptr;
        for (int i = 0; i < links; ++i) {
            dBodyID b = dBodyCreate(world);
            dMass m;
            dMassSetBoxTotal(&m, 1.0, 0.2, 0.2, 0.2);
            dBodySetMass(b, &m);
            dBodySetPosition(b, x + 0.4 * (i + 1), y, 5.0);
            dJointID j = dJointCreateHinge(world, nullptr);
            dJointAttach(j, b, previous);
            dJointSetHingeAnchor(j, x + 0.4 * i, y, 5.0);
            dJointSetHingeAxis(j, 0, 1, 0);
            bodies.push_back(b);
            previous = b;
        }
    }
    static void near(void* data, dGeomID g1, dGeomID g2) {
        auto* self = static_cast<IslandField*>(data);
        dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
        dContact c[4];
        const int n = dCollide(g1, g2, 4, &c[0].geom, sizeof(dContact));
        for (int i = 0; i < n; ++i) {
            c[i].surface.mode = dContactApprox1;
            c[i].surface.mu = 0.8;
            dJointAttach(dJointCreateContact(self->world, self->contacts, &c[i]), b1, b2);
        }
    }
};

/// ODE's built-in thread pool serving one world's island stepping.
class ThreadedStepping {
public:
    ThreadedStepping(dWorldID world, int threads) : world_(world) {
        impl_ = dThreadingAllocateMultiThreadedImplementation();
        pool_ = dThreadingAllocateThreadPool(threads, 0, dAllocateFlagBasicData, nullptr);
        dThreadingThreadPoolServeMultiThreadedImplementation(pool_, impl_);
        dWorldSetStepIslandsProcessingMaxThreadCount(world, threads);
        dWorldSetStepThreadingImplementation(world, dThreadingImplementationGetFunctions(impl_), impl_);
    }
    ~ThreadedStepping() {
        dThreadingImplementationShutdownProcessing(impl_);
        dThreadingFreeThreadPool(pool_);
        dWorldSetStepThreadingImplementation(world_, nullptr, nullptr);
        dThreadingFreeImplementation(impl_);
    }

private:
    dWorldID world_;
    dThreadingImplementationID impl_;
    dThreadingThreadPoolID pool_;
};

/// The world's islands and the islands handed to ODE's Dantzig, from ODE's own statistics, and
/// the threads the islands were solved on (an MLCP observer's).
struct IslandCount {
    long islands = 0;
    long failures = 0;
    std::size_t solving_threads = 0;
};

/// The threads an MLCP observer was called on; the pool's threads call it concurrently.
struct SolvingThreads {
    std::mutex lock;
    std::set<std::thread::id> ids;
};

void note_thread(const dMLCP*, const dMLCPIslandStats* stats, void* data) {
    if (stats == nullptr) return;
    auto& seen = *static_cast<SolvingThreads*>(data);
    const std::lock_guard<std::mutex> g(seen.lock);
    seen.ids.insert(std::this_thread::get_id());
}

std::vector<double> run(const char* solver, int threads, int steps, IslandCount* counters, double nudge = 0) {
    IslandField field(nudge);
    EXPECT_EQ(dWorldSetMLCPSolver(field.world, solver), 1) << solver;
    SolvingThreads seen;
    dWorldSetMLCPObserver(field.world, &note_thread, &seen);
    {
        std::unique_ptr<ThreadedStepping> pool;
        if (threads > 1) pool = std::make_unique<ThreadedStepping>(field.world, threads);
        for (int s = 0; s < steps; ++s) field.step();
    }
    dWorldSetMLCPObserver(field.world, nullptr, nullptr);
    counters->solving_threads = seen.ids.size();
    dMLCPStepStats total{};
    total.struct_size = sizeof total;
    dWorldGetMLCPStats(field.world, nullptr, &total);
    counters->islands = total.islands;
    counters->failures = total.failures;
    ode_bpp::forget_world(field.world);
    return field.positions();
}

TEST(OdeThreads, ThreadPoolIslandsGiveTheSingleThreadedMotion) {
    OdeLifetime ode;
    constexpr int kSteps = 180;
    for (const char* solver : {"bpp", "bpp-sky", "bpp-chol"}) {
        IslandCount one{}, two{};
        const std::vector<double> serial = run(solver, 1, kSteps, &one);
        const std::vector<double> threaded = run(solver, 2, kSteps, &two);
        ASSERT_EQ(serial.size(), threaded.size());
        EXPECT_GE(two.islands, 8 * kSteps) << solver;  // every island of every step went through the hook
        EXPECT_EQ(one.solving_threads, 1u) << solver;
        EXPECT_GE(two.solving_threads, 2u) << solver << ": the pool solved no island besides the stepping thread";
        EXPECT_EQ(two.failures, 0) << solver;
        // a contact at the collision threshold may come and go in one run only
        EXPECT_LE(std::labs(one.islands - two.islands), 4) << solver << ": " << one.islands << " vs " << two.islands;
        for (std::size_t i = 0; i < serial.size(); ++i) {
            ASSERT_TRUE(std::isfinite(threaded[i])) << solver << " coordinate " << i;
            EXPECT_NEAR(serial[i], threaded[i], 1e-6) << solver << " coordinate " << i;
        }
    }
}

// Four boxes on each face, CFM 1e-10: equal and opposite friction at two contacts is an internal
// force that only the CFM resists, so an index set with friction rows at opposite bounds passed
// the 1e-9 tolerance with multipliers of the wrong sign, and warm starts kept it from step to
// step. Such piles slid by centimetres after a nudge of 1e-10 m (7 in 300 nudges; the first eight
// listed here did). The polish of the pivoting loop must leave the motion a smooth function of
// the nudge: 180 steps amplify it about tenfold.
TEST(OdeStacks, ARestingPileRespondsSmoothlyToTinyNudges) {
    OdeLifetime ode;
    constexpr int kSteps = 180;
    IslandCount counters{};
    const std::vector<double> still = run("bpp", 1, kSteps, &counters);
    std::vector<double> nudges = {3.699e-11, 6.028e-11, 8.905e-11, 1.0686e-10, 1.2604e-10, 1.456e-09, 7.189e-09, 8.008e-09};
    for (double e = 1e-11; e < 1e-8; e *= 2.5) nudges.push_back(e);
    for (double nudge : nudges) {
        const std::vector<double> moved = run("bpp", 1, kSteps, &counters, nudge);
        double worst = 0;
        for (std::size_t i = 0; i < still.size(); ++i) worst = std::max(worst, std::abs(moved[i] - still[i]));
        EXPECT_LT(worst, 1e3 * nudge + 1e-6) << "nudge " << nudge;
    }
}

}  // namespace
