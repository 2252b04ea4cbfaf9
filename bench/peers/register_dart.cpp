// Adds DART's solvers to bench_corpus (compiled into it only when DART was found).
#include "dart_peers.h"

namespace {
const ode_bpp::bench::PeerRegistration kDart{ode_bpp::peers::dart_peer_methods};
}  // namespace
