#include "pivoting/boxed_lcp.h"

#include <limits>

#include "pivoting/friction_set.h"

namespace ode_bpp::pivoting {

void build_boxed_lcp(const Problem& p, const linalg::SymmetricRows& Ap, const std::vector<int>& perm, BoxedLcp& lcp,
                     FrictionSet& friction) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const int n = p.n;
    const std::vector<int> to_new = linalg::inverse_permutation(perm);
    lcp.A = &Ap;
    lcp.shift = 0;
    lcp.b.resize(n);
    lcp.lo.resize(n);
    lcp.hi.resize(n);
    lcp.always_free.assign(static_cast<std::size_t>(n), 0);
    lcp.murty_rank = perm;
    lcp.friction_normal.clear();
    lcp.friction_mu.clear();
    friction.clear();
    for (int i = 0; i < n; ++i) {
        const int old = perm[i];
        lcp.b[i] = p.b[old];
        const bool unbounded = old < p.nub;
        lcp.lo[i] = unbounded ? -kInf : p.lo[old];
        lcp.hi[i] = unbounded ? kInf : p.hi[old];
        lcp.always_free[i] = lcp.lo[i] == -kInf && lcp.hi[i] == kInf;
        if (p.findex != nullptr && p.findex[old] >= 0) {
            friction.rows.push_back(i);
            friction.normal_of.push_back(to_new[p.findex[old]]);
            friction.mu.push_back(p.hi[old]);
            lcp.always_free[i] = 0;
        }
    }
}

}  // namespace ode_bpp::pivoting
