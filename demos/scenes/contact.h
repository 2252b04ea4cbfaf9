// demos/scenes/contact.h: the contact-rich scenes that ODE's users simulate (a pyramid of boxes,
// a tall stack with a mass gradient, capsules dropped into a bin, a pile of rocks), by name, and
// what their criteria share: bodies that must stay where they were placed.
#pragma once

#include <deque>
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

/// The mean speed of a pile's bodies averaged over the steps of its last second. A settling pile
/// still slips now and then. At one instant, the bin's mean speed at 5 s was 0.007-0.037 m/s
/// across bpp, bpp-sky, bpp-chol and Dantzig, all of which answer its MLCPs exactly, and 0.067
/// after a change in bpp's rounding alone. The last step decided whether a slip was under way
/// (docs/modelling.md, "Criteria that survive rounding").
class SettlingSpeed {
public:
    /// From the scene's control(w, t) at every step: the bodies' mean speed at time t.
    void observe(const std::vector<dBodyID>& bodies, double t);
    /// The average over the observations of the last second, or the bodies' mean speed now when
    /// nothing was observed (a runner that never calls control).
    double value(const std::vector<dBodyID>& bodies) const;

private:
    std::deque<std::pair<double, double>> last_second_;  ///< (t, mean speed), oldest first
};

/// The criterion of a pile of `bodies` (named `what` in the detail) dropped into the bin of
/// add_bin(centre, inner, ...): settled, their mean speed over the last second below 0.05 m/s
/// (at rest, though one may still roll or slip) and none faster than 1 m/s at the end (none
/// thrown about); contained, every centre inside the bin's rectangle, above the ground and below
/// the walls' top.
SuccessReport judge_pile(const std::vector<dBodyID>& bodies, const SettlingSpeed& settling, const char* what,
                         Vec3 centre, Vec3 inner);

/// Turns a body about its centre `at` by a random angle in [-max_angle, max_angle) [rad] about
/// each world axis in turn.
void turn_at_random(dBodyID body, Vec3 at, double max_angle, SceneRandom& random);

}  // namespace ode_bpp::scenes
