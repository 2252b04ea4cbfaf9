// Stability where methods fail (issue 6), untimed: bpp holds the load at the paper's regime
// corners, PGS at 35 sweeps does not, and BPP's own failure modes end in a documented status
// with a sane world. Every check is a physical property measured in the world (joint gaps,
// contact depths, distances, energy, the stopping distance of friction) against a tolerance
// derived from the physics (sweep_run.h), never a recorded output of the solver.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes/sweep_run.h"

namespace ode_bpp::scenes {
namespace {

constexpr double kPaperStep = 1.0 / 60.0;  // paper Table 1

RunSpec paper_run(SweepPattern pattern, double ratio, double compliance, const std::string& method) {
    RunSpec spec;
    spec.scene = {pattern, ratio, 0};
    spec.method = method;
    spec.step = kPaperStep;
    spec.cfm = cfm_from_compliance(compliance, kPaperStep);
    spec.seconds = 5;
    return spec;
}

std::string describe(const RunSpec& s, const RunResult& r) {
    return std::string(to_string(s.scene.pattern)) + " " + s.method + " r=" + std::to_string(s.scene.mass_ratio) +
           " cfm=" + std::to_string(s.cfm) + ": " + to_string(r.outcome) + " " + r.cause;
}

/// The world stayed finite for the whole run and every measure is within its tolerance.
void expect_physics_held(const RunSpec& s, const RunResult& r) {
    const long steps = std::lround(s.seconds / s.step);
    EXPECT_EQ(r.steps, steps) << describe(s, r);
    EXPECT_NE(r.outcome, Outcome::Exploded) << describe(s, r);
    EXPECT_LT(r.max_joint_error, r.tolerance) << describe(s, r);
    EXPECT_LT(r.max_penetration, r.tolerance) << describe(s, r);
    EXPECT_EQ(r.worst_placement, 0.0) << describe(s, r);
    EXPECT_LT(r.energy_drift, 1e-2) << describe(s, r);  // swinging and resting scenes only lose energy
}

/// The sliding pair decelerates at mu g: the heavy box stops after v0^2 / (2 mu g), less about
/// half a step's travel in the discrete scheme (positions move with the end-of-step velocity).
void expect_friction_stops_the_pair(const RunSpec& s, const RunResult& r) {
    const double v0 = 2.0;  // SweepPattern::SlidingPair's initial speed
    const double g = SceneParams{}.gravity;
    const double expected = v0 * v0 / (2 * s.mu * g), step_travel = v0 * s.step;
    EXPECT_NEAR(r.final_slide, expected - 0.5 * step_travel, 0.05 * expected + step_travel) << describe(s, r);
}

// ---- bpp holds the load at the paper's regime (mass ratio up to 4.4e6:1, compliance 1e-6..1e-10)

struct RegimePoint {
    SweepPattern pattern;
    double ratio;
    double compliance;
};

class PaperRegime : public ::testing::TestWithParam<RegimePoint> {};

TEST_P(PaperRegime, BppHoldsTheLoad) {
    const RegimePoint p = GetParam();
    const RunSpec spec = paper_run(p.pattern, p.ratio, p.compliance, "bpp");
    const RunResult r = run_sweep(spec);
    expect_physics_held(spec, r);
    // bpp answered every island itself: ODE's Dantzig never had to take over
    EXPECT_EQ(r.failures, 0) << describe(spec, r);
    EXPECT_EQ(r.lcp_internal_errors, 0) << describe(spec, r);
    EXPECT_GT(r.islands, 0) << describe(spec, r);
}

std::vector<RegimePoint> regime_corners() {
    std::vector<RegimePoint> points;
    for (SweepPattern pattern : {SweepPattern::HangingChain, SweepPattern::BoxStack, SweepPattern::Offshore,
                                 SweepPattern::Ladder}) {
        // Table 2's mass ratios (winch 400, forklift 2,700, crane 6,300, parkour 20,000, offshore
        // 4,400,000), 1:1 and two decades between; compliance by decades over Table 1's range
        for (double ratio : {1.0, 400.0, 2700.0, 6300.0, 2e4, 1e5, 1e6, 4.4e6}) {
            for (double compliance : {1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) points.push_back({pattern, ratio, compliance});
        }
    }
    return points;
}

std::string regime_name(const ::testing::TestParamInfo<RegimePoint>& info) {
    char name[64];
    std::snprintf(name, sizeof name, "%s_ratio%g_c%g", to_string(info.param.pattern), info.param.ratio,
                  info.param.compliance);
    std::string s = name;
    for (char& c : s) c = (std::isalnum(static_cast<unsigned char>(c)) != 0) ? c : '_';
    return s;
}

INSTANTIATE_TEST_SUITE_P(Corners, PaperRegime, ::testing::ValuesIn(regime_corners()), regime_name);

// ---- the documented contrast: PGS at 35 sweeps lets the heavy load stretch the light chain

TEST(Contrast, PgsAt35SweepsDriftsWhereBppHolds) {
    for (SweepPattern pattern : {SweepPattern::HangingChain, SweepPattern::Offshore}) {
        RunSpec spec = paper_run(pattern, 4.4e6, 1e-8, "pgs");
        spec.iterations = 35;
        const RunResult pgs = run_sweep(spec);
        // the cable stretches by many tolerances and the load leaves the cable's reach
        EXPECT_GT(pgs.max_joint_error, 10 * pgs.tolerance) << describe(spec, pgs);
        EXPECT_GT(pgs.worst_placement, 0.0) << describe(spec, pgs);
        EXPECT_EQ(pgs.outcome, Outcome::Drifted) << describe(spec, pgs);

        spec.method = "bpp";
        const RunResult bpp = run_sweep(spec);
        expect_physics_held(spec, bpp);
    }
}

// ---- failure modes specific to BPP, each in a scene

/// murty_after larger than any pivot budget: Murty's pivot is never taken.
constexpr int kNeverMurty = 1 << 20;

// Cycling: Júdice-Pires block pivots that stop reducing the infeasible rows and revisit index
// sets. In the sliding pair at large mass ratios and stiff CFM the two friction contacts, coupled
// through the light box, make the block steps cycle: with Murty's pivot never taken (and the
// rescue continuation off) islands run out of pivot budget and go to ODE's Dantzig. Which of
// these points cycles depends on rounding (the ordering, the factor path), so the test asks that
// some do, and that Murty's single pivot, forced at the first non-improving step
// (murty_after = 0), ends every cycle at each of them: Murty's finite method alone.
RunSpec cycling_run(int murty_after, double ratio, double cfm) {
    RunSpec spec = paper_run(SweepPattern::SlidingPair, ratio, 0, "bpp");
    spec.cfm = cfm;
    spec.seconds = 3;
    spec.options.tuning.murty_after = murty_after;
    spec.options.tuning.small_island_murty_after = murty_after;  // the pair's islands are small
    spec.options.tuning.rescue_after = 0;
    return spec;
}

TEST(BppFailureModes, BlockPivotsCycleWithoutMurtyAndMurtyEndsEveryCycle) {
    int cycling = 0;
    // Measured: with the hook reusing each island's ordering, the pure block steps cycle at CFM
    // 1e-12 (where Cholesky also needs its regularized retry); at 1e4:1 and CFM 1e-12 Murty's
    // pivot alone then needs more than the 100-step budget on one island (ODE's Dantzig answers).
    for (double ratio : {1e6, 4.4e6})
        for (double cfm : {1e-10, 1e-12}) {
            const RunSpec pure = cycling_run(kNeverMurty, ratio, cfm);
            const RunResult without = run_sweep(pure);
            EXPECT_EQ(without.murty_pivots, 0) << describe(pure, without);
            if (without.max_iterations == 0) continue;
            ++cycling;
            const RunSpec spec = cycling_run(0, ratio, cfm);
            const RunResult r = run_sweep(spec);
            EXPECT_GT(r.murty_pivots, 0) << describe(spec, r);
            EXPECT_EQ(r.rescues, 0) << describe(spec, r);
            EXPECT_EQ(r.failures + r.max_iterations + r.not_spd, 0) << describe(spec, r);
            expect_physics_held(spec, r);
            expect_friction_stops_the_pair(spec, r);
        }
    EXPECT_GT(cycling, 0) << "no sliding pair cycles without Murty any more: the test proves nothing";
}

// Not SPD: at CFM 0 the three redundant hinge rows of each closed parallelogram cell make A
// singular; bpp's documented answer is a regularized solve (A + delta I, fallback
// "regularized") or, past that, ODE's Dantzig. Either way the ladder keeps hanging.
TEST(BppFailureModes, NotSpdAtCfmZeroWithRedundantJoints) {
    RunSpec spec = paper_run(SweepPattern::Ladder, 1e4, 0, "bpp");
    spec.cfm = 0;
    const RunResult r = run_sweep(spec);
    EXPECT_GT(r.regularized + r.not_spd, 0) << describe(spec, r);
    EXPECT_EQ(r.outcome, Outcome::SolverError) << describe(spec, r);  // listed, not hidden
    expect_physics_held(spec, r);
}

// Oscillating friction coupling: consistent bounds (|x_t| <= mu x_n at the answer) are found by
// damped outer rounds, and in the sliding pair each round's friction changes the normals it
// depends on. The status is documented either way (Converged, or FrictionNotConsistent when the
// rounds run out); the pair must still stop where friction stops it.
TEST(BppFailureModes, OscillatingFrictionCouplingInConsistentMode) {
    // Not 4.4e6: there a relative error e of the top friction impulse (within the solver's
    // tolerance) changes the light box's deceleration by e r mu g, so whether the heavy box slips
    // on it is decided by round-off (Frozen and Consistent alike), not by the friction model.
    for (double ratio : {1.0, 1e4}) {
        RunSpec spec = paper_run(SweepPattern::SlidingPair, ratio, 1e-10, "bpp");
        spec.options.friction = FrictionMode::Consistent;
        spec.seconds = 2;
        const RunResult r = run_sweep(spec);
        // every answer is inside the friction cone, or says it is not (FrictionNotConsistent)
        EXPECT_EQ(r.friction_unflagged, 0) << describe(spec, r);
        EXPECT_EQ(r.failures, 0) << describe(spec, r);
        expect_physics_held(spec, r);
        expect_friction_stops_the_pair(spec, r);
    }
}

}  // namespace
}  // namespace ode_bpp::scenes
