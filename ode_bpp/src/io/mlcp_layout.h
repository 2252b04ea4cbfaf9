// Byte layout of an MLCP file, version 1 (docs/mlcp-format.md), and the structural checks
// shared by the reader (which reports byte offsets) and the writer (which reports fields).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace ode_bpp::io {

inline constexpr char kMagic[11] = {'O', 'D', 'E', 'B', 'P', 'P', 'M', 'L', 'C', 'P', '\0'};
inline constexpr std::size_t kMagicBytes = sizeof(kMagic);

/// Offsets of the fixed header fields.
namespace header {
inline constexpr std::size_t kVersion = 11;
inline constexpr std::size_t kFlags = 15;
inline constexpr std::size_t kN = 19;
inline constexpr std::size_t kNub = 23;
inline constexpr std::size_t kNumBlocks = 27;
inline constexpr std::size_t kNumBodies = 31;
inline constexpr std::size_t kMetaBytes = 35;
inline constexpr std::size_t kReserved = 39;
inline constexpr std::size_t kSize = 40;  ///< A starts here, 8-byte aligned
}  // namespace header

inline constexpr std::size_t kChecksumBytes = 4;

/// Bits of the flags field; every other bit must be zero.
namespace flag {
inline constexpr std::uint32_t kFindex = 1u << 0;
inline constexpr std::uint32_t kBlocks = 1u << 1;
inline constexpr std::uint32_t kReferenceX = 1u << 2;
inline constexpr std::uint32_t kMetadata = 1u << 3;
inline constexpr std::uint32_t kKnown = kFindex | kBlocks | kReferenceX | kMetadata;
}  // namespace flag

/// The decoded fixed header.
struct Header {
    std::uint32_t version = 0;
    std::uint32_t flags = 0;
    std::uint32_t n = 0;
    std::uint32_t nub = 0;
    std::uint32_t num_blocks = 0;
    std::uint32_t num_bodies = 0;
    std::uint32_t meta_bytes = 0;
};

/// Start offsets of every section, in file order, and the total size. All in 64 bits; only
/// computed once n is known to fit the file, so nothing overflows.
struct Layout {
    std::uint64_t a = header::kSize;
    std::uint64_t b = 0, lo = 0, hi = 0;
    std::uint64_t findex = 0, block_row = 0, block_body = 0;
    std::uint64_t x = 0, meta = 0, checksum = 0, total = 0;
};

/// Number of stored entries of A's lower triangle, n(n+1)/2 (fits 64 bits for any uint32 n).
inline std::uint64_t triangle_entries(std::uint64_t n) { return n * (n + 1) / 2; }

Layout layout_of(const Header& h);


}  // namespace ode_bpp::io
