// libode_bpp_run.so, what ode-bpp-run preloads in front of libode_bpp.so (docs/launcher.md):
// the program's calls of dWorldStep and dWorldQuickStep bind to these definitions, which tell the
// summary (ode/summary.h) about the step and pass it on unchanged to libode's own (dlsym
// RTLD_NEXT: the next definition in lookup order). Not reached by a libode loaded with dlopen and
// called through dlsym on its handle, as Python's ctypes does; the summary then has no count of
// unrouted quick steps, and SIGINT's handler stays as libode_bpp installed it at load.
//
// Only a preload: a library that defines dWorldStep would be kept by --as-needed in every program
// linked with it, and would stand between every such program and its libode.
#include <ode/mlcp.h>
#include <ode/ode.h>

#include <dlfcn.h>

#include <atomic>
#include <cstdio>

#include "ode/summary.h"

namespace {

using StepFunction = int(dWorldID, dReal);

/// libode's definition of `name`, looked up once; nullptr if there is none after us.
StepFunction* next_definition(const char* name, std::atomic<StepFunction*>& cache) {
    StepFunction* fn = cache.load(std::memory_order_acquire);
    if (fn == nullptr) {
        fn = reinterpret_cast<StepFunction*>(dlsym(RTLD_NEXT, name));
        if (fn == nullptr) std::fprintf(stderr, "ode-bpp: no %s after libode_bpp in the lookup order\n", name);
        cache.store(fn, std::memory_order_release);
    }
    return fn;
}

std::atomic<StepFunction*> g_step{nullptr};
std::atomic<StepFunction*> g_quick_step{nullptr};

[[maybe_unused]] const bool g_sigint_deferred = [] {
    ode_bpp::summary::arm_sigint_at_first_step();
    return true;
}();

}  // namespace

extern "C" int dWorldStep(dWorldID w, dReal stepsize) {
    ode_bpp::summary::note_world_step();
    StepFunction* next = next_definition("dWorldStep", g_step);
    return next != nullptr ? next(w, stepsize) : 0;
}

extern "C" int dWorldQuickStep(dWorldID w, dReal stepsize) {
    ode_bpp::summary::note_world_step();
    // routed quick steps are counted by ODE as world steps of their MLCP solver
    if (w != nullptr && dWorldGetQuickStepMLCPSolver(w) == nullptr) ode_bpp::summary::count_unrouted_quickstep();
    StepFunction* next = next_definition("dWorldQuickStep", g_quick_step);
    return next != nullptr ? next(w, stepsize) : 0;
}
