// The patched world step and ode-bpp's registration: precision, registry, per-world choice,
// observer, statistics, the Dantzig fallback of the hook, the end of a world, and
// dSolveMLCPDantzig.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "ode_bpp/ode.h"
#include "ode_lifetime.h"

namespace {

using ode_bpp::test::OdeLifetime;

/// A box resting on the ground (frictional contacts) and a two-link pendulum on hinges.
class SmallScene {
public:
    explicit SmallScene(const char* solver) {
        world = dWorldCreate();
        space = dHashSpaceCreate(nullptr);
        contacts = dJointGroupCreate(0);
        dWorldSetGravity(world, 0, 0, -9.81);
        dCreatePlane(space, 0, 0, 1, 0);
        box = add_box(0, 0, 0.25, 10.0);
        const dBodyID l1 = add_box(2, 0, 2.0, 1.0), l2 = add_box(2, 0, 1.2, 1.0);
        hinge(nullptr, l1, 2, 0, 2.4);
        hinge(l1, l2, 2, 0, 1.6);
        dBodySetLinearVel(l2, 1, 0, 0);
        bodies = {box, l1, l2};
        if (solver != nullptr) {
            EXPECT_EQ(dWorldSetMLCPSolver(world, solver), 1) << solver;
        }
    }
    ~SmallScene() {
        dJointGroupDestroy(contacts);
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    void step() {
        dSpaceCollide(space, this, &SmallScene::near);
        dWorldStep(world, 1.0 / 60.0);
        dJointGroupEmpty(contacts);
    }
    dWorldID world;
    dSpaceID space;
    dJointGroupID contacts;
    dBodyID box;
    std::vector<dBodyID> bodies;  ///< the box, then the pendulum's two links
    /// Applied to each contact the collider makes, with its index among the pair's contacts.
    void (*tune_contact)(dContact&, int) = nullptr;

private:
    dBodyID add_box(double x, double y, double z, double mass) {
        dBodyID b = dBodyCreate(world);
        dMass m;
        dMassSetBoxTotal(&m, mass, 0.5, 0.5, 0.5);
        dBodySetMass(b, &m);
        dBodySetPosition(b, x, y, z);
        dGeomSetBody(dCreateBox(space, 0.5, 0.5, 0.5), b);
        return b;
    }
    void hinge(dBodyID a, dBodyID b, double x, double y, double z) {
        dJointID j = dJointCreateHinge(world, nullptr);
        dJointAttach(j, b, a);
        dJointSetHingeAnchor(j, x, y, z);
        dJointSetHingeAxis(j, 0, 1, 0);
    }
    static void near(void* data, dGeomID g1, dGeomID g2) {
        auto* self = static_cast<SmallScene*>(data);
        dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
        if (b1 && b2 && dAreConnected(b1, b2)) return;
        dContact c[4];
        const int n = dCollide(g1, g2, 4, &c[0].geom, sizeof(dContact));
        for (int i = 0; i < n; ++i) {
            c[i].surface.mode = dContactApprox1;
            c[i].surface.mu = 0.8;
            if (self->tune_contact != nullptr) self->tune_contact(c[i], i);
            dJointAttach(dJointCreateContact(self->world, self->contacts, &c[i]), b1, b2);
        }
    }
};

TEST(OdeBuild, IsDoublePrecision) {
    OdeLifetime ode;
    EXPECT_EQ(dCheckConfiguration("ODE_double_precision"), 1);
    EXPECT_EQ(dCheckConfiguration("ODE_single_precision"), 0);
    dMass m;
    dMassSetBoxTotal(&m, 30000.0, 1, 1, 1);  // zero in a single-precision library behind a double header
    EXPECT_DOUBLE_EQ(m.mass, 30000.0);
}

TEST(OdeHook, RegistryListsDantzigAndOurSolvers) {
    OdeLifetime ode;
    const std::string names = dListMLCPSolvers();
    for (const char* n : {"dantzig", "bpp", "bpp-sky", "bpp-down", "bpp-chol", "pgs"})
        EXPECT_NE(names.find(n), std::string::npos) << n << " missing from " << names;
}

TEST(OdeHook, PerWorldChoiceAndUnknownNames) {
    OdeLifetime ode;
    SmallScene a("dantzig"), b("bpp");
    EXPECT_STREQ(dWorldGetMLCPSolver(a.world), "dantzig");
    EXPECT_STREQ(dWorldGetMLCPSolver(b.world), "bpp");
    EXPECT_EQ(dWorldSetMLCPSolver(b.world, "no-such-solver"), 0);
    EXPECT_STREQ(dWorldGetMLCPSolver(b.world), "bpp");
    EXPECT_EQ(ode_bpp_use(a.world, "bpp-sky"), 1);
    EXPECT_STREQ(dWorldGetMLCPSolver(a.world), "bpp-sky");
}

TEST(OdeHook, StatisticsNameTheSolverAndCountRows) {
    OdeLifetime ode;
    for (const char* solver : {"dantzig", "bpp"}) {
        SmallScene s(solver);
        for (int i = 0; i < 30; ++i) s.step();
        dMLCPStepStats last{}, total{};
        ASSERT_EQ(dWorldGetMLCPStats(s.world, &last, &total), 1);
        EXPECT_STREQ(last.solver, solver);
        EXPECT_EQ(total.steps, 30u);
        EXPECT_GE(last.islands, 2);              // the box on the ground, the pendulum
        EXPECT_GE(last.max_rows, 10);            // two hinges: 5 rows each
        EXPECT_EQ(last.failures, 0) << solver;
        EXPECT_GT(total.seconds, 0.0);
    }
}

/// dMLCP::step of every island, in call order, with the dWorldStep it came from.
struct StepLog {
    int world_step = 0;
    std::vector<std::pair<int, unsigned long>> seen;  ///< (world step, dMLCP::step)
};

void log_step(const dMLCP* p, const dMLCPIslandStats* stats, void* data) {
    if (stats != nullptr) return;
    auto* log = static_cast<StepLog*>(data);
    log->seen.emplace_back(log->world_step, p->step);
}

TEST(OdeHook, IslandsOfOneStepShareItsStepNumberWhichResetsOfTheStatisticsLeaveAlone) {
    OdeLifetime ode;
    SmallScene s("bpp");
    StepLog log;
    dWorldSetMLCPObserver(s.world, &log_step, &log);
    for (log.world_step = 0; log.world_step < 10; ++log.world_step) {
        if (log.world_step == 5) dWorldResetMLCPStats(s.world);
        s.step();
    }
    dWorldSetMLCPObserver(s.world, nullptr, nullptr);
    ASSERT_GE(log.seen.size(), 20u);  // two islands a step
    for (std::size_t k = 1; k < log.seen.size(); ++k) {
        const auto [prev_step, prev_number] = log.seen[k - 1];
        const auto [step, number] = log.seen[k];
        // the same dWorldStep: the same number; the next: one more, the statistics' reset too
        EXPECT_EQ(number - prev_number, static_cast<unsigned long>(step - prev_step)) << "island " << k;
    }
}

/// Every body of a and b at the same position and linear velocity, to tol (the resting box alone
/// would agree whatever the pendulum's island got: it is the swinging links that tell).
void expect_same_motion(const SmallScene& a, const SmallScene& b, double tol, int step) {
    for (std::size_t k = 0; k < a.bodies.size(); ++k) {
        const dReal *pa = dBodyGetPosition(a.bodies[k]), *pb = dBodyGetPosition(b.bodies[k]);
        const dReal *va = dBodyGetLinearVel(a.bodies[k]), *vb = dBodyGetLinearVel(b.bodies[k]);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(pa[c], pb[c], tol) << "body " << k << ", step " << step;
            EXPECT_NEAR(va[c], vb[c], tol) << "body " << k << ", step " << step;
        }
    }
}

TEST(OdeHook, BppAndDantzigAgreeOnTheTrajectory) {
    OdeLifetime ode;
    SmallScene d("dantzig"), b("bpp");
    for (int i = 0; i < 120; ++i) {
        d.step();
        b.step();
        expect_same_motion(d, b, 1e-6, i);
    }
    // the pendulum swung: a solver that left its island's impulses at 0 would not agree above
    EXPECT_GT(std::abs(dBodyGetLinearVel(b.bodies[1])[0]) + std::abs(dBodyGetLinearVel(b.bodies[2])[0]), 0.1);
    dMLCPStepStats total{};
    total.struct_size = sizeof total;
    ASSERT_TRUE(dWorldGetMLCPStats(b.world, nullptr, &total));
    EXPECT_GT(total.islands, 0);
    EXPECT_STREQ(total.solver, "bpp");
}

struct ObserverLog {
    int before = 0, after = 0, rows = 0;
    bool structure_ok = true;
    bool sparse = true;
};

void observe(const dMLCP* p, const dMLCPIslandStats* stats, void* data) {
    auto* log = static_cast<ObserverLog*>(data);
    if (stats != nullptr) {
        log->after += 1;
        return;
    }
    log->before += 1;
    log->rows += p->m;
    // the joint structure tiles the rows, and A's diagonal is intact before the solve
    int next = 0;
    for (int j = 0; j < p->nj; ++j) {
        log->structure_ok &= p->joints[j].row == next && p->joints[j].m > 0;
        log->structure_ok &= p->joints[j].body[0] < p->nb && p->joints[j].body[1] < p->nb;
        next += p->joints[j].m;
    }
    log->structure_ok &= next == p->m && p->skip >= p->m;
    // "bpp" takes the sparse form: no dense A, but J, J M^-1 and the CFM, whose diagonal
    // A_ii = J_i M^-1 J_i^T + cfm_i must be positive (ode_bpp::island_matrix_lower builds it)
    log->sparse &= p->A == nullptr && p->J != nullptr && p->JinvM != nullptr && p->cfm != nullptr;
    std::vector<double> A;
    ode_bpp::island_matrix_lower(*p, A);
    for (int i = 0; i < p->m; ++i) log->structure_ok &= A[static_cast<std::size_t>(i) * p->m + i] > 0;
}

TEST(OdeHook, ObserverSeesIntactProblemAndStructure) {
    OdeLifetime ode;
    ObserverLog log;
    SmallScene s("bpp");
    dWorldSetMLCPObserver(s.world, &observe, &log);
    for (int i = 0; i < 10; ++i) s.step();
    EXPECT_GT(log.before, 0);
    EXPECT_EQ(log.before, log.after);
    EXPECT_TRUE(log.structure_ok);
    EXPECT_TRUE(log.sparse) << "bpp registers in the sparse form: every island must come without a dense A";
    dMLCPStepStats total{};
    dWorldGetMLCPStats(s.world, nullptr, &total);
    EXPECT_EQ(log.rows, total.rows);
}

dMLCPStatus failing_solver(const dMLCP*, dMLCPIslandStats*, void*) { return dMLCPFailed; }
dMLCPStatus nan_solver(const dMLCP* p, dMLCPIslandStats*, void*) {
    for (int i = 0; i < p->m; ++i) p->pairsbx[2 * i + 1] = std::nan("");
    return dMLCPSolved;
}

TEST(OdeHook, FailedSolverFallsBackToDantzigAndTheWorldStaysSane) {
    OdeLifetime ode;
    ASSERT_EQ(dRegisterMLCPSolver("test-failing", &failing_solver, nullptr, dMLCP_API_VERSION), 1);
    ASSERT_EQ(dRegisterMLCPSolver("test-nan", &nan_solver, nullptr, dMLCP_API_VERSION), 1);
    EXPECT_EQ(dRegisterMLCPSolver("dantzig", &failing_solver, nullptr, dMLCP_API_VERSION), 0);
    EXPECT_EQ(dRegisterMLCPSolver("x", &failing_solver, nullptr, dMLCP_API_VERSION + 1), 0);
    SmallScene ref("dantzig");
    for (const char* name : {"test-failing", "test-nan"}) {
        SmallScene s(name);
        for (int i = 0; i < 60; ++i) s.step();
        dMLCPStepStats total{};
        dWorldGetMLCPStats(s.world, nullptr, &total);
        EXPECT_EQ(total.failures, total.islands) << name;
        EXPECT_EQ(total.fallbacks, total.islands) << name;
        EXPECT_TRUE(std::isfinite(dBodyGetPosition(s.box)[2]));
    }
    SmallScene again("test-nan");
    for (int i = 0; i < 60; ++i) {
        ref.step();
        again.step();
        expect_same_motion(ref, again, 1e-9, i);  // every island answered by ODE's Dantzig
    }
}

/// The fallback names the world step reported after each island's solve.
void record_fallback(const dMLCP*, const dMLCPIslandStats* stats, void* names) {
    if (stats != nullptr && stats->fallback != nullptr)
        static_cast<std::vector<std::string>*>(names)->emplace_back(stats->fallback);
}

/// ODE's messages that come from ode-bpp, while a MessageLog lives (the previous handler after).
struct MessageLog {
    static std::vector<std::string>& lines() {
        static std::vector<std::string> log;
        return log;
    }
    static void record(int, const char* format, va_list args) {
        char text[1024];
        std::vsnprintf(text, sizeof text, format, args);
        if (std::strncmp(text, "ode-bpp:", 8) == 0) lines().emplace_back(text);
    }
    MessageLog() : previous(dGetMessageHandler()) {
        lines().clear();
        dSetMessageHandler(&record);
    }
    ~MessageLog() { dSetMessageHandler(previous); }
    MessageLog(const MessageLog&) = delete;
    MessageLog& operator=(const MessageLog&) = delete;
    dMessageFunction* previous;
};

bool all_finite(const dReal* v, int n) {
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

// A collider may hand over a NaN depth (b turns NaN) or a NaN normal (J does); trimesh colliders
// can. bpp refuses such an island, and ODE's Dantzig would answer it with NaN, which ODE's step
// then aborts on. The world step takes out the joints with non-finite rows instead (patches/0001):
// their rows pinned at zero with J zero, the rest of the island solved once more. A box whose four
// contacts are all bad falls through the ground; with one bad contact of four it stays up on the
// other three. Every body stays finite, the program hears of it once per world, and no island is
// handed to ODE's Dantzig, in the sparse form and in the dense one alike.
TEST(OdeHook, JointsWithNonFiniteRowsAreTakenOutAndTheRestOfTheIslandSolved) {
    OdeLifetime ode;
    using Tune = void (*)(dContact&, int);
    struct Case {
        Tune tune;
        bool box_falls;
    };
    const Case cases[] = {
        {[](dContact& c, int) { c.geom.depth = NAN; }, true},
        {[](dContact& c, int) { c.geom.normal[2] = NAN; }, true},
        {[](dContact& c, int i) { c.geom.depth = i == 0 ? NAN : c.geom.depth; }, false},
    };
    // the sparse form, and the same solver fed ODE's dense A, whose rows and columns are taken out
    ASSERT_EQ(ode_bpp_register_dense_form("bpp", "bpp-dense-form"), 1);
    for (const char* solver : {"bpp", "bpp-dense-form"})
    for (const Case& k : cases) {
        SCOPED_TRACE(solver);
        MessageLog messages;
        SmallScene s(solver);
        s.tune_contact = k.tune;
        std::vector<std::string> fallbacks;
        dWorldSetMLCPObserver(s.world, &record_fallback, &fallbacks);
        for (int i = 0; i < 30; ++i) s.step();
        for (dBodyID b : s.bodies) {
            EXPECT_TRUE(all_finite(dBodyGetPosition(b), 3) && all_finite(dBodyGetLinearVel(b), 3) &&
                        all_finite(dBodyGetAngularVel(b), 3) && all_finite(dBodyGetQuaternion(b), 4));
        }
        if (k.box_falls) EXPECT_LT(dBodyGetPosition(s.box)[2], -0.5) << "0.5 s of free fall from 0.25 m";
        else EXPECT_GT(dBodyGetPosition(s.box)[2], 0.2) << "three good contacts of four hold it";
        dMLCPStepStats total{};
        dWorldGetMLCPStats(s.world, nullptr, &total);
        EXPECT_EQ(total.failures, 0) << "nothing left for ODE's Dantzig";
        EXPECT_EQ(total.fallbacks, 30) << "the box's island, once per step";
        ASSERT_EQ(fallbacks.size(), 30u);
        for (const std::string& name : fallbacks) EXPECT_EQ(name, "joints with non-finite rows taken out");
        ASSERT_EQ(messages.lines().size(), 1u);
        EXPECT_NE(messages.lines()[0].find("bpp could not solve an island of"), std::string::npos) << messages.lines()[0];
        EXPECT_NE(messages.lines()[0].find("invalid-input: row"), std::string::npos) << messages.lines()[0];
        EXPECT_NE(messages.lines()[0].find("not finite"), std::string::npos) << messages.lines()[0];
    }
}

// A world's settings end with it: a world created later at the same address (the allocator
// reuses it) must start from the defaults, not inherit them.
TEST(OdeHook, DestroyingAWorldForgetsItsSettings) {
    OdeLifetime ode;
    dWorldID world = dWorldCreate();
    ode_bpp::WorldSettings settings;
    settings.options.max_pivots = 7;
    settings.warm_start = false;
    ode_bpp::set_world_settings(world, settings);
    ASSERT_EQ(ode_bpp::world_settings(world).options.max_pivots, 7);
    const dWorldID gone = world;
    dWorldDestroy(world);
    const ode_bpp::WorldSettings after = ode_bpp::world_settings(gone);  // a lookup by address only
    EXPECT_EQ(after.options.max_pivots, ode_bpp::WorldSettings{}.options.max_pivots);
    EXPECT_TRUE(after.warm_start);
    EXPECT_EQ(dAddMLCPWorldDestroyedListener(nullptr, nullptr), 0);
}

TEST(OdeHook, SolveMLCPDantzigSolvesABoxedProblem) {
    OdeLifetime ode;
    // A = [[2,.3,.1],[.3,1.5,.2],[.1,.2,1.8]], b = [1,.9,-.2]: box [-0.1, 0.1] on row 2 (docs/maths.md's friction example, no findex)
    const int n = 3, skip = dPAD(n);
    std::vector<dReal> A(n * skip, 0.0);
    const double full[3][3] = {{2, .3, .1}, {.3, 1.5, .2}, {.1, .2, 1.8}};
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) A[i * skip + j] = full[i][j];
    const dReal b[3] = {1, .9, -.2}, lo[3] = {0, -0.1, -0.1}, hi[3] = {dInfinity, 0.1, 0.1};
    dReal x[3];
    ASSERT_EQ(dSolveMLCPDantzig(n, A.data(), x, b, 0, lo, hi, nullptr), 1);
    for (int i = 0; i < n; ++i) {
        double w = -b[i];
        for (int j = 0; j < n; ++j) w += full[i][j] * x[j];
        const bool at_lo = std::abs(x[i] - lo[i]) < 1e-12, at_hi = std::abs(x[i] - hi[i]) < 1e-12;
        EXPECT_GE(x[i], lo[i] - 1e-12);
        EXPECT_LE(x[i], hi[i] + 1e-12);
        if (at_lo) {
            EXPECT_GE(w, -1e-10);
        } else if (at_hi) {
            EXPECT_LE(w, 1e-10);
        } else {
            EXPECT_NEAR(w, 0.0, 1e-10);
        }
    }
    EXPECT_EQ(dSolveMLCPDantzig(0, A.data(), x, b, 0, lo, hi, nullptr), 0);
}

}  // namespace
