// What goes with an iterate x of the pivoting loops (pivot_loop.cpp, active_set.cpp):
// w = (A + shift I) x - b, the row scales (|A||x| + |b|)_i that classify_row.h measures against,
// and Eq. 6's backward error on the free rows.
#pragma once

#include <vector>

#include "pivoting/boxed_lcp.h"
#include "pivoting/classify_row.h"

namespace ode_bpp::pivoting {

/// w, the row scales and the bounds in force (moving friction bounds change them), n entries each.
struct Iterate {
    std::vector<double> w, scale, lo, hi;
};

/// w = (A + shift I) x - b and scale = |A + shift I||x| + |b|, from x (n entries).
void refresh_residual(const BoxedLcp& lcp, const std::vector<double>& x, Iterate& it);

/// max over free rows (tight[i] == 0) of |w_i| / scale_i: Eq. 6's backward error, row by row.
double free_residual(const Iterate& it, const std::vector<char>& tight);

/// Eq. 4 row by row on (A + shift I, b) at x and the index set `states` (classify_row.h), with the
/// bounds and scales of `it`; the infeasible rows go to `inf`.
void classify_iterate(const BoxedLcp& lcp, const Iterate& it, const std::vector<RowState>& states,
                      const std::vector<double>& x, double tolerance, Infeasibility& inf);

/// A fresh Cholesky solve misses Eq. 6 by about n eps relative to |A||x| + |b|; a tenth of the
/// classification tolerance keeps the pivoting decisions unaffected by the factor. A factor
/// that misses by more (after deletions or updates) is replaced by a fresh one.
double accuracy_limit(double tolerance, int n);

}  // namespace ode_bpp::pivoting
