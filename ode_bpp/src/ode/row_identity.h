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
class RowStateMemory {
public:
    /// states: output, one per key; rows never seen start Free. Returns true if any row was known.
    bool recall(const std::vector<RowKey>& keys, std::vector<RowState>& states) const;
    /// Stores the final index set of an island. Old entries are dropped once the memory holds
    /// several steps' worth of rows, so vanished contacts do not accumulate.
    void remember(const std::vector<RowKey>& keys, const std::vector<RowState>& states);

private:
    std::unordered_map<RowKey, RowState, RowKeyHash> current_, previous_;
    std::size_t rows_per_generation_ = 0;
};

}  // namespace ode_bpp
