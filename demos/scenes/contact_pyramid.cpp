// contact_pyramid.cpp: a pyramid of 36 boxes in 8 levels, side faces touching, each box on two
// below, and a box 40 times heavier on top. Every face holds up to four coplanar contacts, the
// neighbours' side contacts carry nothing: a degenerate contact set of over 1,000 rows in one
// island, where the normal impulses of all levels must be found together for the pyramid to stand.
#include <cmath>

#include "scenes/contact.h"

namespace ode_bpp::scenes {
namespace {

constexpr int kLevels = 8;                  // 8 + 7 + ... + 1 = 36 boxes
constexpr double kEdge = 0.4;               // [m]
constexpr double kMass = 10;                // [kg]
constexpr double kTopMass = 400;            // the box on top
constexpr double kLayerDrop = -1e-4 * kEdge; // each level starts just above the one below

class Pyramid final : public Scene {
public:
    std::string name() const override { return "pyramid"; }
    std::string description() const override {
        return "pyramid of 36 touching boxes in 8 levels with a 400 kg box on top (over 1,000 contact rows)";
    }
    double default_seconds() const override { return 3.0; }

    void build(SceneWorld& w) override {
        for (int level = 0; level < kLevels; ++level) {
            const int count = kLevels - level;
            const double z = (level + 0.5) * kEdge + (level + 1) * kLayerDrop;
            for (int i = 0; i < count; ++i) {
                const Vec3 at{(i - 0.5 * (count - 1)) * kEdge, 0, z};
                boxes_.push_back(add_cube(w, level == kLevels - 1 ? kTopMass : kMass, kEdge, at));
            }
        }
    }

    SuccessReport success(const SceneWorld&) const override { return judge_standing(boxes_, kEdge); }

private:
    std::vector<PlacedBody> boxes_;
};

}  // namespace

std::unique_ptr<Scene> make_contact_pyramid() { return std::make_unique<Pyramid>(); }

}  // namespace ode_bpp::scenes
