// Murty's single pivots on an incremental factor (pivoting/single_pivots.h) through solve(): the
// captured islands of the slow tail (tests/data/captured), on which block pivoting and the
// regularization rescue ran out of their 100-step budget, converge and certify without the
// rescue and without ODE's Dantzig.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"
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
        EXPECT_EQ(r.rescues, 0) << name;
        EXPECT_GT(r.murty_pivots, 0) << name;
        EXPECT_LE(r.scaled_fixed_bound_residual, certification_level(Options{}.tolerance)) << name;
    }
}

TEST(PivotingSinglePivots, WithoutThemTheSameIslandsRunOutOfBudget) {
    for (const char* name : kOverBudget) EXPECT_EQ(solve_captured(name, false).status, Status::MaxIterations) << name;
}

}  // namespace
}  // namespace ode_bpp
