// Adds Siconos' relay solvers to bench_corpus (compiled into it only when Siconos was found).
#include "peer_limits.h"
#include "siconos_peers.h"

namespace {
const ode_bpp::bench::PeerRegistration kSiconos{[](const std::vector<int>& sweeps) {
    return ode_bpp::peers::siconos_peer_methods(sweeps, ode_bpp::peers::kLemkeMaxRows);
}};
}  // namespace
