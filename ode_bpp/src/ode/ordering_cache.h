// The row orderings of a world's islands, kept from step to step: an island whose constraint
// structure (rows per joint, bodies per joint) has not changed factors in the same permutation,
// so the hook passes it back (Start::ordering) instead of numbering the graph again.
// An island is known by the identity of its first row as well as by its structure: identical
// islands (a row of equal stacks) may order their rows differently (likely-tight rows last),
// and sharing one entry would make each island's ordering depend on which finished last.
//
// Index space: ODE's island row order (original).
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include <ode/mlcp.h>

#include "ode/row_identity.h"

namespace ode_bpp {

class OrderingCache {
public:
    using Signature = std::vector<std::intptr_t>;
    /// structure: output, the island's signature: the identity of its first row, m, then each
    /// joint's first row and bodies.
    static void signature(const dMLCP& problem, const RowKey& first_row, Signature& structure);
    /// The ordering stored for this signature, or null.
    const std::vector<int>* find(const Signature& structure) const;
    /// Stores (or replaces) the ordering of a signature. Forgets everything once kMaxIslands
    /// signatures are held, so islands that come and go do not accumulate.
    void store(const Signature& structure, const std::vector<int>& ordering);
    /// Signatures held: at most kMaxIslands.
    std::size_t size() const { return orderings_.size(); }
    static constexpr std::size_t kMaxIslands = 256;

private:
    std::map<Signature, std::vector<int>> orderings_;
};

}  // namespace ode_bpp
