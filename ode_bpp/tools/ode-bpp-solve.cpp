// ode-bpp-solve: solves MLCP problem files (docs/mlcp-format.md) with several methods and
// writes one CSV row per (file, method). See usage() for the options.
//
// Exit status: 0 when every file was read, 1 when some file could not be read (or the CSV
// could not be written), 2 on bad arguments. Solver failures are data, not errors: they
// are reported in the status column.
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "io/solve_report.h"
#include "ode_bpp/io.h"
#include "ode_bpp/solver.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;
/// From this many files on, a progress line per file goes to stderr.
constexpr std::size_t kProgressFromFiles = 10;

struct Cli {
    std::vector<ode_bpp::Method> methods;
    ode_bpp::FrictionMode friction = ode_bpp::FrictionMode::Frozen;
    std::optional<int> max_pivots;
    std::optional<int> pgs_iterations;
    int repeat = 1;
    bool factor_error = false;
    bool warm = false;         ///< start from the file's warm_start and ordering metadata
    bool warm_states = false;  ///< the warm_start metadata only; the ordering chosen afresh
    std::string csv_path;  ///< empty: stdout
    std::vector<std::string> inputs;
    bool help = false;
};

bool reject(std::string* error, const std::string& reason) {
    *error = reason;
    return false;
}

std::nullopt_t refuse(std::string* error, const std::string& reason) {
    *error = reason;
    return std::nullopt;
}

std::string joined_method_names() {
    std::string names;
    for (const std::string& name : ode_bpp::method_names()) names += (names.empty() ? "" : ",") + name;
    return names;
}

std::string usage() {
    std::ostringstream out;
    out << "usage: ode-bpp-solve [options] FILE|DIR...\n"
           "Solves MLCP files (a DIR stands for every *.mlcp in it, sorted) and writes CSV,\n"
           "one row per (file, method).\n"
           "  --methods LIST        comma-separated, from: "
        << joined_method_names()
        << " (default: all)\n"
           "  --friction MODE       frozen|consistent (default: frozen)\n"
           "  --max-pivots N        pivot-step budget per fixed-bound solve\n"
           "  --pgs-iterations N    sweeps of pgs\n"
           "  --repeat R            solve R times, report the median time (default: 1)\n"
           "  --factor-error        compute the factor error of the final index set\n"
           "  --warm                start each solve from the file's warm_start and ordering\n"
           "                        metadata (as a capture inside ODE records them; cold where absent)\n"
           "  --warm-states         the same with the warm_start metadata only: each solve chooses\n"
           "                        its ordering afresh (to judge an ordering policy)\n"
           "  --csv OUT.csv         write the CSV there instead of stdout\n"
           "  --help                show this text\n"
           "Exit status: 0 every file read, 1 a file could not be read or the CSV not written,\n"
           "2 bad arguments. A solver's failure is data (the status column), not an error.\n";
    return out.str();
}

std::optional<int> positive_int(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (*end != '\0' || errno == ERANGE || v < 1 || v > 1000000000L) return std::nullopt;
    return static_cast<int>(v);
}

/// The methods of a comma-separated list; nullopt with the reason for an unknown name or none.
std::optional<std::vector<ode_bpp::Method>> parse_methods(const std::string& list, std::string* error) {
    std::vector<ode_bpp::Method> methods;
    std::stringstream in(list);
    std::string name;
    while (std::getline(in, name, ',')) {
        const auto method = ode_bpp::method_from_string(name);
        if (!method) return refuse(error, "unknown method '" + name + "'; valid: " + joined_method_names());
        methods.push_back(*method);
    }
    if (methods.empty()) return refuse(error, "--methods needs at least one of: " + joined_method_names());
    return methods;
}

// Applies one "--name value" option; false with a reason on error.
bool apply_option(Cli& cli, const std::string& name, const std::string& value, std::string* error) {
    if (name == "--methods") {
        const auto methods = parse_methods(value, error);
        if (!methods) return false;
        cli.methods = *methods;
    } else if (name == "--friction") {
        const auto friction = ode_bpp::friction_from_string(value);
        if (!friction) return reject(error, "unknown friction mode \"" + value + "\"; valid: frozen, consistent");
        cli.friction = *friction;
    } else if (name == "--max-pivots" || name == "--pgs-iterations" || name == "--repeat") {
        const auto v = positive_int(value);
        if (!v) return reject(error, name + " needs a positive integer, got \"" + value + "\"");
        if (name == "--max-pivots") cli.max_pivots = *v;
        if (name == "--pgs-iterations") cli.pgs_iterations = *v;
        if (name == "--repeat") cli.repeat = *v;
    } else if (name == "--csv") {
        if (value.empty()) return reject(error, "--csv needs a file name");
        cli.csv_path = value;
    } else {
        return reject(error, "unknown option " + name);
    }
    return true;
}

bool takes_value(const std::string& name) {
    return name == "--methods" || name == "--friction" || name == "--max-pivots" || name == "--pgs-iterations" ||
           name == "--repeat" || name == "--csv";
}

std::optional<Cli> parse_args(int argc, char** argv, std::string* error) {
    Cli cli;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            cli.help = true;
        } else if (arg == "--factor-error") {
            cli.factor_error = true;
        } else if (arg == "--warm") {
            cli.warm = true;
        } else if (arg == "--warm-states") {
            cli.warm = cli.warm_states = true;
        } else if (arg.rfind("--", 0) == 0) {
            const std::size_t eq = arg.find('=');
            const std::string name = arg.substr(0, eq);
            if (!takes_value(name)) return refuse(error, "unknown option " + arg);
            if (eq == std::string::npos && i + 1 >= argc) return refuse(error, name + " needs a value");
            const std::string value = eq == std::string::npos ? argv[++i] : arg.substr(eq + 1);
            if (!apply_option(cli, name, value, error)) return std::nullopt;
        } else {
            cli.inputs.push_back(arg);
        }
    }
    if (cli.methods.empty()) {
        for (const std::string& name : ode_bpp::method_names()) cli.methods.push_back(*ode_bpp::method_from_string(name));
    }
    if (!cli.help && cli.inputs.empty()) return refuse(error, "no FILE or DIR given");
    return cli;
}

ode_bpp::Options options_for(const Cli& cli, ode_bpp::Method method) {
    ode_bpp::Options options;
    options.method = method;
    options.friction = cli.friction;
    if (cli.max_pivots) options.max_pivots = *cli.max_pivots;
    if (cli.pgs_iterations) options.pgs_iterations = *cli.pgs_iterations;
    options.compute_factor_error = cli.factor_error;
    options.record_steps = false;  // not reported; keeps the timing to the solve itself
    return options;
}

// Expands directories; an input that cannot be listed or found still becomes an entry, so
// that reading it reports the reason in the CSV.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs, bool* ok) {
    std::vector<std::string> files;
    for (const std::string& input : inputs) {
        std::error_code ec;
        if (!std::filesystem::is_directory(input, ec)) {
            files.push_back(input);
            continue;
        }
        std::string error;
        const std::size_t before = files.size();
        if (!ode_bpp::io::list_problem_files(input, &files, &error)) {
            std::cerr << "ode-bpp-solve: " << error << "\n";
            *ok = false;
        } else if (files.size() == before) {
            std::cerr << "ode-bpp-solve: " << input << ": no *.mlcp files\n";
            *ok = false;
        }
    }
    return files;
}

/// The Start each solve of `file` begins from: cold, or its metadata's (--warm; --warm-states
/// without the ordering); nullopt, with the reason in *error, when that does not fit the file.
std::optional<ode_bpp::Start> start_for(const Cli& cli, const ode_bpp::MlcpFile& file, std::string* error) {
    if (!cli.warm) return ode_bpp::Start{};
    std::optional<ode_bpp::Start> start = ode_bpp::start_from_metadata(file.meta, file.n, error);
    if (start && cli.warm_states) start->ordering.clear();
    return start;
}

// Reads and solves every file; returns false if some file could not be read.
bool run(const Cli& cli, const std::vector<std::string>& files, std::ostream& csv) {
    bool all_read = true;
    csv << ode_bpp::io::csv_line(ode_bpp::io::report_columns());
    for (std::size_t k = 0; k < files.size(); ++k) {
        if (files.size() >= kProgressFromFiles)
            std::cerr << "ode-bpp-solve: [" << k + 1 << "/" << files.size() << "] " << files[k] << "\n";
        const ode_bpp::ReadResult read = ode_bpp::read_mlcp(files[k]);
        std::string error = read.error;
        std::optional<ode_bpp::Start> start;
        if (read.ok && !(start = start_for(cli, read.file, &error))) error = files[k] + ": " + error;
        if (!start) {
            std::cerr << "ode-bpp-solve: " << error << "\n";
            csv << ode_bpp::io::csv_line(ode_bpp::io::report_fields(ode_bpp::io::read_error_record(files[k], error)));
            all_read = false;
            continue;
        }
        for (ode_bpp::Method method : cli.methods) {
            const auto record =
                ode_bpp::io::solve_and_time(read.file, files[k], options_for(cli, method), cli.repeat, *start);
            csv << ode_bpp::io::csv_line(ode_bpp::io::report_fields(record)) << std::flush;
        }
    }
    return all_read;
}

}  // namespace

int main(int argc, char** argv) {
    std::string error;
    const std::optional<Cli> cli = parse_args(argc, argv, &error);
    if (!cli) {
        std::cerr << "ode-bpp-solve: " << error << "\n" << usage();
        return kExitUsage;
    }
    if (cli->help) {
        std::cout << usage();
        return kExitOk;
    }
    bool ok = true;
    const std::vector<std::string> files = expand_inputs(cli->inputs, &ok);
    std::ofstream csv_file;
    if (!cli->csv_path.empty()) {
        csv_file.open(cli->csv_path);
        if (!csv_file) {
            std::cerr << "ode-bpp-solve: cannot write " << cli->csv_path << "\n";
            return kExitFailure;
        }
    }
    std::ostream& csv = cli->csv_path.empty() ? std::cout : csv_file;
    ok = run(*cli, files, csv) && ok;
    csv.flush();
    if (!csv) {
        std::cerr << "ode-bpp-solve: error writing the CSV\n";
        return kExitFailure;
    }
    return ok ? kExitOk : kExitFailure;
}
