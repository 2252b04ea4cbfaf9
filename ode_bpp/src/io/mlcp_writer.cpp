// Writing MLCP files, from a Problem, from ODE's dMLCP, or from an MlcpFile.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <new>

#include "io/byte_codec.h"
#include "linalg/symmetric_rows.h"
#include "io/mlcp_layout.h"
#include "structure_rules.h"
#include "ode_bpp/io.h"

namespace ode_bpp {
namespace {

namespace flag = io::flag;

bool fail(std::string* error, const std::string& reason) {
    if (error) *error = reason;
    return false;
}

std::nullopt_t no_file(std::string* error, const std::string& reason) {
    if (error) *error = reason;
    return std::nullopt;
}

std::optional<std::string> check_sizes(const MlcpFile& f) {
    const std::size_t n = static_cast<std::size_t>(f.n);
    if (f.n < 0) return "n = " + std::to_string(f.n) + " is negative";
    if (f.nub < 0 || f.nub > f.n) return "nub = " + std::to_string(f.nub) + " outside 0..n = " + std::to_string(f.n);
    if (f.A.size() != n * n) return "A has " + std::to_string(f.A.size()) + " entries, n*n needed";
    if (f.b.size() != n || f.lo.size() != n || f.hi.size() != n) return "b, lo and hi must have n entries each";
    if (!f.findex.empty() && f.findex.size() != n) return "findex must be empty or have n entries";
    if (!f.x_ref.empty() && f.x_ref.size() != n) return "x_ref must be empty or have n entries";
    if (f.block_row.empty() && (!f.block_body.empty() || f.num_bodies != 0))
        return "block_body or num_bodies given without block_row";
    if (!f.block_row.empty() && f.block_body.size() != 2 * (f.block_row.size() - 1))
        return "block_body must have 2 * num_blocks entries";
    if (f.num_bodies < 0) return "num_bodies = " + std::to_string(f.num_bodies) + " is negative";
    return std::nullopt;
}

std::optional<std::string> check_metadata(const Metadata& meta) {
    std::uint64_t bytes = 0;
    for (std::size_t i = 0; i < meta.entries.size(); ++i) {
        const auto& [key, value] = meta.entries[i];
        if (!Metadata::valid_key(key)) return "metadata key \"" + key + "\" invalid (use letters, digits, '_', '.', '-')";
        if (!Metadata::valid_value(value)) return "metadata value of \"" + key + "\" contains a newline or NUL";
        for (std::size_t j = 0; j < i; ++j)
            if (meta.entries[j].first == key) return "duplicate metadata key \"" + key + "\"";
        bytes += key.size() + value.size() + 2;
    }
    if (bytes > std::numeric_limits<std::uint32_t>::max()) return "metadata larger than 4 GiB";
    return std::nullopt;
}

// The reader's structural checks, reported by field name instead of byte offset.
std::optional<std::string> validate(const MlcpFile& f) {
    if (auto e = check_sizes(f)) return e;
    if (!f.findex.empty())
        if (auto issue = check_findex(f.findex.data(), f.n)) return issue->reason;
    if (!f.block_row.empty()) {
        if (auto issue = check_block_row(f.block_row.data(), f.num_blocks(), f.n)) return issue->reason;
        if (auto issue = check_block_body(f.block_body.data(), f.num_blocks(), f.num_bodies))
            return issue->reason;
    }
    return check_metadata(f.meta);
}

std::string metadata_text(const Metadata& meta) {
    std::string text;
    for (const auto& [key, value] : meta.entries) text += key + "=" + value + "\n";
    return text;
}

std::uint32_t flags_of(const MlcpFile& f) {
    std::uint32_t flags = 0;
    if (!f.findex.empty()) flags |= flag::kFindex;
    if (!f.block_row.empty()) flags |= flag::kBlocks;
    if (!f.x_ref.empty()) flags |= flag::kReferenceX;
    if (!f.meta.entries.empty()) flags |= flag::kMetadata;
    return flags;
}

void encode_header(const MlcpFile& f, std::uint32_t meta_bytes, io::ByteSink& out) {
    out.bytes(io::kMagic, io::kMagicBytes);
    out.u32(kMlcpFormatVersion);
    out.u32(flags_of(f));
    out.u32(static_cast<std::uint32_t>(f.n));
    out.u32(static_cast<std::uint32_t>(f.nub));
    out.u32(static_cast<std::uint32_t>(f.num_blocks()));
    out.u32(static_cast<std::uint32_t>(f.num_bodies));
    out.u32(meta_bytes);
    out.u8(0);  // reserved: aligns A to 8 bytes
}

void encode_body(const MlcpFile& f, const std::string& meta, io::ByteSink& out) {
    const std::size_t n = static_cast<std::size_t>(f.n);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j <= i; ++j) out.f64(f.A[i * n + j]);
    for (double v : f.b) out.f64(v);
    for (double v : f.lo) out.f64(v);
    for (double v : f.hi) out.f64(v);
    for (int v : f.findex) out.i32(v);
    for (int v : f.block_row) out.i32(v);
    for (int v : f.block_body) out.i32(v);
    for (double v : f.x_ref) out.f64(v);
    out.bytes(meta.data(), meta.size());
}

bool write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes, std::string* error) {
    const std::string tmp = path + ".tmp";
    std::FILE* fp = std::fopen(tmp.c_str(), "wb");
    if (!fp) return fail(error, path + ": cannot create " + tmp + ": " + std::strerror(errno));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), fp) == bytes.size();
    const int write_errno = errno;
    const bool closed = std::fclose(fp) == 0;
    if (!written || !closed) {
        std::remove(tmp.c_str());
        return fail(error, path + ": write error: " + std::strerror(written ? errno : write_errno));
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const int rename_errno = errno;
        std::remove(tmp.c_str());
        return fail(error, path + ": cannot rename " + tmp + ": " + std::strerror(rename_errno));
    }
    return true;
}

/// The upper triangle of a row-major n x n array set from its lower triangle.
void mirror_lower(std::vector<double>& A, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < i; ++j) A[j * n + i] = A[i * n + j];
}

void copy_matrix(const Problem& p, std::vector<double>* A) {
    const std::size_t n = static_cast<std::size_t>(p.n);
    A->assign(n * n, 0.0);
    if (p.sparse != nullptr) {
        p.sparse->to_dense_lower(A->data(), p.n);
    } else {
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j <= i; ++j) (*A)[i * n + j] = p.A[i * static_cast<std::size_t>(p.lda) + j];
    }
    mirror_lower(*A, n);
}

std::optional<std::string> check_problem_pointers(const Problem& p) {
    if (p.n < 0) return "n = " + std::to_string(p.n) + " is negative";
    if (p.n > 0 && ((!p.A && !p.sparse) || !p.b.data || !p.lo.data || !p.hi.data)) return "A, b, lo and hi must not be null";
    if (p.n > 0 && !p.sparse && p.lda < p.n) return "lda = " + std::to_string(p.lda) + " < n = " + std::to_string(p.n);
    if (p.num_blocks < 0) return "num_blocks = " + std::to_string(p.num_blocks) + " is negative";
    if (p.num_blocks > 0 && (!p.block_row || !p.block_body)) return "num_blocks > 0 but block_row or block_body is null";
    return std::nullopt;
}

void copy_blocks(const Problem& p, MlcpFile* f) {
    if (p.num_blocks <= 0 || !p.block_row || !p.block_body) return;
    f->block_row.assign(p.block_row, p.block_row + p.num_blocks + 1);
    f->block_body.assign(p.block_body, p.block_body + 2 * p.num_blocks);
    const int max_body = *std::max_element(f->block_body.begin(), f->block_body.end());
    // INT_MAX cannot be a valid index; the clamp lets validation reject it instead of overflowing
    f->num_bodies = max_body < std::numeric_limits<int>::max() ? std::max(0, max_body + 1) : max_body;
}

}  // namespace

std::optional<MlcpFile> copy_problem(const Problem& problem, const Metadata& meta, const double* x_ref,
                                     std::string* error) {
    try {
        if (auto e = check_problem_pointers(problem)) return no_file(error, *e);
        MlcpFile f;
        f.n = problem.n;
        f.nub = problem.nub;
        copy_matrix(problem, &f.A);
        for (int i = 0; i < problem.n; ++i) {
            f.b.push_back(problem.b[i]);
            f.lo.push_back(problem.lo[i]);
            f.hi.push_back(problem.hi[i]);
        }
        if (problem.findex) f.findex.assign(problem.findex, problem.findex + problem.n);
        copy_blocks(problem, &f);
        if (x_ref) f.x_ref.assign(x_ref, x_ref + problem.n);
        f.meta = meta;
        if (auto e = validate(f)) return no_file(error, *e);
        return f;
    } catch (const std::bad_alloc&) {
        return no_file(error, "out of memory");
    }
}

bool encode_mlcp(const MlcpFile& file, std::vector<std::uint8_t>* bytes, std::string* error) {
    if (bytes == nullptr) return fail(error, "no output buffer (bytes is null)");
    try {
        if (auto e = validate(file)) return fail(error, *e);
        const std::string meta = metadata_text(file.meta);
        bytes->clear();
        io::ByteSink out(bytes);
        encode_header(file, static_cast<std::uint32_t>(meta.size()), out);
        encode_body(file, meta, out);
        out.u32(crc32(bytes->data(), bytes->size()));
        return true;
    } catch (const std::bad_alloc&) {
        return fail(error, "out of memory");
    }
}

bool write_mlcp(const std::string& path, const MlcpFile& file, std::string* error) {
    std::vector<std::uint8_t> bytes;
    std::string reason;
    if (!encode_mlcp(file, &bytes, &reason)) return fail(error, path + ": " + reason);
    return write_bytes(path, bytes, error);
}

bool write_mlcp(const std::string& path, const Problem& problem, const Metadata& meta, const double* x_ref,
                std::string* error) {
    std::string reason;
    const auto file = copy_problem(problem, meta, x_ref, &reason);
    if (!file) return fail(error, path + ": " + reason);
    return write_mlcp(path, *file, error);
}

}  // namespace ode_bpp
