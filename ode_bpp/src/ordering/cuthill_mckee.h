// Cuthill-McKee ordering (paper Sec. 3.4; Cuthill & McKee 1969, start node by George & Liu 1979).
#pragma once

#include <vector>

#include "ordering/graph.h"

namespace ode_bpp::ordering {

/// Cuthill-McKee (reverse = false) or reverse Cuthill-McKee (reverse = true) ordering of g.
/// Returns perm with perm[new] = old (g.n() entries). Every connected component is ordered
/// (components in order of their lowest vertex), each by a breadth-first search from a
/// pseudo-peripheral vertex found by George & Liu's iteration started at a vertex of minimal
/// degree, visiting the unnumbered neighbours of each vertex by increasing degree (ties by
/// index). Reverse reverses the whole sequence, which never enlarges the envelope (Liu & Sherman).
std::vector<int> cuthill_mckee(const Graph& g, bool reverse);

}  // namespace ode_bpp::ordering
