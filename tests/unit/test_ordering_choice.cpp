// Which ordering each BPP method factors in (ordering/ordering_choice.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "linalg/cost_model.h"
#include "linalg/envelope.h"
#include "linalg/skyline.h"
#include "ordering/order_rows.h"
#include "ordering/ordering_choice.h"
#include "ode_bpp/io.h"
#include "problems/generators.h"
#include "test_io_support.h"

namespace ode_bpp::ordering {
namespace {

std::ptrdiff_t envelope(const linalg::SymmetricRows& A, const std::vector<int>& perm) {
    return linalg::envelope_size(A.row_profile_under(perm));
}

std::vector<int> order(const Problem& p, ordering::OrderingKind kind, const std::vector<char>* tight = nullptr) {
    return ordering::order_rows(p.n, p.A, p.lda, p.num_blocks, p.block_row, p.block_body, kind, tight);
}

TEST(PivotingOrdering, PaperBaselinesKeepTheCallersOrder) {
    const auto owned = problems::chain_mlcp(20, 10);
    const Problem p = owned.view();
    const linalg::SymmetricRows A(p, {});
    for (Method m : {Method::BppChol, Method::BppDown}) {
        const std::vector<int> perm = choose_ordering(m, p, A, {});
        for (int i = 0; i < p.n; ++i) EXPECT_EQ(perm[i], i);
    }
}

TEST(PivotingOrdering, SkylineVariantsShrinkTheEnvelopeOfAnIslandWithContactsLast) {
    const auto owned = problems::chain_mlcp(40, 20);
    const Problem p = owned.view();
    const linalg::SymmetricRows A(p, {});
    const std::vector<int> identity = choose_ordering(Method::BppChol, p, A, {});
    const std::vector<int> sky = choose_ordering(Method::BppSky, p, A, {});
    const std::vector<int> ours = choose_ordering(Method::Bpp, p, A, {});
    ASSERT_TRUE(ordering::is_permutation(sky, p.n));
    ASSERT_TRUE(ordering::is_permutation(ours, p.n));
    EXPECT_EQ(sky, order(p, ordering::OrderingKind::CuthillMcKee));
    EXPECT_LT(envelope(A, sky), envelope(A, identity) / 2);
    const std::ptrdiff_t best = std::min(envelope(A, order(p, ordering::OrderingKind::CuthillMcKee)),
                                         envelope(A, order(p, ordering::OrderingKind::ReverseCuthillMcKee)));
    EXPECT_EQ(envelope(A, ours), best);
}

TEST(PivotingOrdering, WarmStartChoiceIsNeverPricedAboveTheCandidates) {
    const auto owned = problems::chain_mlcp(60, 30);
    const Problem p = owned.view();
    const linalg::SymmetricRows A(p, {});
    for (int every : {1, 3, 10}) {  // many to few tight friction rows
        std::vector<RowState> warm(p.n, RowState::Free);
        std::vector<char> tight(p.n, 0);
        int k = 0;
        for (int i = p.nub; i < p.n; ++i)
            if (owned.findex[i] >= 0 && k++ % every == 0) {
                warm[i] = RowState::AtHi;
                tight[i] = 1;
            }
        const std::vector<int> chosen = choose_ordering(Method::Bpp, p, A, warm);
        ASSERT_TRUE(ordering::is_permutation(chosen, p.n));
        const double price = warm_solve_price(A, chosen, tight);
        for (auto kind : {ordering::OrderingKind::CuthillMcKee, ordering::OrderingKind::ReverseCuthillMcKee})
            for (const std::vector<char>* last : {static_cast<const std::vector<char>*>(nullptr),
                                                  static_cast<const std::vector<char>*>(&tight)})
                EXPECT_LE(price, warm_solve_price(A, order(p, kind, last), tight)) << "every " << every;
    }
}

/// The bound that prunes candidates before they are priced never exceeds the whole factor's
/// count, and with every row flagged it counts at least the envelope (each row's w of its
/// w (w + 1) / 2 terms are its own entries).
TEST(PivotingOrdering, FlaggedRowsBoundTheFactorFromBelow) {
    const auto owned = problems::chain_mlcp(40, 20);
    const Problem p = owned.view();
    const linalg::SymmetricRows A(p, {});
    std::mt19937 rng(7);
    for (int trial = 0; trial < 12; ++trial) {
        std::vector<int> perm = order(p, trial % 2 ? ordering::OrderingKind::CuthillMcKee
                                                   : ordering::OrderingKind::ReverseCuthillMcKee);
        if (trial >= 4) std::shuffle(perm.begin() + trial, perm.end(), rng);
        const double whole = linalg::full_refactor_cost(linalg::SkylineShape::from_row_profile(A.row_profile_under(perm)));
        std::vector<char> some(p.n, 0), all(p.n, 1);
        for (int i = 0; i < p.n; ++i) some[i] = rng() % 3 == 0;
        EXPECT_LE(flagged_rows_factor_bound(A, perm, some), flagged_rows_factor_bound(A, perm, all)) << trial;
        EXPECT_LE(flagged_rows_factor_bound(A, perm, all), whole) << trial;
        EXPECT_GE(flagged_rows_factor_bound(A, perm, all), static_cast<double>(envelope(A, perm))) << trial;
        // summed only until a limit, it stops at or past it and stays a lower bound
        const double full = flagged_rows_factor_bound(A, perm, all);
        const double limited = flagged_rows_factor_bound(A, perm, all, full / 3);
        EXPECT_GE(limited, full / 3) << trial;
        EXPECT_LT(limited, full) << trial;
    }
}

TEST(PivotingOrdering, ALongRowMovedLastIsPricedAsTheColumnsItMakesReachTheBottom) {
    // the column skyline of a row starting at column f ends at that row for every column >= f,
    // so moving one mid-chain contact row last multiplies the factor's cost; the price sees it
    const auto owned = problems::chain_mlcp(60, 30);
    const Problem p = owned.view();
    const linalg::SymmetricRows A(p, {});
    std::vector<RowState> warm(p.n, RowState::Free);
    std::vector<char> tight(p.n, 0);
    const int row = p.nub + 3 * 15 + 1;  // a friction row of a contact mid-chain
    ASSERT_GE(owned.findex[row], 0);
    warm[row] = RowState::AtLo;
    tight[row] = 1;
    const std::vector<int> moved = order(p, ordering::OrderingKind::CuthillMcKee, &tight);
    ASSERT_EQ(moved.back(), row);
    const std::vector<int> plain = order(p, ordering::OrderingKind::CuthillMcKee);
    EXPECT_GT(warm_solve_price(A, moved, tight), 10 * warm_solve_price(A, plain, tight));
    EXPECT_NE(choose_ordering(Method::Bpp, p, A, warm).back(), row);
}

/// Frozen friction's first fixed-bound solve holds every friction row at 0: the choice prices
/// that solve at the friction rows and the later ones at the warm start's, and may move the
/// friction rows last; whatever it picks is priced no higher than any candidate.
TEST(PivotingOrdering, FrozenFirstSolveChoiceIsNeverPricedAboveTheCandidates) {
    for (const auto& [links, contacts] : {std::pair{60, 30}, std::pair{40, 4}, std::pair{30, 10}}) {
        const auto owned = problems::chain_mlcp(links, contacts);
        const Problem p = owned.view();
        const linalg::SymmetricRows A(p, {});
        std::vector<char> friction(p.n, 0), none(p.n, 0);
        for (int i = 0; i < p.n; ++i) friction[i] = owned.findex[i] >= 0;
        const std::vector<int> chosen = choose_ordering(Method::Bpp, p, A, {}, FirstSolve::FrictionRowsTight);
        ASSERT_TRUE(ordering::is_permutation(chosen, p.n));
        const double price = warm_solve_price(A, chosen, none, friction);
        for (auto kind : {ordering::OrderingKind::CuthillMcKee, ordering::OrderingKind::ReverseCuthillMcKee})
            for (const std::vector<char>* last : {static_cast<const std::vector<char>*>(nullptr),
                                                  static_cast<const std::vector<char>*>(&friction)})
                EXPECT_LE(price, warm_solve_price(A, order(p, kind, last), none, friction)) << links << " links";
    }
}

/// An island too small to pay for an ordering keeps the caller's order, or that order with the
/// friction rows last (Frozen friction's first solve holds them at 0), whichever prices lower:
/// ODE lists a contact's rows together after the joints, and a short chain with many ground
/// contacts factors its joints once for both solves with the friction rows last, while a long
/// chain with few contacts pays more for the rows they make reach the bottom.
TEST(PivotingOrdering, ASmallIslandMovesItsFrictionRowsLastWhereThatPricesLower) {
    int moved_taken = 0, caller_kept = 0;
    for (const auto& [links, contacts] : {std::pair{4, 12}, std::pair{12, 4}, std::pair{3, 20}, std::pair{8, 8}}) {
        const auto owned = problems::chain_mlcp(links, contacts);
        const Problem p = owned.view();
        const linalg::SymmetricRows A(p, {});
        std::vector<char> friction(p.n, 0), none(p.n, 0);
        for (int i = 0; i < p.n; ++i) friction[i] = owned.findex[i] >= 0;
        std::vector<int> caller(p.n), moved;
        std::iota(caller.begin(), caller.end(), 0);
        moved = caller;
        move_flagged_last(moved, friction);
        const std::vector<int> chosen = choose_ordering(Method::Bpp, p, A, {}, FirstSolve::FrictionRowsTight);
        ASSERT_TRUE(chosen == caller || chosen == moved) << links << " links: too small to be numbered";
        const std::vector<int>& other = chosen == caller ? moved : caller;
        EXPECT_LE(warm_solve_price(A, chosen, none, friction), warm_solve_price(A, other, none, friction)) << links;
        moved_taken += chosen == moved;
        caller_kept += chosen == caller;
        // without the first solve's friction rows there is nothing to move
        EXPECT_EQ(choose_ordering(Method::Bpp, p, A, {}, FirstSolve::AsWarmStart), caller) << links << " links";
    }
    EXPECT_EQ(moved_taken, 2);
    EXPECT_EQ(caller_kept, 2);
}

/// p with its row blocks in the order `blocks` (each block's rows kept together and in order):
/// A, b, lo, hi and findex permuted alike, nub 0 (the unbounded rows need not lead any more).
problems::OwnedProblem with_blocks_in_order(const problems::OwnedProblem& p, const std::vector<int>& blocks) {
    std::vector<int> perm;  // perm[new] = old
    problems::OwnedProblem q = problems::OwnedProblem::zeros(p.name, p.n);
    for (int k : blocks) {
        q.block_row.push_back(static_cast<int>(perm.size()));
        q.block_body.insert(q.block_body.end(), {p.block_body[2 * k], p.block_body[2 * k + 1]});
        for (int i = p.block_row[k]; i < p.block_row[k + 1]; ++i) perm.push_back(i);
    }
    q.block_row.push_back(p.n);
    std::vector<int> to_new(p.n);
    for (int i = 0; i < p.n; ++i) to_new[perm[i]] = i;
    q.findex.assign(p.n, -1);
    for (int i = 0; i < p.n; ++i) {
        for (int j = 0; j < p.n; ++j) q.a(i, j) = p.a(perm[i], perm[j]);
        q.b[i] = p.b[perm[i]];
        q.lo[i] = p.lo[perm[i]];
        q.hi[i] = p.hi[perm[i]];
        if (p.findex[perm[i]] >= 0) q.findex[i] = to_new[p.findex[perm[i]]];
    }
    return q;
}

/// The caller's order with the friction rows last (Frozen friction's first solve holds them at
/// 0), and that order with their normals moved last just before them.
struct MovedOrders {
    std::vector<int> friction_last, normals_then_friction;
    std::vector<char> friction;
};
MovedOrders moved_orders(int n, const std::vector<int>& findex) {
    MovedOrders m;
    std::vector<char> normals(n, 0);
    m.friction.assign(n, 0);
    for (int i = 0; i < n; ++i)
        if (findex[i] >= 0) m.friction[i] = normals[findex[i]] = 1;
    m.friction_last.resize(n);
    std::iota(m.friction_last.begin(), m.friction_last.end(), 0);
    m.normals_then_friction = m.friction_last;
    move_flagged_last(m.friction_last, m.friction);
    move_flagged_last(m.normals_then_friction, normals);
    move_flagged_last(m.normals_then_friction, m.friction);
    return m;
}

/// ODE lists an island's joints as it walks its bodies, so a contact's rows may sit between two
/// joints. On parkour's islands the hull's joints make most of A one dense block, and a normal
/// left among the joints keeps its wheel's columns reaching to the friction rows at the end: the
/// island, too dense to be numbered, moves its normals last too, just before the friction rows,
/// which stay the tail Frozen friction's first solve leaves out (docs/tuning.md).
TEST(PivotingOrdering, AHullsIslandMovesTheNormalsOfItsFrictionRowsBeforeThem) {
    const ReadResult read =
        read_mlcp((io_test::data_dir() / "captured" / "parkour-hull-normals-last-185.mlcp").string());
    ASSERT_TRUE(read.ok) << read.error;
    const Problem p = read.file.view();
    const linalg::SymmetricRows A(p, {});
    ASSERT_TRUE(ordering_cannot_pay(A));
    const MovedOrders m = moved_orders(read.file.n, read.file.findex);
    ASSERT_NE(m.normals_then_friction, m.friction_last);
    const std::vector<char> none(p.n, 0);
    EXPECT_LT(warm_solve_price(A, m.normals_then_friction, none, m.friction),
              warm_solve_price(A, m.friction_last, none, m.friction));
    EXPECT_EQ(choose_ordering(Method::Bpp, p, A, {}, FirstSolve::FrictionRowsTight), m.normals_then_friction);
}

/// On a chain whose contacts sit between its joints, the normals' rows moved last would reach
/// back along the band: the choice keeps whichever of the caller's orders prices lowest.
TEST(PivotingOrdering, AChainsIslandKeepsItsNormalsWhereMovingThemPricesHigher) {
    const auto chain = problems::chain_mlcp(4, 12);
    // chain_mlcp's blocks: joint j on bodies j and j + 1, then one block per contact; here each
    // contact follows the last joint on its body
    const int joints = 3, num_blocks = static_cast<int>(chain.block_row.size()) - 1;
    std::vector<int> blocks;
    for (int j = 0; j < joints; ++j) {
        blocks.push_back(j);
        for (int c = joints; c < num_blocks; ++c)
            if (std::min(chain.block_body[2 * c], joints - 1) == j) blocks.push_back(c);
    }
    ASSERT_EQ(static_cast<int>(blocks.size()), num_blocks);
    const auto owned = with_blocks_in_order(chain, blocks);
    const Problem p = owned.view();
    const linalg::SymmetricRows A(p, {});
    ASSERT_TRUE(ordering_cannot_pay(A));
    const MovedOrders m = moved_orders(owned.n, owned.findex);
    ASSERT_NE(m.normals_then_friction, m.friction_last);
    const std::vector<char> none(p.n, 0);
    const std::vector<int> chosen = choose_ordering(Method::Bpp, p, A, {}, FirstSolve::FrictionRowsTight);
    EXPECT_NE(chosen, m.normals_then_friction);
    std::vector<int> caller(p.n);
    std::iota(caller.begin(), caller.end(), 0);
    for (const std::vector<int>* candidate :
         std::initializer_list<const std::vector<int>*>{&caller, &m.friction_last, &m.normals_then_friction})
        EXPECT_LE(warm_solve_price(A, chosen, none, m.friction), warm_solve_price(A, *candidate, none, m.friction));
}

/// Without pricing (Tuning::price_tight_last_orderings off: the hook's first look at a new
/// structure) an island that an ordering pays for takes reverse Cuthill-McKee whatever its warm
/// start, where the priced choice moves the friction rows last; an island too small for an
/// ordering takes the caller's order priced as before (ordering_cannot_pay says which).
TEST(PivotingOrdering, UnpricedChoiceIsReverseCuthillMcKeeWhereAnOrderingPays) {
    int reordered = 0, small = 0;
    // long chains with two contacts whose normals start tight (the priced choice moves them last)
    // and short ones with many contacts (too small for an ordering)
    for (const auto& [links, contacts] : {std::pair{40, 2}, std::pair{60, 2}, std::pair{4, 12}, std::pair{3, 20}}) {
        const auto owned = problems::chain_mlcp(links, contacts);
        const Problem p = owned.view();
        const linalg::SymmetricRows A(p, {});
        std::vector<RowState> warm(p.n, RowState::Free);
        for (int i = p.nub, k = 0; i < p.n; ++i)
            if (owned.findex[i] < 0 && k++ % 2 == 0) warm[i] = RowState::AtLo;
        for (const auto first : {FirstSolve::AsWarmStart, FirstSolve::FrictionRowsTight}) {
            const std::vector<int> priced = choose_ordering(Method::Bpp, p, A, warm, first, true);
            const std::vector<int> unpriced = choose_ordering(Method::Bpp, p, A, warm, first, false);
            if (ordering_cannot_pay(A)) {
                EXPECT_EQ(unpriced, priced) << links << " links: the caller's order is priced either way";
                small += 1;
                continue;
            }
            EXPECT_EQ(unpriced, choose_ordering(Method::Bpp, p, A, {}, FirstSolve::AsWarmStart)) << links << " links";
            reordered += unpriced != priced;
        }
    }
    EXPECT_EQ(reordered, 4) << "pricing moves the tight normals of every long chain";
    EXPECT_EQ(small, 4);
}

TEST(PivotingOrdering, FirstSolvePriceAddsTheFrictionRowsStepOnly) {
    const auto owned = problems::chain_mlcp(40, 4);
    const Problem p = owned.view();
    const linalg::SymmetricRows A(p, {});
    std::vector<char> friction(p.n, 0), none(p.n, 0);
    for (int i = 0; i < p.n; ++i) friction[i] = owned.findex[i] >= 0;
    const std::vector<int> cm = order(p, ordering::OrderingKind::CuthillMcKee);
    const double factor_only = warm_solve_price(A, cm, none);
    EXPECT_EQ(warm_solve_price(A, cm, none, none), factor_only);
    EXPECT_GT(warm_solve_price(A, cm, none, friction), factor_only);
    // the later steps at the warm start's tight rows are priced as before
    std::vector<char> one(p.n, 0);
    one[p.n - 1] = 1;
    EXPECT_EQ(warm_solve_price(A, cm, one, friction) - warm_solve_price(A, cm, none, friction),
              (kStepsPerWarmSolve - 1) / kStepsPerWarmSolve * (warm_solve_price(A, cm, one) - factor_only));
}

}  // namespace
}  // namespace ode_bpp::ordering
