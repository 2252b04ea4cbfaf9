#include "ode/row_identity.h"

#include <algorithm>
#include <atomic>
#include <functional>

namespace ode_bpp {

namespace {

void mix(std::size_t& h, std::size_t v) { h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2); }

/// The end of the run of keys from `begin` that belong to one joint.
std::size_t joint_end(const std::vector<RowKey>& keys, std::size_t begin) {
    const JointKey joint(keys[begin]);
    std::size_t end = begin + 1;
    while (end < keys.size() && JointKey(keys[end]) == joint) ++end;
    return end;
}

}  // namespace

std::size_t JointKeyHash::operator()(const JointKey& k) const {
    std::size_t h = std::hash<const void*>()(k.a);
    mix(h, std::hash<const void*>()(k.b));
    mix(h, static_cast<std::size_t>(k.ordinal));
    return h;
}

namespace {

/// Numbers each contact among the island's contacts of the same geom pair, in joint order:
/// sorted by pair, then by joint (the order of a stable sort by pair, without the buffer that
/// std::stable_sort allocates at every call), then counted. O(c log c).
void number_contacts(std::vector<ContactSlot>& contacts) {
    std::sort(contacts.begin(), contacts.end(), [](const ContactSlot& x, const ContactSlot& y) {
        const std::less<const void*> less;
        if (x.g1 != y.g1) return less(x.g1, y.g1);
        if (x.g2 != y.g2) return less(x.g2, y.g2);
        return x.joint < y.joint;
    });
    for (std::size_t k = 0; k < contacts.size(); ++k) {
        const bool same_pair = k > 0 && contacts[k].g1 == contacts[k - 1].g1 && contacts[k].g2 == contacts[k - 1].g2;
        contacts[k].ordinal = same_pair ? contacts[k - 1].ordinal + 1 : 0;
    }
}

}  // namespace

void row_keys(const dMLCP& problem, std::vector<RowKey>& keys, std::vector<ContactSlot>& contacts) {
    keys.assign(static_cast<std::size_t>(problem.m), RowKey{});
    contacts.clear();
    for (int j = 0; j < problem.nj; ++j)
        if (const dContactGeom* c = problem.joints[j].contact) contacts.push_back({c->g1, c->g2, j, 0});
    number_contacts(contacts);
    for (const ContactSlot& c : contacts) {
        const dMLCPJoint& joint = problem.joints[c.joint];
        for (int r = 0; r < joint.m; ++r) keys[static_cast<std::size_t>(joint.row + r)] = {c.g1, c.g2, c.ordinal, r};
    }
    for (int j = 0; j < problem.nj; ++j) {
        const dMLCPJoint& joint = problem.joints[j];
        if (joint.contact != nullptr) continue;
        for (int r = 0; r < joint.m; ++r) keys[static_cast<std::size_t>(joint.row + r)] = {joint.joint, nullptr, 0, r};
    }
}

std::uint64_t RowStateMemory::fresh_id() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

RowStateMemory::RowStateMemory(const RowStateMemory& other)
    : joints_(other.joints_), last_world_step_(other.last_world_step_), steps_(other.steps_) {}

RowStateMemory& RowStateMemory::operator=(const RowStateMemory& other) {
    joints_ = other.joints_;
    last_world_step_ = other.last_world_step_;
    steps_ = other.steps_;
    id_ = fresh_id();
    return *this;
}

void RowStateMemory::enter_step(std::uint64_t step) {
    if (steps_ > 0 && step == last_world_step_) return;
    last_world_step_ = step;
    ++steps_;
    for (auto it = joints_.begin(); it != joints_.end();) {
        if (steps_ - it->second.seen > kKeepSteps) it = joints_.erase(it);
        else ++it;
    }
}

bool RowStateMemory::recall(const std::vector<RowKey>& keys, std::uint64_t step, std::vector<RowState>& states,
                            Slots* slots) {
    enter_step(step);
    states.assign(keys.size(), RowState::Free);
    if (slots != nullptr) {
        slots->joints_.clear();
        slots->memory_ = id_;
        slots->steps_ = steps_;
    }
    bool any = false;
    for (std::size_t begin = 0, end; begin < keys.size(); begin = end) {
        end = joint_end(keys, begin);
        const Entry* entry = nullptr;
        if (slots != nullptr) {
            Entry& made = joints_[JointKey(keys[begin])];  // empty until remember stores into it
            slots->joints_.push_back({end, &made});
            entry = &made;
        } else {
            const auto it = joints_.find(JointKey(keys[begin]));
            if (it == joints_.end()) continue;
            entry = &it->second;
        }
        const std::vector<Row>& rows = entry->rows;
        for (std::size_t i = begin; i < end; ++i) {
            const auto r = static_cast<std::size_t>(keys[i].row);
            if (r >= rows.size() || !is_kept(rows[r])) continue;
            states[i] = rows[r].state;
            any = true;
        }
    }
    return any;
}

void RowStateMemory::store(Entry& entry, const std::vector<RowKey>& keys, std::size_t begin, std::size_t end,
                           const std::vector<RowState>& states) {
    entry.seen = steps_;
    for (std::size_t i = begin; i < end; ++i) {
        const auto r = static_cast<std::size_t>(keys[i].row);
        if (r >= entry.rows.size()) entry.rows.resize(r + 1);
        entry.rows[r] = Row{states[i], steps_};
    }
}

void RowStateMemory::remember(const std::vector<RowKey>& keys, std::uint64_t step, const std::vector<RowState>& states,
                              const Slots* slots) {
    if (keys.size() != states.size()) return;
    enter_step(step);
    const bool filled = slots != nullptr && slots->memory_ == id_ && slots->steps_ == steps_ &&
                        !slots->joints_.empty() && slots->joints_.back().end == keys.size();
    if (filled) {
        std::size_t begin = 0;
        for (const Slots::Joint& joint : slots->joints_) {
            store(*joint.entry, keys, begin, joint.end, states);
            begin = joint.end;
        }
        return;
    }
    for (std::size_t begin = 0, end; begin < keys.size(); begin = end) {
        end = joint_end(keys, begin);
        store(joints_[JointKey(keys[begin])], keys, begin, end, states);
    }
}

std::size_t RowStateMemory::size() const {
    std::size_t held = 0;
    for (const auto& [joint, entry] : joints_)
        for (const Row& row : entry.rows) held += is_kept(row) ? 1 : 0;
    return held;
}

}  // namespace ode_bpp
