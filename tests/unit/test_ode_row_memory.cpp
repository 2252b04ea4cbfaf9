// The hook's memory across world steps: warm-start index sets by row identity (RowStateMemory)
// and row orderings by island (OrderingCache). Both must age by world steps and give each
// island the same answer whatever order the islands of a step are solved in (ODE's thread pool
// solves them concurrently).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "ode/ordering_cache.h"
#include "ode/row_identity.h"

namespace ode_bpp {
namespace {

/// Island k of a scene of `islands` islands: `rows` rows keyed by (joint k, row r).
std::vector<RowKey> island_keys(const std::vector<int>& joints, int k, int rows) {
    std::vector<RowKey> keys(static_cast<std::size_t>(rows));
    for (int r = 0; r < rows; ++r) {
        keys[r].a = &joints[k];
        keys[r].row = r;
    }
    return keys;
}

/// A state that varies with the island, the row and the step, so that stale entries show.
RowState state_of(int island, int row, std::uint64_t step) {
    switch ((island + row + static_cast<int>(step)) % 3) {
        case 0: return RowState::Free;
        case 1: return RowState::AtLo;
        default: return RowState::AtHi;
    }
}

/// Steps a memory through `steps` steps of `islands` islands of different sizes, solved in the
/// order `order_of(step)`, and returns what each island recalled at each step.
template <class Order>
std::vector<std::vector<RowState>> run_steps(int islands, int steps, Order order_of) {
    std::vector<int> joints(static_cast<std::size_t>(islands));
    RowStateMemory memory;
    std::vector<std::vector<RowState>> recalled(static_cast<std::size_t>(islands * steps));
    for (int s = 0; s < steps; ++s) {
        const std::uint64_t step = 100 + static_cast<std::uint64_t>(s);
        for (int k : order_of(s)) {
            const int rows = 6 + 7 * k;  // a step holds far more rows than its largest island
            const std::vector<RowKey> keys = island_keys(joints, k, rows);
            std::vector<RowState> states;
            memory.recall(keys, step, states);
            recalled[static_cast<std::size_t>(s * islands + k)] = states;
            std::vector<RowState> solved(keys.size());
            for (int r = 0; r < rows; ++r) solved[r] = state_of(k, r, step);
            memory.remember(keys, step, solved);
        }
    }
    return recalled;
}

TEST(RowStateMemory, AnIslandRecallsThePreviousStepWhateverOrderTheIslandsRunIn) {
    constexpr int kIslands = 8, kSteps = 12;
    const auto in_order = [](int) {
        std::vector<int> order(kIslands);
        std::iota(order.begin(), order.end(), 0);
        return order;
    };
    std::mt19937 rng(7);
    const auto shuffled = [&](int) {
        std::vector<int> order = in_order(0);
        std::shuffle(order.begin(), order.end(), rng);
        return order;
    };
    const auto a = run_steps(kIslands, kSteps, in_order);
    const auto b = run_steps(kIslands, kSteps, shuffled);
    EXPECT_EQ(a, b);
    // and what is recalled is the previous step's answer, row by row
    for (int s = 1; s < kSteps; ++s)
        for (int k = 0; k < kIslands; ++k)
            for (int r = 0; r < 6 + 7 * k; ++r)
                ASSERT_EQ(a[s * kIslands + k][r], state_of(k, r, 100 + static_cast<std::uint64_t>(s) - 1))
                    << "step " << s << " island " << k << " row " << r;
}

TEST(RowStateMemory, RowsAbsentForMoreThanTheKeptStepsAreForgotten) {
    std::vector<int> joints(2);
    RowStateMemory memory;
    std::vector<RowState> states;
    const std::vector<RowKey> flicker = island_keys(joints, 0, 3), steady = island_keys(joints, 1, 2);
    memory.remember(flicker, 1, std::vector<RowState>(3, RowState::AtLo));
    for (std::uint64_t step = 2; step <= 1 + RowStateMemory::kKeepSteps; ++step) {
        EXPECT_TRUE(memory.recall(flicker, step, states)) << "a contact absent for " << step - 1 << " step(s)";
        EXPECT_EQ(states, std::vector<RowState>(3, RowState::AtLo));
        memory.remember(steady, step, std::vector<RowState>(2, RowState::Free));
    }
    EXPECT_FALSE(memory.recall(flicker, 2 + RowStateMemory::kKeepSteps, states));
    EXPECT_EQ(states, std::vector<RowState>(3, RowState::Free));
    EXPECT_EQ(memory.size(), steady.size());
}

TEST(RowStateMemory, AStepNumberThatGoesBackStillStartsANewStep) {
    std::vector<int> joints(1);
    RowStateMemory memory;
    std::vector<RowState> states;
    const std::vector<RowKey> keys = island_keys(joints, 0, 2);
    memory.remember(keys, 50, std::vector<RowState>(2, RowState::AtHi));
    // a world whose statistics were reset or a new world at the same address: steps restart
    for (std::uint64_t step : {1, 2, 3}) memory.recall({}, step, states);
    EXPECT_FALSE(memory.recall(keys, 4, states));
}

/// The states island rows solve to at `step`, for keys of several joints.
std::vector<RowState> solved_states(std::size_t rows, std::uint64_t step) {
    std::vector<RowState> states(rows);
    for (std::size_t r = 0; r < rows; ++r) states[r] = state_of(0, static_cast<int>(r), step);
    return states;
}

TEST(RowStateMemory, SlotsStoreWhatALookupStoresAndServeOnlyTheMemoryThatFilledThem) {
    std::vector<int> joints(3);
    std::vector<RowKey> keys = island_keys(joints, 0, 2);
    for (int k : {1, 2}) {
        const std::vector<RowKey> more = island_keys(joints, k, 2 + k);
        keys.insert(keys.end(), more.begin(), more.end());
    }
    RowStateMemory with_slots, by_lookup;
    RowStateMemory::Slots slots;
    std::vector<RowState> a, b;
    for (std::uint64_t step = 1; step <= 4; ++step) {
        with_slots.recall(keys, step, a, &slots);
        by_lookup.recall(keys, step, b);
        EXPECT_EQ(a, b) << "step " << step;
        with_slots.remember(keys, step, solved_states(keys.size(), step), &slots);
        by_lookup.remember(keys, step, solved_states(keys.size(), step));
    }
    // a copy holds other entries: slots the original filled store into the copy by lookup
    with_slots.recall(keys, 5, a, &slots);
    RowStateMemory copy = with_slots;
    copy.remember(keys, 5, solved_states(keys.size(), 5), &slots);
    copy.recall(keys, 6, a);
    with_slots.recall(keys, 6, b);
    EXPECT_EQ(a, solved_states(keys.size(), 5));
    EXPECT_EQ(b, solved_states(keys.size(), 4));
}

TEST(OrderingCache, EqualIslandsWithDifferentIdentitiesKeepTheirOwnOrderings) {
    dMLCPJoint joints[2] = {};
    joints[0].row = 0;
    joints[0].m = 3;
    joints[0].body[0] = 0;
    joints[0].body[1] = -1;
    joints[1] = joints[0];
    joints[1].row = 3;
    joints[1].body[1] = 0;
    dMLCP problem = {};
    problem.m = 6;
    problem.nj = 2;
    problem.joints = joints;
    int pile_a = 0, pile_b = 0;
    RowKey first_a, first_b;
    first_a.a = &pile_a;
    first_b.a = &pile_b;

    OrderingCache cache;
    OrderingCache::Signature a, b;
    OrderingCache::signature(problem, first_a, a);
    OrderingCache::signature(problem, first_b, b);
    ASSERT_NE(a, b);
    cache.store(a, {0, 1, 2, 3, 4, 5}, true, 1);
    cache.store(b, {5, 4, 3, 2, 1, 0}, true, 1);
    ASSERT_NE(cache.find(a, 2), nullptr);
    EXPECT_EQ(cache.find(a, 2)->ordering, (std::vector<int>{0, 1, 2, 3, 4, 5}));
    // a change of structure (another joint, other bodies) is another island
    joints[1].body[1] = -1;
    OrderingCache::Signature changed;
    OrderingCache::signature(problem, first_a, changed);
    EXPECT_EQ(cache.find(changed, 2), nullptr);
}

// Contacts that come and go (a pile: new contact pairs every step, each seen once) must not make
// the memory grow: what it holds is bounded by the rows of the last kKeepSteps + 1 steps.
TEST(RowStateMemory, StaysBoundedWhileContactsComeAndGo) {
    constexpr int kRowsPerStep = 300, kSteps = 5000;
    std::vector<int> geoms(static_cast<std::size_t>(kRowsPerStep) * kSteps);
    RowStateMemory memory;
    std::vector<RowState> states;
    std::size_t largest = 0;
    for (int s = 0; s < kSteps; ++s) {
        std::vector<RowKey> keys(kRowsPerStep);
        for (int r = 0; r < kRowsPerStep; ++r) keys[r].a = &geoms[static_cast<std::size_t>(s) * kRowsPerStep + r];
        memory.recall(keys, static_cast<std::uint64_t>(s + 1), states);
        memory.remember(keys, static_cast<std::uint64_t>(s + 1), std::vector<RowState>(kRowsPerStep, RowState::AtLo));
        largest = std::max(largest, memory.size());
    }
    EXPECT_LE(largest, (RowStateMemory::kKeepSteps + 1) * kRowsPerStep);
}

// The hook's first look at a new structure is stored unsettled (ordered without pricing), its
// choice when the structure returns settled; find says which, and a store replaces both.
TEST(OrderingCache, KeepsWhetherAnOrderingIsSettled) {
    OrderingCache cache;
    const OrderingCache::Signature island{1, 7, 0, 3};
    cache.store(island, {2, 1, 0}, false, 1);
    ASSERT_NE(cache.find(island, 2), nullptr);
    EXPECT_FALSE(cache.find(island, 2)->settled);
    cache.store(island, {0, 2, 1}, true, 2);
    EXPECT_TRUE(cache.find(island, 3)->settled);
    EXPECT_EQ(cache.find(island, 3)->ordering, (std::vector<int>{0, 2, 1}));
}

// Islands whose structure changes every step fill the cache, which then starts again: it never
// holds more than kMaxIslands orderings.
TEST(OrderingCache, StaysBoundedWhileIslandsChange) {
    OrderingCache cache;
    std::size_t largest = 0;
    for (std::intptr_t k = 0; k < 10 * static_cast<std::intptr_t>(OrderingCache::kMaxIslands); ++k) {
        cache.store(OrderingCache::Signature{k, 7, 0, 3}, {0, 1, 2}, true, 1);
        largest = std::max(largest, cache.size());
    }
    EXPECT_EQ(largest, OrderingCache::kMaxIslands);
    EXPECT_NE(cache.find(OrderingCache::Signature{10 * static_cast<std::intptr_t>(OrderingCache::kMaxIslands) - 1, 7, 0, 3}, 1), nullptr);
}

// A resting pile meets a new structure now and then, each seen for a few steps only: the cache
// forgets them once unseen for kKeepSteps, so it holds what recurs, not every structure met.
TEST(OrderingCache, ForgetsStructuresUnseenForKeepSteps) {
    OrderingCache cache;
    const OrderingCache::Signature steady{1, 7, 0, 3};
    std::uint64_t step = 1;
    for (std::intptr_t k = 0; k < 100; ++k, step += 10) {
        if (cache.find(steady, step) == nullptr) cache.store(steady, {2, 1, 0}, true, step);
        const OrderingCache::Signature passing{1000 + k, 7, 0, 3};
        if (cache.find(passing, step) == nullptr) cache.store(passing, {0, 1, 2}, true, step);
        EXPECT_LE(cache.size(), 1 + OrderingCache::kKeepSteps / 10 + 1) << "step " << step;
    }
    EXPECT_NE(cache.find(steady, step), nullptr);  // seen every 10 steps: kept
    EXPECT_EQ(cache.find(OrderingCache::Signature{1000, 7, 0, 3}, step), nullptr);
    EXPECT_NE(cache.find(OrderingCache::Signature{1099, 7, 0, 3}, step), nullptr);  // seen 10 steps ago
}

}  // namespace
}  // namespace ode_bpp
