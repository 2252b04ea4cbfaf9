// Shared helpers of the test_io_* suites: a small structured MLCP, byte surgery on file
// images, and the documented layout of format version 1 (docs/mlcp-format.md), written out
// here independently of the library so that the tests check the library against the spec.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "ode_bpp/io.h"

namespace io_test {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// Byte offsets of format version 1, straight from docs/mlcp-format.md.
struct SpecLayout {
    std::size_t a, b, lo, hi, findex, block_row, block_body, x, meta, checksum, total;
    SpecLayout(std::size_t n, std::size_t num_blocks, bool has_findex, bool has_blocks, bool has_x,
               std::size_t meta_bytes) {
        a = 40;
        b = a + 8 * (n * (n + 1) / 2);
        lo = b + 8 * n;
        hi = lo + 8 * n;
        findex = hi + 8 * n;
        block_row = findex + (has_findex ? 4 * n : 0);
        block_body = block_row + (has_blocks ? 4 * (num_blocks + 1) : 0);
        x = block_body + (has_blocks ? 8 * num_blocks : 0);
        meta = x + (has_x ? 8 * n : 0);
        checksum = meta + meta_bytes;
        total = checksum + 4;
    }
};

/// An SPD MLCP of n rows (n >= 6) with every feature of the format: an unbounded leading
/// block, contacts with friction rows, a two-sided bound, +-inf bounds, joint blocks of
/// 1..3 rows over 4 bodies, a reference x and metadata.
inline ode_bpp::MlcpFile make_sample(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    ode_bpp::MlcpFile f;
    f.n = n;
    f.nub = 2;
    const std::size_t nn = static_cast<std::size_t>(n);
    std::vector<double> M(nn * nn);
    for (double& m : M) m = u(rng);
    f.A.assign(nn * nn, 0.0);
    for (std::size_t i = 0; i < nn; ++i)
        for (std::size_t j = 0; j < nn; ++j) {
            double s = (i == j) ? double(n) : 0.0;
            for (std::size_t k = 0; k < nn; ++k) s += M[i * nn + k] * M[j * nn + k];
            f.A[i * nn + j] = s;
        }
    f.findex.assign(nn, -1);
    for (int i = 0; i < n; ++i) {
        f.b.push_back(u(rng));
        f.x_ref.push_back(u(rng));
        if (i < 2) {
            f.lo.push_back(-kInf), f.hi.push_back(kInf);
        } else if (i % 3 == 2) {
            f.lo.push_back(0.0), f.hi.push_back(kInf);   // contact normal
        } else {
            f.lo.push_back(-0.5), f.hi.push_back(0.5);   // friction, mu = 0.5
            f.findex[static_cast<std::size_t>(i)] = i - (i % 3 == 0 ? 1 : 2);
        }
    }
    f.num_bodies = 4;
    for (int r = 0, k = 0; r < n; ++k) {
        f.block_row.push_back(r);
        f.block_body.push_back(k % 4);
        f.block_body.push_back(k % 3 == 0 ? -1 : (k + 1) % 4);
        r += 1 + k % 3;
        if (r > n) r = n;
    }
    f.block_row.push_back(n);
    f.meta.set("scene", "unit test");
    f.meta.set("frame", "17");
    f.meta.set("cfm", "1e-10");
    return f;
}

inline std::vector<std::uint8_t> encode(const ode_bpp::MlcpFile& f) {
    std::vector<std::uint8_t> bytes;
    std::string error;
    if (!ode_bpp::encode_mlcp(f, &bytes, &error)) throw std::runtime_error("encode failed: " + error);
    return bytes;
}

inline void put_u32(std::vector<std::uint8_t>& bytes, std::size_t offset, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) bytes[offset + k] = static_cast<std::uint8_t>(v >> (8 * k));
}

inline void put_i32(std::vector<std::uint8_t>& bytes, std::size_t offset, std::int32_t v) {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    put_u32(bytes, offset, u);
}

/// Recomputes the trailing CRC-32, so that a deliberate edit reaches the checks behind it.
inline void reseal(std::vector<std::uint8_t>& bytes) {
    put_u32(bytes, bytes.size() - 4, ode_bpp::crc32(bytes.data(), bytes.size() - 4));
}

inline ode_bpp::ReadResult read(const std::vector<std::uint8_t>& bytes, const std::string& name = "sample.mlcp") {
    return ode_bpp::read_mlcp_bytes(bytes.data(), bytes.size(), name);
}

/// A small RFC 4180 reader (quoted fields, doubled quotes, embedded newlines): the oracle
/// for the report's CSV. Returns the records, each a list of fields.
inline std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
    std::vector<std::vector<std::string>> records;
    std::vector<std::string> record;
    std::string field;
    bool quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                field += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            record.push_back(field);
            field.clear();
        } else if (c == '\n') {
            record.push_back(field);
            field.clear();
            records.push_back(record);
            record.clear();
        } else {
            field += c;
        }
    }
    return records;
}

/// tests/data, found from this source file's location.
inline std::filesystem::path data_dir() {
    return std::filesystem::path(__FILE__).parent_path().parent_path() / "data";
}

}  // namespace io_test
