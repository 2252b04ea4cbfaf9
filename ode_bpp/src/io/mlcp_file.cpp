// Metadata, MlcpFile::view and the checksum.
#include <array>

#include "ode_bpp/io.h"

namespace ode_bpp {

void Metadata::set(const std::string& key, const std::string& value) {
    for (auto& entry : entries) {
        if (entry.first == key) {
            entry.second = value;
            return;
        }
    }
    entries.emplace_back(key, value);
}

const std::string* Metadata::find(std::string_view key) const {
    for (const auto& entry : entries)
        if (entry.first == key) return &entry.second;
    return nullptr;
}

bool Metadata::valid_key(std::string_view key) {
    if (key.empty()) return false;
    for (char c : key) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                        c == '_' || c == '.' || c == '-';
        if (!ok) return false;
    }
    return true;
}

bool Metadata::valid_value(std::string_view value) {
    return value.find('\n') == std::string_view::npos && value.find('\0') == std::string_view::npos;
}

Problem MlcpFile::view() const {
    Problem p;
    p.n = n;
    p.A = A.data();
    p.lda = n;
    p.b = {b.data(), 1};
    p.lo = {lo.data(), 1};
    p.hi = {hi.data(), 1};
    p.findex = findex.empty() ? nullptr : findex.data();
    p.nub = nub;
    p.num_blocks = num_blocks();
    p.block_row = block_row.empty() ? nullptr : block_row.data();
    p.block_body = block_body.empty() ? nullptr : block_body.data();
    return p;
}

namespace {
// Table of the reflected IEEE polynomial 0xEDB88320, one entry per byte value.
std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t i = 0; i < 256; ++i) {
        std::uint32_t c = i;
        for (int bit = 0; bit < 8; ++bit) c = (c & 1u) ? (0xEDB88320u ^ (c >> 1)) : (c >> 1);
        table[i] = c;
    }
    return table;
}
}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size) {
    static const std::array<std::uint32_t, 256> table = make_crc_table();
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < size; ++i) c = table[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

}  // namespace ode_bpp
