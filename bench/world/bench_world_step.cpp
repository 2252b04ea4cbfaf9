// bench_world_step: the whole world step (dWorldStep or dWorldQuickStep, collision excluded),
// timed step by step, with the joint error and the solver's statistics, for the benchmarks of the
// sparse world step (docs/benchmarks.md). Each call appends CSV rows to --csv FILE (the header
// first when the file is new or empty) and prints progress on stderr.
//
//   bench_world_step chain   --links N --method M [--steps K] [--ratio R] [--cfm X] [--exact] --csv FILE
//       the sweeps' HangingChain (N ball-jointed links, a 100 kg load; sweep_scenes.h) with one
//       method in this process, so that the peak memory it reports is that method's alone;
//       --exact: no factor limit (Options::max_factor_entries 0), for a reference whose dense
//       factor would pass it and be answered by PGS instead
//   bench_world_step scene   --scene NAME --methods M,M,... [--seconds S] --csv FILE
//   bench_world_step islands --kind contact|marble|chain|stack [--size K] [--copies C]
//                            --methods M,M,... [--steps K] --csv FILE
//       one world per method, stepped in turn (the order rotated every step), so that every
//       method meets the same machine load; `islands` builds C copies of one island (island_family.h)
//   bench_world_step limit   --scene NAME [--method M] [--seconds S] --csv FILE
//       one row per island: the solver's own time inside dWorldStep (M, default bpp, warm-started
//       as always), the physical limit of its final index set (physical_limit.h) and the least
//       time to form its A from J (assembly_time.h), measured by an MLCP observer outside the
//       timed solve
//
// Methods (world_method.h): an MLCP solver name for dWorldStep ("bpp", "dantzig", ...),
// "quickstep-<k>" for dWorldQuickStep with k iterations, "quickstep-<solver>" for dWorldQuickStep
// routed to that solver. Exit status: 0, 1 when a world could not be made or stepped to the end,
// 2 for bad arguments.
#include <ode/mlcp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "assembly_time.h"
#include "island_family.h"
#include "ode_bpp/capture.h"
#include "ode_bpp/ode.h"
#include "peak_memory.h"
#include "physical_limit.h"
#include "sample_summary.h"
#include "scenes/joint_gap.h"
#include "scenes/scene.h"
#include "scenes/sweep_scenes.h"
#include "world_method.h"

namespace {

using ode_bpp::bench::SampleSummary;
using ode_bpp::bench::WorldMethod;
using ode_bpp::scenes::SceneParams;
using ode_bpp::scenes::SceneWorld;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void usage(const std::string& why) {
    std::cerr << "bench_world_step: " << why << "\n"
              << "usage: bench_world_step chain --links N --method M [--steps K] [--ratio R] [--cfm X] [--exact] --csv FILE\n"
                 "       bench_world_step scene --scene NAME --methods M,M,... [--seconds S] --csv FILE\n"
                 "       bench_world_step islands --kind contact|marble|chain|stack [--size K] [--copies C]\n"
                 "                        --methods M,M,... [--steps K] --csv FILE\n"
                 "       bench_world_step limit --scene NAME [--method M] [--seconds S] --csv FILE\n"
                 "methods: an MLCP solver (bpp, dantzig, ...), quickstep-<iterations>, quickstep-<solver>\n";
    std::exit(2);
}

// ---- command line

struct Cli {
    std::string command;
    std::string csv;
    std::vector<WorldMethod> methods;
    std::string scene;
    std::string kind;
    int links = 0, size = 1, copies = 1, steps = 0;
    double seconds = 0, ratio = 1000, cfm = 1e-10;
    bool exact = false;  ///< chain: no factor limit
};

double parse_number(const std::string& flag, const std::string& text) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value)) usage(flag + " needs a number, got '" + text + "'");
    return value;
}

int parse_count(const std::string& flag, const std::string& text) {
    const double value = parse_number(flag, text);
    if (value < 1 || value > 1e7 || value != std::floor(value)) usage(flag + " needs a whole number >= 1, got '" + text + "'");
    return static_cast<int>(value);
}

std::vector<WorldMethod> parse_methods(const std::string& list) {
    std::vector<WorldMethod> methods;
    std::stringstream stream(list);
    for (std::string name; std::getline(stream, name, ',');) {
        if (name.empty()) continue;
        const auto method = ode_bpp::bench::parse_world_method(name);
        if (!method) usage("malformed method '" + name + "'");
        methods.push_back(*method);
    }
    if (methods.empty()) usage("no method given");
    return methods;
}

Cli parse_cli(int argc, char** argv) {
    if (argc < 2) usage("no command");
    Cli cli;
    cli.command = argv[1];
    for (int i = 2; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--csv") cli.csv = value();
        else if (arg == "--method" || arg == "--methods") cli.methods = parse_methods(value());
        else if (arg == "--scene") cli.scene = value();
        else if (arg == "--kind") cli.kind = value();
        else if (arg == "--links") cli.links = parse_count(arg, value());
        else if (arg == "--size") cli.size = parse_count(arg, value());
        else if (arg == "--copies") cli.copies = parse_count(arg, value());
        else if (arg == "--steps") cli.steps = parse_count(arg, value());
        else if (arg == "--seconds") cli.seconds = parse_number(arg, value());
        else if (arg == "--ratio") cli.ratio = parse_number(arg, value());
        else if (arg == "--cfm") cli.cfm = parse_number(arg, value());
        else if (arg == "--exact") cli.exact = true;
        else usage("unknown option " + arg);
    }
    if (cli.csv.empty()) usage("--csv FILE is required");
    if (cli.methods.empty() && cli.command == "limit") cli.methods = parse_methods("bpp");
    if (cli.methods.empty()) usage("--method(s) is required");
    if (cli.seconds < 0 || !(cli.ratio >= 1) || cli.cfm < 0) usage("--seconds >= 0, --ratio >= 1, --cfm >= 0");
    return cli;
}

// ---- one world stepped by one method

/// The MLCP statistics of the last step (zeros for QuickStep, which has none).
dMLCPStepStats last_stats(dWorldID world) {
    dMLCPStepStats last{};
    last.struct_size = sizeof last;
    if (!dWorldGetMLCPStats(world, &last, nullptr)) last = dMLCPStepStats{};
    return last;
}

/// A world, the scene that drives it (or none) and what its steps measured.
struct Contestant {
    WorldMethod method;
    std::unique_ptr<ode_bpp::scenes::Scene> scene;
    std::unique_ptr<SceneWorld> world;
    std::vector<double> step_ms, solve_ms, gaps;
    std::vector<double> step_per_island_us, solve_per_island_us;  ///< per step with islands
    long islands = 0, rows = 0, max_rows = 0, pivots = 0, failures = 0;
    bool broken = false;  ///< a step failed or left a non-finite body: the world stops there

    /// One step: control, the timed step, the statistics and the joint gap after it.
    void step() {
        if (broken) return;
        if (scene) scene->control(*world, world->time());
        if (!world->step()) {
            broken = true;
            return;
        }
        step_ms.push_back(1e3 * world->last_step_seconds());
        gaps.push_back(ode_bpp::scenes::max_anchor_gap(world->bodies()));
        if (!method.uses_mlcp()) return;
        const dMLCPStepStats s = last_stats(world->world());
        solve_ms.push_back(1e3 * s.seconds);
        if (s.islands > 0) {
            step_per_island_us.push_back(1e3 * step_ms.back() / static_cast<double>(s.islands));
            solve_per_island_us.push_back(1e6 * s.seconds / static_cast<double>(s.islands));
        }
        islands += s.islands;
        rows += s.rows;
        max_rows = std::max<long>(max_rows, s.max_rows);
        pivots += s.pivots;
        failures += s.failures;
    }
    double solve_total_ms() const {
        double sum = 0;
        for (double v : solve_ms) sum += v;
        return method.uses_mlcp() ? sum : kNaN;
    }
    double step_total_ms() const {
        double sum = 0;
        for (double v : step_ms) sum += v;
        return sum;
    }
};

Contestant make_contestant(const WorldMethod& method, SceneParams params) {
    Contestant c;
    c.method = method;
    c.world = std::make_unique<SceneWorld>(ode_bpp::bench::params_for(method, params));
    ode_bpp::bench::configure_world(method, *c.world);
    return c;
}

/// Steps every contestant `steps` times, in an order rotated every step; progress every 10 %.
void step_in_turn(std::vector<Contestant>& all, long steps, const std::string& what) {
    const long tenth = std::max(1L, steps / 10);
    for (long k = 0; k < steps; ++k) {
        for (std::size_t i = 0; i < all.size(); ++i) all[(i + static_cast<std::size_t>(k)) % all.size()].step();
        if ((k + 1) % tenth == 0 || k + 1 == steps)
            std::cerr << "bench_world_step: " << what << " [" << k + 1 << "/" << steps << " steps]\n";
    }
}

// ---- CSV

/// Opens FILE for appending and writes the header when the file is empty.
std::ofstream open_csv(const std::string& path, const char* header) {
    std::ofstream probe(path, std::ios::app);
    if (!probe) usage("cannot write " + path);
    const bool empty = probe.tellp() == 0;
    probe.precision(6);
    if (empty) probe << header << '\n';
    return probe;
}

std::string csv_text(std::string text) {
    for (char& c : text) c = c == ',' ? ';' : c == '"' ? '\'' : c;
    return "\"" + text + "\"";
}

/// step_median_ms,step_mean_ms,step_slowest1_ms,step_max_ms
void write_times(std::ostream& out, const std::vector<double>& ms) {
    const SampleSummary s = ode_bpp::bench::summarize(ms);
    out << s.median << ',' << s.mean << ',' << s.slowest_percent << ',' << s.max;
}

double max_of(const std::vector<double>& v) { return v.empty() ? kNaN : *std::max_element(v.begin(), v.end()); }

// ---- commands

const char* kChainHeader =
    "links,rows,method,ratio,cfm,steps,completed,step_median_ms,step_mean_ms,step_slowest1_ms,step_max_ms,"
    "solve_median_ms,pivots_per_step,failures,gap_max_m,gap_final_m,rss_before_kb,rss_peak_kb";

int run_chain(const Cli& cli) {
    if (cli.links < 1) usage("chain: --links N is required");
    if (cli.methods.size() != 1) usage("chain: one --method per process (its peak memory is measured)");
    const long rss_before = ode_bpp::bench::peak_resident_kb();
    SceneParams params;
    params.cfm = cli.cfm;
    std::vector<Contestant> one;
    one.push_back(make_contestant(cli.methods[0], params));
    if (cli.exact) {
        ode_bpp::WorldSettings settings = ode_bpp::world_settings(one[0].world->world());
        settings.options.max_factor_entries = 0;
        ode_bpp::set_world_settings(one[0].world->world(), settings);
    }
    const ode_bpp::scenes::SweepLayout layout = ode_bpp::scenes::build_sweep_scene(
        *one[0].world, {ode_bpp::scenes::SweepPattern::HangingChain, cli.ratio, cli.links});
    const long steps = cli.steps > 0 ? cli.steps : 120;
    step_in_turn(one, steps, "chain of " + std::to_string(cli.links) + " links, " + cli.methods[0].name);
    const Contestant& c = one[0];
    std::ofstream csv = open_csv(cli.csv, kChainHeader);
    const long done = static_cast<long>(c.step_ms.size());
    csv << cli.links << ',' << 3 * layout.joints << ',' << c.method.name << ',' << cli.ratio << ',' << cli.cfm << ','
        << steps << ',' << done << ',';
    write_times(csv, c.step_ms);
    csv << ',' << ode_bpp::bench::summarize(c.solve_ms).median << ','
        << (c.method.uses_mlcp() && done ? static_cast<double>(c.pivots) / static_cast<double>(done) : kNaN) << ','
        << c.failures << ',' << max_of(c.gaps) << ',' << (c.gaps.empty() ? kNaN : c.gaps.back()) << ','
        << rss_before << ',' << ode_bpp::bench::peak_resident_kb() << '\n';
    return c.broken ? 1 : 0;
}

const char* kSceneHeader =
    "scene,method,steps,completed,step_median_ms,step_mean_ms,step_slowest1_ms,step_max_ms,solve_median_ms,"
    "solve_mean_ms,islands_per_step,rows_per_island,max_rows,step_per_island_us,solve_per_island_us,"
    "step_per_island_median_us,solve_per_island_median_us,pivots,failures,gap_max_m,gap_median_m,success,detail";

/// One summary row per contestant of a scene or an island family.
void write_scene_rows(std::ostream& csv, const std::string& label, const std::vector<Contestant>& all, long steps) {
    for (const Contestant& c : all) {
        const long done = static_cast<long>(c.step_ms.size());
        const SampleSummary solve = ode_bpp::bench::summarize(c.solve_ms);
        const double islands = c.method.uses_mlcp() && done ? static_cast<double>(c.islands) / done : kNaN;
        const double per_island = c.islands > 0 ? 1e3 / static_cast<double>(c.islands) : kNaN;
        csv << label << ',' << c.method.name << ',' << steps << ',' << done << ',';
        write_times(csv, c.step_ms);
        const double rows = c.islands > 0 ? static_cast<double>(c.rows) / static_cast<double>(c.islands) : kNaN;
        csv << ',' << solve.median << ',' << solve.mean << ',' << islands << ',' << rows << ',' << c.max_rows << ','
            << c.step_total_ms() * per_island << ',' << c.solve_total_ms() * per_island << ','
            << ode_bpp::bench::summarize(c.step_per_island_us).median << ','
            << ode_bpp::bench::summarize(c.solve_per_island_us).median << ',' << c.pivots << ',' << c.failures << ',' << max_of(c.gaps) << ',' << ode_bpp::bench::summarize(c.gaps).median << ',';
        if (c.scene) {
            const ode_bpp::scenes::SuccessReport report = c.scene->success(*c.world);
            csv << (report.ok ? "yes" : "no") << ',' << csv_text(report.detail) << '\n';
        } else {
            csv << "-,-\n";
        }
    }
}

int run_scene(const Cli& cli) {
    if (cli.scene.empty()) usage("scene: --scene NAME is required");
    std::vector<Contestant> all;
    for (const WorldMethod& method : cli.methods) {
        Contestant c = make_contestant(method, SceneParams{});
        c.scene = ode_bpp::scenes::make_scene(cli.scene);
        if (!c.scene) usage("unknown scene '" + cli.scene + "'");
        c.scene->build(*c.world);
        all.push_back(std::move(c));
    }
    const double seconds = cli.seconds > 0 ? cli.seconds : all[0].scene->default_seconds();
    const long steps = std::lround(seconds / all[0].world->params().step);
    step_in_turn(all, steps, cli.scene);
    std::ofstream csv = open_csv(cli.csv, kSceneHeader);
    write_scene_rows(csv, cli.scene, all, steps);
    return std::any_of(all.begin(), all.end(), [](const Contestant& c) { return c.broken; }) ? 1 : 0;
}

int run_islands(const Cli& cli) {
    const auto kind = ode_bpp::bench::island_kind_from_string(cli.kind);
    if (!kind) usage("islands: --kind contact|marble|chain|stack is required");
    std::vector<Contestant> all;
    for (const WorldMethod& method : cli.methods) {
        Contestant c = make_contestant(method, ode_bpp::bench::family_params(*kind, SceneParams{}));
        ode_bpp::bench::build_island_family(*c.world, *kind, cli.size, cli.copies);
        all.push_back(std::move(c));
    }
    const long steps = cli.steps > 0 ? cli.steps : 60;
    const std::string label = std::string(to_string(*kind)) + "-" + std::to_string(cli.size) + "x" + std::to_string(cli.copies);
    step_in_turn(all, steps, label);
    std::ofstream csv = open_csv(cli.csv, kSceneHeader);
    write_scene_rows(csv, label, all, steps);
    return std::any_of(all.begin(), all.end(), [](const Contestant& c) { return c.broken; }) ? 1 : 0;
}


const char* kLimitHeader =
    "scene,method,step,island,rows,friction_rows,pivots,status,solve_us,physical_limit_us,assembly_us";
constexpr int kLimitRepeat = 3;  // rounds of the physical limit's timing (median)

/// The MLCP observer of `limit`: captures each island before its solve and, after it, writes the
/// solver's time, the physical limit of the index set it returned and the least time to form its
/// A (timed after the solve, like the limit, so that neither warms the solve's caches).
struct LimitProbe {
    std::ofstream* csv = nullptr;
    std::string scene, method;
    long step = 0;
    int island = 0;
    std::optional<ode_bpp::MlcpFile> pending;
};

void observe_limit(const dMLCP* problem, const dMLCPIslandStats* stats, void* userdata) {
    auto* probe = static_cast<LimitProbe*>(userdata);
    if (stats == nullptr) {
        std::string error;
        probe->pending = ode_bpp::capture_from_ode(*problem, ode_bpp::Metadata{}, &error);
        if (!probe->pending) std::cerr << "bench_world_step: island not captured: " << error << "\n";
        return;
    }
    if (!probe->pending) return;
    const ode_bpp::MlcpFile& file = *probe->pending;
    const ode_bpp::Result result = ode_bpp::last_island_result(problem->world);
    const bool answered = stats->status != dMLCPFailed && static_cast<int>(result.states.size()) == file.n;
    const double limit = answered ? ode_bpp::bench::physical_limit_us(file, result.states, kLimitRepeat) : kNaN;
    const double assembly = ode_bpp::bench::assembly_time_us(*problem, kLimitRepeat);
    const long friction = std::count_if(file.findex.begin(), file.findex.end(), [](int f) { return f >= 0; });
    *probe->csv << probe->scene << ',' << probe->method << ',' << probe->step << ',' << probe->island++ << ','
                << file.n << ',' << friction << ',' << stats->pivots << ','
                << (stats->status == dMLCPSolved ? "solved" : stats->status == dMLCPSolvedByFallback ? "fallback" : "failed")
                << ',' << 1e6 * stats->seconds << ',' << limit << ',' << assembly << '\n';
    probe->pending.reset();
}

int run_limit(const Cli& cli) {
    if (cli.scene.empty()) usage("limit: --scene NAME is required");
    if (cli.methods.size() != 1 || !cli.methods[0].uses_mlcp()) usage("limit: one method that calls an MLCP solver");
    Contestant c = make_contestant(cli.methods[0], SceneParams{});
    c.scene = ode_bpp::scenes::make_scene(cli.scene);
    if (!c.scene) usage("unknown scene '" + cli.scene + "'");
    c.scene->build(*c.world);
    std::ofstream csv = open_csv(cli.csv, kLimitHeader);
    LimitProbe probe;
    probe.csv = &csv;
    probe.scene = cli.scene;
    probe.method = c.method.name;
    dWorldSetMLCPObserver(c.world->world(), &observe_limit, &probe);
    const double seconds = cli.seconds > 0 ? cli.seconds : c.scene->default_seconds();
    const long steps = std::lround(seconds / c.world->params().step);
    const long tenth = std::max(1L, steps / 10);
    for (long k = 0; k < steps && !c.broken; ++k) {
        probe.step = k + 1;
        probe.island = 0;
        c.step();
        if ((k + 1) % tenth == 0) std::cerr << "bench_world_step: limit " << cli.scene << " [" << k + 1 << "/" << steps << " steps]\n";
    }
    dWorldSetMLCPObserver(c.world->world(), nullptr, nullptr);
    return c.broken ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    const Cli cli = parse_cli(argc, argv);
    try {
        if (cli.command == "chain") return run_chain(cli);
        if (cli.command == "scene") return run_scene(cli);
        if (cli.command == "islands") return run_islands(cli);
        if (cli.command == "limit") return run_limit(cli);
    } catch (const std::exception& e) {
        std::cerr << "bench_world_step: " << e.what() << "\n";
        return 1;
    }
    usage("unknown command '" + cli.command + "'");
}
