// Little-endian encoding of the file's scalar types, independent of the host's byte order.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace ode_bpp::io {

inline std::uint32_t load_u32(const std::uint8_t* p) {
    return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) |
           (std::uint32_t{p[3]} << 24);
}

inline std::int32_t load_i32(const std::uint8_t* p) {
    const std::uint32_t u = load_u32(p);
    std::int32_t v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

inline double load_f64(const std::uint8_t* p) {
    const std::uint64_t u = std::uint64_t{load_u32(p)} | (std::uint64_t{load_u32(p + 4)} << 32);
    double v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

/// Appends little-endian values to a byte vector.
class ByteSink {
public:
    explicit ByteSink(std::vector<std::uint8_t>* out) : out_(out) {}
    void u8(std::uint8_t v) { out_->push_back(v); }
    void u32(std::uint32_t v) {
        for (int s = 0; s < 32; s += 8) out_->push_back(static_cast<std::uint8_t>(v >> s));
    }
    void i32(std::int32_t v) {
        std::uint32_t u;
        std::memcpy(&u, &v, sizeof u);
        u32(u);
    }
    void f64(double v) {
        std::uint64_t u;
        std::memcpy(&u, &v, sizeof u);
        u32(static_cast<std::uint32_t>(u));
        u32(static_cast<std::uint32_t>(u >> 32));
    }
    void bytes(const void* data, std::size_t size) {
        const auto* p = static_cast<const std::uint8_t*>(data);
        out_->insert(out_->end(), p, p + size);
    }

private:
    std::vector<std::uint8_t>* out_;
};

}  // namespace ode_bpp::io
