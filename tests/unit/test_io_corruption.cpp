// Every damaged file is rejected with "<name>: offset <k>: <reason>", k pointing at the
// offending bytes, without crashing and without allocating more than the file's own size.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <cctype>

#include "test_io_support.h"

// Largest single allocation since the last reset: the reader must size nothing from the
// header alone, so this stays within a small multiple of the file size.
namespace {
std::atomic<std::size_t> g_largest_allocation{0};
}  // namespace

void* operator new(std::size_t size) {
    std::size_t seen = g_largest_allocation.load();
    while (size > seen && !g_largest_allocation.compare_exchange_weak(seen, size)) {
    }
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
// the non-throwing form too (std::get_temporary_buffer's): every delete here frees
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    try {
        return ::operator new(size);
    } catch (const std::bad_alloc&) {
        return nullptr;
    }
}
// GCC cannot see that these pair with the malloc in operator new above.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace {

using io_test::SpecLayout;

const char* kName = "damaged.mlcp";

struct Sample {
    ode_bpp::MlcpFile file = io_test::make_sample(6, 42);
    std::vector<std::uint8_t> bytes = io_test::encode(file);
    std::size_t meta_bytes() const {
        std::size_t total = 0;
        for (const auto& [key, value] : file.meta.entries) total += key.size() + value.size() + 2;
        return total;
    }
    SpecLayout layout() const {
        return SpecLayout(6, file.block_row.size() - 1, true, true, true, meta_bytes());
    }
};

// Parses "<kName>: offset <k>: <reason>"; fails the test if the message has another shape.
struct ParsedError {
    bool ok = false;
    std::size_t offset = 0;
    std::string reason;
};

ParsedError parse(const std::string& error) {
    const std::string prefix = std::string(kName) + ": offset ";
    ParsedError p;
    if (error.compare(0, prefix.size(), prefix) != 0) return p;
    std::size_t pos = prefix.size(), digits = 0;
    for (; pos < error.size() && std::isdigit(static_cast<unsigned char>(error[pos])); ++pos, ++digits)
        p.offset = 10 * p.offset + static_cast<std::size_t>(error[pos] - '0');
    if (digits == 0 || error.compare(pos, 2, ": ") != 0 || pos + 2 >= error.size()) return p;
    p.reason = error.substr(pos + 2);
    p.ok = true;
    return p;
}

ParsedError expect_rejected(const std::vector<std::uint8_t>& bytes) {
    g_largest_allocation = 0;
    const ode_bpp::ReadResult r = io_test::read(bytes, kName);
    EXPECT_FALSE(r.ok);
    EXPECT_LE(g_largest_allocation.load(), 4 * bytes.size() + 4096) << r.error;
    const ParsedError p = parse(r.error);
    EXPECT_TRUE(p.ok) << "badly shaped error: " << r.error;
    EXPECT_LE(p.offset, bytes.size()) << r.error;
    return p;
}

void expect_error(const std::vector<std::uint8_t>& bytes, std::size_t offset, const std::string& words) {
    const ParsedError p = expect_rejected(bytes);
    EXPECT_EQ(p.offset, offset) << p.reason;
    EXPECT_NE(p.reason.find(words), std::string::npos) << "\"" << words << "\" not in: " << p.reason;
}

TEST(IoCorruption, TruncatedAtEveryByte) {
    const Sample s;
    ASSERT_TRUE(io_test::read(s.bytes, kName).ok);
    for (std::size_t k = 0; k < s.bytes.size(); ++k) {
        const std::vector<std::uint8_t> cut(s.bytes.begin(), s.bytes.begin() + k);
        const ParsedError p = expect_rejected(cut);
        const bool says_why = p.reason.find("truncated") != std::string::npos ||
                              p.reason.find("too large for a file") != std::string::npos;
        EXPECT_TRUE(says_why) << "at " << k << ": " << p.reason;
    }
}

TEST(IoCorruption, EveryFlippedByteIsCaught) {
    const Sample s;
    for (std::size_t k = 0; k < s.bytes.size(); ++k) {
        for (std::uint8_t mask : {std::uint8_t{0x01}, std::uint8_t{0x80}, std::uint8_t{0xFF}}) {
            std::vector<std::uint8_t> bad = s.bytes;
            bad[k] ^= mask;
            SCOPED_TRACE("byte " + std::to_string(k) + " mask " + std::to_string(mask));
            expect_rejected(bad);
        }
    }
}

TEST(IoCorruption, FlippedDataByteReportsTheChecksum) {
    const Sample s;
    std::vector<std::uint8_t> bad = s.bytes;
    bad[s.layout().b + 3] ^= 0x10;
    expect_error(bad, s.layout().checksum, "bad checksum");
}

TEST(IoCorruption, BadMagic) {
    const Sample s;
    std::vector<std::uint8_t> bad = s.bytes;
    bad[0] = 'P';
    expect_error(bad, 0, "bad magic");
    bad = s.bytes;
    bad[10] = '!';  // the terminating NUL of the magic
    expect_error(bad, 10, "bad magic");
    const std::string text = "n,nub\n3,1\n";
    expect_error(std::vector<std::uint8_t>(text.begin(), text.end()), 0, "bad magic");
}

TEST(IoCorruption, FutureVersion) {
    const Sample s;
    std::vector<std::uint8_t> bad = s.bytes;
    io_test::put_u32(bad, 11, 2);
    expect_error(bad, 11, "unsupported format version 2");
    // a future version is recognised even if its header is shorter than version 1's
    expect_error(std::vector<std::uint8_t>(bad.begin(), bad.begin() + 15), 11, "unsupported format version 2");
}

TEST(IoCorruption, AbsurdNDoesNotAllocate) {
    const Sample s;
    for (std::uint32_t n : {0x80000000u, 0xFFFFFFFFu, 0x7FFFFFFFu, 100000u, 7u}) {
        std::vector<std::uint8_t> bad = s.bytes;
        io_test::put_u32(bad, 19, n);
        io_test::reseal(bad);
        const ParsedError p = expect_rejected(bad);
        if (n > 7) {
            EXPECT_EQ(p.offset, 19u) << p.reason;
            EXPECT_NE(p.reason.find("too large"), std::string::npos) << p.reason;
        } else {
            EXPECT_NE(p.reason.find("truncated"), std::string::npos) << p.reason;
        }
    }
}

TEST(IoCorruption, ShorterNLeavesTrailingBytes) {
    const Sample s;
    std::vector<std::uint8_t> bad = s.bytes;
    io_test::put_u32(bad, 19, 5);
    const SpecLayout five(5, s.file.block_row.size() - 1, true, true, true, s.meta_bytes());
    expect_error(bad, five.total, "trailing bytes");
}

TEST(IoCorruption, BadHeaderFields) {
    const Sample s;
    auto with = [&](std::size_t offset, std::uint32_t v) {
        std::vector<std::uint8_t> bad = s.bytes;
        io_test::put_u32(bad, offset, v);
        return bad;
    };
    expect_error(with(15, 0x10 | 0xF), 15, "unknown flag bits 0x00000010");
    expect_error(with(23, 7), 23, "nub = 7 exceeds n = 6");
    expect_error(with(27, 7), 27, "num_blocks = 7 exceeds n = 6");
    expect_error(with(15, 0x1 | 0x4 | 0x8), 27, "without the has_blocks flag");
    expect_error(with(15, 0x1 | 0x2 | 0x4), 35, "has_meta");
    std::vector<std::uint8_t> bad = s.bytes;
    bad[39] = 1;
    expect_error(bad, 39, "reserved");
}

TEST(IoCorruption, EmptyProblemAnnouncingRowSectionsIsNotCanonical) {
    for (std::uint32_t flags : {0x1u, 0x4u}) {
        std::vector<std::uint8_t> bad = io_test::encode(ode_bpp::MlcpFile{});
        io_test::put_u32(bad, 15, flags);
        io_test::reseal(bad);
        expect_error(bad, 15, "set for n = 0");
    }
}

TEST(IoCorruption, BadFindex) {
    const Sample s;
    const std::size_t at = s.layout().findex;
    for (int bad_value : {6, 100, -2, -2147483647 - 1}) {
        std::vector<std::uint8_t> bad = s.bytes;
        io_test::put_i32(bad, at + 4 * 4, bad_value);
        io_test::reseal(bad);
        expect_error(bad, at + 4 * 4, "findex[4] = " + std::to_string(bad_value) + " out of range");
    }
    std::vector<std::uint8_t> bad = s.bytes;
    io_test::put_i32(bad, at + 4 * 3, 3);
    io_test::reseal(bad);
    expect_error(bad, at + 4 * 3, "findex[3] refers to its own row");
    // row 3 is a friction row (of normal 2): a friction row's normal cannot be one, in a file as
    // in validate() (structure_rules.h)
    ASSERT_EQ(s.file.findex[3], 2);
    bad = s.bytes;
    io_test::put_i32(bad, at + 4 * 4, 3);
    io_test::reseal(bad);
    expect_error(bad, at + 4 * 4, "findex[4] = 3 refers to a friction row");
}

TEST(IoCorruption, BadBlocks) {
    const Sample s;
    const SpecLayout l = s.layout();
    const int num_blocks = static_cast<int>(s.file.block_row.size()) - 1;
    ASSERT_GE(num_blocks, 3);
    auto spoil = [&](std::size_t offset, std::int32_t v) {
        std::vector<std::uint8_t> bad = s.bytes;
        io_test::put_i32(bad, offset, v);
        io_test::reseal(bad);
        return bad;
    };
    expect_error(spoil(l.block_row + 4 * 2, s.file.block_row[1]), l.block_row + 4 * 2, "non-increasing block_row");
    expect_error(spoil(l.block_row + 4 * 1, -3), l.block_row + 4 * 1, "non-increasing block_row");
    expect_error(spoil(l.block_row, 1), l.block_row, "block_row[0] = 1, must be 0");
    expect_error(spoil(l.block_row + 4 * num_blocks, 5), l.block_row + 4 * num_blocks, "must be n = 6");
    expect_error(spoil(l.block_body + 4 * 3, 4), l.block_body + 4 * 3, "block_body[3] = 4 out of range");
    expect_error(spoil(l.block_body, -2), l.block_body, "block_body[0] = -2 out of range");
}

TEST(IoCorruption, BadMetadata) {
    const Sample s;
    const SpecLayout l = s.layout();
    const std::string first = s.file.meta.entries[0].first + "=" + s.file.meta.entries[0].second + "\n";
    auto spoil = [&](std::size_t offset, char c) {
        std::vector<std::uint8_t> bad = s.bytes;
        bad[offset] = static_cast<std::uint8_t>(c);
        io_test::reseal(bad);
        return bad;
    };
    expect_error(spoil(l.checksum - 1, 'x'), l.checksum - s.file.meta.entries.back().first.size() -
                                                 s.file.meta.entries.back().second.size() - 2,
                 "not terminated");
    expect_error(spoil(l.meta + s.file.meta.entries[0].first.size(), ':'), l.meta, "without '='");
    expect_error(spoil(l.meta, ' '), l.meta, "bad metadata key");
    expect_error(spoil(l.meta + first.size() + 7, '\0'), l.meta + first.size(), "NUL");  // in "frame=17"
    // turn the second key into a copy of the first ("scene" and "frame" have the same length)
    std::vector<std::uint8_t> dup = s.bytes;
    std::copy(first.begin(), first.begin() + 5, dup.begin() + static_cast<std::ptrdiff_t>(l.meta + first.size()));
    io_test::reseal(dup);
    expect_error(dup, l.meta + first.size(), "duplicate metadata key \"scene\"");
}

TEST(IoCorruption, MissingFileNamesThePath) {
    const ode_bpp::ReadResult r = ode_bpp::read_mlcp("/nonexistent/x.mlcp");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error.rfind("/nonexistent/x.mlcp: offset 0: cannot open", 0), 0u) << r.error;
}

TEST(IoCorruption, DirectoryIsNotAFile) {
    const ode_bpp::ReadResult r = ode_bpp::read_mlcp(io_test::data_dir().string());
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find(io_test::data_dir().string() + ": offset 0:"), std::string::npos) << r.error;
}

TEST(IoCorruption, RandomGarbageNeverCrashes) {
    const Sample s;
    std::mt19937 rng(7);
    for (int trial = 0; trial < 2000; ++trial) {
        std::vector<std::uint8_t> bad = s.bytes;
        const int edits = 1 + static_cast<int>(rng() % 8);
        for (int e = 0; e < edits; ++e) bad[rng() % bad.size()] = static_cast<std::uint8_t>(rng());
        if (trial % 2) io_test::reseal(bad);
        g_largest_allocation = 0;
        const ode_bpp::ReadResult r = io_test::read(bad, kName);
        EXPECT_LE(g_largest_allocation.load(), 4 * bad.size() + 4096);
        if (r.ok) {
            EXPECT_EQ(io_test::encode(r.file), bad);  // whatever passes is a canonical file
        } else {
            EXPECT_TRUE(parse(r.error).ok) << r.error;
        }
    }
}

}  // namespace
