// An island whose A alone would pass Options::max_factor_entries is answered inside dWorldStep by
// projected Gauss-Seidel on J and J M^-1, without forming A (ode/jacobian_pgs.h; docs/modelling.md,
// "Islands too large for an exact step"): the same iterates as solve()'s PGS fallback on the
// assembled A, up to rounding, and reported as that fallback.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <ode/mlcp.h>
#include <ode/ode.h>

#include "ode_bpp/capture.h"
#include "ode_bpp/ode.h"
#include "ode_bpp/residuals.h"
#include "ode_lifetime.h"

namespace {

using ode_bpp::test::OdeLifetime;

/// Spheres dropped into one heap at once, overlapping: one island of a few hundred contact rows
/// (mu = infinity on half the contacts, 0.5 on the rest).
class Heap {
public:
    explicit Heap(int spheres) {
        world = dWorldCreate();
        space = dSimpleSpaceCreate(nullptr);
        contacts = dJointGroupCreate(0);
        dWorldSetGravity(world, 0, 0, -9.81);
        dWorldSetCFM(world, 1e-5);
        dRandSetSeed(7);
        for (int i = 0; i < spheres; ++i) {
            const dBodyID b = dBodyCreate(world);
            bodies.push_back(b);
            dBodySetPosition(b, dRandReal() * 0.6, dRandReal() * 0.6, dRandReal() * 0.6 + 0.2);
            dMass m;
            dMassSetSphere(&m, 1000.0, 0.15);
            dBodySetMass(b, &m);
            dGeomSetBody(dCreateSphere(space, 0.15), b);
        }
        dCreatePlane(space, 0, 0, 1, 0);
    }
    ~Heap() {
        dJointGroupDestroy(contacts);
        dSpaceDestroy(space);
        dWorldDestroy(world);
    }
    void step() {
        dSpaceCollide(space, this, &Heap::touch);
        dWorldStep(world, 1.0 / 60.0);
        dJointGroupEmpty(contacts);
    }
    bool finite() const {
        for (const dBodyID b : bodies)
            for (int k = 0; k < 3; ++k)
                if (!std::isfinite(dBodyGetPosition(b)[k])) return false;
        return true;
    }
    dWorldID world;
    dSpaceID space;
    dJointGroupID contacts;
    std::vector<dBodyID> bodies;

private:
    static void touch(void* data, dGeomID o1, dGeomID o2) {
        auto* heap = static_cast<Heap*>(data);
        const dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
        dContact c[4];
        const int n = dCollide(o1, o2, 4, &c[0].geom, sizeof(dContact));
        for (int i = 0; i < n; ++i) {
            c[i].surface.mode = dContactApprox1;
            c[i].surface.mu = (heap->made++ % 2 == 0) ? dInfinity : 0.5;
            dJointAttach(dJointCreateContact(heap->world, heap->contacts, c + i), b1, b2);
        }
    }
    int made = 0;
};

/// The largest island of a step, as ODE handed it over, and the answer the solver wrote.
struct Largest {
    std::optional<ode_bpp::MlcpFile> problem;
    std::vector<double> x;
    std::string fallback;
    int status = -1;
};

void observe(const dMLCP* p, const dMLCPIslandStats* stats, void* data) {
    auto* largest = static_cast<Largest*>(data);
    if (largest->problem && largest->problem->n > p->m) return;
    if (stats == nullptr) {
        std::string error;
        largest->problem = ode_bpp::capture_from_ode(*p, {}, &error);
        ASSERT_TRUE(largest->problem.has_value()) << error;
        return;
    }
    largest->x.resize(static_cast<std::size_t>(p->m));
    for (int i = 0; i < p->m; ++i) largest->x[i] = p->pairsbx[2 * i + 1];
    largest->fallback = stats->fallback != nullptr ? stats->fallback : "";
    largest->status = stats->status;
}

ode_bpp::WorldSettings with_factor_limit(std::int64_t entries) {
    ode_bpp::WorldSettings s;
    s.options.max_factor_entries = entries;
    return s;
}

TEST(MatrixFreePgs, AnIslandWhoseAWouldPassTheLimitIsAnsweredFromJAsPgsOnAWould) {
    OdeLifetime ode;
    Heap heap(40);
    ASSERT_EQ(ode_bpp_use(heap.world, "bpp"), 1);
    constexpr std::int64_t kLimit = 200;  // far below the heap's A
    ode_bpp::set_world_settings(heap.world, with_factor_limit(kLimit));
    for (int step = 0; step < 3; ++step) {
        Largest largest;
        dWorldSetMLCPObserver(heap.world, &observe, &largest);
        heap.step();
        ASSERT_TRUE(largest.problem.has_value());
        ASSERT_GT(largest.problem->n, 100) << "not the heap this test is about";
        EXPECT_EQ(largest.fallback, "pgs");
        EXPECT_EQ(largest.status, dMLCPSolvedByFallback);
        const ode_bpp::Result hook = ode_bpp::last_island_result(heap.world);
        EXPECT_EQ(hook.fallback, ode_bpp::Fallback::Pgs);
        EXPECT_NE(hook.message.find("without forming A"), std::string::npos) << hook.message;

        // the same island through solve(), whose PGS fallback sweeps the assembled A
        ode_bpp::Options o = with_factor_limit(kLimit).options;
        std::vector<double> x(largest.x.size());
        const ode_bpp::Result assembled = ode_bpp::solve(largest.problem->view(), o, x.data());
        ASSERT_EQ(assembled.fallback, ode_bpp::Fallback::Pgs) << assembled.message;
        double largest_x = 0, difference = 0;
        for (std::size_t i = 0; i < x.size(); ++i) {
            largest_x = std::max(largest_x, std::abs(x[i]));
            difference = std::max(difference, std::abs(x[i] - largest.x[i]));
        }
        ASSERT_GT(largest_x, 0.0);
        EXPECT_LE(difference, 1e-9 * largest_x) << "step " << step;
        // residuals from J: the natural one as on A, the scaled one from a larger row scale
        EXPECT_NEAR(hook.residuals.natural, assembled.residuals.natural, 1e-9 * (1 + assembled.residuals.natural));
        EXPECT_LE(hook.residuals.scaled_natural, assembled.residuals.scaled_natural * (1 + 1e-9) + 1e-300);
        EXPECT_EQ(hook.tight, assembled.tight);
    }
    EXPECT_TRUE(heap.finite());
}

/// The count a message of the matrix-free path quotes: "... would hold [at least] N entries ...".
std::int64_t quoted_entries(const std::string& message) {
    const std::size_t at = message.find("hold ");
    if (at == std::string::npos) return -1;
    std::size_t digits = message.find_first_of("0123456789", at);
    return digits == std::string::npos ? -1 : std::stoll(message.substr(digits));
}

/// The heap's first step under a factor limit: the world's last result (the heap is one island
/// besides spheres alone, which have no rows), and its largest island as ODE saw it answered.
struct FirstStep {
    ode_bpp::Result result;
    int rows = 0;
    std::string fallback;
    int status = -1;
};

FirstStep first_step_with_limit(std::int64_t limit) {
    Heap heap(40);
    EXPECT_EQ(ode_bpp_use(heap.world, "bpp"), 1);
    ode_bpp::set_world_settings(heap.world, with_factor_limit(limit));
    Largest largest;
    dWorldSetMLCPObserver(heap.world, &observe, &largest);
    heap.step();
    EXPECT_TRUE(heap.finite());
    return {ode_bpp::last_island_result(heap.world), largest.problem ? largest.problem->n : 0, largest.fallback,
            largest.status};
}

TEST(MatrixFreePgs, AnIslandWhoseFactorWouldPassTheLimitIsAnsweredFromJWithTheSolvesOwnCount) {
    OdeLifetime ode;
    // A's entries, bounded from below: the matrix-free path's message at a limit of 1
    const FirstStep tiny = first_step_with_limit(1);
    const std::int64_t a_entries = quoted_entries(tiny.result.message);
    ASSERT_GT(a_entries, 0) << tiny.result.message;
    ASSERT_GT(tiny.rows, 100) << "not the heap this test is about";

    // A within the limit, its factor past it: counted from the joints, A never formed
    const FirstStep past = first_step_with_limit(a_entries);
    EXPECT_EQ(past.fallback, "pgs");
    EXPECT_EQ(past.result.fallback, ode_bpp::Fallback::Pgs);
    EXPECT_NE(past.result.message.find("the Cholesky factor would hold"), std::string::npos) << past.result.message;
    EXPECT_NE(past.result.message.find("without forming A"), std::string::npos) << past.result.message;
    const std::int64_t factor = quoted_entries(past.result.message);
    ASSERT_GT(factor, a_entries);
    const auto n = static_cast<std::int64_t>(tiny.rows);
    ASSERT_LT(factor, n * (n + 1) / 2) << "the limit must not be decided by the dense triangle alone";

    // the count is the solve's: exact at it, and the solve's own check passes with it
    const FirstStep at = first_step_with_limit(factor);
    EXPECT_EQ(at.fallback, "");
    EXPECT_EQ(at.status, dMLCPSolved);
    EXPECT_EQ(at.result.fallback, ode_bpp::Fallback::None) << at.result.message;
    EXPECT_EQ(at.result.status, ode_bpp::Status::Converged) << at.result.message;
    const FirstStep below = first_step_with_limit(factor - 1);
    EXPECT_EQ(below.fallback, "pgs");
    EXPECT_EQ(below.result.fallback, ode_bpp::Fallback::Pgs);
    EXPECT_EQ(quoted_entries(below.result.message), factor);
}

TEST(MatrixFreePgs, WithinTheLimitTheHeapIsSolvedExactly) {
    OdeLifetime ode;
    Heap heap(40);
    ASSERT_EQ(ode_bpp_use(heap.world, "bpp"), 1);
    Largest largest;
    dWorldSetMLCPObserver(heap.world, &observe, &largest);
    heap.step();
    ASSERT_TRUE(largest.problem.has_value());
    EXPECT_EQ(largest.fallback, "");
    EXPECT_EQ(largest.status, dMLCPSolved);
}

}  // namespace
