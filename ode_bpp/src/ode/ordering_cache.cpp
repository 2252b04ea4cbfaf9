#include "ode/ordering_cache.h"

#include <iterator>

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

const OrderingCache::Remembered* OrderingCache::find(const Signature& structure, std::uint64_t step) {
    if (step != swept_) forget_older_than(step);
    const auto it = orderings_.find(structure);
    if (it == orderings_.end()) return nullptr;
    it->second.seen = step;
    return &it->second;
}

void OrderingCache::store(const Signature& structure, const std::vector<int>& ordering, bool settled,
                          std::uint64_t step) {
    if (orderings_.size() >= kMaxIslands && orderings_.count(structure) == 0) orderings_.clear();
    Remembered& entry = orderings_[structure];
    entry.ordering = ordering;
    entry.settled = settled;
    entry.seen = step;
}

void OrderingCache::forget_older_than(std::uint64_t step) {
    swept_ = step;
    for (auto it = orderings_.begin(); it != orderings_.end();)
        it = step > it->second.seen + kKeepSteps ? orderings_.erase(it) : std::next(it);
}

}  // namespace ode_bpp
