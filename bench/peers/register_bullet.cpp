// Adds Bullet's solvers to bench_corpus (compiled into it only when Bullet was found).
#include "bullet_peers.h"
#include "peer_limits.h"

namespace {
const ode_bpp::bench::PeerRegistration kBullet{[](const std::vector<int>& sweeps) {
    return ode_bpp::peers::bullet_peer_methods(sweeps, ode_bpp::peers::kLemkeMaxRows);
}};
}  // namespace
