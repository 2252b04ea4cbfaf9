// Writing then reading an MLCP file gives back the same problem, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <unistd.h>

#include "test_io_support.h"

namespace {

using io_test::kInf;
using ode_bpp::MlcpFile;

// Bitwise equality, so that -0.0, NaN payloads and infinities are all held to the same standard.
bool same_bits(const std::vector<double>& x, const std::vector<double>& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), 8 * x.size()) == 0);
}

void expect_same(const MlcpFile& want, const MlcpFile& got) {
    EXPECT_EQ(want.n, got.n);
    EXPECT_EQ(want.nub, got.nub);
    EXPECT_TRUE(same_bits(want.A, got.A));
    EXPECT_TRUE(same_bits(want.b, got.b));
    EXPECT_TRUE(same_bits(want.lo, got.lo));
    EXPECT_TRUE(same_bits(want.hi, got.hi));
    EXPECT_TRUE(same_bits(want.x_ref, got.x_ref));
    EXPECT_EQ(want.findex, got.findex);
    EXPECT_EQ(want.block_row, got.block_row);
    EXPECT_EQ(want.block_body, got.block_body);
    EXPECT_EQ(want.num_bodies, got.num_bodies);
    EXPECT_EQ(want.meta.entries, got.meta.entries);
}

class TempDir {
public:
    TempDir() : path_(std::filesystem::temp_directory_path() / ("ode_bpp_io_" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

TEST(IoRoundTrip, EveryFieldSurvivesBitForBit) {
    MlcpFile f = io_test::make_sample(11, 1);
    f.b[3] = -0.0;                                              // sign of zero
    f.x_ref[4] = std::nan("0x5a5");                             // NaN payload
    f.A[0] = std::numeric_limits<double>::denorm_min();         // subnormal
    f.lo[5] = -kInf;
    f.hi[5] = kInf;
    f.meta.set("solver", "dantzig");
    f.meta.set("note", "a value = with equals, spaces and unicode \xc2\xb5");
    const ode_bpp::ReadResult r = io_test::read(io_test::encode(f));
    ASSERT_TRUE(r.ok) << r.error;
    expect_same(f, r.file);
}

TEST(IoRoundTrip, EncodingIsCanonical) {
    const MlcpFile f = io_test::make_sample(9, 2);
    const std::vector<std::uint8_t> bytes = io_test::encode(f);
    const ode_bpp::ReadResult r = io_test::read(bytes);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(bytes, io_test::encode(r.file));
}

TEST(IoRoundTrip, EncodingIntoNoBufferFailsWithAReason) {
    const MlcpFile f = io_test::make_sample(5, 1);
    std::string error;
    EXPECT_FALSE(ode_bpp::encode_mlcp(f, nullptr, &error));
    EXPECT_NE(error.find("null"), std::string::npos) << error;
    EXPECT_FALSE(ode_bpp::encode_mlcp(f, nullptr, nullptr));  // no reason wanted: still no crash
}

TEST(IoRoundTrip, SizeMatchesTheDocumentedLayout) {
    const MlcpFile f = io_test::make_sample(8, 3);
    std::size_t meta_bytes = 0;
    for (const auto& [key, value] : f.meta.entries) meta_bytes += key.size() + value.size() + 2;
    const io_test::SpecLayout spec(8, f.block_row.size() - 1, true, true, true, meta_bytes);
    EXPECT_EQ(io_test::encode(f).size(), spec.total);
}

TEST(IoRoundTrip, OnlyTheLowerTriangleIsStored) {
    MlcpFile f = io_test::make_sample(6, 4);
    MlcpFile skewed = f;
    for (int i = 0; i < f.n; ++i)
        for (int j = i + 1; j < f.n; ++j) skewed.A[i * f.n + j] = 1e300;  // never read
    EXPECT_EQ(io_test::encode(f), io_test::encode(skewed));
}

TEST(IoRoundTrip, OptionalSectionsMayBeAbsent) {
    MlcpFile f = io_test::make_sample(7, 5);
    f.findex.clear();
    f.block_row.clear();
    f.block_body.clear();
    f.num_bodies = 0;
    f.x_ref.clear();
    f.meta.entries.clear();
    const std::vector<std::uint8_t> bytes = io_test::encode(f);
    EXPECT_EQ(bytes.size(), io_test::SpecLayout(7, 0, false, false, false, 0).total);
    const ode_bpp::ReadResult r = io_test::read(bytes);
    ASSERT_TRUE(r.ok) << r.error;
    expect_same(f, r.file);
    EXPECT_EQ(r.file.view().findex, nullptr);
    EXPECT_EQ(r.file.view().block_row, nullptr);
}

TEST(IoRoundTrip, EmptyProblem) {
    MlcpFile f;
    const ode_bpp::ReadResult r = io_test::read(io_test::encode(f));
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.file.n, 0);
}

TEST(IoRoundTrip, ThroughTheFileSystem) {
    TempDir dir;
    const MlcpFile f = io_test::make_sample(10, 6);
    std::string error;
    ASSERT_TRUE(ode_bpp::write_mlcp(dir.file("a.mlcp"), f, &error)) << error;
    EXPECT_FALSE(std::filesystem::exists(dir.file("a.mlcp.tmp")));
    const ode_bpp::ReadResult r = ode_bpp::read_mlcp(dir.file("a.mlcp"));
    ASSERT_TRUE(r.ok) << r.error;
    expect_same(f, r.file);
}

TEST(IoRoundTrip, ProblemViewWithStridesAndPaddedRows) {
    // ODE's layout: A with a padded row stride, b and lo/hi interleaved in pairs.
    const MlcpFile f = io_test::make_sample(7, 7);
    const int n = f.n, lda = 8;
    std::vector<double> A(static_cast<std::size_t>(n * lda), std::nan("")), pairsbx(2 * n), pairslh(2 * n);
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j <= i; ++j) A[i * lda + j] = f.A[i * n + j];
        pairsbx[2 * i] = f.b[i];
        pairslh[2 * i] = f.lo[i];
        pairslh[2 * i + 1] = f.hi[i];
    }
    ode_bpp::Problem p = f.view();
    p.A = A.data();
    p.lda = lda;
    p.b = {pairsbx.data(), 2};
    p.lo = {pairslh.data(), 2};
    p.hi = {pairslh.data() + 1, 2};
    std::string error;
    const auto copy = ode_bpp::copy_problem(p, f.meta, f.x_ref.data(), &error);
    ASSERT_TRUE(copy) << error;
    expect_same(f, *copy);
}

TEST(IoRoundTrip, ViewDescribesTheFile) {
    const MlcpFile f = io_test::make_sample(9, 8);
    const ode_bpp::Problem p = f.view();
    EXPECT_EQ(p.n, f.n);
    EXPECT_EQ(p.lda, f.n);
    EXPECT_EQ(p.nub, f.nub);
    EXPECT_EQ(p.num_blocks, static_cast<int>(f.block_row.size()) - 1);
    for (int i = 0; i < f.n; ++i) {
        EXPECT_EQ(p.b[i], f.b[i]);
        EXPECT_EQ(p.hi[i], f.hi[i]);
        EXPECT_EQ(p.findex[i], f.findex[i]);
        for (int j = 0; j < f.n; ++j) EXPECT_EQ(p.A[i * p.lda + j], p.A[j * p.lda + i]);
    }
}

TEST(IoRoundTrip, WriterRejectsBadStructureAndNamesTheField) {
    const MlcpFile good = io_test::make_sample(8, 9);
    struct Case {
        const char* what;
        void (*spoil)(MlcpFile&);
    };
    const Case cases[] = {
        {"findex[5]", [](MlcpFile& f) { f.findex[5] = 8; }},
        {"findex[4]", [](MlcpFile& f) { f.findex[4] = 4; }},
        {"block_row", [](MlcpFile& f) { f.block_row[2] = f.block_row[1]; }},
        {"block_body", [](MlcpFile& f) { f.block_body[1] = 4; }},
        {"nub", [](MlcpFile& f) { f.nub = 9; }},
        {"metadata key", [](MlcpFile& f) { f.meta.entries.emplace_back("bad key", "v"); }},
        {"duplicate", [](MlcpFile& f) { f.meta.entries.emplace_back("scene", "again"); }},
        {"metadata value", [](MlcpFile& f) { f.meta.set("scene", "two\nlines"); }},
        {"n entries", [](MlcpFile& f) { f.hi.pop_back(); }},
    };
    TempDir dir;
    for (const Case& c : cases) {
        MlcpFile f = good;
        c.spoil(f);
        std::string error;
        EXPECT_FALSE(ode_bpp::write_mlcp(dir.file("bad.mlcp"), f, &error)) << c.what;
        EXPECT_NE(error.find(c.what), std::string::npos) << c.what << " not in: " << error;
        EXPECT_NE(error.find("bad.mlcp"), std::string::npos) << error;
        EXPECT_FALSE(std::filesystem::exists(dir.file("bad.mlcp")));
    }
}

TEST(IoRoundTrip, WriteToAMissingDirectoryFails) {
    std::string error;
    EXPECT_FALSE(ode_bpp::write_mlcp("/nonexistent-dir/x.mlcp", io_test::make_sample(6, 10), &error));
    EXPECT_NE(error.find("/nonexistent-dir/x.mlcp"), std::string::npos) << error;
}

TEST(IoRoundTrip, Crc32MatchesTheStandardCheckValue) {
    const char* check = "123456789";  // the CRC-32/ISO-HDLC catalogue's check input
    EXPECT_EQ(ode_bpp::crc32(reinterpret_cast<const std::uint8_t*>(check), 9), 0xCBF43926u);
}

TEST(IoRoundTrip, MetadataSetReplacesInPlace) {
    ode_bpp::Metadata m;
    m.set("a", "1");
    m.set("b", "2");
    m.set("a", "3");
    ASSERT_EQ(m.entries.size(), 2u);
    EXPECT_EQ(m.entries[0].second, "3");
    ASSERT_NE(m.find("b"), nullptr);
    EXPECT_EQ(*m.find("b"), "2");
    EXPECT_EQ(m.find("c"), nullptr);
}

}  // namespace
