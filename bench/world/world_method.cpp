// bench/world/world_method.cpp: parsing and applying a world-stepping method.
#include "world_method.h"

#include <ode/mlcp.h>

#include <cctype>
#include <stdexcept>

namespace ode_bpp::bench {

namespace {

constexpr const char* kQuickStepPrefix = "quickstep-";

bool all_digits(const std::string& text) {
    if (text.empty()) return false;
    for (char c : text)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    return true;
}

}  // namespace

std::optional<WorldMethod> parse_world_method(const std::string& name) {
    WorldMethod m;
    m.name = name;
    if (name.rfind(kQuickStepPrefix, 0) != 0) {
        m.solver = name;
        return m;
    }
    const std::string rest = name.substr(std::string(kQuickStepPrefix).size());
    if (rest.empty()) return std::nullopt;
    m.quickstep = true;
    m.solver = "dantzig";
    if (!all_digits(rest)) {
        m.route = rest;
        return m;
    }
    if (rest.size() > 6 || std::stoi(rest) < 1) return std::nullopt;
    m.iterations = std::stoi(rest);
    return m;
}

scenes::SceneParams params_for(const WorldMethod& method, scenes::SceneParams base) {
    base.solver = method.solver;
    base.stepper = method.quickstep ? "quickstep" : "step";
    return base;
}

void configure_world(const WorldMethod& method, scenes::SceneWorld& world) {
    if (!method.quickstep) return;
    if (!method.route.empty()) {
        if (dWorldSetQuickStepMLCPSolver(world.world(), method.route.c_str()) == 0)
            throw std::invalid_argument("unknown MLCP solver '" + method.route + "' to route QuickStep to");
        return;
    }
    dWorldSetQuickStepNumIterations(world.world(), method.iterations);
}

}  // namespace ode_bpp::bench
