#include "ode/row_identity.h"

#include <algorithm>
#include <functional>
#include <map>
#include <utility>

namespace ode_bpp {

std::size_t RowKeyHash::operator()(const RowKey& k) const {
    std::size_t h = std::hash<const void*>()(k.a);
    auto mix = [&h](std::size_t v) { h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2); };
    mix(std::hash<const void*>()(k.b));
    mix(static_cast<std::size_t>(k.ordinal));
    mix(static_cast<std::size_t>(k.row));
    return h;
}

void row_keys(const dMLCP& problem, std::vector<RowKey>& keys) {
    keys.assign(static_cast<std::size_t>(problem.m), RowKey{});
    std::map<std::pair<const void*, const void*>, int> contacts_per_pair;
    for (int j = 0; j < problem.nj; ++j) {
        const dMLCPJoint& joint = problem.joints[j];
        RowKey key;
        if (joint.contact != nullptr) {
            key.a = joint.contact->g1;
            key.b = joint.contact->g2;
            key.ordinal = contacts_per_pair[{key.a, key.b}]++;
        } else {
            key.a = joint.joint;
        }
        for (int r = 0; r < joint.m; ++r) {
            key.row = r;
            keys[static_cast<std::size_t>(joint.row + r)] = key;
        }
    }
}

bool RowStateMemory::recall(const std::vector<RowKey>& keys, std::vector<RowState>& states) const {
    states.assign(keys.size(), RowState::Free);
    bool any = false;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        auto it = current_.find(keys[i]);
        if (it == current_.end()) {
            it = previous_.find(keys[i]);
            if (it == previous_.end()) continue;
        }
        states[i] = it->second;
        any = true;
    }
    return any;
}

void RowStateMemory::remember(const std::vector<RowKey>& keys, const std::vector<RowState>& states) {
    if (keys.size() != states.size()) return;
    // a generation holds about one step's rows: beyond twice that, start a new one
    rows_per_generation_ = std::max(rows_per_generation_, keys.size());
    if (current_.size() + keys.size() > 2 * rows_per_generation_ + 64) {
        previous_ = std::move(current_);
        current_.clear();
    }
    for (std::size_t i = 0; i < keys.size(); ++i) current_[keys[i]] = states[i];
}

}  // namespace ode_bpp
