// Siconos' relay Lemke and PGS through the adapters, against brute-force enumeration.
#include <gtest/gtest.h>

#include "peer_test_support.h"
#include "problems/generators.h"
#include "problems/oracle.h"
#include "siconos_peers.h"

namespace {

using ode_bpp::bench::PeerStatus;
using ode_bpp::peers::testing::agrees;
namespace problems = ode_bpp::problems;
constexpr int kNoLimit = 1000;

std::vector<double> lemke_answer(const problems::OwnedProblem& p, PeerStatus expected) {
    std::vector<double> x(static_cast<std::size_t>(p.n), -1.0);
    EXPECT_EQ(ode_bpp::peers::siconos_lemke(p, kNoLimit, x.data()), expected);
    return x;
}

TEST(SiconosPeers, LemkeMatchesEnumerationWithoutFriction) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const problems::OwnedProblem p = problems::random_boxed_mlcp(10, 2, 0, 1e2, seed);
        const auto oracle = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
        ASSERT_TRUE(oracle.has_value());
        EXPECT_TRUE(agrees(lemke_answer(p, PeerStatus::Solved), *oracle, 1e-7)) << "seed " << seed;
    }
}

TEST(SiconosPeers, LemkeFreezesFrictionLikeTheEnumeration) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const problems::OwnedProblem p = problems::random_boxed_mlcp(12, 1, 3, 1e2, seed);
        const auto oracle = problems::enumerate_frozen_friction(p);
        ASSERT_TRUE(oracle.has_value());
        EXPECT_TRUE(agrees(lemke_answer(p, PeerStatus::Solved), *oracle, 1e-7)) << "seed " << seed;
    }
}

TEST(SiconosPeers, PgsApproachesEnumerationOnAWellConditionedProblem) {
    const problems::OwnedProblem p = problems::random_boxed_mlcp(10, 0, 0, 4.0, 7);
    const auto oracle = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
    ASSERT_TRUE(oracle.has_value());
    for (const auto& [sweeps, close] : {std::pair{1, false}, std::pair{3000, true}}) {
        std::vector<double> x(static_cast<std::size_t>(p.n), -1.0);
        EXPECT_EQ(ode_bpp::peers::siconos_pgs(p, sweeps, x.data()), PeerStatus::Iterated);
        EXPECT_EQ(static_cast<bool>(agrees(x, *oracle, 1e-6)), close) << sweeps << " sweeps";
    }
}

}  // namespace
