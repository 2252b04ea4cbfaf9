// ode-bpp-demo: runs a scene headless with a chosen MLCP solver inside dWorldStep and measures,
// per step and island, what the paper measures (Table 2, Fig. 3, Fig. 7): rows, tight rows,
// solve time, pivots, residual, cond(A), mass ratio.
//
//   ode-bpp-demo SCENE [--solver NAME] [--seconds S] [--cfm X | --compliance C] [--csv FILE]
//                [--capture DIR [--capture-every K]] [--cond-every N] [--friction MODE] [--quiet]
//   ode-bpp-demo SCENE --compare dantzig,bpp [...]
//   ode-bpp-demo --list
// SCENE "paper" runs the paper's six scenes one after the other.
// Exit status: 0 when every run met its scene's success criterion (or ran too short to judge it),
// 1 when one did not, 2 for bad arguments (unknown scene or solver included), 3 when --capture
// could not create its directory or write a file.
#include <ode/mlcp.h>
#include <ode/ode.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "ode_bpp/capture.h"
#include "ode_bpp/io.h"
#include "ode_bpp/ode.h"
#include "ode_bpp/residuals.h"
#include "scenes/paper_scenes.h"
#include "scenes/scene.h"

namespace {

using namespace ode_bpp::scenes;
using Clock = std::chrono::steady_clock;

constexpr int kExitCriterionFailed = 1;
constexpr int kExitUsage = 2;
constexpr int kExitCaptureFailed = 3;
const bool kStderrIsTty = isatty(STDERR_FILENO) != 0;

// --------------------------------------------------------------------------------------------
// command line

struct Args {
    std::vector<std::string> scenes;
    std::vector<std::string> solvers;     ///< one, or several with --compare
    bool compare = false;
    std::optional<double> seconds;
    std::optional<double> cfm;
    std::optional<double> compliance;
    std::string csv;
    std::string capture_dir;
    int capture_every = 1;
    bool capture_failures = false;
    int cond_every = 30;
    ode_bpp::FrictionMode friction = ode_bpp::FrictionMode::Frozen;
    std::optional<int> max_pivots;
    bool quiet = false;
    bool list = false;
};

std::vector<std::string> split_commas(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string item;
    while (std::getline(in, item, ',')) {
        if (!item.empty()) out.push_back(item);
    }
    return out;
}

std::string valid_scenes() {
    std::string names = "paper";
    for (const std::string& s : scene_names()) names += ", " + s;
    return names;
}

void print_usage(FILE* out) {
    std::fprintf(out,
                 "usage: ode-bpp-demo SCENE [--solver NAME] [--seconds S] [--cfm X | --compliance C]\n"
                 "                    [--csv FILE] [--capture DIR [--capture-every K | --capture-failures]]\n"
                 "                    [--cond-every N] [--friction MODE] [--max-pivots N] [--quiet]\n"
                 "       ode-bpp-demo SCENE --compare NAME,NAME[,...] [same options]\n"
                 "       ode-bpp-demo --list | --help\n"
                 "Steps SCENE with an MLCP solver inside dWorldStep and reports solve times, pivots,\n"
                 "residuals and the scene's success criterion (judged only on runs of the scene's full length).\n"
                 "  --solver      MLCP solver inside dWorldStep (default bpp)\n"
                 "  --compare     the same runs with each solver, as one table; speed-up against the first\n"
                 "  --seconds     simulated time (default: the scene's own, 20 s for the paper's scenes)\n"
                 "  --cfm         ODE CFM of joints and contacts (default 1e-10, ODE's)\n"
                 "  --compliance  the paper's compliance c; sets CFM = c / h (paper: 1e-6 .. 1e-10)\n"
                 "  --csv         one row per island per step\n"
                 "  --capture     writes every island's MLCP (every K-th step) into DIR (created), with the\n"
                 "                warm start it was solved from (ode-bpp-solve --warm replays it)\n"
                 "  --capture-failures  with --capture: only the islands, of every step, that the solver\n"
                 "                answered through a fallback or handed to ODE's Dantzig\n"
                 "  --cond-every  estimate cond(A) of the largest island every N steps (default 30; 0: never)\n"
                 "  --friction    frozen|consistent: friction mode of ode-bpp's solvers (default frozen)\n"
                 "  --max-pivots  pivot budget per fixed-bound solve of ode-bpp's solvers (default 100)\n"
                 "  --quiet       no progress lines on stderr\n"
                 "scenes: %s (paper: the paper's six, in turn)\n"
                 "solvers: %s\n"
                 "exit status: 0 every criterion met (or not judged: run shorter than the scene's), 1 a criterion\n"
                 "             missed, 2 bad arguments, 3 --capture could not create DIR or write a file\n",
                 valid_scenes().c_str(), dListMLCPSolvers());
}

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "ode-bpp-demo: %s (ode-bpp-demo --help for the usage)\n", message.c_str());
    std::exit(kExitUsage);
}

double parse_number(const std::string& flag, const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !std::isfinite(v)) {
        usage_error("bad number for " + flag + ": '" + text + "'");
    }
    return v;
}

std::vector<std::string> expand_scene(const std::string& name) {
    if (name == "paper") {
        std::vector<std::string> six;
        for (const auto& [scene, factory] : paper_scenes()) six.push_back(scene);
        return six;
    }
    if (!make_scene(name)) usage_error("unknown scene '" + name + "'; valid: " + valid_scenes());
    return {name};
}

Args parse_args(int argc, char** argv) {
    Args a;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage_error(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--list") a.list = true;
        else if (arg == "--quiet") a.quiet = true;
        else if (arg == "--solver") a.solvers = {value()};
        else if (arg == "--compare") { a.solvers = split_commas(value()); a.compare = true; }
        else if (arg == "--seconds") a.seconds = parse_number(arg, value());
        else if (arg == "--cfm") a.cfm = parse_number(arg, value());
        else if (arg == "--compliance") a.compliance = parse_number(arg, value());
        else if (arg == "--csv") a.csv = value();
        else if (arg == "--capture") a.capture_dir = value();
        else if (arg == "--capture-every") a.capture_every = static_cast<int>(parse_number(arg, value()));
        else if (arg == "--capture-failures") a.capture_failures = true;
        else if (arg == "--max-pivots") a.max_pivots = static_cast<int>(parse_number(arg, value()));
        else if (arg == "--cond-every") a.cond_every = static_cast<int>(parse_number(arg, value()));
        else if (arg == "--friction") {
            const std::string mode = value();
            const auto friction = ode_bpp::friction_from_string(mode);
            if (!friction) usage_error("unknown friction mode '" + mode + "' (frozen or consistent)");
            a.friction = *friction;
        }
        else if (arg == "-h" || arg == "--help") { print_usage(stdout); std::exit(0); }
        else if (!arg.empty() && arg[0] == '-') usage_error("unknown option " + arg);
        else positional.push_back(arg);
    }
    if (a.list) return a;
    if (positional.size() != 1) usage_error("expected exactly one SCENE");
    a.scenes = expand_scene(positional[0]);
    if (a.solvers.empty()) a.solvers = {"bpp"};
    if (a.cfm && a.compliance) usage_error("--cfm and --compliance exclude each other");
    if (a.seconds && *a.seconds <= 0) usage_error("--seconds must be positive");
    if ((a.cfm && *a.cfm < 0) || (a.compliance && *a.compliance < 0)) usage_error("CFM must be >= 0");
    if (a.capture_every < 1 || a.cond_every < 0) usage_error("--capture-every >= 1, --cond-every >= 0");
    if (a.capture_failures && a.capture_dir.empty()) usage_error("--capture-failures needs --capture DIR");
    if (a.capture_failures && a.capture_every != 1) usage_error("--capture-failures captures every step: no --capture-every");
    if (a.max_pivots && *a.max_pivots < 1) usage_error("--max-pivots must be at least 1");
    if (a.compare && a.solvers.size() < 2) usage_error("--compare needs at least two solvers");
    for (const std::string& s : a.solvers) {
        if (!is_solver_registered(s)) usage_error("unknown solver '" + s + "'; valid: " + dListMLCPSolvers());
    }
    return a;
}

// --------------------------------------------------------------------------------------------
// what the MLCP observer records per island (the "before" call copies, since Dantzig destroys A)

struct IslandRecord {
    int m = 0, nub = 0;
    std::vector<double> A;               ///< m x m row-major, lower triangle (diagonal included)
    std::vector<double> b, lo, hi, x;    ///< m each
    std::vector<int> findex;             ///< m
    dMLCPIslandStats stats{};
    bool solved = false;                 ///< the "after" call came
    double mass_ratio = 1;               ///< heaviest / lightest body of the island
};

struct Recorder {
    std::vector<IslandRecord> islands;   ///< of the current step
    std::string capture_dir, scene, solver;
    bool capture_this_step = false;
    /// --capture-failures: the island as ODE handed it over, written only if its solve did not
    /// end dMLCPSolved (the before call cannot know; the after call no longer has A intact).
    bool capture_failures = false;
    /// The island of the before call, written in the after call with the warm start the hook
    /// solved it from (ode_bpp::last_island_start): every island of a captured step, or the
    /// failures.
    std::optional<ode_bpp::MlcpFile> pending;
    long step = 0;
    double cfm = 0, erp = 0;
    std::string capture_error;
    long capture_files = 0;              ///< files written
    std::uintmax_t capture_bytes = 0;    ///< their sizes, summed
    /// Time spent in observe() during the current step. It runs inside dWorldStep (copying each
    /// island's dense A before the solve, O(rows²)), which no user's step pays, so the step's time
    /// is reported without it (advance()).
    Clock::duration observing{};
};

/// Adds the time from its construction to its destruction to rec.observing.
class ObserverClock {
public:
    explicit ObserverClock(Recorder& rec) : rec_(rec), start_(Clock::now()) {}
    ~ObserverClock() { rec_.observing += Clock::now() - start_; }
    ObserverClock(const ObserverClock&) = delete;
    ObserverClock& operator=(const ObserverClock&) = delete;

private:
    Recorder& rec_;
    const Clock::time_point start_;
};

double island_mass_ratio(const dMLCP& p) {
    double heaviest = 0, lightest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < p.nj; ++k) {
        for (int e = 0; e < 2; ++e) {
            dBodyID body = dJointGetBody(p.joints[k].joint, e);
            if (!body) continue;
            dMass mass;
            dBodyGetMass(body, &mass);
            heaviest = std::max(heaviest, static_cast<double>(mass.mass));
            lightest = std::min(lightest, static_cast<double>(mass.mass));
        }
    }
    return heaviest > 0 ? heaviest / lightest : 1.0;
}

void copy_before(const dMLCP& p, IslandRecord& r) {
    const auto m = static_cast<size_t>(p.m);
    r.m = p.m;
    r.nub = p.nub;
    ode_bpp::island_matrix_lower(p, r.A);
    r.b.resize(m), r.lo.resize(m), r.hi.resize(m), r.findex.resize(m);
    for (size_t i = 0; i < m; ++i) {
        r.b[i] = p.pairsbx[2 * i];
        r.lo[i] = p.pairslh[2 * i];
        r.hi[i] = p.pairslh[2 * i + 1];
        r.findex[i] = p.findex ? p.findex[i] : -1;
    }
    r.mass_ratio = p.joints ? island_mass_ratio(p) : 1.0;
}

ode_bpp::Metadata capture_metadata(const Recorder& rec, size_t island) {
    ode_bpp::Metadata meta;
    meta.set("scene", rec.scene);
    meta.set("solver", rec.solver);
    meta.set("frame", std::to_string(rec.step));
    meta.set("island", std::to_string(island));
    return meta;
}

std::filesystem::path capture_path(const Recorder& rec, size_t island) {
    char file[256];
    std::snprintf(file, sizeof file, "%s-%s-s%06ld-i%02zu.mlcp", rec.scene.c_str(), rec.solver.c_str(), rec.step,
                  island);
    return std::filesystem::path(rec.capture_dir) / file;
}

/// Writes `file` (the island as ODE handed it over, with its metadata) and counts it.
void capture_island(Recorder& rec, size_t island, const ode_bpp::MlcpFile& file) {
    namespace fs = std::filesystem;
    std::string error;
    const fs::path path = capture_path(rec, island);
    const bool written = ode_bpp::write_mlcp(path.string(), file, &error);
    if (!written) {
        if (rec.capture_error.empty()) rec.capture_error = error;
        return;
    }
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    rec.capture_files += 1;
    rec.capture_bytes += ec ? 0 : size;
}

void observe(const dMLCP* p, const dMLCPIslandStats* stats, void* data) {
    auto& rec = *static_cast<Recorder*>(data);
    const ObserverClock clock(rec);
    if (stats == nullptr) {
        rec.islands.emplace_back();
        copy_before(*p, rec.islands.back());
        rec.pending.reset();
        if (rec.capture_failures || rec.capture_this_step) {
            std::string error;
            rec.pending = ode_bpp::capture_from_ode(*p, capture_metadata(rec, rec.islands.size() - 1), &error);
            if (!rec.pending && rec.capture_error.empty()) rec.capture_error = error;
        }
        return;
    }
    if (rec.pending && (rec.capture_this_step || stats->status != dMLCPSolved)) {
        if (stats->status != dMLCPSolved) {
            rec.pending->meta.set("status", stats->status == dMLCPFailed ? "failed" : "solved-by-fallback");
            if (stats->fallback != nullptr) rec.pending->meta.set("fallback", stats->fallback);
        }
        if (rec.solver != "dantzig") ode_bpp::set_start_metadata(ode_bpp::last_island_start(), rec.pending->meta);
        capture_island(rec, rec.islands.size() - 1, *rec.pending);
    }
    // SceneWorld attaches no threading implementation, so ODE solves the islands one at a time:
    // the "after" call belongs to the latest "before"
    IslandRecord& r = rec.islands.back();
    r.stats = *stats;
    r.stats.fallback = nullptr;  // points into the solver's storage; not needed later
    r.x.resize(static_cast<size_t>(r.m));
    for (size_t i = 0; i < r.x.size(); ++i) r.x[i] = p->pairsbx[2 * i + 1];
    r.solved = true;
}

// --------------------------------------------------------------------------------------------
// analysis of one island: residuals (ode_bpp's definitions), tight rows, cond(A)

struct IslandMeasures {
    int tight = 0;
    int bounded = 0;
    ode_bpp::Residuals residuals;
    double cond = std::numeric_limits<double>::quiet_NaN();
};

ode_bpp::Problem view(const IslandRecord& r) {
    ode_bpp::Problem p;
    p.n = r.m;
    p.A = r.A.data();
    p.lda = r.m;
    p.b = {r.b.data(), 1};
    p.lo = {r.lo.data(), 1};
    p.hi = {r.hi.data(), 1};
    p.findex = r.findex.data();
    p.nub = r.nub;
    return p;
}

// x at a bound, the paper's tight set (Fig. 3). A row counts as at a bound when within a
// relative distance of the island's largest impulse: Dantzig and BPP set such rows exactly,
// other methods land within rounding.
int count_tight(const ode_bpp::Problem& p, const std::vector<double>& x, int* bounded) {
    double xmax = 0;
    for (double v : x) xmax = std::max(xmax, std::abs(v));
    const double tol = 1e-9 * xmax;
    int tight = 0;
    *bounded = 0;
    for (int i = 0; i < p.n; ++i) {
        const auto [lo, hi] = ode_bpp::effective_bounds(p, {x.data(), 1}, i);
        if (std::isinf(lo) && std::isinf(hi)) continue;
        ++*bounded;
        if (x[static_cast<size_t>(i)] <= lo + tol || x[static_cast<size_t>(i)] >= hi - tol) ++tight;
    }
    return tight;
}

// cond_2(A) = lambda_max / lambda_min of the symmetric A (read from its lower triangle);
// infinite if A is not positive definite.
double condition_number(const IslandRecord& r) {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Eigen::MatrixXd A = Eigen::Map<const RowMajor>(r.A.data(), r.m, r.m);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
    const double lmin = eig.eigenvalues().minCoeff(), lmax = eig.eigenvalues().maxCoeff();
    return lmin > 0 ? lmax / lmin : std::numeric_limits<double>::infinity();
}

IslandMeasures measure(const IslandRecord& r, bool with_cond) {
    IslandMeasures m;
    const ode_bpp::Problem p = view(r);
    m.residuals = ode_bpp::compute_residuals(p, {r.x.data(), 1});
    m.tight = count_tight(p, r.x, &m.bounded);
    if (with_cond) m.cond = condition_number(r);
    return m;
}

// --------------------------------------------------------------------------------------------
// a run: one scene, one solver

struct RunResult {
    std::string scene, solver;
    long steps = 0;
    bool finite = true;
    int max_islands = 0;
    int max_rows = 0;
    std::vector<double> solve_ms;        ///< per step, summed over islands
    std::vector<double> step_ms;         ///< per step, collide + dWorldStep, without observe()
    std::vector<double> tight_fraction;  ///< per step, of that step's largest island
    double max_tight_fraction = 0;
    double worst_relative_residual = 0;
    double worst_scaled_residual = 0;
    double max_mass_ratio = 1;
    double max_cond = 0;
    double max_joint_error = 0;
    dMLCPStepStats totals{};
    SuccessReport success;
    /// false when the run was shorter than the scene's own length and its world stayed sound: the
    /// criterion says nothing about a partial run, so it was not evaluated
    bool judged = true;
    double criterion_seconds = 0;        ///< the scene's own length, after which it is judged
    double simulated_seconds = 0;        ///< simulated time the run reached
    long lcp_messages = 0;               ///< ODE's Dantzig "LCP internal error" messages
    TableTwo paper;
    double wall_seconds = 0;
    std::string capture_error;
    long capture_files = 0;
    std::uintmax_t capture_bytes = 0;
};

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

void write_csv_header(std::ofstream& csv) {
    csv << "scene,solver,step,time,island,rows,nub,bounded,tight,tight_fraction,solve_ms,pivots,"
           "fallbacks,status,natural_residual,relative_residual,scaled_residual,friction_error,"
           "mass_ratio,cond,step_ms\n";
}

void write_csv_row(std::ofstream& csv, const RunResult& run, double time, size_t island,
                   const IslandRecord& r, const IslandMeasures& m, double step_ms) {
    csv << run.scene << ',' << run.solver << ',' << run.steps << ',' << time << ',' << island << ','
        << r.m << ',' << r.nub << ',' << m.bounded << ',' << m.tight << ','
        << static_cast<double>(m.tight) / r.m << ',' << r.stats.seconds * 1e3 << ','
        << r.stats.pivots << ',' << r.stats.fallbacks << ',' << r.stats.status << ','
        << m.residuals.natural << ',' << m.residuals.relative_natural << ','
        << m.residuals.scaled_natural << ',' << m.residuals.friction << ',' << r.mass_ratio << ','
        << m.cond << ',' << step_ms << '\n';
}

struct RunOptions {
    SceneParams params;
    double seconds = 20;
    int cond_every = 30;
    bool quiet = false;
    std::string capture_dir;
    int capture_every = 1;
    bool capture_failures = false;
    ode_bpp::FrictionMode friction = ode_bpp::FrictionMode::Frozen;
    std::optional<int> max_pivots;
    std::ofstream* csv = nullptr;
};

void account_step(RunResult& run, Recorder& rec, const RunOptions& opt, double step_ms,
                  double time) {
    size_t largest = 0;
    for (size_t k = 0; k < rec.islands.size(); ++k) {
        if (rec.islands[k].m > rec.islands[largest].m) largest = k;
    }
    double solve = 0;
    for (size_t k = 0; k < rec.islands.size(); ++k) {
        const IslandRecord& r = rec.islands[k];
        if (!r.solved) continue;
        const bool with_cond = k == largest && opt.cond_every > 0 && run.steps % opt.cond_every == 0;
        const IslandMeasures m = measure(r, with_cond);
        solve += r.stats.seconds * 1e3;
        run.max_rows = std::max(run.max_rows, r.m);
        run.max_mass_ratio = std::max(run.max_mass_ratio, r.mass_ratio);
        run.worst_relative_residual = std::max(run.worst_relative_residual, m.residuals.relative_natural);
        run.worst_scaled_residual = std::max(run.worst_scaled_residual, m.residuals.scaled_natural);
        if (with_cond) run.max_cond = std::max(run.max_cond, m.cond);
        if (k == largest) {  // Fig. 3: the tight share of the largest island
            const double fraction = static_cast<double>(m.tight) / r.m;
            run.max_tight_fraction = std::max(run.max_tight_fraction, fraction);
            run.tight_fraction.push_back(fraction);
        }
        if (opt.csv) write_csv_row(*opt.csv, run, time, k, r, m, step_ms);
    }
    run.max_islands = std::max(run.max_islands, static_cast<int>(rec.islands.size()));
    run.solve_ms.push_back(solve);
    run.step_ms.push_back(step_ms);
    rec.islands.clear();
}

// A progress line on stderr: on a terminal it rewrites itself twice a second, in a log it is a
// plain line every 5 s.
class Progress {
public:
    explicit Progress(bool quiet) : quiet_(quiet) {}

    void maybe_report(const RunResult& run, double t, double seconds) {
        const auto every = kStderrIsTty ? std::chrono::milliseconds(500) : std::chrono::milliseconds(5000);
        if (quiet_ || Clock::now() - last_ < every) return;
        last_ = Clock::now();
        const double wall = std::chrono::duration<double>(last_ - start_).count();
        std::fprintf(stderr, "%s%s [%s] t = %5.2f / %.0f s, %6.1f steps/s   %s", kStderrIsTty ? "\r" : "",
                     run.scene.c_str(), run.solver.c_str(), t, seconds,
                     static_cast<double>(run.steps) / std::max(wall, 1e-9), kStderrIsTty ? "" : "\n");
        std::fflush(stderr);
    }

    void finish() const {
        if (!quiet_ && kStderrIsTty) std::fprintf(stderr, "\r%78s\r", "");
    }

private:
    bool quiet_;
    Clock::time_point start_ = Clock::now(), last_ = Clock::now();
};

// ODE's messages as ODE prints them, and once per process a line that explains Dantzig's
// "LCP internal error, s <= 0": a step of length s <= 0 on a nearly singular system, where ODE's
// Dantzig stops, keeps its answer with the remaining rows' impulses at zero, and the world step
// goes on (docs/maths.md). They are counted per run.
std::atomic<long> g_lcp_messages{0};

void on_ode_message(int number, const char* format, va_list ap) {
    char text[512];
    std::vsnprintf(text, sizeof text, format, ap);
    std::fprintf(stderr, "\nODE Message %d: %s\n", number, text);
    if (std::strstr(text, "LCP internal error") == nullptr) return;
    static bool explained = false;
    if (!explained) {
        std::fprintf(stderr, "ode-bpp-demo: this comes from ODE's Dantzig (the dantzig solver, or a fallback to it): it "
                             "could not take a pivot step (s <= 0), kept its answer with the remaining impulses at zero, "
                             "and the step went on; counted per run in the results\n");
        explained = true;
    }
    g_lcp_messages.fetch_add(1);
}

// One step: the scene's control, collision and dWorldStep, and the step's measurements.
// Returns false when the run must stop (the world blew up, or a capture file was lost).
bool advance(Scene& scene, SceneWorld& w, Recorder& rec, const RunOptions& opt, RunResult& run) {
    rec.step = run.steps;
    rec.capture_this_step = !opt.capture_dir.empty() && !opt.capture_failures && run.steps % opt.capture_every == 0;
    scene.control(w, w.time());
    rec.observing = Clock::duration::zero();
    const Clock::time_point t0 = Clock::now();
    const bool ok = w.step();
    const double step_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0 - rec.observing).count();
    account_step(run, rec, opt, step_ms, w.time());
    ++run.steps;
    run.max_joint_error = std::max(run.max_joint_error, w.max_joint_error());
    run.finite = ok;
    return ok && rec.capture_error.empty();
}

RunResult run_scene(const std::string& name, const RunOptions& opt) {
    RunResult run;
    run.scene = name;
    run.solver = opt.params.solver;
    std::unique_ptr<Scene> scene = make_scene(name);
    run.paper = scene->paper_table_two();
    SceneWorld w(opt.params);
    ode_bpp::WorldSettings settings = ode_bpp::world_settings(w.world());  // the hook's defaults
    settings.options.friction = opt.friction;
    if (opt.max_pivots) settings.options.max_pivots = *opt.max_pivots;
    ode_bpp::set_world_settings(w.world(), settings);
    scene->build(w);
    Recorder rec;
    rec.capture_dir = opt.capture_dir;
    rec.capture_failures = opt.capture_failures;
    rec.scene = name;
    rec.solver = run.solver;
    dWorldSetMLCPObserver(w.world(), &observe, &rec);
    const long total_steps = std::lround(opt.seconds / opt.params.step);
    const Clock::time_point start = Clock::now();
    Progress progress(opt.quiet);
    while (run.steps < total_steps && advance(*scene, w, rec, opt, run)) {
        progress.maybe_report(run, w.time(), opt.seconds);
    }
    progress.finish();
    dWorldSetMLCPObserver(w.world(), nullptr, nullptr);
    dWorldGetMLCPStats(w.world(), nullptr, &run.totals);
    run.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    run.criterion_seconds = scene->default_seconds();
    run.simulated_seconds = w.time();
    run.judged = !run.finite || w.time() >= run.criterion_seconds - 0.5 * opt.params.step;
    if (!run.finite) run.success = {false, "the world blew up (non-finite or failed step)"};
    else if (run.judged) run.success = scene->success(w);
    run.lcp_messages = g_lcp_messages.exchange(0);
    run.capture_error = rec.capture_error;
    run.capture_files = rec.capture_files;
    run.capture_bytes = rec.capture_bytes;
    return run;
}

// --------------------------------------------------------------------------------------------
// reports

std::string ratio_text(double r) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f:1", r);
    return buf;
}

std::string cond_text(double c) {
    if (!(c > 0)) return "-";
    if (std::isinf(c)) return "inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "1e%.0f", std::floor(std::log10(c) + 0.5));
    return buf;
}

std::string success_text(const RunResult& r) {
    if (!r.judged) return "n/a";
    return r.success.ok ? "yes" : "NO";
}

std::string table_two_text(double mass_ratio, int rows, double cond, const TableTwo& paper) {
    return "measured mass ratio " + ratio_text(mass_ratio) + ", rows " + std::to_string(rows) + ", cond " +
           cond_text(cond) + " | paper " + ratio_text(paper.mass_ratio) + ", " + std::to_string(paper.rows) + ", " +
           cond_text(paper.cond);
}

void print_summary(const RunResult& r) {
    std::printf("%s [%s]: %ld steps (%.1f s wall), islands/step <= %d, max rows %d, "
                "solve median %.3f ms max %.3f ms, step median %.3f ms, pivots %ld, fallbacks %ld, "
                "failures %ld, tight <= %.1f %%, worst residual %.1e (scaled %.1e), joint error <= %.1e m\n",
                r.scene.c_str(), r.solver.c_str(), r.steps, r.wall_seconds, r.max_islands, r.max_rows,
                percentile(r.solve_ms, 0.5), percentile(r.solve_ms, 1.0), percentile(r.step_ms, 0.5),
                static_cast<long>(r.totals.pivots), static_cast<long>(r.totals.fallbacks),
                static_cast<long>(r.totals.failures), 100 * r.max_tight_fraction,
                r.worst_relative_residual, r.worst_scaled_residual, r.max_joint_error);
    if (r.judged)
        std::printf("  success: %s (%s)\n", r.success.ok ? "yes" : "NO", r.success.detail.c_str());
    else
        std::printf("  success: not evaluated (the criterion is judged after the scene's %.0f s; this run: %.2f s)\n",
                    r.criterion_seconds, r.simulated_seconds);
    if (r.lcp_messages > 0) std::printf("  ODE's Dantzig printed 'LCP internal error' %ld times\n", r.lcp_messages);
    std::printf("  Table 2: %s\n",
                table_two_text(r.max_mass_ratio, r.max_rows, r.max_cond, r.paper).c_str());
}

std::string speedup_text(const RunResult& baseline, const RunResult& r) {
    const double mine = percentile(r.solve_ms, 0.5);
    if (!(mine > 0)) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2fx", percentile(baseline.solve_ms, 0.5) / mine);
    return buf;
}

/// The scene's Table 2 line, measured over its runs (every solver sees the same scene).
void print_table_two(const std::vector<RunResult>& runs, size_t first, size_t end) {
    double mass_ratio = 1, cond = 0;
    int rows = 0;
    for (size_t k = first; k < end; ++k) {
        mass_ratio = std::max(mass_ratio, runs[k].max_mass_ratio);
        cond = std::max(cond, runs[k].max_cond);
        rows = std::max(rows, runs[k].max_rows);
    }
    std::printf("  Table 2 (%s): %s\n", runs[first].scene.c_str(),
                table_two_text(mass_ratio, rows, cond, runs[first].paper).c_str());
}

void print_legend(const std::string& baseline) {
    std::printf(
        "solve ms/step: wall time in the solver per world step (all islands), median and slowest; lower is better.\n"
        "speed-up: %s's median / this solver's, same scene and run. pivots: ode-bpp's pivot steps (Dantzig counts none).\n"
        "fallbacks: islands answered through a fallback (regularization, ODE's Dantzig); failures: of those, islands the\n"
        "  world step handed to ODE's Dantzig. success: the scene's own criterion (n/a: a run shorter than the scene).\n"
        "worst resid: largest natural residual / max(1, |b|), friction bounds from the answer's own normals. With Frozen\n"
        "  friction (Dantzig's semantics, the default) the bounds come from earlier normals, so 1e1-1e3 is expected there\n"
        "  for every solver (--friction consistent holds each friction impulse to its own normal). Table 2: measured | paper.\n",
        baseline.c_str());
}

// fallbacks: every fallback (ODE counts a failed solve answered by its Dantzig as one too);
// failures: of those, the solves the world step handed to ODE's Dantzig. Runs come scene by
// scene, the solvers of one scene in the order given; the first is the speed-up's baseline.
void print_comparison(const std::vector<RunResult>& runs, size_t solvers) {
    std::printf("%-10s %-10s %21s %9s %9s %10s %9s %9s %8s %12s\n", "scene", "solver", "solve ms/step", "speed-up",
                "max rows", "pivots", "fallbacks", "failures", "success", "worst resid");
    std::printf("%-10s %-10s %10s %10s\n", "", "", "median", "max");
    long lcp_messages = 0;
    for (size_t first = 0; first < runs.size(); first += solvers) {
        for (size_t k = first; k < first + solvers; ++k) {
            const RunResult& r = runs[k];
            std::printf("%-10s %-10s %10.3f %10.3f %9s %9d %10ld %9ld %9ld %8s %12.1e\n", r.scene.c_str(),
                        r.solver.c_str(), percentile(r.solve_ms, 0.5), percentile(r.solve_ms, 1.0),
                        speedup_text(runs[first], r).c_str(), r.max_rows, static_cast<long>(r.totals.pivots),
                        static_cast<long>(r.totals.fallbacks), static_cast<long>(r.totals.failures),
                        success_text(r).c_str(), r.worst_relative_residual);
            lcp_messages += r.lcp_messages;
        }
        print_table_two(runs, first, first + solvers);
    }
    std::printf("\n");
    print_legend(runs.front().solver);
    if (lcp_messages == 0) return;
    std::printf("ODE's Dantzig printed 'LCP internal error' (see above) in:");
    for (const RunResult& r : runs)
        if (r.lcp_messages > 0) std::printf(" %s/%s %ldx", r.scene.c_str(), r.solver.c_str(), r.lcp_messages);
    std::printf("\n");
}

/// Creates DIR (and its parents) for --capture; false with the reason if it is not a directory
/// afterwards.
bool make_capture_directory(const std::string& dir, std::string* error) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
        *error = "cannot create the directory: " + ec.message();
        return false;
    }
    if (!std::filesystem::is_directory(dir, ec)) {
        *error = "exists and is not a directory";
        return false;
    }
    return true;
}

/// What --capture wrote, over all runs so far.
void report_capture(const std::vector<RunResult>& runs, const std::string& dir, FILE* out) {
    long files = 0;
    std::uintmax_t bytes = 0;
    for (const RunResult& r : runs) files += r.capture_files, bytes += r.capture_bytes;
    std::fprintf(out, "capture: %ld files, %ju bytes (%.1f MB) in %s\n", files, bytes, static_cast<double>(bytes) / 1e6,
                 dir.c_str());
}

void print_list() {
    for (const std::string& name : scene_names()) {
        std::printf("%-10s %s\n", name.c_str(), make_scene(name)->description().c_str());
    }
    std::printf("solvers: %s\n", dListMLCPSolvers());
}

}  // namespace

int main(int argc, char** argv) {
    dInitODE2(0);
    dSetMessageHandler(&on_ode_message);
    const Args args = parse_args(argc, argv);
    if (args.list) {
        print_list();
        dCloseODE();
        return 0;
    }
    std::ofstream csv;
    if (!args.csv.empty()) {
        csv.open(args.csv);
        if (!csv) usage_error("cannot write " + args.csv);
        write_csv_header(csv);
    }
    if (!args.capture_dir.empty()) {
        std::string error;
        if (!make_capture_directory(args.capture_dir, &error)) {
            std::fprintf(stderr, "ode-bpp-demo: --capture %s: %s\n", args.capture_dir.c_str(), error.c_str());
            dCloseODE();
            return kExitCaptureFailed;
        }
    }
    bool all_ok = true;
    std::vector<RunResult> runs;
    for (const std::string& scene : args.scenes) {
        for (const std::string& solver : args.solvers) {
            RunOptions opt;
            opt.params.solver = solver;
            opt.params.cfm = args.cfm ? *args.cfm
                                      : args.compliance ? cfm_from_compliance(*args.compliance, opt.params.step)
                                                        : opt.params.cfm;
            opt.seconds = args.seconds ? *args.seconds : make_scene(scene)->default_seconds();
            opt.cond_every = args.cond_every;
            opt.quiet = args.quiet;
            opt.capture_dir = args.capture_dir;
            opt.capture_every = args.capture_every;
            opt.capture_failures = args.capture_failures;
            opt.friction = args.friction;
            opt.max_pivots = args.max_pivots;
            opt.csv = csv.is_open() ? &csv : nullptr;
            runs.push_back(run_scene(scene, opt));
            if (!runs.back().capture_error.empty()) {
                std::fprintf(stderr, "ode-bpp-demo: capture into %s failed: %s\n", args.capture_dir.c_str(),
                             runs.back().capture_error.c_str());
                report_capture(runs, args.capture_dir, stderr);
                dCloseODE();
                return kExitCaptureFailed;
            }
            if (!args.compare) print_summary(runs.back());
            all_ok = all_ok && (!runs.back().judged || runs.back().success.ok);
        }
    }
    if (args.compare) print_comparison(runs, args.solvers.size());
    if (!args.capture_dir.empty()) report_capture(runs, args.capture_dir, stdout);
    dCloseODE();
    return all_ok ? 0 : kExitCriterionFailed;
}
