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
    /// What is kept of a signature.
    struct Remembered {
        std::vector<int> ordering;
        /// The ordering came from the choice the world's settings ask for; false: from the
        /// unpriced first look at a new structure (Tuning::price_tight_last_orderings), which the
        /// hook replaces when the structure returns. Only settled orderings are passed back.
        bool settled = true;
        std::uint64_t seen = 0;  ///< the latest step that found or stored it
    };
    /// structure: output, the island's signature: the identity of its first row, m, then each
    /// joint's first row and bodies.
    static void signature(const dMLCP& problem, const RowKey& first_row, Signature& structure);
    /// What is stored for this signature, or null; marks it seen at `step` (the world's step
    /// number). The first call of a later step first forgets every ordering not seen for more
    /// than kKeepSteps steps.
    const Remembered* find(const Signature& structure, std::uint64_t step);
    /// Stores (or replaces) the ordering of a signature, seen at `step`. Forgets everything once
    /// kMaxIslands signatures are held.
    void store(const Signature& structure, const std::vector<int>& ordering, bool settled, std::uint64_t step);
    /// Signatures held: at most kMaxIslands, and only those seen in the last kKeepSteps + 1 steps.
    std::size_t size() const { return orderings_.size(); }
    static constexpr std::size_t kMaxIslands = 256;
    /// A resting pile meets a new contact structure now and then and never sees most of them
    /// again; without an age limit each stayed until the cache was full, and the process's
    /// memory rose by a few kB per new structure for tens of thousands of steps (the pyramid's
    /// 940-row island: about 11 kB each). 64 steps (about a second at 60 Hz) keeps what recurs.
    static constexpr std::uint64_t kKeepSteps = 64;

private:
    void forget_older_than(std::uint64_t step);

    std::map<Signature, Remembered> orderings_;
    std::uint64_t swept_ = 0;  ///< the step whose first find() last swept
};

}  // namespace ode_bpp
