// ode-bpp-soak: steps scenes for a long time and watches what must not drift: the bodies stay
// finite, islands stop going to ODE's Dantzig, and the process's memory stays flat.
//
//   ode-bpp-soak SCENE... [--solver NAME] [--steps N] [--every K] [--baseline STEP] [--csv FILE]
//
// Every K steps (default 1,000) one CSV row per scene: resident memory (RSS, from /proc/self/statm),
// its peak, ODE's statistics (islands, largest island since the last row, solves that fell back,
// solves answered by ODE's Dantzig), and wall time; a progress line goes to stderr. At the end of
// each scene, one verdict line on stdout:
//   - finite: every body's position, velocity and orientation finite at every row;
//   - fallbacks: the count at the last step equals the count at the baseline step (10,000);
//   - memory: RSS at the last step within 1 % of RSS at the baseline step.
// Nothing is kept per step, so the tool's own memory is flat. Exit status: 0 when every scene
// passed, 1 when one did not, 2 on bad arguments.
#include <ode/mlcp.h>
#include <ode/ode.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace {

using namespace ode_bpp::scenes;
using Clock = std::chrono::steady_clock;

constexpr int kExitFailed = 1, kExitUsage = 2;
/// Memory may differ by this share between the baseline step and the last one.
constexpr double kRssTolerance = 0.01;

struct Args {
    std::vector<std::string> scenes;
    std::string solver = "bpp";
    long steps = 100000;
    long every = 1000;
    long baseline = 10000;
    std::string csv;
};

[[noreturn]] void usage(const std::string& error) {
    std::fprintf(stderr,
                 "ode-bpp-soak: %s\n"
                 "usage: ode-bpp-soak SCENE... [--solver NAME] [--steps N] [--every K] [--baseline STEP] [--csv FILE]\n",
                 error.c_str());
    std::exit(kExitUsage);
}

long parse_count(const std::string& option, const char* text) {
    char* end = nullptr;
    const long value = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || value < 1) usage(option + " needs a positive integer, got '" + text + "'");
    return value;
}

Args parse_args(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) usage(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--solver") a.solver = value();
        else if (arg == "--steps") a.steps = parse_count(arg, value());
        else if (arg == "--every") a.every = parse_count(arg, value());
        else if (arg == "--baseline") a.baseline = parse_count(arg, value());
        else if (arg == "--csv") a.csv = value();
        else if (!arg.empty() && arg[0] == '-') usage("unknown option " + arg);
        else if (!make_scene(arg)) usage("unknown scene '" + arg + "'");
        else a.scenes.push_back(arg);
    }
    if (a.scenes.empty()) usage("no scene given");
    if (a.baseline % a.every != 0 || a.steps % a.every != 0 || a.baseline >= a.steps)
        usage("--baseline and --steps must be multiples of --every, the baseline before the last step");
    if (!is_solver_registered(a.solver)) usage("unknown solver '" + a.solver + "'");
    return a;
}

/// Resident and peak resident memory of this process [kB] (Linux /proc).
struct Memory {
    long rss_kb = 0, peak_kb = 0;
};

Memory memory_now() {
    Memory m;
    long pages = 0, resident = 0;
    if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%ld %ld", &pages, &resident) == 2) m.rss_kb = resident * (sysconf(_SC_PAGESIZE) / 1024);
        std::fclose(f);
    }
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0) m.peak_kb = std::atol(line.c_str() + 6);
    return m;
}

bool body_is_finite(dBodyID b) {
    const dReal* p = dBodyGetPosition(b);
    const dReal* v = dBodyGetLinearVel(b);
    const dReal* q = dBodyGetQuaternion(b);
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(p[k]) || !std::isfinite(v[k])) return false;
    return std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]) && std::isfinite(q[3]);
}

int non_finite_bodies(const SceneWorld& w) {
    return static_cast<int>(std::count_if(w.bodies().begin(), w.bodies().end(), [](dBodyID b) { return !body_is_finite(b); }));
}

/// One CSV row's worth of a scene run.
struct Sample {
    long step = 0;
    Memory memory;
    dMLCPStepStats total{};
    long window_max_rows = 0;
    int non_finite = 0;
    double wall_seconds = 0;
};

const char* kCsvHeader =
    "scene,solver,step,sim_seconds,rss_kb,peak_rss_kb,islands,max_rows_window,fallbacks,failures,non_finite,"
    "solve_seconds,wall_seconds\n";

void write_row(std::ofstream* csv, const std::string& scene, const std::string& solver, double step_size, const Sample& s) {
    if (!csv) return;
    *csv << scene << ',' << solver << ',' << s.step << ',' << s.step * step_size << ',' << s.memory.rss_kb << ','
         << s.memory.peak_kb << ',' << s.total.islands << ',' << s.window_max_rows << ',' << s.total.fallbacks << ','
         << s.total.failures << ',' << s.non_finite << ',' << s.total.seconds << ',' << s.wall_seconds << '\n';
    csv->flush();
}

void report_progress(const std::string& scene, const Args& a, const Sample& s) {
    const double eta = s.wall_seconds / s.step * (a.steps - s.step);
    std::fprintf(stderr, "[soak] %s/%s step %ld of %ld: RSS %ld kB, fallbacks %lld, largest island %ld rows, %.0f s, ~%.0f s to go\n",
                 scene.c_str(), a.solver.c_str(), s.step, a.steps, s.memory.rss_kb, static_cast<long long>(s.total.fallbacks),
                 s.window_max_rows, s.wall_seconds, eta);
}

/// Runs one scene for a.steps steps; prints its verdict and returns whether it passed.
bool soak(const std::string& name, const Args& a, std::ofstream* csv) {
    std::unique_ptr<Scene> scene = make_scene(name);
    SceneParams params;
    params.solver = a.solver;
    SceneWorld w(params);
    scene->build(w);
    const Clock::time_point start = Clock::now();
    Sample baseline, s;
    bool finite = true;
    dMLCPStepStats last{};
    for (long step = 1; step <= a.steps; ++step) {
        scene->control(w, w.time());
        const bool stepped = w.step();
        if (dWorldGetMLCPStats(w.world(), &last, nullptr)) s.window_max_rows = std::max(s.window_max_rows, static_cast<long>(last.max_rows));
        if (step % a.every != 0 && stepped) continue;
        s.step = step;
        s.memory = memory_now();
        dWorldGetMLCPStats(w.world(), nullptr, &s.total);
        s.non_finite = stepped ? non_finite_bodies(w) : static_cast<int>(w.bodies().size());
        s.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
        write_row(csv, name, a.solver, params.step, s);
        report_progress(name, a, s);
        finite = finite && stepped && s.non_finite == 0;
        if (!finite) break;
        if (step == a.baseline) baseline = s;
        s.window_max_rows = 0;
    }
    const bool reached = finite && s.step == a.steps;
    const bool fallbacks_flat = reached && s.total.fallbacks == baseline.total.fallbacks;
    const double rss_change = baseline.memory.rss_kb > 0 ? double(s.memory.rss_kb - baseline.memory.rss_kb) / baseline.memory.rss_kb : 0;
    const bool memory_flat = reached && std::abs(rss_change) <= kRssTolerance;
    std::printf("%s/%s: %s: %ld steps, finite %s; fallbacks %lld at step %ld, %lld at step %ld (%s); RSS %ld kB at step %ld, "
                "%ld kB at step %ld (%+.2f %%, %s)\n",
                name.c_str(), a.solver.c_str(), reached && fallbacks_flat && memory_flat ? "PASS" : "FAIL", s.step,
                finite ? "yes" : "NO", static_cast<long long>(baseline.total.fallbacks), a.baseline,
                static_cast<long long>(s.total.fallbacks), s.step, fallbacks_flat ? "flat" : "GREW", baseline.memory.rss_kb,
                a.baseline, s.memory.rss_kb, s.step, 100 * rss_change, memory_flat ? "flat" : "GREW");
    std::fflush(stdout);
    return reached && fallbacks_flat && memory_flat;
}

}  // namespace

int main(int argc, char** argv) {
    dInitODE2(0);
    const Args args = parse_args(argc, argv);
    std::ofstream csv;
    if (!args.csv.empty()) {
        csv.open(args.csv);
        if (!csv) usage("cannot write " + args.csv);
        csv << kCsvHeader;
    }
    bool all = true;
    for (const std::string& scene : args.scenes) all = soak(scene, args, csv.is_open() ? &csv : nullptr) && all;
    dCloseODE();
    return all ? 0 : kExitFailed;
}
