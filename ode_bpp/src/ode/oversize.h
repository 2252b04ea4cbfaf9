// Whether an island's exact solve would pass Options::max_factor_entries, decided from its joints
// before A is formed (docs/modelling.md, "Islands too large for an exact step"). Such an island
// is answered by projected Gauss-Seidel on J (ode/jacobian_pgs.h) instead of being assembled,
// ordered and counted first.
//
// Index space: the island's own row order (ODE's); orderings are perm[new] = old.
#pragma once

#include <ode/mlcp.h>

#include <cstdint>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp::ode {

/// Why an island is answered without forming A: the count that passed the limit, and what it
/// counts.
struct Oversize {
    enum class Measure {
        None,           ///< within the limit, or not known without A: solve as usual
        MatrixEntries,  ///< A's own entries, at least (coupled_entries_lower_bound)
        FactorEntries,  ///< the factor's envelope in the order the solve would factor in
    };
    Measure measure = Measure::None;
    std::int64_t entries = 0;
    explicit operator bool() const { return measure != Measure::None; }
};

/// Decides, for an island in the sparse form, whether a BPP method's factor would pass
/// Options::max_factor_entries, in O(rows + joints + bodies) plus an ordering of the joint graph
/// where one is needed, without forming A:
///  - only where the dense triangle would pass it (pivoting::factor_may_be_too_large);
///  - A's entries first, bounded from below by the joints (coupled_entries_lower_bound);
///  - then the factor's envelope, exactly: ode/assemble.h stores every entry of each block of two
///    joints that share a body, so A's pattern, and with it the envelope in any order, follows
///    from the joints (ordering::block_row_profile). Counted in the order the solve will factor
///    in: `order` (in/out, the island's Start::ordering) where it is a permutation of the rows,
///    else the order it is set to here, the joint graph's (ordering::block_ordering), which the
///    caller hands to the solve. The strategies that factor densely hold n(n + 1) / 2.
/// island: has the sparse form; problem: its rows (IslandView::rows_of: the joints as blocks).
/// An island whose structure is defective (structure_defect) is left to the solve to report:
/// None.
Oversize oversize(const dMLCP& island, const Problem& problem, const Options& options, std::vector<int>& order,
                  std::vector<std::int64_t>& rows_on_body);

}  // namespace ode_bpp::ode
