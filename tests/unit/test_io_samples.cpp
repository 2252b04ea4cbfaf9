// The committed samples in tests/data were written by tests/data/make-samples.py, a second
// implementation of docs/mlcp-format.md: reader and writer must agree with it byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "test_io_support.h"

namespace {

namespace fs = std::filesystem;
using io_test::kInf;

std::vector<std::uint8_t> slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<fs::path> samples() {
    std::vector<fs::path> paths;
    for (const auto& entry : fs::directory_iterator(io_test::data_dir()))
        if (entry.path().extension() == ".mlcp") paths.push_back(entry.path());
    std::sort(paths.begin(), paths.end());
    return paths;
}

ode_bpp::MlcpFile read_sample(const std::string& name) {
    const ode_bpp::ReadResult r = ode_bpp::read_mlcp((io_test::data_dir() / name).string());
    if (!r.ok) ADD_FAILURE() << r.error;
    return r.file;
}

TEST(IoSamples, EverySampleReadsAndReencodesIdentically) {
    const std::vector<fs::path> paths = samples();
    ASSERT_GE(paths.size(), 5u);
    for (const fs::path& path : paths) {
        const ode_bpp::ReadResult r = ode_bpp::read_mlcp(path.string());
        ASSERT_TRUE(r.ok) << r.error;
        EXPECT_EQ(io_test::encode(r.file), slurp(path)) << path;
    }
}

TEST(IoSamples, NotesFrictionExample) {
    const ode_bpp::MlcpFile f = read_sample("notes-friction-3.mlcp");
    ASSERT_EQ(f.n, 3);
    const std::vector<double> A = {2, .3, .1, .3, 1.5, .2, .1, .2, 1.8};
    EXPECT_EQ(f.A, A);
    EXPECT_EQ(f.b, (std::vector<double>{1, .9, -.2}));
    EXPECT_EQ(f.lo, (std::vector<double>{0, -.5, -.5}));
    EXPECT_EQ(f.hi, (std::vector<double>{kInf, .5, .5}));
    EXPECT_EQ(f.findex, (std::vector<int>{-1, 0, 0}));
    EXPECT_TRUE(f.block_row.empty());
    EXPECT_TRUE(f.x_ref.empty());
    ASSERT_NE(f.meta.find("scene"), nullptr);
    EXPECT_EQ(*f.meta.find("scene"), "notes-friction-example");
}

TEST(IoSamples, BallChainReferenceSolvesTheEqualities) {
    const ode_bpp::MlcpFile f = read_sample("ball-chain-12.mlcp");
    ASSERT_EQ(f.n, 12);
    EXPECT_EQ(f.nub, 12);
    ASSERT_EQ(f.x_ref.size(), 12u);
    double scale = 0, worst = 0;
    for (int i = 0; i < f.n; ++i) {
        double r = -f.b[i], row_scale = std::abs(f.b[i]);
        for (int j = 0; j < f.n; ++j) {
            r += f.A[i * f.n + j] * f.x_ref[j];
            row_scale += std::abs(f.A[i * f.n + j] * f.x_ref[j]);
        }
        worst = std::max(worst, std::abs(r));
        scale = std::max(scale, row_scale);
    }
    EXPECT_LE(worst, 1e-10 * scale);
    EXPECT_EQ(f.block_row, (std::vector<int>{0, 3, 6, 9, 12}));
    EXPECT_EQ(f.block_body, (std::vector<int>{0, -1, 1, 0, 2, 1, 3, 2}));
    EXPECT_EQ(f.num_bodies, 4);
    // joints 0 and 2 share no body, so their block of A is zero
    for (int i = 6; i < 9; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_EQ(f.A[i * f.n + j], 0.0);
}

TEST(IoSamples, BoxContactBounds) {
    const ode_bpp::MlcpFile f = read_sample("box-contact-13.mlcp");
    ASSERT_EQ(f.n, 13);
    for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(f.lo[3 * c], 0.0);
        EXPECT_EQ(f.hi[3 * c], kInf);
        EXPECT_EQ(f.findex[3 * c + 1], 3 * c);
        EXPECT_EQ(f.findex[3 * c + 2], 3 * c);
    }
    EXPECT_EQ(f.num_blocks(), 5);
    EXPECT_EQ(f.lo[12], -0.25);
    ASSERT_NE(f.meta.find("frame"), nullptr);
    EXPECT_EQ(*f.meta.find("frame"), "0");
}

TEST(IoSamples, PlainAndEmpty) {
    const ode_bpp::MlcpFile plain = read_sample("plain-2.mlcp");
    EXPECT_EQ(plain.n, 2);
    EXPECT_EQ(plain.A, (std::vector<double>{1, .5, .5, 2}));
    EXPECT_TRUE(plain.findex.empty());
    EXPECT_TRUE(plain.meta.entries.empty());
    EXPECT_EQ(read_sample("empty-0.mlcp").n, 0);
}

}  // namespace
