// The row orderings of a world's islands, kept from step to step: an island whose constraint
// structure (rows per joint, bodies per joint) has not changed factors in the same permutation,
// so the hook passes it back (Options::ordering) instead of numbering the graph again.
//
// Index space: ODE's island row order (original).
#pragma once

#include <map>
#include <vector>

#include <ode/mlcp.h>

namespace ode_bpp {

class OrderingCache {
public:
    /// structure: output, the island's signature (m, then each joint's first row and bodies).
    static void signature(const dMLCP& problem, std::vector<int>& structure);
    /// The ordering stored for this signature, or null.
    const std::vector<int>* find(const std::vector<int>& structure) const;
    /// Stores (or replaces) the ordering of a signature. Forgets everything once kMaxIslands
    /// signatures are held, so islands that come and go do not accumulate.
    void store(const std::vector<int>& structure, const std::vector<int>& ordering);

private:
    static constexpr std::size_t kMaxIslands = 256;
    std::map<std::vector<int>, std::vector<int>> orderings_;
};

}  // namespace ode_bpp
