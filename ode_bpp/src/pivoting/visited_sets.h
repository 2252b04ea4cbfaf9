// The index sets a pivoting loop has entered, to recognize a cycle (pivot_loop.cpp,
// single_pivots.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp::pivoting {

/// Index sets entered by the pivot steps of one run. A step is a function of the index set (x_F
/// from Eq. 6, then Eq. 4 and a deterministic choice), so a revisit is a cycle: on nearly
/// redundant contact rows the rescue stages met cycles of 2-6 sets, which the stall count alone
/// let run 6-30 steps (winch, forklift, parkour at ODE's CFM 1e-10).
class VisitedSets {
public:
    void clear() {
        hashes_.clear();
        sets_.clear();
    }
    /// True if states was entered before; otherwise records it.
    bool revisits(const std::vector<RowState>& states) {
        std::uint64_t h = 1469598103934665603ULL;  // FNV-1a over the states
        for (RowState s : states) h = (h ^ static_cast<std::uint64_t>(static_cast<int>(s) + 1)) * 1099511628211ULL;
        const std::size_t n = states.size();
        for (std::size_t k = 0; k < hashes_.size(); ++k)
            if (hashes_[k] == h && std::equal(states.begin(), states.end(), sets_.begin() + static_cast<std::ptrdiff_t>(k * n)))
                return true;
        hashes_.push_back(h);
        sets_.insert(sets_.end(), states.begin(), states.end());
        return false;
    }

private:
    std::vector<std::uint64_t> hashes_;
    std::vector<RowState> sets_;  ///< n entries each
};

}  // namespace ode_bpp::pivoting
