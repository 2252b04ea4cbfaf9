// demos/scenes/classic.h: ODE's classic demos, written anew as Scenes.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scenes/scene.h"

namespace ode_bpp::scenes {

using SceneFactory = std::function<std::unique_ptr<Scene>()>;

/// The ported classic demos by name (box stack, chain, buggy, cannon and wall, motors and limits),
/// and `islands`: many tiny independent mechanisms, the way games built on ODE step their worlds.
std::vector<std::pair<std::string, SceneFactory>> classic_scenes();

}  // namespace ode_bpp::scenes
