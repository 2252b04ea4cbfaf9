// solve() in an explicit Workspace (ode_bpp/workspace.h): the same answers as in the thread's own
// workspace whatever the workspace solved before, independent workspaces on concurrent threads,
// a warm small-island solve that allocates nothing beyond its Result, and nothing at all once a
// spent Result has been recycled.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <new>
#include <thread>
#include <vector>

#include "ode_bpp/solver.h"
#include "ode_bpp/workspace.h"
#include "problems/generators.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// Counts every allocation of this test executable (AllocatesNothingOnceWarm).
void* operator new(std::size_t size) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
// std::get_temporary_buffer (std::stable_partition's scratch) asks for it without throwing: it
// must come from malloc too, since every delete here frees (AddressSanitizer checks the pairing)
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace ode_bpp {
namespace {

/// Islands of falling and rising sizes, so that each solve meets buffers a different one grew.
std::vector<problems::OwnedProblem> mixed_islands() {
    std::vector<problems::OwnedProblem> islands;
    std::uint64_t seed = 11;
    for (int n : {120, 6, 48, 24, 120, 9, 60})
        islands.push_back(problems::random_boxed_mlcp(n, n / 4, n / 6, 1e5, seed++));
    return islands;
}

struct Answer {
    Status status;
    int pivots;
    std::vector<double> x;
    bool operator==(const Answer& o) const {
        return status == o.status && pivots == o.pivots && x.size() == o.x.size() &&
               std::memcmp(x.data(), o.x.data(), x.size() * sizeof(double)) == 0;  // bit for bit
    }
};

std::vector<Options> option_sets() {
    std::vector<Options> sets;
    for (Method m : {Method::Bpp, Method::BppSky, Method::BppChol, Method::Pgs})
        for (FrictionMode f : {FrictionMode::Frozen, FrictionMode::Consistent}) {
            Options o;
            o.method = m;
            o.friction = f;
            sets.push_back(o);
        }
    return sets;
}

/// Every island under every option set; workspace null: the thread's own.
std::vector<Answer> solve_all(const std::vector<problems::OwnedProblem>& islands, Workspace* workspace) {
    std::vector<Answer> answers;
    for (const Options& o : option_sets())
        for (const auto& p : islands) {
            std::vector<double> x(p.n);
            const Result r = workspace ? solve(p, o, Strided{x.data(), 1}, {}, *workspace) : solve(p, o, x.data());
            answers.push_back({r.status, r.pivoting.pivots, x});
        }
    return answers;
}

TEST(SolverWorkspace, GivesTheThreadWorkspacesAnswersWhateverItSolvedBefore) {
    const auto islands = mixed_islands();
    const std::vector<Answer> reference = solve_all(islands, nullptr);
    Workspace workspace;
    EXPECT_EQ(solve_all(islands, &workspace), reference);
    EXPECT_EQ(solve_all(islands, &workspace), reference) << "second round, on grown buffers";
    Workspace moved = std::move(workspace);
    EXPECT_EQ(solve_all(islands, &moved), reference);
    EXPECT_EQ(solve_all(islands, &workspace), reference) << "a moved-from workspace starts empty again";
}

TEST(SolverWorkspace, IndependentWorkspacesSolveOnConcurrentThreads) {
    const auto islands = mixed_islands();
    const std::vector<Answer> reference = solve_all(islands, nullptr);
    constexpr int kThreads = 4;
    std::vector<std::vector<Answer>> answers(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            Workspace workspace;
            answers[t] = solve_all(islands, t % 2 == 0 ? &workspace : nullptr);
        });
    for (std::thread& t : threads) t.join();
    for (int t = 0; t < kThreads; ++t) EXPECT_EQ(answers[t], reference) << "thread " << t;
}

TEST(SolverWorkspace, AWarmSmallIslandSolveAllocatesOnlyItsResultsIndexSet) {
    const auto p = problems::random_boxed_mlcp(6, 2, 1, 1e3, 5);
    Options o;
    o.record_steps = false;  // Result::tight_per_step would grow step by step
    Workspace workspace;
    std::vector<double> x(p.n);
    ASSERT_EQ(solve(p, o, Strided{x.data(), 1}, {}, workspace).status, Status::Converged);
    const long before = g_allocations.load();
    const Result r = solve(p, o, Strided{x.data(), 1}, {}, workspace);
    const long allocations = g_allocations.load() - before;
    ASSERT_EQ(r.status, Status::Converged);
    EXPECT_EQ(allocations, 1) << "Result::states only";
}

TEST(SolverWorkspace, ASmallIslandSolveAfterARecycledResultAllocatesNothing) {
    const auto p = problems::random_boxed_mlcp(6, 2, 1, 1e3, 5);
    Options o;
    o.record_steps = false;
    Workspace workspace;
    std::vector<double> x(p.n);
    Result spent = solve(p, o, Strided{x.data(), 1}, {}, workspace);
    ASSERT_EQ(spent.status, Status::Converged);
    const std::vector<RowState> expected = spent.states;
    const RowState* storage = spent.states.data();
    workspace.recycle(std::move(spent));
    const long before = g_allocations.load();
    const Result r = solve(p, o, Strided{x.data(), 1}, {}, workspace);
    const long allocations = g_allocations.load() - before;
    ASSERT_EQ(r.status, Status::Converged);
    EXPECT_EQ(allocations, 0);
    EXPECT_EQ(r.states.data(), storage) << "the recycled index set's storage";
    EXPECT_EQ(r.states, expected);
}

}  // namespace
}  // namespace ode_bpp
