// The ODE glue: ode-bpp's solvers registered with the patched world step (<ode/mlcp.h>).
//
// Index space: ODE's island row order (original) throughout; the solver permutes inside.
// ODE's interleaved arrays are used in place: b = pairsbx[2i], x = pairsbx[2i+1],
// lo = pairslh[2i], hi = pairslh[2i+1]. The solvers register in the sparse form: ODE hands over
// J, J M^-1 and the CFM and never forms its dense A; A is assembled into compressed rows in
// O(entries) (ode/assemble.h). A dense A (an ODE without the sparse form) is read in place.
//
// An island whose A or whose factor would pass Options::max_factor_entries, as its joints tell
// (ode/oversize.h), is not assembled: projected Gauss-Seidel sweeps J and J M^-1 instead
// (ode/jacobian_pgs.h), fallback "pgs".
//
// Fallback chain of one island (reported in dMLCPIslandStats::fallback):
//   1. the solver's own chain (regularize and retry, then ODE's Dantzig: Status::FallbackUsed);
//   2. a result that is not usable (max iterations, not SPD, invalid input): we return
//      dMLCPFailed without touching A, b, lo, hi, and the world step answers with ODE's Dantzig.
#include "ode_bpp/ode.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>
#include <utility>

#include "linalg/symmetric_rows.h"
#include "ode/island_view.h"
#include "ode/jacobian_pgs.h"
#include "ode/ordering_cache.h"
#include "ode/oversize.h"
#include "ode/row_identity.h"
#include "ordering/ordering_choice.h"
#include "pivoting/bpp_driver.h"
#include "pivoting/small_island.h"

namespace ode_bpp {
namespace {

/// The settings of a world that set_world_settings never reached (ode.h): the defaults, but no
/// record of |T| per pivot step, which would cost every island an allocation for a Result the
/// hook keeps only as last_island_result.
WorldSettings hook_default_settings() {
    WorldSettings s;
    s.options.record_steps = false;
    return s;
}

struct WorldState {
    WorldSettings settings = hook_default_settings();
    RowStateMemory memory;       // index sets of the previous steps, by row identity
    OrderingCache orderings;     // row orderings of the previous steps, by island structure
    Result last;
    bool failure_reported = false;  // report_failure has spoken for this world
};

struct HookState {
    std::mutex lock;
    std::unordered_map<dWorldID, WorldState> worlds;
};

HookState& hook() {
    static HookState* state = new HookState();  // never destroyed: ODE may step during exit
    return *state;
}

/// ODE's name and our Method of every solver we register: every method of solver.h but dantzig,
/// which ODE registers itself. Userdata of the registrations points at `method` (never moves).
struct Registration {
    std::string name;
    Method method;
};

const std::vector<Registration>& registrations() {
    static const std::vector<Registration>* table = [] {
        auto* t = new std::vector<Registration>();  // never destroyed: ODE may step during exit
        for (const std::string& name : method_names()) {
            const Method m = *method_from_string(name);
            if (m != Method::Dantzig) t->push_back({name, m});
        }
        return t;
    }();
    return *table;
}

/// True when some row can be tight (bounded, or a friction row): only then does an index set of
/// an earlier step say anything about this one. A chain of ball joints has none; its rows are
/// free at every step, so its islands skip the row memory (two hash lookups per row).
bool has_bounded_rows(const dMLCP& p) {
    for (int i = p.nub; i < p.m; ++i) {
        if (p.findex != nullptr && p.findex[i] >= 0) return true;
        if (p.pairslh[2 * i] > -dInfinity || p.pairslh[2 * i + 1] < dInfinity) return true;
    }
    return false;
}

/// The rows' identities serve the warm-start memory (islands with a row that can be tight) and
/// the ordering cache (islands past the small-island path). The path's bound is read from the
/// default Tuning here, before the world's settings are: a world that raised it computes keys it
/// does not use, one that lowered it leaves its unbounded islands between the two bounds to a
/// fresh ordering at every step (time only, the answers are the same).
bool wants_row_keys(const dMLCP& p, bool bounded) {
    return p.joints != nullptr && (bounded || p.m > Tuning{}.dense_island_rows);
}

dMLCPStatus to_ode_status(const Result& r) {
    // an iterative method's answer after its fixed sweep count is its answer, as in quickstep
    if (r.method == Method::Pgs && r.status == Status::MaxIterations) return dMLCPSolved;
    switch (r.status) {
        case Status::Converged: return dMLCPSolved;
        case Status::FallbackUsed:
        case Status::FrictionNotConsistent: return dMLCPSolvedByFallback;
        default: return dMLCPFailed;
    }
}

const char* fallback_name(const Result& r) {
    if (r.status == Status::FrictionNotConsistent) return "friction-not-consistent";
    return r.fallback == Fallback::None ? nullptr : to_string(r.fallback);
}

/// What the hook works in besides the solver's Workspace, reused from island to island.
struct IslandScratch {
    std::vector<RowKey> keys;
    std::vector<ContactSlot> contacts;
    RowStateMemory::Slots slots;  ///< where recall found the island's joints, for remember
    OrderingCache::Signature structure;
    ode::IslandView view;
    Start start;
    Workspace workspace;
    std::vector<std::int64_t> rows_on_body;  ///< ode::oversize's scratch
    ode::JacobianPgsBuffers jacobian_pgs;
    linalg::SymmetricRows dense_rows;  ///< a dense-form island's A, where ordering_priced_either_way reads it
};

/// The hook's memory on the calling thread: ODE may step islands on several threads at once,
/// each solves one island at a time (one solve per workspace).
IslandScratch& thread_scratch() {
    thread_local IslandScratch scratch;
    return scratch;
}

/// What an island's solve takes from its world's state, read under the hook's lock.
struct IslandPlan {
    Options options;
    bool small = false;     ///< pivoting::is_small_island: no ordering is looked up or kept
    bool recalled = false;  ///< the warm-start memory was asked (scratch.slots says where)
    bool warm = false;      ///< and it knew the island: scratch.start.states holds its index set
    bool ordering_remembered = false;  ///< scratch.start.ordering came from the ordering cache
    bool settled_ordering = true;  ///< the solve orders as the world's settings ask (OrderingCache::Remembered)
};

/// The world's options for `method`, the island's warm start (by row identity, when some row can
/// be tight) and its remembered ordering (by structure), into scratch.start.
IslandPlan plan_island(const dMLCP& problem, Method method, bool known_rows, bool use_memory, IslandScratch& scratch) {
    Start& start = scratch.start;
    start.ordering.clear();
    std::lock_guard<std::mutex> g(hook().lock);
    IslandPlan plan;
    WorldState& ws = hook().worlds[problem.world];
    plan.options = ws.settings.options;
    plan.options.method = method;
    plan.small = pivoting::is_small_island(problem.m, plan.options);
    if (ws.settings.warm_start && use_memory) {
        plan.warm = ws.memory.recall(scratch.keys, problem.step, start.states, &scratch.slots);
        plan.recalled = true;
    }
    if (known_rows && !plan.small) {
        OrderingCache::signature(problem, scratch.keys.front(), scratch.structure);
        const OrderingCache::Remembered* known = ws.orderings.find(scratch.structure, problem.step);
        if (known != nullptr && known->settled) {
            start.ordering = known->ordering;
            plan.ordering_remembered = true;
        }
        // a structure met for the first time is ordered unpriced, and priced when it returns
        bool& prices = plan.options.tuning.price_tight_last_orderings;
        plan.settled_ordering = known != nullptr || !prices;
        prices = prices && known != nullptr;
    }
    if (!plan.warm) start.states.clear();
    return plan;
}

/// The answer's index set and ordering kept for the next step; r becomes the world's last result,
/// and r is left holding the previous last result's index set (its storage, for recycling).
void keep_island(const dMLCP& problem, const IslandPlan& plan, bool known_rows, bool use_memory, bool usable,
                 IslandScratch& scratch, Result& r) {
    std::lock_guard<std::mutex> g(hook().lock);
    WorldState& ws = hook().worlds[problem.world];  // looked up again: forget_world may have run meanwhile
    if (use_memory && usable)
        ws.memory.remember(scratch.keys, problem.step, r.states, plan.recalled ? &scratch.slots : nullptr);
    if (known_rows && !plan.small && !r.ordering.empty() &&
        (!plan.ordering_remembered || r.ordering != scratch.start.ordering))
        ws.orderings.store(scratch.structure, r.ordering, plan.settled_ordering, problem.step);
    std::vector<RowState> previous = std::move(ws.last.states);
    ws.last = std::move(r);  // no copy of its vectors per island
    r.states = std::move(previous);
}

/// True for a world's first island handed back to ODE unsolved, false for every later one.
bool first_failure_of(dWorldID world) {
    std::lock_guard<std::mutex> g(hook().lock);
    return !std::exchange(hook().worlds[world].failure_reported, true);
}

/// An island handed back to ODE unsolved means the program's model is at fault (a NaN contact,
/// a negative CFM: docs/ode-world-step.md) or ode-bpp is, which the statistics alone would keep
/// quiet. The first one of a world says so through ODE's message handler (dSetMessageHandler), as
/// ODE's Dantzig reports its own failures; the later ones are counted in dWorldGetMLCPStats only.
void report_failure(const dMLCP& problem, Method method, const char* status, const char* why) {
    if (!first_failure_of(problem.world)) return;
    dMessage(d_ERR_LCP,
             "ode-bpp: %s could not solve an island of %d rows (%s: %s); the world step's fallbacks answer it. "
             "Later failures in this world are counted (dWorldGetMLCPStats), not printed",
             to_string(method), problem.m, status, why);
}

/// True when the solver orders q alike with the pricing of Tuning::price_tight_last_orderings
/// and without: an island too small for an ordering keeps the caller's order, priced either way
/// (ordering::ordering_cannot_pay). A dense-form island's A is read into rows for the test, as the
/// solver reads it, so that both forms keep the same orderings.
bool ordering_priced_either_way(const Problem& q, linalg::SymmetricRows& rows) {
    if (q.sparse != nullptr) return ordering::ordering_cannot_pay(*q.sparse);
    rows.assign(q, {});
    return ordering::ordering_cannot_pay(rows);
}

/// The island's answer, x written in place into pairsbx[2i+1] (A, b, lo, hi only read). An
/// island whose A or factor would pass the limit (ode::oversize, counted in
/// scratch.start.ordering, the remembered order, or else in the one it sets there for the solve)
/// is answered without forming A (ode/jacobian_pgs.h); any other by solve().
Result answer_of(const dMLCP& island, IslandPlan& plan, IslandScratch& scratch) {
    const Strided x{island.pairsbx + 1, 2};
    if (!plan.small && pivoting::factor_may_be_too_large(island.m, plan.options)) {
        const Problem rows = scratch.view.rows_of(island);
        const ode::Oversize oversize =
            ode::oversize(island, rows, plan.options, scratch.start.ordering, scratch.rows_on_body);
        if (oversize) return ode::solve_by_jacobian_pgs(island, rows, plan.options, oversize, x, scratch.jacobian_pgs);
    }
    const Problem q = scratch.view.of(island, plan.small, scratch.start.ordering);
    if (!plan.settled_ordering && ordering_priced_either_way(q, scratch.dense_rows)) plan.settled_ordering = true;
    return solve(q, plan.options, x, scratch.start, scratch.workspace);
}

dMLCPStatus answer_island(const dMLCP* problem, dMLCPIslandStats* stats, void* userdata) {
    const Method method = *static_cast<const Method*>(userdata);
    IslandScratch& scratch = thread_scratch();
    const bool bounded = has_bounded_rows(*problem);
    const bool keyed = wants_row_keys(*problem, bounded);
    if (keyed) row_keys(*problem, scratch.keys, scratch.contacts);
    const bool known_rows = keyed && !scratch.keys.empty();
    const bool use_memory = known_rows && bounded;
    IslandPlan plan = plan_island(*problem, method, known_rows, use_memory, scratch);
    Result r = answer_of(*problem, plan, scratch);
    const dMLCPStatus status = to_ode_status(r);
    stats->pivots = r.pivoting.pivots;
    stats->tight = r.tight;
    stats->fallbacks = r.fallback == Fallback::None ? 0 : 1;
    stats->fallback = fallback_name(r);
    if (status == dMLCPFailed) report_failure(*problem, method, to_string(r.status), r.message.c_str());
    keep_island(*problem, plan, known_rows, use_memory, status != dMLCPFailed, scratch, r);
    scratch.workspace.recycle(std::move(r));  // the world's previous last result
    return status;
}

/// ODE's C code calls this: no exception may cross it. Memory that runs out (an island whose A
/// alone outgrows it, docs/modelling.md) fails the island, which ODE then gives to its Dantzig,
/// or, where that has no memory for its dense A either, answers with x = 0; x is not read then.
dMLCPStatus solve_island(const dMLCP* problem, dMLCPIslandStats* stats, void* userdata) {
    try {
        return answer_island(problem, stats, userdata);
    } catch (const std::bad_alloc&) {
        stats->fallback = "out of memory";
    } catch (const std::exception& e) {
        stats->fallback = "internal error";
        report_failure(*problem, *static_cast<const Method*>(userdata), "internal error", e.what());
    }
    stats->fallbacks = 1;
    return dMLCPFailed;
}

/// A world's settings, warm-start memory and orderings end with it: a world created later may
/// get the same address, and must not inherit them.
void on_world_destroyed(dWorldID world, void*) { forget_world(world); }

int register_all() {
    int registered = 0;
    for (const Registration& r : registrations())
        registered += dRegisterMLCPSolverEx(r.name.c_str(), &solve_island, const_cast<Method*>(&r.method),
                                            dMLCP_API_VERSION, dMLCP_SPARSE);
    dAddMLCPWorldDestroyedListener(&on_world_destroyed, nullptr);  // 0 when already added: fine
    return registered;
}

// Registration when the library loads, so that linking (or preloading) is enough.
[[maybe_unused]] const int g_registered_at_load = register_all();

}  // namespace

void set_world_settings(dWorldID world, const WorldSettings& settings) {
    std::lock_guard<std::mutex> g(hook().lock);
    hook().worlds[world].settings = settings;
}

WorldSettings world_settings(dWorldID world) {
    std::lock_guard<std::mutex> g(hook().lock);
    auto it = hook().worlds.find(world);
    return it != hook().worlds.end() ? it->second.settings : hook_default_settings();
}

Result last_island_result(dWorldID world) {
    std::lock_guard<std::mutex> g(hook().lock);
    auto it = hook().worlds.find(world);
    return it != hook().worlds.end() ? it->second.last : Result{};
}

Start last_island_start() { return thread_scratch().start; }

void forget_world(dWorldID world) {
    std::lock_guard<std::mutex> g(hook().lock);
    hook().worlds.erase(world);
}


}  // namespace ode_bpp

extern "C" int ode_bpp_register_solvers(void) { return ode_bpp::register_all(); }

extern "C" int ode_bpp_register_dense_form(const char* method, const char* as_name) {
    if (method == nullptr || as_name == nullptr) return 0;
    for (const ode_bpp::Registration& r : ode_bpp::registrations())
        if (r.name == method)
            return dRegisterMLCPSolverEx(as_name, &ode_bpp::solve_island, const_cast<ode_bpp::Method*>(&r.method),
                                         dMLCP_API_VERSION, 0);
    return 0;
}

extern "C" int ode_bpp_use(dWorldID world, const char* solver_name) {
    ode_bpp::register_all();
    return dWorldSetMLCPSolver(world, solver_name);
}
