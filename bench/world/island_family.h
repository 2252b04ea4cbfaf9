// bench/world/island_family.h: worlds made of many copies of one island, of a chosen size, to
// measure what a world step costs per island as islands grow from 1 row to hundreds.
#pragma once

#include <optional>
#include <string>

#include "scenes/scene.h"

namespace ode_bpp::bench {

enum class IslandKind {
    Contact,  ///< a sphere resting on the ground without friction: 1 row
    Marble,   ///< a sphere resting on the ground with friction: 3 rows
    Chain,    ///< the sweeps' HangingChain (sweep_scenes.h) of `size` links, mass ratio 1: 3 (size + 1) rows
    Stack,    ///< the sweeps' BoxStack of `size` light boxes under the heavy one, ratio 1: about 12 (size + 1) rows
};
const char* to_string(IslandKind kind);
std::optional<IslandKind> island_kind_from_string(const std::string& name);

/// The world parameters a kind needs (Contact: mu = 0, so that contacts have no friction rows).
scenes::SceneParams family_params(IslandKind kind, scenes::SceneParams base);

/// Builds `copies` independent islands of the kind (size >= 1 for Chain and Stack, ignored
/// otherwise) into w, apart from each other. The rows of an island are ODE's to count (a stack's
/// contacts come and go): read them from dWorldGetMLCPStats. Throws std::invalid_argument for
/// copies < 1, or size < 1 where it counts.
void build_island_family(scenes::SceneWorld& w, IslandKind kind, int size, int copies);

}  // namespace ode_bpp::bench
