// Projected Gauss-Seidel on an island's sparse form without forming A (ode/jacobian_pgs.h), against
// the same sweeps on the assembled A (baselines/pgs.h), its bound on A's entries, and its refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "baselines/pgs.h"
#include "ode/assemble.h"
#include "ode/island_view.h"
#include "ode/jacobian_pgs.h"
#include "test_ode_support.h"

namespace ode_bpp::ode {
namespace {

/// What the hook found past the limit, as the sweeps' message reports it.
const Oversize kPastA{Oversize::Measure::MatrixEntries, 123};

/// A star of `spokes` bodies around body 0 plus a joint of body 0 to the environment, each joint
/// of `rows` rows; J random, J M^-1 = J M^-1 with a positive diagonal M^-1 per body (so A is
/// positive definite), cfm 1e-3; a contact-like box problem: the first row of every joint a
/// normal (lo 0), the second its friction row (mu 0.5, findex to the normal), the rest unbounded
/// in value (lo -inf, hi +inf).
struct Star : test::SparseIsland {
    Star(int spokes, int rows, unsigned seed) {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> value(-1.0, 1.0);
        const int nj = spokes + 1;
        for (int k = 0; k < nj; ++k) {
            dMLCPJoint joint{};
            joint.row = k * rows;
            joint.m = rows;
            joint.body[0] = k == 0 ? 0 : k;
            joint.body[1] = k == 0 ? -1 : 0;
            joints.push_back(joint);
        }
        p.m = nj * rows;
        p.nb = spokes + 1;
        std::vector<double> inverse_mass(static_cast<std::size_t>(p.nb) * 6);
        for (double& v : inverse_mass) v = 0.5 + std::abs(value(rng));
        J.resize(2 * static_cast<std::size_t>(p.m) * dMLCP_J_ROW);
        JinvM.assign(2 * static_cast<std::size_t>(p.m) * dMLCP_JINVM_ROW, 0.0);
        for (const dMLCPJoint& joint : joints)
            for (int side = 0; side < 2; ++side)
                for (int r = 0; r < joint.m; ++r) {
                    const std::size_t index = 2 * joint.row + side * joint.m + r;
                    const int body = joint.body[side];
                    for (int k = 0; k < dMLCP_J_ROW; ++k) {
                        const double j = body < 0 ? 0.0 : value(rng);
                        J[index * dMLCP_J_ROW + k] = j;
                        JinvM[index * dMLCP_JINVM_ROW + (k < 3 ? k : k + 1)] =
                            body < 0 ? 0.0 : j * inverse_mass[static_cast<std::size_t>(body) * 6 + k];
                    }
                }
        cfm.assign(static_cast<std::size_t>(p.m), 1e-3);
        pairsbx.assign(2 * static_cast<std::size_t>(p.m), 0.0);
        pairslh.assign(2 * static_cast<std::size_t>(p.m), 0.0);
        findex.assign(static_cast<std::size_t>(p.m), -1);
        for (int i = 0; i < p.m; ++i) {
            pairsbx[2 * i] = value(rng) * 3;
            const int r = i % rows;
            pairslh[2 * i] = r == 0 ? 0.0 : -INFINITY;
            pairslh[2 * i + 1] = r == 1 ? 0.5 : INFINITY;
            if (r == 1) findex[i] = i - 1;
        }
        point_at_arrays();
    }
};

using test::assembled;

TEST(OdeJacobianPgs, SweepsAsPgsOnTheAssembledMatrix) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
        Star star(6, 3, seed);
        Problem q = star.rows();
        const linalg::SymmetricRows A = assembled(star.p);
        q.sparse = &A;
        Options o;
        o.pgs_iterations = 40;
        std::vector<double> on_a;
        baselines::solve_pgs(q, A, o.pgs_iterations, on_a);
        JacobianPgsBuffers buffers;
        const Result r = solve_by_jacobian_pgs(star.p, star.rows(), o, kPastA, star.x(), buffers);
        EXPECT_EQ(r.status, Status::FallbackUsed) << r.message;
        EXPECT_EQ(r.fallback, Fallback::Pgs);
        EXPECT_NE(r.message.find("A would hold at least 123 entries"), std::string::npos) << r.message;
        EXPECT_EQ(r.pivoting.pivots, o.pgs_iterations);
        double largest = 0;
        for (double v : on_a) largest = std::max(largest, std::abs(v));
        ASSERT_GT(largest, 0.0);
        for (int i = 0; i < star.p.m; ++i) EXPECT_NEAR(star.x()[i], on_a[i], 1e-12 * largest) << "row " << i;
        // residuals: the natural one as on A; the scaled one against a row scale at least |A||x| + |b|
        const Residuals exact = compute_residuals(q, ConstStrided{on_a.data(), 1});
        EXPECT_NEAR(r.residuals.natural, exact.natural, 1e-12 * (1 + exact.natural));
        EXPECT_LE(r.residuals.scaled_natural, exact.scaled_natural * (1 + 1e-12));
        // the same sweeps where the factor, not A, passed the limit: only the message differs
        const Oversize past_factor{Oversize::Measure::FactorEntries, 456};
        EXPECT_NE(solve_by_jacobian_pgs(star.p, star.rows(), o, past_factor, star.x(), buffers)
                      .message.find("the Cholesky factor would hold 456 entries"),
                  std::string::npos);
    }
}

TEST(OdeJacobianPgs, BoundsTheAssembledEntriesFromBelow) {
    for (int spokes : {1, 3, 12}) {
        Star star(spokes, 3, 9);
        const linalg::SymmetricRows A = assembled(star.p);
        const std::int64_t lower_entries = A.off_diagonal_entries() / 2 + A.n();
        std::vector<std::int64_t> scratch;
        const std::int64_t bound = coupled_entries_lower_bound(star.p, scratch);
        EXPECT_LE(bound, lower_entries) << spokes;
        EXPECT_GE(2 * bound + 2 * A.n(), lower_entries) << spokes;  // at most a factor 2 off
    }
}

TEST(OdeJacobianPgs, RefusesBadStructureNonFiniteInputAndANonPositiveDiagonalByName) {
    JacobianPgsBuffers buffers;
    const Options o;
    {
        Star star(4, 3, 3);
        star.J[5 * dMLCP_J_ROW + 2] = NAN;  // row 2's side for body[1] = -1 (joint 0): never read
        star.JinvM[6 * dMLCP_JINVM_ROW + 1] = NAN;  // row 3's side for body[0] (joint 1)
        for (int i = 0; i < star.p.m; ++i) star.x()[i] = 7;
        const Result r = solve_by_jacobian_pgs(star.p, star.rows(), o, kPastA, star.x(), buffers);
        EXPECT_EQ(r.status, Status::InvalidInput);
        EXPECT_NE(r.message.find("row 3"), std::string::npos) << r.message;
        for (int i = 0; i < star.p.m; ++i) EXPECT_EQ(star.x()[i], 0.0) << i;
    }
    {
        Star star(4, 3, 4);
        star.cfm[4] = 0;
        for (int side = 0; side < 2; ++side) {  // row 4: joint 1's second row, both sides
            const std::size_t index = 2 * 3 + side * 3 + 1;
            std::fill_n(star.J.begin() + static_cast<std::ptrdiff_t>(index * dMLCP_J_ROW), dMLCP_J_ROW, 0.0);
        }
        const Result r = solve_by_jacobian_pgs(star.p, star.rows(), o, kPastA, star.x(), buffers);
        EXPECT_EQ(r.status, Status::InvalidInput);
        EXPECT_NE(r.message.find("A(4,4)"), std::string::npos) << r.message;
    }
    {
        Star star(4, 3, 5);
        star.joints[2].body[1] = star.p.nb;  // one past the island's bodies
        const Result r = solve_by_jacobian_pgs(star.p, star.rows(), o, kPastA, star.x(), buffers);
        EXPECT_EQ(r.status, Status::InvalidInput);
        EXPECT_NE(r.message.find("joint 2"), std::string::npos) << r.message;
    }
    {
        Star star(4, 3, 6);
        star.joints[1].row += 1;  // a gap before joint 1, and joint 4 past the last row
        const Result r = solve_by_jacobian_pgs(star.p, star.rows(), o, kPastA, star.x(), buffers);
        EXPECT_EQ(r.status, Status::InvalidInput);
        EXPECT_NE(r.message.find("joint 1"), std::string::npos) << r.message;
        star.joints[1].row -= 1;
        star.p.m -= 1;  // the joints run one row past m
        const Result past = solve_by_jacobian_pgs(star.p, star.rows(), o, kPastA, star.x(), buffers);
        EXPECT_EQ(past.status, Status::InvalidInput);
        EXPECT_NE(past.message.find("not at m"), std::string::npos) << past.message;
    }
}

}  // namespace
}  // namespace ode_bpp::ode
