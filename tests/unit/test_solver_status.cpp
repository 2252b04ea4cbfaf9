// Statuses agree with residuals, for every method (solver.cpp, agree_with_residual): Converged
// only where the residual of the method's friction semantics is within certification_level(),
// never Converged-less where the natural residual certifies. And mu = +inf ("never slips") is
// legal input whose friction rows every method treats as unbounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "ode_bpp/io.h"
#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "problems/generators.h"
#include "problems/named.h"
#include "test_io_support.h"

namespace ode_bpp {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool keeps_friction_consistent(const Options& o) {
    return o.method == Method::Pgs || (o.method != Method::Dantzig && o.friction == FrictionMode::Consistent);
}

/// The status rule written out from solver.h's contract, against the residuals solve() reports.
void expect_status_agrees(const Result& r, const Options& o, const std::string& where) {
    SCOPED_TRACE(where + ": " + to_string(o.method) + "/" + to_string(o.friction) + " " + to_string(r.status) +
                 " (" + r.message + ")");
    const double level = certification_level(o.tolerance);
    const double natural = std::min(r.residuals.scaled_natural, r.residuals.relative_natural);
    const double fixed = std::min(r.residuals.scaled_fixed_bound, r.residuals.fixed_bound);
    // Converged: certified (natural), or unrefuted by the fixed-bound residual of a frozen method
    if (r.status == Status::Converged) {
        EXPECT_LE(keeps_friction_consistent(o) ? natural : std::min(natural, fixed), level);
    }
    if (r.status == Status::MaxIterations || r.status == Status::FrictionNotConsistent) {
        EXPECT_GT(natural, level);
        EXPECT_FALSE(r.message.empty());
    }
}

Options options_for(Method m, FrictionMode f, int budget) {
    Options o;
    o.method = m;
    o.friction = f;
    o.max_pivots = budget;
    o.pgs_iterations = 4 * budget;
    o.dantzig_fallback = false;
    return o;
}

// Small budgets make every method end short of an answer now and then, and sometimes on one
// that is exact already: both sides of the rule are exercised (counted below).
TEST(SolverStatus, AgreesWithTheResidualForEveryMethod) {
    int certified_after_budget = 0, not_certified = 0;
    for (std::uint64_t seed = 0; seed < 40; ++seed) {
        const problems::OwnedProblem problems_of_seed[] = {
            problems::random_boxed_mlcp(14, 2, 3, 1e4, seed),
            problems::chain_mlcp(3 + static_cast<int>(seed % 5), 1 + static_cast<int>(seed % 3), 1e3, 1e-10),
        };
        for (const problems::OwnedProblem& p : problems_of_seed)
            for (Method m : {Method::Bpp, Method::BppChol, Method::Dantzig, Method::Pgs})
                for (FrictionMode f : {FrictionMode::Frozen, FrictionMode::Consistent})
                    for (int budget : {1, 3, 100}) {
                        const Options o = options_for(m, f, budget);
                        std::vector<double> x(static_cast<std::size_t>(p.n));
                        const Result r = solve(p, o, x.data());
                        expect_status_agrees(r, o, p.name + " seed " + std::to_string(seed));
                        certified_after_budget += r.message.rfind("certified", 0) == 0 ? 1 : 0;
                        not_certified += r.status == Status::MaxIterations ? 1 : 0;
                    }
    }
    EXPECT_GT(certified_after_budget, 0) << "no budget ran out on an exact answer: the upgrade is untested";
    EXPECT_GT(not_certified, 0) << "no answer stayed uncertified: the downgrade side is untested";
}

// A 39-row forklift island (first frame: the pallet lands on the tines) on which ODE's Dantzig
// prints "LCP internal error, s <= 0" and zeroes the rest of x: residual 1.0. It used to report
// converged.
TEST(SolverStatus, DantzigsEarlyExitIsNotConverged) {
    const ReadResult read = read_mlcp((io_test::data_dir() / "captured" / "forklift-dantzig-early-exit-39.mlcp").string());
    ASSERT_TRUE(read.ok) << read.error;
    const Options o = options_for(Method::Dantzig, FrictionMode::Frozen, 100);
    std::vector<double> x(static_cast<std::size_t>(read.file.n));
    const Result r = solve(read.file.view(), o, x.data());
    EXPECT_EQ(r.status, Status::MaxIterations);
    EXPECT_NE(r.message.find("residual"), std::string::npos) << r.message;
    EXPECT_GT(r.residuals.fixed_bound, 0.5);
    expect_status_agrees(r, o, "forklift island");
    // bpp on the same island: converged and certified
    const Options b = options_for(Method::Bpp, FrictionMode::Frozen, 100);
    const Result rb = solve(read.file.view(), b, x.data());
    EXPECT_EQ(rb.status, Status::Converged) << rb.message;
    expect_status_agrees(rb, b, "forklift island");
}

// The captured islands (tests/data/captured, README there): whatever each method makes of them,
// its status agrees with its residual.
TEST(SolverStatus, AgreesWithTheResidualOnCapturedIslands) {
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(io_test::data_dir() / "captured")) {
        if (entry.path().extension() != ".mlcp") continue;
        const ReadResult read = read_mlcp(entry.path().string());
        ASSERT_TRUE(read.ok) << read.error;
        ++files;
        for (Method m : {Method::Bpp, Method::Dantzig, Method::Pgs})
            for (FrictionMode f : {FrictionMode::Frozen, FrictionMode::Consistent}) {
                const Options o = options_for(m, f, 100);
                std::vector<double> x(static_cast<std::size_t>(read.file.n));
                expect_status_agrees(solve(read.file.view(), o, x.data()), o, entry.path().filename().string());
            }
    }
    EXPECT_GE(files, 4);
}

// mu = +inf: Consistent friction converges (it ended friction-not-consistent), and every method's
// answer leaves the friction rows unbounded: w_f = 0 wherever x_f is not 0 or even where it is.
TEST(SolverStatus, InfiniteFrictionIsUnboundedForEveryMethod) {
    const problems::OwnedProblem p = problems::never_slipping_chain();
    int friction_rows = 0;
    for (int i = 0; i < p.n; ++i) friction_rows += p.findex[i] >= 0 && p.hi[i] == kInf ? 1 : 0;
    ASSERT_EQ(friction_rows, 8);
    for (Method m : {Method::Bpp, Method::BppSky, Method::BppChol, Method::Dantzig})
        for (FrictionMode f : {FrictionMode::Frozen, FrictionMode::Consistent}) {
            const Options o = options_for(m, f, 100);
            std::vector<double> x(static_cast<std::size_t>(p.n));
            const Result r = solve(p, o, x.data());
            SCOPED_TRACE(std::string(to_string(m)) + "/" + to_string(f));
            EXPECT_EQ(r.status, Status::Converged) << r.message;
            EXPECT_LE(std::min(r.residuals.scaled_natural, r.residuals.relative_natural), 1e-10);
            std::vector<double> w, scale;
            residual_vectors(p, ConstStrided{x.data(), 1}, w, scale);
            for (int i = 0; i < p.n; ++i) {
                if (p.findex[i] < 0) continue;
                EXPECT_LE(std::abs(w[i]), 1e-9 * scale[i] + 1e-12) << "friction row " << i;
            }
            expect_status_agrees(r, o, p.name);
        }
}

// Illegal friction coefficients stay illegal: -inf and NaN are refused with the row named.
TEST(SolverStatus, NegativeOrNanFrictionCoefficientIsInvalidInput) {
    for (const double mu : {-kInf, std::numeric_limits<double>::quiet_NaN()}) {
        problems::OwnedProblem p = problems::never_slipping_chain();
        int row = 0;
        while (p.findex[row] < 0) ++row;
        p.hi[row] = mu;
        std::vector<double> x(static_cast<std::size_t>(p.n), 1.0);
        const Result r = solve(p, options_for(Method::Bpp, FrictionMode::Consistent, 100), x.data());
        EXPECT_EQ(r.status, Status::InvalidInput) << mu;
        EXPECT_NE(r.message.find("row " + std::to_string(row)), std::string::npos) << r.message;
        EXPECT_TRUE(std::all_of(x.begin(), x.end(), [](double v) { return v == 0.0; }));
    }
}

// The fuzz seeds of the same cases (tests/data/make-samples.py): mu = +inf solves, mu = -inf is refused.
TEST(SolverStatus, FrictionCoefficientSamples) {
    const ReadResult legal = read_mlcp((io_test::data_dir() / "never-slipping-3.mlcp").string());
    const ReadResult illegal = read_mlcp((io_test::data_dir() / "negative-friction-3.mlcp").string());
    ASSERT_TRUE(legal.ok) << legal.error;
    ASSERT_TRUE(illegal.ok) << illegal.error;
    for (Method m : {Method::Bpp, Method::Dantzig, Method::Pgs})
        for (FrictionMode f : {FrictionMode::Frozen, FrictionMode::Consistent}) {
            const Options o = options_for(m, f, 100);
            std::vector<double> x(3);
            const Result r = solve(legal.file.view(), o, x.data());
            EXPECT_EQ(r.status, Status::Converged) << to_string(m) << "/" << to_string(f) << ": " << r.message;
            EXPECT_EQ(solve(illegal.file.view(), o, x.data()).status, Status::InvalidInput);
        }
}

}  // namespace
}  // namespace ode_bpp

namespace ode_bpp {
namespace {

/// heavy_internal_impulse from row 2 at its bound, in the three routes a bpp solve can take.
struct PolishCase {
    const char* name;
    FrictionMode friction;
    int dense_island_rows;  ///< Tuning::dense_island_rows: 0 keeps a 3-row island off the small path
};

void PrintTo(const PolishCase& c, std::ostream* os) { *os << c.name; }

class SolverPolish : public ::testing::TestWithParam<PolishCase> {};

TEST_P(SolverPolish, AnswerCertifiedOnlyByRowScalesIsSolvedAgainUntilItCertifiesAgainstB) {
    const problems::OwnedProblem p = problems::heavy_internal_impulse();
    Options o;
    o.friction = GetParam().friction;
    o.tuning.dense_island_rows = GetParam().dense_island_rows;
    Start at_bound;
    at_bound.states = {RowState::Free, RowState::Free, RowState::AtLo};
    std::vector<double> x(3);
    const Result r = solve(p.view(), o, x.data(), at_bound);
    EXPECT_EQ(r.status, Status::Converged) << r.message;
    EXPECT_LE(r.residuals.relative_natural, certification_level(o.tolerance)) << r.message;
    EXPECT_GT(x[2], 0.5e-7) << "row 2 stayed at its bound";
    EXPECT_NE(r.message.find("solved again at tolerance"), std::string::npos) << r.message;
    EXPECT_GE(r.pivoting.pivots, 2) << "the counts must include both solves";
    expect_status_agrees(r, o, "heavy_internal_impulse");
}

TEST_P(SolverPolish, CertifiedAnswerIsNotSolvedAgain) {
    const problems::OwnedProblem p = problems::heavy_internal_impulse();
    Options o;
    o.friction = GetParam().friction;
    o.tuning.dense_island_rows = GetParam().dense_island_rows;
    std::vector<double> x(3);
    const Result r = solve(p.view(), o, x.data());  // from all rows free: row 2 is found free at once
    EXPECT_EQ(r.status, Status::Converged) << r.message;
    EXPECT_TRUE(r.message.empty()) << r.message;
    EXPECT_LE(r.residuals.relative_natural, certification_level(o.tolerance));
}

const PolishCase kPolishCases[] = {
    {"FrozenSmallIsland", FrictionMode::Frozen, 32},
    {"FrozenSkyline", FrictionMode::Frozen, 0},
    {"Consistent", FrictionMode::Consistent, 32},
};

INSTANTIATE_TEST_SUITE_P(Routes, SolverPolish, ::testing::ValuesIn(kPolishCases),
                         [](const ::testing::TestParamInfo<PolishCase>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace ode_bpp
