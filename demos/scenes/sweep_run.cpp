// demos/scenes/sweep_run.cpp: run one sweep scene with one method, measure and classify it.
#include "scenes/sweep_run.h"

#include <ode/mlcp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "ode_bpp/ode.h"

namespace ode_bpp::scenes {

namespace {

constexpr double kContactSurfaceLayer = 0.001;  // [m] SceneWorld's, part of tau
constexpr double kLinkFraction = 0.02;          // tau's geometric part: 2 % of a link
constexpr double kComplianceFactor = 2;         // tau's elastic part: twice the static yield
// Exploded: the energy gained exceeds the reference g * sum(m) * height (everything lifted by
// the scene's own height); nothing in the sweep scenes drives the bodies, so a sound step can
// only lose energy (ERP and friction) apart from CFM's spring energy, which is far smaller.
constexpr double kExplodedEnergyGain = 1.0;

// Relative friction-cone excess above which a consistent-mode answer is not consistent: well
// above the solver's relative tolerance (1e-9), far below a real violation.
constexpr double kFrictionExcess = 1e-6;

std::atomic<int> g_lcp_internal_errors{0};

/// ODE's message handler while a run is on: counts Dantzig's "LCP internal error" and stays
/// quiet (the run reports the count; the sweep would otherwise flood the terminal).
void count_message(int errnum, const char* msg, va_list ap) {
    (void)errnum;
    char text[256];
    std::vsnprintf(text, sizeof text, msg, ap);
    if (std::strstr(text, "LCP internal error") != nullptr) ++g_lcp_internal_errors;
}

/// Installs count_message for the scope and restores the previous handler.
class MessageCounter {
public:
    MessageCounter() : previous_(dGetMessageHandler()) {
        g_lcp_internal_errors = 0;
        dSetMessageHandler(&count_message);
    }
    ~MessageCounter() { dSetMessageHandler(previous_); }
    MessageCounter(const MessageCounter&) = delete;
    MessageCounter& operator=(const MessageCounter&) = delete;
    int count() const { return g_lcp_internal_errors; }

private:
    dMessageFunction* previous_;
};

bool is_ode_bpp_method(const std::string& m) { return m != "dantzig" && m != "quickstep"; }

struct IslandCounts {
    bool ode_bpp = false;
    RunResult* out = nullptr;
};

/// Friction-cone excess of the answer (see RunResult::friction_excess), from ODE's arrays:
/// x_i = pairsbx[2i+1], and a friction row's hi_i = pairslh[2i+1] holds its mu.
double relative_friction_excess(const dMLCP& p) {
    if (p.findex == nullptr) return 0;
    double excess = 0, largest = 0;
    for (int i = 0; i < p.m; ++i) largest = std::max(largest, std::fabs(p.pairsbx[2 * i + 1]));
    for (int i = 0; i < p.m; ++i) {
        const int normal = p.findex[i];
        if (normal < 0) continue;
        const double cone = std::fabs(p.pairslh[2 * i + 1] * p.pairsbx[2 * normal + 1]);
        excess = std::max(excess, std::fabs(p.pairsbx[2 * i + 1]) - cone);
    }
    return largest > 0 ? excess / largest : 0;
}

/// MLCP observer (after each island's solve): the solver's status and the hook's Result.
void observe_island(const dMLCP* problem, const dMLCPIslandStats* stats, void* userdata) {
    if (stats == nullptr) return;  // the call before the solve
    auto* c = static_cast<IslandCounts*>(userdata);
    RunResult& r = *c->out;
    ++r.islands;
    r.pivots += stats->pivots;
    if (stats->status == dMLCPFailed) ++r.failures;
    else if (stats->status == dMLCPSolvedByFallback) ++r.fallbacks;
    if (!c->ode_bpp) return;
    // ODE's Dantzig rewrites lo and hi in place, so the cone is read only from ode-bpp's answers
    const double excess = stats->status == dMLCPFailed ? 0 : relative_friction_excess(*problem);
    r.friction_excess = std::max(r.friction_excess, excess);
    const Result last = last_island_result(problem->world);
    r.max_iterations += last.status == Status::MaxIterations && last.method != Method::Pgs ? 1 : 0;
    r.not_spd += last.status == Status::NotSpd ? 1 : 0;
    r.regularized += last.fallback == Fallback::Regularized || last.fallback == Fallback::RegularizedDantzig ? 1 : 0;
    r.friction_not_consistent += last.status == Status::FrictionNotConsistent ? 1 : 0;
    r.murty_pivots += last.pivoting.murty_pivots;
    r.rescues += last.pivoting.rescues;
    r.friction_rounds += last.pivoting.friction_rounds;
    const bool flagged = last.status == Status::FrictionNotConsistent;
    r.friction_unflagged += last.friction == FrictionMode::Consistent && !flagged && excess > kFrictionExcess ? 1 : 0;
}

/// Kinetic (translation + rotation) plus potential energy of the world's bodies [J].
double total_energy(const SceneWorld& w) {
    double e = 0;
    for (dBodyID b : w.bodies()) {
        dMass m;
        dBodyGetMass(b, &m);
        const dReal* v = dBodyGetLinearVel(b);
        const dReal* omega = dBodyGetAngularVel(b);
        const dReal* R = dBodyGetRotation(b);
        dVector3 wb;  // body-frame angular velocity R^T omega: m.I is in the body frame
        dMultiply1_331(wb, R, omega);
        double rot = 0;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) rot += wb[i] * m.I[4 * i + j] * wb[j];
        }
        e += 0.5 * m.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + 0.5 * rot +
             m.mass * w.params().gravity * dBodyGetPosition(b)[2];
    }
    return e;
}

double energy_reference(const SceneWorld& w, const SweepLayout& l) {
    double mass = 0;
    for (dBodyID b : w.bodies()) {
        dMass m;
        dBodyGetMass(b, &m);
        mass += m.mass;
    }
    return w.params().gravity * mass * std::max(l.height, l.link_length);
}

struct DepthProbe {
    double deepest = 0;
};

/// Near callback of a measuring collision pass: the deepest contact, no joints created.
void probe_pair(void* data, dGeomID a, dGeomID b) {
    dBodyID ba = dGeomGetBody(a), bb = dGeomGetBody(b);
    if (ba == bb) return;
    if (ba && bb && dAreConnectedExcluding(ba, bb, dJointTypeContact)) return;
    dContactGeom contacts[8];
    const int n = dCollide(a, b, 8, contacts, sizeof(dContactGeom));
    auto* probe = static_cast<DepthProbe*>(data);
    for (int i = 0; i < n; ++i) probe->deepest = std::max(probe->deepest, static_cast<double>(contacts[i].depth));
}

double deepest_contact(const SceneWorld& w) {
    DepthProbe probe;
    dSpaceCollide(w.space(), &probe, &probe_pair);
    return probe.deepest;
}

/// How far the placement's distance lies outside its interval widened by the compliance [m].
double placement_excursion(const PlacementCheck& c, double tolerance) {
    const Vec3 from = c.from != nullptr ? world_point(c.from, c.from_local) : c.from_local;
    const double d = norm(position(c.body) - from);
    const double slack = c.compliant_in_series * tolerance;
    return std::max({0.0, (c.min_distance - slack) - d, d - (c.max_distance + slack)});
}

bool finite_state(const SceneWorld& w) {
    for (dBodyID b : w.bodies()) {
        for (const dReal* v : {dBodyGetPosition(b), dBodyGetLinearVel(b), dBodyGetAngularVel(b)}) {
            if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) return false;
        }
    }
    return true;
}

std::string format_cause(const char* what, double value, double limit) {
    std::ostringstream s;
    s.precision(3);
    s << what << ' ' << value << " > " << limit;
    return s.str();
}

std::string solver_cause(const RunResult& r) {
    std::ostringstream s;
    const char* sep = "";
    auto add = [&](int count, const char* what) {
        if (count > 0) {
            s << sep << what << " x" << count;
            sep = "; ";
        }
    };
    add(r.lcp_internal_errors, "LCP internal error");
    add(r.max_iterations, "max-iterations");
    add(r.not_spd, "not-spd");
    add(r.friction_not_consistent, "friction-not-consistent");
    add(r.regularized, "regularized");
    add(r.failures, "answered by ODE's Dantzig");
    add(r.fallbacks - r.regularized - r.friction_not_consistent, "other fallback");
    return s.str();
}

/// Exploded > drifted > solver error > held: the first physical failure decides.
void classify(RunResult& r, bool finite) {
    if (!finite) {
        r.outcome = Outcome::Exploded;
        r.cause = "non-finite state at step " + std::to_string(r.steps);
    } else if (r.energy_drift > kExplodedEnergyGain) {
        r.outcome = Outcome::Exploded;
        r.cause = format_cause("energy gain", r.energy_drift, kExplodedEnergyGain);
    } else if (r.max_joint_error > r.tolerance) {
        r.outcome = Outcome::Drifted;
        r.cause = format_cause("joint error [m]", r.max_joint_error, r.tolerance);
    } else if (r.max_penetration > r.tolerance) {
        r.outcome = Outcome::Drifted;
        r.cause = format_cause("penetration [m]", r.max_penetration, r.tolerance);
    } else if (r.worst_placement > 0) {
        r.outcome = Outcome::Drifted;
        r.cause = format_cause("placement off by [m]", r.worst_placement, 0);
    } else if (r.lcp_internal_errors + r.failures + r.fallbacks > 0) {
        r.outcome = Outcome::SolverError;
        r.cause = solver_cause(r);
    } else {
        r.outcome = Outcome::Held;
        r.cause.clear();
    }
}

SceneParams params_of(const RunSpec& spec) {
    SceneParams p;
    p.step = spec.step;
    p.seconds = spec.seconds;
    p.mu = spec.mu;
    p.cfm = spec.cfm;
    p.erp = spec.erp;
    p.solver = spec.method == "quickstep" ? "dantzig" : spec.method;
    p.stepper = spec.method == "quickstep" ? "quickstep" : "step";
    return p;
}

/// The method's settings: quickstep's iterations, or the ode-bpp hook's per-world options.
void configure_solver(SceneWorld& w, const RunSpec& spec) {
    if (spec.method == "quickstep") dWorldSetQuickStepNumIterations(w.world(), spec.iterations);
    WorldSettings settings;
    settings.options = spec.options;
    settings.options.record_steps = false;  // as the hook's own defaults: no one here reads |T| per step
    settings.options.pgs_iterations = spec.iterations;
    settings.warm_start = spec.warm_start;
    set_world_settings(w.world(), settings);
}

struct EnergyBaseline {
    double start;      ///< total energy before the first step [J]
    double reference;  ///< g * (sum of masses) * scene height [J]
};

/// Updates the run's maxima after one finite step (an energy gain beyond kExplodedEnergyGain
/// ends the run: there is no need to watch it fly away).
void measure_step(const SceneWorld& w, const SweepLayout& layout, const EnergyBaseline& energy, RunResult& r) {
    r.max_joint_error = std::max(r.max_joint_error, w.max_joint_error());
    r.max_penetration = std::max(r.max_penetration, deepest_contact(w));
    for (const PlacementCheck& c : layout.placements) {
        r.worst_placement = std::max(r.worst_placement, placement_excursion(c, r.tolerance));
    }
    r.energy_drift = std::max(r.energy_drift, (total_energy(w) - energy.start) / energy.reference);
}

}  // namespace

const char* to_string(Outcome o) {
    switch (o) {
        case Outcome::Held: return "held";
        case Outcome::Drifted: return "drifted";
        case Outcome::Exploded: return "exploded";
        case Outcome::SolverError: return "solver-error";
    }
    return "?";
}

std::vector<std::string> sweep_methods() {
    return {"dantzig", "bpp", "bpp-sky", "bpp-down", "bpp-chol", "pgs", "quickstep"};
}

RunResult run_sweep(const RunSpec& spec) {
    const auto t0 = std::chrono::steady_clock::now();
    SceneWorld w(params_of(spec));  // throws for an unknown solver name
    configure_solver(w, spec);
    const SweepLayout layout = build_sweep_scene(w, spec.scene);
    RunResult r;
    r.tolerance = kLinkFraction * layout.link_length + kContactSurfaceLayer +
                  kComplianceFactor * layout.carried_weight * spec.step * spec.cfm / spec.erp;
    IslandCounts counts{is_ode_bpp_method(spec.method), &r};
    dWorldSetMLCPObserver(w.world(), &observe_island, &counts);
    MessageCounter messages;

    const EnergyBaseline energy{total_energy(w), energy_reference(w, layout)};
    const long steps = std::lround(spec.seconds / spec.step);
    bool finite = true;
    for (long k = 0; k < steps && finite && r.energy_drift <= kExplodedEnergyGain; ++k) {
        finite = w.step() && finite_state(w);
        r.steps = k + 1;
        if (finite) measure_step(w, layout, energy, r);
    }
    if (finite && layout.slider != nullptr) r.final_slide = position(layout.slider).x - layout.slide_start_x;
    r.lcp_internal_errors = messages.count();
    dWorldSetMLCPObserver(w.world(), nullptr, nullptr);
    classify(r, finite);
    r.seconds_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace ode_bpp::scenes
