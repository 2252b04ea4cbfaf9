// Row identity across world steps, for warm-starting the index sets (issue: "joints persist
// between steps, and contacts can be matched by their bodies and geoms").
//
// A joint's row is identified by (joint, row within the joint). A contact joint is new every
// step, so its rows are identified by (geom 1, geom 2, ordinal of the contact within that geom
// pair in this island, row within the joint): dCollide reports persistent contacts in a stable order.
#pragma once

#include <ode/ode.h>

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp {

struct RowKey {
    const void* a = nullptr;   ///< joint, or geom 1 of a contact
    const void* b = nullptr;   ///< null, or geom 2 of a contact
    std::int32_t ordinal = 0;  ///< contacts: index among this island's contacts of the same pair
    std::int32_t row = 0;      ///< row within the joint
    bool operator==(const RowKey& o) const { return a == o.a && b == o.b && ordinal == o.ordinal && row == o.row; }
};

struct RowKeyHash {
    std::size_t operator()(const RowKey& k) const;
};

/// keys[i] = identity of island row i (original row order). keys: output, m entries.
void row_keys(const dMLCP& problem, std::vector<RowKey>& keys);

/// The index sets of the most recent steps, by row identity.
///
/// Ageing counts world steps (dMLCP::step), never calls: the islands of one step are solved in
/// any order, or concurrently, and what an island recalls must not depend on which of its
/// neighbours finished first. Within a step islands hold disjoint keys, so an island only ever
/// sees what earlier steps stored.
class RowStateMemory {
public:
    /// Entries not refreshed for this many steps are dropped (a contact that vanishes for one
    /// step is still recalled when it returns).
    static constexpr std::uint64_t kKeepSteps = 2;

    /// step: the world step of the island. states: output, one per key; rows never seen start
    /// Free. Returns true if any row was known.
    bool recall(const std::vector<RowKey>& keys, std::uint64_t step, std::vector<RowState>& states);
    /// Stores the final index set of an island solved in world step `step`.
    void remember(const std::vector<RowKey>& keys, std::uint64_t step, const std::vector<RowState>& states);
    std::size_t size() const { return rows_.size(); }

private:
    struct Entry {
        RowState state;
        std::uint64_t seen;  ///< steps_ when stored
    };
    /// Counts a new step when `step` differs from the last one seen (a reset counts too), and
    /// drops the entries older than kKeepSteps.
    void enter_step(std::uint64_t step);

    std::unordered_map<RowKey, Entry, RowKeyHash> rows_;
    std::uint64_t last_world_step_ = 0;
    std::uint64_t steps_ = 0;  ///< distinct world steps seen so far
};

}  // namespace ode_bpp
