#include "scenes/classic.h"

namespace ode_bpp::scenes {

std::vector<std::pair<std::string, SceneFactory>> classic_scenes() { return {}; }

}  // namespace ode_bpp::scenes
