// The small-island path of Method::Bpp (pivoting/small_island.h): the same answers as the general
// driver (Tuning::dense_island_rows = 0 sends every island there), the same certificate and
// polish, and the general driver taking over whatever the path cannot finish.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"
#include "ode_bpp/validation.h"
#include "pivoting/small_island.h"
#include "residuals.h"
#include "test_io_support.h"
#include "problems/generators.h"
#include "problems/named.h"
#include "problems/vectors.h"

namespace ode_bpp {
namespace {

using problems::inf_norm;
using problems::max_abs_diff;

Result run(const problems::OwnedProblem& p, std::vector<double>& x, Options o = {}, const Start& start = {}) {
    o.method = Method::Bpp;
    x.assign(p.n, std::numeric_limits<double>::quiet_NaN());
    return solve(p, o, x.data(), start);
}

/// The general driver's answer to the same problem.
Result run_general(const problems::OwnedProblem& p, std::vector<double>& x, Options o = {}) {
    o.tuning.dense_island_rows = 0;
    return run(p, x, o);
}

TEST(SmallIsland, TakesOnlyFrozenBppIslandsInTheDenseFormUpToTheThreshold) {
    const auto p = problems::random_boxed_mlcp(12, 2, 2, 1e4, 7);
    Options o;
    EXPECT_TRUE(pivoting::takes_small_island(p.view(), o));
    o.tuning.dense_island_rows = 12;
    EXPECT_TRUE(pivoting::takes_small_island(p.view(), o));
    o.tuning.dense_island_rows = 11;
    EXPECT_FALSE(pivoting::takes_small_island(p.view(), o));
    o = {};
    o.friction = FrictionMode::Consistent;
    EXPECT_FALSE(pivoting::takes_small_island(p.view(), o));
    o = {};
    o.method = Method::BppChol;
    EXPECT_FALSE(pivoting::takes_small_island(p.view(), o));
}

/// Frozen friction, boxes and unbounded rows on random islands of 3 to 32 rows: the answer of
/// the general driver, certified to the same tolerance.
TEST(SmallIsland, AgreesWithTheGeneralDriver) {
    int compared = 0;
    for (int n : {3, 8, 17, 32})
        for (std::uint64_t seed = 1; seed <= 4; ++seed) {
            const int contacts = n / 6;
            const auto p = problems::random_boxed_mlcp(n, n / 5, contacts, 1e6, 100 * n + seed);
            std::vector<double> small, general;
            Options on_the_small_path;
            on_the_small_path.tuning.dense_island_rows = 32;  // the path works at any threshold
            const Result a = run(p, small, on_the_small_path);
            const Result b = run_general(p, general);
            ASSERT_EQ(b.status, Status::Converged) << n << " " << seed << ": " << b.message;
            ASSERT_EQ(a.status, Status::Converged) << n << " " << seed << ": " << a.message;
            EXPECT_LT(max_abs_diff(small, general), 1e-7 * (1 + inf_norm(general))) << n << " " << seed;
            // Frozen bounds are not those of the answer's own normals: the residual (which takes
            // them from the answer) is the general driver's, and the certificate without friction
            if (contacts == 0) {
                EXPECT_LT(a.residuals.scaled_natural, 1e-8) << n << " " << seed;
            }
            EXPECT_NEAR(a.residuals.scaled_natural, b.residuals.scaled_natural, 1e-8) << n << " " << seed;
            EXPECT_EQ(a.pivoting.refactor_steps, a.pivoting.pivots);  // a dense refactorization per step
            EXPECT_EQ(a.pivoting.downdate_steps, 0);
            EXPECT_TRUE(a.ordering.empty());        // the caller's order: nothing for the hook to keep
            EXPECT_EQ(static_cast<int>(a.pivoting.tight_per_step.size()), a.pivoting.pivots);
            ++compared;
        }
    EXPECT_EQ(compared, 16);
}

/// Dantzig's frozen friction on the 3x3 example of docs/maths.md, and a warm start that only
/// the polish turns away from opposed friction at its bounds (pivot_loop.cpp's story).
TEST(SmallIsland, KeepsTheGeneralDriversFrictionSemanticsAndPolish) {
    for (const auto& p : {problems::dantzig_friction_3x3(), problems::opposed_friction_pair()}) {
        std::vector<double> small, general;
        ASSERT_EQ(run(p, small).status, Status::Converged) << p.name;
        ASSERT_EQ(run_general(p, general).status, Status::Converged) << p.name;
        // opposed_friction_pair: CFM 1e-9 of the diagonal, so answers agree to about 1e-9 |x|
        EXPECT_LT(max_abs_diff(small, general), 1e-8 * (1 + inf_norm(general))) << p.name;
    }
    const auto p = problems::opposed_friction_pair();
    Start start;
    start.states = {RowState::Free, RowState::AtHi, RowState::Free, RowState::AtLo};
    std::vector<double> x;
    const Result r = run(p, x, {}, start);
    ASSERT_EQ(r.status, Status::Converged);
    EXPECT_EQ(r.states[1], RowState::Free);
    EXPECT_EQ(r.states[3], RowState::Free);
    EXPECT_LT(std::abs(x[1]) + std::abs(x[3]), 1e-6 * 0.5 * x[0]);
}

/// A Cholesky breakdown (duplicated rows, no CFM) is the general driver's to regularize.
TEST(SmallIsland, LeavesABreakdownToTheGeneralDriversRegularization) {
    const auto p = problems::duplicated_rows();
    std::vector<double> x;
    const Result r = run(p, x);
    EXPECT_EQ(r.status, Status::FallbackUsed) << r.message;
    EXPECT_EQ(r.fallback, Fallback::Regularized);
    EXPECT_TRUE(std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); }));
}

/// Out of budget, the path hands over, and the steps it took are counted in the answer's pivots.
TEST(SmallIsland, HandsAnUnfinishedIslandToTheGeneralDriverAndCountsItsSteps) {
    const auto p = problems::block_pivoting_cycle();
    Options o;
    o.max_pivots = 1;
    std::vector<double> small, general;
    const Result a = run(p, small, o);
    const Result b = run_general(p, general, o);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.pivoting.pivots, b.pivoting.pivots + 1);  // its one step, then the general driver's
}

/// Frozen friction's first solve refreshes w on the rows that are not pinned friction rows alone
/// (residuals.h, dense_residual_vectors_on): with x = 0 on the others, their w and scale are the
/// full pass's, bit for bit up to the sign of a zero, and the other rows are left as they were.
TEST(SmallIsland, ResidualPassOnSomeRowsMatchesTheFullPassThere) {
    const auto p = problems::random_boxed_mlcp(12, 2, 3, 1e4, 11);
    std::vector<int> rows;
    std::vector<double> x(12, 0.0);
    for (int i = 0; i < 12; ++i)
        if (p.findex[i] < 0) {
            rows.push_back(i);
            x[i] = 0.25 * (i + 1) * (i % 2 == 0 ? 1 : -1);
        }
    ASSERT_GT(rows.size(), 2u);
    ASSERT_LT(rows.size(), 12u);
    std::vector<double> w_all(12), scale_all(12), w(12, 7.0), scale(12, 7.0);
    dense_residual_vectors(p.view(), ConstStrided{x.data(), 1}, w_all.data(), scale_all.data());
    dense_residual_vectors_on(p.view(), ConstStrided{x.data(), 1}, rows.data(), static_cast<int>(rows.size()), w.data(),
                              scale.data());
    for (int i = 0; i < 12; ++i) {
        const bool on = std::find(rows.begin(), rows.end(), i) != rows.end();
        EXPECT_EQ(w[i], on ? w_all[i] : 7.0) << i;
        EXPECT_EQ(scale[i], on ? scale_all[i] : 7.0) << i;
    }
}

/// A box on three coplanar contacts (tests/data/captured/README.md): its six friction rows have
/// rank three, and the previous step's index set is the mirror of this one's (the third contact's
/// two friction rows at the opposite bounds). Eq. 4 frees both, a block step then frees every
/// redundant row and x swings by orders of magnitude. Murty's pivot at the first step that does
/// not improve (Tuning::small_island_murty_after = 0) settles it in fewer steps than block steps
/// with the general path's patience, and both reach the same answer.
TEST(SmallIsland, MurtysPivotSettlesRedundantFrictionRowsFromAMirroredWarmStart) {
    const ReadResult read = read_mlcp((io_test::data_dir() / "captured" / "friction-demo-mirrored-warm-start-9.mlcp").string());
    ASSERT_TRUE(read.ok) << read.error;
    const MlcpFile& f = read.file;
    std::vector<double> cold(f.n), patient(f.n), eager(f.n);
    const Result own = solve(f.view(), Options{}, cold.data());
    ASSERT_EQ(own.status, Status::Converged) << own.message;
    Start mirrored{own.states, {}};
    int swapped = 0;
    for (int i = 0; i < f.n; ++i) {
        RowState& s = mirrored.states[i];
        if (f.findex[i] < 0 || s == RowState::Free) continue;
        s = s == RowState::AtLo ? RowState::AtHi : RowState::AtLo;
        ++swapped;
    }
    ASSERT_EQ(swapped, 2);
    Options o;
    o.tuning.small_island_murty_after = 3;
    const Result block = solve(f.view(), o, patient.data(), mirrored);
    o.tuning.small_island_murty_after = 0;
    const Result murty = solve(f.view(), o, eager.data(), mirrored);
    ASSERT_EQ(block.status, Status::Converged) << block.message;
    ASSERT_EQ(murty.status, Status::Converged) << murty.message;
    EXPECT_GT(murty.pivoting.murty_pivots, 0);
    EXPECT_LT(murty.pivoting.pivots, block.pivoting.pivots);
    EXPECT_LT(max_abs_diff(eager, cold), 1e-9);
    EXPECT_LT(max_abs_diff(patient, cold), 1e-9);
}

/// A box of the cannon scene sliding on four coplanar contacts (tests/data/captured/README.md),
/// from the index set the world step started it from: its eight friction rows have rank three,
/// and once the block steps of Frozen friction's second solve stop improving (its third step),
/// Murty's single pivots wander through their near null space, x swinging to 1e7, until the small
/// path's budget runs out and the general driver takes over. From Tuning::rescue_after plain steps on, the active set settles
/// it on the small path, at the answer of the general driver.
TEST(SmallIsland, ActiveSetSettlesASlidingBoxWhereMurtysPivotsWander) {
    const ReadResult read = read_mlcp((io_test::data_dir() / "captured" / "cannon-sliding-box-murty-wanders-168.mlcp").string());
    ASSERT_TRUE(read.ok) << read.error;
    const MlcpFile& f = read.file;
    std::string error;
    const std::optional<Start> start = start_from_metadata(f.meta, f.n, &error);
    ASSERT_TRUE(start.has_value()) << error;
    Options murty_only;
    murty_only.tuning.rescue_after = 0;
    std::vector<double> settled(f.n), wandered(f.n), general(f.n);
    const Result active = solve(f.view(), Options{}, settled.data(), *start);
    const Result murty = solve(f.view(), murty_only, wandered.data(), *start);
    Options general_only;
    general_only.tuning.dense_island_rows = 0;
    const Result reference = solve(f.view(), general_only, general.data(), *start);
    ASSERT_EQ(active.status, Status::Converged) << active.message;
    ASSERT_EQ(reference.status, Status::Converged) << reference.message;
    ASSERT_GT(active.pivoting.murty_pivots, 0);
    // every step on the small path refactors densely (general driver: deletions and updates)
    EXPECT_EQ(active.pivoting.refactor_steps, active.pivoting.pivots);
    EXPECT_LE(active.pivoting.pivots, 2 * f.n);  // measured: 14
    EXPECT_GT(murty.pivoting.pivots, 100);  // one fixed-bound solve's budget, spent
    // cond(A) near 1e10 (CFM 1e-10 on the redundant rows): agreement to about eps * cond
    EXPECT_LT(max_abs_diff(settled, general), 1e-8 * (1 + inf_norm(general)));
}

TEST(SmallIsland, ReportsInvalidMatricesAsValidateDoes) {
    auto p = problems::random_boxed_mlcp(6, 1, 1, 1e3, 3);
    p.a(4, 2) = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> x;
    const Result r = run(p, x);
    EXPECT_EQ(r.status, Status::InvalidInput);
    EXPECT_EQ(r.message, validate(p.view()).message);
    EXPECT_EQ(x, std::vector<double>(6, 0.0));
    p.a(4, 2) = 0;
    p.a(3, 3) = -1;
    EXPECT_EQ(run(p, x).message, validate(p.view()).message);
}

}  // namespace
}  // namespace ode_bpp
