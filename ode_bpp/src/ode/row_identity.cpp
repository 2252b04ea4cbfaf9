#include "ode/row_identity.h"

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

void RowStateMemory::enter_step(std::uint64_t step) {
    if (steps_ > 0 && step == last_world_step_) return;
    last_world_step_ = step;
    ++steps_;
    for (auto it = rows_.begin(); it != rows_.end();) {
        if (steps_ - it->second.seen > kKeepSteps) it = rows_.erase(it);
        else ++it;
    }
}

bool RowStateMemory::recall(const std::vector<RowKey>& keys, std::uint64_t step, std::vector<RowState>& states) {
    enter_step(step);
    states.assign(keys.size(), RowState::Free);
    bool any = false;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const auto it = rows_.find(keys[i]);
        if (it == rows_.end()) continue;
        states[i] = it->second.state;
        any = true;
    }
    return any;
}

void RowStateMemory::remember(const std::vector<RowKey>& keys, std::uint64_t step, const std::vector<RowState>& states) {
    if (keys.size() != states.size()) return;
    enter_step(step);
    for (std::size_t i = 0; i < keys.size(); ++i) rows_[keys[i]] = Entry{states[i], steps_};
}

}  // namespace ode_bpp
