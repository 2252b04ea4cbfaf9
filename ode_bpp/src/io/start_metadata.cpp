// A warm start in a file's metadata (docs/mlcp-format.md, "Metadata"): the index set as one
// character per row and the ordering as decimal permutation entries.
//
// Index space: the file's own (original) row order for the states; the ordering maps it as
// Start::ordering does (perm[new] = old).
#include <algorithm>
#include <cstdlib>
#include <string>

#include "ode_bpp/io.h"

namespace ode_bpp {

namespace {

constexpr char kFree = 'F', kAtLo = 'L', kAtHi = 'H';

char state_char(RowState s) { return s == RowState::AtLo ? kAtLo : s == RowState::AtHi ? kAtHi : kFree; }

std::nullopt_t refuse(std::string* error, const std::string& reason) {
    if (error != nullptr) *error = reason;
    return std::nullopt;
}

std::optional<std::vector<RowState>> decode_states(const std::string& text, int n, std::string* error) {
    if (static_cast<long>(text.size()) != n)
        return refuse(error, std::string(kWarmStartKey) + " has " + std::to_string(text.size()) + " rows, n = " +
                                 std::to_string(n));
    std::vector<RowState> states(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c != kFree && c != kAtLo && c != kAtHi)
            return refuse(error, std::string(kWarmStartKey) + ": row " + std::to_string(i) + " is '" + c +
                                     "', not F, L or H");
        states[i] = c == kAtLo ? RowState::AtLo : c == kAtHi ? RowState::AtHi : RowState::Free;
    }
    return states;
}

/// One decimal entry of the ordering in [0, n), from text[pos] up to the next comma or the end.
std::optional<int> ordering_entry(const std::string& text, std::size_t& pos, int n) {
    const std::size_t end = std::min(text.find(',', pos), text.size());
    const std::string digits = text.substr(pos, end - pos);
    pos = end + 1;
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 10)
        return std::nullopt;
    const long v = std::strtol(digits.c_str(), nullptr, 10);
    if (v >= n) return std::nullopt;
    return static_cast<int>(v);
}

std::optional<std::vector<int>> decode_ordering(const std::string& text, int n, std::string* error) {
    std::vector<int> order;
    std::vector<char> seen(static_cast<std::size_t>(n), 0);
    for (std::size_t pos = 0; pos <= text.size() && static_cast<int>(order.size()) <= n;) {
        const std::optional<int> entry = ordering_entry(text, pos, n);
        if (!entry || seen[*entry])
            return refuse(error, std::string(kOrderingKey) + ": entry " + std::to_string(order.size()) +
                                     " is not a new row in [0, " + std::to_string(n) + ")");
        seen[*entry] = 1;
        order.push_back(*entry);
    }
    if (static_cast<int>(order.size()) != n)
        return refuse(error, std::string(kOrderingKey) + " has " + std::to_string(order.size()) + " entries, n = " +
                                 std::to_string(n));
    return order;
}

}  // namespace

void set_start_metadata(const Start& start, Metadata& meta) {
    if (!start.states.empty()) {
        std::string text;
        text.reserve(start.states.size());
        for (RowState s : start.states) text.push_back(state_char(s));
        meta.set(kWarmStartKey, text);
    }
    if (!start.ordering.empty()) {
        std::string text;
        for (std::size_t k = 0; k < start.ordering.size(); ++k)
            text += (k == 0 ? "" : ",") + std::to_string(start.ordering[k]);
        meta.set(kOrderingKey, text);
    }
}

std::optional<Start> start_from_metadata(const Metadata& meta, int n, std::string* error) {
    Start start;
    if (const std::string* text = meta.find(kWarmStartKey)) {
        auto states = decode_states(*text, n, error);
        if (!states) return std::nullopt;
        start.states = std::move(*states);
    }
    if (const std::string* text = meta.find(kOrderingKey)) {
        auto order = decode_ordering(*text, n, error);
        if (!order) return std::nullopt;
        start.ordering = std::move(*order);
    }
    return start;
}

}  // namespace ode_bpp
