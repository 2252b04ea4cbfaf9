#include "ode/island_view.h"

#include <algorithm>

#include "ode/assemble.h"
#include "ordering/order_rows.h"

namespace ode_bpp::ode {

namespace {

const std::vector<int> kBuiltOrder;  ///< the island's own row order

/// True when order is a permutation of 0 .. n-1 other than the identity.
bool is_reordering(const std::vector<int>& order, int n) {
    // sortedness first: it ends at the first descent, and the usual cached order of a chain is
    // the identity, which the permutation test would mark row by row
    return !order.empty() && !std::is_sorted(order.begin(), order.end()) && ordering::is_permutation(order, n);
}

}  // namespace

Problem IslandView::of(const dMLCP& p, bool dense_lower, const std::vector<int>& order) {
    Problem q = rows_of(p);
    q.A = p.A;
    q.lda = p.skip;
    // The buffers only grow: islands of changing sizes would otherwise pay a zero fill at every
    // growth, and every entry read is written first (the lower triangle by the assembly, the
    // blocks below).
    if (has_sparse_form(p) && dense_lower) {
        if (const auto entries = static_cast<std::size_t>(p.m) * p.m; dense_.size() < entries) dense_.resize(entries);
        assemble_dense_lower(p, dense_.data(), p.m, assembly_);
        q.A = dense_.data();
        q.lda = p.m;
    } else if (has_sparse_form(p)) {
        assemble_rows(p, assembled_, assembly_, is_reordering(order, p.m) ? order : kBuiltOrder);
        q.sparse = &assembled_;
    }
    return q;
}

Problem IslandView::rows_of(const dMLCP& p) {
    Problem q;
    q.n = p.m;
    q.b = ConstStrided{p.pairsbx, 2};
    q.lo = ConstStrided{p.pairslh, 2};
    q.hi = ConstStrided{p.pairslh + 1, 2};
    q.findex = p.findex;
    q.nub = p.nub;
    if (p.joints != nullptr && p.nj > 0) {
        const auto nj = static_cast<std::size_t>(p.nj);
        if (block_row_.size() < nj + 1) block_row_.resize(nj + 1);
        if (block_body_.size() < 2 * nj) block_body_.resize(2 * nj);
        block_row_[nj] = p.m;
        for (int k = 0; k < p.nj; ++k) {
            block_row_[k] = p.joints[k].row;
            block_body_[2 * k] = p.joints[k].body[0];
            block_body_[2 * k + 1] = p.joints[k].body[1];
        }
        q.num_blocks = p.nj;
        q.block_row = block_row_.data();
        q.block_body = block_body_.data();
    }
    return q;
}

int first_untiled_joint(const dMLCP& p) {
    for (int k = 0; k < p.nj; ++k) {
        const int expected = k == 0 ? 0 : p.joints[k - 1].row + p.joints[k - 1].m;
        if (p.joints[k].row != expected || p.joints[k].m <= 0) return k;
    }
    return -1;
}

std::string structure_defect(const dMLCP& island) {
    if (island.joints == nullptr || island.nj <= 0) return "the island has no joints";
    if (const int k = first_untiled_joint(island); k >= 0)
        return "joint " + std::to_string(k) + "'s rows do not follow the previous joint's";
    const dMLCPJoint& last = island.joints[island.nj - 1];
    if (last.row + last.m != island.m)
        return "the joints' rows end at " + std::to_string(last.row + last.m) + ", not at m = " + std::to_string(island.m);
    for (int k = 0; k < island.nj; ++k)
        for (int body : island.joints[k].body)
            if (body < -1 || body >= island.nb)
                return "joint " + std::to_string(k) + ": body " + std::to_string(body) + " outside [-1, " +
                       std::to_string(island.nb) + ")";
    return {};
}

}  // namespace ode_bpp::ode
