// chain_conditioning: is the joint gap of a long hanging chain ODE's model or the conditioning of
// A? The sweeps' HangingChain (N ball-jointed links, mass ratio R) is stepped by dWorldStep with
// a probe solver registered in the sparse form, which, every step, solves the island in one of
// three ways and writes one of the answers back:
//     bpp          ode_bpp::solve (method bpp), as the world step does
//     refined      bpp, then iterative refinement: the residual r = b - A x accumulated in long
//                  double, a correction A d = r solved by bpp again, x += d (kRefinements rounds)
//     longdouble   a sparse LDL^T of A in long double (Eigen's SimplicialLDLT, 64-bit mantissa)
// and, whatever it writes back, measures all three against each other: the relative residual
// |b - A x|_inf / |b|_inf (in long double) of each answer and its distance to the long-double
// answer. Every kCondEvery steps it estimates cond_2(A) (power iteration on A and on A^-1).
// A chain's rows are all unbounded (ball joints), so each answer is one linear solve.
//
//   chain_conditioning --links N [--ratio R] [--seconds S] [--step H] [--variant bpp|refined|longdouble]
//                      [--csv FILE] [--summary FILE]
// --csv FILE gets one row per step; --summary FILE one row per run, appended (the header first
// when the file is new); stdout the same summary as one line.
#include <ode/mlcp.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "ode/island_view.h"
#include "ode_bpp/ode.h"
#include "ode_bpp/solver.h"
#include "scenes/joint_gap.h"
#include "scenes/scene.h"
#include "scenes/sweep_scenes.h"

namespace {

using Real = long double;
using SparseLd = Eigen::SparseMatrix<Real>;
using VectorLd = Eigen::Matrix<Real, Eigen::Dynamic, 1>;

constexpr int kRefinements = 2;
constexpr int kCondEvery = 30;
constexpr int kPowerIterations = 60;
constexpr const char* kProbeName = "chain-probe";

enum class Variant { Bpp, Refined, LongDouble };

struct Cli {
    int links = 1000;
    double ratio = 30;
    double seconds = 2;
    double step = 1.0 / 60.0;
    Variant variant = Variant::Bpp;
    std::string csv, summary;
};

[[noreturn]] void usage(const std::string& why) {
    std::cerr << "chain_conditioning: " << why << "\n"
              << "usage: chain_conditioning --links N [--ratio R] [--seconds S] [--step H]\n"
                 "                          [--variant bpp|refined|longdouble] [--csv FILE] [--summary FILE]\n";
    std::exit(2);
}

/// What the probe measured on the island of one step.
struct StepRecord {
    long step = 0;
    int rows = 0;
    double residual_bpp = 0, residual_refined = 0, residual_ld = 0;  ///< |b - A x|_inf / |b|_inf
    double error_bpp = 0, error_refined = 0;  ///< |x - x_ld|_inf / |x_ld|_inf
    double cond = std::numeric_limits<double>::quiet_NaN();
};

struct Probe {
    Variant variant = Variant::Bpp;
    long step = 0;
    std::vector<StepRecord> records;
    ode_bpp::ode::IslandView view;
};

SparseLd to_long_double(const ode_bpp::linalg::SymmetricRows& a) {
    std::vector<Eigen::Triplet<Real>> entries;
    for (int i = 0; i < a.n(); ++i) {
        entries.emplace_back(i, i, a.diag(i));
        for (int k = a.row_begin(i); k < a.row_end(i); ++k) entries.emplace_back(i, a.col(k), a.val(k));
    }
    SparseLd m(a.n(), a.n());
    m.setFromTriplets(entries.begin(), entries.end());
    return m;
}

VectorLd to_ld(const std::vector<double>& v) {
    VectorLd out(static_cast<Eigen::Index>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) out[static_cast<Eigen::Index>(i)] = v[i];
    return out;
}

Real inf_norm(const VectorLd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0; }

Real relative_residual(const SparseLd& a, const VectorLd& b, const std::vector<double>& x) {
    return inf_norm(b - a * to_ld(x)) / std::max<Real>(1, inf_norm(b));
}

Real relative_error(const std::vector<double>& x, const VectorLd& reference) {
    return inf_norm(to_ld(x) - reference) / std::max<Real>(std::numeric_limits<Real>::min(), inf_norm(reference));
}

/// cond_2(A) of the symmetric positive definite A: power iteration on A and on A^-1 (through
/// the long-double factor), kPowerIterations each.
double condition_estimate(const SparseLd& a, const Eigen::SimplicialLDLT<SparseLd>& factor) {
    VectorLd v = VectorLd::Ones(a.rows()).normalized(), w = v;
    Real largest = 0, smallest_inverse = 0;
    for (int k = 0; k < kPowerIterations; ++k) {
        const VectorLd av = a * v;
        largest = v.dot(av);
        v = av.normalized();
        const VectorLd iw = factor.solve(w);
        smallest_inverse = w.dot(iw);
        w = iw.normalized();
    }
    return static_cast<double>(largest * smallest_inverse);
}

/// bpp's answer to A x = rhs (all rows unbounded) for the island's problem with b replaced.
std::vector<double> bpp_solve(const ode_bpp::Problem& island, const std::vector<double>& rhs) {
    ode_bpp::Problem p = island;
    p.b = ode_bpp::ConstStrided{rhs.data(), 1};
    std::vector<double> x(rhs.size());
    ode_bpp::Options options;
    options.method = ode_bpp::Method::Bpp;
    ode_bpp::solve(p, options, x.data());
    return x;
}

bool all_unbounded(const ode_bpp::Problem& p) {
    for (int i = 0; i < p.n; ++i)
        if (std::isfinite(p.lo[i]) || std::isfinite(p.hi[i])) return false;
    return true;
}

dMLCPStatus probe_solve(const dMLCP* island, dMLCPIslandStats* stats, void* userdata) {
    auto* probe = static_cast<Probe*>(userdata);
    const auto start = std::chrono::steady_clock::now();
    const ode_bpp::Problem p = probe->view.of(*island);
    if (p.sparse == nullptr || !all_unbounded(p)) return dMLCPFailed;  // not a chain: Dantzig answers
    std::vector<double> b(static_cast<std::size_t>(p.n));
    for (int i = 0; i < p.n; ++i) b[static_cast<std::size_t>(i)] = p.b[i];
    const SparseLd a = to_long_double(*p.sparse);
    const VectorLd b_ld = to_ld(b);
    Eigen::SimplicialLDLT<SparseLd> factor(a);
    if (factor.info() != Eigen::Success) return dMLCPFailed;
    const VectorLd x_ld = factor.solve(b_ld);

    const std::vector<double> x_bpp = bpp_solve(p, b);
    std::vector<double> x_refined = x_bpp;
    for (int round = 0; round < kRefinements; ++round) {
        const VectorLd r = b_ld - a * to_ld(x_refined);
        std::vector<double> r_double(b.size());
        for (std::size_t i = 0; i < b.size(); ++i) r_double[i] = static_cast<double>(r[static_cast<Eigen::Index>(i)]);
        const std::vector<double> d = bpp_solve(p, r_double);
        for (std::size_t i = 0; i < b.size(); ++i) x_refined[i] += d[i];
    }
    std::vector<double> x_long(b.size());
    for (std::size_t i = 0; i < b.size(); ++i) x_long[i] = static_cast<double>(x_ld[static_cast<Eigen::Index>(i)]);

    StepRecord rec;
    rec.step = probe->step;
    rec.rows = p.n;
    rec.residual_bpp = static_cast<double>(relative_residual(a, b_ld, x_bpp));
    rec.residual_refined = static_cast<double>(relative_residual(a, b_ld, x_refined));
    rec.residual_ld = static_cast<double>(relative_residual(a, b_ld, x_long));
    rec.error_bpp = static_cast<double>(relative_error(x_bpp, x_ld));
    rec.error_refined = static_cast<double>(relative_error(x_refined, x_ld));
    if (probe->step % kCondEvery == 1) rec.cond = condition_estimate(a, factor);
    probe->records.push_back(rec);

    const std::vector<double>& answer =
        probe->variant == Variant::Bpp ? x_bpp : probe->variant == Variant::Refined ? x_refined : x_long;
    for (int i = 0; i < p.n; ++i) island->pairsbx[2 * i + 1] = answer[static_cast<std::size_t>(i)];
    stats->status = dMLCPSolved;
    stats->pivots = 1;
    stats->fallbacks = 0;
    stats->tight = 0;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->fallback = nullptr;
    return dMLCPSolved;
}

Cli parse_cli(int argc, char** argv) {
    Cli cli;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--links") cli.links = std::atoi(value().c_str());
        else if (arg == "--ratio") cli.ratio = std::atof(value().c_str());
        else if (arg == "--seconds") cli.seconds = std::atof(value().c_str());
        else if (arg == "--step") cli.step = std::atof(value().c_str());
        else if (arg == "--csv") cli.csv = value();
        else if (arg == "--summary") cli.summary = value();
        else if (arg == "--variant") {
            const std::string v = value();
            if (v == "bpp") cli.variant = Variant::Bpp;
            else if (v == "refined") cli.variant = Variant::Refined;
            else if (v == "longdouble") cli.variant = Variant::LongDouble;
            else usage("unknown variant " + v);
        } else usage("unknown option " + arg);
    }
    if (cli.links < 1 || !(cli.ratio >= 1) || !(cli.seconds > 0) || !(cli.step > 0))
        usage("--links >= 1, --ratio >= 1, --seconds > 0, --step > 0");
    return cli;
}

/// ODE's linearised joint rows: a link of length ell turning at omega drifts by about
/// (omega h)^2 ell / 2 per step while ERP removes a fraction ERP of the gap per step, so the gap
/// settles near (omega h)^2 ell / (2 ERP) (docs/modelling.md).
double drift_bound(double omega, const ode_bpp::scenes::SceneParams& p) {
    constexpr double kLinkLength = 0.5;  // the sweeps' link length (sweep_scenes.cpp)
    return (omega * p.step) * (omega * p.step) * kLinkLength / (2 * p.erp);
}

/// The fastest-turning body: |omega| [rad/s] and its place along the chain (0: the anchored link,
/// 1: the load; bodies are created from the anchor down).
struct Spin {
    double omega = 0;
    double place = 0;
};

Spin fastest_body(const std::vector<dBodyID>& bodies) {
    Spin s;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        const dReal* w = dBodyGetAngularVel(bodies[k]);
        const double omega = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        if (omega > s.omega) s = {omega, bodies.size() > 1 ? static_cast<double>(k) / (bodies.size() - 1) : 0};
    }
    return s;
}

const char* kSummaryHeader =
    "links,rows,ratio,step,variant,steps,gap_max_m,residual_bpp_max,residual_refined_max,residual_longdouble_max,"
    "error_bpp_max,error_refined_max,cond_max,omega_max,linearisation_drift_max_m";

const char* to_string(Variant v) { return v == Variant::Bpp ? "bpp" : v == Variant::Refined ? "refined" : "longdouble"; }

}  // namespace

int main(int argc, char** argv) {
    const Cli cli = parse_cli(argc, argv);
    dInitODE2(0);
    ode_bpp_register_solvers();
    Probe probe;
    probe.variant = cli.variant;
    if (!dRegisterMLCPSolverEx(kProbeName, &probe_solve, &probe, dMLCP_API_VERSION, dMLCP_SPARSE)) {
        std::cerr << "chain_conditioning: cannot register the probe solver\n";
        return 1;
    }
    ode_bpp::scenes::SceneParams params;
    params.solver = kProbeName;
    params.step = cli.step;
    ode_bpp::scenes::SceneWorld world(params);
    ode_bpp::scenes::build_sweep_scene(world, {ode_bpp::scenes::SweepPattern::HangingChain, cli.ratio, cli.links});
    const long steps = std::lround(cli.seconds / params.step);
    std::vector<double> gaps;
    std::vector<Spin> spins;
    for (long k = 0; k < steps; ++k) {
        probe.step = k + 1;
        if (!world.step()) break;
        gaps.push_back(ode_bpp::scenes::max_anchor_gap(world.bodies()));
        spins.push_back(fastest_body(world.bodies()));
        if ((k + 1) % std::max(1L, steps / 10) == 0)
            std::cerr << "chain_conditioning: " << cli.links << " links, " << to_string(cli.variant) << " [" << k + 1
                      << "/" << steps << "] gap " << gaps.back() << " m\n";
    }
    if (!cli.csv.empty()) {
        std::ofstream csv(cli.csv);
        csv.precision(6);
        csv << "links,ratio,variant,step,rows,gap_m,residual_bpp,residual_refined,residual_longdouble,error_bpp,"
               "error_refined,cond,omega_max,omega_place,linearisation_drift_m\n";
        for (std::size_t k = 0; k < probe.records.size() && k < gaps.size(); ++k) {
            const StepRecord& r = probe.records[k];
            csv << cli.links << ',' << cli.ratio << ',' << to_string(cli.variant) << ',' << r.step << ',' << r.rows << ','
                << gaps[k] << ',' << r.residual_bpp << ',' << r.residual_refined << ',' << r.residual_ld << ','
                << r.error_bpp << ',' << r.error_refined << ',' << r.cond << ',' << spins[k].omega << ','
                << spins[k].place << ',' << drift_bound(spins[k].omega, params) << '\n';
        }
    }
    auto worst = [&](double StepRecord::*field) {
        double w = 0;
        for (const StepRecord& r : probe.records) w = std::max(w, r.*field);
        return w;
    };
    double omega_max = 0;
    for (const Spin& spin : spins) omega_max = std::max(omega_max, spin.omega);
    double cond = 0;
    for (const StepRecord& r : probe.records)
        if (std::isfinite(r.cond)) cond = std::max(cond, r.cond);
    const double gap_max = gaps.empty() ? 0 : *std::max_element(gaps.begin(), gaps.end());
    std::ostringstream row;
    row.precision(6);
    row << cli.links << ',' << 3 * (cli.links + 1) << ',' << cli.ratio << ',' << params.step << ','
        << to_string(cli.variant) << ',' << gaps.size() << ',' << gap_max << ',' << worst(&StepRecord::residual_bpp) << ','
        << worst(&StepRecord::residual_refined) << ',' << worst(&StepRecord::residual_ld) << ','
        << worst(&StepRecord::error_bpp) << ',' << worst(&StepRecord::error_refined) << ',' << cond << ',' << omega_max
        << ',' << drift_bound(omega_max, params);
    std::cout << kSummaryHeader << '\n' << row.str() << '\n';
    if (!cli.summary.empty()) {
        std::ofstream summary(cli.summary, std::ios::app);
        if (summary.tellp() == 0) summary << kSummaryHeader << '\n';
        summary << row.str() << '\n';
    }
    return 0;
}
