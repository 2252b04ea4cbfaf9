// demos/scenes/paper_scenes.h: the six scenes of the paper's Sec. 4.1, by name.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scenes/classic.h"
#include "scenes/scene.h"

namespace ode_bpp::scenes {

std::unique_ptr<Scene> make_crane();      ///< Sec. 4.1.2, mobile crane
std::unique_ptr<Scene> make_winch();      ///< Sec. 4.1.6, winch
std::unique_ptr<Scene> make_parkour();    ///< Sec. 4.1.3, vehicle parkour
std::unique_ptr<Scene> make_offshore();   ///< Sec. 4.1.4, offshore knuckle-boom crane
std::unique_ptr<Scene> make_forklift();   ///< Sec. 4.1.1, forklift
std::unique_ptr<Scene> make_forwarder();  ///< Sec. 4.1.5, forwarder

/// The six paper scenes in the paper's Table 2 order, by command-line name.
std::vector<std::pair<std::string, SceneFactory>> paper_scenes();

}  // namespace ode_bpp::scenes
