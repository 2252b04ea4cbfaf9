// bench_corpus: times every solver on a corpus of captured MLCP files in one process, with
// the methods interleaved file by file, and writes one CSV row per (file, method variant).
//
//   bench_corpus [--methods bpp,bpp-sky,...] [--pgs-iterations 10,35,...] [--repeat R]
//                [--warmup N] [--factor-error] [--limit] [--cond] [--consistent]
//                [--peers all|none|name,...] [--peer-iterations 10,35,...] [--peer-every K]
//                [--peer-repeat R] [--list-peers]
//                --csv OUT DIR|FILE...
//
// Peers (bench/peers, when built with their Debian packages): other libraries' solvers, each
// given the same Problem and timed the same way (their copies of A and the bounds included, as
// any caller pays them); their answers are judged by ode_bpp::compute_residuals, the residual
// Result carries for ode_bpp's methods. --peer-every K runs them only on frames whose number is a
// multiple of K, with --peer-repeat timed rounds (default --repeat); the dense PGS and Lemke peers
// cost far more than the rest on large islands.
//
// --consistent adds the variant "bpp-consistent": bpp with FrictionMode::Consistent, whose answer
// satisfies |x_i| <= mu_i x_findex[i] at convergence, so that its natural residual (friction bounds
// from the answer's own normals) can reach rounding level; the Frozen methods (Dantzig's semantics)
// keep the bounds of a first solve and need not.
//
// Timing: for each file, every variant is solved once untimed (caches, allocations), then R
// rounds follow; in each round the variants run in an order rotated by file and round, so no
// method always runs first or right after another one. The median of the R times is reported.
// The first N files are solved once more beforehand, untimed, to warm the process up.
//
// bpp's "limit" (--limit): bpp re-solved from its own final index set (Start::states)
// with max_pivots = 1, i.e. the cost of factoring for the final A_FF plus one solve. It
// approximates the time of a method that guessed the index set right at once; it includes the
// ordering and the factorization of A before the rows of T are taken out, and every fixed cost
// of a solve (validation, residuals), so it is an upper bound of one Cholesky of A_FF plus one
// solve. Beside it, --limit also writes the *physical* limit (physical_limit.h): that one
// factorization of the final A_FF in envelope storage and one solve, timed alone.
//
// --factor-error writes Table 4's ‖L_deleted − chol(A_FF)‖_F for every factoring method and, for
// bpp, the precision floor it is read against (factor_precision.h): how far a fresh factor of the
// same A_FF (fresh_factor_error) and the downdated one (deleted_factor_error), in bpp's order,
// each are from the exact factor.
#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "ode_bpp/io.h"
#include "ode_bpp/residuals.h"
#include "ode_bpp/solver.h"
#include "factor_precision.h"
#include "peer_registry.h"
#include "physical_limit.h"

namespace {

/// One timed configuration: a method and, for PGS, its sweep count.
struct Variant {
    ode_bpp::Method method = ode_bpp::Method::Bpp;
    int pgs_iterations = 0;  ///< 0 for the direct methods
    ode_bpp::FrictionMode friction = ode_bpp::FrictionMode::Frozen;
    std::string name;        ///< "bpp", "pgs-35", "bullet-lemke", ...
    ode_bpp::bench::PeerMethod peer;  ///< set (peer.solve callable) for a peer's variant
    bool is_peer() const { return static_cast<bool>(peer.solve); }
};

struct Cli {
    std::vector<ode_bpp::Method> methods;
    std::vector<int> pgs_iterations{10, 35, 100, 300, 1000};
    int repeat = 5;
    int warmup_files = 10;
    bool factor_error = false;
    bool limit = false;
    bool cond = false;
    bool consistent = false;
    std::vector<std::string> peers;  ///< names, or {"all"}; empty: none
    std::vector<int> peer_iterations{10, 35, 100, 300};
    int peer_every = 1;
    int peer_repeat = 0;  ///< 0: as repeat
    bool list_peers = false;
    std::string csv;
    std::vector<std::string> inputs;
};

[[noreturn]] void usage(const std::string& why) {
    std::cerr << "bench_corpus: " << why << "\n"
              << "usage: bench_corpus [--methods a,b,...] [--pgs-iterations 10,35,...] [--repeat R]\n"
                 "                    [--warmup N] [--factor-error] [--limit] [--cond] [--consistent]\n"
                 "                    [--peers all|none|name,...] [--peer-iterations 10,35,...] [--peer-every K]\n"
                 "                    [--peer-repeat R] [--list-peers] --csv OUT DIR|FILE...\n";
    std::exit(2);
}

std::vector<std::string> split_commas(const std::string& text) {
    std::vector<std::string> parts;
    std::stringstream stream(text);
    for (std::string part; std::getline(stream, part, ',');) {
        if (!part.empty()) parts.push_back(part);
    }
    return parts;
}

int parse_positive(const std::string& flag, const std::string& text) {
    try {
        const int value = std::stoi(text);
        if (value >= 1) return value;
    } catch (const std::exception&) {
    }
    usage(flag + " needs a positive integer, got '" + text + "'");
}

Cli parse_cli(int argc, char** argv) {
    Cli cli;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--methods") {
            for (const std::string& name : split_commas(value())) {
                const auto method = ode_bpp::method_from_string(name);
                if (!method) usage("unknown method '" + name + "'");
                cli.methods.push_back(*method);
            }
        } else if (arg == "--pgs-iterations") {
            cli.pgs_iterations.clear();
            for (const std::string& count : split_commas(value())) cli.pgs_iterations.push_back(parse_positive(arg, count));
        } else if (arg == "--repeat") {
            cli.repeat = parse_positive(arg, value());
        } else if (arg == "--warmup") {
            cli.warmup_files = parse_positive(arg, value());
        } else if (arg == "--factor-error") {
            cli.factor_error = true;
        } else if (arg == "--limit") {
            cli.limit = true;
        } else if (arg == "--cond") {
            cli.cond = true;
        } else if (arg == "--consistent") {
            cli.consistent = true;
        } else if (arg == "--peers") {
            cli.peers = split_commas(value());
            if (cli.peers.size() == 1 && cli.peers[0] == "none") cli.peers.clear();
        } else if (arg == "--peer-iterations") {
            cli.peer_iterations.clear();
            for (const std::string& count : split_commas(value())) cli.peer_iterations.push_back(parse_positive(arg, count));
        } else if (arg == "--peer-every") {
            cli.peer_every = parse_positive(arg, value());
        } else if (arg == "--peer-repeat") {
            cli.peer_repeat = parse_positive(arg, value());
        } else if (arg == "--list-peers") {
            cli.list_peers = true;
        } else if (arg == "--csv") {
            cli.csv = value();
        } else if (!arg.empty() && arg[0] == '-') {
            usage("unknown option " + arg);
        } else {
            cli.inputs.push_back(arg);
        }
    }
    if (cli.list_peers) return cli;
    if (cli.csv.empty()) usage("--csv OUT is required");
    if (cli.inputs.empty()) usage("no DIR or FILE given");
    if (cli.methods.empty()) {
        for (const std::string& name : ode_bpp::method_names()) cli.methods.push_back(*ode_bpp::method_from_string(name));
    }
    return cli;
}

std::vector<Variant> make_variants(const Cli& cli) {
    std::vector<Variant> variants;
    for (ode_bpp::Method method : cli.methods) {
        if (method != ode_bpp::Method::Pgs) {
            variants.push_back({method, 0, ode_bpp::FrictionMode::Frozen, ode_bpp::to_string(method), {}});
            continue;
        }
        for (int sweeps : cli.pgs_iterations)
            variants.push_back({method, sweeps, ode_bpp::FrictionMode::Frozen, "pgs-" + std::to_string(sweeps), {}});
    }
    if (cli.consistent)
        variants.push_back({ode_bpp::Method::Bpp, 0, ode_bpp::FrictionMode::Consistent, "bpp-consistent", {}});
    const bool all = cli.peers.size() == 1 && cli.peers[0] == "all";
    for (ode_bpp::bench::PeerMethod& peer : ode_bpp::bench::all_peer_methods(cli.peer_iterations)) {
        if (all || std::find(cli.peers.begin(), cli.peers.end(), peer.name) != cli.peers.end())
            variants.push_back({ode_bpp::Method::Bpp, peer.iterations, ode_bpp::FrictionMode::Frozen, peer.name, peer});
    }
    return variants;
}

/// Every *.mlcp file under the inputs, sorted by path so that frames come in order.
std::vector<std::string> list_files(const std::vector<std::string>& inputs) {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    for (const std::string& input : inputs) {
        std::error_code ec;
        if (!fs::is_directory(input, ec)) {
            files.push_back(input);
            continue;
        }
        for (const auto& entry : fs::recursive_directory_iterator(input, ec)) {
            if (entry.is_regular_file() && entry.path().extension() == ".mlcp") files.push_back(entry.path().string());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

ode_bpp::Options options_for(const Variant& variant) {
    ode_bpp::Options options;
    options.method = variant.method;
    options.friction = variant.friction;
    if (variant.pgs_iterations > 0) options.pgs_iterations = variant.pgs_iterations;
    options.record_steps = false;  // keeps the timing to the solve itself
    return options;
}

/// Wall time of one solve in microseconds; result and x receive the solve's answer.
double timed_solve(const ode_bpp::Problem& problem, const ode_bpp::Options& options,
                   std::vector<double>& x, ode_bpp::Result* result, const ode_bpp::Start& from = {}) {
    const auto start = std::chrono::steady_clock::now();
    *result = ode_bpp::solve(problem, options, x.data(), from);
    const auto stop = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::micro>(stop - start).count();
}

/// Wall time of one peer solve in microseconds; status receives the peer's claim.
double timed_peer_solve(const ode_bpp::Problem& problem, const Variant& variant, std::vector<double>& x,
                        ode_bpp::bench::PeerStatus* status) {
    const auto start = std::chrono::steady_clock::now();
    *status = variant.peer.solve(problem, x.data());
    const auto stop = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::micro>(stop - start).count();
}

double median(std::vector<double> values) {
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(values.begin(), values.end());
    const std::size_t mid = values.size() / 2;
    return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

/// cond_2(A) = lambda_max / lambda_min of the symmetric A; infinite when A is not positive definite.
double condition_number(const ode_bpp::MlcpFile& file) {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Eigen::MatrixXd A = Eigen::Map<const RowMajor>(file.A.data(), file.n, file.n);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
    const double lmin = eig.eigenvalues().minCoeff(), lmax = eig.eigenvalues().maxCoeff();
    return lmin > 0 ? lmax / lmin : std::numeric_limits<double>::infinity();
}

/// What one variant did on one file.
struct Measurement {
    ode_bpp::Result result;  ///< for a peer: status unused, residual fields from compute_residuals
    std::vector<double> x;
    ode_bpp::bench::PeerStatus peer_status = ode_bpp::bench::PeerStatus::Skipped;
    bool measured = false;   ///< false: not run on this file (a peer outside --peer-every)
    double nonfriction_residual = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> times_us;
    double factor_error = std::numeric_limits<double>::quiet_NaN();
    /// bpp only: how far a fresh and the downdated factor of A_FF (its final index set and order)
    /// each are from the exact one, the floor factor_error is read against (factor_precision.h)
    ode_bpp::bench::FactorPrecision precision;
    double limit_us = std::numeric_limits<double>::quiet_NaN();
    std::string limit_status;
    double physical_limit_us = std::numeric_limits<double>::quiet_NaN();
};

/// The group of a file: the name of the directory holding it ("crane-cfm1e-10").
std::string group_of(const std::string& path) {
    return std::filesystem::path(path).parent_path().filename().string();
}

std::string meta_or(const ode_bpp::MlcpFile& file, const char* key, const std::string& fallback) {
    const std::string* value = file.meta.find(key);
    return value ? *value : fallback;
}

/// Times bpp warm-started from its own final index set with one pivot step, and the physical
/// limit of that index set (see the header).
void measure_limit(const ode_bpp::MlcpFile& file, int repeat, Measurement& bpp) {
    const ode_bpp::Problem problem = file.view();
    ode_bpp::Options options;
    options.method = ode_bpp::Method::Bpp;
    options.record_steps = false;
    ode_bpp::Start from;
    from.states = bpp.result.states;
    options.max_pivots = 1;
    options.dantzig_fallback = false;
    std::vector<double> x(static_cast<std::size_t>(problem.n));
    std::vector<double> times;
    ode_bpp::Result result;
    timed_solve(problem, options, x, &result, from);
    for (int r = 0; r < repeat; ++r) times.push_back(timed_solve(problem, options, x, &result, from));
    bpp.limit_us = median(times);
    bpp.limit_status = ode_bpp::to_string(result.status);
    bpp.physical_limit_us = ode_bpp::bench::physical_limit_us(file, bpp.result.states, repeat);
}

/// The relative natural residual (as Residuals::relative_natural) over the rows without
/// friction only (findex < 0), where every method solves the same fixed-bound conditions and the
/// Frozen/Consistent friction semantics play no part. x: n entries, original order.
double nonfriction_residual(const ode_bpp::Problem& problem, const std::vector<double>& x) {
    const ode_bpp::ConstStrided xs{x.data(), 1};
    std::vector<double> w, scale;
    ode_bpp::residual_vectors(problem, xs, w, scale);
    double worst = 0.0, b_norm = 1.0;
    for (int i = 0; i < problem.n; ++i) {
        b_norm = std::max(b_norm, std::fabs(problem.b[i]));
        if (problem.findex && problem.findex[i] >= 0) continue;
        const auto [lo, hi] = ode_bpp::effective_bounds(problem, xs, i);
        worst = std::max(worst, std::fabs(x[i] - std::clamp(x[i] - w[i], lo, hi)));
    }
    return worst / b_norm;
}

/// One run of a variant into m (its answer in m.x); returns the wall time in microseconds.
double run_variant(const ode_bpp::Problem& problem, const Variant& variant, Measurement& m) {
    if (variant.is_peer()) return timed_peer_solve(problem, variant, m.x, &m.peer_status);
    return timed_solve(problem, options_for(variant), m.x, &m.result);
}

/// A peer's answer judged like ode_bpp's: the residuals of ode_bpp/residuals.h at its x.
void judge_peer_answer(const ode_bpp::Problem& problem, Measurement& m) {
    const ode_bpp::Residuals r = ode_bpp::compute_residuals(problem, ode_bpp::ConstStrided{m.x.data(), 1});
    m.result.residuals.natural = r.natural;
    m.result.residuals.relative_natural = r.relative_natural;
    m.result.residuals.scaled_natural = r.scaled_natural;
    m.result.residuals.friction = r.friction;
    m.result.pivoting.pivots = 0;
    m.result.tight = 0;
}

std::vector<Measurement> measure_file(const ode_bpp::MlcpFile& file, const std::vector<Variant>& variants,
                                      const Cli& cli, std::size_t file_index, bool with_peers) {
    const ode_bpp::Problem problem = file.view();
    const std::size_t count = variants.size();
    std::vector<Measurement> out(count);
    for (std::size_t v = 0; v < count; ++v) {
        out[v].measured = with_peers || !variants[v].is_peer();
        out[v].x.assign(static_cast<std::size_t>(problem.n), 0.0);
        if (out[v].measured) run_variant(problem, variants[v], out[v]);
    }
    const int peer_repeat = cli.peer_repeat > 0 ? cli.peer_repeat : cli.repeat;
    for (int r = 0; r < std::max(cli.repeat, peer_repeat); ++r) {
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t v = (k + file_index + static_cast<std::size_t>(r)) % count;
            const int rounds = variants[v].is_peer() ? peer_repeat : cli.repeat;
            if (out[v].measured && r < rounds) out[v].times_us.push_back(run_variant(problem, variants[v], out[v]));
        }
    }
    for (std::size_t v = 0; v < count; ++v) {
        if (!out[v].measured) continue;
        out[v].nonfriction_residual = nonfriction_residual(problem, out[v].x);
        if (variants[v].is_peer()) judge_peer_answer(problem, out[v]);
        if (variants[v].is_peer()) continue;
        const bool factored = variants[v].method != ode_bpp::Method::Dantzig && variants[v].method != ode_bpp::Method::Pgs;
        if (cli.factor_error && factored) {
            ode_bpp::Options options = options_for(variants[v]);
            options.compute_factor_error = true;
            ode_bpp::Result with_error = ode_bpp::solve(problem, options, out[v].x.data());
            out[v].factor_error = with_error.factor_error;
            if (variants[v].name == "bpp" && with_error.tight > 0)
                out[v].precision = ode_bpp::bench::factor_precision(file, with_error.ordering, with_error.states);
        }
        if (cli.limit && variants[v].name == "bpp") measure_limit(file, cli.repeat, out[v]);
    }
    return out;
}

const char* kHeader =
    "group,scene,frame,island,file,n,nub,cond,method,iterations,status,time_us,pivots,murty_pivots,"
    "tight,natural_residual,relative_natural_residual,scaled_natural_residual,friction_error,"
    "factor_error,fallback,limit_us,limit_status,nonfriction_residual,physical_limit_us,friction_rows,"
    "fresh_factor_error,deleted_factor_error\n";

/// Rows with a friction coupling (findex >= 0): Frozen friction solves such an island twice
/// (frictionless first), so its fewest pivot steps are 2, else 1.
long friction_rows(const ode_bpp::MlcpFile& file) {
    return std::count_if(file.findex.begin(), file.findex.end(), [](int f) { return f >= 0; });
}

void write_row(std::ostream& csv, const ode_bpp::MlcpFile& file, const std::string& path, double cond,
               const Variant& variant, const Measurement& m) {
    const ode_bpp::Result& r = m.result;
    csv << group_of(path) << ',' << meta_or(file, "scene", "") << ',' << meta_or(file, "frame", "") << ','
        << meta_or(file, "island", "") << ',' << std::filesystem::path(path).filename().string() << ','
        << file.n << ',' << file.nub << ',' << cond << ',' << variant.name << ',' << variant.pgs_iterations << ','
        << (variant.is_peer() ? ode_bpp::bench::to_string(m.peer_status) : ode_bpp::to_string(r.status)) << ','
        << median(m.times_us) << ',' << r.pivoting.pivots << ',' << r.pivoting.murty_pivots
        << ',' << r.tight << ',' << r.residuals.natural << ',' << r.residuals.relative_natural << ','
        << r.residuals.scaled_natural << ',' << r.residuals.friction << ',' << m.factor_error << ','
        << (r.fallback == ode_bpp::Fallback::None ? "-" : ode_bpp::to_string(r.fallback)) << ',' << m.limit_us << ','
        << (m.limit_status.empty() ? "-" : m.limit_status) << ',' << m.nonfriction_residual << ','
        << m.physical_limit_us << ',' << friction_rows(file) << ',' << m.precision.fresh << ',' << m.precision.deleted
        << '\n';
}

void warm_up(const std::vector<std::string>& files, const std::vector<Variant>& variants, int count) {
    for (std::size_t k = 0; k < files.size() && k < static_cast<std::size_t>(count); ++k) {
        const ode_bpp::ReadResult read = ode_bpp::read_mlcp(files[k]);
        if (!read.ok) continue;
        std::vector<double> x(static_cast<std::size_t>(read.file.n));
        ode_bpp::Result result;
        for (const Variant& variant : variants) {
            if (variant.is_peer()) continue;  // peers are warmed up by their untimed first run per file
            timed_solve(read.file.view(), options_for(variant), x, &result);
        }
    }
}

}  // namespace

/// Peers run on frames whose number is a multiple of --peer-every (files without a frame: always).
bool peers_on(const ode_bpp::MlcpFile& file, int peer_every) {
    const std::string frame = meta_or(file, "frame", "");
    if (frame.empty() || peer_every <= 1) return true;
    try {
        return std::stol(frame) % peer_every == 0;
    } catch (const std::exception&) {
        return true;
    }
}

int list_peers() {
    const std::vector<ode_bpp::bench::PeerMethod> peers = ode_bpp::bench::all_peer_methods({10});
    if (peers.empty()) std::cout << "none (bench_corpus was built without peers; see bench/peers)\n";
    for (const auto& peer : peers) std::cout << peer.name << "\n";
    return 0;
}

int main(int argc, char** argv) {
    const Cli cli = parse_cli(argc, argv);
    if (cli.list_peers) return list_peers();
    const std::vector<Variant> variants = make_variants(cli);
    if (!cli.peers.empty() && std::none_of(variants.begin(), variants.end(), [](const Variant& v) { return v.is_peer(); }))
        std::cerr << "bench_corpus: no peer matches --peers (built without peers? --list-peers shows them)\n";
    const std::vector<std::string> files = list_files(cli.inputs);
    if (files.empty()) usage("no *.mlcp files under the inputs");
    std::ofstream csv(cli.csv);
    if (!csv) usage("cannot write " + cli.csv);
    csv.precision(6);
    csv << kHeader;
    warm_up(files, variants, cli.warmup_files);
    int unread = 0;
    for (std::size_t k = 0; k < files.size(); ++k) {
        const ode_bpp::ReadResult read = ode_bpp::read_mlcp(files[k]);
        if (!read.ok) {
            std::cerr << "bench_corpus: " << read.error << "\n";
            ++unread;
            continue;
        }
        const double cond = cli.cond ? condition_number(read.file) : std::numeric_limits<double>::quiet_NaN();
        const std::vector<Measurement> measured =
            measure_file(read.file, variants, cli, k, peers_on(read.file, cli.peer_every));
        for (std::size_t v = 0; v < variants.size(); ++v)
            if (measured[v].measured) write_row(csv, read.file, files[k], cond, variants[v], measured[v]);
        if ((k + 1) % 100 == 0 || k + 1 == files.size())
            std::cerr << "bench_corpus: [" << k + 1 << "/" << files.size() << "] " << group_of(files[k]) << "\n";
    }
    csv.flush();
    if (!csv) {
        std::cerr << "bench_corpus: writing " << cli.csv << " failed\n";
        return 1;
    }
    return unread == 0 ? 0 : 1;
}
