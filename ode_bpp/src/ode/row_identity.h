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

/// RowKey without the row: the joint (or contact) the row belongs to.
struct JointKey {
    const void* a = nullptr;
    const void* b = nullptr;
    std::int32_t ordinal = 0;
    explicit JointKey(const RowKey& k) : a(k.a), b(k.b), ordinal(k.ordinal) {}
    bool operator==(const JointKey& o) const { return a == o.a && b == o.b && ordinal == o.ordinal; }
};

struct JointKeyHash {
    std::size_t operator()(const JointKey& k) const;
};

/// A contact joint of an island and its ordinal among the island's contacts of the same geom pair.
struct ContactSlot {
    const void* g1 = nullptr;
    const void* g2 = nullptr;
    int joint = 0;
    std::int32_t ordinal = 0;
};

/// keys[i] = identity of island row i (original row order). keys: output, m entries; contacts:
/// buffer reused from call to call (no allocation once it has grown).
void row_keys(const dMLCP& problem, std::vector<RowKey>& keys, std::vector<ContactSlot>& contacts);

/// The index sets of the most recent steps, by row identity.
///
/// Stored per joint: the rows of a joint come as consecutive keys, and one hash lookup serves
/// them all (a lookup per row cost more than a small island's factorization). Each row keeps
/// its own age, so a row that a joint drops for a step (a limit that lets go) is recalled as if
/// it were stored alone.
///
/// Ageing counts world steps (dMLCP::step), never calls: the islands of one step are solved in
/// any order, or concurrently, and what an island recalls must not depend on which of its
/// neighbours finished first. Within a step islands hold disjoint keys, so an island only ever
/// sees what earlier steps stored.
class RowStateMemory {
    struct Entry;

public:
    /// Entries not refreshed for this many steps are dropped (a contact that vanishes for one
    /// step is still recalled when it returns).
    static constexpr std::uint64_t kKeepSteps = 2;

    /// The joints of one island where recall found them (or made room for them), so that
    /// remember stores the island's index set without a second hash lookup per joint (on an
    /// island of one joint the lookups cost as much as its factorization). Kept by the caller;
    /// it serves the keys it was filled with, in the step it was filled in.
    class Slots {
        friend class RowStateMemory;
        struct Joint {
            std::size_t end;  ///< one past the joint's last key
            Entry* entry;     ///< stable: entries are erased only when a later step begins
        };
        std::vector<Joint> joints_;
        std::uint64_t memory_ = 0;  ///< RowStateMemory::id_ of the memory that filled it
        std::uint64_t steps_ = 0;   ///< its steps_ then
    };

    RowStateMemory() = default;
    /// A copy (or an assignment) holds other entries, so it takes a new identity: slots filled
    /// by the original never serve it.
    RowStateMemory(const RowStateMemory& other);
    RowStateMemory& operator=(const RowStateMemory& other);

    /// step: the world step of the island. states: output, one per key; rows never seen start
    /// Free. Returns true if any row was known. slots: null, or filled for remember.
    bool recall(const std::vector<RowKey>& keys, std::uint64_t step, std::vector<RowState>& states,
                Slots* slots = nullptr);
    /// Stores the final index set of an island solved in world step `step`. slots: null, or
    /// filled by recall with the same keys in the same step (otherwise the joints are looked up).
    void remember(const std::vector<RowKey>& keys, std::uint64_t step, const std::vector<RowState>& states,
                  const Slots* slots = nullptr);
    /// Rows held (stored within the last kKeepSteps steps).
    std::size_t size() const;

private:
    struct Row {
        RowState state = RowState::Free;
        std::uint64_t seen = 0;  ///< steps_ when stored; 0: never
    };
    struct Entry {
        std::vector<Row> rows;   ///< by row within the joint
        std::uint64_t seen = 0;  ///< the newest of the rows' seen
    };
    /// Counts a new step when `step` differs from the last one seen (a reset counts too), and
    /// drops the joints whose rows are all older than kKeepSteps.
    void enter_step(std::uint64_t step);
    bool is_kept(const Row& row) const { return row.seen != 0 && steps_ - row.seen <= kKeepSteps; }
    /// The states of keys [begin, end), one joint's rows, into its entry, as of this step.
    void store(Entry& entry, const std::vector<RowKey>& keys, std::size_t begin, std::size_t end,
               const std::vector<RowState>& states);

    std::unordered_map<JointKey, Entry, JointKeyHash> joints_;
    std::uint64_t last_world_step_ = 0;
    std::uint64_t steps_ = 0;  ///< distinct world steps seen so far
    /// Unique in the process, so that slots of a memory since destroyed (a world forgotten while
    /// one of its islands was being solved) are never taken for this one's.
    std::uint64_t id_ = fresh_id();
    static std::uint64_t fresh_id();
};

}  // namespace ode_bpp
