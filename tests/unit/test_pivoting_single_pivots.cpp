// Murty's single pivots on an incremental factor (pivoting/single_pivots.h) through solve(): the
// captured islands of the slow tail (tests/data/captured), on which block pivoting and the
// regularization rescue ran out of their 100-step budget, converge and certify without the
// rescue and without ODE's Dantzig.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"
#include "problems/generators.h"
#include "problems/vectors.h"
#include "test_io_support.h"

namespace ode_bpp {
namespace {

const char* const kOverBudget[] = {"bin-frozen-over-budget-93.mlcp", "bin-frozen-over-budget-114.mlcp",
                                   "forwarder-frozen-over-budget-226.mlcp"};

Result solve_captured(const std::string& name, bool single_pivots) {
    const ReadResult read = read_mlcp((io_test::data_dir() / "captured" / name).string());
    EXPECT_TRUE(read.ok) << read.error;
    Options o;  // Bpp, Frozen friction, a budget of 100
    o.dantzig_fallback = false;
    o.tuning.single_pivots = single_pivots;
    std::vector<double> x(static_cast<std::size_t>(read.file.n));
    return solve(read.file.view(), o, x.data());
}

TEST(PivotingSinglePivots, FinishTheCapturedIslandsThatRanOutOfBudget) {
    for (const char* name : kOverBudget) {
        const Result r = solve_captured(name, true);
        EXPECT_EQ(r.status, Status::Converged) << name << ": " << r.message;
        EXPECT_EQ(r.fallback, Fallback::None) << name;
        EXPECT_EQ(r.pivoting.rescues, 0) << name;
        EXPECT_GT(r.pivoting.murty_pivots, 0) << name;
        EXPECT_LE(r.residuals.scaled_fixed_bound, certification_level(Options{}.tolerance)) << name;
    }
}

TEST(PivotingSinglePivots, WithoutThemTheSameIslandsRunOutOfBudget) {
    for (const char* name : kOverBudget) EXPECT_EQ(solve_captured(name, false).status, Status::MaxIterations) << name;
}

// With one plain step before them, single pivots answer most of the problem on random boxed
// MLCPs: the answer is Dantzig's (both solve the same frozen-friction problem exactly).
TEST(PivotingSinglePivots, AgreeWithDantzigWhenTheyDoMostOfTheWork) {
    int used = 0;
    for (double cond : {1e2, 1e6})
        for (std::uint64_t seed = 1; seed <= 6; ++seed) {
            const auto p = problems::random_boxed_mlcp(40, 4, 8, cond, seed);
            Options o;
            o.dantzig_fallback = false;
            o.method = Method::Dantzig;
            std::vector<double> reference(static_cast<std::size_t>(p.n)), x(static_cast<std::size_t>(p.n));
            ASSERT_EQ(solve(p, o, reference.data()).status, Status::Converged);
            for (Method m : {Method::Bpp, Method::BppSky, Method::BppChol}) {
                o.method = m;
                o.tuning.rescue_after = 1;
                o.tuning.dense_island_rows = 0;  // the skyline path, not the small-island one
                const Result r = solve(p, o, x.data());
                ASSERT_EQ(r.status, Status::Converged) << to_string(m) << " seed " << seed << ": " << r.message;
                used += r.pivoting.update_steps > 0;
                EXPECT_EQ(r.pivoting.downdate_steps + r.pivoting.refactor_steps + r.pivoting.update_steps, r.pivoting.pivots);
                const double tol = 1e3 * cond * std::numeric_limits<double>::epsilon() * (1 + problems::inf_norm(reference));
                EXPECT_LT(problems::max_abs_diff(x, reference), tol) << to_string(m) << " cond " << cond << " seed " << seed;
            }
        }
    EXPECT_GT(used, 0);  // the path under test was taken
}

}  // namespace
}  // namespace ode_bpp
