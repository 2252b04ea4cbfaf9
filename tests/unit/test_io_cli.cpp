// ode-bpp-solve end to end: exit codes, usage, CSV rows, damaged files.
// The binary is found beside this test in the build tree (<build>/ode_bpp/ode-bpp-solve).
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sys/wait.h>
#include <unistd.h>

#include "test_io_support.h"

namespace {

namespace fs = std::filesystem;

fs::path tool_path() {
    return fs::read_symlink("/proc/self/exe").parent_path().parent_path() / "ode_bpp" / "ode-bpp-solve";
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct ToolRun {
    int exit_code = -1;
    std::string out, err;
};

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_TRUE(fs::exists(tool_path())) << "build the target ode-bpp-solve first: " << tool_path();
        dir = fs::temp_directory_path() / ("ode_bpp_cli_" + std::to_string(::getpid()));
        fs::create_directories(dir / "in");
    }
    void TearDown() override { fs::remove_all(dir); }

    ToolRun run(const std::string& args) {
        const std::string command = tool_path().string() + " " + args + " > " + (dir / "out").string() + " 2> " +
                                    (dir / "err").string();
        const int status = std::system(command.c_str());
        ToolRun r;
        r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.out = slurp(dir / "out");
        r.err = slurp(dir / "err");
        return r;
    }
    void copy_samples() {
        for (const char* name : {"notes-friction-3.mlcp", "box-contact-13.mlcp", "plain-2.mlcp"})
            fs::copy_file(io_test::data_dir() / name, dir / "in" / name);
    }
    fs::path dir;
};

TEST_F(Cli, BadArgumentsPrintUsageWithEveryMethodAndExit2) {
    for (const char* args : {"", "--methods nope x.mlcp", "--repeat 0 x.mlcp", "--friction sticky x.mlcp",
                             "--max-pivots x.mlcp", "--bogus x.mlcp", "--methods=bpp,,pgs x.mlcp"}) {
        const ToolRun r = run(args);
        EXPECT_EQ(r.exit_code, 2) << args;
        EXPECT_NE(r.err.find("usage: ode-bpp-solve"), std::string::npos) << args << ": " << r.err;
        for (const std::string& method : ode_bpp::method_names())
            EXPECT_NE(r.err.find(method), std::string::npos) << method << " missing from usage";
        EXPECT_TRUE(r.out.empty()) << args;
    }
}

TEST_F(Cli, HelpGoesToStdout) {
    const ToolRun r = run("--help");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("--pgs-iterations"), std::string::npos);
}

TEST_F(Cli, DirectoryGivesOneRowPerFileAndMethod) {
    copy_samples();
    const ToolRun r = run("--methods bpp,pgs,dantzig --repeat 2 --csv " + (dir / "r.csv").string() + " " +
                      (dir / "in").string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto rows = io_test::parse_csv(slurp(dir / "r.csv"));
    ASSERT_EQ(rows.size(), 1 + 3 * 3u);
    EXPECT_EQ(rows[0][0], "file");
    const std::vector<std::string> sorted = {"box-contact-13.mlcp", "notes-friction-3.mlcp", "plain-2.mlcp"};
    const std::vector<std::string> n = {"13", "3", "2"};
    for (std::size_t k = 1; k < rows.size(); ++k) {
        ASSERT_EQ(rows[k].size(), rows[0].size()) << "row " << k;
        EXPECT_EQ(fs::path(rows[k][0]).filename(), sorted[(k - 1) / 3]);
        EXPECT_EQ(rows[k][1], n[(k - 1) / 3]);
        EXPECT_EQ(rows[k][4], (std::vector<std::string>{"bpp", "pgs", "dantzig"})[(k - 1) % 3]);
    }
}

TEST_F(Cli, DamagedFileIsReportedAndTheOthersStillRun) {
    copy_samples();
    std::vector<std::uint8_t> bytes = io_test::encode(io_test::make_sample(6, 1));
    bytes[60] ^= 0x40;
    std::ofstream(dir / "in" / "damaged.mlcp", std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                                     static_cast<std::streamsize>(bytes.size()));
    const ToolRun r = run("--methods bpp " + (dir / "in").string() + " " + (dir / "missing.mlcp").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("damaged.mlcp: offset "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bad checksum"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("missing.mlcp: offset 0: cannot open"), std::string::npos) << r.err;
    const auto rows = io_test::parse_csv(r.out);
    ASSERT_EQ(rows.size(), 1 + 5u);  // box, damaged, notes, plain, missing
    EXPECT_EQ(fs::path(rows[2][0]).filename(), "damaged.mlcp");
    EXPECT_EQ(rows[2][5], "read-error");
    EXPECT_NE(rows[2][6].find("bad checksum"), std::string::npos);
    EXPECT_EQ(rows[5][5], "read-error");
    for (int k : {1, 3, 4}) EXPECT_NE(rows[k][5], "read-error") << rows[k][0];
}

TEST_F(Cli, OptionsReachTheSolver) {
    // docs/maths.md (Dantzig's friction semantics): on this problem frozen (Dantzig's) friction leaves |x1| > mu x0; consistent must not
    const std::string file = (io_test::data_dir() / "notes-friction-3.mlcp").string();
    const ToolRun frozen = run("--methods bpp " + file);
    const ToolRun consistent = run("--friction=consistent --methods bpp,pgs --pgs-iterations 3 " + file);
    ASSERT_EQ(frozen.exit_code, 0) << frozen.err;
    ASSERT_EQ(consistent.exit_code, 0) << consistent.err;
    const auto frozen_rows = io_test::parse_csv(frozen.out);
    const auto rows = io_test::parse_csv(consistent.out);
    ASSERT_EQ(frozen_rows.size(), 2u);
    ASSERT_EQ(rows.size(), 3u);
    const std::size_t friction_error = 16, pivots = 8;
    ASSERT_EQ(rows[0][friction_error], "friction_error");
    ASSERT_EQ(rows[0][pivots], "pivots");
    EXPECT_GT(std::stod(frozen_rows[1][friction_error]), 1e-3);
    EXPECT_EQ(rows[1][5], "converged");
    EXPECT_LE(std::stod(rows[1][friction_error]), 1e-9);
    EXPECT_EQ(rows[2][4], "pgs");
    EXPECT_LE(std::stoi(rows[2][pivots]), 3);  // a PGS pivot is one sweep
}

}  // namespace
