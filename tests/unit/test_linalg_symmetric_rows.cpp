// Compressed symmetric rows stored in another order (linalg/symmetric_rows.h): the world step
// assembles A straight into the solver's order (ode/island_view.h), and every reader of
// Problem::sparse must see the same matrix as in the problem's own order.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "linalg/symmetric_rows.h"
#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "problems/generators.h"

namespace ode_bpp::linalg {
namespace {

/// A's diagonal and strictly lower entries, row by row with increasing columns.
void lower_of(const SymmetricRows& A, std::vector<double>& diagonal, std::vector<LowerEntry>& lower) {
    diagonal.clear();
    lower.clear();
    for (int i = 0; i < A.n(); ++i) {
        diagonal.push_back(A.diag(i));
        for (int k = A.row_begin(i); k < A.row_end(i); ++k)
            if (A.col(k) < i) lower.push_back({i, A.col(k), A.val(k)});
    }
}

std::vector<int> shuffled(int n, unsigned seed) {
    std::vector<int> perm(static_cast<std::size_t>(n));
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), std::mt19937(seed));
    return perm;
}

void expect_same_rows(const SymmetricRows& a, const SymmetricRows& b) {
    ASSERT_EQ(a.n(), b.n());
    for (int i = 0; i < a.n(); ++i) {
        EXPECT_EQ(a.diag(i), b.diag(i)) << "row " << i;
        ASSERT_EQ(a.row_end(i) - a.row_begin(i), b.row_end(i) - b.row_begin(i)) << "row " << i;
        for (int k = 0; k < a.row_end(i) - a.row_begin(i); ++k) {
            EXPECT_EQ(a.col(a.row_begin(i) + k), b.col(b.row_begin(i) + k)) << "row " << i;
            EXPECT_EQ(a.val(a.row_begin(i) + k), b.val(b.row_begin(i) + k)) << "row " << i;
        }
    }
}

// A dense problem's A read into rows (SymmetricRows::assign): the non-zeros, and with blocks that
// tile the rows also every entry of two blocks that share a body (the joints' structural
// pattern, zeros included), each row in increasing column. Long zero runs, zeros of either sign
// and a NaN against the rule written out pair by pair.
TEST(SymmetricRows, DenseAssignKeepsTheNonZerosAndTheCoupledBlocks) {
    const int sizes[] = {3, 1, 4, 2, 6, 3, 5, 9, 2};
    std::vector<int> block_row{0};
    for (int s : sizes) block_row.push_back(block_row.back() + s);
    const int n = block_row.back(), blocks = static_cast<int>(block_row.size()) - 1;
    // bodies 0..5, -1 the static environment; blocks 2 and 7 touch nothing but the environment
    const std::vector<int> block_body{0, 1, 1, -1, -1, -1, 2, 3, 0, 2, 4, -1, 5, 4, -1, -1, 3, 5};
    std::vector<int> block_of;
    for (int q = 0; q < blocks; ++q) block_of.insert(block_of.end(), sizes[q], q);
    const auto coupled = [&](int p, int q) {
        if (p == q) return true;
        for (int a : {block_body[2 * p], block_body[2 * p + 1]})
            for (int b : {block_body[2 * q], block_body[2 * q + 1]})
                if (a >= 0 && a == b) return true;
        return false;
    };
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<double> a(static_cast<std::size_t>(n) * n, 0.0);
    for (int i = 0; i < n; ++i) {
        a[i * n + i] = 10;
        for (int j = 0; j < i; ++j) {
            const double r = u(rng);
            a[i * n + j] = r < 0.15 ? r - 0.5 : r < 0.25 ? -0.0 : 0.0;
        }
    }
    a[20 * n + 3] = std::numeric_limits<double>::quiet_NaN();
    for (const bool with_blocks : {false, true}) {
        Problem p;
        p.n = n;
        p.A = a.data();
        p.lda = n;
        if (with_blocks) {
            p.num_blocks = blocks;
            p.block_row = block_row.data();
            p.block_body = block_body.data();
        }
        const SymmetricRows rows(p, {});
        for (int i = 0; i < n; ++i) {
            std::vector<int> expected;
            for (int j = 0; j < n; ++j) {
                const double v = i > j ? a[i * n + j] : a[j * n + i];
                if (j != i && (v != 0 || (with_blocks && coupled(block_of[i], block_of[j])))) expected.push_back(j);
            }
            std::vector<int> stored;
            for (int k = rows.row_begin(i); k < rows.row_end(i); ++k) stored.push_back(rows.col(k));
            EXPECT_EQ(stored, expected) << "row " << i << (with_blocks ? " with blocks" : "");
        }
    }
}

TEST(SymmetricRows, OrderedAssemblyIsThePermutedMatrixEntryForEntry) {
    const auto owned = problems::chain_mlcp(30, 20);
    const SymmetricRows A(owned.view(), {});
    std::vector<double> diagonal;
    std::vector<LowerEntry> lower;
    lower_of(A, diagonal, lower);
    for (unsigned seed : {1u, 2u, 3u}) {
        const std::vector<int> perm = shuffled(A.n(), seed);
        SymmetricRows ordered;
        ordered.assign_lower(diagonal, lower, perm);
        EXPECT_EQ(ordered.order(), perm);
        expect_same_rows(ordered, A.permuted(perm));  // same entries in the same order in each row
        EXPECT_EQ(ordered.row_profile(), A.permuted(perm).row_profile());  // found while counting
        SymmetricRows scratch;
        expect_same_rows(ordered.in_built_order(scratch), A);
        EXPECT_TRUE(ordered.in_built_order(scratch).order().empty());
    }
}

/// first[i] = min({i} U {stored j < i}), read off the rows.
std::vector<int> profile_read_off(const SymmetricRows& A) {
    std::vector<int> first(static_cast<std::size_t>(A.n()));
    for (int i = 0; i < A.n(); ++i) {
        first[i] = i;
        for (int k = A.row_begin(i); k < A.row_end(i); ++k) first[i] = std::min(first[i], A.col(k));
    }
    return first;
}

TEST(SymmetricRows, ProfileFoundWhileCountingIsTheOneReadOffTheRows) {
    const auto owned = problems::chain_mlcp(30, 20);
    const SymmetricRows A(owned.view(), {});  // the unordered assign_lower
    EXPECT_EQ(A.row_profile(), profile_read_off(A));
    const SymmetricRows reordered(owned.view(), shuffled(A.n(), 7));
    EXPECT_EQ(reordered.row_profile(), profile_read_off(reordered));
    const SymmetricRows permuted = A.permuted(shuffled(A.n(), 8));  // permute_into: read off
    EXPECT_EQ(permuted.row_profile(), profile_read_off(permuted));
}

// Rows moved last in groups (the ordering choice's candidates that move a contact's rows last):
// the profile read off the unmoved rows' own profile is the permuted matrix's, whatever the
// groups and the order the matrix is stored in.
TEST(SymmetricRows, ProfileWithRowsMovedLastIsThePermutedOnesFromTheMovedRowsAlone) {
    const auto owned = problems::chain_mlcp(30, 20);
    std::mt19937 rng(3);
    for (const SymmetricRows& A : {SymmetricRows(owned.view(), {}), SymmetricRows(owned.view(), shuffled(owned.n, 9))}) {
        const std::vector<int> first = A.row_profile();
        for (int trial = 0; trial < 20; ++trial) {
            std::vector<unsigned char> rank(A.n());
            for (auto& r : rank) r = static_cast<unsigned char>(rng() % 5 == 0 ? 1 + rng() % 2 : 0);
            std::vector<int> perm(A.n());
            std::iota(perm.begin(), perm.end(), 0);
            std::stable_sort(perm.begin(), perm.end(), [&](int a, int b) { return rank[a] < rank[b]; });
            EXPECT_EQ(A.row_profile_ranked(perm, rank, first), A.row_profile_under(perm)) << "trial " << trial;
        }
    }
}

TEST(SymmetricRows, PermutingCarriesTheOrderAndUndoingItGivesTheIdentity) {
    const auto owned = problems::chain_mlcp(10, 6);
    const SymmetricRows A(owned.view(), {});
    const std::vector<int> first = shuffled(A.n(), 4), second = shuffled(A.n(), 5);
    const SymmetricRows once = A.permuted(first);
    const SymmetricRows twice = once.permuted(second);
    for (int i = 0; i < A.n(); ++i) EXPECT_EQ(twice.built_row(i), first[second[i]]);
    EXPECT_TRUE(once.permuted(inverse_permutation(first)).order().empty());
    std::vector<double> dense_a(static_cast<std::size_t>(A.n()) * A.n(), 0.0), dense_b = dense_a;
    A.to_dense_lower(dense_a.data(), A.n());
    twice.to_dense_lower(dense_b.data(), A.n());
    EXPECT_EQ(dense_a, dense_b);  // in the order the matrix was built in
}

TEST(SymmetricRows, AProblemWhoseRowsComeInTheSolversOrderGetsTheSameAnswer) {
    const auto owned = problems::chain_mlcp(40, 20);
    Problem p = owned.view();
    const SymmetricRows A(p, {});
    p.A = nullptr;
    p.sparse = &A;
    std::vector<double> x(static_cast<std::size_t>(p.n));
    const Result plain = solve(p, Options{}, x.data());
    ASSERT_EQ(plain.status, Status::Converged);
    ASSERT_FALSE(plain.ordering.empty());
    std::vector<double> diagonal;
    std::vector<LowerEntry> lower;
    lower_of(A, diagonal, lower);
    for (const std::vector<int>& stored : {plain.ordering, shuffled(p.n, 6)}) {
        SymmetricRows ordered;
        ordered.assign_lower(diagonal, lower, stored);
        Problem q = p;
        q.sparse = &ordered;
        Start start;
        start.ordering = plain.ordering;
        std::vector<double> y(static_cast<std::size_t>(p.n));
        const Result r = solve(q, Options{}, y.data(), start);
        EXPECT_EQ(r.status, plain.status);
        EXPECT_EQ(r.pivoting.pivots, plain.pivoting.pivots);
        EXPECT_EQ(y, x);
        EXPECT_EQ(r.residuals.natural, plain.residuals.natural);
        EXPECT_EQ(r.residuals.scaled_natural, plain.residuals.scaled_natural);
        const Residuals stored_order = compute_residuals(q, ConstStrided{x.data(), 1});
        const Residuals own_order = compute_residuals(p, ConstStrided{x.data(), 1});
        EXPECT_EQ(stored_order.natural, own_order.natural);
        EXPECT_EQ(stored_order.scaled_fixed_bound, own_order.scaled_fixed_bound);
        EXPECT_EQ(stored_order.free, own_order.free);
    }
}

}  // namespace
}  // namespace ode_bpp::linalg
