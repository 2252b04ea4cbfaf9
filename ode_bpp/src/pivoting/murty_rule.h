// Murty's least-index rule, in reverse (Murty 1974; paper Sec. 3.1): of the infeasible rows, only
// the one of largest rank in a fixed order changes set. From any index set this terminates
// finitely on a P-matrix (A SPD, hence A_FF SPD for every F), which block steps do not.
#pragma once

#include "pivoting/boxed_lcp.h"
#include "pivoting/classify_row.h"

namespace ode_bpp::pivoting {

/// The position in inf (inf.count() > 0) of the row Murty's rule flips: largest
/// BoxedLcp::murty_rank, or largest permuted index where the ranks are empty.
inline int murty_choice(const BoxedLcp& lcp, const Infeasibility& inf) {
    int chosen = inf.count() - 1;
    if (!lcp.murty_rank.empty())
        for (int k = 0; k < inf.count(); ++k)
            if (lcp.murty_rank[inf.rows[k]] > lcp.murty_rank[inf.rows[chosen]]) chosen = k;
    return chosen;
}

/// The position in inf (inf.count() > 0) of the row that breaks its condition most.
inline int most_violated(const Infeasibility& inf) {
    int chosen = 0;
    for (int k = 1; k < inf.count(); ++k)
        if (inf.excess[k] > inf.excess[chosen]) chosen = k;
    return chosen;
}

}  // namespace ode_bpp::pivoting
