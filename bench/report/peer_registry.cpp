#include "peer_registry.h"

namespace ode_bpp::bench {

const char* to_string(PeerStatus status) {
    switch (status) {
        case PeerStatus::Solved: return "solved";
        case PeerStatus::Failed: return "failed";
        case PeerStatus::Skipped: return "skipped";
        case PeerStatus::Iterated: return "iterated";
    }
    return "unknown";
}

std::vector<PeerFactory>& peer_factories() {
    // A function-local static: registrations run during static initialization of other
    // translation units, in an unspecified order.
    static std::vector<PeerFactory> factories;
    return factories;
}

PeerRegistration::PeerRegistration(PeerFactory factory) { peer_factories().push_back(std::move(factory)); }

std::vector<PeerMethod> all_peer_methods(const std::vector<int>& iterations) {
    std::vector<PeerMethod> methods;
    for (const PeerFactory& factory : peer_factories()) {
        std::vector<PeerMethod> made = factory(iterations);
        methods.insert(methods.end(), made.begin(), made.end());
    }
    return methods;
}

}  // namespace ode_bpp::bench
