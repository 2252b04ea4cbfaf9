#include "problems/owned_problem.h"

#include <limits>

namespace ode_bpp::problems {

Problem OwnedProblem::view() const {
    Problem p;
    p.n = n;
    p.A = A.data();
    p.lda = lda;
    p.b = {b.data(), 1};
    p.lo = {lo.data(), 1};
    p.hi = {hi.data(), 1};
    p.findex = findex.empty() ? nullptr : findex.data();
    p.nub = nub;
    if (!block_row.empty()) {
        p.num_blocks = static_cast<int>(block_row.size()) - 1;
        p.block_row = block_row.data();
        p.block_body = block_body.data();
    }
    return p;
}

OwnedProblem OwnedProblem::zeros(std::string name, int n) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    OwnedProblem p;
    p.name = std::move(name);
    p.n = n;
    p.lda = n > 1 ? (n + 3) / 4 * 4 : n;
    p.A.assign(static_cast<std::size_t>(n) * p.lda, 0.0);
    p.b.assign(n, 0.0);
    p.lo.assign(n, -inf);
    p.hi.assign(n, inf);
    return p;
}

}  // namespace ode_bpp::problems
