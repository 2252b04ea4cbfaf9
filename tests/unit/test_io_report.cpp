// The CSV report of ode-bpp-solve: quoting, alignment of fields with columns, file listing.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <unistd.h>

#include "io/solve_report.h"
#include "test_io_support.h"

namespace {

namespace fs = std::filesystem;
using ode_bpp::io::csv_escape;
using ode_bpp::io::csv_line;

TEST(IoReport, PlainFieldsAreNotQuoted) {
    EXPECT_EQ(csv_escape("bpp-sky"), "bpp-sky");
    EXPECT_EQ(csv_escape("1.5e-09"), "1.5e-09");
    EXPECT_EQ(csv_escape(""), "");
}

TEST(IoReport, SpecialCharactersAreQuotedPerRfc4180) {
    EXPECT_EQ(csv_escape("a,b"), "\"a,b\"");
    EXPECT_EQ(csv_escape("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csv_escape("two\nlines"), "\"two\nlines\"");
}

TEST(IoReport, LinesParseBackToTheSameFields) {
    const std::vector<std::string> fields = {"dir/a,b.mlcp", "", "x: offset 3: \"bad\", really", "multi\nline", "7"};
    const auto records = io_test::parse_csv(csv_line(fields) + csv_line({"1", "2"}));
    ASSERT_EQ(records.size(), 2u);
    EXPECT_EQ(records[0], fields);
    EXPECT_EQ(records[1], (std::vector<std::string>{"1", "2"}));
}

TEST(IoReport, EveryRowHasOneFieldPerColumn) {
    const std::size_t columns = ode_bpp::io::report_columns().size();
    EXPECT_EQ(columns, 18u);
    const auto failed = ode_bpp::io::report_fields(ode_bpp::io::read_error_record("f.mlcp", "f.mlcp: offset 0: bad magic"));
    ASSERT_EQ(failed.size(), columns);
    EXPECT_EQ(failed[0], "f.mlcp");
    EXPECT_EQ(failed[5], "read-error");
    EXPECT_EQ(failed[6], "f.mlcp: offset 0: bad magic");
    ode_bpp::io::SolveRecord solved;
    solved.file = "g.mlcp";
    EXPECT_EQ(ode_bpp::io::report_fields(solved).size(), columns);
}

TEST(IoReport, SolveRecordDescribesTheProblem) {
    const ode_bpp::ReadResult read = ode_bpp::read_mlcp((io_test::data_dir() / "box-contact-13.mlcp").string());
    ASSERT_TRUE(read.ok) << read.error;
    ode_bpp::Options options;
    options.method = ode_bpp::Method::Bpp;
    const auto record = ode_bpp::io::solve_and_time(read.file, "box.mlcp", options, 3);
    const auto fields = ode_bpp::io::report_fields(record);
    const auto& columns = ode_bpp::io::report_columns();
    auto column = [&](const std::string& name) {
        return fields[std::find(columns.begin(), columns.end(), name) - columns.begin()];
    };
    EXPECT_EQ(column("file"), "box.mlcp");
    EXPECT_EQ(column("n"), "13");
    EXPECT_EQ(column("nub"), "0");
    EXPECT_EQ(column("friction_rows"), "8");  // 4 contacts x 2 friction rows
    EXPECT_EQ(column("method"), "bpp");
    // printed with 9 significant digits
    EXPECT_NEAR(std::stod(column("natural_residual")), record.result.residuals.natural,
                1e-8 * record.result.residuals.natural);
}

TEST(IoReport, EqualityProblemIsSolved) {
    // every row of the ball chain is an equality, so any correct method meets x_ref's residual
    const ode_bpp::ReadResult read = ode_bpp::read_mlcp((io_test::data_dir() / "ball-chain-12.mlcp").string());
    ASSERT_TRUE(read.ok) << read.error;
    double b_norm = 0;
    for (double b : read.file.b) b_norm = std::max(b_norm, std::abs(b));
    for (ode_bpp::Method method : {ode_bpp::Method::Bpp, ode_bpp::Method::BppChol, ode_bpp::Method::Dantzig}) {
        ode_bpp::Options options;
        options.method = method;
        const auto record = ode_bpp::io::solve_and_time(read.file, "chain", options, 1);
        EXPECT_TRUE(ode_bpp::is_usable(record.result.status)) << to_string(method);
        EXPECT_LE(record.result.residuals.natural, 1e-9 * std::max(1.0, b_norm)) << to_string(method);
    }
}

TEST(IoReport, ListsOnlyProblemFilesSorted) {
    const fs::path dir = fs::temp_directory_path() / ("ode_bpp_list_" + std::to_string(::getpid()));
    fs::create_directories(dir / "sub.mlcp");
    for (const char* name : {"b.mlcp", "a.mlcp", "c.txt", "a.mlcp.bak"}) std::ofstream(dir / name) << "x";
    std::vector<std::string> files = {"already-there"};
    std::string error;
    ASSERT_TRUE(ode_bpp::io::list_problem_files(dir.string(), &files, &error)) << error;
    EXPECT_EQ(files, (std::vector<std::string>{"already-there", (dir / "a.mlcp").string(), (dir / "b.mlcp").string()}));
    fs::remove_all(dir);
    EXPECT_FALSE(ode_bpp::io::list_problem_files(dir.string(), &files, &error));
    EXPECT_NE(error.find(dir.string()), std::string::npos) << error;
}

}  // namespace
