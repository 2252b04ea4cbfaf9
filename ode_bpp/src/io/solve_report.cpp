#include "io/solve_report.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <system_error>

namespace ode_bpp::io {
namespace {

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string microseconds(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.3f", v);
    return buf;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t mid = values.size() / 2;
    return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

}  // namespace

const std::vector<std::string>& report_columns() {
    static const std::vector<std::string> columns = {
        "file", "n", "nub", "friction_rows", "method", "status", "message", "time_us", "pivots",
        "murty_pivots", "downdate_steps", "refactor_steps", "tight", "natural_residual",
        "relative_natural_residual", "free_residual", "friction_error", "factor_error"};
    return columns;
}

std::vector<std::string> report_fields(const SolveRecord& rec) {
    if (rec.read_error) {
        std::vector<std::string> fields(report_columns().size());
        fields[0] = rec.file;
        fields[5] = "read-error";
        fields[6] = rec.result.message;
        return fields;
    }
    const Result& r = rec.result;
    return {rec.file,
            std::to_string(rec.n),
            std::to_string(rec.nub),
            std::to_string(rec.friction_rows),
            to_string(r.method),
            to_string(r.status),
            r.message,
            microseconds(rec.time_us),
            std::to_string(r.pivoting.pivots),
            std::to_string(r.pivoting.murty_pivots),
            std::to_string(r.pivoting.downdate_steps),
            std::to_string(r.pivoting.refactor_steps),
            std::to_string(r.tight),
            number(r.residuals.natural),
            number(r.residuals.relative_natural),
            number(r.residuals.free),
            number(r.residuals.friction),
            number(r.factor_error)};
}

std::string csv_escape(std::string_view field) {
    if (field.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(field);
    std::string quoted = "\"";
    for (char c : field) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
    std::string line;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        if (i) line += ',';
        line += csv_escape(fields[i]);
    }
    return line + "\n";
}

SolveRecord solve_and_time(const MlcpFile& problem, const std::string& file, const Options& options, int repeat,
                           const Start& start) {
    SolveRecord rec;
    rec.file = file;
    rec.n = problem.n;
    rec.nub = problem.nub;
    rec.friction_rows = static_cast<int>(std::count_if(problem.findex.begin(), problem.findex.end(),
                                                       [](int f) { return f >= 0; }));
    const Problem view = problem.view();
    std::vector<double> x(static_cast<std::size_t>(problem.n));
    std::vector<double> times;
    for (int run = 0; run < std::max(1, repeat); ++run) {
        std::fill(x.begin(), x.end(), 0.0);
        const auto began = std::chrono::steady_clock::now();
        rec.result = solve(view, options, x.data(), start);
        const auto stop = std::chrono::steady_clock::now();
        times.push_back(std::chrono::duration<double, std::micro>(stop - began).count());
    }
    rec.time_us = median(times);
    return rec;
}

SolveRecord read_error_record(const std::string& file, const std::string& error) {
    SolveRecord rec;
    rec.file = file;
    rec.read_error = true;
    rec.result.message = error;
    return rec;
}

bool list_problem_files(const std::string& dir, std::vector<std::string>* files, std::string* error) {
    namespace fs = std::filesystem;
    std::vector<std::string> found;
    std::error_code ec;
    fs::directory_iterator it(dir, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
        std::error_code kind_ec;  // a dangling *.mlcp link is listed, so that reading it reports why
        if (it->path().extension() == ".mlcp" && !it->is_directory(kind_ec)) found.push_back(it->path().string());
    }
    if (ec) {
        *error = dir + ": cannot list: " + ec.message();
        return false;
    }
    std::sort(found.begin(), found.end());
    files->insert(files->end(), found.begin(), found.end());
    return true;
}

}  // namespace ode_bpp::io
