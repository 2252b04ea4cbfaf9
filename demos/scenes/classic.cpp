#include "scenes/classic.h"

namespace ode_bpp::scenes {

// Defined one per file in classic_<name>.cpp.
std::unique_ptr<Scene> make_classic_boxstack();
std::unique_ptr<Scene> make_classic_chain();
std::unique_ptr<Scene> make_classic_buggy();
std::unique_ptr<Scene> make_classic_cannon();
std::unique_ptr<Scene> make_classic_motors();
std::unique_ptr<Scene> make_classic_islands();

std::vector<std::pair<std::string, SceneFactory>> classic_scenes() {
    return {
        {"boxstack", make_classic_boxstack},
        {"chain", make_classic_chain},
        {"buggy", make_classic_buggy},
        {"cannon", make_classic_cannon},
        {"motors", make_classic_motors},
        {"islands", make_classic_islands},
    };
}

}  // namespace ode_bpp::scenes
