// contact_rockpile.cpp: 96 rocks (boxes of random size and attitude, seeded; 9 to 110 kg)
// dropped into a bin and settling into one pile of well over 1,000 contact rows: the size of
// island where dense methods cost most, with box-box contacts of up to four points per pair.
#include "scenes/contact.h"

namespace ode_bpp::scenes {
namespace {

constexpr int kPerSide = 4, kLayers = 6;          // 4 x 4 rocks per layer, 96 in all
constexpr double kMinSide = 0.15, kMaxSide = 0.35;  // [m]
constexpr double kDensity = 2600;                 // [kg/m^3], granite
constexpr double kPitch = 0.42;                   // between neighbours in a layer [m]
constexpr double kFirstLayer = 0.3, kLayerPitch = 0.4;  // drop heights [m]
constexpr double kMaxTurn = 0.6;                  // random turn about each axis [rad]
const Vec3 kBinCentre{0, 0, 0}, kBinInner{1.8, 1.8, 1.8};
constexpr double kWall = 0.15;
constexpr std::uint64_t kSeed = 1013;

class RockPile final : public Scene {
public:
    std::string name() const override { return "rockpile"; }
    std::string description() const override {
        return "96 rocks (random boxes, 9-110 kg) dropped into a bin: one pile of over 1,000 contact rows";
    }
    double default_seconds() const override { return 3.0; }

    void build(SceneWorld& w) override {
        add_bin(w, kBinCentre, kBinInner, kWall);
        SceneRandom random(kSeed);
        for (int layer = 0; layer < kLayers; ++layer)
            for (int i = 0; i < kPerSide; ++i)
                for (int j = 0; j < kPerSide; ++j) {
                    const Vec3 at = kBinCentre + Vec3{(i - 0.5 * (kPerSide - 1)) * kPitch, (j - 0.5 * (kPerSide - 1)) * kPitch,
                                                      kFirstLayer + layer * kLayerPitch};
                    add_rock(w, at, random);
                }
    }

    void control(SceneWorld&, double t) override { settling_.observe(rocks_, t); }

    SuccessReport success(const SceneWorld&) const override {
        return judge_pile(rocks_, settling_, "rocks", kBinCentre, kBinInner);
    }

private:
    void add_rock(SceneWorld& w, Vec3 at, SceneRandom& random) {
        const Vec3 size{random.uniform(kMinSide, kMaxSide), random.uniform(kMinSide, kMaxSide),
                        random.uniform(kMinSide, kMaxSide)};
        dBodyID body = add_body(w, box_mass(kDensity * size.x * size.y * size.z, size), at);
        turn_at_random(body, at, kMaxTurn, random);
        add_box(w, body, size);
        rocks_.push_back(body);
    }

    std::vector<dBodyID> rocks_;
    SettlingSpeed settling_;
};

}  // namespace

std::unique_ptr<Scene> make_contact_rockpile() { return std::make_unique<RockPile>(); }

}  // namespace ode_bpp::scenes
