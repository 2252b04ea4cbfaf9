// Eq. 6's right-hand side from the tight columns only (pivoting/iterate.h): the pivoting loop's
// decisions must not change with it, so it must equal the full product bit for bit on the free
// rows, for A in its built order and in a solver's order (permuted, or assembled in that order);
// off_diagonal_product, the same over every non-zero column, gives the same vector.
#include <gtest/gtest.h>

#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include "linalg/symmetric_rows.h"
#include "pivoting/friction_set.h"
#include "pivoting/iterate.h"
#include "problems/generators.h"

namespace ode_bpp::pivoting {
namespace {

using linalg::LowerEntry;
using linalg::SymmetricRows;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// For several random index sets: x_T at random values (some exactly 0), x_F = 0; the product
/// over the tight columns must be A->multiply's on every free row, to the bit.
void expect_full_product_on_free_rows(const SymmetricRows& A, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> value(-3.0, 3.0);
    std::vector<char> tight(static_cast<std::size_t>(A.n()));
    std::vector<double> x(tight.size()), full, y;
    std::vector<int> scratch;
    for (int trial = 0; trial < 20; ++trial) {
        int free_rows = 0, used_columns = 0;
        for (int i = 0; i < A.n(); ++i) {
            tight[i] = rng() % 2;
            x[i] = tight[i] && rng() % 4 != 0 ? value(rng) : 0.0;
            free_rows += !tight[i];
            used_columns += x[i] != 0;
        }
        ASSERT_GT(free_rows, 0);
        ASSERT_GT(used_columns, 0);
        A.multiply(x, /*shift=*/1e-3, full);
        tight_columns_product(A, tight, x, scratch, y);
        for (int i = 0; i < A.n(); ++i) {
            if (tight[i]) continue;
            EXPECT_TRUE(same_bits(full[i], y[i])) << "row " << i << ": " << full[i] << " vs " << y[i];
        }
        // off_diagonal_product is the same product over every non-zero column (x is 0 on F):
        // the same vector on every row, to the bit
        std::vector<double> off;
        off_diagonal_product(A, x, scratch, off);
        for (int i = 0; i < A.n(); ++i)
            EXPECT_TRUE(same_bits(off[i], y[i])) << "row " << i << ": " << off[i] << " vs " << y[i];
    }
}

TEST(TightColumnsProduct, IsTheFullProductOnTheFreeRowsBitForBit) {
    const auto owned = problems::chain_mlcp(40, 30);
    const SymmetricRows built(owned.view(), {});
    expect_full_product_on_free_rows(built, 1);

    std::vector<int> order(static_cast<std::size_t>(built.n()));
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    expect_full_product_on_free_rows(built.permuted(order), 2);

    std::vector<double> diagonal;
    std::vector<LowerEntry> lower;
    for (int i = 0; i < built.n(); ++i) {
        diagonal.push_back(built.diag(i));
        for (int k = built.row_begin(i); k < built.row_end(i); ++k)
            if (built.col(k) < i) lower.push_back({i, built.col(k), built.val(k)});
    }
    SymmetricRows assembled;
    assembled.assign_lower(diagonal, lower, order);
    expect_full_product_on_free_rows(assembled, 3);
    std::shuffle(order.begin(), order.end(), std::mt19937(11));
    expect_full_product_on_free_rows(assembled.permuted(order), 4);
}

// The pivoting loop's later steps refresh w and the scales on the rows that can be tight only
// (refresh_bounded_residual); completing them must give the full refresh's vectors to the bit,
// or the answer's residuals would depend on how many steps it took.
TEST(BoundedResidual, CompletedItIsTheFullRefreshBitForBit) {
    const auto owned = problems::chain_mlcp(30, 12);  // joint rows (unbounded) and contacts
    const Problem p = owned.view();
    const SymmetricRows A(p, {});
    std::vector<int> identity(static_cast<std::size_t>(A.n()));
    std::iota(identity.begin(), identity.end(), 0);
    BoxedLcp lcp;
    FrictionSet friction;
    build_boxed_lcp(p, A, identity, lcp, friction);
    lcp.shift = 1e-6;
    int always_free = 0;
    for (char f : lcp.always_free) always_free += f;
    ASSERT_GT(always_free, 0);
    ASSERT_LT(always_free, A.n());

    std::mt19937 rng(5);
    std::uniform_real_distribution<double> value(-2.0, 2.0);
    std::vector<double> x(static_cast<std::size_t>(A.n()));
    for (double& v : x) v = value(rng);
    Iterate full, partial;
    refresh_residual(lcp, x, full);
    EXPECT_TRUE(full.complete);
    partial.w.assign(x.size(), 12345.0);  // stale values from an earlier iterate
    partial.scale.assign(x.size(), 12345.0);
    refresh_bounded_residual(lcp, x, partial);
    EXPECT_FALSE(partial.complete);
    for (int i = 0; i < A.n(); ++i) {
        if (lcp.always_free[i]) {
            EXPECT_EQ(partial.w[i], 12345.0) << "row " << i << " is never read before completion";
        } else {
            EXPECT_TRUE(same_bits(partial.w[i], full.w[i])) << "row " << i;
            EXPECT_TRUE(same_bits(partial.scale[i], full.scale[i])) << "row " << i;
        }
    }
    complete_residual(lcp, x, partial);
    EXPECT_TRUE(partial.complete);
    for (int i = 0; i < A.n(); ++i) {
        EXPECT_TRUE(same_bits(partial.w[i], full.w[i])) << "row " << i;
        EXPECT_TRUE(same_bits(partial.scale[i], full.scale[i])) << "row " << i;
    }
}

}  // namespace
}  // namespace ode_bpp::pivoting
