// The CSV report of ode-bpp-solve: one row per (problem file, method).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"

namespace ode_bpp::io {

/// One report row. A file that could not be read has read_error set, its message in
/// result.message, and no problem data.
struct SolveRecord {
    std::string file;
    bool read_error = false;
    int n = 0;
    int nub = 0;
    int friction_rows = 0;  ///< rows with findex >= 0
    double time_us = 0;     ///< median wall time of one solve() call
    Result result;
};

/// The report's column names, in order.
const std::vector<std::string>& report_columns();
/// The fields of one row, aligned with report_columns().
std::vector<std::string> report_fields(const SolveRecord& record);

/// RFC 4180 quoting: a field containing a comma, a quote, CR or LF is enclosed in quotes,
/// with inner quotes doubled.
std::string csv_escape(std::string_view field);
/// Escaped fields joined by commas, terminated by "\n".
std::string csv_line(const std::vector<std::string>& fields);

/// Solves the file's problem repeat >= 1 times with the given options from `start` (x starts
/// from zero each time) and records the last Result and the median time.
SolveRecord solve_and_time(const MlcpFile& problem, const std::string& file, const Options& options, int repeat,
                           const Start& start = {});

/// A row for a file that could not be read; error is the reader's message.
SolveRecord read_error_record(const std::string& file, const std::string& error);

/// The regular files named *.mlcp directly inside dir, sorted by path. Fails (false, error
/// set) if dir cannot be listed.
bool list_problem_files(const std::string& dir, std::vector<std::string>* files, std::string* error);

}  // namespace ode_bpp::io
