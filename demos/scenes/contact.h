// demos/scenes/contact.h: the contact-rich scenes that ODE's users simulate (a pyramid of boxes,
// a tall stack with a mass gradient, capsules dropped into a bin, a pile of rocks), by name, and
// what their criteria share: bodies that must stay where they were placed.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scenes/build_helpers.h"
#include "scenes/classic.h"

namespace ode_bpp::scenes {

/// The contact-rich scenes by name: pyramid, stack, bin, rockpile.
std::vector<std::pair<std::string, SceneFactory>> contact_scenes();

/// A body and where it was placed.
struct PlacedBody {
    dBodyID body = nullptr;
    Vec3 rest;
};

/// A cube of side `edge` and `mass` centred at `at`, axes along the world's.
PlacedBody add_cube(SceneWorld& w, double mass, double edge, Vec3 at);

/// The criterion of boxes built into a standing structure: every box within 5 % of `edge` of
/// where it was placed and upright within about 3 degrees.
SuccessReport judge_standing(const std::vector<PlacedBody>& boxes, double edge);

/// The criterion of a pile of `bodies` (named `what` in the detail) dropped into the bin of
/// add_bin(centre, inner, ...): settled, their mean speed below 0.05 m/s (at rest, though one may
/// still roll or slip) and none faster than 1 m/s (none thrown about); contained, every centre
/// inside the bin's rectangle, above the ground and below the walls' top.
SuccessReport judge_pile(const std::vector<dBodyID>& bodies, const char* what, Vec3 centre, Vec3 inner);

/// Turns a body about its centre `at` by a random angle in [-max_angle, max_angle) [rad] about
/// each world axis in turn.
void turn_at_random(dBodyID body, Vec3 at, double max_angle, SceneRandom& random);

}  // namespace ode_bpp::scenes
