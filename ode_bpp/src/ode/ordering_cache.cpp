#include "ode/ordering_cache.h"

namespace ode_bpp {

void OrderingCache::signature(const dMLCP& p, const RowKey& first_row, Signature& structure) {
    structure.clear();
    structure.reserve(5 + 3 * static_cast<std::size_t>(p.nj));
    structure.push_back(reinterpret_cast<std::intptr_t>(first_row.a));
    structure.push_back(reinterpret_cast<std::intptr_t>(first_row.b));
    structure.push_back(first_row.ordinal);
    structure.push_back(p.m);
    for (int k = 0; k < p.nj; ++k) {
        structure.push_back(p.joints[k].row);
        structure.push_back(p.joints[k].body[0]);
        structure.push_back(p.joints[k].body[1]);
    }
}

const std::vector<int>* OrderingCache::find(const Signature& structure) const {
    const auto it = orderings_.find(structure);
    return it == orderings_.end() ? nullptr : &it->second;
}

void OrderingCache::store(const Signature& structure, const std::vector<int>& ordering) {
    if (orderings_.size() >= kMaxIslands && orderings_.count(structure) == 0) orderings_.clear();
    orderings_[structure] = ordering;
}

}  // namespace ode_bpp
