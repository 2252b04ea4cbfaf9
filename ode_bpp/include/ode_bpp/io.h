// ode_bpp/io.h: MLCP problem files (format version 1, specified byte by byte in
// docs/mlcp-format.md).
//
// A file holds one MLCP as ODE builds it (see solver.h): A's lower triangle, b, lo, hi,
// optional findex, optional joint blocks, an optional reference solution x, optional
// key=value metadata, and a CRC-32 of everything before it. Every index space here is the
// original row order of the problem; nothing is permuted.
//
// Readers never throw and never trust sizes: every count in the header is checked against
// the number of bytes actually present before anything is allocated.
#pragma once

#include "ode_bpp/export.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ode_bpp/solver.h"

namespace ode_bpp {

/// The format version this library reads and writes.
inline constexpr std::uint32_t kMlcpFormatVersion = 1;

/// Ordered key=value text attached to a problem. Keys are non-empty and use only
/// [A-Za-z0-9_.-]; values contain neither '\n' nor '\0'; keys are unique.
/// Conventional keys: scene, frame, island, cfm, erp, step_size, solver, warm_start, ordering.
struct ODE_BPP_API Metadata {
    std::vector<std::pair<std::string, std::string>> entries;  ///< (key, value), in file order

    /// Sets key to value, replacing an existing entry in place or appending a new one.
    void set(const std::string& key, const std::string& value);
    /// The value of key, or null if absent.
    const std::string* find(std::string_view key) const;

    /// True when key obeys the rules above (non-empty, [A-Za-z0-9_.-] only).
    static bool valid_key(std::string_view key);
    /// True when value holds neither '\n' nor '\0'.
    static bool valid_value(std::string_view value);
};

/// One MLCP that owns its data.
struct ODE_BPP_API MlcpFile {
    int n = 0;    ///< rows
    int nub = 0;  ///< leading unbounded rows (Problem::nub)
    /// n x n row-major with lda = n, symmetric: the file's lower triangle mirrored.
    std::vector<double> A;
    std::vector<double> b, lo, hi;   ///< n each; lo/hi may be -inf/+inf
    std::vector<int> findex;         ///< n entries, or empty when the problem has no friction rows
    std::vector<int> block_row;      ///< num_blocks + 1 entries, or empty (no block structure)
    std::vector<int> block_body;     ///< 2 * num_blocks entries, -1 for the static environment
    int num_bodies = 0;              ///< block_body entries lie in [-1, num_bodies)
    std::vector<double> x_ref;       ///< n entries of a reference solution, or empty
    Metadata meta;                   ///< where the problem came from (scene, frame, cfm, ...)

    /// Row blocks (joints) of the block structure: block_row.size() - 1, or 0 without one.
    int num_blocks() const { return block_row.empty() ? 0 : static_cast<int>(block_row.size()) - 1; }
    /// A view for solve(); valid while this object is alive and unchanged.
    Problem view() const;
};

/// Outcome of reading: on failure error is "<name>: offset <k>: <reason>", where k is the
/// byte offset of the first offending field, and file is empty.
struct ReadResult {
    bool ok = false;
    MlcpFile file;
    std::string error;
};

/// Reads and validates a whole file (structure only: NaN or lo > hi are left to solve()).
ODE_BPP_API ReadResult read_mlcp(const std::string& path);
/// Same on an in-memory image of size bytes; name is used in error messages only.
ODE_BPP_API ReadResult read_mlcp_bytes(const std::uint8_t* data, std::size_t size, const std::string& name);

/// Copies a Problem (strided vectors, any lda) into an owning MlcpFile; x_ref is n contiguous
/// doubles or null. num_bodies becomes 1 + the largest body index. Fails, with a message
/// naming the field, when the structure is invalid (same checks as the reader).
/// error (here and below): out, may be null; the reason, set only on failure.
ODE_BPP_API std::optional<MlcpFile> copy_problem(const Problem& problem, const Metadata& meta,
                                     const double* x_ref, std::string* error);

/// Serializes a file image (version kMlcpFormatVersion) into *bytes (out, replaced). Fails on an
/// invalid structure or a null bytes.
ODE_BPP_API bool encode_mlcp(const MlcpFile& file, std::vector<std::uint8_t>* bytes, std::string* error);

/// Writes the file through a temporary and a rename, so readers never see half a file.
ODE_BPP_API bool write_mlcp(const std::string& path, const MlcpFile& file, std::string* error);
/// copy_problem followed by write_mlcp.
ODE_BPP_API bool write_mlcp(const std::string& path, const Problem& problem, const Metadata& meta,
                const double* x_ref, std::string* error);
/// The metadata keys that carry a warm start (docs/mlcp-format.md, "Metadata"): `warm_start`,
/// one character per row (F free, L at lo, H at hi), and `ordering`, Start::ordering's entries in
/// decimal, comma-separated. A capture writes them so that a solve of the file can start where
/// the solve inside ODE started.
inline constexpr const char* kWarmStartKey = "warm_start";
inline constexpr const char* kOrderingKey = "ordering";

/// Writes `start` into meta (each key only when its part is non-empty; an empty part removes
/// nothing that is there).
ODE_BPP_API void set_start_metadata(const Start& start, Metadata& meta);

/// The Start a file's metadata names for its n rows: empty parts where a key is absent. Fails,
/// with a message naming the key, on a value of another length than n, an unknown state
/// character, or an ordering that is not a permutation of 0 .. n-1.
ODE_BPP_API std::optional<Start> start_from_metadata(const Metadata& meta, int n, std::string* error);

/// CRC-32 (IEEE 802.3, reflected, as zlib's crc32) of size bytes: the file's checksum.
ODE_BPP_API std::uint32_t crc32(const std::uint8_t* data, std::size_t size);

}  // namespace ode_bpp
