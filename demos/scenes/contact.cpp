#include "scenes/contact.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ode_bpp::scenes {

// Defined one per file in contact_<name>.cpp.
std::unique_ptr<Scene> make_contact_pyramid();
std::unique_ptr<Scene> make_contact_stack();
std::unique_ptr<Scene> make_contact_bin();
std::unique_ptr<Scene> make_contact_rockpile();

std::vector<std::pair<std::string, SceneFactory>> contact_scenes() {
    return {
        {"pyramid", make_contact_pyramid},
        {"stack", make_contact_stack},
        {"bin", make_contact_bin},
        {"rockpile", make_contact_rockpile},
    };
}

namespace {

constexpr double kSettledSpeed = 0.05, kThrownSpeed = 1.0;  // [m/s], judge_pile()
constexpr double kStandingDrift = 0.05, kStandingCosine = 0.9986;  // judge_standing()

}  // namespace

PlacedBody add_cube(SceneWorld& w, double mass, double edge, Vec3 at) {
    dBodyID body = add_body(w, box_mass(mass, {edge, edge, edge}), at);
    add_box(w, body, {edge, edge, edge});
    return {body, at};
}

SuccessReport judge_standing(const std::vector<PlacedBody>& boxes, double edge) {
    double drift = 0, upright = 1;
    for (const PlacedBody& b : boxes) {
        drift = std::max(drift, norm(position(b.body) - b.rest));
        upright = std::min(upright, static_cast<double>(dBodyGetRotation(b.body)[10]));  // body z . world z
    }
    std::ostringstream d;
    d << boxes.size() << " boxes: largest drift " << drift << " m (limit " << kStandingDrift * edge
      << "), smallest up-cosine " << upright << " (limit " << kStandingCosine << ")";
    return {drift < kStandingDrift * edge && upright > kStandingCosine, d.str()};
}

namespace {

double mean_speed(const std::vector<dBodyID>& bodies) {
    double mean = 0;
    for (dBodyID b : bodies) mean += norm(to_vec(dBodyGetLinearVel(b))) / static_cast<double>(bodies.size());
    return mean;
}

}  // namespace

void SettlingSpeed::observe(const std::vector<dBodyID>& bodies, double t) {
    last_second_.emplace_back(t, mean_speed(bodies));
    while (last_second_.front().first < t - 1.0) last_second_.pop_front();
}

double SettlingSpeed::value(const std::vector<dBodyID>& bodies) const {
    if (last_second_.empty()) return mean_speed(bodies);
    double sum = 0;
    for (const auto& [t, speed] : last_second_) sum += speed;
    return sum / static_cast<double>(last_second_.size());
}

SuccessReport judge_pile(const std::vector<dBodyID>& bodies, const SettlingSpeed& settling, const char* what,
                         Vec3 centre, Vec3 inner) {
    int outside = 0;
    double fastest = 0, highest = 0;
    for (dBodyID b : bodies) {
        const Vec3 p = position(b);
        outside += std::abs(p.x - centre.x) < 0.5 * inner.x && std::abs(p.y - centre.y) < 0.5 * inner.y && p.z > 0 ? 0 : 1;
        fastest = std::max(fastest, norm(to_vec(dBodyGetLinearVel(b))));
        highest = std::max(highest, p.z);
    }
    const double settled = settling.value(bodies);
    std::ostringstream d;
    d << bodies.size() << ' ' << what << ": " << outside << " outside the bin (needs 0), mean speed over the last second "
      << settled << " m/s (< " << kSettledSpeed << "), fastest " << fastest << " m/s (< " << kThrownSpeed
      << "), highest centre " << highest << " m (wall " << inner.z << ")";
    return {outside == 0 && settled < kSettledSpeed && fastest < kThrownSpeed && highest < inner.z, d.str()};
}

void turn_at_random(dBodyID body, Vec3 at, double max_angle, SceneRandom& random) {
    for (const Vec3 axis : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}})
        rotate_about(body, at, axis, random.uniform(-max_angle, max_angle));
}

}  // namespace ode_bpp::scenes
