// classic_boxstack.cpp: a pyramid of boxes and a single column of boxes resting on the ground
// (ODE's boxstack demo, written anew). Resting contact is the hardest case for a pivoting
// solver: every contact row is tight or sticking at once, and the stack only stands if the
// normal impulses of all layers are found consistently.
#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

#include "scenes/scene.h"

namespace ode_bpp::scenes {
namespace {

constexpr double kEdge = 0.5;            // box edge [m]
constexpr double kMass = 10.0;           // box mass [kg]
constexpr double kColumnGap = 0.05 * kEdge;  // keeps side faces of neighbours apart
constexpr double kLayerDrop = 1e-3 * kEdge;  // start just above the layer below: no penetration
constexpr int kPyramidBase = 5;
constexpr int kColumnHeight = 6;
// Standing means each box stays within a small fraction of its edge and tilts less than ~3 deg.
constexpr double kMaxDriftFraction = 0.05;
constexpr double kMinUprightCosine = 0.9986;

/// One box as it was placed: the body and its rest position.
struct PlacedBox {
    dBodyID body;
    double rest[3];
};

/// A pyramid (kPyramidBase boxes at the bottom, one at the top) and a free-standing column of
/// kColumnHeight boxes. Success: every box ends within kMaxDriftFraction * edge of where it was
/// placed and stays upright.
class BoxStack final : public Scene {
public:
    std::string name() const override { return "boxstack"; }
    std::string description() const override {
        return "pyramid of 15 boxes and a column of 6 boxes resting on the ground";
    }
    double default_seconds() const override { return 5.0; }

    void build(SceneWorld& w) override {
        const double pitch = kEdge + kColumnGap;
        for (int layer = 0; layer < kPyramidBase; ++layer) {
            const int count = kPyramidBase - layer;
            for (int i = 0; i < count; ++i) {
                const double x = (i - 0.5 * (count - 1)) * pitch;
                add_box(w, x, 0.0, layer_height(layer));
            }
        }
        const double column_x = 0.5 * kPyramidBase * pitch + 2.0 * kEdge;
        for (int layer = 0; layer < kColumnHeight; ++layer) add_box(w, column_x, 0.0, layer_height(layer));
    }

    SuccessReport success(const SceneWorld&) const override {
        double worst_drift = 0, worst_cosine = 1;
        for (const PlacedBox& box : boxes_) {
            const dReal* p = dBodyGetPosition(box.body);
            const dReal* R = dBodyGetRotation(box.body);
            worst_drift = std::max(worst_drift, std::hypot(p[0] - box.rest[0], p[1] - box.rest[1],
                                                           p[2] - box.rest[2]));
            worst_cosine = std::min(worst_cosine, double(R[10]));  // body z axis . world z
        }
        const double drift_limit = kMaxDriftFraction * kEdge;
        std::ostringstream detail;
        detail << boxes_.size() << " boxes: largest drift " << worst_drift << " m (limit " << drift_limit
               << "), smallest up-cosine " << worst_cosine << " (limit " << kMinUprightCosine << ")";
        return {worst_drift < drift_limit && worst_cosine > kMinUprightCosine, detail.str()};
    }

private:
    static double layer_height(int layer) { return (layer + 0.5) * kEdge + (layer + 1) * kLayerDrop; }

    void add_box(SceneWorld& w, double x, double y, double z) {
        dBodyID body = w.create_body();
        dMass mass;
        dMassSetBoxTotal(&mass, kMass, kEdge, kEdge, kEdge);
        dBodySetMass(body, &mass);
        dBodySetPosition(body, x, y, z);
        dGeomSetBody(dCreateBox(w.space(), kEdge, kEdge, kEdge), body);
        boxes_.push_back({body, {x, y, z}});
    }

    std::vector<PlacedBox> boxes_;
};

}  // namespace

std::unique_ptr<Scene> make_classic_boxstack() { return std::make_unique<BoxStack>(); }

}  // namespace ode_bpp::scenes
