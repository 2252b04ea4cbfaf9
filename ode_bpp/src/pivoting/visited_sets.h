// The index sets a pivoting loop has entered, to recognize a cycle (pivot_loop.cpp).
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
/// Only a 64-bit hash of each set is kept (8 bytes a step, where whole sets took n bytes a step
/// and grew the process as longer runs of single pivots came): two different sets with one hash
/// (probability about k² / 2^64 after k steps) end a stage early, which
/// the rescue does not depend on.
class VisitedSets {
public:
    void clear() { hashes_.clear(); }
    /// True if states (by its hash) was entered before; otherwise records it.
    bool revisits(const std::vector<RowState>& states) {
        std::uint64_t h = 1469598103934665603ULL;  // FNV-1a over the states
        for (RowState s : states) h = (h ^ static_cast<std::uint64_t>(static_cast<int>(s) + 1)) * 1099511628211ULL;
        if (std::find(hashes_.begin(), hashes_.end(), h) != hashes_.end()) return true;
        hashes_.push_back(h);
        return false;
    }

private:
    std::vector<std::uint64_t> hashes_;
};

}  // namespace ode_bpp::pivoting
