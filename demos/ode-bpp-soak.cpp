// ode-bpp-soak: steps scenes for a long time and watches what must not drift: the bodies stay
// finite, islands stop going to ODE's Dantzig, and the process's memory stays flat.
//
//   ode-bpp-soak SCENE... [--solver NAME] [--steps N] [--every K] [--baseline STEP] [--csv FILE]
//
// Every K steps (default 1,000) one CSV row per scene: the bytes in live heap allocations (malloc's
// own count, mallinfo2), resident memory (RSS, from /proc/self/statm) and its peak, ODE's
// statistics (islands, largest island since the last row, solves that fell back, solves answered by
// ODE's Dantzig), and wall time; a progress line goes to stderr. At the end of each scene, one
// verdict line on stdout:
//   - finite: every body's position, velocity and orientation finite at every row;
//   - fallbacks: the count at the last step equals the count at the baseline step (10,000);
//   - heap: no steady growth of the live heap. From the baseline step to the last, ten windows
//     of steps each give the heap's floor (the smallest sample); what the floor gained beyond
//     its two largest rises between neighbouring windows is at most 1 % of the first window's;
//   - RSS: at the last step at most 5 % above the baseline step's.
// Why (docs/soak.md has the measurements): the live heap holds the scene's current contacts,
// islands and warm starts, so it moves with the trajectory between samples (the winch: +-20 kB of
// 2.6 MB), and the floor of a window is what stays. Buffers kept for reuse grow where an island
// needs more than any before (a high-water mark): the floor steps up once or twice. A leak raises
// it in every window: one of 32 bytes a step fails the short soak of make test. RSS counts the
// pages of malloc's arena the first time they are touched, and where the arena's pages fall
// differs between runs (address space layout randomization): the same scene and steps read RSS
// changes of -1.4 % to +1.5 %. RSS stays judged, loosely, so that fragmentation and one-off
// growth of many megabytes (RSS growing while the heap's rises are excused) still fail.
// Nothing is kept per step, so the tool's own memory is flat. Exit status: 0 when every scene
// passed, 1 when one did not, 2 on bad arguments.
#include <malloc.h>
#include <ode/mlcp.h>
#include <ode/ode.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace {

using namespace ode_bpp::scenes;
using Clock = std::chrono::steady_clock;

constexpr int kExitFailed = 1, kExitUsage = 2;
/// Growth allowed from the baseline step to the last one: of the live heap's floor beyond its two
/// largest rises, and of RSS (see the header).
constexpr double kHeapGrowthLimit = 0.01, kRssGrowthLimit = 0.05;
/// Windows of steps from the baseline to the last step, and the rises between them excused as
/// high-water marks of kept buffers.
constexpr int kHeapWindows = 10, kExcusedRises = 2;

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

/// Memory of this process [kB]: bytes in live heap allocations (arena and mmapped blocks, glibc's
/// mallinfo2), resident memory and its peak (Linux /proc).
struct Memory {
    long heap_kb = 0, rss_kb = 0, peak_kb = 0;
};

Memory memory_now() {
    Memory m;
    const struct mallinfo2 heap = mallinfo2();
    m.heap_kb = static_cast<long>((heap.uordblks + heap.hblkhd) / 1024);
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
    "solve_seconds,wall_seconds,heap_kb\n";

void write_row(std::ofstream* csv, const std::string& scene, const std::string& solver, double step_size, const Sample& s) {
    if (!csv) return;
    *csv << scene << ',' << solver << ',' << s.step << ',' << s.step * step_size << ',' << s.memory.rss_kb << ','
         << s.memory.peak_kb << ',' << s.total.islands << ',' << s.window_max_rows << ',' << s.total.fallbacks << ','
         << s.total.failures << ',' << s.non_finite << ',' << s.total.seconds << ',' << s.wall_seconds << ',' << s.memory.heap_kb
         << '\n';
    csv->flush();
}

void report_progress(const std::string& scene, const Args& a, const Sample& s) {
    const double eta = s.wall_seconds / s.step * (a.steps - s.step);
    std::fprintf(stderr, "[soak] %s/%s step %ld of %ld: heap %ld kB, RSS %ld kB, fallbacks %lld, largest island %ld rows, %.0f s, ~%.0f s to go\n",
                 scene.c_str(), a.solver.c_str(), s.step, a.steps, s.memory.heap_kb, s.memory.rss_kb, static_cast<long long>(s.total.fallbacks),
                 s.window_max_rows, s.wall_seconds, eta);
}

/// A memory measure before and after [kB], and the growth allowed between.
struct Growth {
    long before_kb, after_kb;
    double limit;

    double change() const { return before_kb > 0 ? double(after_kb - before_kb) / before_kb : 0; }
    /// A fall passes: only growth is a leak's signature.
    bool within() const { return change() <= limit; }
    std::string describe() const {
        char text[96];
        std::snprintf(text, sizeof text, "%ld -> %ld kB (%+.2f %%, limit +%.0f %%, %s)", before_kb, after_kb, 100 * change(),
                      100 * limit, within() ? "flat" : "GREW");
        return text;
    }
};

/// The live heap's floor (smallest sample) in each of kHeapWindows windows of steps from the
/// baseline step to the last, and its steady growth: the gain from the first window to the last
/// beyond the kExcusedRises largest rises between neighbouring windows.
class HeapFloors {
public:
    explicit HeapFloors(const Args& a) : baseline_(a.baseline), span_(a.steps - a.baseline) { floors_.fill(kNone); }

    void add(long step, long heap_kb) {
        if (step < baseline_) return;
        const auto k = static_cast<std::size_t>(std::min<long>(kHeapWindows - 1, (step - baseline_) * kHeapWindows / span_));
        floors_[k] = std::min(floors_[k], heap_kb);
    }

    long first_kb() const { return floors_.front(); }
    long last_kb() const { return floors_.back(); }

    /// The gain beyond the excused rises [kB]; windows without a sample are skipped.
    long steady_gain_kb() const {
        std::vector<long> rises;
        long previous = kNone, gain = 0;
        for (long f : floors_) {
            if (f == kNone) continue;
            if (previous != kNone) rises.push_back(f - previous);
            previous = f;
        }
        std::sort(rises.begin(), rises.end(), std::greater<>());
        for (std::size_t k = 0; k < rises.size(); ++k)
            if (k >= static_cast<std::size_t>(kExcusedRises) || rises[k] < 0) gain += rises[k];
        return gain;
    }

    bool within() const { return first_kb() > 0 && steady_gain_kb() <= kHeapGrowthLimit * first_kb(); }

    std::string describe() const {
        char text[160];
        const double first = static_cast<double>(std::max(1L, first_kb()));
        std::snprintf(text, sizeof text, "%ld -> %ld kB (%+.2f %%; beyond its %d largest rises %+.2f %%, limit +%.0f %%, %s)",
                      first_kb(), last_kb(), 100 * (last_kb() - first_kb()) / first, kExcusedRises,
                      100 * steady_gain_kb() / first, 100 * kHeapGrowthLimit, within() ? "flat" : "GREW");
        return text;
    }

private:
    static constexpr long kNone = std::numeric_limits<long>::max();
    long baseline_, span_;
    std::array<long, kHeapWindows> floors_;
};

/// Runs one scene for a.steps steps; prints its verdict and returns whether it passed.
bool soak(const std::string& name, const Args& a, std::ofstream* csv) {
    std::unique_ptr<Scene> scene = make_scene(name);
    SceneParams params;
    params.solver = a.solver;
    SceneWorld w(params);
    scene->build(w);
    const Clock::time_point start = Clock::now();
    Sample baseline, s;
    HeapFloors heap_floors(a);
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
        heap_floors.add(step, s.memory.heap_kb);
        s.window_max_rows = 0;
    }
    const bool reached = finite && s.step == a.steps;
    const bool fallbacks_flat = reached && s.total.fallbacks == baseline.total.fallbacks;
    const Growth rss{baseline.memory.rss_kb, s.memory.rss_kb, kRssGrowthLimit};
    const bool passed = reached && fallbacks_flat && heap_floors.within() && rss.within();
    std::printf("%s/%s: %s: %ld steps, finite %s; fallbacks %lld at step %ld, %lld at step %ld (%s); heap floor %s; RSS %s "
                "(from step %ld to %ld)\n",
                name.c_str(), a.solver.c_str(), passed ? "PASS" : "FAIL", s.step, finite ? "yes" : "NO",
                static_cast<long long>(baseline.total.fallbacks), a.baseline, static_cast<long long>(s.total.fallbacks), s.step,
                fallbacks_flat ? "flat" : "GREW", heap_floors.describe().c_str(), rss.describe().c_str(), a.baseline, s.step);
    std::fflush(stdout);
    return passed;
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
