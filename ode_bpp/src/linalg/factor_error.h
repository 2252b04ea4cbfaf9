// The error of a downdated factor against a fresh one (paper Table 4).
#pragma once

#include <vector>

#include "linalg/skyline.h"

namespace ode_bpp::linalg {

/// ||La - Lb||_F over the entries (r, k), r >= k, with neither r nor k removed (the factor of
/// A_FF). Entries outside a matrix's skyline count as 0, so La and Lb may have different shapes
/// of the same n. removed: n flags or empty for none. Index space: the factors' (permuted).
double factor_error(const SkylineMatrix& La, const SkylineMatrix& Lb, const std::vector<char>& removed);

}  // namespace ode_bpp::linalg
