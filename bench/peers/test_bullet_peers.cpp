// Bullet's Dantzig, Lemke and PGS through the adapters, against brute-force and ODE's own Dantzig.
#include <gtest/gtest.h>

#include "bullet_peers.h"
#include "ode_bpp/solver.h"
#include "peer_test_support.h"
#include "problems/generators.h"
#include "problems/oracle.h"

namespace {

using ode_bpp::bench::PeerStatus;
using ode_bpp::peers::testing::agrees;
using ode_bpp::peers::testing::odes_dantzig_answer;
namespace problems = ode_bpp::problems;
constexpr int kNoLimit = 1000;

std::vector<double> answer_of(PeerStatus (*solver)(const ode_bpp::Problem&, double*), const problems::OwnedProblem& p) {
    std::vector<double> x(static_cast<std::size_t>(p.n), -1.0);
    EXPECT_EQ(solver(p, x.data()), PeerStatus::Solved);
    return x;
}

std::vector<double> lemke_answer(const problems::OwnedProblem& p, int max_rows, PeerStatus expected) {
    std::vector<double> x(static_cast<std::size_t>(p.n), -1.0);
    EXPECT_EQ(ode_bpp::peers::bullet_lemke(p, max_rows, x.data()), expected);
    return x;
}

TEST(BulletPeers, DantzigAndLemkeMatchEnumerationWithoutFriction) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const problems::OwnedProblem p = problems::random_boxed_mlcp(10, 2, 0, 1e2, seed);
        const auto oracle = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
        ASSERT_TRUE(oracle.has_value());
        EXPECT_TRUE(agrees(answer_of(ode_bpp::peers::bullet_dantzig, p), *oracle, 1e-9)) << "seed " << seed;
        EXPECT_TRUE(agrees(lemke_answer(p, kNoLimit, PeerStatus::Solved), *oracle, 1e-7)) << "seed " << seed;
    }
}

TEST(BulletPeers, DantzigMatchesOdesDantzigWithFriction) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const problems::OwnedProblem p = problems::random_boxed_mlcp(12, 1, 3, 1e2, seed);
        ode_bpp::Status status;
        const std::vector<double> ode = odes_dantzig_answer(p, &status);
        ASSERT_EQ(status, ode_bpp::Status::Converged);
        EXPECT_TRUE(agrees(answer_of(ode_bpp::peers::bullet_dantzig, p), ode, 1e-9)) << "seed " << seed;
    }
}

TEST(BulletPeers, LemkeFreezesFrictionLikeTheEnumeration) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const problems::OwnedProblem p = problems::random_boxed_mlcp(12, 1, 3, 1e2, seed);
        const auto oracle = problems::enumerate_frozen_friction(p);
        ASSERT_TRUE(oracle.has_value());
        EXPECT_TRUE(agrees(lemke_answer(p, kNoLimit, PeerStatus::Solved), *oracle, 1e-7)) << "seed " << seed;
    }
}

TEST(BulletPeers, LemkeSkipsIslandsAboveItsLimit) {
    const problems::OwnedProblem p = problems::random_boxed_mlcp(10, 2, 0, 1e2, 3);
    EXPECT_EQ(lemke_answer(p, 9, PeerStatus::Skipped), std::vector<double>(10, 0.0));
}

TEST(BulletPeers, PgsApproachesEnumerationOnAWellConditionedProblem) {
    const problems::OwnedProblem p = problems::random_boxed_mlcp(10, 0, 0, 4.0, 7);
    const auto oracle = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
    ASSERT_TRUE(oracle.has_value());
    for (const auto& [sweeps, close] : {std::pair{1, false}, std::pair{3000, true}}) {
        std::vector<double> x(static_cast<std::size_t>(p.n), -1.0);
        EXPECT_EQ(ode_bpp::peers::bullet_pgs(p, sweeps, x.data()), PeerStatus::Iterated);
        EXPECT_EQ(static_cast<bool>(agrees(x, *oracle, 1e-6)), close) << sweeps << " sweeps";
    }
}

}  // namespace
