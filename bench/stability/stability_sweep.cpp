// stability_sweep: where each method stops working. Runs table-driven grids of the sweep scenes
// (demos/scenes/sweep_scenes.h) with every method and writes one CSV row per run
// (demos/scenes/sweep_run.h defines the outcome and the measures).
//
//   stability_sweep --out DIR [--quick] [--sweep NAME]...   the grids below, DIR/NAME.csv each
//   stability_sweep --list [--quick]                         the grids and their run counts
//   stability_sweep --one PATTERN METHOD RATIO CFM H LINKS SECONDS   a single run, to stdout
#include <sys/wait.h>
#include <unistd.h>

#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/sweep_run.h"

namespace {

using ode_bpp::scenes::RunResult;
using ode_bpp::scenes::RunSpec;
using ode_bpp::scenes::SweepPattern;

/// One grid: the cross product of its lists, each run with every method.
struct Sweep {
    std::string name;
    std::string what;
    std::vector<SweepPattern> patterns;
    std::vector<double> ratios;
    std::vector<double> cfms;
    std::vector<double> steps;
    std::vector<int> links;      ///< 0: the pattern's default
    double seconds = 5;
    bool consistent_bpp_too = false;  ///< also run "bpp" with Consistent friction ("bpp-consistent")
};

std::vector<double> powers_of_ten(int from, int to, int by) {
    std::vector<double> v;
    for (int e = from; by > 0 ? e <= to : e >= to; e += by) v.push_back(std::pow(10.0, e));
    return v;
}

/// The coarse list for --quick, the full one otherwise.
template <class T>
std::vector<T> pick(bool quick, std::vector<T> coarse, std::vector<T> full) {
    return quick ? coarse : full;
}

std::vector<Sweep> sweeps(bool quick) {
    using P = SweepPattern;
    const double h60 = 1.0 / 60;  // paper Table 1
    std::vector<Sweep> s;
    // mass ratio 1:1 .. 1e7:1 x CFM 1e-4 .. 1e-12 (the map); 20 s per run as in Table 1
    s.push_back({"mass-cfm", "mass ratio x CFM, three heavy-on-light patterns, h = 1/60",
                 {P::HangingChain, P::BoxStack, P::Offshore},
                 pick<double>(quick, {1, 1e2, 1e4, 1e6, 1e7}, powers_of_ten(0, 7, 1)),
                 powers_of_ten(-4, -12, quick ? -2 : -1), {h60}, {0}, quick ? 3.0 : 20.0});
    // time step 1/30 .. 1/240 at hard points of the map, at ODE's default CFM
    s.push_back({"timestep", "time step at mass ratio 1e4 and 1e6, CFM 1e-10", {P::HangingChain, P::Offshore},
                 pick<double>(quick, {1e6}, {1e4, 1e6}), {1e-10},
                 pick<double>(quick, {1.0 / 30, 1.0 / 240}, {1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240}), {0},
                 quick ? 2.0 : 10.0});
    // closed loops: redundant hinge rows; CFM 0 makes A singular
    s.push_back({"loops", "ladder of parallelogram cells (redundant hinges), CFM down to 0", {P::Ladder},
                 pick<double>(quick, {1, 1e4}, {1, 1e2, 1e4, 1e6}),
                 pick<double>(quick, {1e-6, 0}, {1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 0}), {h60}, {0},
                 quick ? 3.0 : 20.0});
    // long chains
    s.push_back({"chain-length", "hanging chain of N links, mass ratio 100, CFM 1e-10", {P::HangingChain}, {100},
                 {1e-10}, {h60}, pick<int>(quick, {50, 100}, {50, 100, 200, 400}), quick ? 1.0 : 2.0});
    // coupled friction: two friction contacts stacked, the top one at its limit; the pair stops
    // after about 0.2 s
    s.push_back({"friction", "sliding pair (coupled friction), mass ratio x CFM", {P::SlidingPair},
                 pick<double>(quick, {1, 1e4}, {1, 1e2, 1e4, 1e6}), pick<double>(quick, {1e-8}, {1e-4, 1e-8, 1e-12}),
                 {h60}, {0}, 2.0, true});
    return s;
}

struct MethodRun {
    std::string method;
    int iterations;
    bool consistent_friction;
};

std::vector<MethodRun> methods(const Sweep& s) {
    std::vector<MethodRun> m;
    for (const std::string& name : ode_bpp::scenes::sweep_methods()) {
        m.push_back({name, name == "quickstep" ? 20 : 35, false});  // quickstep: ODE's default iterations
    }
    if (s.consistent_bpp_too) m.push_back({"bpp", 35, true});
    return m;
}

/// The method column: the solver name, "-consistent" when friction is Consistent.
std::string method_label(const RunSpec& spec) {
    return spec.method + (spec.options.friction == ode_bpp::FrictionMode::Consistent ? "-consistent" : "");
}

long count_runs(const Sweep& s) {
    return static_cast<long>(s.patterns.size() * s.ratios.size() * s.cfms.size() * s.steps.size() * s.links.size() *
                             methods(s).size());
}

const char* kCsvHeader =
    "sweep,pattern,method,iterations,mass_ratio,cfm,step,links,seconds,outcome,cause,steps_run,tolerance,"
    "max_joint_error,max_penetration,worst_placement,energy_drift,final_slide,lcp_internal_errors,islands,failures,"
    "fallbacks,max_iterations,not_spd,regularized,friction_not_consistent,murty_pivots,rescues,friction_rounds,"
    "friction_excess,pivots,wall_seconds";

int links_of(const RunSpec& spec) {
    return spec.scene.links > 0 ? spec.scene.links : ode_bpp::scenes::default_links(spec.scene.pattern);
}

/// One CSV line (kCsvHeader's columns); commas in the cause become semicolons.
std::string csv_row(const Sweep& s, const RunSpec& spec, const RunResult& r) {
    std::ostringstream o;
    o.precision(6);
    std::string cause = r.cause;
    for (char& c : cause) c = c == ',' ? ';' : c;
    o << s.name << ',' << to_string(spec.scene.pattern) << ',' << method_label(spec) << ',' << spec.iterations << ','
      << spec.scene.mass_ratio << ',' << spec.cfm << ',' << spec.step << ',' << links_of(spec) << ','
      << spec.seconds << ',' << to_string(r.outcome) << ",\"" << cause << "\"," << r.steps << ',' << r.tolerance
      << ',' << r.max_joint_error << ',' << r.max_penetration << ',' << r.worst_placement << ',' << r.energy_drift
      << ',' << r.final_slide << ',' << r.lcp_internal_errors << ',' << r.islands << ',' << r.failures << ','
      << r.fallbacks << ',' << r.max_iterations << ',' << r.not_spd << ',' << r.regularized << ','
      << r.friction_not_consistent << ',' << r.murty_pivots << ',' << r.rescues << ',' << r.friction_rounds << ','
      << r.friction_excess << ',' << r.pivots << ',' << r.seconds_wall;
    return o.str();
}

std::string describe(const RunSpec& spec) {
    char line[200];
    std::snprintf(line, sizeof line, "%-8s %-14s r=%-7.0e cfm=%-7.0e h=1/%-3.0f N=%-3d", to_string(spec.scene.pattern),
                  method_label(spec).c_str(), spec.scene.mass_ratio, spec.cfm, 1.0 / spec.step, links_of(spec));
    return line;
}

// ---- each run in a child process: ODE aborts on some internal errors (e.g. a quaternion that
// can no longer be normalized after a non-finite step); that is an explosion of the run, not the
// end of the sweep.

const Sweep* g_sweep = nullptr;
const RunSpec* g_spec = nullptr;
int g_row_fd = -1;

void write_all(int fd, const std::string& text) {
    size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n <= 0) return;
        done += static_cast<size_t>(n);
    }
}

RunResult crashed(const std::string& why) {
    RunResult r;
    r.outcome = ode_bpp::scenes::Outcome::Exploded;
    r.cause = why;
    r.steps = -1;  // unknown: the process ended inside the step
    return r;
}

/// ODE's error and debug handlers in the child: record the run as exploded and end the child.
void on_ode_fatal(int errnum, const char* msg, va_list ap) {
    char text[300];
    std::vsnprintf(text, sizeof text, msg, ap);
    std::string why = "ODE internal error " + std::to_string(errnum) + ": " + text;
    for (char& c : why) c = c == '"' ? '\'' : c;
    write_all(g_row_fd, csv_row(*g_sweep, *g_spec, crashed(why)) + "\n");
    _exit(3);
}

/// One run in a forked child; returns its CSV row and fills outcome and cause for the progress line.
std::string run_isolated(const Sweep& s, const RunSpec& spec, std::string& outcome, std::string& cause, double& wall) {
    int fds[2];
    if (::pipe(fds) != 0) {
        const RunResult r = ode_bpp::scenes::run_sweep(spec);
        outcome = to_string(r.outcome), cause = r.cause, wall = r.seconds_wall;
        return csv_row(s, spec, r);
    }
    const auto t0 = std::chrono::steady_clock::now();
    const pid_t child = ::fork();
    if (child == 0) {
        ::close(fds[0]);
        g_sweep = &s, g_spec = &spec, g_row_fd = fds[1];
        dSetErrorHandler(&on_ode_fatal);
        dSetDebugHandler(&on_ode_fatal);
        write_all(fds[1], csv_row(s, spec, ode_bpp::scenes::run_sweep(spec)) + "\n");
        _exit(0);
    }
    ::close(fds[1]);
    std::string row;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) row.append(buffer, static_cast<size_t>(n));
    ::close(fds[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (row.empty()) {
        const std::string why = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                                    : "ended with status " + std::to_string(WEXITSTATUS(status));
        row = csv_row(s, spec, crashed(why)) + "\n";
    }
    while (!row.empty() && row.back() == '\n') row.pop_back();
    // outcome and cause are the 10th and 11th fields; the cause is the only quoted one
    size_t field = 0, at = 0;
    for (; field < 9 && at < row.size(); ++at) field += row[at] == ',' ? 1 : 0;
    const size_t comma = row.find(',', at);
    outcome = row.substr(at, comma - at);
    const size_t open = row.find('"', comma), close = row.find('"', open + 1);
    cause = open != std::string::npos && close != std::string::npos ? row.substr(open + 1, close - open - 1) : "";
    return row;
}

/// Runs one grid into DIR/NAME.csv, printing one progress line per run.
bool run_sweep_grid(const Sweep& s, const std::string& dir, long& done, long total) {
    std::ofstream csv(dir + "/" + s.name + ".csv");
    if (!csv) {
        std::cerr << "stability_sweep: cannot write " << dir << "/" << s.name << ".csv\n";
        return false;
    }
    csv << kCsvHeader << '\n';
    for (SweepPattern p : s.patterns)
        for (int links : s.links)
            for (double h : s.steps)
                for (double cfm : s.cfms)
                    for (double ratio : s.ratios)
                        for (const MethodRun& m : methods(s)) {
                            RunSpec spec;
                            spec.scene = {p, ratio, links};
                            spec.method = m.method;
                            spec.iterations = m.iterations;
                            if (m.consistent_friction) spec.options.friction = ode_bpp::FrictionMode::Consistent;
                            spec.step = h;
                            spec.cfm = cfm;
                            spec.seconds = s.seconds;
                            std::string outcome, cause;
                            double wall = 0;
                            csv << run_isolated(s, spec, outcome, cause, wall) << '\n' << std::flush;
                            ++done;
                            std::printf("[%4ld/%4ld] %-12s %s %-12s %6.2fs %s\n", done, total, s.name.c_str(),
                                        describe(spec).c_str(), outcome.c_str(), wall, cause.c_str());
                            std::fflush(stdout);
                        }
    return true;
}

int run_one(char** argv) {
    RunSpec spec;
    const auto pattern = ode_bpp::scenes::sweep_pattern_from_string(argv[0]);
    if (!pattern) {
        std::cerr << "stability_sweep: unknown pattern " << argv[0] << '\n';
        return 2;
    }
    spec.scene = {*pattern, std::atof(argv[2]), std::atoi(argv[5])};
    spec.method = argv[1];
    spec.iterations = spec.method == "quickstep" ? 20 : 35;
    spec.cfm = std::atof(argv[3]);
    spec.step = std::atof(argv[4]);
    spec.seconds = std::atof(argv[6]);
    const Sweep none{"one", "", {}, {}, {}, {}, {}, 0};
    std::cout << kCsvHeader << '\n' << csv_row(none, spec, ode_bpp::scenes::run_sweep(spec)) << '\n';
    return 0;
}

int usage() {
    std::cerr << "usage: stability_sweep --out DIR [--quick] [--sweep NAME]...\n"
                 "       stability_sweep --list [--quick]\n"
                 "       stability_sweep --one PATTERN METHOD RATIO CFM H LINKS SECONDS\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::string out;
    bool quick = false, list = false;
    std::vector<std::string> only;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick") quick = true;
        else if (a == "--list") list = true;
        else if (a == "--out" && i + 1 < argc) out = argv[++i];
        else if (a == "--sweep" && i + 1 < argc) only.push_back(argv[++i]);
        else if (a == "--one" && i + 7 < argc) return run_one(argv + i + 1);
        else return usage();
    }
    std::vector<Sweep> chosen;
    for (const Sweep& s : sweeps(quick)) {
        if (only.empty() || std::find(only.begin(), only.end(), s.name) != only.end()) chosen.push_back(s);
    }
    long total = 0;
    for (const Sweep& s : chosen) total += count_runs(s);
    if (list) {
        for (const Sweep& s : chosen) std::cout << s.name << '\t' << count_runs(s) << '\t' << s.what << '\n';
        return 0;
    }
    if (out.empty() || chosen.empty()) return usage();
    long done = 0;
    for (const Sweep& s : chosen) {
        if (!run_sweep_grid(s, out, done, total)) return 1;
    }
    return 0;
}
