// Size limits of the peers whose cost grows too fast for the whole corpus.
#pragma once

namespace ode_bpp::peers {

/// Largest island the Lemke peers are run on. Both build a 2n-variable LCP (Bullet's on a dense
/// Gauss-Jordan inverse of A), O(n^3) per solve and up to 20 n pivots on a 2n x 4n tableau: at
/// 200 rows a solve takes about as long as the rest of the methods on that island together,
/// and the corpus' largest islands (400+ rows) would dominate the run.
inline constexpr int kLemkeMaxRows = 200;

}  // namespace ode_bpp::peers
