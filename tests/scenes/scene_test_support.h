// Helpers shared by the scene tests that step two worlds side by side.
#pragma once

#include <algorithm>
#include <cmath>

#include "scenes/scene.h"

namespace ode_bpp::scenes {

/// Largest difference [m] of any body's position between two worlds built from the same scene
/// (bodies compared in creation order).
inline double largest_position_difference(const SceneWorld& a, const SceneWorld& b) {
    double worst = 0;
    for (std::size_t k = 0; k < a.bodies().size() && k < b.bodies().size(); ++k) {
        const dReal *pa = dBodyGetPosition(a.bodies()[k]), *pb = dBodyGetPosition(b.bodies()[k]);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, static_cast<double>(std::abs(pa[c] - pb[c])));
    }
    return worst;
}

}  // namespace ode_bpp::scenes
