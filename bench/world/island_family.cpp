// bench/world/island_family.cpp
#include "island_family.h"

#include <cmath>
#include <stdexcept>

#include "scenes/build_helpers.h"
#include "scenes/sweep_scenes.h"

namespace ode_bpp::bench {

namespace {

constexpr double kPitch = 3.0;          // [m] between neighbouring copies (stacks: 0.5 m boxes)
constexpr double kSphereRadius = 0.1;   // [m]
constexpr double kSphereMass = 1.0;     // [kg]

struct Named {
    IslandKind kind;
    const char* name;
};
constexpr Named kNames[] = {{IslandKind::Contact, "contact"},
                            {IslandKind::Marble, "marble"},
                            {IslandKind::Chain, "chain"},
                            {IslandKind::Stack, "stack"}};

/// Grid position of copy k: a square grid kPitch apart.
scenes::Vec3 grid_position(int k, int copies) {
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(copies))));
    return {(k % side) * kPitch, (k / side) * kPitch, 0};
}

void add_resting_sphere(scenes::SceneWorld& w, scenes::Vec3 at) {
    dBodyID b = scenes::add_body(w, scenes::sphere_mass(kSphereMass, kSphereRadius), at + scenes::Vec3{0, 0, kSphereRadius});
    scenes::add_sphere(w, b, kSphereRadius);
}

/// Moves the bodies w created from index `first` on by `offset` (their geoms follow).
void translate_new_bodies(scenes::SceneWorld& w, std::size_t first, scenes::Vec3 offset) {
    for (std::size_t k = first; k < w.bodies().size(); ++k) {
        const scenes::Vec3 p = scenes::position(w.bodies()[k]) + offset;
        dBodySetPosition(w.bodies()[k], p.x, p.y, p.z);
    }
}

}  // namespace

const char* to_string(IslandKind kind) {
    for (const Named& n : kNames)
        if (n.kind == kind) return n.name;
    return "?";
}

std::optional<IslandKind> island_kind_from_string(const std::string& name) {
    for (const Named& n : kNames)
        if (name == n.name) return n.kind;
    return std::nullopt;
}

scenes::SceneParams family_params(IslandKind kind, scenes::SceneParams base) {
    if (kind == IslandKind::Contact) base.mu = 0;
    return base;
}

void build_island_family(scenes::SceneWorld& w, IslandKind kind, int size, int copies) {
    if (copies < 1) throw std::invalid_argument("island family: copies must be >= 1");
    const bool sized = kind == IslandKind::Chain || kind == IslandKind::Stack;
    if (sized && size < 1) throw std::invalid_argument("island family: size must be >= 1");
    for (int k = 0; k < copies; ++k) {
        const scenes::Vec3 at = grid_position(k, copies);
        switch (kind) {
        case IslandKind::Contact:
        case IslandKind::Marble: add_resting_sphere(w, at); break;
        case IslandKind::Chain:
            // hung from one anchor point: the chains have no geoms, so copies never touch
            scenes::build_sweep_scene(w, {scenes::SweepPattern::HangingChain, 1, size});
            break;
        case IslandKind::Stack: {
            const std::size_t first = w.bodies().size();
            scenes::build_sweep_scene(w, {scenes::SweepPattern::BoxStack, 1, size});
            translate_new_bodies(w, first, at);
            break;
        }
        }
    }
}

}  // namespace ode_bpp::bench
