// demos/scenes/sweep_scenes.cpp: the sweep patterns of sweep_scenes.h.
#include "scenes/sweep_scenes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ode_bpp::scenes {

namespace {

// [kg] the load of every pattern: with CFM up to 1e-4 its weight stays within what ODE's
// contacts can hold (CFM W below the 2 m/s cap on their correcting velocity, scene.cpp)
constexpr double kHeavyMass = 100;
constexpr double kOffshoreBaseMass = 1e3; // [kg] ten loads, as the ship outweighs the crane
constexpr double kLinkLength = 0.5;       // [m] chain links, ladder links, box sides
constexpr double kLinkRadius = 0.02;      // [m]
constexpr double kSwingAngle = 0.3;       // [rad] initial tilt of the chains from the vertical
constexpr double kClearance = 1.5;        // [m] between a hanging load and what is under it
constexpr double kSlideSpeed = 2.0;       // [m/s] SlidingPair's initial speed
// A hanging load may swing up and the chain may sag: the load stays between this fraction of
// the chain's length and its full length from the anchor.
constexpr double kSagFraction = 0.9;

struct Named {
    SweepPattern pattern;
    const char* name;
};
constexpr Named kNames[] = {
    {SweepPattern::HangingChain, "chain"}, {SweepPattern::BoxStack, "stack"},
    {SweepPattern::Offshore, "offshore"},  {SweepPattern::Ladder, "ladder"},
    {SweepPattern::SlidingPair, "sliding"},
};

double light_mass(const SweepSpec& s, double heavy) {
    if (!(s.mass_ratio >= 1)) throw std::invalid_argument("sweep scene: mass ratio must be >= 1");
    return heavy / s.mass_ratio;
}

int links_of(const SweepSpec& s) { return s.links > 0 ? s.links : default_links(s.pattern); }

/// The modelling trap of docs/modelling.md (light links under heavy loads): at h = 1/60, light links with their true inertia under a swinging
/// heavy load tear with every solver. As in the crane and offshore scenes, a light link
/// gets the rotational inertia of a link as heavy as the load (its mass, hence the ratio, stays).
double light_inertia_factor(double light) { return std::max(1.0, kHeavyMass / light); }

/// A box-section beam whose rotational inertia is inflated by light_inertia_factor().
dBodyID add_light_beam(SceneWorld& w, double mass, double section, Vec3 from, Vec3 to) {
    dBodyID b = add_beam(w, mass, section, from, to);
    dMass m;
    dBodyGetMass(b, &m);
    scale_inertia(m, light_inertia_factor(mass));
    dBodySetMass(b, &m);
    return b;
}

Vec3 swing_direction() { return {std::sin(kSwingAngle), 0, -std::cos(kSwingAngle)}; }

/// Light ball-jointed links from `anchor` along `dir`, and a heavy sphere at the end; the first
/// link is jointed to `holder` (null: the static world). Returns the load.
dBodyID hang_chain(SceneWorld& w, dBodyID holder, Vec3 anchor, Vec3 dir, int links, double link_mass,
                   double load_radius) {
    CableSpec spec;
    spec.start = anchor;
    spec.end = anchor + (links * kLinkLength) * dir;
    spec.links = links;
    spec.radius = kLinkRadius;
    spec.total_mass = links * link_mass;
    spec.collide = false;  // the phenomenon is the joint chain; contacts would only add noise
    spec.inertia_factor = light_inertia_factor(link_mass);
    const Cable cable = build_cable(w, spec);
    add_ball(w, holder, cable.links.front(), anchor);
    dBodyID load = add_body(w, sphere_mass(kHeavyMass, load_radius), spec.end + load_radius * dir);
    add_ball(w, cable.links.back(), load, spec.end);
    return load;
}

SweepLayout build_chain(SceneWorld& w, const SweepSpec& s) {
    const int n = links_of(s);
    const double m = light_mass(s, kHeavyMass);
    const double radius = 0.25, length = n * kLinkLength + radius;
    const Vec3 anchor{0, 0, length + kClearance};
    SweepLayout l;
    l.link_length = kLinkLength;
    l.height = anchor.z;
    l.carried_weight = w.params().gravity * (kHeavyMass + n * m);
    l.joints = n + 1;
    dBodyID load = hang_chain(w, nullptr, anchor, swing_direction(), n, m, radius);
    l.placements.push_back({nullptr, anchor, load, kSagFraction * length, length, n + 1,
                            "load hangs at the chain's length from the anchor"});
    return l;
}

SweepLayout build_stack(SceneWorld& w, const SweepSpec& s) {
    const int n = links_of(s);
    const double m = light_mass(s, kHeavyMass), side = kLinkLength;
    for (int k = 0; k < n; ++k) {
        dBodyID box = add_body(w, box_mass(m, {side, side, side}), {0, 0, (k + 0.5) * side});
        add_box(w, box, {side, side, side});
    }
    const double top_z = (n + 0.5) * side;
    dBodyID top = add_body(w, box_mass(kHeavyMass, {side, side, side}), {0, 0, top_z});
    add_box(w, top, {side, side, side});
    SweepLayout l;
    l.link_length = side;
    l.height = top_z + 0.5 * side;
    l.carried_weight = w.params().gravity * (kHeavyMass + n * m);
    // the top box stays on the column: a slide off it or a collapse drops it by a box side
    l.placements.push_back({nullptr, {0, 0, 0}, top, top_z, top_z, n + 1, "heavy box rests on the column"});
    return l;
}

SweepLayout build_offshore(SceneWorld& w, const SweepSpec& s) {
    const int n = links_of(s);
    const double m = light_mass(s, kHeavyMass);
    const Vec3 base_size{4, 4, 1};
    dBodyID base = add_body(w, box_mass(kOffshoreBaseMass, base_size), {0, 0, 0.5 * base_size.z});
    add_box(w, base, base_size);
    const double radius = 0.4, length = n * kLinkLength + radius;
    // the mast on the base is rigid and needs no geom: only its top, the cable's anchor, matters
    const Vec3 mast_top_local{0, 0, 0.5 * base_size.z + length + radius + kClearance};
    const Vec3 anchor = world_point(base, mast_top_local);
    dBodyID load = hang_chain(w, base, anchor, swing_direction(), n, m, radius);
    SweepLayout l;
    l.link_length = kLinkLength;
    l.height = anchor.z;
    l.carried_weight = w.params().gravity * (kOffshoreBaseMass + kHeavyMass + n * m);
    l.joints = n + 1;
    l.placements.push_back({base, mast_top_local, load, kSagFraction * length, length, n + 1,
                            "load hangs at the cable's length from the mast"});
    l.placements.push_back({nullptr, {0, 0, 0}, base, 0.5 * base_size.z, 0.5 * base_size.z, 1,
                            "base stays on the ground"});
    return l;
}

SweepLayout build_ladder(SceneWorld& w, const SweepSpec& s) {
    const int cells = links_of(s);
    const double m = light_mass(s, kHeavyMass), half_width = 0.5, section = 0.05;
    const Vec3 axis{0, 1, 0};
    const double top = cells * kLinkLength + kClearance;
    dBodyID above = nullptr;  // the static top bar, then each cell's rung
    dBodyID rung = nullptr;
    for (int k = 0; k < cells; ++k) {
        const double z_top = top - k * kLinkLength, z_bottom = z_top - kLinkLength;
        const double rung_mass = k + 1 == cells ? kHeavyMass : m;
        rung = add_light_beam(w, rung_mass, section, {-half_width, 0, z_bottom}, {half_width, 0, z_bottom});
        for (double x : {-half_width, half_width}) {
            dBodyID side = add_light_beam(w, m, section, {x, 0, z_top}, {x, 0, z_bottom});
            add_hinge(w, above, side, {x, 0, z_top}, axis);
            add_hinge(w, side, rung, {x, 0, z_bottom}, axis);
        }
        above = rung;
    }
    // the load starts with a push: the parallelogram cells shear and swing
    dBodySetLinearVel(rung, 1.0, 0, 0);
    SweepLayout l;
    l.link_length = kLinkLength;
    l.height = top;
    l.carried_weight = w.params().gravity * (kHeavyMass + 3 * cells * m);
    l.joints = 4 * cells;
    const double length = cells * kLinkLength;
    l.placements.push_back({nullptr, {0, 0, top}, rung, kSagFraction * length, length, 2 * cells,
                            "load rung hangs at the ladder's length"});
    return l;
}

SweepLayout build_sliding(SceneWorld& w, const SweepSpec& s) {
    // flat boxes: with mu = 1 a cube would be at the brink of tipping over while it slides
    const double m = light_mass(s, kHeavyMass), side = 2 * kLinkLength, thick = 0.5 * kLinkLength;
    const Vec3 size{side, side, thick};
    dBodyID bottom = add_body(w, box_mass(m, size), {0, 0, 0.5 * thick});
    add_box(w, bottom, size);
    dBodyID top = add_body(w, box_mass(kHeavyMass, size), {0, 0, 1.5 * thick});
    add_box(w, top, size);
    for (dBodyID b : {bottom, top}) dBodySetLinearVel(b, kSlideSpeed, 0, 0);
    SweepLayout l;
    l.link_length = thick;
    l.height = 2 * thick;
    l.carried_weight = w.params().gravity * (kHeavyMass + m);
    // ground friction mu (M + m) g decelerates the pair at mu g; the top contact needs exactly
    // mu M g to keep the heavy box along, its limit: the pair sticks (or barely slips) and stops
    // together after v0^2 / (2 mu g)
    l.expected_slide = kSlideSpeed * kSlideSpeed / (2 * w.params().mu * w.params().gravity);
    l.slider = top;
    l.slide_start_x = 0;
    l.placements.push_back({bottom, {0, 0, 0}, top, thick, thick, 1, "heavy box stays on the light box"});
    return l;
}

}  // namespace

const char* to_string(SweepPattern p) {
    for (const Named& n : kNames) {
        if (n.pattern == p) return n.name;
    }
    return "?";
}

std::optional<SweepPattern> sweep_pattern_from_string(std::string_view name) {
    for (const Named& n : kNames) {
        if (name == n.name) return n.pattern;
    }
    return std::nullopt;
}

std::vector<SweepPattern> all_sweep_patterns() {
    std::vector<SweepPattern> all;
    for (const Named& n : kNames) all.push_back(n.pattern);
    return all;
}

int default_links(SweepPattern p) {
    switch (p) {
        case SweepPattern::HangingChain: return 10;
        case SweepPattern::BoxStack: return 4;
        case SweepPattern::Offshore: return 10;
        case SweepPattern::Ladder: return 4;
        case SweepPattern::SlidingPair: return 1;
    }
    return 1;
}

SweepLayout build_sweep_scene(SceneWorld& w, const SweepSpec& spec) {
    switch (spec.pattern) {
        case SweepPattern::HangingChain: return build_chain(w, spec);
        case SweepPattern::BoxStack: return build_stack(w, spec);
        case SweepPattern::Offshore: return build_offshore(w, spec);
        case SweepPattern::Ladder: return build_ladder(w, spec);
        case SweepPattern::SlidingPair: return build_sliding(w, spec);
    }
    throw std::invalid_argument("unknown sweep pattern");
}

}  // namespace ode_bpp::scenes
