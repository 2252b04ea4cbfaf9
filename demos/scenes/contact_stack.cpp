// contact_stack.cpp: a tall column of 40 boxes whose masses grow geometrically from 1 kg at the
// bottom to 1,000 kg at the top: light boxes carry heavy ones, so the contact rows of one island
// span three orders of magnitude in effective mass (and A's entries with them), and every face
// holds four coplanar contacts.
#include <cmath>

#include "scenes/contact.h"

namespace ode_bpp::scenes {
namespace {

constexpr int kBoxes = 40;
constexpr double kEdge = 0.3;                // [m]
constexpr double kBottomMass = 1, kTopMass = 1000;  // [kg]
constexpr double kLayerDrop = -1e-4 * kEdge;

class Stack final : public Scene {
public:
    std::string name() const override { return "stack"; }
    std::string description() const override {
        return "column of 40 boxes, 1 kg at the bottom to 1,000 kg at the top";
    }
    double default_seconds() const override { return 3.0; }

    void build(SceneWorld& w) override {
        for (int k = 0; k < kBoxes; ++k) {
            const double mass = kBottomMass * std::pow(kTopMass / kBottomMass, k / double(kBoxes - 1));
            const Vec3 at{0, 0, (k + 0.5) * kEdge + (k + 1) * kLayerDrop};
            boxes_.push_back(add_cube(w, mass, kEdge, at));
        }
    }

    SuccessReport success(const SceneWorld&) const override { return judge_standing(boxes_, kEdge); }

private:
    std::vector<PlacedBody> boxes_;
};

}  // namespace

std::unique_ptr<Scene> make_contact_stack() { return std::make_unique<Stack>(); }

}  // namespace ode_bpp::scenes
