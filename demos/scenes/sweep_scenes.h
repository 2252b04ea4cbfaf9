// demos/scenes/sweep_scenes.h: parameterised scenes for the stability sweeps (make stability)
// and the stability tests. Each models one phenomenon where MLCP methods are known to fail
// (heavy on light, closed loops, long chains, coupled friction) and nothing more.
//
// Masses are set by one number, the mass ratio r = heavy : light (see each pattern), so that a
// sweep over r changes the conditioning of A while the geometry and the loads stay put.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scenes/build_helpers.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {

enum class SweepPattern {
    /// A 100 kg load on a chain of light links hanging from a fixed point, swinging.
    /// r = load : link. Ball joints only, no contacts. `links` sets the chain length.
    HangingChain,
    /// A 100 kg box resting on a column of light boxes on the ground. r = top : light box.
    /// Contacts with friction only, no joints.
    BoxStack,
    /// Offshore: a 1,000 kg base on the ground, a light cable hanging from a mast on it and a
    /// 100 kg load swinging on the cable above the base. r = load : link, so base : link is
    /// 10 r (the paper's 4,400,000:1 is ship : cable link). Contacts under the base, ball joints
    /// along the cable.
    Offshore,
    /// A hanging ladder of parallelogram cells (closed loops of four parallel hinges, so three
    /// rows per cell are redundant); its bottom rung is the 100 kg load. r = load : light body.
    Ladder,
    /// A 100 kg box on a light box, both sliding at 2 m/s on the ground until friction stops
    /// them: the two friction contacts are coupled through the light box. r = top : bottom.
    SlidingPair,
};
const char* to_string(SweepPattern p);
std::optional<SweepPattern> sweep_pattern_from_string(std::string_view name);
std::vector<SweepPattern> all_sweep_patterns();

struct SweepSpec {
    SweepPattern pattern = SweepPattern::HangingChain;
    double mass_ratio = 1;   ///< r >= 1, see SweepPattern
    int links = 0;           ///< chain links / stacked light boxes / ladder cells; 0: the pattern's default
};

/// A distance that physics bounds: |world_point(from, from_local) - position(body)| (from null:
/// from_local is a world point) must lie in [min_distance, max_distance] [m].
struct PlacementCheck {
    dBodyID from = nullptr;
    Vec3 from_local;
    dBodyID body = nullptr;
    double min_distance = 0;
    double max_distance = 0;
    /// Compliant constraints (joints or contacts) in series between the two: the measurement
    /// widens [min, max] by this many drift tolerances, the give that CFM allows each of them.
    int compliant_in_series = 0;
    std::string what;        ///< e.g. "load below the anchor at the chain's length"
};

/// What a built sweep scene tells the measurement (sweep_run.h) about itself.
struct SweepLayout {
    double link_length = 0;       ///< the smallest body's size ell [m]: scales the drift tolerances
    double height = 0;            ///< the scene's vertical size [m]: scales the energy reference
    /// Largest weight [N] that one joint or contact carries at rest: with CFM, a constraint
    /// yields by about W h CFM / ERP (ODE's spring: kp = ERP / (h CFM)).
    double carried_weight = 0;
    int joints = 0;               ///< tracked joints (0: the scene has none)
    std::vector<PlacementCheck> placements;
    /// SlidingPair only: where friction stops the pair, v0^2 / (2 mu g) from its start [m]
    /// (0 for the other patterns).
    double expected_slide = 0;
    dBodyID slider = nullptr;     ///< SlidingPair: the heavy box whose slide is measured
    double slide_start_x = 0;
};

/// Builds the pattern into the world (mu, gravity and CFM are the world's).
SweepLayout build_sweep_scene(SceneWorld& w, const SweepSpec& spec);

/// The default `links` of a pattern (chain links, stacked light boxes, ladder cells).
int default_links(SweepPattern p);

}  // namespace ode_bpp::scenes
