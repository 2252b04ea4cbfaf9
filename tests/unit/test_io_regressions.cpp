// Every input that once broke a fuzz target (tests/data/fuzz-regressions), every sample and
// every captured island (tests/data/captured) goes through the reader and, when it reads, through solve() with every method, exactly as
// the fuzz targets do: nothing may crash, x stays finite, rejected input leaves x zero.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "test_io_support.h"

namespace {

namespace fs = std::filesystem;

std::vector<std::string> regression_inputs() {
    std::vector<std::string> names;
    for (const fs::path& dir : {io_test::data_dir() / "fuzz-regressions", io_test::data_dir(), io_test::data_dir() / "captured"}) {
        if (!fs::is_directory(dir)) continue;
        for (const auto& entry : fs::directory_iterator(dir)) {
            const fs::path& p = entry.path();
            const bool sample = p.extension() == ".mlcp";
            const bool regression = dir.filename() == "fuzz-regressions" && p.extension() != ".md";
            if (entry.is_regular_file() && (sample || regression)) names.push_back(p.string());
        }
    }
    std::sort(names.begin(), names.end());
    return names;
}

std::vector<std::uint8_t> slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The fuzz targets' fix-up: the last 4 bytes become the CRC-32 of the rest.
std::vector<std::uint8_t> resealed(std::vector<std::uint8_t> bytes) {
    if (bytes.size() >= 4) io_test::reseal(bytes);
    return bytes;
}

void expect_solve_is_safe(const ode_bpp::MlcpFile& file, ode_bpp::Method method, ode_bpp::FrictionMode friction) {
    ode_bpp::Options options;  // the budgets of fuzz_solve
    options.method = method;
    options.friction = friction;
    options.max_pivots = 12;
    options.pgs_iterations = 8;
    options.tuning.max_friction_rounds = 4;
    std::vector<double> x(static_cast<std::size_t>(file.n) + 1, 0.0);
    const ode_bpp::Result r = ode_bpp::solve(file.view(), options, x.data());
    SCOPED_TRACE(std::string(to_string(method)) + "/" + to_string(friction) + ": " + to_string(r.status));
    for (int i = 0; i < file.n; ++i) {
        EXPECT_TRUE(std::isfinite(x[i])) << "x[" << i << "]";
        if (r.status == ode_bpp::Status::InvalidInput) {
            EXPECT_EQ(x[i], 0.0) << "x[" << i << "]";
        }
    }
    if (r.status != ode_bpp::Status::Converged) {
        EXPECT_FALSE(r.message.empty());
    }
}

class FuzzRegression : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzRegression, ReadsOrFailsCleanly) {
    for (const auto& bytes : {slurp(GetParam()), resealed(slurp(GetParam()))}) {
        const ode_bpp::ReadResult r = io_test::read(bytes, "input");
        if (r.ok) {
            EXPECT_EQ(io_test::encode(r.file), bytes);
        } else {
            EXPECT_EQ(r.error.rfind("input: offset ", 0), 0u) << r.error;
        }
    }
}

TEST_P(FuzzRegression, SolvesWithoutCrashing) {
    const ode_bpp::ReadResult r = io_test::read(resealed(slurp(GetParam())), "input");
    if (!r.ok) return;  // nothing to solve; the reader's side is checked above
    for (const std::string& name : ode_bpp::method_names()) {
        const auto method = ode_bpp::method_from_string(name);
        ASSERT_TRUE(method);
        expect_solve_is_safe(r.file, *method, ode_bpp::FrictionMode::Frozen);
        expect_solve_is_safe(r.file, *method, ode_bpp::FrictionMode::Consistent);
    }
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
    std::string name = fs::path(info.param).filename().string();
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

INSTANTIATE_TEST_SUITE_P(Inputs, FuzzRegression, ::testing::ValuesIn(regression_inputs()), test_name);

}  // namespace
