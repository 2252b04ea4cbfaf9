// DART's Dantzig and PGS through the adapters, against brute-force and ODE's own Dantzig.
#include <gtest/gtest.h>

#include "dart_peers.h"
#include "ode_bpp/solver.h"
#include "peer_test_support.h"
#include "problems/generators.h"
#include "problems/oracle.h"

namespace {

using ode_bpp::bench::PeerStatus;
using ode_bpp::peers::testing::agrees;
using ode_bpp::peers::testing::odes_dantzig_answer;
namespace problems = ode_bpp::problems;

std::vector<double> dart_answer(const problems::OwnedProblem& p, PeerStatus expected, int sweeps = 0) {
    std::vector<double> x(static_cast<std::size_t>(p.n), -1.0);
    const PeerStatus status = sweeps > 0 ? ode_bpp::peers::dart_pgs(p, sweeps, x.data()) : ode_bpp::peers::dart_dantzig(p, x.data());
    EXPECT_EQ(status, expected);
    return x;
}

TEST(DartPeers, DantzigMatchesEnumerationWithoutFriction) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const problems::OwnedProblem p = problems::random_boxed_mlcp(10, 2, 0, 1e2, seed);
        const auto oracle = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
        ASSERT_TRUE(oracle.has_value());
        EXPECT_TRUE(agrees(dart_answer(p, PeerStatus::Solved), *oracle, 1e-9)) << "seed " << seed;
    }
}

TEST(DartPeers, DantzigMatchesOdesDantzigWithFriction) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        const problems::OwnedProblem p = problems::random_boxed_mlcp(12, 1, 3, 1e2, seed);
        ode_bpp::Status status;
        const std::vector<double> ode = odes_dantzig_answer(p, &status);
        ASSERT_EQ(status, ode_bpp::Status::Converged);
        EXPECT_TRUE(agrees(dart_answer(p, PeerStatus::Solved), ode, 1e-9)) << "seed " << seed;
    }
}

TEST(DartPeers, PgsApproachesEnumerationOnAWellConditionedProblem) {
    const problems::OwnedProblem p = problems::random_boxed_mlcp(10, 0, 0, 4.0, 7);
    const auto oracle = problems::enumerate_boxed_lcp(p, p.lo, p.hi);
    ASSERT_TRUE(oracle.has_value());
    EXPECT_FALSE(agrees(dart_answer(p, PeerStatus::Iterated, 1), *oracle, 1e-6));  // one sweep is not enough
    EXPECT_TRUE(agrees(dart_answer(p, PeerStatus::Iterated, 3000), *oracle, 1e-6));
}

}  // namespace
