// Helpers shared by the fuzz targets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ode_bpp/io.h"

namespace fuzz {

/// The input with its last 4 bytes replaced by the CRC-32 of the rest. Random mutations
/// almost never keep the checksum right, so without this the fuzzer would only ever reach
/// the checksum test; with it, it explores the checks and the solver behind it.
inline std::vector<std::uint8_t> resealed(const std::uint8_t* data, std::size_t size) {
    std::vector<std::uint8_t> bytes(data, data + size);
    if (size < 4) return bytes;
    const std::uint32_t crc = ode_bpp::crc32(bytes.data(), size - 4);
    for (int k = 0; k < 4; ++k) bytes[size - 4 + k] = static_cast<std::uint8_t>(crc >> (8 * k));
    return bytes;
}

/// Stops the run where libFuzzer records the input, when an invariant fails.
inline void require(bool invariant) {
    if (!invariant) __builtin_trap();
}

}  // namespace fuzz
