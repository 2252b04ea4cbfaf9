// contact_bin.cpp: 64 capsules dropped into a bin in eight crossed layers, turned a little at
// random (seeded), settling into a pile: contacts appear, slide and vanish every step, among
// bodies of one mass, as in the piles ODE's users drop into containers.
#include "scenes/contact.h"

namespace ode_bpp::scenes {
namespace {

constexpr int kRows = 4, kEndToEnd = 2, kLayers = 8;  // 4 rows of 2 capsules per layer, 64 in all
constexpr double kRadius = 0.08, kLength = 0.5;   // capsule: radius and cylinder length [m]
constexpr double kMass = 4;                       // [kg]
constexpr double kPitch = 0.36;                   // between neighbours in a layer [m]
constexpr double kFirstLayer = 0.3, kLayerPitch = 0.22;  // drop heights [m]
constexpr double kMaxTurn = 0.15;                 // random turn about each axis [rad]
const Vec3 kBinCentre{0, 0, 0}, kBinInner{1.7, 1.7, 1.5};
constexpr double kWall = 0.1;
constexpr std::uint64_t kSeed = 13;

class Bin final : public Scene {
public:
    std::string name() const override { return "bin"; }
    std::string description() const override { return "64 capsules dropped into a bin, settling into a pile"; }
    double default_seconds() const override { return 7.0; }

    void build(SceneWorld& w) override {
        add_bin(w, kBinCentre, kBinInner, kWall);
        SceneRandom random(kSeed);
        for (int layer = 0; layer < kLayers; ++layer) {
            const Vec3 along = layer % 2 == 0 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
            for (int i = 0; i < kRows; ++i) {
                const double across = (i - 0.5 * (kRows - 1)) * kPitch;
                for (int j = 0; j < kEndToEnd; ++j) {
                    const double lengthwise = (j - 0.5 * (kEndToEnd - 1)) * (kLength + 2 * kRadius + 0.1);
                    const Vec3 at = kBinCentre + lengthwise * along + across * Vec3{along.y, along.x, 0} +
                                    Vec3{0, 0, kFirstLayer + layer * kLayerPitch};
                    add_capsule_body(w, at, along, random);
                }
            }
        }
    }

    void control(SceneWorld&, double t) override { settling_.observe(capsules_, t); }

    SuccessReport success(const SceneWorld&) const override {
        return judge_pile(capsules_, settling_, "capsules", kBinCentre, kBinInner);
    }

private:
    void add_capsule_body(SceneWorld& w, Vec3 at, Vec3 along, SceneRandom& random) {
        dBodyID body = add_body(w, capsule_mass(kMass, kRadius, kLength), at);
        align_z(body, along);
        turn_at_random(body, at, kMaxTurn, random);
        add_capsule(w, body, kRadius, kLength);
        capsules_.push_back(body);
    }

    std::vector<dBodyID> capsules_;
    SettlingSpeed settling_;
};

}  // namespace

std::unique_ptr<Scene> make_contact_bin() { return std::make_unique<Bin>(); }

}  // namespace ode_bpp::scenes
