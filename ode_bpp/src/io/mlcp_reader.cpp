// Reading MLCP files. Checks run in file order, and no count from the header is used to
// allocate or index before it has been checked against the bytes actually present.
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <new>

#include "io/byte_codec.h"
#include "io/mlcp_layout.h"
#include "structure_rules.h"
#include "ode_bpp/io.h"

namespace ode_bpp {
namespace {

using io::Header;
using io::Layout;
namespace hdr = io::header;
namespace flag = io::flag;

struct Error {
    std::uint64_t offset = 0;
    std::string reason;
};
using Check = std::optional<Error>;

std::string hex(std::uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%08x", v);
    return buf;
}

Check check_magic(const std::uint8_t* data, std::size_t size) {
    const std::size_t present = size < io::kMagicBytes ? size : io::kMagicBytes;
    for (std::size_t i = 0; i < present; ++i)
        if (data[i] != static_cast<std::uint8_t>(io::kMagic[i]))
            return Error{i, "bad magic (not an ode-bpp MLCP file; expected \"ODEBPPMLCP\\0\")"};
    if (size < io::kMagicBytes) return Error{size, "truncated in the magic"};
    return std::nullopt;
}

// The version comes before anything else, as a later version may lay out its header differently.
Check check_version(const std::uint8_t* data, std::size_t size) {
    if (size < hdr::kFlags) return Error{size, "truncated in the format version"};
    const std::uint32_t version = io::load_u32(data + hdr::kVersion);
    if (version != kMlcpFormatVersion)
        return Error{hdr::kVersion, "unsupported format version " + std::to_string(version) +
                                        " (this reader knows version " + std::to_string(kMlcpFormatVersion) + ")"};
    if (size < hdr::kSize) return Error{size, "truncated in the " + std::to_string(hdr::kSize) + "-byte header"};
    return std::nullopt;
}

Header decode_header(const std::uint8_t* data) {
    Header h;
    h.version = io::load_u32(data + hdr::kVersion);
    h.flags = io::load_u32(data + hdr::kFlags);
    h.n = io::load_u32(data + hdr::kN);
    h.nub = io::load_u32(data + hdr::kNub);
    h.num_blocks = io::load_u32(data + hdr::kNumBlocks);
    h.num_bodies = io::load_u32(data + hdr::kNumBodies);
    h.meta_bytes = io::load_u32(data + hdr::kMetaBytes);
    return h;
}

// Field consistency that needs no knowledge of the file size.
Check check_header_fields(const Header& h, std::uint8_t reserved) {
    const bool has_blocks = (h.flags & flag::kBlocks) != 0;
    const bool has_meta = (h.flags & flag::kMetadata) != 0;
    if (h.flags & ~flag::kKnown) return Error{hdr::kFlags, "unknown flag bits " + hex(h.flags & ~flag::kKnown)};
    // an empty problem has no per-row section to announce; refusing the flags keeps one
    // encoding per problem (files are canonical, docs/mlcp-format.md)
    if (h.n == 0 && (h.flags & (flag::kFindex | flag::kReferenceX)))
        return Error{hdr::kFlags, "has_findex or has_x set for n = 0"};
    if (h.n > static_cast<std::uint32_t>(INT_MAX))
        return Error{hdr::kN, "n = " + std::to_string(h.n) + " too large (more than INT_MAX)"};
    if (h.nub > h.n)
        return Error{hdr::kNub, "nub = " + std::to_string(h.nub) + " exceeds n = " + std::to_string(h.n)};
    if (!has_blocks && h.num_blocks != 0)
        return Error{hdr::kNumBlocks, "num_blocks = " + std::to_string(h.num_blocks) + " without the has_blocks flag"};
    if (!has_blocks && h.num_bodies != 0)
        return Error{hdr::kNumBodies, "num_bodies = " + std::to_string(h.num_bodies) + " without the has_blocks flag"};
    if (h.num_blocks > h.n)
        return Error{hdr::kNumBlocks, "num_blocks = " + std::to_string(h.num_blocks) + " exceeds n = " +
                                          std::to_string(h.n) + " (every block owns a row)"};
    if (h.num_bodies > static_cast<std::uint32_t>(INT_MAX))
        return Error{hdr::kNumBodies, "num_bodies = " + std::to_string(h.num_bodies) + " too large (more than INT_MAX)"};
    if (has_meta != (h.meta_bytes != 0))
        return Error{hdr::kMetaBytes, "meta_bytes = " + std::to_string(h.meta_bytes) + " disagrees with the has_meta flag"};
    if (reserved != 0) return Error{hdr::kReserved, "reserved byte is " + std::to_string(reserved) + ", must be 0"};
    return std::nullopt;
}

// The header's sizes against the real size; A's triangle is checked first so that the
// layout arithmetic below never overflows and never asks for more than the file holds.
Check check_sizes(const Header& h, std::size_t size, Layout* layout) {
    const std::uint64_t file_size = size;
    const std::uint64_t entries = io::triangle_entries(h.n);
    if (entries > file_size / 8)
        return Error{hdr::kN, "n = " + std::to_string(h.n) + " too large for a file of " + std::to_string(size) +
                                  " bytes (A's lower triangle alone needs " + std::to_string(entries) +
                                  " doubles): the file is truncated or n is damaged"};
    *layout = io::layout_of(h);
    if (layout->total > file_size)
        return Error{file_size, "truncated: the header (n = " + std::to_string(h.n) + ", num_blocks = " +
                                    std::to_string(h.num_blocks) + ", flags = " + hex(h.flags) + ", meta_bytes = " +
                                    std::to_string(h.meta_bytes) + ") announces " + std::to_string(layout->total) +
                                    " bytes, the file ends after " + std::to_string(size)};
    if (layout->total < file_size)
        return Error{layout->total, "trailing bytes: the header announces " + std::to_string(layout->total) +
                                        " bytes, the file has " + std::to_string(size)};
    return std::nullopt;
}

Check check_checksum(const std::uint8_t* data, const Layout& l) {
    const std::uint32_t stored = io::load_u32(data + l.checksum);
    const std::uint32_t computed = crc32(data, l.checksum);
    if (stored != computed)
        return Error{l.checksum, "bad checksum: stored CRC-32 " + hex(stored) + ", computed " + hex(computed) +
                                     " (the file is damaged)"};
    return std::nullopt;
}

std::vector<double> load_doubles(const std::uint8_t* p, std::size_t count) {
    std::vector<double> v(count);
    for (std::size_t i = 0; i < count; ++i) v[i] = io::load_f64(p + 8 * i);
    return v;
}

std::vector<int> load_ints(const std::uint8_t* p, std::size_t count) {
    std::vector<int> v(count);
    for (std::size_t i = 0; i < count; ++i) v[i] = io::load_i32(p + 4 * i);
    return v;
}

void load_matrix(const std::uint8_t* p, int n, std::vector<double>* A) {
    const std::size_t nn = static_cast<std::size_t>(n);
    A->assign(nn * nn, 0.0);
    for (std::size_t i = 0; i < nn; ++i) {
        for (std::size_t j = 0; j <= i; ++j, p += 8) {
            const double a = io::load_f64(p);
            (*A)[i * nn + j] = a;
            (*A)[j * nn + i] = a;
        }
    }
}

// Lines "key=value\n"; the offset of an error is that of the offending line.
Check parse_metadata(const std::uint8_t* text, std::size_t size, std::uint64_t base, Metadata* meta) {
    std::size_t pos = 0;
    while (pos < size) {
        const auto* line = reinterpret_cast<const char*>(text + pos);
        const void* nl = std::memchr(line, '\n', size - pos);
        if (!nl) return Error{base + pos, "metadata line not terminated by a newline"};
        const std::string_view content(line, static_cast<const char*>(nl) - line);
        const std::size_t eq = content.find('=');
        if (eq == std::string_view::npos) return Error{base + pos, "metadata line without '='"};
        const std::string_view key = content.substr(0, eq), value = content.substr(eq + 1);
        if (!Metadata::valid_key(key))
            return Error{base + pos, "bad metadata key (use letters, digits, '_', '.', '-')"};
        if (!Metadata::valid_value(value)) return Error{base + pos, "metadata value contains a NUL byte"};
        if (meta->find(key)) return Error{base + pos, "duplicate metadata key \"" + std::string(key) + "\""};
        meta->entries.emplace_back(std::string(key), std::string(value));
        pos += content.size() + 1;
    }
    return std::nullopt;
}

Check decode_body(const std::uint8_t* data, const Header& h, const Layout& l, MlcpFile* f) {
    const int n = static_cast<int>(h.n);
    const int num_blocks = static_cast<int>(h.num_blocks);
    f->n = n;
    f->nub = static_cast<int>(h.nub);
    load_matrix(data + l.a, n, &f->A);
    f->b = load_doubles(data + l.b, h.n);
    f->lo = load_doubles(data + l.lo, h.n);
    f->hi = load_doubles(data + l.hi, h.n);
    if (h.flags & flag::kFindex) {
        f->findex = load_ints(data + l.findex, h.n);
        if (auto issue = check_findex(f->findex.data(), n)) return Error{l.findex + 4 * issue->index, issue->reason};
    }
    if (h.flags & flag::kBlocks) {
        f->num_bodies = static_cast<int>(h.num_bodies);
        f->block_row = load_ints(data + l.block_row, h.num_blocks + std::size_t{1});
        f->block_body = load_ints(data + l.block_body, 2 * std::size_t{h.num_blocks});
        if (auto issue = check_block_row(f->block_row.data(), num_blocks, n))
            return Error{l.block_row + 4 * issue->index, issue->reason};
        if (auto issue = check_block_body(f->block_body.data(), num_blocks, f->num_bodies))
            return Error{l.block_body + 4 * issue->index, issue->reason};
    }
    if (h.flags & flag::kReferenceX) f->x_ref = load_doubles(data + l.x, h.n);
    return parse_metadata(data + l.meta, h.meta_bytes, l.meta, &f->meta);
}

Check decode(const std::uint8_t* data, std::size_t size, MlcpFile* file) {
    if (auto e = check_magic(data, size)) return e;
    if (auto e = check_version(data, size)) return e;
    const Header h = decode_header(data);
    if (auto e = check_header_fields(h, data[hdr::kReserved])) return e;
    Layout layout;
    if (auto e = check_sizes(h, size, &layout)) return e;
    if (auto e = check_checksum(data, layout)) return e;
    return decode_body(data, h, layout, file);
}

ReadResult failure(const std::string& name, std::uint64_t offset, const std::string& reason) {
    ReadResult r;
    r.error = name + ": offset " + std::to_string(offset) + ": " + reason;
    return r;
}

}  // namespace

ReadResult read_mlcp_bytes(const std::uint8_t* data, std::size_t size, const std::string& name) {
    try {
        ReadResult r;
        if (size > 0 && data == nullptr) return failure(name, 0, "no data");
        if (auto e = decode(data, size, &r.file)) return failure(name, e->offset, e->reason);
        r.ok = true;
        return r;
    } catch (const std::bad_alloc&) {
        return failure(name, 0, "out of memory");
    } catch (const std::exception& e) {
        return failure(name, 0, std::string("unexpected error: ") + e.what());
    }
}

ReadResult read_mlcp(const std::string& path) {
    try {
        std::FILE* fp = std::fopen(path.c_str(), "rb");
        if (!fp) return failure(path, 0, std::string("cannot open: ") + std::strerror(errno));
        std::vector<std::uint8_t> bytes;
        std::uint8_t chunk[1 << 16];
        std::size_t got;
        while ((got = std::fread(chunk, 1, sizeof chunk, fp)) > 0) bytes.insert(bytes.end(), chunk, chunk + got);
        const bool failed = std::ferror(fp) != 0;
        const int read_errno = errno;
        std::fclose(fp);
        if (failed) return failure(path, bytes.size(), std::string("read error: ") + std::strerror(read_errno));
        return read_mlcp_bytes(bytes.data(), bytes.size(), path);
    } catch (const std::bad_alloc&) {
        return failure(path, 0, "out of memory");
    } catch (const std::exception& e) {
        return failure(path, 0, std::string("unexpected error: ") + e.what());
    }
}

}  // namespace ode_bpp
